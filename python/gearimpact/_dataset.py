"""Labelled data sets (docs/datasets.md): the program's `gearimpact dataset` in-process, and a
loader of a merged set."""

import csv
import os

from . import _arguments, _core

_BOUNDS = {"max_records": 1e6, "max_samples": 1e11, "max_bytes": 200e9}


def _spec(spec):
    return os.fspath(spec) if isinstance(spec, os.PathLike) else _arguments.text(
        "spec", spec, "a spec file's path (str or path)")


def _bounds(max_records, max_samples, max_bytes):
    return [_arguments.real(name, value) for name, value in
            (("max_records", max_records), ("max_samples", max_samples),
             ("max_bytes", max_bytes))]


def dataset_plan(spec, max_records=_BOUNDS["max_records"], max_samples=_BOUNDS["max_samples"],
                 max_bytes=_BOUNDS["max_bytes"]):
    """The plan of a data set's spec file, as ``gearimpact dataset SPEC --plan``: a dict of
    records, conditions, samples_per_record, bytes_estimate, spec_sha256 and code_version (which
    every record carries: files are the same bytes on one build). Every key and bound
    is checked first; a refusal raises CaseError naming the key as the spec writes it."""
    return _core.dataset_plan(_spec(spec), *_bounds(max_records, max_samples, max_bytes))


def dataset_run(spec, out, shard=(0, 1), threads=1, max_records=_BOUNDS["max_records"],
                max_samples=_BOUNDS["max_samples"], max_bytes=_BOUNDS["max_bytes"]):
    """Makes the records of shard (K, N) of a spec into the folder `out` (made if absent), as
    ``gearimpact dataset SPEC --out OUT --shard K/N``: bit for bit the program's files. Records
    found complete are kept (a rerun resumes). `threads`: records made at once, 0 to 1024 (0: one
    per core); the files are the same bytes for any count. Returns a dict: made, found_complete,
    records, signal_s, cpu_s."""
    if (not isinstance(shard, (tuple, list)) or len(shard) != 2
            or any(_arguments.is_bool(v) for v in shard)):
        raise _arguments.case_error(f"shard={shard!r}: a pair (K, N) with 0 <= K < N", "shard")
    k = _arguments.integer("shard", shard[0])
    n = _arguments.integer("shard", shard[1])
    if not 0 <= k < n:
        raise _arguments.case_error(f"shard={shard!r}: a pair (K, N) with 0 <= K < N", "shard")
    out = os.fspath(out) if isinstance(out, os.PathLike) else _arguments.text("out", out)
    workers = _arguments.integer("threads", threads)
    if not 0 <= workers <= 1024:
        raise _arguments.case_error(f"threads={threads!r}: an integer in [0, 1024] (0: all cores)",
                                    "threads")
    return _core.dataset_run(_spec(spec), out, k, n, workers,
                             *_bounds(max_records, max_samples, max_bytes))


def dataset_merge(folders, out, overwrite=False):
    """Checks the shards' folders (every record once, one spec, each file's sha256) and writes
    the set to `out`, as ``gearimpact dataset merge``."""
    if isinstance(folders, (str, os.PathLike)):
        folders = [folders]
    paths = [os.fspath(f) if isinstance(f, os.PathLike) else _arguments.text("folders", f)
             for f in folders]
    out = os.fspath(out) if isinstance(out, os.PathLike) else _arguments.text("out", out)
    _core.dataset_merge(paths, out, bool(overwrite))


def load_dataset(folder, channels=("signals/sensor",)):
    """A merged set: a dict with "labels" (labels.csv's columns; numbers as float64 arrays,
    texts as str arrays) and each channel of `channels` as an (n_records, n_samples) float64
    array read by h5py (Debian: python3-h5py), by numpy.load from a set of .npz records
    (dataset.format = "npz") or by scipy.io.loadmat from .mat records ("mat")."""
    import numpy
    folder = os.fspath(folder)
    with open(os.path.join(folder, "labels.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    npz = bool(rows) and rows[0]["file"].endswith(".npz")
    mat = bool(rows) and rows[0]["file"].endswith(".mat")
    if mat:
        try:
            import scipy.io
        except ImportError:
            raise ImportError("load_dataset reads the records' MAT-files with scipy "
                              "(Debian: python3-scipy; pip: scipy)") from None
    elif not npz:
        try:
            import h5py
        except ImportError:
            raise ImportError("load_dataset reads the records' HDF5 files with h5py "
                              "(Debian: python3-h5py; pip: h5py)") from None
    labels = {}
    for column in (rows[0].keys() if rows else []):
        values = [r[column] for r in rows]
        try:
            labels[column] = numpy.array([float(v) if v != "" else numpy.nan for v in values])
        except ValueError:
            labels[column] = numpy.array(values)
    data = {"labels": labels}
    for channel in channels:
        arrays = []
        for r in rows:
            if npz:
                with numpy.load(os.path.join(folder, r["file"])) as z:
                    arrays.append(z[channel])
            elif mat:
                value = scipy.io.loadmat(os.path.join(folder, r["file"]), simplify_cells=True)
                for part in channel.split("/"):
                    value = value[part]
                arrays.append(numpy.asarray(value).ravel())
            else:
                with h5py.File(os.path.join(folder, r["file"]), "r") as h:
                    arrays.append(h[channel][:])
        data[channel] = numpy.stack(arrays) if arrays else numpy.empty((0, 0))
    return data
