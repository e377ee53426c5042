"""Python that behaves as Python users expect: a case from keywords alone,
keys by their bare names with a suggestion for a typo, typed columns, one
exception class for every bad input, warnings a user can filter, a readable
repr, and a warning for a plain number that is an implausible length in metres.

The pair is a user's, not the paper's: 23/67 teeth, module 3 mm, face 25 mm,
shifts +0.2/-0.2, bores 30/80 mm, 150 N*m on the pinion."""

import math
import warnings

import gearimpact
import numpy as np
import pytest

# Rounding in a few operations of double arithmetic: a handful of ulps.
FEW_ULPS = 8 * np.finfo(float).eps
RPM = math.pi / 30  # rad/s per rpm

# The balancing torque and the rolling speed of gear 2: the base radii are
# m Z cos(a0) / 2 for any shift, so Rb2 / Rb1 = Z2 / Z1 = 67 / 23.
RATIO = 67 / 23
PAIR = dict(
    teeth1=23, teeth2=67, module="3 mm", pressure_angle="20 deg", face_width="25 mm",
    profile_shift1=0.2, profile_shift2=-0.2, bore_diameter1="30 mm", bore_diameter2="80 mm",
    youngs_modulus="206 GPa", poisson_ratio=0.3, density="7850 kg/m^3", backlash="0.05 mm",
    torque1_value="150 N*m", torque2_value=-150 * RATIO, w1="1000 rpm",
    w2=f"{1000 * RPM / RATIO!r} rad/s", friction_coefficient=0, end_time="20 ms",
)

# The same pair written by hand as a case file: the keys case() leaves out
# take the case file's defaults.
PAIR_TOML = """
name = "my-pair"
[gears]
teeth1 = 23
teeth2 = 67
module = "3 mm"
pressure_angle = "20 deg"
face_width = "25 mm"
profile_shift1 = 0.2
profile_shift2 = -0.2
bore_diameter1 = "30 mm"
bore_diameter2 = "80 mm"
youngs_modulus = "206 GPa"
poisson_ratio = 0.3
density = "7850 kg/m^3"
backlash = "0.05 mm"
[torque1]
kind = "constant"
value = "150 N*m"
[torque2]
kind = "constant"
value = "%r N*m"
[initial]
w1 = "1000 rpm"
w2 = "%r rad/s"
[model]
friction_coefficient = 0.0
[integrator]
end_time = "20 ms"
""" % (-150 * RATIO, 1000 * RPM / RATIO)


