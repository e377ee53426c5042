"""The program's commands that the package runs in-process (the library behind
``gearimpact sweep``, ``iso6336``, ``mesh-stiffness`` and ``reproduce``), and
the program and the paper's data that come with the package."""

import csv
import io
import json
import math
import numbers
import os
from pathlib import Path

import numpy

from . import _arguments, _cases, _core, _warnings

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

    out_dir, paper_data: a str or a pathlib.Path; paper_data is another folder of
    statements (default: this package's). Returns
    the path of REPORT.md. Raises CaseError for a folder that cannot be used (no
    statements in paper_data, an output that cannot be written).
    """
    out = _arguments.path("out_dir", out_dir)
    data = paper_data_dir() if paper_data is None else paper_data
    data = _arguments.path("paper_data", data)
    if not (Path(data) / "dynamics_statements.csv").is_file():
        raise _arguments.case_error(
            f"paper_data={str(data)!r}: a folder of the paper's statements, and "
            "dynamics_statements.csv is not in it (None: this package's)", "paper_data")
    _core.reproduce(out, data)
    return Path(out_dir) / "REPORT.md"


# The columns of the program's CSV files whose type their values alone do not
# tell: the program prints an integral double without a decimal point, and a
# column may be empty throughout (every point of a sweep unconverged). Keys and
# counts are int64 (0 where a row has none: the period of an aperiodic or
# unconverged point), `converged` bool, names str. Any other column is bool
# when it holds only true/false, float64 when it holds only numbers (NaN for
# an empty field), str otherwise, so that a column the program adds arrives
# with its type.
_INTEGER_COLUMNS = frozenset({"line", "index", "period", "pairs", "loaded_pairs", "mode",
                              "harmonic"})
_BOOL_COLUMNS = frozenset({"converged"})
_TEXT_COLUMNS = frozenset({"direction", "regime", "teeth"})


def _column(name, values):
    if name in _INTEGER_COLUMNS:
        return numpy.array([int(v) if v.isdigit() else 0 for v in values], dtype=numpy.int64)
    if name in _BOOL_COLUMNS or (values and set(values) <= {"true", "false"}):
        return numpy.array([v == "true" for v in values], dtype=bool)
    if name not in _TEXT_COLUMNS:
        try:
            return numpy.array([float(v) if v else math.nan for v in values],
                               dtype=numpy.float64)
        except ValueError:
            pass
    return numpy.array(values, dtype=str)


def _table(csv_text):
    """A CSV with a header as a dict of numpy arrays, column by column, each of its type."""
    rows = list(csv.reader(io.StringIO(csv_text)))
    header, body = rows[0], rows[1:]
    return {name: _column(name, [row[i] for row in body]) for i, name in enumerate(header)}


def _case_or_none(case):
    if case is not None and not isinstance(case, _core.Case):
        raise _arguments.case_error(
            f"case={case!r}: a Case (gearimpact.paper_case, read_case) or None for the paper's "
            f"pair, not {type(case).__name__}",
            "case",
        )
    return case


def iso6336(case=None, helix_angle_deg=0.0, load=None):
    """ISO 6336-1 method B for a case's gear pair (a Case; None: the paper's), as
    ``gearimpact iso6336``, at the helix angle helix_angle_deg (a number of degrees in
    [0, 45]): a dict with zn1, zn2, c_prime_th_n_mm_um, c_prime_n_mm_um,
    c_gamma_alpha_n_mm_um, eps_alpha, c_prime_b_n_m, c_gamma_alpha_b_n_m. load, as
    ``--load``: F_t K_A / b ("50 N/mm") or the pinion's torque ("150 N*m", K_A = 1); below
    100 N/mm c' takes the low-load factor (specific_load_n_mm, low_load_factor added)."""
    return json.loads(_core.iso6336(_case_or_none(case),
                                    _arguments.real("helix_angle_deg", helix_angle_deg),
                                    None if load is None else _arguments.text("load", load)))


def mesh_stiffness(case=None, model=None, samples=200):
    """The mesh stiffness over the true period of the teeth (one mesh period when every tooth
    is alike; a pinion or wheel revolution or the hunting period with the case's faults) with
    exact line-of-action kinematics, as ``gearimpact mesh-stiffness``: (table, summary), the
    table a dict of numpy arrays fraction, theta1_rad, pairs, ke_n_m, healthy_ke_n_m and
    pairJ_pinion_tooth, pairJ_wheel_tooth, pairJ_ke_n_m (NaN where fewer pairs touch), the
    summary a dict with min_n_m, max_n_m, mean_n_m (the exact time mean over the true
    period), contact_ratio, period, mesh_periods, healthy_mean_n_m, extrapolated. case: a Case
    or None (the paper's pair); model: yang-lin-1987, potential-energy or ross-compatible
    (default: the case's); samples: an int per mesh period, 2 up to the program's --samples
    bound. A helical pair (gears.helix_angle > 0, docs/helical.md): one mesh period by the
    slice model, the table's arrays fraction, theta1_rad, k_slices_n_m (model.face_slices
    slices), k_face_n_m (the face integral), contact_line_length_m and
    contact_line_length_slices_m, the summary that of ``mesh-stiffness --summary``; with the
    case's faults the true-period table and summary above, each pair reading the faulted table
    a run reads (docs/helical.md, Faults)."""
    chosen = _case_or_none(case)
    table, summary = _core.mesh_stiffness(
        chosen, None if model is None else _arguments.text("model", model),
        _arguments.integer("samples", samples))
    summary = json.loads(summary)
    # A helical pair's summary has no fitted tables to extrapolate.
    if summary.get("extrapolated"):
        _warnings.warn(f"{chosen.name if chosen else 'the paper pair'}: {summary['warning']}")
    return table, summary


