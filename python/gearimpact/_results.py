"""Stiffness tables, energy ratios, simulations and the friction sweep, as numpy arrays."""

import json
import numbers
import os

import numpy

from . import _arguments, _core, _warnings
from ._arguments import case_error
from ._cases import paper_case, read_case
from ._core import Case, CaseError, GearPair, StiffnessModel


def _as_case(case, name="case"):
    """A Case from a Case, a Table 1 case number or a case file's path."""
    if isinstance(case, Case):
        return case
    if isinstance(case, numbers.Integral) and not _arguments.is_bool(case):
        return paper_case(case)
    if isinstance(case, (str, os.PathLike)):
        return read_case(case)
    raise case_error(
        f"{name}={case!r}: a Case, a case number of Table 1 (1, 2, 3) or a case file's path, "
        f"not {type(case).__name__}",
        name,
    )


def _pair_and_model(case_or_pair, method, flipped_moment):
    """The gear pair and stiffness model: the paper's, a GearPair's with the
    default model, or a case's; `method` and `flipped_moment` change the model
    when given (as the program's --method and --flipped-moment do)."""
    if case_or_pair is None:
        pair, model = GearPair(), StiffnessModel()
    elif isinstance(case_or_pair, GearPair):
        pair, model = case_or_pair, StiffnessModel()
    else:
        case = _as_case(case_or_pair, "case_or_pair")
        pair, model = case.gears, case.stiffness_model
    if method is not None:
        model.method = _arguments.text("method", method)
    if flipped_moment is not None:
        flipped = _arguments.flag("flipped_moment", flipped_moment)
        model.moment_sign = "flipped" if flipped else "physical"
    return pair, model


def stiffness(case_or_pair=None, points=None, x=None, method=None, flipped_moment=None):
    """Kb, Ka of both gears, Kh and Ke (N/m) of one tooth pair along the contact segment.

    case_or_pair: a GearPair (with the default stiffness model), a Case or a
    case file's path (its pair and stiffness model), a Table 1 case number, or
    None for the paper's pair. Either `points` positions from X_start to X_end
    inclusive (an int, 2 up to the program's --points bound; 201 when neither
    is given), spaced as
    ``gearimpact stiffness --points N`` spaces them, or the contact positions
    `x` (a 1-dimensional sequence or numpy array of finite numbers, m, from C1,
    within (0, lp)). method: "gsl", "gsl-cquad", "boost-gk", "boost-ts" or
    "xform"; flipped_moment: True adds the Fa h moment instead of subtracting
    it, False subtracts it (as printed), None keeps the case's.

    Returns a dict of numpy arrays with the program's columns: x_m, phi1_rad
    (the contact angle (12)), kb1, ka1, kb2, ka2, kh, ke.
    """
    if x is not None and points is not None:
        raise case_error("points and x: give one of them, not both", "points")
    count = 201 if points is None else _arguments.integer("points", points)
    pair, model = _pair_and_model(case_or_pair, method, flipped_moment)
    if x is not None:
        return _core.stiffness_at(pair, model, _positions(x))
    return _core.stiffness_samples(pair, model, count)


def _positions(x):
    """x as a 1-dimensional float64 array, each element a real number (the
    library checks that each is finite and within (0, lp))."""

    if isinstance(x, (str, bytes)) or _arguments.is_bool(x):
        raise case_error(f"x={x!r}: a sequence of contact positions, m", "x")
    if isinstance(x, numbers.Real):
        x = [x]
    array = numpy.asarray(x, dtype=object) if not isinstance(x, numpy.ndarray) else x
    if array.dtype == object:
        if array.ndim != 1:
            raise case_error(
                f"x: a 1-dimensional sequence of numbers, not shape {array.shape}", "x"
            )
        return numpy.array([_arguments.real(f"x[{i}]", v) for i, v in enumerate(array)],
                           dtype=numpy.float64)
    if array.dtype.kind not in "iuf":
        raise case_error(f"x: numbers, m, not an array of {array.dtype}", "x")
    return array.astype(numpy.float64)


def energy_ratios(case_or_pair=None, points=121, method=None, flipped_moment=None):
    """The elastic energy ratios of Fig. 8 over one meshing cycle.

    Arguments as for stiffness() (points: an int, 2 up to the program's
    --points bound). Returns a dict of numpy arrays with the
    columns of ``gearimpact energy-ratios``: angle_deg (phi1 of (12)), pairs,
    hertz_over_bending_one_pair, axial_over_bending_one_pair,
    hertz_over_bending_system, axial_over_bending_system; and x_m, the
    contact position of the tooth followed.
    """
    count = _arguments.integer("points", points)
    pair, model = _pair_and_model(case_or_pair, method, flipped_moment)
    table = _core.energy_ratios(pair, model, count)
    table["pairs"] = table["pairs"].astype(numpy.int64)
    return table


