"""The Python API itself: cases from keyword arguments, errors, the columns
against the equations they hold, the GIL and Ctrl-C."""

import math
import os
import signal
import subprocess
import sys
import threading
import time

import gearimpact
import numpy as np
import pytest

# Rounding in a few operations of double arithmetic: a handful of ulps.
FEW_ULPS = 8 * np.finfo(float).eps


# Cases and keyword arguments ------------------------------------------------


def test_paper_cases_equal_the_hand_written_case_files():
    # paper_data/caseN.toml is Table 1 written by hand in readable units;
    # paper_case(N) is the library's Table 1: two independent writings.
    for n in (1, 2, 3):
        assert gearimpact.read_case(gearimpact.paper_data_dir() / f"case{n}.toml") == \
            gearimpact.paper_case(n)


def test_replace_leaves_the_other_fields_and_the_original_alone():
    case = gearimpact.paper_case(1)
    before = case.fields()
    changed = case.replace(module="2.5 mm", friction_coefficient=0.06)
    assert case.fields() == before
    after = changed.fields()
    assert after["gears.module"] == "0.0025 m"
    assert after["model.friction_coefficient"] == 0.06
    assert {k: v for k, v in after.items() if k not in ("gears.module", "model.friction_coefficient")} \
        == {k: v for k, v in before.items() if k not in ("gears.module", "model.friction_coefficient")}
    assert case.replace() == case


def test_unit_strings_and_si_floats_give_the_same_case():
    case = gearimpact.paper_case(2)
    assert case.replace(module="2.5 mm", step="0.05 us", w1="60 rad/s") == \
        case.replace(module=0.0025, step=5e-8, w1=60.0)
    assert case.replace(pressure_angle="25 deg").gears.pressure_angle_rad == \
        pytest.approx(25 * math.pi / 180, rel=FEW_ULPS)
    assert case.replace(**{"torque1.value": "50 N*mm"}).fields()["torque1.value"] == "0.05 N*m"
    assert case.replace(torque1_value="50 N*mm") == case.replace(**{"torque1.value": "50 N*mm"})


def test_a_torque_of_another_kind_is_given_whole():
    # Case 1's free gear 1 turned into case 3's sinusoidal forcing.
    case = gearimpact.paper_case(1).replace(**{
        "torque1.kind": "sinusoidal",
        "torque1.amplitude": "200 kgf*mm",
    }, torque1_angular_frequency="10000 rad/s")
    case3 = gearimpact.paper_case(3).fields()
    assert {k: v for k, v in case.fields().items() if k.startswith("torque1.")} == \
        {k: v for k, v in case3.items() if k.startswith("torque1.")}
    with pytest.raises(gearimpact.CaseError, match="amplitude"):
        gearimpact.paper_case(1).replace(**{"torque1.kind": "sinusoidal"})


def test_bool_for_on_off_switches():
    case = gearimpact.paper_case(1).replace(axial_term=False)
    assert case.fields()["model.axial_term"] == "off"
    assert case.stiffness_model.term("axial") is False


def test_gear_pair_from_keys():
    pair = gearimpact.gear_pair(teeth1=25, module="3 mm", face_width=0.02)
    assert (pair.teeth1, pair.teeth2, pair.module_m, pair.face_width_m) == (25, 80, 0.003, 0.02)


@pytest.mark.parametrize(
    "changes, field, words",
    [
        ({"module": "-2 mm"}, "gears.module", ["module='-2 mm'", "[1e-6, 1] m"]),
        ({"module": "2 kg"}, "gears.module", ["module='2 kg'", "mm"]),
        ({"teeth1": 2}, "gears.teeth1", ["teeth1=2", "[4, 100000]"]),
        ({"poisson_ratio": 0.7}, "gears.poisson_ratio", ["poisson_ratio=0.7", "0.5"]),
        ({"damping_form": "viscous"}, "model.damping_form", ["damping_form='viscous'", "lee-wang"]),
        ({"modul": 1}, "modul", ["modul", "gears.module"]),
        ({"kind": "adaptive"}, "kind", ["integrator.kind", "torque1.kind"]),
        ({"module": [1]}, "module", ["module=[1]", "list"]),
        (
            {"friction_smoothing_speed": "1e300 m/s"},
            "model.friction_smoothing_speed",
            ["friction_smoothing_speed='1e300 m/s'", "0.1 m/s"],
        ),
    ],
)
def test_bad_keyword_arguments_name_the_key_and_the_range(changes, field, words):
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.paper_case(1).replace(**changes)
    assert error.value.field == field
    for word in words:
        assert word in str(error.value)
    assert "<keyword arguments>" not in str(error.value)