def ste(case, torque, points=200):
    """The loaded static transmission error of a case's pair with its [modifications], as
    ``gearimpact ste`` (docs/faults.md): `case` a Case, `torque` the pinion's torque T1 > 0 as
    case files write it ("100 N*m") or a finite number of N m, `points` pinion angles per mesh
    period (an int, 2 to 100000). Returns a dict: "ste" and "unmodified" (dicts of numpy arrays
    with the columns of ste.csv and ste_unmodified.csv: theta1_rad, theta1_deg, ste_m, kte_m,
    effective_stiffness_n_per_m, pairs and loaded_pairs int64, share_1..share_4 and
    gap_1..gap_4 float64 with NaN beyond the pairs in contact, teeth str) and "summary"
    (summary.json). Faulted teeth ([[faults]]) read their own stiffness; "unmodified" is then
    the healthy pair, and where every pair in contact has a missing tooth ste_m and
    effective_stiffness_n_per_m are NaN (with a warning). A helical pair takes the slice
    model with its lead modifications and misalignment (docs/helical.md): the columns
    theta1_rad, theta1_deg, ste_m, kte_m, effective_stiffness_n_per_m, elements,
    loaded_elements, load_centre_m, face_load_factor, and its summary."""
    if not isinstance(case, _core.Case):
        raise _arguments.case_error(
            f"case={case!r}: a Case (gearimpact.case, paper_case, read_case), "
            f"not {type(case).__name__}",
            "case",
        )
    if isinstance(torque, numbers.Real) and not _arguments.is_bool(torque):
        torque = repr(_arguments.real("torque", torque)) + " N*m"
    modified, unmodified, summary = _core.ste(case, _arguments.text("torque", torque),
                                              _arguments.integer("points", points))
    summary = json.loads(summary)
    # A helical pair's summary has no missing teeth to leave points uncarried.
    if summary.get("uncarried_points"):
        _warnings.warn(f"{case.name}: at {summary['uncarried_points']} of {summary['points']:.0f} "
                       "angles every pair in the contact segment has a missing tooth: no pair "
                       "carries the load, and ste_m is NaN there")
    return {"ste": modified, "unmodified": unmodified, "summary": summary}


def modes(case, harmonics=3, max_speed=None):
    """The natural modes of a case's linearised model at its mean mesh stiffness, as
    ``gearimpact modes`` (docs/vibration.md): torsional, or planar with [bearings]
    kind = "elastic", with a motor and a load with [shafts] kind = "elastic". `case` a Case,
    `harmonics` the mesh harmonics of the Campbell table (an int, 1 to 100), `max_speed` its
    largest pinion speed as case files write it ("6000 rpm") or a number of rad/s (None: 1.1
    times where the first harmonic meets the highest mode). Returns a dict: "modes" and
    "campbell" (dicts of numpy arrays with the columns of modes.csv and campbell.csv: mode and
    harmonic int64, rigid bool, the rest float64), "dofs" (the shape's degrees of freedom in
    order), "shapes" (a float64 array, one mass-normalised shape a row, one column a DOF),
    "mode_shapes" (mode_shapes.csv: each shape with its rotations as Rb theta, the largest
    component 1, as the program's mode_shapes.png draws them) and "summary" (summary.json)."""
    if not isinstance(case, _core.Case):
        raise _arguments.case_error(
            f"case={case!r}: a Case (gearimpact.case, paper_case, read_case), "
            f"not {type(case).__name__}",
            "case",
        )
    if max_speed is not None and isinstance(max_speed, numbers.Real) and not \
            _arguments.is_bool(max_speed):
        number = _arguments.real("max_speed", max_speed)
        _cases.check_plausible("max_speed", "initial.w1", number)
        max_speed = repr(number) + " rad/s"
    table, campbell, mode_shapes, summary = _core.modes(
        case, _arguments.integer("harmonics", harmonics),
        None if max_speed is None else _arguments.text("max_speed", max_speed))
    summary = json.loads(summary)
    dofs = summary["dofs"]
    columns = [next(name for name in table if name.startswith(dof + "_")) for dof in dofs]
    shapes = numpy.column_stack([table[name] for name in columns]) if table["mode"].size else \
        numpy.zeros((0, len(dofs)))
    return {"modes": table, "campbell": campbell, "dofs": dofs, "shapes": shapes,
            "mode_shapes": mode_shapes, "summary": summary}


