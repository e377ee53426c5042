#include "gearimpact/signals/decimate.hpp"

#include <algorithm>
#include <boost/math/special_functions/bessel.hpp>
#include <cmath>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact::signals {
namespace {

// sin(pi x) / (pi x), 1 at 0.
double sinc_pi(double x) {
  if (x == 0.0) return 1.0;
  return std::sin(pi * x) / (pi * x);
}

// Kaiser's beta for a stopband of A dB, Oppenheim & Schafer (7.62).
double kaiser_beta(double a_db) {
  if (a_db > 50.0) return 0.1102 * (a_db - 8.7);
  if (a_db >= 21.0) return 0.5842 * std::pow(a_db - 21.0, 0.4) + 0.07886 * (a_db - 21.0);
  return 0.0;
}

}  // namespace

KaiserLowPass kaiser_low_pass(double rate_hz, double pass_hz, double stop_hz,
                              double attenuation_db) {
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    throw InputError("sample rate", rate_hz, "a finite rate > 0 Hz");
  }
  if (!(std::isfinite(stop_hz) && stop_hz > 0.0 && stop_hz <= 0.5 * rate_hz)) {
    throw InputError("stopband edge", stop_hz,
                     "in (0, rate / 2] = (0, " + format_number(0.5 * rate_hz) + "] Hz");
  }
  if (!(std::isfinite(pass_hz) && pass_hz > 0.0 && pass_hz < stop_hz)) {
    throw InputError("passband edge", pass_hz,
                     "in (0, stopband edge) = (0, " + format_number(stop_hz) + ") Hz");
  }
  if (!(attenuation_db >= 21.0 && attenuation_db <= 200.0)) {
    throw InputError("attenuation", attenuation_db, "21 to 200 dB");
  }
  KaiserLowPass f;
  f.rate_hz = rate_hz;
  f.pass_hz = pass_hz;
  f.stop_hz = stop_hz;
  f.attenuation_db = attenuation_db;
  f.beta = kaiser_beta(attenuation_db);
  // Oppenheim & Schafer (7.63), the order for the transition width dw.
  const double transition = 2.0 * pi * (stop_hz - pass_hz) / rate_hz;
  auto order = static_cast<std::size_t>(std::ceil((attenuation_db - 8.0) / (2.285 * transition)));
  if (order % 2 == 1) ++order;
  f.order = std::max<std::size_t>(order, 2);
  return f;
}

namespace {

// The kernel with the window's normalisation I0(beta) given, which does not change from tap to
// tap: evaluated once per filter instead of at every tap of every output.
double kernel_normalised_by(const KaiserLowPass& f, double tau_s, double i0_beta) {
  const double half_span_s = 0.5 * static_cast<double>(f.order) / f.rate_hz;
  const double r = tau_s / half_span_s;
  if (!(std::fabs(r) <= 1.0)) return 0.0;
  const double cutoff_hz = 0.5 * (f.pass_hz + f.stop_hz);
  const double window = boost::math::cyl_bessel_i(0, f.beta * std::sqrt(1.0 - r * r)) / i0_beta;
  return 2.0 * cutoff_hz / f.rate_hz * sinc_pi(2.0 * cutoff_hz * tau_s) * window;
}

}  // namespace

double kernel(const KaiserLowPass& f, double tau_s) {
  return kernel_normalised_by(f, tau_s, boost::math::cyl_bessel_i(0, f.beta));
}

double response(const KaiserLowPass& f, double f_hz) {
  const auto half = static_cast<long long>(f.order / 2);
  double sum = kernel(f, 0.0);
  for (long long n = 1; n <= half; ++n) {
    const double tau = static_cast<double>(n) / f.rate_hz;
    sum += 2.0 * kernel(f, tau) * std::cos(2.0 * pi * f_hz * tau);
  }
  return sum;
}

UniformRecord anti_alias_resample(const UniformRecord& record, double rate_out_hz,
                                  double attenuation_db) {
  const double rate_in = record.rate_hz;
  if (!(std::isfinite(rate_out_hz) && rate_out_hz > 0.0 && rate_out_hz < rate_in)) {
    throw InputError("output rate", rate_out_hz,
                     "a rate > 0 and below the record's " + format_number(rate_in) + " Hz");
  }
  for (std::size_t i = 0; i < record.values.size(); ++i) {
    if (!std::isfinite(record.values[i])) {
      throw InputError("signal (sample " + std::to_string(i + 1) + ")", record.values[i],
                       "a finite value");
    }
  }
  const KaiserLowPass f = kaiser_low_pass(rate_in, kAliasFreeFraction * rate_out_hz,
                                          kStopbandFraction * rate_out_hz, attenuation_db);
  const auto half = static_cast<long long>(f.order / 2);
  const auto size = static_cast<long long>(record.values.size());
  // Output n sits at input position n * ratio; its span [n ratio - half, n ratio + half] must
  // lie inside [0, size - 1].
  // A ratio within 1e-9 of an integer is that integer: a record's rate read from its times
  // (1 / their median spacing) carries their rounding.
  const double nearest = std::round(rate_in / rate_out_hz);
  const bool integer = std::fabs(rate_in / rate_out_hz - nearest) <= 1e-9 * nearest;
  const double ratio = integer ? nearest : rate_in / rate_out_hz;
  const auto first = static_cast<long long>(std::ceil(static_cast<double>(half) / ratio));
  const auto last =
      static_cast<long long>(std::floor(static_cast<double>(size - 1 - half) / ratio));
  if (last < first + 1) {
    throw InputError("record",
                     format_number(static_cast<double>(size) / rate_in) + " s (" +
                         std::to_string(size) + " samples at " + format_number(rate_in) + " Hz)",
                     "longer than the anti-alias filter's span of " +
                         format_number(static_cast<double>(f.order) / rate_in) +
                         " s plus two output intervals");
  }
  UniformRecord out;
  out.rate_hz = rate_out_hz;
  out.values.reserve(static_cast<std::size_t>(last - first + 1));
  if (integer) {
    const auto step = static_cast<long long>(nearest);
    out.start_s = record.start_s + static_cast<double>(first * step) / rate_in;
    std::vector<double> taps(static_cast<std::size_t>(half) + 1);
    for (long long k = 0; k <= half; ++k) {
      taps[static_cast<std::size_t>(k)] = kernel(f, static_cast<double>(k) / rate_in);
    }
    for (long long n = first; n <= last; ++n) {
      const long long centre = n * step;
      double sum = taps[0] * record.values[static_cast<std::size_t>(centre)];
      for (long long k = 1; k <= half; ++k) {
        sum += taps[static_cast<std::size_t>(k)] *
               (record.values[static_cast<std::size_t>(centre - k)] +
                record.values[static_cast<std::size_t>(centre + k)]);
      }
      out.values.push_back(sum);
    }
    return out;
  }
  out.start_s = record.start_s + static_cast<double>(first) / rate_out_hz;
  const double i0_beta = boost::math::cyl_bessel_i(0, f.beta);
  for (long long n = first; n <= last; ++n) {
    const double position = static_cast<double>(n) * ratio;
    const auto low = static_cast<long long>(std::ceil(position - static_cast<double>(half)));
    const auto high = static_cast<long long>(std::floor(position + static_cast<double>(half)));
    double sum = 0.0;
    for (long long k = low; k <= high; ++k) {
      sum += kernel_normalised_by(f, (position - static_cast<double>(k)) / rate_in, i0_beta) *
             record.values[static_cast<std::size_t>(k)];
    }
    out.values.push_back(sum);
  }
  return out;
}

}  // namespace gearimpact::signals
