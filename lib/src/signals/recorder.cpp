#include "gearimpact/signals/recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact::signals {

namespace {

std::string text(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

double mean_of(const std::vector<double>& x) {
  double sum = 0.0;
  for (const double v : x) sum += v;
  return x.empty() ? 0.0 : sum / static_cast<double>(x.size());
}

double central_power(const std::vector<double>& x) {
  const double m = mean_of(x);
  double sum = 0.0;
  for (const double v : x) sum += (v - m) * (v - m);
  return x.empty() ? 0.0 : sum / static_cast<double>(x.size());
}

}  // namespace

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

RandomStream::RandomStream(std::uint64_t seed, std::uint64_t stream)
    : engine_(splitmix64(splitmix64(seed) ^ stream)) {}

double RandomStream::uniform() {
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double RandomStream::gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Box-Muller: u1 in (0, 1] keeps the logarithm finite.
  const double u1 = 1.0 - uniform();
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  spare_ = r * std::sin(2.0 * pi * u2);
  has_spare_ = true;
  return r * std::cos(2.0 * pi * u2);
}

SecondOrderSection accelerometer(double resonance_hz, double damping_ratio) {
  const double w = 2.0 * pi * resonance_hz;
  return {resonance_hz, damping_ratio, 0.0, w * w};
}

SecondOrderSection path_mode(double frequency_hz, double damping_ratio, double gain) {
  const double w = 2.0 * pi * frequency_hz;
  return {frequency_hz, damping_ratio, gain * 2.0 * damping_ratio * w, gain * w * w};
}

double gain_at(const SecondOrderSection& s, double f_hz) {
  const double w = 2.0 * pi * s.frequency_hz;
  const double v = 2.0 * pi * f_hz;
  const double re = w * w - v * v;
  const double im = 2.0 * s.damping_ratio * w * v;
  return std::hypot(s.b0, s.b1 * v) / std::hypot(re, im);
}

std::vector<double> filter_sections(const std::vector<double>& x, double rate_hz,
                                    const std::vector<SecondOrderSection>& sections,
                                    const std::string& name) {
  std::vector<double> y(x.size(), 0.0);
  if (x.empty()) return y;
  const double T = 1.0 / rate_hz;
  for (const SecondOrderSection& s : sections) {
    if (!(s.frequency_hz > 0.0 && s.frequency_hz < rate_hz / 4.0)) {
      throw InputError(name, text(s.frequency_hz) + " Hz",
                       "a frequency in (0, " + text(rate_hz / 4.0) +
                           ") Hz, below a quarter of the record's rate " + text(rate_hz) + " Hz");
    }
    if (!(s.damping_ratio > 0.0 && s.damping_ratio < 1.0)) {
      throw InputError(name, "damping ratio " + text(s.damping_ratio), "a damping ratio in (0, 1)");
    }
    // Controllable form: x1' = x2, x2' = -w^2 x1 - 2 zeta w x2 + u, y = b0 x1 + b1 x2. For u
    // held constant the state relaxes to (u / w^2, 0): x(T) = x* + Phi (x(0) - x*), with
    // Phi = e^{-sigma T} [cos(wd T) I + sin(wd T) / wd (A + sigma I)], sigma = zeta w.
    const double w = 2.0 * pi * s.frequency_hz;
    const double sigma = s.damping_ratio * w;
    const double wd = w * std::sqrt(1.0 - s.damping_ratio * s.damping_ratio);
    const double decay = std::exp(-sigma * T);
    const double c = decay * std::cos(wd * T);
    const double sn = decay * std::sin(wd * T) / wd;
    const double p11 = c + sigma * sn;
    const double p12 = sn;
    const double p21 = -w * w * sn;
    const double p22 = c - sigma * sn;
    // From rest at the first sample's level: the state at its equilibrium.
    double x1 = x.front() / (w * w);
    double x2 = 0.0;
    y[0] += s.b0 * x1 + s.b1 * x2;
    for (std::size_t n = 1; n < x.size(); ++n) {
      const double equilibrium = x[n] / (w * w);
      const double d1 = x1 - equilibrium;
      const double d2 = x2;
      x1 = equilibrium + p11 * d1 + p12 * d2;
      x2 = p21 * d1 + p22 * d2;
      y[n] += s.b0 * x1 + s.b1 * x2;
    }
  }
  return y;
}

std::vector<double> path_then_accelerometer(const std::vector<double>& x, double rate_hz,
                                            const std::vector<SecondOrderSection>& path,
                                            const std::optional<SecondOrderSection>& accelerometer,
                                            const std::string& path_name,
                                            const std::string& accelerometer_name) {
  // The path's modes sum to the path; the accelerometer follows it.
  std::vector<double> y = path.empty() ? x : filter_sections(x, rate_hz, path, path_name);
  if (accelerometer) y = filter_sections(y, rate_hz, {*accelerometer}, accelerometer_name);
  return y;
}

std::vector<SecondOrderSection> draw_path(std::uint64_t seed, int modes, double band_low_hz,
                                          double band_high_hz, double damping_low,
                                          double damping_high) {
  if (modes < 1 || modes > 16) {
    throw InputError("path modes", std::to_string(modes), "an integer in [1, 16]");
  }
  if (!(band_low_hz > 0.0 && band_high_hz >= band_low_hz && std::isfinite(band_high_hz))) {
    throw InputError("path band", text(band_low_hz) + " to " + text(band_high_hz) + " Hz",
                     "0 < low <= high, finite");
  }
  if (!(damping_low > 0.0 && damping_high >= damping_low && damping_high < 1.0)) {
    throw InputError("path damping", text(damping_low) + " to " + text(damping_high),
                     "0 < low <= high < 1");
  }
  RandomStream random(seed, 2);
  std::vector<double> f(static_cast<std::size_t>(modes));
  std::vector<double> zeta(f.size());
  std::vector<double> g(f.size());
  double total = 0.0;
  for (std::size_t r = 0; r < f.size(); ++r) {
    f[r] = band_low_hz * std::pow(band_high_hz / band_low_hz, random.uniform());
    zeta[r] = damping_low + (damping_high - damping_low) * random.uniform();
    // A flat Dirichlet: normalised unit exponentials.
    g[r] = -std::log(1.0 - random.uniform());
    total += g[r];
  }
  std::vector<SecondOrderSection> path;
  for (std::size_t r = 0; r < f.size(); ++r) path.push_back(path_mode(f[r], zeta[r], g[r] / total));
  return path;
}

NoiseResult add_noise(std::vector<double>& x, double snr_db, std::uint64_t seed, bool exact) {
  if (!std::isfinite(snr_db))
    throw InputError("noise SNR", text(snr_db) + " dB", "a finite SNR in dB");
  if (x.size() < 2) throw InputError("signal", std::to_string(x.size()) + " samples", "at least 2");
  const double signal_power = central_power(x);
  NoiseResult result;
  result.sigma = std::sqrt(signal_power) * std::pow(10.0, -snr_db / 20.0);
  RandomStream random(seed, 1);
  std::vector<double> noise(x.size());
  for (double& v : noise) v = result.sigma * random.gaussian();
  double noise_power = 0.0;
  for (const double v : noise) noise_power += v * v;
  noise_power /= static_cast<double>(noise.size());
  if (exact && noise_power > 0.0) {
    const double scale = result.sigma / std::sqrt(noise_power);
    for (double& v : noise) v *= scale;
    noise_power = result.sigma * result.sigma;
  }
  for (std::size_t i = 0; i < x.size(); ++i) x[i] += noise[i];
  result.realised_snr_db = 10.0 * std::log10(signal_power / noise_power);
  return result;
}

AdcResult adc(std::vector<double>& x, double range, int bits) {
  if (!(range > 0.0 && std::isfinite(range))) {
    throw InputError("range", text(range), "a finite range > 0");
  }
  if (bits < 0 || bits > 32)
    throw InputError("bits", std::to_string(bits), "an integer in [0, 32]");
  AdcResult result;
  result.lsb = bits == 0 ? 0.0 : 2.0 * range / std::ldexp(1.0, bits);
  for (double& v : x) {
    if (v > range || v < -range) {
      ++result.clipped;
      v = std::clamp(v, -range, range);
    }
    // 2^bits codes, -2^(bits-1) ... 2^(bits-1) - 1: the top of the range reads one code below.
    if (bits > 0) {
      const double half = std::ldexp(1.0, bits - 1);
      v = result.lsb * std::clamp(std::nearbyint(v / result.lsb), -half, half - 1.0);
    }
  }
  return result;
}

}  // namespace gearimpact::signals
