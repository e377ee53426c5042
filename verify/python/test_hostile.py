"""Hostile input through the Python API: every bad argument gets one
CaseError (a ValueError) naming the keyword as the caller wrote it and what
it takes, before any work starts (no file is made, no NaN comes back); every
valid call in between returns finite numbers."""

import math
import os

import gearimpact
import numpy as np
import pytest

CASE1 = gearimpact.paper_case(1)
# Case 1 with a two-harmonic torque on gear 1, built through replace() itself.
HARMONIC = dict(
    torque1_kind="harmonic",
    torque1_mean="0 N*m",
    torque1_amplitudes=["10 N*m", 2.0],
    torque1_angular_frequencies=np.array([100.0, 200.0]),
    torque1_phases=(0, "90 deg"),
)


def harmonic(**changes):
    return CASE1.replace(**HARMONIC).replace(**changes)


# A signal and its shaft's angle: 4 revolutions of 64 samples, a 20-tooth gear's mesh order.
ANGLE = np.linspace(0.0, 8.0 * np.pi, 257)
SIGNAL = np.cos(20.0 * ANGLE)


RIG = gearimpact.read_case(os.path.join(os.environ["GEARIMPACT_SOURCE_DIR"], "examples",
                                        "rig_17_38.toml"))


def fault_text(tooth):
    """Case 1 with one missing pinion tooth numbered `tooth`, as a case file writes it."""
    return (CASE1.to_toml() + '\n[[faults]]\ngear = "pinion"\ntooth = ' + str(tooth)
            + '\nkind = "missing"\n')


def nan_pair():
    pair = gearimpact.GearPair()
    pair.module_m = float("nan")
    return pair


