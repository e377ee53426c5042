"""The layout of a data set's records, read back by h5py (an independent HDF5 reader), against
docs/datasets.md; and labels.csv against each record's own case text.

test_dataset_layout.py GEARIMPACT SPEC WORKDIR
Exit 77 (skipped) where h5py is not installed.
"""
import csv
import math
import pathlib
import shutil
import subprocess
import sys
import tomllib

try:
    import h5py
except ImportError:
    print("h5py is not installed (Debian: python3-h5py): skipped")
    sys.exit(77)

gearimpact, spec, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
subprocess.run([gearimpact, "dataset", str(spec), "--out", str(work / "set"), "--quiet"],
               check=True, stdout=subprocess.DEVNULL)
subprocess.run([gearimpact, "dataset", "merge", str(work / "set"), "--out", str(work / "merged")],
               check=True, stdout=subprocess.DEVNULL)
merged = work / "merged"
rows = list(csv.DictReader(open(merged / "labels.csv", newline="")))
assert len(rows) == 6, len(rows)
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


truth = ["theta1_rad", "theta2_rad", "w1_rad_s", "w2_rad_s", "drive_force_N", "coast_force_N",
         "dte_m"]
units = {"theta1_rad": "rad", "theta2_rad": "rad", "w1_rad_s": "rad/s", "w2_rad_s": "rad/s",
         "drive_force_N": "N", "coast_force_N": "N", "dte_m": "m"}
for row in rows:
    with h5py.File(merged / row["file"], "r") as f:
        name = row["file"]
        a = f.attrs
        check(a["format"] == b"gearimpact-record", f"{name}: format")
        check(a["format_version"] == 1, f"{name}: format_version")
        check(a["record_id"] == int(row["record_id"]), f"{name}: record_id")
        check(a["split"].decode() == row["split"], f"{name}: split")
        check(a["seed"].decode() == row["seed"], f"{name}: seed")
        n = int(a["n_samples"])
        check(n == 1000, f"{name}: n_samples {n}")
        check(a["sample_rate_hz"] == 20000.0, f"{name}: sample_rate_hz")
        check(a["settle_s"] == 0.02 and a["duration_s"] == 0.05, f"{name}: settle, duration")
        check(f["time"].shape == (n,) and f["time"].attrs["units"] == b"s", f"{name}: /time")
        check(f["time"][1] == 1.0 / 20000.0, f"{name}: /time step")
        s = f["signals/sensor"]
        check(s.shape == (n,) and s.dtype == "<f8" and s.attrs["units"] == b"m/s2",
              f"{name}: /signals/sensor")
        for t in truth:
            d = f["truth/" + t]
            check(d.shape == (n,) and d.dtype == "<f8" and d.attrs["units"].decode() == units[t],
                  f"{name}: /truth/{t}")
        c = f["truth/contact"]
        check(c.shape == (n,) and c.dtype == "i1" and set(c[:]) <= {0, 1, 2, 3},
              f"{name}: /truth/contact")
        # The flags agree with the forces.
        check(all((int(k) & 1) == (fd > 0) for k, fd in zip(c[:], f["truth/drive_force_N"][:])),
              f"{name}: contact flag 1 where the drive flanks carry")
        labels = f["labels"].attrs
        check(labels["torque1.mean_speed_rad_s"] == float(row["torque1.mean_speed_rad_s"]),
              f"{name}: speed label")
        check(labels["faults[0].depth_m"] == float(row["faults[0].depth_m"]),
              f"{name}: depth label")
        check(abs(labels["realised_snr_db"] - float(row["realised_snr_db"])) == 0.0,
              f"{name}: realised SNR")
        # The realised SNR is of the noise drawn at 30 dB: within 5 sigma of its sampling error,
        # (10 / ln 10) sqrt(2 / N) dB (docs/datasets.md).
        check(abs(labels["realised_snr_db"] - 30.0) < 5 * 10 / math.log(10) * math.sqrt(2 / n),
              f"{name}: realised SNR {labels['realised_snr_db']} near 30 dB")
        # The labels are the record's own case keys, read from its provenance.
        case = tomllib.loads(f["provenance/case_toml"][()].decode())
        depth = case["faults"][0]["depth"]
        check(depth.endswith(" m") and float(depth[:-2]) == float(row["faults[0].depth_m"]),
              f"{name}: case depth {depth}")
        speed = case["torque1"]["mean_speed"]
        check(float(speed.split()[0]) == float(row["torque1.mean_speed_rad_s"]),
              f"{name}: case speed {speed}")
        check(f["provenance"].attrs["seed"].decode() == row["seed"], f"{name}: provenance seed")
        # The seeded start: the pinion turned by less than one of its 17 teeth' pitch from the
        # base case's 0, the wheel by the same arc on its base circle (Rb ratio 17/38).
        theta1 = float(case["initial"]["theta1"].split()[0])
        theta2 = float(case["initial"]["theta2"].split()[0])
        check(theta1 == float(row["theta1_start_rad"]) == labels["theta1_start_rad"],
              f"{name}: theta1_start_rad")
        check(0 <= theta1 < 2 * math.pi / 17, f"{name}: start angle {theta1} within a pitch")
        check(abs(theta2 / (theta1 * 17 / 38) - 1) < 1e-14, f"{name}: wheel turned alike")
        check(len(f["provenance"].attrs["code_version"]) > 0, f"{name}: code_version")

check((merged / "DATASET_CARD.md").read_text().startswith("---\npretty_name: six"), "card")
if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"{len(rows)} records read back by h5py {h5py.__version__} match docs/datasets.md")
