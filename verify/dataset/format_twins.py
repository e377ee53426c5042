"""The set-up the tests of a data set's other record formats share: one spec made twice, as HDF5
records and in the format under test, and the latter merged.

twin_sets(fmt) reads the script's arguments (GEARIMPACT SPEC WORKDIR), writes WORKDIR/h5.toml (the
spec, its base case's path made absolute) and WORKDIR/FMT.toml (the same with format = FMT), runs
both into WORKDIR/h5 and WORKDIR/FMT, merges the latter into WORKDIR/merged and returns
(gearimpact, work, rows of merged/labels.csv).
"""
import csv
import pathlib
import shutil
import subprocess
import sys


def twin_sets(fmt):
    gearimpact, spec, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    text = spec.read_text().replace('case = "', f'case = "{spec.parent}/')
    (work / "h5.toml").write_text(text)
    (work / f"{fmt}.toml").write_text(text.replace("[dataset]\n", f'[dataset]\nformat = "{fmt}"\n'))
    for kind in ("h5", fmt):
        subprocess.run([gearimpact, "dataset", str(work / f"{kind}.toml"), "--out",
                        str(work / kind), "--quiet"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([gearimpact, "dataset", "merge", str(work / fmt), "--out",
                    str(work / "merged")], check=True, stdout=subprocess.DEVNULL)
    rows = list(csv.DictReader(open(work / "merged" / "labels.csv", newline="")))
    return gearimpact, work, rows