# (what, call, the keyword the message must name, more words it must hold).
# Each call is refused before any computation; the words are what the caller
# needs to mend it (the allowed range, the form to write).
REFUSED = [
    # Integers beyond a double's exact range, in every kind of key.
    ("int 10**300 for a number", lambda: CASE1.replace(friction_coefficient=10**300),
     "friction_coefficient", ["2**53"]),
    ("int 2**60 for an integer", lambda: CASE1.replace(teeth1=2**60), "teeth1", ["2**53"]),
    ("int 2**53+1 for a quantity", lambda: CASE1.replace(w1=2**53 + 1), "w1", ["2**53"]),
    ("int beyond 2**53 in gear_pair", lambda: gearimpact.gear_pair(teeth2=-(10**20)), "teeth2",
     ["2**53"]),
    ("int beyond 2**53 for points", lambda: gearimpact.stiffness(points=2**64), "points",
     ["2**53"]),
    ("int beyond 2**53 for from_", lambda: gearimpact.sweep_friction(from_=10**30), "from_",
     ["2**53"]),
    # NaN and infinity in every field.
    ("NaN quantity", lambda: CASE1.replace(module=float("nan")), "module", ["finite"]),
    ("inf quantity", lambda: CASE1.replace(end_time=float("inf")), "end_time", ["finite"]),
    ("-inf number", lambda: CASE1.replace(friction_coefficient=-math.inf),
     "friction_coefficient", ["finite"]),
    ("NaN numpy float", lambda: CASE1.replace(w1=np.float64("nan")), "w1", ["finite"]),
    ("NaN case3 frequency", lambda: gearimpact.paper_case(3, case3_frequency_rad_s=float("nan")),
     "case3_frequency_rad_s", ["finite"]),
    ("negative case3 frequency", lambda: gearimpact.paper_case(3, case3_frequency_rad_s=-1.0),
     "case3_frequency_rad_s", [">= 0 rad/s"]),
    ("NaN from_", lambda: gearimpact.sweep_friction(from_=float("nan")), "from_", ["finite"]),
    ("negative from_", lambda: gearimpact.sweep_friction(from_=-0.01), "from_", [">= 0"]),
    ("inf to", lambda: gearimpact.sweep_friction(to=math.inf), "to", ["finite"]),
    ("zero step", lambda: gearimpact.sweep_friction(step=0.0), "step", ["> 0"]),
    ("NaN step", lambda: gearimpact.sweep_friction(step=float("nan")), "step", ["finite"]),
    ("NaN helix angle", lambda: gearimpact.iso6336(helix_angle_deg=float("nan")),
     "helix_angle_deg", ["finite"]),
    ("helix angle 46", lambda: gearimpact.iso6336(helix_angle_deg=46), "helix_angle_deg",
     ["[0, 45]"]),
    ("NaN x", lambda: gearimpact.stiffness(x=[0.005, float("nan")]), "x[1]", ["finite"]),
    ("NaN start of sweep", lambda: gearimpact.sweep(CASE1, "initial.w1", float("nan"), 2.0, 2),
     "start", ["finite"]),
    ("NaN x1_m", lambda: gearimpact.contact_angle(gearimpact.GearPair(), 1, float("nan")),
     "x1_m", ["finite"]),
    ("NaN field of a GearPair", lambda: gearimpact.base_radius(nan_pair(), 1), "module",
     ["[1e-6, 1] m"]),
    ("NaN pair to contact_ratio", lambda: gearimpact.contact_ratio(nan_pair()), "module",
     ["[1e-6, 1] m"]),
    # Booleans are True/False, nothing else.
    ("str for flipped_moment", lambda: gearimpact.stiffness(flipped_moment="no"),
     "flipped_moment", ["True or False"]),
    ("int for flipped_moment", lambda: gearimpact.energy_ratios(flipped_moment=1),
     "flipped_moment", ["True or False"]),
    ("str for keep_series", lambda: gearimpact.simulate(1, keep_series="no"), "keep_series",
     ["True or False"]),
    ("None for keep_series", lambda: gearimpact.simulate(1, keep_series=None), "keep_series",
     ["True or False"]),
    ("bool for a number", lambda: CASE1.replace(friction_coefficient=True),
     "friction_coefficient", []),
    ("bool for points", lambda: gearimpact.stiffness(points=True), "points", ["integer"]),
    ("bool for threads", lambda: gearimpact.sweep_friction(threads=False), "threads",
     ["integer"]),
    ("bool for a gear", lambda: gearimpact.base_radius(gearimpact.GearPair(), True), "gear",
     ["1 or 2"]),
    ("bool for a case number", lambda: gearimpact.paper_case(True), "number", ["integer"]),
    ("int for set_term's on", lambda: gearimpact.StiffnessModel().set_term("axial", 1), "on",
     ["True or False"]),
    ("str for set_term's on", lambda: gearimpact.StiffnessModel().set_term("axial", "off"), "on",
     ["True or False"]),
    ("'no' for an on/off key", lambda: CASE1.replace(axial_term="no"), "axial_term",
     ['"on", "off"']),
    ("unknown spall_reading", lambda: CASE1.replace(spall_reading="wide"), "spall_reading",
     ['"hertz-only"', '"effective-width"']),
    ("effective-width with the paper's model",
     lambda: CASE1.replace(spall_reading="effective-width"), "spall_reading",
     ['"hertz-only" with stiffness_model = "yang-lin-1987"']),
    ("unknown spall_reading of a StiffnessModel",
     lambda: setattr(gearimpact.StiffnessModel(), "spall_reading", "wide"), "spall_reading",
     ["hertz-only, effective-width"]),
    # Lists.
    ("empty list", lambda: harmonic(torque1_amplitudes=[]), "torque1_amplitudes",
     ["at least one"]),
    ("ragged list", lambda: harmonic(torque1_amplitudes=[[1.0], [2.0, 3.0]]),
     "torque1_amplitudes[0]", ["unit string"]),
    ("2-d array", lambda: harmonic(torque1_amplitudes=np.zeros((2, 2))), "torque1_amplitudes",
     ["1-dimensional"]),
    ("text in a list", lambda: harmonic(torque1_amplitudes=["10 N*m", "lots"]),
     "torque1_amplitudes[1]", ["N*m"]),
    ("None in a list", lambda: harmonic(torque1_phases=[0.0, None]), "torque1_phases[1]",
     ["unit string"]),
    ("NaN in a list", lambda: harmonic(torque1_amplitudes=[1.0, float("nan")]),
     "torque1_amplitudes[1]", ["finite"]),
    ("negative element", lambda: harmonic(torque1_angular_frequencies=[100.0, -3.0]),
     "torque1_angular_frequencies[1]", [">= 0"]),
    ("str for a list", lambda: harmonic(torque1_amplitudes="10 N*m"), "torque1_amplitudes",
     ["list"]),
    ("lists of two lengths", lambda: harmonic(torque1_amplitudes=[1.0]), "torque1_amplitudes",
     ["as many values"]),
    ("list for a number", lambda: CASE1.replace(module=[0.002]), "module", ["list"]),
    ("str for cases", lambda: gearimpact.sweep_friction(cases="case1.toml"), "cases", ["list"]),
    ("empty cases", lambda: gearimpact.sweep_friction(cases=[]), "cases", ["list"]),
    ("None in cases", lambda: gearimpact.sweep_friction(cases=[1, None]), "cases[1]", ["Case"]),
    ("str for options", lambda: gearimpact.sweep(CASE1, "initial.w1", 1, 2, 2,
                                                 options="--threads 1"),
     "options", ["['--threads', '1']"]),
    ("int in options", lambda: gearimpact.sweep(CASE1, "initial.w1", 1, 2, 2, options=[3]),
     "options[0]", ["str"]),
    ("3-d x", lambda: gearimpact.stiffness(x=np.zeros((1, 1, 1))), "x", []),
    ("str for x", lambda: gearimpact.stiffness(x="0.01"), "x", []),
    # Counts and threads.
    ("points=0", lambda: gearimpact.stiffness(points=0), "points", ["[2, 1000000]"]),
    ("points=1", lambda: gearimpact.energy_ratios(points=1), "points", ["[2, 1000000]"]),
    ("points=10**12", lambda: gearimpact.energy_ratios(points=10**12), "points",
     ["[2, 1000000]"]),
    ("negative points", lambda: gearimpact.stiffness(points=-5), "points", ["[2, 1000000]"]),
    ("float points", lambda: gearimpact.stiffness(points=2.5), "points", ["integer"]),
    ("str points", lambda: gearimpact.energy_ratios(points="10"), "points", ["integer"]),
    ("sweep points=0", lambda: gearimpact.sweep(CASE1, "initial.w1", 1, 2, 0), "points=0",
     ["at least 1"]),
    ("sweep direction typo", lambda: gearimpact.sweep(CASE1, "initial.w1", 1, 2, 2,
                                                      direction="sideways"),
     "direction='sideways'", ["up"]),
    ("sweep unknown vary", lambda: gearimpact.sweep(CASE1, "initial.w9", 1, 2, 2),
     "vary='initial.w9'", ["section.key"]),
    ("sweep start unit typo", lambda: gearimpact.sweep(CASE1, "initial.w1", "1 rad/ss", 2, 2),
     "start='1 rad/ss'", ["rad/s"]),
    ("samples=1", lambda: gearimpact.mesh_stiffness(samples=1), "samples", ["[2, 1000000]"]),
    ("samples=10**12", lambda: gearimpact.mesh_stiffness(samples=10**12), "samples",
     ["[2, 1000000]"]),
    ("threads=10**6", lambda: gearimpact.sweep_friction(threads=10**6), "threads", ["1024"]),
    ("threads=-1", lambda: gearimpact.sweep_friction(threads=-1), "threads", ["1024"]),
    ("sweep --threads 10**5", lambda: gearimpact.sweep(CASE1, "initial.w1", 1, 2, 2,
                                                       options=["--threads", "100000"]),
     "--threads", ["1024"]),
    ("negative teeth", lambda: CASE1.replace(teeth1=-5), "teeth1", ["[4, 100000]"]),
    ("output_every=0", lambda: CASE1.replace(output_every=0), "output_every", []),
    # Wrong types everywhere.
    ("None for a number", lambda: CASE1.replace(friction_coefficient=None),
     "friction_coefficient", ["NoneType"]),
    ("dict for a quantity", lambda: CASE1.replace(module={}), "module", ["dict"]),
    ("bytes for a quantity", lambda: CASE1.replace(module=b"2 mm"), "module", ["bytes"]),
    ("complex for a number", lambda: CASE1.replace(friction_coefficient=1j),
     "friction_coefficient", ["complex"]),
    ("str that is no number", lambda: CASE1.replace(friction_coefficient="0.o6"),
     "friction_coefficient", []),
    ("unit typo", lambda: CASE1.replace(module="2 mmm"), "module", ["mm"]),
    ("unit of another dimension", lambda: CASE1.replace(step="0.1 mm"), "step", ["us"]),
    ("unknown keyword", lambda: CASE1.replace(modul=1), "modul", ["gears.module"]),
    ("unknown section.key", lambda: CASE1.replace(**{"gears.modul": 1}), "gears.modul",
     ["gears.module"]),
    ("unknown key with TOML in it", lambda: CASE1.replace(**{"gears.x = 1\n[y]\nz": 1}),
     "gears.x", ["no such key"]),
    ("unknown gear_pair key", lambda: gearimpact.gear_pair(modul=1), "modul", ["module"]),
    ("unknown paper_case key", lambda: gearimpact.paper_case(2, frictio=0.1), "frictio", []),
    ("unknown simulate key", lambda: gearimpact.simulate(1, end_tme="1 ms"), "end_tme", []),
    ("str case number", lambda: gearimpact.paper_case("1"), "number", ["integer"]),
    ("case number 4", lambda: gearimpact.paper_case(4), "number", ["1, 2 or 3"]),
    ("None torque unit", lambda: gearimpact.paper_case(1, torque_unit=None), "torque_unit",
     ["str"]),
    ("torque unit typo", lambda: gearimpact.paper_case(1, torque_unit="kgf-mn"), "torque_unit",
     ["kgf-mm"]),
    ("None for simulate's case", lambda: gearimpact.simulate(None), "case", ["Case"]),
    ("float for simulate's case", lambda: gearimpact.simulate(1.5), "case", ["Case"]),
    ("dict for stiffness' case", lambda: gearimpact.stiffness({}), "case_or_pair", ["Case"]),
    ("int for method", lambda: gearimpact.stiffness(method=3), "method", ["str"]),
    ("method typo", lambda: gearimpact.stiffness(method="gls"), "method", ["gsl-cquad"]),
    ("int for mesh_stiffness' case", lambda: gearimpact.mesh_stiffness(3), "case", ["Case"]),
    ("int for model", lambda: gearimpact.mesh_stiffness(model=1), "model", ["str"]),
    ("str for iso6336's case", lambda: gearimpact.iso6336("case1.toml"), "case", ["Case"]),
    ("str for helix angle", lambda: gearimpact.iso6336(helix_angle_deg="10"),
     "helix_angle_deg", ["number"]),
    ("int for sweep's case", lambda: gearimpact.sweep(1, "initial.w1", 1, 2, 2), "case",
     ["Case"]),
    ("None for vary", lambda: gearimpact.sweep(CASE1, None, 1, 2, 2), "vary", ["str"]),
    ("list for stop", lambda: gearimpact.sweep(CASE1, "initial.w1", 1, [2], 2), "stop",
     ["unit string"]),
    ("None for parse_case", lambda: gearimpact.parse_case(None), "text", ["str"]),
    ("bytes for parse_case", lambda: gearimpact.parse_case(b"[gears]"), "text", ["str"]),
    ("int for parse_case's name", lambda: gearimpact.parse_case("", name=3), "name", ["str"]),
    ("None for read_case", lambda: gearimpact.read_case(None), "path", ["path"]),
    ("missing case file", lambda: gearimpact.read_case("no-such-case.toml"), "no-such-case.toml",
     []),
    ("None for reproduce's folder", lambda: gearimpact.reproduce(None), "out_dir", ["path"]),
    ("units typo in to_toml", lambda: CASE1.to_toml("SI"), "units", ['"si"']),
    ("gear 3", lambda: gearimpact.tip_radius(gearimpact.GearPair(), 3), "gear", ["1 or 2"]),
    ("gear 10**30", lambda: gearimpact.pitch_radius(gearimpact.GearPair(), 10**30), "gear",
     ["1 or 2"]),
    ("numpy bool for a gear", lambda: gearimpact.base_radius(gearimpact.GearPair(), np.bool_(1)),
     "gear", ["1 or 2"]),
    ("float for a gear", lambda: gearimpact.moment_of_inertia(gearimpact.GearPair(), 1.0),
     "gear", ["1 or 2"]),
    # The kept series is bounded like the program's: 10 s at 0.1 us are 1e8 rows.
    ("a series over the row budget", lambda: gearimpact.simulate(1, end_time="10 s"),
     "end_time", ["at most 50000000 rows", "about 100000001 rows", "max_rows lifts"]),
    ("max_rows below the series", lambda: gearimpact.simulate(1, end_time="1 ms", max_rows=100),
     "end_time", ["at most 100 rows", "about 10001 rows"]),
    ("max_rows 0", lambda: gearimpact.simulate(1, max_rows=0), "max_rows", [">= 1"]),
    ("max_rows True", lambda: gearimpact.simulate(1, max_rows=True), "max_rows", ["integer"]),
    # A list over the schema's length is refused before a text of it is built.
    ("1001 harmonics", lambda: CASE1.replace(torque1_kind="harmonic",
                                             torque1_amplitudes=[0.0] * 1001,
                                             torque1_angular_frequencies=[1.0] * 1001,
                                             torque1_phases=[0.0] * 1001),
     "torque1_amplitudes", ["1001 values", "at most 1000"]),
    ("a lone surrogate in parse_case", lambda: gearimpact.parse_case('name = "a\udcff"'), "text",
     ["surrogate"]),
    # A fault's tooth past int32 once wrapped to -2**31 (ste crashed the interpreter).
    ("tooth 2**31", lambda: gearimpact.parse_case(fault_text(2**31)), "faults[0].tooth",
     ["[0, 99999]"]),
    ("tooth 2**63-1", lambda: gearimpact.parse_case(fault_text(2**63 - 1)), "faults[0].tooth",
     ["[0, 99999]"]),
    ("tooth of the pinion's 20", lambda: gearimpact.parse_case(fault_text(20)), "faults[0].tooth",
     ["0 ... 19"]),
    # Values past any gear, bearing or shaft, once blamed on other keys or NaN mid-run.
    ("module 1e-30 m", lambda: CASE1.replace(module="1e-30 m"), "module", ["[1e-6, 1] m"]),
    ("module 1e300 m", lambda: CASE1.replace(module="1e300 m"), "module", ["[1e-6, 1] m"]),
    ("bearing damping 1e300", lambda: RIG.replace(damping_x1="1e300 N*s/m"), "damping_x1",
     ["[0, 1000000] N*s/m"]),
    ("bearing mass 1e-300", lambda: RIG.replace(mass1="1e-300 kg"), "mass1",
     ["[0.0001, 1000000] kg"]),
    ("bearing stiffness 1e-300", lambda: RIG.replace(stiffness_x1="1e-300 N/m"),
     "stiffness_x1", ["[0.001, 1e16] N/m"]),
    # The signal functions' arguments: each a CaseError naming it, never pybind's TypeError or a
    # silent conversion.
    ("bool rate", lambda: gearimpact.spectrum(SIGNAL, True), "rate", ["number"]),
    ("str rate", lambda: gearimpact.spectrum(SIGNAL, "100"), "rate", ["number"]),
    ("complex signal", lambda: gearimpact.spectrum(SIGNAL * (1 + 1j), 100.0), "signal",
     ["complex"]),
    ("text signal", lambda: gearimpact.spectrum(["a", "b"], 100.0), "signal", ["real numbers"]),
    ("2-d signal", lambda: gearimpact.spectrum(np.zeros((4, 4)), 100.0), "signal",
     ["1-dimensional"]),
    ("int window", lambda: gearimpact.spectrum(SIGNAL, 100.0, window=1), "window", ["str"]),
    ("samples that overflow the DFT", lambda: gearimpact.spectrum(np.full(8, 1e308), 100),
     "signal", ["1e300"]),
    ("low_pass samples that overflow", lambda: gearimpact.low_pass(np.full(8, 1e308), 100, 10),
     "signal", ["1e300"]),
    ("bool cutoff", lambda: gearimpact.low_pass(SIGNAL, 100.0, True), "cutoff", ["number"]),
    ("teeth=0", lambda: gearimpact.order_analysis(ANGLE, SIGNAL, teeth=0), "teeth", [">= 1"]),
    ("sidebands=100000", lambda: gearimpact.order_analysis(ANGLE, SIGNAL, 64, teeth=20,
                                                            sidebands=100000),
     "sidebands", ["0 to 9 for 20 teeth"]),
    ("float teeth", lambda: gearimpact.order_analysis(ANGLE, SIGNAL, teeth=20.0), "teeth",
     ["integer"]),
    ("str samples_per_revolution", lambda: gearimpact.order_analysis(
        ANGLE, SIGNAL, samples_per_revolution="64"), "samples_per_revolution", ["integer"]),
    ("complex angle", lambda: gearimpact.order_analysis(ANGLE + 0j, SIGNAL), "angle",
     ["complex"]),
    ("str record", lambda: gearimpact.indicators("abc"), "record", ["real numbers"]),
    # sweep() writes no file: an --out among its options was ignored.
    ("sweep --out", lambda: gearimpact.sweep(CASE1, "initial.w1", 1, 2, 2,
                                             options=["--out", "sweep-out"]),
     "options", ["--out", "writes no file"]),
    ("sweep --points among options", lambda: gearimpact.sweep(CASE1, "initial.w1", 1, 2, 2,
                                                              options=["--points=5"]),
     "options", ["points="]),
]


