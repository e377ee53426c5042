// Resampling of a signal sampled at irregular instants: onto a uniform time
// grid, or onto equal steps of a known, increasing angle (order tracking with
// the simulated angle, no tachometer estimate).
//
// Interpolation: cubic Lagrange through the four nearest samples (two each
// side; the end intervals use the four end samples). It is fourth order: for
// a smooth signal and spacing h the error is at most h^4 max|x''''| / 24
// times the node factor (9/16 for equal spacing inside), it reproduces
// cubics exactly, and it needs no end condition, unlike a spline.
#pragma once

#include <cstddef>
#include <vector>

namespace gearimpact::signals {

// Throws InputError naming "sample rate" unless `rate` is finite and > 0.
void check_sample_rate(double rate);
// Throws InputError naming "samples per revolution" unless it is 16 to 2^24.
void check_samples_per_revolution(std::size_t samples_per_revolution);

// x at `at` from samples (abscissa[i], value[i]), abscissa strictly
// increasing, `at` inside [abscissa.front(), abscissa.back()].
double interpolate_cubic(const std::vector<double>& abscissa, const std::vector<double>& value,
                         double at);

// The signal at t0 + n / rate, n = 0, 1, ... while inside [t0, t_end].
// Throws InputError naming `time_name` unless the times are finite and
// strictly increasing (at least 4 of them), naming `signal_name` for a
// non-finite sample, and "sample rate" unless rate is finite, > 0 and gives
// at least 2 samples.
std::vector<double> resample_uniform(const std::vector<double>& time,
                                     const std::vector<double>& signal, double rate,
                                     const char* time_name = "time",
                                     const char* signal_name = "signal");

// The most instants of a uniform grid: each copy of a signal on it is then at most 400 MB
// (as many as simulate's max_rows), and an analysis holds a few.
constexpr std::size_t kMostUniformSamples = 50000000;

// The instants resample_uniform's grid over [t0, t_end] has, checked before any is made:
// throws InputError naming "sample rate" unless rate is finite and > 0 and gives 2 to
// kMostUniformSamples instants (the message says how many it would give, and their size).
std::size_t uniform_sample_count(double t0, double t_end, double rate);

// The instants of resample_uniform's grid over [t0, t_end]: t0 + n / rate,
// n = 0, 1, ... while inside (the last one clamped to t_end against the
// rounding of n / rate). Throws as uniform_sample_count.
std::vector<double> uniform_times(double t0, double t_end, double rate);

// The content of a uniformly sampled record below `cutoff_hz`, at the same
// samples: an ideal low-pass by the record's DFT (the bins at and above the
// cutoff set to 0; the record taken as periodic, so the mismatch of its ends
// rings into its first and last stretch). A recorder's anti-alias filter
// before a coarser rate: a simulated acceleration steps where a pair enters
// or leaves, and its content far above a coarser grid's Nyquist frequency
// would fold onto the spectrum (the program's recorder uses the anti-alias decimator of
// decimate.hpp instead, which neither leaks nor rings). Throws InputError naming "sample rate" or
// "cutoff" unless each is finite and > 0, and "signal" for fewer than 2
// samples or a non-finite one.
std::vector<double> low_pass(const std::vector<double>& uniform, double rate_hz, double cutoff_hz);

// A signal sampled at equal steps of a shaft's angle, whole revolutions only.
struct AngleSignal {
  std::size_t samples_per_revolution = 0;
  std::size_t revolutions = 0;
  // The angle of the first sample (rad): the first multiple of 2 pi at or
  // after the first angle, so that revolution r covers [start + 2 pi r,
  // start + 2 pi (r + 1)) and an average keeps the shaft's own phase.
  double start_angle = 0.0;
  std::vector<double> values;  // samples_per_revolution * revolutions
};

// Resamples (angle[i], signal[i]) at start + 2 pi j / samples_per_revolution.
// The angle must be finite and strictly increasing (InputError naming
// `angle_name`), cover at least one whole revolution after its first multiple
// of 2 pi, and samples_per_revolution 16 to 2^24.
AngleSignal resample_on_angle(const std::vector<double>& angle, const std::vector<double>& signal,
                              std::size_t samples_per_revolution, const char* angle_name = "angle",
                              const char* signal_name = "signal");

}  // namespace gearimpact::signals
