#include "gearimpact/signals/order_tracking.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact::signals {

std::vector<double> angle_from_pulses(const std::vector<double>& pulse_times,
                                      std::size_t pulses_per_revolution,
                                      const std::vector<double>& t, const char* name) {
  if (pulses_per_revolution < 1 || pulses_per_revolution > (std::size_t{1} << 20)) {
    throw InputError("pulses per revolution", std::to_string(pulses_per_revolution),
                     "1 to 1048576");
  }
  const std::size_t n = pulse_times.size();
  if (n < 3) {
    throw InputError(name, std::to_string(n) + " pulses",
                     "at least 3 pulse times (a quadratic through three)");
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(pulse_times[k]) || (k > 0 && !(pulse_times[k] > pulse_times[k - 1]))) {
      throw InputError(std::string(name) + " pulse " + std::to_string(k),
                       std::to_string(pulse_times[k]) + " s",
                       "finite and later than the pulse before it");
    }
  }
  const double step = 2.0 * pi / static_cast<double>(pulses_per_revolution);
  std::vector<double> angle(t.size());
  for (std::size_t j = 0; j < t.size(); ++j) {
    const double tj = t[j];
    if (!(tj >= pulse_times.front() && tj <= pulse_times.back())) {
      throw InputError("time", std::to_string(tj) + " s",
                       "between the first and the last pulse, [" +
                           std::to_string(pulse_times.front()) + ", " +
                           std::to_string(pulse_times.back()) + "] s");
    }
    // The interval [t_k, t_k+1] holding tj, and the three pulses about it.
    const auto upper = std::upper_bound(pulse_times.begin(), pulse_times.end(), tj);
    std::size_t k = static_cast<std::size_t>(upper - pulse_times.begin());
    k = k == 0 ? 0 : k - 1;
    const std::size_t a = std::min(k == 0 ? 0 : k - 1, n - 3);
    const double ta = pulse_times[a];
    const double tb = pulse_times[a + 1];
    const double tc = pulse_times[a + 2];
    // Newton's form about pulse a: divided differences of the angles step
    // apart, so that the large angle enters once, as a * step.
    const double d1 = step / (tb - ta);
    const double d2 = (step / (tc - tb) - d1) / (tc - ta);
    angle[j] = static_cast<double>(a) * step + (tj - ta) * (d1 + d2 * (tj - tb));
  }
  return angle;
}

namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30U)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27U)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31U);
}

// A uniform in (0, 1) from the top 53 bits, never 0 (Box-Muller takes its log).
double uniform_open(std::mt19937_64& engine) {
  return (static_cast<double>(engine() >> 11U) + 0.5) * 0x1.0p-53;
}

}  // namespace

std::vector<double> tacho_jitter(const std::vector<double>& pulse_times, double sigma_s,
                                 std::uint64_t seed) {
  if (!(std::isfinite(sigma_s) && sigma_s >= 0.0)) {
    throw InputError("jitter", std::to_string(sigma_s) + " s", "a time >= 0 s");
  }
  std::vector<double> moved = pulse_times;
  if (sigma_s == 0.0) return moved;
  std::mt19937_64 engine(splitmix64(seed));
  for (std::size_t k = 0; k < moved.size(); k += 2) {
    const double r = std::sqrt(-2.0 * std::log(uniform_open(engine)));
    const double phase = 2.0 * pi * uniform_open(engine);
    moved[k] += sigma_s * r * std::cos(phase);
    if (k + 1 < moved.size()) moved[k + 1] += sigma_s * r * std::sin(phase);
  }
  return moved;
}

}  // namespace gearimpact::signals
