"""The signal layer from Python: numpy arrays in and out, the same closed forms
as verify/signals/test_signals.cpp, and the library's refusals naming keywords."""

import json
import math

import numpy
import pytest

import gearimpact


def test_spectrum_reads_a_sine_on_a_bin():
    # 1024 samples at 2048 Hz: bin k at 2k Hz; 200 Hz is bin 100. The mean reads itself.
    t = numpy.arange(1024) / 2048.0
    x = 0.7 + 2.5 * numpy.cos(2 * math.pi * 200.0 * t + 0.3)
    for window in ("hann", "rectangular"):
        s = gearimpact.spectrum(x, 2048.0, window)
        assert isinstance(s["amplitude"], numpy.ndarray)
        assert s["frequency"][100] == 200.0
        assert abs(s["amplitude"][100] - 2.5) / 2.5 < 1e-11
        assert abs(s["amplitude"][0] - 0.7) / 0.7 < 1e-11


def test_low_pass_keeps_the_tones_below_its_cutoff():
    # 1000 samples at 1 kHz (bins 1 Hz apart): the mean and 50 Hz kept to
    # rounding, 300 Hz gone, as numpy's own DFT with those bins zeroed gives.
    t = numpy.arange(1000) / 1000.0
    x = 0.5 + numpy.cos(2 * math.pi * 50.0 * t) + 0.75 * numpy.sin(2 * math.pi * 300.0 * t)
    y = gearimpact.low_pass(x, 1000.0, 100.0)
    assert isinstance(y, numpy.ndarray) and y.shape == x.shape
    assert numpy.max(numpy.abs(y - (0.5 + numpy.cos(2 * math.pi * 50.0 * t)))) < 1e-11
    half = numpy.fft.rfft(x)
    half[100:] = 0.0
    assert numpy.max(numpy.abs(y - numpy.fft.irfft(half, n=1000))) < 1e-11


def test_decimate_keeps_the_band_and_removes_what_would_fold():
    # 0.1 s at 160 kHz of cos(2 pi 680 t) + cos(2 pi 17.3 kHz t), kept at 20 kHz: 17.3 kHz would
    # fold to 2.7 kHz. The decimator passes to 8 kHz with a ripple of 1e-5 and stops from 10 kHz
    # at 100 dB (docs/signals.md), each within Kaiser's 1 dB: 1.2e-5 of the tone is the bar, on
    # its own instants (no delay) and on numpy's DFT of the result.
    rate = 160e3
    t = 0.5 + numpy.arange(16000) / rate
    x = numpy.cos(2 * math.pi * 680.0 * t) + numpy.cos(2 * math.pi * 17300.0 * t)
    d = gearimpact.decimate(x, rate, 20e3, start=0.5)
    assert d["alias_free_band"] == 8000.0
    assert isinstance(d["values"], numpy.ndarray) and d["values"].shape == d["t"].shape
    assert abs(d["t"][1] - d["t"][0] - 1 / 20e3) < 1e-15
    assert d["t"][0] > 0.5 and d["t"][-1] < t[-1]
    assert numpy.max(numpy.abs(d["values"] - numpy.cos(2 * math.pi * 680.0 * d["t"]))) < 1.2e-5
    with pytest.raises(gearimpact.CaseError, match="rate_out"):
        gearimpact.decimate(x, rate, 2 * rate)


def test_order_analysis_of_mesh_harmonics_in_an_uneven_angle():
    # x = 1 + cos(20 theta) + 0.25 cos(40 theta), theta advancing unevenly:
    # FM0 = (2.25 - 0.25) / (1 + 0.25) = 1.6 (640 samples a revolution hit
    # both extremes); orders 20 and 40 read 1 and 0.25; the interpolation's
    # error is below 1e-7 (docs/signals.md), 1e-6 leaves a margin.
    t = numpy.arange(50001) * 2e-5
    theta = 2 * math.pi * 5.0 * t + 0.3 * numpy.sin(2 * math.pi * 3.0 * t)
    x = 1.0 + numpy.cos(20 * theta) + 0.25 * numpy.cos(40 * theta)
    r = gearimpact.order_analysis(theta, x, samples_per_revolution=640, teeth=20)
    assert r["revolutions"] == 5
    assert r["grid"] >= 640
    per_order = r["revolutions"]  # bins per order
    assert abs(r["amplitude"][20 * per_order] - 1.0) < 1e-6
    assert abs(r["amplitude"][40 * per_order] - 0.25) / 0.25 < 1e-6
    assert r["tsa"].shape == (640,)
    assert abs(r["indicators"]["fm0"] - 1.6) / 1.6 < 1e-6
    # Nothing but interpolation error outside the regular orders.
    assert numpy.max(numpy.abs(r["difference"])) < 1e-6


