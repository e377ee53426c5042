"""Speeds and rates from Python: a plain number for a speed is read in rad/s and warns (as an
implausible plain length does), a speed with its unit ("1500 rpm") does not; a sample rate with
its unit ("80 kHz") is the rate of the plain number in Hz. References: rpm = rad/s * 60 / (2 pi)
and 1 kHz = 1000 Hz, by definition."""

import math
import warnings

import gearimpact
import numpy as np
import pytest

PAIR = dict(name="p", youngs_modulus="206 GPa", poisson_ratio=0.3, density="7850 kg/m^3",
            backlash="0.05 mm", teeth1=29, teeth2=71, module="2.5 mm", face_width="18 mm",
            pressure_angle="20 deg", bore_diameter1="25 mm", bore_diameter2="60 mm")


def _speed_warnings(caught):
    return [str(w.message) for w in caught if "is read as" in str(w.message)]


def test_a_plain_speed_warns_and_a_speed_with_its_unit_does_not():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        case = gearimpact.paper_case(1).replace(w1=1500)
    found = _speed_warnings(caught)
    assert len(found) == 1, found
    assert "w1 = 1500 is read as 1500 rad/s (14323.9 rpm)" in found[0]
    assert '"1500 rpm"' in found[0]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        in_rpm = gearimpact.paper_case(1).replace(w1="1500 rpm")
    assert _speed_warnings(caught) == []
    w1 = float(in_rpm.fields()["initial.w1"].split()[0])
    assert w1 == pytest.approx(1500 * 2 * math.pi / 60, rel=1e-15)
    assert float(case.fields()["initial.w1"].split()[0]) == 1500.0
    # 0 is 0 in every unit: no warning.
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        gearimpact.paper_case(1).replace(w1=0)
    assert _speed_warnings(caught) == []


def test_case_of_keywords_warns_of_a_plain_speed():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        gearimpact.case(**PAIR, torque1_value="50 N*m", torque2_value="122 N*m", w1=1500,
                        w2="612.676 rad/s", end_time="1 ms")
    assert any("w1 = 1500 is read as 1500 rad/s" in w for w in _speed_warnings(caught))


def test_modes_max_speed_as_a_number_warns():
    pair = gearimpact.case(**PAIR)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        by_number = gearimpact.modes(pair, max_speed=300)
    assert any("max_speed = 300 is read as 300 rad/s" in w for w in _speed_warnings(caught))
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        by_unit = gearimpact.modes(pair, max_speed="300 rad/s")
    assert _speed_warnings(caught) == []
    assert np.array_equal(by_number["modes"]["frequency_hz"], by_unit["modes"]["frequency_hz"])


def test_a_sample_rate_with_its_unit():
    kilo = gearimpact.simulate(1, end_time="0.2 ms", keep_series=False, sample_rate="80 kHz")
    plain = gearimpact.simulate(1, end_time="0.2 ms", keep_series=False, sample_rate=80000.0)
    assert len(kilo.samples["t_s"]) > 10
    for column in ("t_s", "s_m", "w1_rad_s"):
        assert np.array_equal(kilo.samples[column], plain.samples[column])
    with pytest.raises(gearimpact.CaseError) as error:
        gearimpact.simulate(1, end_time="0.2 ms", keep_series=False, sample_rate="80 rpm")
    assert error.value.field == "sample_rate"
    assert "kHz" in str(error.value)