@pytest.mark.parametrize("call, field, words", [r[1:] for r in REFUSED],
                         ids=[r[0] for r in REFUSED])
def test_a_bad_argument_is_one_case_error_naming_it(call, field, words, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(gearimpact.CaseError) as error:
        call()
    message = str(error.value)
    assert field in message
    for word in words:
        assert word in message, message
    assert "<keyword arguments>" not in message
    assert list(tmp_path.iterdir()) == []


# Arguments pybind's own typing refuses before the library is reached: a
# GearPair where its C++ type is required. TypeError names the argument's type.
TYPE_ERRORS = [
    ("None for a pair", lambda: gearimpact.base_radius(None, 1)),
    ("Case for a pair", lambda: gearimpact.contact_segment(CASE1)),
    ("str for x1_m", lambda: gearimpact.contact_angle(gearimpact.GearPair(), 1, "0.01")),
]


@pytest.mark.parametrize("call", [r[1] for r in TYPE_ERRORS], ids=[r[0] for r in TYPE_ERRORS])
def test_a_wrong_type_for_a_bound_object_is_a_type_error(call, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(TypeError):
        call()
    assert list(tmp_path.iterdir()) == []


def test_a_text_over_one_mib_is_refused_as_a_case_file_is():
    # read_case_file refuses a file over 1 MiB; parse_case holds its text to
    # the same bound. The text is a valid case but for a 2 MiB comment, so
    # only its size can be refused.
    text = CASE1.to_toml() + "#" + "x" * (2 * 1024 * 1024) + "\n"
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.parse_case(text)
    assert "1 MiB" in str(error.value)


# Accepted forms -------------------------------------------------------------


def test_lists_tuples_and_arrays_give_the_same_harmonic_torque():
    # Three spellings of one torque; the SI numbers are written in the key's SI
    # unit, the strings read as a case file reads them.
    as_strings = CASE1.replace(torque1_kind="harmonic", torque1_mean="0 N*m",
                               torque1_amplitudes=["10 N*m", "2 N*m"],
                               torque1_angular_frequencies=["100 rad/s", "200 rad/s"],
                               torque1_phases=["0 deg", "90 deg"])
    as_numbers = CASE1.replace(torque1_kind="harmonic", torque1_mean=0.0,
                               torque1_amplitudes=(10, 2.0),
                               torque1_angular_frequencies=np.array([100.0, 200.0]),
                               torque1_phases=[0.0, math.pi / 2])
    assert as_strings == as_numbers
    assert as_numbers.fields()["torque1.amplitudes"] == ["10 N*m", "2 N*m"]
    # A case that has lists is changed again without touching them.
    again = as_numbers.replace(friction_coefficient=0.05)
    assert again.fields()["torque1.phases"] == as_numbers.fields()["torque1.phases"]


def test_numpy_scalars_are_numbers_and_numpy_bools_are_bools():
    assert CASE1.replace(teeth1=np.int64(25), module=np.float32(0.0025)).gears.teeth1 == 25
    assert CASE1.replace(axial_term=np.bool_(False)).fields()["model.axial_term"] == "off"
    model = gearimpact.StiffnessModel()
    model.set_term("axial", np.bool_(False))
    assert model.term("axial") is False
    model.set_term("axial", True)
    assert model.term("axial") is True
    assert model.spall_reading == "by-model"
    model.spall_reading = "effective-width"
    assert model.spall_reading == "effective-width"
    flipped = gearimpact.stiffness(points=3, flipped_moment=np.bool_(True))
    assert np.array_equal(flipped["ke"], gearimpact.stiffness(points=3, flipped_moment=True)["ke"])


def test_the_exact_integers_are_accepted_up_to_2_53():
    # 2**53 itself is a double exactly; only beyond it do integers collapse.
    case3 = gearimpact.paper_case(3)
    assert case3.replace(torque1_phase=2**53).fields()["torque1.phase"] == "9007199254740992 rad"


def _numbers_in(value):
    """Every float in a result: arrays, dicts, lists and scalars, recursively."""
    if isinstance(value, dict):
        for item in value.values():
            yield from _numbers_in(item)
    elif isinstance(value, (list, tuple)):
        for item in value:
            yield from _numbers_in(item)
    elif isinstance(value, np.ndarray):
        if value.dtype.kind == "f":
            yield from value.ravel().tolist()
    elif isinstance(value, float):
        yield value


VALID = [
    ("stiffness", lambda: gearimpact.stiffness(points=3)),
    ("stiffness at x", lambda: gearimpact.stiffness(x=(0.005, 0.006))),
    ("energy ratios", lambda: gearimpact.energy_ratios(points=3)),
    ("mesh stiffness", lambda: gearimpact.mesh_stiffness(samples=3)),
    ("iso6336", lambda: gearimpact.iso6336(helix_angle_deg=np.float64(10))),
    ("geometry", lambda: [f(gearimpact.GearPair(), g) for g in (1, np.int64(2)) for f in (
        gearimpact.pitch_radius, gearimpact.base_radius, gearimpact.tip_radius,
        gearimpact.moment_of_inertia)] + list(gearimpact.contact_segment(gearimpact.GearPair()))),
    ("harmonic simulation", lambda: (lambda r: [r.summary, r.series, r.impacts])(
        gearimpact.simulate(harmonic(end_time="0.5 ms"), keep_series=True))),
    ("spectrum", lambda: gearimpact.spectrum(SIGNAL.tolist(), np.int64(100))),
    ("order analysis", lambda: gearimpact.order_analysis(ANGLE, SIGNAL, 64, teeth=np.int64(20))),
    ("friction sweep", lambda: gearimpact.sweep_friction(
        [1], from_=0.02, to=0.02, step=0.01, threads=np.int64(1), end_time="0.5 ms")),
]


@pytest.mark.parametrize("call", [r[1] for r in VALID], ids=[r[0] for r in VALID])
def test_a_valid_call_returns_no_nan_and_writes_no_file(call, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    values = list(_numbers_in(call()))
    assert values, "the call returned no numbers to check"
    assert not any(math.isnan(v) for v in values)
    assert list(tmp_path.iterdir()) == []


def test_the_longest_lists_go_through_replace():
    # 1000 harmonics: the text replace() builds keeps its lines under the
    # reader's 4096 bytes, as the case-file writer does.
    n = 1000
    case = CASE1.replace(torque1_kind="harmonic", torque1_mean="0.5 N*m",
                         torque1_amplitudes=[1e-3 * (i + 1) for i in range(n)],
                         torque1_angular_frequencies=[1000.0 * (i + 1) for i in range(n)],
                         torque1_phases=[0.0] * n)
    assert len(case.fields()["torque1.amplitudes"]) == n
    again = case.replace(friction_coefficient=0.05)
    assert again.fields()["torque1.amplitudes"] == case.fields()["torque1.amplitudes"]