def test_a_smoothing_speed_the_step_cannot_resolve_is_refused_before_the_run():
    # Case 2 at 0.1 us needs v_s >= 10 h Rb1 |w1| (|w1| + |w2|) = 4.698e-05 m/s.
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.simulate(2, keep_series=False, friction_smoothing_speed="1e-5 m/s")
    assert "model.friction_smoothing_speed" in str(error.value)
    assert ">= 4.698e-05 m/s" in str(error.value)
    result = gearimpact.simulate(
        2, keep_series=False, end_time="0.2 ms", friction_smoothing_speed="1e-4 m/s"
    )
    assert result.summary["friction_loss_J"] > 0


def test_errors_are_value_and_runtime_errors():
    assert issubclass(gearimpact.CaseError, ValueError)
    assert issubclass(gearimpact.QuadratureError, RuntimeError)
    assert issubclass(gearimpact.SimulationError, RuntimeError)


def test_a_broken_case_file_names_file_line_and_key(source_dir):
    path = source_dir / "fuzz" / "corpus" / "case_file" / "broken-poisson.toml"
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.read_case(path)
    assert error.value.file == str(path)
    assert error.value.field == "gears.poisson_ratio"
    assert str(path) in str(error.value)


def test_a_step_too_large_for_the_contact_is_a_case_error():
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.simulate(1, step="1 ms")
    assert "step" in error.value.field


# Stiffness and geometry against their equations ------------------------------


def test_geometry_against_the_involute_formulas():
    pair = gearimpact.GearPair()
    rb1 = pair.module_m * pair.teeth1 / 2 * math.cos(pair.pressure_angle_rad)
    rb2 = pair.module_m * pair.teeth2 / 2 * math.cos(pair.pressure_angle_rad)
    ra1 = pair.module_m * (pair.teeth1 / 2 + pair.addendum_coefficient)
    ra2 = pair.module_m * (pair.teeth2 / 2 + pair.addendum_coefficient)
    lp = (rb1 + rb2) * math.tan(pair.pressure_angle_rad)
    start, end = gearimpact.contact_segment(pair)
    # Each a few operations from the same inputs: a few ulps apart at most.
    for ours, formula in [
        (gearimpact.base_radius(pair, 1), rb1),
        (gearimpact.base_radius(pair, 2), rb2),
        (gearimpact.tip_radius(pair, 2), ra2),
        (gearimpact.line_of_action_length(pair), lp),
        (end, math.sqrt(ra1**2 - rb1**2)),
        (start, lp - math.sqrt(ra2**2 - rb2**2)),
        (gearimpact.base_pitch(pair), math.pi * pair.module_m * math.cos(pair.pressure_angle_rad)),
    ]:
        assert abs(ours - formula) <= FEW_ULPS * abs(formula)


def test_stiffness_columns_hold_equations_4_and_29():
    pair = gearimpact.GearPair()
    k = gearimpact.stiffness(pair, points=11)
    kh = math.pi * pair.youngs_modulus_pa * pair.face_width_m / (4 * (1 - pair.poisson_ratio**2))
    assert np.all(np.abs(k["kh"] - kh) <= FEW_ULPS * kh)
    series = 1 / (1 / k["kh"] + 1 / k["kb1"] + 1 / k["ka1"] + 1 / k["kb2"] + 1 / k["ka2"])
    assert np.all(np.abs(k["ke"] - series) <= FEW_ULPS * series)
    start, end = gearimpact.contact_segment(pair)
    assert k["x_m"][0] == start and k["x_m"][-1] == end
    rb1 = gearimpact.base_radius(pair, 1)
    theta_b1 = math.pi / (2 * pair.teeth1) + math.tan(pair.pressure_angle_rad) - pair.pressure_angle_rad
    phi1 = k["x_m"] / rb1 - theta_b1  # (12)
    assert np.all(np.abs(k["phi1_rad"] - phi1) <= FEW_ULPS * 4)


