"""Spectra, order analysis, time-synchronous average and condition indicators of
sampled signals, as numpy arrays (docs/signals.md gives every definition)."""

from . import _core


def spectrum(signal, rate, window="hann"):
    """The single-sided amplitude spectrum of a uniformly sampled real signal.

    ``rate``: samples per second (or per revolution: the bins are then orders).
    ``window``: "hann" (periodic) or "rectangular". A sinusoid of amplitude A
    on a bin reads A with either window. Returns a dict: ``frequency``,
    ``amplitude`` (numpy arrays, bins 0..N/2), ``resolution``, ``coherent_gain``.
    """
    return _core.amplitude_spectrum(signal, float(rate), str(window))


def low_pass(signal, rate, cutoff):
    """The content of a uniformly sampled ``signal`` below ``cutoff`` (Hz), at the
    same samples: an ideal low-pass by its DFT, the record taken as periodic.

    A recorder's anti-alias filter: sample a run faster than the rate you keep,
    low-pass below that rate's Nyquist frequency, then keep every n-th sample.
    ``rate``: samples per second. Returns a numpy array.
    """
    return _core.low_pass(signal, float(rate), float(cutoff))


def tacho_angle(tacho, pulses_per_revolution, time):
    """The shaft's angle (rad, 0 at the first edge) at the instants ``time`` (s)
    estimated from a tacho's edge times ``tacho`` (s), edge k at 2 pi k /
    pulses_per_revolution: on each interval the quadratic through three
    consecutive edges (constant angular acceleration), exact under a linear
    speed ramp. ``time`` must lie between the first and the last edge."""
    return _core.angle_from_pulses(tacho, int(pulses_per_revolution), time)


def tacho_jitter(tacho, jitter, seed):
    """Edge times moved by a seeded Gaussian jitter of standard deviation
    ``jitter`` (s), as ``gearimpact simulate --tacho-out`` emits them."""
    return _core.tacho_jitter(tacho, float(jitter), int(seed))


def order_analysis(angle, signal, samples_per_revolution=None, teeth=None, shaft_orders=1,
                   sidebands=1, window="hann", max_order=None, nb4_half_width=None, tacho=None,
                   time=None, pulses_per_revolution=1):
    """Order spectrum and time-synchronous average of ``signal`` sampled with its
    shaft's strictly increasing ``angle`` (rad), at any instants.

    The samples are interpolated (cubic, fourth order) onto equal angle steps at
    least as fine as the record; the TSA over the whole revolutions is reduced to
    ``samples_per_revolution`` by an ideal low-pass. With ``teeth`` (the gear on
    that shaft) the dict also holds the regular, residual and difference signals,
    the mesh band and its envelope, and ``indicators`` (FM0, FM4, NA4, NB4, M6A,
    M8A, energy ratio, sideband level, of the TSA; None where 0/0).

    The TSA keeps the orders the record's band holds, up to ``max_order``
    (None: 0.4 of the fewest samples any whole revolution holds, i.e. 0.4 of a
    uniform record's rate over the fastest revolution's speed, as ``gearimpact
    signals`` takes it). ``samples_per_revolution`` (None: the indicators' grid,
    the smallest power of two >= 8 max_order + 1) sets the TSA's samples only:
    the indicators are computed on the indicators' grid whatever it is.
    ``nb4_half_width``: NB4's band h* z +- W about the strongest mesh harmonic
    (None: (z - 1) // 2; 1 is refused, its NB4 being 1.5 whatever the fault).

    Computed order tracking: with ``tacho`` (edge times, s) and ``time`` (the
    signal's sample times, s, inside the edges' span) and ``angle`` None, the
    angle is ``tacho_angle(tacho, pulses_per_revolution, time)``.
    """
    if tacho is not None:
        if angle is not None:
            raise ValueError("order_analysis: angle or tacho, not both")
        if time is None:
            raise ValueError("order_analysis: tacho needs time, the signal's sample times (s)")
        angle = tacho_angle(tacho, pulses_per_revolution, time)
    return _core.order_analysis(angle, signal,
                                0 if samples_per_revolution is None else samples_per_revolution,
                                0 if teeth is None else teeth, shaft_orders, sidebands,
                                str(window), -1 if max_order is None else max_order,
                                0 if nb4_half_width is None else nb4_half_width)


def indicators(record):
    """RMS, peak, crest factor and kurtosis of a record (a dict; None where 0/0)."""
    return _core.condition_indicators(record)
