"""The gearimpact program and the paper's data that come with the package."""

import os
import subprocess
from pathlib import Path

# Not resolved: in the build tree the package's files are links into the
# source tree, and the program and the data sit beside the links.
_PACKAGE = Path(os.path.abspath(__file__)).parent


def program_path():
    """The gearimpact program of this package (gearimpact/bin/gearimpact)."""
    program = _PACKAGE / "bin" / "gearimpact"
    if not program.is_file():
        raise FileNotFoundError(f"the gearimpact program is not in this package: looked for {program}")
    return program


def paper_data_dir():
    """The paper's data of this package: case1.toml ... case3.toml and the statement files."""
    data = _PACKAGE / "share" / "gearimpact" / "paper_data"
    if not (data / "dynamics_statements.csv").is_file():
        raise FileNotFoundError(f"the paper's data is not in this package: looked in {data}")
    return data


def reproduce(out_dir, paper_data=None):
    """Reproduces the paper into `out_dir`: every figure as CSV, PNG and SVG (PNG and
    SVG need gnuplot) and REPORT.md, by running ``gearimpact reproduce``.

    paper_data: another folder of statements (default: this package's). Returns
    the path of REPORT.md. Raises RuntimeError with the program's message when
    it fails.
    """
    command = [str(program_path()), "reproduce", "--out", os.fspath(out_dir)]
    if paper_data is not None:
        command += ["--paper-data", os.fspath(paper_data)]
    finished = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if finished.returncode != 0:
        raise RuntimeError(
            f"gearimpact reproduce failed (exit {finished.returncode}): {finished.stderr.strip()}"
        )
    return Path(out_dir) / "REPORT.md"