def test_indicators_of_a_sine():
    x = 3.0 * numpy.cos(5 * 2 * math.pi * numpy.arange(1024) / 1024)
    i = gearimpact.indicators(x)
    assert abs(i["kurtosis"] - 1.5) / 1.5 < 1e-11
    assert abs(i["crest_factor"] - math.sqrt(2)) / math.sqrt(2) < 1e-11
    assert gearimpact.indicators(numpy.full(8, 2.0))["kurtosis"] is None


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: gearimpact.spectrum([1.0, 2.0, 3.0], 0.0), "rate"),
        (lambda: gearimpact.low_pass([1.0, 2.0, 3.0], 0.0, 1.0), "rate"),
        (lambda: gearimpact.low_pass([1.0, 2.0, 3.0], 10.0, -1.0), "cutoff"),
        (lambda: gearimpact.spectrum([1.0, 2.0, 3.0], 1.0, "hamming"), "window"),
        (lambda: gearimpact.spectrum([[1.0, 2.0]], 1.0), "signal"),
        (lambda: gearimpact.order_analysis(numpy.linspace(0, 20, 100), numpy.zeros(100),
                                           samples_per_revolution=8), "samples_per_revolution"),
        (lambda: gearimpact.order_analysis(numpy.linspace(0, 20, 100), numpy.zeros(100),
                                           teeth=300), "teeth"),
        (lambda: gearimpact.order_analysis(numpy.linspace(0, 20, 100), numpy.zeros(100),
                                           teeth=20, shaft_orders=19), "shaft_orders"),
        (lambda: gearimpact.order_analysis(numpy.linspace(0, 20, 100), numpy.zeros(100),
                                           teeth=-3), "teeth"),
        (lambda: gearimpact.order_analysis(numpy.linspace(20, 0, 100), numpy.zeros(100)),
         "angle (sample 2)"),
        (lambda: gearimpact.order_analysis(numpy.linspace(0, 20, 100), numpy.zeros(100),
                                           teeth=20, nb4_half_width=1), "nb4_half_width"),
        (lambda: gearimpact.order_analysis(numpy.linspace(0, 20, 100), numpy.zeros(100),
                                           teeth=20, max_order=15), "max_order"),
    ],
)
def test_bad_arguments_are_named(call, field):
    with pytest.raises(gearimpact.CaseError) as error:
        call()
    assert error.value.field == field


def test_order_tracking_from_a_tacho_on_a_ramp_is_the_true_angle():
    # Edges of w0 t + alpha t^2 / 2 = 2 pi k / PPR in closed form (the root
    # without cancellation): the quadratic through three edges is the ramp's
    # own angle, so the estimate equals the truth to rounding and the order
    # analysis of sin(3 theta) on it matches the one on the true angle.
    w0, alpha, ppr = 240.0, 400.0, 2
    theta = 2 * math.pi * numpy.arange(0, 40) / ppr
    edges = 2 * theta / (w0 + numpy.sqrt(w0 * w0 + 2 * alpha * theta))
    t = numpy.arange(0, int(edges[-1] * 20000) + 1) / 20000.0
    truth = w0 * t + 0.5 * alpha * t * t
    estimate = gearimpact.tacho_angle(edges, ppr, t)
    assert numpy.max(numpy.abs(estimate - truth)) < 1e-9
    x = numpy.sin(3 * truth)
    tracked = gearimpact.order_analysis(None, x, 512, window="rectangular", tacho=edges,
                                        time=t, pulses_per_revolution=ppr)
    true = gearimpact.order_analysis(truth, x, 512, window="rectangular")
    assert numpy.max(numpy.abs(tracked["amplitude"] - true["amplitude"])) < 1e-6
    jittered = gearimpact.tacho_jitter(edges, 1e-6, 3)
    assert numpy.array_equal(jittered, gearimpact.tacho_jitter(edges, 1e-6, 3))
    assert 0 < numpy.max(numpy.abs(jittered - edges)) < 1e-5


def test_order_analysis_defaults_are_the_programs(cli, tmp_path):
    # The same record through `gearimpact signals` and order_analysis with both defaults: the
    # same band, TSA grid and indicators (before, the program's 512 and other grids differed).
    t = numpy.arange(50001) * 2e-5
    theta = 2 * math.pi * 5.0 * t + 0.3 * numpy.sin(2 * math.pi * 3.0 * t)
    x = (1.0 + numpy.cos(20 * theta) + 0.25 * numpy.cos(40 * theta)
         + 0.1 * numpy.cos(17 * theta) * numpy.exp(-((theta % (2 * math.pi)) - 1.0) ** 2 * 40))
    path = tmp_path / "record.csv"
    numpy.savetxt(path, numpy.column_stack([t, theta, x]), delimiter=",", fmt="%.17g",
                  header="t_s,theta_rad,x", comments="")
    out = tmp_path / "out"
    program = json.loads(cli("signals", path, "--column", "x", "--angle-column", "theta_rad",
                             "--teeth", "20", "--no-plots", "--out", out))
    ours = gearimpact.order_analysis(theta, x, teeth=20)
    assert ours["max_order"] == program["max_order"]
    assert ours["samples_per_revolution"] == program["samples_per_revolution"]
    assert ours["nb4_half_width"] == program["nb4_half_width"]
    for name in ("fm0", "fm4", "na4", "nb4", "m6a", "m8a", "energy_ratio"):
        assert ours["indicators"][name] == program["gear"][name], name