class SimulationResult:
    """One run: .case (the Case run), .summary (a dict with the keys of the
    program's JSON summary; the losses damping_loss_J (Hertzian damping),
    friction_loss_J and, with a viscous mesh damper, mesh_damper_loss_J), .series (a dict of numpy arrays with the columns
    of its time-series CSV, ``gearimpact simulate --out``'s: with [bearings] kind = "elastic"
    the planar series' (docs/usage.md, "Output columns"; a helical pair's adds axial_force1_N,
    axial_force2_N, tilting_moment1_N_m, tilting_moment2_N_m); each column a member of the rows is
    a view of it; zero-length when keep_series was False) and .impacts (a
    list of dicts: line "N1" or "N2", start_s, impact_speed_m_s, restitution,
    end_s, end_speed_m_s, the last two None for a contact still on at the end)
    and .samples (with sample_rate, a dict of numpy arrays with the columns of
    ``gearimpact simulate --sample-rate``; zero-length without it) and .tacho
    (with [tacho] pulses_per_revolution >= 1, a planar run's true edge times, s,
    jitter-free: gearimpact.tacho_jitter gives the emitted ones)."""

    def __init__(self, case, summary, series, impacts, samples=None, tacho=None):
        self.case = case
        self.summary = summary
        self.series = series
        self.impacts = impacts
        self.samples = samples
        self.tacho = tacho

    def __repr__(self):
        s = self.summary
        # The viscous mesh damper's loss, a term of its own, where the run has one.
        damper = (
            f", mesh damper loss {s['mesh_damper_loss_J']:.6g} J" if "mesh_damper_loss_J" in s else ""
        )
        return (
            f"<SimulationResult {s['case']}: {s['impacts_n1']} impacts on N1, "
            f"{s['impacts_n2']} on N2 in {s['end_time_s']} s; damping loss "
            f"{s['damping_loss_J']:.6g} J, friction loss {s['friction_loss_J']:.6g} J{damper}>"
        )


def _sample_rate(sample_rate):
    """sample_rate as given to simulate and train: None, a number of Hz or a text with a unit."""
    if sample_rate is None:
        return None
    if isinstance(sample_rate, str):
        return _core.parse_frequency(sample_rate, "sample_rate")
    return _arguments.real("sample_rate", sample_rate)


def _sample_kind(sample, rate):
    """sample as given to simulate and train: None (interval-average) or a kind's name, refused
    without a sample rate, whose samples it defines (as the program refuses --sample without
    --sample-rate)."""
    if sample is None:
        return "interval-average"
    kind = _arguments.text("sample", sample)
    if rate is None:
        raise _arguments.case_error(
            f"sample={sample!r}: needs sample_rate, whose samples it defines", "sample")
    return kind


