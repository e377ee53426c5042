"""Shared by the Python suites: the program to compare with and the source tree.

ctest sets GEARIMPACT_CLI (the program built beside the module) and
GEARIMPACT_SOURCE_DIR, and PYTHONPATH to the build tree's package.
"""

import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest


def _required_path(variable):
    value = os.environ.get(variable)
    if not value:
        pytest.fail(f"{variable} is not set: run the suite through ctest, which sets it")
    return Path(value)


@pytest.fixture(scope="session")
def cli():
    """Runs the gearimpact program; returns its standard output (fails the test on an error)."""
    program = _required_path("GEARIMPACT_CLI")

    def run(*arguments):
        finished = subprocess.run(
            [str(program), *map(str, arguments)], capture_output=True, text=True
        )
        assert finished.returncode == 0, finished.stderr
        return finished.stdout

    return run


@pytest.fixture(scope="session")
def source_dir():
    return _required_path("GEARIMPACT_SOURCE_DIR")


def parse_csv(text):
    """The program's CSV as {column: float64 array}. Its numbers have 17
    significant digits, which read back to the very doubles it printed; an
    empty cell (a pair column where fewer pairs touch) reads as NaN."""
    lines = text.strip().splitlines()
    header = lines[0].split(",")
    rows = [[float(field) if field else math.nan for field in line.split(",")]
            for line in lines[1:]]
    table = np.array(rows, dtype=np.float64).reshape(len(rows), len(header))
    return {name: table[:, j] for j, name in enumerate(header)}


def assert_bitwise_equal(ours, theirs, what):
    """Equal bit for bit (so -0.0 differs from 0.0), as float64."""
    ours = np.ascontiguousarray(ours, dtype=np.float64)
    theirs = np.ascontiguousarray(theirs, dtype=np.float64)
    assert ours.shape == theirs.shape, f"{what}: {ours.shape} rows against {theirs.shape}"
    different = np.flatnonzero(ours.view(np.uint64) != theirs.view(np.uint64))
    assert different.size == 0, (
        f"{what}: {different.size} values differ, the first at row {different[0]}: "
        f"{ours[different[0]]!r} against {theirs[different[0]]!r}"
    )