def test_stiffness_at_given_positions_matches_the_samples():
    samples = gearimpact.stiffness(points=7)
    at = gearimpact.stiffness(x=samples["x_m"][1:5])
    for name in ("kb1", "ka2", "ke"):
        assert np.array_equal(at[name], samples[name][1:5])


def test_stiffness_arguments_out_of_range():
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.stiffness(x=[0.005, 1.0])
    assert error.value.field == "x[1]"
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.stiffness(points=1)
    assert error.value.field == "points"
    with pytest.raises(gearimpact.CaseError):
        gearimpact.stiffness(points=5, x=[0.005])
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.stiffness(method="simpson")
    assert "gsl-cquad" in str(error.value)
    pair = gearimpact.GearPair()
    pair.teeth1 = 3
    with pytest.raises(gearimpact.CaseError):
        gearimpact.stiffness(pair)


# Simulation -----------------------------------------------------------------


def test_series_columns_hold_their_definitions():
    result = gearimpact.simulate(2, end_time="5 ms", output_every=7)
    s = result.series
    pair = result.case.gears
    rb1, rb2 = gearimpact.base_radius(pair, 1), gearimpact.base_radius(pair, 2)
    # s = Rb1 theta1 - Rb2 theta2 along the line of action: the columns are
    # the angles and s they are named after, to rounding of the two products.
    scale = np.abs(rb1 * s["theta1_rad"]) + np.abs(rb2 * s["theta2_rad"])
    assert np.all(np.abs(s["s_m"] - (rb1 * s["theta1_rad"] - rb2 * s["theta2_rad"])) <= FEW_ULPS * scale)
    # The output grid: every 7th step of 0.1 us.
    assert np.allclose(np.diff(s["t_s"])[:-1], 7e-7, rtol=1e-9, atol=0)
    assert set(np.unique(s["region"])) <= {-1, 0, 1}
    assert np.all(s["delta_m"][s["region"] == 0] == 0)
    assert np.all(s["normal_force_N"][s["region"] == 0] == 0)
    impacts = result.impacts
    assert len(impacts) == result.summary["impacts_n1"] + result.summary["impacts_n2"]
    assert sum(i["line"] == "N1" for i in impacts) == result.summary["impacts_n1"]
    assert impacts[0]["start_s"] == result.summary["first_impact_s"]


def test_the_mesh_damper_loss_is_a_term_of_its_own_and_closes_the_ledger():
    # No Hertzian damping: the viscous mesh damper alone dissipates at the
    # contacts, and its loss is mesh_damper_loss_J.
    result = gearimpact.simulate(
        2, keep_series=False, end_time="5 ms", damping_update="off", mesh_damping_ratio=0.05
    )
    s = result.summary
    assert s["damping_loss_J"] == 0
    closure = (
        s["kinetic_energy_final_J"] + s["stored_energy_final_J"]
        - s["kinetic_energy_initial_J"] - s["stored_energy_initial_J"]
        - s["torque_work_J"] + s["damping_loss_J"] + s["friction_loss_J"]
        + s["mesh_damper_loss_J"] - s["parametric_work_J"]
    )
    # The printed terms sum to the printed residual but for the rounding of
    # sums of terms of the scale's size; the residual is within the ledger's
    # bound (1e-7 of the scale), the damper's loss far above it.
    assert abs(closure - s["ledger_residual_J"]) < 1e-12 * s["ledger_scale_J"]
    assert abs(s["ledger_residual_J"]) < 1e-7 * s["ledger_scale_J"]
    assert s["mesh_damper_loss_J"] > 1e-5 * s["ledger_scale_J"]
    assert "mesh damper loss" in repr(result)
    plain = gearimpact.simulate(2, keep_series=False, end_time="1 ms")
    assert "mesh_damper_loss_J" not in plain.summary