def simulate(
    case, keep_series=True, max_rows=None, sample_rate=None, sample=None, **changes
):
    """Runs a case: the same run as ``gearimpact simulate``, bit for bit.

    case: a Case, a Table 1 case number (1, 2, 3) or a case file's path.
    changes: fields to change first, as Case.replace takes them, e.g.
    friction_coefficient=0.06, end_time="10 ms", output_every=100,
    integrator_kind="adaptive". keep_series: True or False; False skips the time series
    (faster, less memory). max_rows: the most rows the kept series may have
    (None: the library's bound, 5e7 rows, 4.4 GB; a longer run is refused
    before it starts, naming end_time). sample_rate: Hz, > 0, a number or with
    its unit ("80 kHz"): .samples holds
    samples at t = n / sample_rate exactly from the integrator's dense output
    (t_s, theta1_rad, theta2_rad, w1_rad_s, w2_rad_s, w1_dot_rad_s2,
    w2_dot_rad_s2, s_m, dte_m = s - B, normal_force_n1_N, normal_force_n2_N,
    region, pairs; docs/usage.md), the run itself unchanged; at most max_rows
    of them. With [bearings] kind = "elastic" the columns are the planar
    samples' (t_s, the state x1_m ... w_load_rad_s, ax1_m_per_s2 ...
    alpha2_rad_per_s2, bearing_fx1_N ... bearing_fy2_N, dte_m, drive_force_N,
    coast_force_N, sensor_acceleration_m_per_s2; docs/vibration.md). sample, with
    sample_rate only: "interval-average" (the default, None: each acceleration is the mean over the
    interval ending at its sample, the velocity difference over 1 /
    sample_rate, so the samples start at n = 1; transfer sinc(f T), delay
    T / 2; docs/signals.md) or "point" (the value at the instant). The computation runs without the GIL; Ctrl-C stops it
    (KeyboardInterrupt). Raises CaseError for a case outside its ranges (with
    the step checked against the contact's period) and SimulationError for a
    run that cannot continue.
    """
    keep = _arguments.flag("keep_series", keep_series)
    rows = _core.most_series_rows if max_rows is None else _arguments.integer("max_rows", max_rows)
    if rows < 1:
        raise _arguments.case_error(f"max_rows={max_rows!r}: a count >= 1, or None", "max_rows")
    rate = _sample_rate(sample_rate)
    kind = _sample_kind(sample, rate)
    run = _as_case(case)
    if changes:
        run = run.replace(**changes)
    try:
        summary_json, series, impacts, samples, tacho, warnings = _core.simulate(
            run, keep, rows, rate, kind)
    except CaseError as error:
        if "rows of time series" not in str(error):
            raise
        raise _arguments.case_error(
            f"{error} (end_time shortens the run, output_every keeps fewer rows, "
            "keep_series=False keeps none, max_rows lifts the bound)",
            getattr(error, "field", ""),
        ) from None
    summary = json.loads(summary_json)
    if summary.get("foundation_extrapolated"):
        _warnings.warn(f"{run.name or 'the case'}: {summary['warning']}")
    # The run's own warnings, as the program prints them (a drifting speed, teeth pressed far in).
    for warning in warnings:
        _warnings.warn(f"{run.name or 'the case'}: {warning}")
    return SimulationResult(run, summary, series, impacts, samples, tacho)


def sweep_friction(
    cases=None,
    from_=0.01,
    to=0.09,
    step=0.01,
    threads=0,
    torque_unit="kgf-mm",
    case3_frequency_rad_s=10000.0,
    **changes,
):
    """Fig. 7: friction loss / damping loss against the friction coefficient f.

    f runs from `from_` to `to` inclusive in steps of `step` (finite numbers;
    0 <= from_ <= to, step > 0), for each case: Table 1's three (read with
    torque_unit and case3_frequency_rad_s, as paper_case takes them) unless
    `cases` lists others (a list or tuple of Cases, numbers or paths).
    changes: fields changed in every case first (e.g. step="0.05 us",
    end_time="10 ms", damping_form="hunt-crossley"). threads: an int, 0 uses
    every core, at most the program's --threads bound; the result does not
    depend on it. Ctrl-C stops it.

    Returns a dict of numpy arrays: "f" and one "ratio_<case name>" a case,
    the columns of ``gearimpact sweep-friction`` for Table 1's cases.
    """
    start = _arguments.real("from_", from_)
    stop = _arguments.real("to", to)
    interval = _arguments.real("step", step)
    workers = _arguments.integer("threads", threads)
    if cases is None:
        runs = [paper_case(n, torque_unit, case3_frequency_rad_s) for n in (1, 2, 3)]
    else:
        if not isinstance(cases, (list, tuple)) or not cases:
            raise case_error(
                f"cases={cases!r}: a non-empty list of Cases, Table 1 numbers or case file paths",
                "cases",
            )
        runs = [_as_case(case, f"cases[{i}]") for i, case in enumerate(cases)]
    if changes:
        runs = [run.replace(**changes) for run in runs]
    names = [run.name for run in runs]
    if len(set(names)) != len(names):
        raise case_error(
            "cases: " + ", ".join(names) + ": each case needs its own name (name=...)", "cases"
        )
    frictions, ratio = _core.sweep_friction(runs, start, stop, interval, workers)
    table = {"f": frictions}
    for j, name in enumerate(names):
        table["ratio_" + name] = ratio[:, j].copy()
    return table


def planetary_modes(case_file):
    """The modes of a linear planetary stage (Lin & Parker 1999) from a planetary file (a
    [planetary] section; docs/planetary.md), as ``gearimpact modes FILE`` gives them, bit for
    bit. case_file: a str or pathlib.Path. Returns a dict: "modes" (numpy arrays by column of
    the command's modes.csv: mode and multiplicity integers, rigid bool, type str, frequency_hz
    and each spring kind's strain-energy share float64) and "summary" (summary.json as a dict).
    Raises CaseError naming a bad key as planetary.KEY."""
    path = _arguments.path("case_file", case_file)
    modes, summary = _core.planetary_modes(path)
    return {"modes": modes, "summary": json.loads(summary)}