def sweep(case, vary, start, stop, points, direction="both", options=()):
    """The steady state of a loaded, running pair along one parameter, as
    ``gearimpact sweep`` (docs/sweep.md): `case` a Case, `vary` any numeric case-file key as
    section.key (a str), `start` and `stop` with units as case files write them ("500 rad/s")
    or finite SI numbers, `points` an int, `direction` "up", "down" or "both", `options` more of
    the command's options as a list of str, one a word (e.g. ["--vary2", "gears.backlash",
    ..., "--threads", "2"]); `vary` may also be a bare key or section_key, as Case.replace
    takes them ("w1"). Returns a dict: "sweep" and "poincare" (dicts of numpy arrays with the
    columns of sweep.csv and poincare.csv: direction and regime str, converged bool, line,
    index and period int64 (period 0 for a point not periodic), the figures float64 with NaN
    where a point has none) and "summary" (summary.json), so that
    ``sw["value_si"][sw["direction"] == "up"]`` selects. Warns (GearimpactWarning) of a
    foundation fit used outside its range and of the sweep's own warnings (summary["warnings"])."""
    if not isinstance(case, _core.Case):
        raise _arguments.case_error(
            f"case={case!r}: a Case (gearimpact.case, paper_case, read_case), "
            f"not {type(case).__name__}",
            "case",
        )
    try:
        key = _cases.resolve(_arguments.text("vary", vary))
    except _core.CaseError as error:
        raise _arguments.case_error(
            f"vary={vary!r}: {error} (a numeric key as section.key, section_key or bare)",
            "vary") from None
    ends = {}
    for name, value in (("start", start), ("stop", stop)):
        ends[name] = _arguments.quantity(name, value)
        if isinstance(value, numbers.Real) and not _arguments.is_bool(value):
            _cases.check_plausible(name, key, _arguments.real(name, value))
            # Warned here; the unit keeps the program from warning again.
            if _cases.is_speed(key):
                ends[name] += " rad/s"
    arguments = ["--vary", key,
                 "--from", ends["start"],
                 "--to", ends["stop"],
                 "--points", str(_arguments.integer("points", points)),
                 "--direction", _arguments.text("direction", direction)]
    more = _arguments.strings("options", options, ["--threads", "2"])
    for option in more:
        flag = option.split("=")[0]
        if flag in _SWEEP_FILE_OPTIONS or flag in _SWEEP_ARGUMENTS:
            what = (f"sweep()'s own argument {_SWEEP_ARGUMENTS[flag]}=" if flag in _SWEEP_ARGUMENTS
                    else "nothing here: sweep() writes no file and returns the tables")
            raise _arguments.case_error(
                f"options: {flag} sets {what}; the options are the command's others "
                f"(e.g. --vary2, --threads, --tolerance)", "options")
    try:
        sweep_text, poincare_text, summary_text = _core.sweep(case, arguments + more)
    except _core.CaseError as error:
        raise _sweep_error(error, dict(vary=vary, start=start, stop=stop, points=points,
                                       direction=direction)) from None
    extrapolated = _warnings.conditions(case).get("extrapolated")
    if extrapolated:
        _warnings.warn(extrapolated)
    summary = json.loads(summary_text)
    # The sweep's own warnings (hysteresis of an undamped sweep, speeds that do not roll).
    for warning in summary.get("warnings", []):
        _warnings.warn(f"{case.name or 'the case'}: {warning}")
    return {
        "sweep": _table(sweep_text),
        "poincare": _table(poincare_text),
        "summary": summary,
    }


# The command's options about its files, which sweep() has none of: they would be ignored.
_SWEEP_FILE_OPTIONS = {"--out", "--overwrite", "--no-plots", "--shard"}

# The command's options that sweep() sets from its own arguments.
_SWEEP_ARGUMENTS = {"--vary": "vary", "--from": "start", "--to": "stop", "--points": "points",
                    "--direction": "direction"}


def _sweep_error(error, given):
    """The command's CaseError about an option that an argument of sweep() set,
    naming that argument as the caller wrote it; others (options) as they are."""
    field = getattr(error, "field", "")
    message = str(error)
    flag = field.split(" ")[0]
    if flag not in _SWEEP_ARGUMENTS and field == "options":
        # A parse error of the command line names its option in the message.
        flag = next((f for f in _SWEEP_ARGUMENTS if f"= {f}:" in message), flag)
    keyword = _SWEEP_ARGUMENTS.get(flag)
    if keyword is None:
        return error
    return _arguments.case_error(f"{keyword}={given[keyword]!r}: {message}", keyword)
