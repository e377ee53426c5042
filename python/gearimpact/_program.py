"""The program's commands that the package runs in-process (the library behind
``gearimpact sweep``, ``iso6336``, ``mesh-stiffness`` and ``reproduce``), and
the program and the paper's data that come with the package."""

import os
from pathlib import Path

from . import _core

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
    SVG need gnuplot) and REPORT.md, as ``gearimpact reproduce`` does (progress on
    standard error).

    paper_data: another folder of statements (default: this package's). Returns
    the path of REPORT.md. Raises RuntimeError with the program's message when
    it fails.
    """
    data = paper_data_dir() if paper_data is None else paper_data
    try:
        _core.reproduce(os.fspath(out_dir), os.fspath(data))
    except (ValueError, RuntimeError, OSError) as error:
        raise RuntimeError(f"gearimpact reproduce failed: {error}") from error
    return Path(out_dir) / "REPORT.md"


def _table(csv_text):
    """A CSV with a header as a dict of numpy arrays, column by column (text columns stay
    lists of str)."""
    import csv
    import io

    import numpy
    rows = list(csv.reader(io.StringIO(csv_text)))
    header, body = rows[0], rows[1:]
    table = {}
    for i, name in enumerate(header):
        values = [row[i] for row in body]
        try:
            table[name] = numpy.array([float(v) for v in values])
        except ValueError:
            table[name] = values
    return table


def iso6336(case=None, helix_angle_deg=0.0):
    """ISO 6336-1 method B for a case's gear pair (default: the paper's), as
    ``gearimpact iso6336``: a dict with zn1, zn2, c_prime_th_n_mm_um, c_prime_n_mm_um,
    c_gamma_alpha_n_mm_um, eps_alpha, c_prime_b_n_m, c_gamma_alpha_b_n_m."""
    import json
    return json.loads(_core.iso6336(case, float(helix_angle_deg)))


def mesh_stiffness(case=None, model=None, samples=200):
    """The mesh stiffness over one mesh period with exact line-of-action kinematics, as
    ``gearimpact mesh-stiffness``: (table, summary), the table a dict of numpy arrays
    fraction, theta1_rad, pairs, ke_n_m, the summary a dict with min_n_m, max_n_m, mean_n_m
    (the exact time mean), contact_ratio, extrapolated. model: yang-lin-1987,
    potential-energy or ross-compatible (default: the case's)."""
    import json
    table, summary = _core.mesh_stiffness(case, None if model is None else str(model),
                                          int(samples))
    return _table(table), json.loads(summary)


def sweep(case, vary, start, stop, points, direction="both", options=()):
    """The steady state of a loaded, running pair along one parameter, as
    ``gearimpact sweep`` (docs/sweep.md): `case` a Case, `vary` any numeric case-file key as
    section.key, `start` and `stop` with units as case files write them ("500 rad/s") or SI
    floats, `options` more of the command's options as strings (e.g. ["--vary2",
    "gears.backlash", ...]). Returns a dict: "sweep" and "poincare" (dicts of arrays with the
    columns of sweep.csv and poincare.csv) and "summary" (summary.json)."""
    import json
    arguments = ["--vary", str(vary), "--from", str(start), "--to", str(stop),
                 "--points", str(int(points)), "--direction", str(direction)]
    sweep_text, poincare_text, summary_text = _core.sweep(
        case, arguments + [str(o) for o in options])
    return {
        "sweep": _table(sweep_text),
        "poincare": _table(poincare_text),
        "summary": json.loads(summary_text),
    }
