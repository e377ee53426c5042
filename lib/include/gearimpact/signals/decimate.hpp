// A recorder's anti-alias filter before a coarser rate (docs/signals.md, "The anti-alias
// decimator"): a linear-phase low-pass by Kaiser's window method, evaluated at the coarser grid's
// instants only. A simulated acceleration steps where pairs enter and leave, so its content far
// above a coarser grid's Nyquist frequency would fold onto the spectrum; the interval-average
// sample's sinc attenuates a folded line only by about f_alias / (k fs). The filter passes
// [0, 0.4 fs_out] with a ripple of at most 10^(-A/20) and stops from 0.5 fs_out at A dB, so the
// coarser record is alias-free to A dB below 0.4 fs_out, its `alias_free_band_hz`.
#pragma once

#include <cstddef>
#include <vector>

namespace gearimpact::signals {

// The passband's and the stopband's edges as fractions of the coarser rate: the stopband starts
// at its Nyquist frequency, nothing above which may fold below 0.4 fs_out.
inline constexpr double kAliasFreeFraction = 0.4;
inline constexpr double kStopbandFraction = 0.5;
// The stopband attenuation a recorder's filter asks by default (dB): below a 16-bit ADC's
// quantisation (98 dB) and a delta-sigma DAQ's alias rejection.
inline constexpr double kAntiAliasAttenuationDb = 100.0;

// A low-pass FIR designed by Kaiser's window method (Kaiser 1974; Oppenheim & Schafer,
// Discrete-Time Signal Processing, 3rd ed., (7.62)-(7.63)) for an input sampled at rate_hz:
// h(tau) = 2 f_c / rate sinc(2 f_c tau) I0(beta sqrt(1 - (tau / half_span)^2)) / I0(beta), the
// ideal low-pass cut at f_c = (pass + stop) / 2 under a Kaiser window of beta = 0.1102 (A - 8.7)
// (A > 50 dB; Kaiser's lower ranges below), of order N = ceil((A - 7.95) / (2.285 dw)),
// dw = 2 pi (stop - pass) / rate, raised to an even N so that the filter is symmetric about its
// middle tap and adds no delay. Any instant tau of the continuous kernel may be taken: the
// decimation of an integer ratio takes its taps, another ratio its fractional offsets.
struct KaiserLowPass {
  double rate_hz = 0.0;
  double pass_hz = 0.0;
  double stop_hz = 0.0;
  double attenuation_db = 0.0;
  double beta = 0.0;
  std::size_t order = 0;  // N: N + 1 taps, half_span = N / 2 input samples
};

// Throws InputError naming "sample rate", "passband edge" or "stopband edge" unless
// 0 < pass < stop <= rate / 2, and "attenuation" unless it is in [21, 200] dB (below 21 dB the
// window is rectangular; above 200 dB the taps' rounding decides).
KaiserLowPass kaiser_low_pass(double rate_hz, double pass_hz, double stop_hz,
                              double attenuation_db);

// The kernel at an offset of tau_s (seconds) from its middle: 0 outside its span.
double kernel(const KaiserLowPass& f, double tau_s);

// The filter's frequency response at f_hz, sum_n h_n cos(2 pi f n / rate) over its taps (real:
// the filter is symmetric).
double response(const KaiserLowPass& f, double f_hz);

// A record on a uniform grid, from start_s at rate_hz.
struct UniformRecord {
  double start_s = 0.0;
  double rate_hz = 0.0;
  std::vector<double> values;
};

// The record at the coarser rate_out_hz through the anti-alias filter kaiser_low_pass(rate_in,
// 0.4 rate_out, 0.5 rate_out, attenuation_db), at the instants start + n / rate_out whose whole
// span lies inside the record (so the coarser record starts and ends half the filter's span
// inside the record: no end is extended, none rings). With an integer ratio rate_in / rate_out
// each output is the filter centred on an input sample: the decimation, no interpolation.
// Throws InputError naming "output rate" unless 0 < rate_out < rate_in, "signal" for a non-finite
// sample, and "record" when the record is shorter than the filter's span plus one output
// interval (the message gives both spans).
UniformRecord anti_alias_resample(const UniformRecord& record, double rate_out_hz,
                                  double attenuation_db = kAntiAliasAttenuationDb);

}  // namespace gearimpact::signals
