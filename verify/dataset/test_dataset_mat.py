"""A data set's MATLAB v5 records (written through libmatio) read back by scipy.io.loadmat (an
independent reader of the MAT format) against the same set's HDF5 records read by h5py: every
array the same values, dtype and length, every attribute the same value under its MATLAB name,
the texts the same; labels.csv names the .mat files.

test_dataset_mat.py GEARIMPACT SPEC WORKDIR [--no-matio] (the set-up: format_twins.py)
Exit 77 (skipped) where the build has no libmatio, or scipy or h5py is not installed.
"""
import math
import re
import subprocess
import sys

from format_twins import twin_sets

if "--no-matio" in sys.argv:
    print("this build has no libmatio (Debian: libmatio-dev; reconfigure after installing it): "
          "skipped")
    sys.exit(77)
try:
    import h5py
    import numpy
    import scipy.io
except ImportError:
    print("scipy, numpy or h5py is not installed (Debian: python3-scipy, python3-h5py): skipped")
    sys.exit(77)

gearimpact, work, rows = twin_sets("mat")
# The same set in two shards: the same bytes (no date or temporary name enters a file).
# The second shard on two threads: the images take turns.
for k in (0, 1):
    subprocess.run([gearimpact, "dataset", str(work / "mat.toml"), "--out", str(work / "shards"),
                    "--shard", f"{k}/2", "--threads", str(k + 1), "--quiet"], check=True,
                   stdout=subprocess.DEVNULL)
assert len(rows) == 6, len(rows)
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def matlab_name(name):
    """docs/datasets.md's rule: other characters than letters, digits and _ become _, leading
    _ dropped, "root" for none, "x" before a leading digit, at most 63 characters."""
    out = re.sub(r"[^A-Za-z0-9]", "_", name).lstrip("_") or "root"
    return ("x" + out if not out[0].isalpha() else out)[:63]


def same_value(a, b):
    if isinstance(a, bytes):
        return a.decode() == b
    a, b = numpy.asarray(a), numpy.asarray(b)
    if numpy.issubdtype(a.dtype, numpy.integer):
        return numpy.issubdtype(b.dtype, numpy.integer) and int(a) == int(b)
    return (math.isnan(float(a)) and math.isnan(float(b))) or float(a) == float(b)


for row in rows:
    name = row["file"]
    check(name.endswith(".mat"), f"{name}: labels.csv names the .mat file")
    check((work / "merged" / name).read_bytes() == (work / "shards" / name).read_bytes(),
          f"{name}: the same bytes whole and in two shards")
    mat = scipy.io.loadmat(work / "merged" / name, simplify_cells=True)
    attributes = mat["attributes"]
    with h5py.File(work / "h5" / name.replace(".mat", ".h5"), "r") as f:
        paths = {"root"}

        def visit(key, obj):
            parts = key.split("/")
            if isinstance(obj, h5py.Dataset):
                value = mat[parts[0]] if len(parts) == 1 else mat[parts[0]][parts[1]]
                if obj.shape == ():
                    expected = obj[()].decode()
                    if key == "provenance/spec_toml":
                        # The specs differ by their format line: each record holds its own.
                        expected = (work / "mat.toml").read_text()
                    check(value == expected, f"{name}: {key}")
                else:
                    array = numpy.asarray(value).ravel()
                    check(array.dtype == obj.dtype and array.shape == obj.shape,
                          f"{name}: {key} dtype and length {array.dtype} {array.shape}")
                    check(array.tobytes() == obj[:].tobytes(), f"{name}: {key}'s values")
            h5_attrs = dict(obj.attrs)
            if h5_attrs:
                paths.add(matlab_name(key))
            mat_attrs = attributes.get(matlab_name(key), {})
            check(sorted(matlab_name(a) for a in h5_attrs) == sorted(mat_attrs),
                  f"{name}: /{key}'s attribute names")
            for a, v in h5_attrs.items():
                check(same_value(v, mat_attrs.get(matlab_name(a))), f"{name}: /{key} {a}")

        f.visititems(visit)
        for a, v in f.attrs.items():
            if a == "spec_sha256":
                sha = (work / "mat" / "spec.sha256").read_text().strip()
                check(attributes["root"][a] == sha, f"{name}: the MAT set's spec sha256")
            else:
                check(same_value(v, attributes["root"].get(a)), f"{name}: / attribute {a}")
        check(sorted(paths) == sorted(attributes), f"{name}: the same attributed paths")
        check(float(numpy.std(mat["signals"]["sensor"])) > 0.0, f"{name}: a sensor signal")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"{len(rows)} MAT records equal their HDF5 twins")
