// What a recorder does to a sampled acceleration beyond the band-limited sample
// (docs/signals.md, "The recorder"): an optional accelerometer resonance and a
// transfer path of a few seeded modes, each a second-order section discretised
// exactly for the piecewise-constant input the interval averages define;
// white Gaussian noise at a stated SNR from a seeded stream; an ADC's range
// (clipping counted) and quantisation. Each function is seeded explicitly, so
// that a record regenerates bit for bit on one build.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace gearimpact::signals {

// A stream of random numbers that does not depend on the standard library's
// distributions (implementation-defined): std::mt19937_64 seeded by the
// SplitMix64 hash of (seed, stream); uniforms from its top 53 bits, Gaussians
// by our own Box-Muller.
class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint64_t stream);
  double uniform();   // in [0, 1)
  double gaussian();  // N(0, 1)

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

// SplitMix64's finaliser of x (Steele, Lea & Flood 2014): the seeds' hash.
std::uint64_t splitmix64(std::uint64_t x);

// One second-order section, H(s) = (b1 s + b0) / (s^2 + 2 zeta w s + w^2), w = 2 pi f.
struct SecondOrderSection {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;  // in (0, 1)
  double b1 = 0.0;
  double b0 = 0.0;
};
// The accelerometer: w^2 / (s^2 + 2 zeta w s + w^2), unit gain at low frequency.
SecondOrderSection accelerometer(double resonance_hz, double damping_ratio);
// A path mode: g (2 zeta w s + w^2) / (s^2 + 2 zeta w s + w^2), a base-excitation
// transmissibility of gain g at low frequency.
SecondOrderSection path_mode(double frequency_hz, double damping_ratio, double gain);
// |H(i 2 pi f)| of a section.
double gain_at(const SecondOrderSection& s, double f_hz);

// The sections' summed response to x, each sample x[n] held constant over the
// interval that ends at it (the mean an interval-average sample is), from
// rest at the first sample's level: exact for that input (a matrix
// exponential per interval). Throws InputError naming `name` for a
// frequency at or above rate / 4 (the discretisation's error, (2 pi f /
// rate)^2, would not be small) or a damping ratio outside (0, 1).
std::vector<double> filter_sections(const std::vector<double>& x, double rate_hz,
                                    const std::vector<SecondOrderSection>& sections,
                                    const std::string& name);

// What the recorder's filters do to a record, in their order: the path's modes summed (none when
// `path` is empty), then the accelerometer's resonance (when given). Errors name `path_name`
// or `accelerometer_name` as filter_sections does.
std::vector<double> path_then_accelerometer(const std::vector<double>& x, double rate_hz,
                                            const std::vector<SecondOrderSection>& path,
                                            const std::optional<SecondOrderSection>& accelerometer,
                                            const std::string& path_name,
                                            const std::string& accelerometer_name);

// A transfer path of `modes` modes, seeded: f_r log-uniform in [band_low,
// band_high], zeta_r uniform in [damping_low, damping_high], the gains a flat
// Dirichlet draw (sum 1). Stream 2 of `seed`.
std::vector<SecondOrderSection> draw_path(std::uint64_t seed, int modes, double band_low_hz,
                                          double band_high_hz, double damping_low,
                                          double damping_high);

// White Gaussian noise added to x in place at a signal-to-noise ratio of
// snr_db: sigma = RMS(x - mean x) 10^(-snr_db / 20). Exact mode rescales
// the draw to sigma exactly. Stream 1 of `seed`. Returns what was realised.
struct NoiseResult {
  double sigma = 0.0;            // the target's
  double realised_snr_db = 0.0;  // 10 log10(mean (x - mean x)^2 / mean n^2)
};
NoiseResult add_noise(std::vector<double>& x, double snr_db, std::uint64_t seed, bool exact);

// An ADC in place: clip at +-range (counted), then round to LSB = 2 range / 2^bits
// (bits 0: no rounding). Throws InputError naming "range" or "bits" outside
// (0, inf) and [0, 32].
struct AdcResult {
  long long clipped = 0;
  double lsb = 0.0;
};
AdcResult adc(std::vector<double>& x, double range, int bits);

}  // namespace gearimpact::signals