def quiet(call):
    """call() with any GearimpactWarning an error: the call must not warn."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", gearimpact.GearimpactWarning)
        return call()


def my_pair(**changes):
    return quiet(lambda: gearimpact.case(name="my-pair", **{**PAIR, **changes}))


# 1. A case from keywords --------------------------------------------------------------------


def test_a_case_from_keywords_equals_the_case_file_written_by_hand():
    assert my_pair() == quiet(lambda: gearimpact.parse_case(PAIR_TOML, "my-pair.toml"))
    assert my_pair().name == "my-pair"


def test_keys_left_out_take_the_schemas_defaults():
    fields = my_pair().fields()
    # `gearimpact schema`: friction_law "constant", mesh_damping_ratio 0, integrator rk4 at 0.1 us.
    assert fields["integrator.kind"] == "rk4"
    assert fields["integrator.step"] == "1e-7 s"
    assert fields.get("model.friction_law", "constant") == "constant"
    assert fields.get("model.mesh_damping_ratio", 0.0) == 0.0


def test_bare_keys_section_keys_and_dotted_keys_name_the_same_fields():
    bare = my_pair()
    keys = {k: v for k, v in PAIR.items() if k not in ("bore_diameter1", "w1")}
    spelled = quiet(lambda: gearimpact.case(name="my-pair", gears_bore_diameter1="30 mm",
                                            **{"initial.w1": "1000 rpm"}, **keys))
    assert bare == spelled
    pair = bare.gears
    assert pair.teeth1 == 23 and pair.teeth2 == 67
    assert abs(pair.module_m / 3e-3 - 1) < FEW_ULPS
    fields = bare.fields()
    assert fields["gears.bore_diameter1"] == "0.03 m"
    assert fields["gears.bore_diameter2"] == "0.08 m"
    # A unit string is read as a case file reads it: 1000 rpm = 1000 pi / 30 rad/s.
    assert abs(float(fields["initial.w1"].split()[0]) / (1000 * RPM) - 1) < FEW_ULPS


def test_a_torque_kind_follows_from_its_keys():
    case = my_pair()
    assert case.fields()["torque1.kind"] == "constant"
    sinusoidal = quiet(lambda: case.replace(torque1_kind="sinusoidal", torque1_mean="150 N*m",
                                            torque1_amplitude="10 N*m",
                                            torque1_angular_frequency="100 rad/s"))
    keys = {k: v for k, v in PAIR.items() if k != "torque1_value"}
    implied = quiet(lambda: gearimpact.case(name="my-pair", torque1_mean="150 N*m",
                                            torque1_amplitude="10 N*m",
                                            torque1_angular_frequency="100 rad/s", **keys))
    assert implied == sinusoidal


def test_paper_case_and_replace_take_bare_optional_keys():
    case = gearimpact.paper_case(2, bore_diameter1="10 mm", bore_diameter2="50 mm")
    assert case.fields()["gears.bore_diameter1"] == "0.01 m"
    assert case.replace(poisson_ratio2=0.28).gears.poisson_ratio == 0.3


def test_missing_keys_are_listed_together():
    # The pair's keys alone make a gear pair alone: only the pair's missing keys are listed.
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.case(name="my-pair", teeth1=23, teeth2=67, module="3 mm")
    message = str(error.value)
    for key in ("pressure_angle", "face_width", "youngs_modulus", "poisson_ratio", "density",
                "backlash"):
        assert key in message, key
    for key in ("torque1_kind", "torque2_kind", "end_time"):
        assert key not in message, key
    assert "teeth1" not in message
    assert "gears.face_width, in mm: a length > 0 m" in message
    # A key of a run makes it a run: the run's keys are listed too.
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.case(name="my-pair", teeth1=23, teeth2=67, module="3 mm", w1="100 rpm")
    message = str(error.value)
    for key in ("pressure_angle", "backlash", "torque1_kind", "torque2_kind", "end_time"):
        assert key in message, key


def test_a_case_needs_a_name():
    keys = dict(PAIR)
    with pytest.raises(gearimpact.CaseError, match='name="my-pair"'):
        gearimpact.case(**keys)
    with pytest.raises(gearimpact.CaseError, match="name"):
        gearimpact.case(name="my pair", **keys)


@pytest.mark.parametrize(
    "typo, suggested",
    [
        ("modul", "module (gears.module)"),
        ("bore_diamter1", "bore_diameter1 (gears.bore_diameter1)"),
        ("torque1_valeu", "torque1_value (torque1.value)"),
        ("gears.face_widht", "face_width (gears.face_width)"),
        ("frictoin_coefficient", "friction_coefficient (model.friction_coefficient)"),
    ],
)
def test_a_misspelt_key_gets_the_nearest(typo, suggested):
    for call in (lambda: gearimpact.case(name="x", **{typo: 1}),
                 lambda: gearimpact.paper_case(1).replace(**{typo: 1})):
        with pytest.raises(gearimpact.CaseError) as error:
            call()
        assert error.value.field == typo
        assert f"did you mean {suggested}" in str(error.value)


def test_a_key_of_two_sections_and_a_key_given_twice_are_refused():
    with pytest.raises(gearimpact.CaseError, match="torque1.value .torque1_value., "
                                                   "torque2.value .torque2_value."):
        my_pair(value="1 N*m")
    with pytest.raises(gearimpact.CaseError, match="given twice"):
        my_pair(gears_module="3 mm")


# 2. Typed columns ---------------------------------------------------------------------------


def test_a_sweeps_columns_have_their_types():
    result = gearimpact.sweep(my_pair(), "w1", "1000 rpm", "1500 rpm", 3,
                              options=["--threads", "2"])
    sw = result["sweep"]
    assert sw["direction"].dtype.kind == "U" and sw["regime"].dtype.kind == "U"
    assert sw["converged"].dtype == np.bool_
    for name in ("line", "index", "period"):
        assert sw[name].dtype == np.int64, name
    assert sw["value_si"].dtype == np.float64 and sw["dte_mean_m"].dtype == np.float64
    # The selection: the up line's values, the grid from 1000 to 1500 rpm.
    up = sw["value_si"][sw["direction"] == "up"]
    expected = 1000 * RPM + np.arange(3) * (500 * RPM / 2)
    assert up.shape == (3,)
    assert np.all(np.abs(up / expected - 1) < FEW_ULPS)
    assert np.array_equal(sw["index"][sw["direction"] == "up"], [0, 1, 2])
    # Booleans are booleans: an unconverged point is not truthy.
    assert sw["converged"].all() == all(sw["period"] > 0)
    poincare = result["poincare"]
    assert poincare["index"].dtype == np.int64 and poincare["s_m"].dtype == np.float64


def test_columns_the_program_adds_arrive_with_their_types():
    # The types are read from the CSV, not from a list of today's columns: a new
    # speed column of whole numbers stays float64 (the program prints 1000.0 as
    # "1000"), a new word column is str, a new true/false column bool; an
    # empty figure is NaN; a regime column empty throughout stays str.
    from gearimpact import _program

    text = ("line,direction,index,regime,period,converged,pinion_rpm,flank,near_jump,dte_m\n"
            "0,up,0,,,false,1000,drive,true,\n"
            "0,up,1,,aperiodic,true,1500,coast,false,1.5e-05\n")
    table = _program._table(text)
    assert table["pinion_rpm"].dtype == np.float64
    assert table["flank"].tolist() == ["drive", "coast"]
    assert table["near_jump"].dtype == np.bool_ and table["near_jump"].tolist() == [True, False]
    assert np.isnan(table["dte_m"][0]) and table["dte_m"][1] == 1.5e-05
    assert table["regime"].dtype.kind == "U"
    # No period for an unconverged or aperiodic point: 0, as the library's SteadyPoint has it.
    assert table["period"].tolist() == [0, 0] and table["period"].dtype == np.int64


def test_counts_are_int64_elsewhere_too():
    table, _ = gearimpact.mesh_stiffness(samples=5)
    assert table["pairs"].dtype == np.int64
    assert set(table["pairs"].tolist()) <= {1, 2}
    assert gearimpact.energy_ratios(points=3)["pairs"].dtype == np.int64


# 3. One exception class for bad input -------------------------------------------------------


def test_the_exception_classes():
    assert issubclass(gearimpact.CaseError, ValueError)
    assert not issubclass(gearimpact.CaseError, RuntimeError)
    assert issubclass(gearimpact.ConvergenceError, RuntimeError)
    assert issubclass(gearimpact.QuadratureError, gearimpact.ConvergenceError)
    assert not issubclass(gearimpact.SimulationError, ValueError)
    assert issubclass(gearimpact.GearimpactWarning, UserWarning)


BAD_INPUT = [
    ("sweep with friction", lambda: gearimpact.sweep(
        gearimpact.paper_case(2), "initial.w1", "500 rad/s", "600 rad/s", 2)),
    ("sweep option", lambda: gearimpact.sweep(my_pair(), "w1", 1, 2, 2, options=["--bogus"])),
    ("sweep key", lambda: gearimpact.sweep(my_pair(), "w11", 1, 2, 2)),
    ("mesh stiffness model", lambda: gearimpact.mesh_stiffness(my_pair(), model="exact")),
    ("mesh stiffness without bores", lambda: gearimpact.mesh_stiffness(
        gearimpact.paper_case(2), model="potential-energy")),
    ("iso6336 helix", lambda: gearimpact.iso6336(my_pair(), helix_angle_deg=50)),
    ("reproduce data", lambda: gearimpact.reproduce("out", paper_data="/nonexistent-data")),
    ("simulate key", lambda: gearimpact.simulate(my_pair(), end_tim="1 ms")),
]


@pytest.mark.parametrize("call", [c for _, c in BAD_INPUT], ids=[n for n, _ in BAD_INPUT])
def test_every_bad_input_is_a_case_error(call, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(gearimpact.CaseError):
        call()


# 4. Warnings ---------------------------------------------------------------------------------


def test_unbalanced_torques_warn_with_the_balancing_torque():
    with pytest.warns(gearimpact.GearimpactWarning, match="mean torques unbalanced") as caught:
        gearimpact.case(name="my-pair", **{**PAIR, "torque2_value": "-436.96 N*m"})
    message = next(str(w.message) for w in caught if "unbalanced" in str(w.message))
    balancing = float(message.split("torque2_value=")[1].split(" ")[0])
    assert abs(balancing / (-150 * RATIO) - 1) < FEW_ULPS
    # The warning points at the caller's line, not into the package.
    assert all(w.filename == __file__ for w in caught)
    assert "accelerates without bound and has no steady state" in message
    # With friction, torques with an excess can hold a speed against it, so the warning says
    # what a steady speed needs instead of that none exists.
    with pytest.warns(gearimpact.GearimpactWarning, match="mean torques unbalanced") as caught:
        gearimpact.case(name="my-pair", **{**PAIR, "torque2_value": "-436.96 N*m",
                                           "friction_coefficient": 0.04})
    message = next(str(w.message) for w in caught if "unbalanced" in str(w.message))
    assert "friction's mean power" in message


def test_speeds_that_do_not_roll_warn_with_the_rolling_speed():
    with pytest.warns(gearimpact.GearimpactWarning, match="do not roll") as caught:
        gearimpact.case(name="my-pair", **{**PAIR, "w2": 0})
    message = str(caught[0].message)
    rolling = float(message.split('w2="')[1].split(" ")[0])
    assert abs(rolling / (1000 * RPM / RATIO) - 1) < FEW_ULPS


def test_the_foundation_fits_extrapolation_warns_and_keeps_its_key():
    # The 23-tooth pinion's theta_f lies beyond the fit's 0.12 rad.
    with pytest.warns(gearimpact.GearimpactWarning, match="fillet-foundation"):
        case = my_pair().replace(stiffness_model="potential-energy")
    with pytest.warns(gearimpact.GearimpactWarning, match="fillet-foundation"):
        _, summary = gearimpact.mesh_stiffness(case, samples=5)
    assert summary["extrapolated"] is True


def test_a_change_warns_of_what_it_brings_only():
    case2 = gearimpact.paper_case(2)  # Table 1's transient: unbalanced and not rolling
    quiet(lambda: case2.replace(end_time="1 ms"))
    with pytest.warns(gearimpact.GearimpactWarning, match="unbalanced"):
        my_pair().replace(torque1_value="100 N*m")
    quiet(lambda: my_pair().replace(torque1_value="100 N*m", torque2_value=-100 * RATIO))
    quiet(lambda: gearimpact.paper_case(1))


def test_warnings_can_be_errors():
    with warnings.catch_warnings():
        warnings.simplefilter("error", gearimpact.GearimpactWarning)
        with pytest.raises(gearimpact.GearimpactWarning):
            gearimpact.case(name="my-pair", **{**PAIR, "w2": 0})


# 5. repr -------------------------------------------------------------------------------------


def test_a_cases_repr_says_what_it_is():
    assert repr(my_pair()) == (
        "<gearimpact.Case 'my-pair': 23/67 teeth, module 3 mm, face width 25 mm; "
        "T1 = 150 N*m, T2 = -436.957 N*m; w1 = 104.72 rad/s (1000 rpm), "
        "w2 = 35.9486 rad/s (343.284 rpm)>")
    case3 = repr(gearimpact.paper_case(3))
    assert "sin(10000 rad/s t) N*m" in case3


# 6. Plain numbers for lengths ----------------------------------------------------------------


@pytest.mark.parametrize(
    "key, value, words",
    [
        ("module", 3, ['module = 3 m: SI metres assumed', 'did you mean "3 mm"?']),
        ("face_width", 25, ["face_width = 25 m", "0.1 mm to 2000 mm", 'did you mean "25 mm"?']),
        ("backlash", 0.05, ["backlash = 0.05 m", 'did you mean "0.05 mm"?']),
        # Too small to be millimetres either: no suggestion.
        ("module", 1e-5, ["module = 1e-5 m", "0.05 mm to 100 mm"]),
    ],
)
def test_an_implausible_plain_length_warns(key, value, words):
    with pytest.warns(gearimpact.GearimpactWarning) as caught:
        try:
            gearimpact.paper_case(1).replace(**{key: value})
        except gearimpact.CaseError:
            pass  # the length may break the pair; the warning came first
    message = str(caught[0].message)
    for word in words:
        assert word in message
    assert ("did you mean" in message) == (value > 1e-3)


def test_plausible_lengths_and_unit_strings_do_not_warn():
    quiet(lambda: my_pair(module=0.003, face_width=0.025, bore_diameter1=0.03, backlash=0.0))
    quiet(lambda: my_pair(module="3 mm", backlash="0 mm"))


def test_gear_pair_takes_optional_keys_and_only_keys_of_the_pair():
    pair = gearimpact.gear_pair(teeth1=23, teeth2=67, module="3 mm", bore_diameter1="30 mm")
    assert (pair.teeth1, pair.teeth2) == (23, 67)
    with pytest.raises(gearimpact.CaseError, match="not a key of .gears."):
        gearimpact.gear_pair(w1="100 rad/s")


def test_a_swept_length_given_as_a_plain_number_warns():
    with pytest.warns(gearimpact.GearimpactWarning, match='start = 10 m.*did you mean "10 mm"'):
        with pytest.raises(gearimpact.CaseError):
            gearimpact.sweep(my_pair(), "backlash", 10, 0.05e-3, 2)


def test_a_sweeps_own_warnings_arrive_as_warnings():
    # With no viscous mesh damping and D updated at every impact, up and down
    # sweeps differ by an artefact: the program warns, and so does Python.
    undamped = my_pair().replace(mesh_damping_ratio=0, damping_update="each-impact")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = gearimpact.sweep(undamped, "w1", "1000 rpm", "1500 rpm", 2,
                                  options=["--threads", "2"])
    texts = [str(w.message) for w in caught if issubclass(w.category, gearimpact.GearimpactWarning)]
    assert result["summary"]["warnings"], "the sweep itself warns"
    assert any("mesh_damping_ratio = 0" in text for text in texts), texts
    damped = my_pair().replace(mesh_damping_ratio=0.05)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = gearimpact.sweep(damped, "w1", "1000 rpm", "1500 rpm", 2,
                                  options=["--threads", "2"])
    assert not result["summary"]["warnings"]
    assert not any("mesh_damping_ratio = 0" in str(w.message) for w in caught)


def test_a_loose_gear_case_reads_builds_and_runs_from_python():
    # A kinematic driver and a drag have no mean torque before the run: no
    # balance to warn about, and the case builds, prints and runs.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        driven = gearimpact.paper_case(1).replace(
            torque1_kind="prescribed-speed", mean_speed="800 rpm", orders=[2],
            speed_amplitudes=["8 rad/s"], torque1_phases=["0 deg"], torque2_kind="drag",
            drag_constant="0.05 N*m", drag_viscous="1e-4 N*m*s/rad", w1="800 rpm",
            w2="200 rpm", end_time="5 ms")
        text = repr(driven)
        assert "a driver at 83.7758 rad/s (800 rpm) + 1 orders" in text, text
        assert "a drag of 0.05 N*m" in text, text
        result = gearimpact.simulate(driven)
    assert result.summary["rattle_regime"] in ("no-impact", "single-sided", "double-sided")


def test_iso6336_takes_a_load_as_the_program_does():
    # 50 N/mm is half ISO's 100 N/mm: c' takes (1/2)^0.25.
    plain = gearimpact.iso6336(my_pair())
    loaded = gearimpact.iso6336(my_pair(), load="50 N/mm")
    assert abs(loaded["low_load_factor"] - 0.5 ** 0.25) < FEW_ULPS
    assert abs(loaded["c_prime_n_mm_um"] / plain["c_prime_n_mm_um"] - 0.5 ** 0.25) < 1e-12
    with pytest.raises(gearimpact.CaseError, match="load"):
        gearimpact.iso6336(my_pair(), load="50 N/mmm")


# Faulted teeth ---------------------------------------------------------------------------------


FAULT_TOML = """
[[faults]]
gear = "pinion"
tooth = 0
kind = "root-crack"
depth = "0.5 mm"
angle = "45 deg"
"""


def test_faults_from_keywords_read_as_the_case_file_does():
    faulted = my_pair(faults=[dict(gear="pinion", tooth=0, kind="root-crack", depth="0.5 mm",
                                   angle="45 deg")])
    assert faulted == quiet(lambda: gearimpact.parse_case(PAIR_TOML + FAULT_TOML, "my-pair.toml"))
    assert faulted != my_pair()
    # A change of another key keeps the faults.
    assert "[[faults]]" in faulted.replace(end_time="10 ms").to_toml("si")


SURFACE_FAULT_TOML = """
[[faults]]
gear = "pinion"
tooth = 0
kind = "spall"
depth = "0.3 mm"
width = "8 mm"
start_radius = "35 mm"
end_radius = "36.5 mm"
flank = "coast"

