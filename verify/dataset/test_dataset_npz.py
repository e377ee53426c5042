"""A data set's NPZ records read back by numpy (an independent reader of the ZIP and .npy
formats) against the same set's HDF5 records read by h5py: every array the same bytes, dtype
and shape, every attribute the same value, the texts the same; labels.csv names the .npz files.

test_dataset_npz.py GEARIMPACT SPEC WORKDIR (the set-up: format_twins.py)
Exit 77 (skipped) where numpy or h5py is not installed.
"""
import json
import math
import sys
import zipfile

from format_twins import twin_sets

try:
    import h5py
    import numpy
except ImportError:
    print("numpy or h5py is not installed (Debian: python3-numpy, python3-h5py): skipped")
    sys.exit(77)

gearimpact, work, rows = twin_sets("npz")
assert len(rows) == 6, len(rows)
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def same_value(a, b):
    """An HDF5 attribute (numpy scalar or bytes) against its JSON value (NaN written as null)."""
    if isinstance(a, bytes):
        return a.decode() == b
    if b is None:
        return math.isnan(float(a))
    if isinstance(b, int) and not isinstance(b, bool):
        return int(a) == b and numpy.issubdtype(numpy.asarray(a).dtype, numpy.integer)
    return float(a) == float(b)


for row in rows:
    name = row["file"]
    check(name.endswith(".npz"), f"{name}: labels.csv names the .npz file")
    path = work / "merged" / name
    with zipfile.ZipFile(path) as z:
        check(z.testzip() is None, f"{name}: every member's CRC-32")
    npz = numpy.load(path)
    attributes = json.loads(npz["attributes.json"])
    h5_name = name.replace(".npz", ".h5")
    with h5py.File(work / "h5" / h5_name, "r") as f:
        seen = set()

        def visit(key, obj):
            seen.add("/" + key)
            if isinstance(obj, h5py.Dataset):
                if obj.shape == ():
                    member = key + ".txt"
                    if key == "provenance/spec_toml":
                        # The specs differ by their format line: each record holds its own.
                        check(npz[member] == (work / "npz.toml").read_bytes()
                              and obj[()] == (work / "h5.toml").read_bytes(), f"{name}: {member}")
                    else:
                        check(npz[member] == obj[()], f"{name}: {member}")
                else:
                    array = npz[key]
                    check(array.dtype == obj.dtype and array.shape == obj.shape,
                          f"{name}: {key} dtype and shape {array.dtype} {array.shape}")
                    check(array.tobytes() == obj[:].tobytes(), f"{name}: {key}'s bytes")
            h5_attrs = dict(obj.attrs)
            json_attrs = attributes.get("/" + key, {})
            check(sorted(h5_attrs) == sorted(json_attrs),
                  f"{name}: /{key}'s attribute names {sorted(json_attrs)}")
            for a, v in h5_attrs.items():
                check(same_value(v, json_attrs.get(a)), f"{name}: /{key} attribute {a}")

        f.visititems(visit)
        root = dict(f.attrs)
        check(sorted(root) == sorted(attributes["/"]), f"{name}: / attribute names")
        sha = (work / "npz" / "spec.sha256").read_text().strip()
        check(attributes["/"]["spec_sha256"] == sha, f"{name}: the NPZ set's spec sha256")
        for a, v in root.items():
            if a != "spec_sha256":
                check(same_value(v, attributes["/"].get(a)), f"{name}: / attribute {a}")
        check(sorted(seen | {"/"}) == sorted(attributes), f"{name}: the same groups and datasets")
        check(float(npz["signals/sensor"].std()) > 0.0, f"{name}: a sensor signal")

if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"{len(rows)} NPZ records equal their HDF5 twins")
