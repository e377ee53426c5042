"""A gear pair alone from Python: gearimpact.case() of the pair's keys, read_case and parse_case
of a pair file, through every function that needs the gears only; every run refuses it naming
the keys it lacks. The reference of each gears-only result is the same function on the same pair
given as a whole run case: the run keys must not change a result that does not read them."""

import warnings

import gearimpact
import numpy as np
import pytest

PAIR = dict(name="p", youngs_modulus="206 GPa", poisson_ratio=0.3, density="7850 kg/m^3",
            backlash="0.05 mm", teeth1=29, teeth2=71, module="2.5 mm", face_width="18 mm",
            pressure_angle="20 deg", bore_diameter1="25 mm", bore_diameter2="60 mm",
            stiffness_model="potential-energy")
RUN_KEYS = ["torque1.kind", "torque2.kind", "integrator.end_time"]


def _pair():
    return gearimpact.case(**PAIR)


def _whole():
    return gearimpact.case(**PAIR, torque1_value="50 N*m", torque2_value="-122.41379310344827 N*m",
                           w1="1000 rpm", w2="408.45070422535213 rpm", end_time="1 ms")


def test_the_pairs_keys_make_a_gear_pair_alone_that_reads_back():
    pair = _pair()
    assert pair.run_keys_absent == RUN_KEYS
    assert _whole().run_keys_absent == []
    assert "a gear pair alone" in repr(pair)
    text = pair.to_toml("si")
    assert "[torque1]" not in text and "[integrator]" not in text
    assert gearimpact.parse_case(text, "p.toml") == pair
    # A change of the pair keeps it a pair; a run's keys make it a run, or name what is missing.
    assert pair.replace(module="3 mm").run_keys_absent == RUN_KEYS
    with pytest.raises(gearimpact.CaseError) as error:
        pair.replace(end_time="1 ms")
    assert "torque1" in str(error.value)


def test_read_case_takes_a_pair_file(tmp_path):
    path = tmp_path / "p.toml"
    path.write_text(_pair().to_toml())
    assert gearimpact.read_case(path) == _pair()
    assert gearimpact.read_case(str(path)).run_keys_absent == RUN_KEYS


def test_every_gears_only_function_gives_what_it_gives_on_the_whole_case():
    pair, whole = _pair(), _whole()
    assert np.array_equal(gearimpact.stiffness(pair, points=9)["ke"],
                          gearimpact.stiffness(whole, points=9)["ke"])
    assert gearimpact.iso6336(pair) == gearimpact.iso6336(whole)
    assert np.array_equal(gearimpact.ste(pair, "50 N*m", points=8)["ste"]["ste_m"],
                          gearimpact.ste(whole, "50 N*m", points=8)["ste"]["ste_m"])
    assert np.array_equal(gearimpact.mesh_stiffness(pair, samples=8)[0]["ke_n_m"],
                          gearimpact.mesh_stiffness(whole, samples=8)[0]["ke_n_m"])
    modes = gearimpact.modes(pair, max_speed="3000 rpm")["modes"]
    assert np.array_equal(modes["frequency_hz"],
                          gearimpact.modes(whole, max_speed="3000 rpm")["modes"]["frequency_hz"])


def test_every_run_refuses_a_gear_pair_alone_naming_the_keys():
    pair = _pair()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(gearimpact.CaseError) as error:
            gearimpact.simulate(pair)
        assert error.value.field == "torque1.kind"
        for key in RUN_KEYS:
            assert key in str(error.value)
        with pytest.raises(gearimpact.CaseError) as error:
            gearimpact.sweep(pair, "w1", "100 rad/s", "200 rad/s", 2)
        assert "torque1.kind" in str(error.value)