def test_without_the_series():
    result = gearimpact.simulate(1, keep_series=False, end_time="2 ms")
    assert all(len(column) == 0 for column in result.series.values())
    assert result.summary["steps"] >= 20000


def test_sweep_friction_names_its_columns_after_the_cases():
    table = gearimpact.sweep_friction(
        [gearimpact.paper_case(1, name="free"), gearimpact.paper_case(2, name="loaded")],
        from_=0.02, to=0.04, step=0.02, end_time="2 ms")
    assert list(table) == ["f", "ratio_free", "ratio_loaded"]
    assert np.array_equal(table["f"], [0.02, 0.04])
    with pytest.raises(gearimpact.CaseError):
        gearimpact.sweep_friction([1, 1])


def test_the_gil_is_released_while_a_case_runs():
    # A Python thread started while the simulation runs finishes before it
    # does: it could not run at all if the simulation held the GIL. Case 1
    # over 2 s of simulated time is 20 million steps, far longer than the
    # thread's few operations.
    order = []
    entered = threading.Event()

    def run():
        entered.set()
        gearimpact.simulate(1, keep_series=False, end_time="2 s")
        order.append("simulation")

    simulation = threading.Thread(target=run)
    simulation.start()
    entered.wait()
    time.sleep(0.2)  # into the C++ call
    other = threading.Thread(target=lambda: order.append("other thread"))
    other.start()
    other.join()
    simulation.join()
    assert order == ["other thread", "simulation"]


INTERRUPTED = {
    "simulate": "gearimpact.simulate(1, keep_series=False, end_time='90 s')",
    "sweep_friction": "gearimpact.sweep_friction(end_time='20 s')",
    "stiffness": "gearimpact.stiffness(points=1000000)",
}


@pytest.mark.parametrize("call", sorted(INTERRUPTED))
def test_ctrl_c_stops_a_long_computation(call):
    # Each call would take minutes (9e8 steps; 27 runs of 2e8; a million
    # quadratures). SIGINT must end it with KeyboardInterrupt; the timeout
    # only keeps a broken build from hanging the suite.
    code = (
        "import gearimpact, sys\n"
        "print('started', flush=True)\n"
        "try:\n"
        f"    {INTERRUPTED[call]}\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n"
        "    sys.exit(0)\n"
        "sys.exit(3)\n"
    )
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True,
                             env=os.environ.copy())
    assert child.stdout.readline().strip() == "started"
    time.sleep(1.0)  # into the C++ call
    child.send_signal(signal.SIGINT)
    try:
        out, _ = child.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        child.kill()
        pytest.fail(f"{call} did not stop on SIGINT")
    assert child.returncode == 0 and "interrupted" in out


# The program and the data that come with the package ------------------------


def test_reproduce_with_the_bundled_program(tmp_path):
    report = gearimpact.reproduce(tmp_path / "out")
    assert report == tmp_path / "out" / "REPORT.md"
    assert "unexplained failures: 0" in report.read_text()
    assert (tmp_path / "out" / "case1_time_series.csv").is_file()


def test_reproduce_names_a_missing_data_folder(tmp_path):
    with pytest.raises(gearimpact.CaseError, match=str(tmp_path / "nowhere")):
        gearimpact.reproduce(tmp_path / "out", paper_data=tmp_path / "nowhere")


def test_replace_reaches_keys_the_writer_leaves_out_at_their_defaults():
    # friction_law is not among paper_case(2)'s fields (the constant law is left out); the bare
    # key still names it, and the new law's keys come with it.
    case = gearimpact.paper_case(2)
    assert "model.friction_law" not in case.fields()
    bk = case.replace(friction_law="benedict-kelley", lubricant_viscosity="100 cP",
                      surface_roughness="0.4 um")
    fields = bk.fields()
    assert fields["model.friction_law"] == "benedict-kelley"
    assert fields["model.lubricant_viscosity"] == "0.1 Pa*s"  # the fields are in SI
    with pytest.raises(gearimpact.CaseError, match="model.lubricant_viscosity"):
        case.replace(friction_law="benedict-kelley")
