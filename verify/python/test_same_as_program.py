"""Python gives the program's numbers bit for bit: the same function of the
library behind both, the same sampling, the same case. The program's CSV and
JSON are parsed at their 17 significant digits, which read back exactly."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np

import gearimpact
import pytest

from conftest import assert_bitwise_equal, parse_csv

STIFFNESS_COLUMNS = ["x_m", "phi1_rad", "kb1", "ka1", "kb2", "ka2", "kh", "ke", "ks1", "ks2", "kf1", "kf2"]
SERIES_COLUMNS = [
    "t_s", "theta1_rad", "theta2_rad", "w1_rad_s", "w2_rad_s", "s_m", "delta_m",
    "region", "pairs", "normal_force_N", "friction_force_N",
]


def assert_same_table(ours, program_csv, columns, what):
    theirs = parse_csv(program_csv)
    assert list(theirs) == columns, f"{what}: the program's columns changed"
    assert list(ours)[: len(columns)] == columns
    for name in columns:
        assert_bitwise_equal(ours[name], theirs[name], f"{what}, {name}")


@pytest.mark.parametrize(
    "options, arguments",
    [
        ([], {}),
        (["--points", "17", "--method", "xform"], {"points": 17, "method": "xform"}),
        (["--points", "9", "--method", "boost-gk", "--flipped-moment"],
         {"points": 9, "method": "boost-gk", "flipped_moment": True}),
    ],
)
def test_stiffness_of_the_papers_pair(cli, options, arguments):
    assert_same_table(gearimpact.stiffness(**arguments), cli("stiffness", *options),
                      STIFFNESS_COLUMNS, f"stiffness {options}")


def test_stiffness_of_a_case_file(cli):
    path = gearimpact.paper_data_dir() / "case2.toml"
    assert_same_table(gearimpact.stiffness(path, points=13, method="gsl-cquad"),
                      cli("stiffness", "--case-file", path, "--points", "13", "--method",
                          "gsl-cquad"),
                      STIFFNESS_COLUMNS, "stiffness of case2.toml")


def test_energy_ratios(cli):
    columns = ["angle_deg", "pairs", "hertz_over_bending_one_pair", "axial_over_bending_one_pair",
               "hertz_over_bending_system", "axial_over_bending_system"]
    assert_same_table(gearimpact.energy_ratios(), cli("energy-ratios"), columns, "energy ratios")
    assert_same_table(gearimpact.energy_ratios(points=31, flipped_moment=True),
                      cli("energy-ratios", "--points", "31", "--flipped-moment"), columns,
                      "energy ratios, flipped moment")


def simulate_both(cli, tmp_path, program_options, case, **changes):
    out = tmp_path / "series.csv"
    summary = json.loads(cli("simulate", *program_options, "--out", out))
    result = gearimpact.simulate(case, **changes)
    assert result.summary == summary, "the JSON summaries differ"
    assert_same_table(result.series, out.read_text(), SERIES_COLUMNS, f"simulate {program_options}")
    return result


def test_simulate_case1_whole_run(cli, tmp_path):
    # Every 10th row of the 300,001 keeps the CSV near 7 MB; the summary
    # covers every step.
    result = simulate_both(cli, tmp_path, ["--case", "1", "--every", "10"], 1, output_every=10)
    assert len(result.series["t_s"]) == 30001


def test_simulate_with_the_readings_changed(cli, tmp_path):
    # The program's reading options against the case-file keys that hold them.
    simulate_both(
        cli, tmp_path,
        ["--case", "3", "--friction", "0.07", "--dt", "5e-8", "--t-end", "0.004",
         "--damping-form", "hunt-crossley", "--damping-stiffness", "pitch-pair",
         "--restitution-exponent", "0.36", "--speed-unit", "in/s", "--coast-phase", "in-phase"],
        3, friction_coefficient=0.07, step=5e-8, end_time="4 ms", damping_form="hunt-crossley",
        damping_stiffness="pitch-pair-at-impact", restitution_exponent=0.36,
        restitution_speed_unit="1 in/s", coast_phase="in-phase")


def test_simulate_table1_torques_in_newton_millimetres(cli, tmp_path):
    simulate_both(cli, tmp_path, ["--case", "2", "--torque-unit", "n-mm", "--t-end", "0.003"],
                  gearimpact.paper_case(2, torque_unit="n-mm"), end_time=0.003)


def test_simulate_a_case_with_relief_and_a_pitch_error(cli, tmp_path):
    # Case 2 with both tips relieved and one pinion tooth out of position: the
    # dynamics read the gaps, the same in Python as in the program.
    path = tmp_path / "relieved.toml"
    pitch = ", ".join('"0.05 um"' if i == 0 else '"0 um"' for i in range(20))
    path.write_text((gearimpact.paper_data_dir() / "case2.toml").read_text()
                    + '\n[modifications]\ntip_relief1 = "0.2 um"\n'
                    + 'tip_relief_start1 = "43.2 mm"\ntip_relief2 = "0.2 um"\n'
                    + f'tip_relief_start2 = "163.2 mm"\npitch_deviations1 = [{pitch}]\n')
    relieved = simulate_both(cli, tmp_path, ["--case-file", path, "--t-end", "0.003"], path,
                             end_time="3 ms")
    plain = gearimpact.simulate(gearimpact.paper_data_dir() / "case2.toml", end_time="3 ms")
    assert relieved.summary["final_w2_rad_s"] != plain.summary["final_w2_rad_s"]


def test_simulate_a_case_file_with_the_adaptive_integrator(cli, tmp_path):
    path = gearimpact.paper_data_dir() / "case2.toml"
    simulate_both(cli, tmp_path,
                  ["--case-file", path, "--integrator", "adaptive", "--t-end", "0.002"],
                  path, integrator_kind="adaptive", end_time="2 ms")


def test_sweep_friction(cli):
    ours = gearimpact.sweep_friction(from_=0.02, to=0.06, step=0.02, end_time="5 ms")
    theirs = cli("sweep-friction", "--from", "0.02", "--to", "0.06", "--step", "0.02", "--t-end",
                 "0.005")
    assert_same_table(ours, theirs, ["f", "ratio_case1", "ratio_case2", "ratio_case3"],
                      "sweep-friction")


def test_iso6336_and_mesh_stiffness_equal_the_program(cli, source_dir, tmp_path):
    # The paper's pair: ISO's c'b for it is 1.34e8 N/m (docs/stiffness-models.md, section 3, Which stiffness model).
    ours = gearimpact.iso6336()
    assert ours == json.loads(cli("iso6336", "--helix-angle", "0.0"))
    assert abs(ours["c_prime_b_n_m"] / 1.34e8 - 1.0) < 5e-3
    table, summary = gearimpact.mesh_stiffness(samples=40)
    theirs = parse_csv(cli("mesh-stiffness", "--samples", "40"))
    assert set(table) == set(theirs)
    for name in theirs:
        assert_bitwise_equal(table[name], theirs[name], f"mesh-stiffness {name}")
    assert summary == json.loads(cli("mesh-stiffness", "--samples", "40", "--summary"))
    # A faulted pair: the true period (a pinion revolution) with each pair's teeth, the same.
    faulted = str(tmp_path / "cracked.toml")
    Path(faulted).write_text(
        (Path(source_dir) / "paper_data" / "case1.toml").read_text()
        + '\n[[faults]]\ngear = "pinion"\ntooth = 3\nkind = "root-crack"\n'
        'depth = "0.8 mm"\nangle = "45 deg"\n')
    table, summary = gearimpact.mesh_stiffness(gearimpact.read_case(faulted), samples=6)
    theirs = parse_csv(cli("mesh-stiffness", "--case-file", faulted, "--samples", "6"))
    assert set(table) == set(theirs)
    for name in theirs:
        assert_bitwise_equal(table[name], theirs[name], f"faulted mesh-stiffness {name}")
    assert summary == json.loads(
        cli("mesh-stiffness", "--case-file", faulted, "--samples", "6", "--summary"))
    assert summary["period"] == "pinion-revolution"
    table, summary = gearimpact.mesh_stiffness(samples=40)
    # The exact time mean lies between the extremes of the samples' range.
    assert summary["min_n_m"] <= summary["mean_n_m"] <= summary["max_n_m"]


@pytest.mark.parametrize("case_path, start, stop", [
    # The sharded tests' case, a short line.
    ("verify/slurm/sharded-sweep.toml", "3000 rad/s", "4000 rad/s"),
    # A helical pair (GEARpie's H501), run in its transverse section with the slice model's
    # face-integrated pair table (docs/helical.md, Dynamics).
    ("examples/helical_h501_run.toml", "100 rad/s", "300 rad/s"),
])
def test_sweep_equals_the_program(cli, source_dir, tmp_path, case_path, start, stop):
    case_file = Path(source_dir) / case_path
    case = gearimpact.read_case(case_file)
    ours = gearimpact.sweep(case, "initial.w1", start, stop, 2, direction="up")
    out = tmp_path / "out"
    cli("sweep", case_file, "--vary", "initial.w1", "--from", start, "--to", stop,
        "--points", "2", "--direction", "up", "--out", out, "--no-plots")
    lines = (out / "sweep.csv").read_text().strip().splitlines()
    header = lines[0].split(",")
    assert list(ours["sweep"]) == header
    for j, name in enumerate(header):
        written = [line.split(",")[j] for line in lines[1:]]
        column = ours["sweep"][name]
        if column.dtype == np.float64:
            assert_bitwise_equal(column, [float(v) if v else np.nan for v in written],
                                 f"sweep {name}")
        else:
            assert [as_written(v) for v in column.tolist()] == written, name
    assert ours["summary"] == json.loads((out / "summary.json").read_text())


def as_written(value):
    """A value of a typed column as the program writes it: a bool as true/false."""
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def test_ste_equals_the_program(cli, tmp_path):
    # Case 2 with tip relief on the pinion and one pinion tooth out of position.
    case_file = tmp_path / "relieved.toml"
    pitch = ", ".join('"5 um"' if i == 0 else '"0 um"' for i in range(20))
    case_file.write_text((gearimpact.paper_data_dir() / "case2.toml").read_text()
                         + '\n[modifications]\ntip_relief1 = "10 um"\n'
                         + 'tip_relief_start1 = "43.2 mm"\n'
                         + f"pitch_deviations1 = [{pitch}]\n")
    case = gearimpact.read_case(case_file)
    ours = gearimpact.ste(case, torque="100 N*m", points=20)
    out = tmp_path / "out"
    cli("ste", case_file, "--torque", "100 N*m", "--points", "20", "--out", out, "--no-plots")
    for key, name in (("ste", "ste.csv"), ("unmodified", "ste_unmodified.csv")):
        lines = (out / name).read_text().strip().splitlines()
        header = lines[0].split(",")
        assert list(ours[key]) == header
        for j, column_name in enumerate(header):
            written = [line.split(",")[j] for line in lines[1:]]
            column = ours[key][column_name]
            if column.dtype == np.float64:
                assert_bitwise_equal(column, [float(v) if v else np.nan for v in written],
                                     f"ste {name} {column_name}")
            else:
                assert [as_written(v) for v in column.tolist()] == written, column_name
    assert ours["summary"] == json.loads((out / "summary.json").read_text())
    # A number is N m.
    assert gearimpact.ste(case, torque=100.0, points=20)["summary"] == ours["summary"]
    with pytest.raises(gearimpact.CaseError, match="torque"):
        gearimpact.ste(case, torque="0 N*m", points=20)


def test_ste_of_errors_drawn_from_a_tolerance_class_equals_the_program(cli, tmp_path):
    # Case 2 with the pinion's errors drawn from ISO 1328-1 class 6: the
    # keywords give the case the file gives, and the drawn teeth reach the STE
    # of both alike, bit for bit.
    case_file = tmp_path / "class6.toml"
    case_file.write_text((gearimpact.paper_data_dir() / "case2.toml").read_text()
                         + "\n[modifications]\niso1328_class1 = 6\nerror_seed = 42\n")
    case = gearimpact.read_case(case_file)
    plain = gearimpact.read_case(gearimpact.paper_data_dir() / "case2.toml")
    assert case == plain.replace(iso1328_class1=6, error_seed=42)
    assert case != plain.replace(iso1328_class1=6, error_seed=43)
    ours = gearimpact.ste(case, torque="100 N*m", points=20)
    out = tmp_path / "out"
    cli("ste", case_file, "--torque", "100 N*m", "--points", "20", "--out", out, "--no-plots")
    lines = (out / "ste.csv").read_text().strip().splitlines()
    header = lines[0].split(",")
    j = header.index("ste_m")
    assert_bitwise_equal(ours["ste"]["ste_m"], [float(line.split(",")[j]) for line in lines[1:]],
                         "ste_m")
    # The pinion's teeth differ: the STE repeats once a pinion revolution.
    assert len(lines) - 1 == 20 * 20
    with pytest.raises(gearimpact.CaseError, match="iso1328_class1"):
        plain.replace(iso1328_class1=12)


def test_modes_equal_the_program(cli, tmp_path):
    # Case 1 on elastic bearings with a motor and a load: 8 DOF.
    case_file = tmp_path / "planar.toml"
    case_file.write_text((gearimpact.paper_data_dir() / "case1.toml").read_text()
                         + '\n[bearings]\nkind = "elastic"\nstiffness_x1 = "500 N/um"\n'
                         + 'stiffness_x2 = "700 N/um"\n'
                         + '[shafts]\nkind = "elastic"\nmotor_inertia = "2e-3 kg*m^2"\n'
                         + 'motor_stiffness = "5e4 N*m/rad"\nload_inertia = "8e-3 kg*m^2"\n'
                         + 'load_stiffness = "9e4 N*m/rad"\n')
    case = gearimpact.read_case(case_file)
    ours = gearimpact.modes(case, harmonics=2, max_speed="20000 rpm")
    out = tmp_path / "out"
    cli("modes", case_file, "--harmonics", "2", "--max-speed", "20000 rpm", "--out", out,
        "--no-plots")
    for key, name in (("modes", "modes.csv"), ("campbell", "campbell.csv"),
                      ("mode_shapes", "mode_shapes.csv")):
        lines = (out / name).read_text().strip().splitlines()
        header = lines[0].split(",")
        assert list(ours[key]) == header
        for j, column_name in enumerate(header):
            written = [line.split(",")[j] for line in lines[1:]]
            column = ours[key][column_name]
            if column.dtype == np.float64:
                assert_bitwise_equal(column, [float(v) for v in written], f"{name} {column_name}")
            else:
                assert [as_written(v) for v in column.tolist()] == written, column_name
    assert ours["summary"] == json.loads((out / "summary.json").read_text())
    assert ours["dofs"] == ["x1", "y1", "theta1", "x2", "y2", "theta2", "theta_motor",
                            "theta_load"]
    assert ours["shapes"].shape == (8, 8)
    assert ours["modes"]["mode"].dtype == np.int64
    assert ours["modes"]["rigid"].tolist() == [True] + [False] * 7
    # A number is rad/s.
    assert gearimpact.modes(case, harmonics=2, max_speed=20000 * np.pi / 30)["summary"][
        "max_pinion_speed_rad_per_s"] == pytest.approx(20000 * np.pi / 30, rel=1e-15)
    with pytest.raises(gearimpact.CaseError, match="harmonics"):
        gearimpact.modes(case, harmonics=0)
    with pytest.raises(gearimpact.CaseError, match="max_speed"):
        gearimpact.modes(case, max_speed="0 rpm")
    # simulate runs the planar dynamics through the library call the program makes.
    summary = json.loads(cli("simulate", "--case-file", case_file, "--t-end", "0.001"))
    result = gearimpact.simulate(case, keep_series=False, end_time="1 ms")
    assert result.summary == summary
    assert summary["bearing_energy_final_J"] > 0.0


SAMPLE_COLUMNS = [
    "t_s", "theta1_rad", "theta2_rad", "w1_rad_s", "w2_rad_s", "w1_dot_rad_s2", "w2_dot_rad_s2",
    "s_m", "dte_m", "normal_force_n1_N", "normal_force_n2_N", "region", "pairs",
]


def test_simulate_samples_as_the_program_writes_them(cli, tmp_path):
    out = tmp_path / "samples.csv"
    summary = json.loads(cli("simulate", "--case", "3", "--t-end", "0.002", "--sample-rate",
                             "1.5e6", "--out", out))
    result = gearimpact.simulate(3, keep_series=False, sample_rate=1.5e6, end_time="2 ms")
    assert result.summary == summary
    assert_same_table(result.samples, out.read_text(), SAMPLE_COLUMNS, "samples of case 3")
    # Interval averages by default: n = 1 ... 3000 (n = 0 ends no interval).
    assert len(result.samples["t_s"]) == 3000
    # The point samples, the same way on both sides, with n = 0.
    cli("simulate", "--case", "3", "--t-end", "0.002", "--sample-rate", "1.5e6", "--sample",
        "point", "--out", out)
    point = gearimpact.simulate(3, keep_series=False, sample_rate=1.5e6, sample="point",
                                end_time="2 ms")
    assert_same_table(point.samples, out.read_text(), SAMPLE_COLUMNS, "point samples of case 3")
    assert len(point.samples["t_s"]) == 3001


PLANAR_SAMPLE_COLUMNS = [
    "t_s", "x1_m", "y1_m", "theta1_rad", "x2_m", "y2_m", "theta2_rad", "vx1_m_s", "vy1_m_s",
    "w1_rad_s", "vx2_m_s", "vy2_m_s", "w2_rad_s", "theta_motor_rad", "theta_load_rad",
    "w_motor_rad_s", "w_load_rad_s", "ax1_m_per_s2", "ay1_m_per_s2", "alpha1_rad_per_s2",
    "ax2_m_per_s2", "ay2_m_per_s2", "alpha2_rad_per_s2", "bearing_fx1_N", "bearing_fy1_N",
    "bearing_fx2_N", "bearing_fy2_N", "dte_m", "drive_force_N", "coast_force_N",
    "sensor_acceleration_m_per_s2",
]


def test_simulate_planar_samples_as_the_program_writes_them(cli, tmp_path):
    # Case 1 on elastic bearings, the sensor on the wheel's bearing at 30 deg.
    case_file = tmp_path / "planar.toml"
    case_file.write_text((gearimpact.paper_data_dir() / "case1.toml").read_text()
                         + '\n[bearings]\nkind = "elastic"\nstiffness_x1 = "500 N/um"\n'
                         + 'stiffness_x2 = "700 N/um"\nsensor_gear = 2\n'
                         + 'sensor_angle = "30 deg"\n')
    out = tmp_path / "samples.csv"
    summary = json.loads(cli("simulate", "--case-file", case_file, "--t-end", "0.001",
                             "--sample-rate", "2e5", "--out", out))
    result = gearimpact.simulate(case_file, keep_series=False, sample_rate=2e5,
                                 end_time="1 ms")
    assert result.summary == summary
    assert_same_table(result.samples, out.read_text(), PLANAR_SAMPLE_COLUMNS,
                      "planar samples of case 1")
    assert len(result.samples["t_s"]) == 200
    # The wheel moved, and the sensor reads it.
    assert np.max(np.abs(result.samples["sensor_acceleration_m_per_s2"])) > 0.0


PLANAR_SERIES_COLUMNS = PLANAR_SAMPLE_COLUMNS[:17] + [
    "bearing_fx1_N", "bearing_fy1_N", "bearing_fx2_N", "bearing_fy2_N", "drive_force_N",
    "coast_force_N", "drive_penetration_m", "coast_penetration_m",
]


def test_simulate_planar_series_as_the_program_writes_it(cli, tmp_path):
    # Case 1 on elastic bearings: .series holds the planar series, the columns of the program's
    # --out, the same doubles (before, the torsional columns, empty).
    case_file = tmp_path / "planar.toml"
    case_file.write_text((gearimpact.paper_data_dir() / "case1.toml").read_text()
                         + '\n[bearings]\nkind = "elastic"\nstiffness_x1 = "500 N/um"\n'
                         + 'stiffness_x2 = "700 N/um"\n')
    out = tmp_path / "series.csv"
    summary = json.loads(cli("simulate", "--case-file", case_file, "--t-end", "0.0005",
                             "--every", "10", "--out", out))
    result = gearimpact.simulate(case_file, end_time="0.5 ms", output_every=10)
    assert result.summary == summary
    assert_same_table(result.series, out.read_text(), PLANAR_SERIES_COLUMNS,
                      "planar series of case 1")
    assert len(result.series["t_s"]) > 100
    assert np.max(np.abs(result.series["x2_m"])) > 0.0


def test_simulate_helical_pair_with_modifications_by_slices(cli, tmp_path):
    # A crowned, misaligned helical pair runs by route A (its slices as a train's meshes,
    # docs/helical.md "Route A in the two-gear run"): Python's simulate passes through the same
    # library function as the program, so the series and the summary (its slices included) are
    # the program's to the bit.
    case_file = Path(os.environ["GEARIMPACT_SOURCE_DIR"]) / "examples" / "helical_crowned_run.toml"
    result = simulate_both(cli, tmp_path, ["--case-file", case_file, "--t-end", "0.0005"],
                           case_file, end_time="0.5 ms")
    assert len(result.summary["slices"]) == result.summary["face_slices"] == 8
    assert sum(s["impacts_n1"] for s in result.summary["slices"]) == result.summary["impacts_n1"]


def test_simulate_helical_planar_series_as_the_program_writes_it(cli, tmp_path):
    # The helical example on elastic bearings: the planar series adds the axial forces and the
    # tilting moments, reported only, in Python as in the program's --out.
    case_file = Path(os.environ["GEARIMPACT_SOURCE_DIR"]) / "examples" / "helical_h501_planar.toml"
    out = tmp_path / "series.csv"
    summary = json.loads(cli("simulate", "--case-file", case_file, "--t-end", "0.0002",
                             "--every", "10", "--out", out))
    result = gearimpact.simulate(case_file, end_time="0.2 ms", output_every=10)
    assert result.summary == summary
    columns = PLANAR_SERIES_COLUMNS + ["axial_force1_N", "axial_force2_N",
                                       "tilting_moment1_N_m", "tilting_moment2_N_m"]
    assert_same_table(result.series, out.read_text(), columns, "helical planar series")
    assert summary["axial_force_max_N"] > 0.0
    assert np.array_equal(result.series["axial_force2_N"], -result.series["axial_force1_N"])


@pytest.mark.parametrize("rate", [0, -1.0, float("inf"), True, "fast"])
def test_simulate_refuses_a_bad_sample_rate(rate):
    with pytest.raises(gearimpact.CaseError, match="sample_rate"):
        gearimpact.simulate(1, keep_series=False, sample_rate=rate, end_time="1 ms")


def test_train_equals_the_program(cli, source_dir, tmp_path):
    # The example train over 2 ms: the series by the file's bodies and meshes, bit for bit.
    example = Path(source_dir) / "examples" / "pinion_idler_wheel.toml"
    out = tmp_path / "out"
    cli("train", example, "--set", "integrator.end_time=2 ms", "--out", out)
    ours = gearimpact.train(example, sets=["integrator.end_time=2 ms"])
    assert ours["summary"] == json.loads((out / "summary.json").read_text())
    theirs = parse_csv((out / "series.csv").read_text())
    assert list(ours["series"]) == list(theirs)
    assert "w_idler_rad_per_s" in theirs and "normal_force_idler-wheel_N" in theirs
    for name in theirs:
        assert_bitwise_equal(ours["series"][name], theirs[name], f"train {name}")
    assert ours["series"]["region_pinion-idler"].dtype == np.int64
    assert [b["name"] for b in ours["summary"]["bodies"]] == ["pinion", "idler", "wheel",
                                                               "brake-disc"]
    with pytest.raises(gearimpact.CaseError, match="bodies.whel"):
        gearimpact.train(example, sets=["bodies.whel.inertia=1 kg*m^2"])


def test_train_samples_equal_the_program(cli, source_dir, tmp_path):
    # The rig's sensor sampled at 51.2 kHz over 5 ms as a train: samples.csv, bit for bit, of
    # either kind; the interval averages start at n = 1.
    example = Path(source_dir) / "examples" / "rig_17_38.toml"
    sets = ["integrator.end_time=5 ms"]
    for kind, first in [("interval-average", 1 / 51200), ("point", 0.0)]:
        out = tmp_path / kind
        cli("train", example, "--set", sets[0], "--sample-rate", "51.2 kHz", "--sample", kind,
            "--out", out)
        ours = gearimpact.train(example, sets=sets, sample_rate="51.2 kHz", sample=kind)
        theirs = parse_csv((out / "samples.csv").read_text())
        assert list(ours["samples"]) == list(theirs)
        assert "sensor_acceleration_m_per_s2" in theirs
        for name in theirs:
            assert_bitwise_equal(ours["samples"][name], theirs[name], f"train sample {name}")
        assert ours["samples"]["t_s"][0] == first
    # The tacho's true edges, as tacho.csv's t_s.
    out = tmp_path / "tacho"
    tacho_sets = sets + ["tacho.pulses_per_revolution=200"]
    cli("train", example, "--set", tacho_sets[0], "--set", tacho_sets[1], "--out", out)
    ours = gearimpact.train(example, sets=tacho_sets)
    theirs = parse_csv((out / "tacho.csv").read_text())
    assert len(ours["tacho"]) > 5
    assert_bitwise_equal(ours["tacho"], theirs["t_s"], "train tacho")
    # A drift beyond drive.speed_tolerance warns as the program does, naming the two-gear key.
    with pytest.warns(UserWarning, match="torque1.bandwidth"):
        gearimpact.train(example, sets=["integrator.end_time=50 ms", "drive.settle=0 s",
                                        "drive.speed_tolerance=1e-12"])
    # A kind of sample without a rate is refused by name, as the program refuses --sample alone.
    for run in (lambda: gearimpact.train(example, sets=sets, sample="point"),
                lambda: gearimpact.simulate(2, end_time="1 ms", sample="point")):
        with pytest.raises(gearimpact.CaseError, match="needs sample_rate") as caught:
            run()
        assert caught.value.field == "sample"
    # No samples asked, none returned; a train without a [sensor] refuses them by name.
    assert "samples" not in gearimpact.train(example, sets=["integrator.end_time=0.1 ms"])
    with pytest.raises(gearimpact.CaseError, match="sample_rate") as caught:
        gearimpact.train(Path(source_dir) / "examples" / "pinion_idler_wheel.toml",
                         sets=["integrator.end_time=0.1 ms"], sample_rate=1000.0)
    assert caught.value.field == "sample_rate"


def test_stage_train_equals_the_program(cli, source_dir, tmp_path):
    # The example stage over 1 ms: series.csv, ring_sensor.csv and summary.json (with the
    # stage's Willis residual) as the program writes them, bit for bit.
    example = Path(source_dir) / "examples" / "planetary_stage.toml"
    out = tmp_path / "out"
    sets = ["integrator.end_time=1 ms"]
    cli("train", example, "--set", sets[0], "--out", out)
    ours = gearimpact.train(example, sets=sets)
    assert ours["summary"] == json.loads((out / "summary.json").read_text())
    assert set(ours["summary"]["stage"]) == {"mean_w_sun_rad_per_s", "mean_w_ring_rad_per_s",
                                             "mean_w_carrier_rad_per_s", "willis_residual"}
    theirs = parse_csv((out / "series.csv").read_text())
    assert list(ours["series"]) == list(theirs)
    assert "w_planet3_rad_per_s" in theirs and "normal_force_ring_planet2_N" in theirs
    for name in theirs:
        assert_bitwise_equal(ours["series"][name], theirs[name], f"stage {name}")
    ring = parse_csv((out / "ring_sensor.csv").read_text())
    assert list(ours["ring_sensor"]) == list(ring) == ["t_s", "ring_sensor_y_N"]
    for name in ring:
        assert_bitwise_equal(ours["ring_sensor"][name], ring[name], f"ring sensor {name}")
    teeth = parse_csv((out / "mesh_teeth.csv").read_text())
    assert list(ours["mesh_teeth"]) == list(teeth)
    assert ours["mesh_teeth"]["sun_tooth_at_sun_planet2"].dtype == np.int64
    for name in teeth:
        assert_bitwise_equal(ours["mesh_teeth"][name], teeth[name], f"mesh teeth {name}")
    # keep_series=False: the same summary, the arrays empty.
    short = gearimpact.train(example, sets=sets, keep_series=False)
    assert short["summary"] == ours["summary"]
    assert len(short["series"]["t_s"]) == len(short["ring_sensor"]["ring_sensor_y_N"]) == 0
    # A train file's dict has no ring sensor.
    assert "ring_sensor" not in gearimpact.train(
        Path(source_dir) / "examples" / "pinion_idler_wheel.toml",
        sets=["integrator.end_time=0.1 ms"])
    # Bad keys refused by name, as the command refuses them.
    for bad, key in [(["stage.planet=3"], "stage.planet"),
                     (["stage.planets=0"], "stage.planets"),
                     (["stage.ring_teeth=80"], "stage.ring_teeth")]:
        with pytest.raises(gearimpact.CaseError, match=key) as caught:
            gearimpact.train(example, sets=sets + bad)
        program = subprocess.run(
            [os.environ["GEARIMPACT_CLI"], "train", str(example), "--set", bad[0], "--out",
             str(tmp_path / "bad")], capture_output=True, text=True)
        assert program.returncode != 0 and key in program.stderr
        assert caught.value.field.startswith(key)


def test_planetary_modes_equal_the_program(cli, source_dir, tmp_path):
    # The LP99 stage (N = 4): modes.csv column by column, the numbers bit for bit, the mode
    # types and the rigid flag as the program writes them, and summary.json whole.
    example = Path(source_dir) / "examples" / "planetary_lp99.toml"
    out = tmp_path / "out"
    cli("modes", example, "--out", out)
    ours = gearimpact.planetary_modes(example)
    assert ours["summary"] == json.loads((out / "summary.json").read_text())
    lines = (out / "modes.csv").read_text().strip().splitlines()
    header = lines[0].split(",")
    cells = [line.split(",") for line in lines[1:]]
    assert list(ours["modes"]) == header
    for j, name in enumerate(header):
        column = [row[j] for row in cells]
        if name == "type":
            assert list(ours["modes"][name]) == column
        elif name == "rigid":
            assert list(ours["modes"][name]) == [cell == "true" for cell in column]
        else:
            assert_bitwise_equal(ours["modes"][name], [float(cell) for cell in column],
                                 f"planetary {name}")
    assert ours["modes"]["multiplicity"].dtype.kind == "i"
    with pytest.raises(gearimpact.CaseError, match="planetary.planets"):
        bad = tmp_path / "bad.toml"
        bad.write_text(example.read_text().replace("planets = 4", "planets = 0"))
        gearimpact.planetary_modes(bad)


def test_train_modes_equal_the_program(cli, source_dir, tmp_path):
    # The two-stage rig with a --set: modes.csv column by column, bit for bit, the rigid flag as
    # the program writes it, and summary.json whole; a bad --set key refused by its name.
    example = Path(source_dir) / "examples" / "two_stage_rig.toml"
    out = tmp_path / "out"
    sets = ["shafts_x=1"]
    with pytest.raises(gearimpact.CaseError, match="shafts_x"):
        gearimpact.train_modes(example, sets=sets)
    sets = ["meshes.stage2.gears.backlash=0.1 mm"]
    cli("modes", example, "--set", sets[0], "--out", out)
    ours = gearimpact.train_modes(example, sets=sets)
    assert ours["summary"] == json.loads((out / "summary.json").read_text())
    lines = (out / "modes.csv").read_text().strip().splitlines()
    header = lines[0].split(",")
    cells = [line.split(",") for line in lines[1:]]
    assert list(ours["modes"]) == header
    for j, name in enumerate(header):
        column = [row[j] for row in cells]
        if name == "rigid":
            assert list(ours["modes"][name]) == [cell == "true" for cell in column]
        else:
            assert_bitwise_equal(ours["modes"][name], [float(cell) for cell in column],
                                 f"train {name}")
    assert ours["modes"]["mode"].dtype.kind == "i"


def test_helical_mesh_stiffness_and_ste_equal_the_program(cli, source_dir, tmp_path):
    # GEARpie's H501 (examples/helical_h501.toml) with crowning and a misalignment.
    example = Path(source_dir) / "examples" / "helical_h501.toml"
    case_file = tmp_path / "crowned.toml"
    case_file.write_text(example.read_text().replace(
        "[model]", '[modifications]\ncrowning1 = "4 um"\nmisalignment_y = "0.01 deg"\n\n[model]'))
    case = gearimpact.read_case(case_file)
    table, summary = gearimpact.mesh_stiffness(case, samples=12)
    columns = ["fraction", "theta1_rad", "k_slices_n_m", "k_face_n_m", "contact_line_length_m",
               "contact_line_length_slices_m"]
    assert_same_table(table, cli("mesh-stiffness", "--case-file", case_file, "--samples", "12"),
                      columns, "helical mesh-stiffness")
    assert summary == json.loads(cli("mesh-stiffness", "--case-file", case_file, "--samples", "12",
                                     "--summary"))
    ours = gearimpact.ste(case, torque="150 N*m", points=9)
    out = tmp_path / "out"
    cli("ste", case_file, "--torque", "150 N*m", "--points", "9", "--out", out, "--no-plots")
    for key, name in (("ste", "ste.csv"), ("unmodified", "ste_unmodified.csv")):
        lines = (out / name).read_text().strip().splitlines()
        header = lines[0].split(",")
        assert list(ours[key]) == header
        for j, column_name in enumerate(header):
            written = [line.split(",")[j] for line in lines[1:]]
            column = ours[key][column_name]
            if column.dtype == np.float64:
                assert_bitwise_equal(column, [float(v) for v in written], f"{name} {column_name}")
            else:
                assert [as_written(v) for v in column.tolist()] == written, column_name
    assert ours["summary"] == json.loads((out / "summary.json").read_text())
    assert ours["summary"]["route"] == "slices"


def test_faulted_stage_train_equals_the_program(cli, source_dir, tmp_path):
    # The cracked-sun example (a [[faults]] table on the sun) over 1 ms: its series.csv,
    # ring_sensor.csv, mesh_teeth.csv and summary.json as the program writes them, bit for bit.
    example = Path(source_dir) / "examples" / "planetary_stage_cracked_sun.toml"
    out = tmp_path / "out"
    sets = ["integrator.end_time=1 ms"]
    cli("train", example, "--set", sets[0], "--out", out)
    ours = gearimpact.train(example, sets=sets)
    assert ours["summary"] == json.loads((out / "summary.json").read_text())
    for key, file in [("series", "series.csv"), ("ring_sensor", "ring_sensor.csv"),
                      ("mesh_teeth", "mesh_teeth.csv")]:
        theirs = parse_csv((out / file).read_text())
        assert list(ours[key]) == list(theirs)
        assert len(theirs["t_s"]) > 1
        for name in theirs:
            assert_bitwise_equal(ours[key][name], theirs[name], f"cracked stage {file} {name}")
