#include "gearimpact/signals/resample.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>

#include "../require.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/signals/fft.hpp"

namespace gearimpact::signals {
namespace {

// Finite, strictly increasing, at least 4 values (the cubic's nodes).
void check_abscissa(const std::vector<double>& a, const char* name) {
  if (a.size() < 4) {
    throw InputError(name, std::to_string(a.size()) + " samples", "at least 4 samples");
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(a[i])) {
      throw InputError(std::string(name) + " (sample " + std::to_string(i + 1) + ")", a[i],
                       "a finite value");
    }
    if (i > 0 && !(a[i] > a[i - 1])) {
      throw InputError(std::string(name) + " (sample " + std::to_string(i + 1) + ")",
                       format_number(a[i]) + " after " + format_number(a[i - 1]),
                       "strictly increasing values");
    }
  }
}

void check_values(const std::vector<double>& v, std::size_t size, const char* name) {
  if (v.size() != size) {
    throw InputError(name, std::to_string(v.size()) + " samples",
                     "as many samples as the abscissa (" + std::to_string(size) + ")");
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw InputError(std::string(name) + " (sample " + std::to_string(i + 1) + ")", v[i],
                       "a finite value");
    }
  }
}

// Cubic Lagrange through nodes i0..i0+3, at u.
double lagrange4(const std::vector<double>& a, const std::vector<double>& v, std::size_t i0,
                 double u) {
  double sum = 0.0;
  for (std::size_t j = i0; j < i0 + 4; ++j) {
    double basis = 1.0;
    for (std::size_t m = i0; m < i0 + 4; ++m) {
      if (m != j) basis *= (u - a[m]) / (a[j] - a[m]);
    }
    sum += basis * v[j];
  }
  return sum;
}

// First node of the four about the interval [a[i], a[i+1]] holding u.
std::size_t stencil(const std::vector<double>& a, double u) {
  const auto upper = std::upper_bound(a.begin(), a.end(), u);
  const std::size_t i = upper == a.begin() ? 0 : static_cast<std::size_t>(upper - a.begin()) - 1;
  const std::size_t first = i == 0 ? 0 : i - 1;
  return std::min(first, a.size() - 4);
}

}  // namespace

void check_sample_rate(double rate) {
  checks::require_finite_positive("sample rate", rate, "Hz (or samples per unit of the abscissa)");
}

void check_samples_per_revolution(std::size_t samples_per_revolution) {
  if (samples_per_revolution < 16 || samples_per_revolution > (1u << 24)) {
    throw InputError("samples per revolution", std::to_string(samples_per_revolution),
                     "16 to 16777216");
  }
}

double interpolate_cubic(const std::vector<double>& abscissa, const std::vector<double>& value,
                         double at) {
  check_abscissa(abscissa, "abscissa");
  check_values(value, abscissa.size(), "value");
  if (!(at >= abscissa.front() && at <= abscissa.back())) {
    throw InputError(
        "interpolation point", at,
        "inside [" + format_number(abscissa.front()) + ", " + format_number(abscissa.back()) + "]");
  }
  return lagrange4(abscissa, value, stencil(abscissa, at), at);
}

std::vector<double> resample_uniform(const std::vector<double>& time,
                                     const std::vector<double>& signal, double rate,
                                     const char* time_name, const char* signal_name) {
  check_abscissa(time, time_name);
  check_values(signal, time.size(), signal_name);
  const std::vector<double> grid = uniform_times(time.front(), time.back(), rate);
  std::vector<double> out(grid.size());
  for (std::size_t k = 0; k < grid.size(); ++k) {
    out[k] = lagrange4(time, signal, stencil(time, grid[k]), grid[k]);
  }
  return out;
}

std::size_t uniform_sample_count(double t0, double t_end, double rate) {
  check_sample_rate(rate);
  const double span = t_end - t0;
  // Whole samples inside the span; the tiny allowance keeps the last one
  // when span * rate is an integer spoiled by rounding.
  const double count = std::floor(span * rate * (1.0 + 1e-12)) + 1.0;
  if (!(count >= 2.0 && count <= static_cast<double>(kMostUniformSamples))) {
    char estimate[96];
    std::snprintf(estimate, sizeof estimate, "%.3g samples, %.3g GB a copy", count,
                  count * 8.0 * 1e-9);
    throw InputError("sample rate", rate,
                     "a rate giving 2 to " + std::to_string(kMostUniformSamples) +
                         " samples over the record of " + format_number(span) + " s (this one " +
                         estimate + ")");
  }
  return static_cast<std::size_t>(count);
}

std::vector<double> uniform_times(double t0, double t_end, double rate) {
  const std::size_t n = uniform_sample_count(t0, t_end, rate);
  std::vector<double> grid(n);
  for (std::size_t k = 0; k < n; ++k) {
    grid[k] = std::min(t0 + static_cast<double>(k) / rate, t_end);
  }
  return grid;
}

std::vector<double> low_pass(const std::vector<double>& uniform, double rate_hz, double cutoff_hz) {
  check_sample_rate(rate_hz);
  if (!(std::isfinite(cutoff_hz) && cutoff_hz > 0.0)) {
    throw InputError("cutoff", cutoff_hz, "a finite frequency > 0 Hz");
  }
  if (uniform.size() < 2) {
    throw InputError("signal", std::to_string(uniform.size()) + " samples", "at least 2 samples");
  }
  check_values(uniform, uniform.size(), "signal");
  check_dft_range(uniform, "signal");
  std::vector<std::complex<double>> spectrum = real_dft(uniform);
  const double n = static_cast<double>(uniform.size());
  // Bin k lies at k rate / N: those at and above the cutoff go.
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    if (static_cast<double>(k) * rate_hz / n >= cutoff_hz) spectrum[k] = 0.0;
  }
  return inverse_real_dft(spectrum, uniform.size());
}

AngleSignal resample_on_angle(const std::vector<double>& angle, const std::vector<double>& signal,
                              std::size_t samples_per_revolution, const char* angle_name,
                              const char* signal_name) {
  check_abscissa(angle, angle_name);
  check_values(signal, angle.size(), signal_name);
  check_samples_per_revolution(samples_per_revolution);
  const double turn = 2.0 * pi;
  AngleSignal out;
  out.samples_per_revolution = samples_per_revolution;
  out.start_angle = std::ceil(angle.front() / turn) * turn;
  const double whole = std::floor((angle.back() - out.start_angle) / turn * (1.0 + 1e-12));
  if (!(whole >= 1.0)) {
    throw InputError(
        angle_name,
        "from " + format_number(angle.front()) + " to " + format_number(angle.back()) + " rad",
        "at least one whole revolution after the first multiple of 2 pi (" +
            format_number(out.start_angle) + " rad)");
  }
  out.revolutions = static_cast<std::size_t>(whole);
  const std::size_t n = out.revolutions * samples_per_revolution;
  out.values.resize(n);
  const double step = turn / static_cast<double>(samples_per_revolution);
  for (std::size_t j = 0; j < n; ++j) {
    const double u = std::min(out.start_angle + static_cast<double>(j) * step, angle.back());
    out.values[j] = lagrange4(angle, signal, stencil(angle, u), u);
  }
  return out;
}

}  // namespace gearimpact::signals