[[faults]]
gear = "pinion"
tooth = 1
kind = "tip-chip"
radius = "37.5 mm"
width = "5 mm"
"""


def test_a_spall_and_a_chip_from_keywords_read_as_the_case_file_does():
    faulted = my_pair(faults=[
        dict(gear="pinion", tooth=0, kind="spall", depth="0.3 mm", width="8 mm",
             start_radius="35 mm", end_radius="36.5 mm", flank="coast"),
        dict(gear="pinion", tooth=1, kind="tip-chip", radius="37.5 mm", width="5 mm")])
    assert faulted == quiet(
        lambda: gearimpact.parse_case(PAIR_TOML + SURFACE_FAULT_TOML, "my-pair.toml"))
    # The pinion's half thickness at r = 36.5 mm is about 2 mm: a 3 mm pit does not fit.
    with pytest.raises(gearimpact.CaseError) as error:
        my_pair(faults=[dict(gear="pinion", tooth=0, kind="spall", depth="3 mm", width="8 mm",
                             start_radius="35 mm", end_radius="36.5 mm")])
    assert "faults[0].depth" in str(error.value)
    assert "the half thickness of the pinion tooth" in str(error.value)


def test_a_fault_on_a_tooth_the_gear_lacks_names_the_key_and_range():
    with pytest.raises(gearimpact.CaseError) as error:
        my_pair(faults=[dict(gear="pinion", tooth=25, kind="missing")])
    assert "faults[0].tooth" in str(error.value)
    assert "0 ... " in str(error.value)
    with pytest.raises(gearimpact.CaseError):
        my_pair(faults=dict(gear="pinion", tooth=0, kind="missing"))


def test_mesh_stiffness_and_ste_of_a_faulted_case_span_its_true_period():
    faulted = my_pair(faults=[dict(gear="pinion", tooth=0, kind="missing")])
    table, summary = gearimpact.mesh_stiffness(faulted, samples=4)
    # A pinion tooth missing: one pinion revolution, z1 = 23 mesh periods of 4 samples.
    assert summary["period"] == "pinion-revolution"
    assert summary["mesh_periods"] == 23
    assert len(table["fraction"]) == 4 * 23
    assert summary["mean_n_m"] < summary["healthy_mean_n_m"]
    # The missing tooth's pair alone in the segment carries nothing: ste_m is NaN there.
    with pytest.warns(UserWarning, match="missing tooth"):
        ste = gearimpact.ste(faulted, torque="10 N*m", points=4)
    assert len(ste["ste"]["ste_m"]) == 4 * 23
    uncarried = int(np.isnan(ste["ste"]["ste_m"]).sum())
    assert uncarried == ste["summary"]["uncarried_points"] > 0
    assert ste["summary"]["unmodified_uncarried_points"] == 0