def train_modes(case_file, sets=()):
    """The natural modes of a torsional gear train at each mesh's mean mesh stiffness
    (docs/planetary.md, "Modes of a torsional train"), as ``gearimpact modes FILE`` gives them
    on a train file, bit for bit. case_file: a str or pathlib.Path; sets: a list of "KEY=VALUE"
    str as the command's --set. Returns a dict: "modes" (numpy arrays by column of the command's
    modes.csv: mode int64, rigid bool, frequency_hz, angular_frequency_rad_per_s, share_MESH and
    share_shaft_A_B per mesh and torsional shaft, theta_BODY_rad_per_sqrt_kg_m per body) and
    "summary" (summary.json as a dict). Raises CaseError naming a bad key."""
    path = _arguments.path("case_file", case_file)
    more = _arguments.strings("sets", sets, ["meshes.stage1.model.mesh_stiffness=constant"])
    modes, summary = _core.train_modes(path, list(more))
    return {"modes": modes, "summary": json.loads(summary)}


def train(case_file, sets=(), keep_series=True, sample_rate=None, sample=None):
    """Runs a gear train's case file (docs/case-files.md, "A gear train"; a two-gear case file
    is the train of its pair; a stage file, "A planetary stage", is the stage's train) as
    ``gearimpact train`` does, bit for bit.

    case_file: a str or pathlib.Path. sets: a list of "KEY=VALUE" str, as the command's --set
    (e.g. ["integrator.end_time=2 ms", "meshes.idler-wheel.gears.backlash=0.1 mm"]).
    keep_series: True or False. Returns a dict: "series" (numpy arrays by column of the
    command's series.csv: t_s, theta_BODY_rad and w_BODY_rad_per_s per body, s_MESH_m,
    delta_MESH_m, region_MESH and pairs_MESH (int64), normal_force_MESH_N and
    friction_force_MESH_N per mesh, BODY and MESH the file's names; docs/usage.md, "Output
    columns"; zero-length with keep_series=False) and "summary" (summary.json as a dict: the
    train's counts and energy ledger, "meshes" with each mesh's impacts, largest penetration and
    losses, "bodies" with each body's final speed). A stage file's dict has also "ring_sensor"
    (the command's ring_sensor.csv as arrays: t_s and ring_sensor_y_N), "mesh_teeth" (its
    mesh_teeth.csv: t_s, then per planet n sun_tooth_at_sun_planetN,
    planetN_tooth_at_sun_planetN, planetN_tooth_at_ring_planetN and ring_tooth_at_ring_planetN,
    int64, the teeth at each mesh in the stage's count) and its summary a
    "stage" entry (the members' mean speeds and the Willis residual); the stage's run keeps its
    series for these, keep_series=False only leaves the arrays empty. sample_rate: None, or Hz
    (> 0, a number or with a unit, "51.2 kHz") for a train file with a [sensor]: the dict's
    "samples" has the series' columns at t = n / sample_rate exactly (the steps' continuous
    extension), the command's samples.csv; its sensor_acceleration_m_per_s2 as sample says (with
    sample_rate only), "interval-average" (the default, None: the mean over the interval ending
    at each sample, from n = 1 on) or "point". A train with a [tacho] (or a two-gear file's) adds "tacho", its true edge times in
    s (tacho.csv's t_s). Raises CaseError naming a bad key (stage.KEY in a stage file) or
    sample_rate."""
    path = _arguments.path("case_file", case_file)
    more = _arguments.strings("sets", sets, ["integrator.end_time=2 ms"])
    keep = _arguments.flag("keep_series", keep_series)
    rate = _sample_rate(sample_rate)
    kind = _sample_kind(sample, rate)
    summary, series, ring_sensor, mesh_teeth, samples, tacho, warnings = _core.train(
        path, list(more), keep, rate, kind)
    result = {"series": series, "summary": json.loads(summary)}
    # The run's own warnings, as the program prints them (a drifting speed).
    for warning in warnings:
        _warnings.warn(f"{path}: {warning}")
    if samples is not None:
        result["samples"] = samples
    if tacho is not None:
        result["tacho"] = tacho
    if ring_sensor is not None:
        result["ring_sensor"] = ring_sensor
        result["mesh_teeth"] = mesh_teeth
    return result
