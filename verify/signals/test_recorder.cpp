// The recorder's parts (signals/recorder.hpp): the seeded streams, noise at a stated SNR (its
// realised value within its sampling error), the sections' gains on tones against |H(i 2 pi f)|,
// the ADC's clipping and quantisation.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/signals/recorder.hpp"

using namespace gearimpact;
using namespace gearimpact::signals;

namespace {

std::vector<double> tone(std::size_t n, double f, double rate, double amplitude = 1.0) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = amplitude * std::cos(2.0 * pi * f * static_cast<double>(i) / rate + 0.3);
  }
  return x;
}

double sinc(double x) {
  return std::sin(pi * x) / (pi * x);
}

}  // namespace

TEST_CASE("a stream is a function of its seed and id: equal seeds equal draws, others differ") {
  RandomStream a(7, 1);
  RandomStream b(7, 1);
  RandomStream c(7, 2);
  RandomStream d(8, 1);
  int same_c = 0;
  int same_d = 0;
  for (int i = 0; i < 1000; ++i) {
    const double x = a.gaussian();
    REQUIRE(x == b.gaussian());
    same_c += x == c.gaussian();
    same_d += x == d.gaussian();
  }
  CHECK(same_c == 0);
  CHECK(same_d == 0);
}

TEST_CASE("noise: the realised SNR scatters as (10 / ln 10) sqrt(2 / N) about its target") {
  constexpr std::size_t n = 20000;
  constexpr int records = 400;
  constexpr double snr = 30.0;
  // The scatter of 10 log10 of a mean of N squared Gaussians over its expectation.
  const double deviation = 10.0 / std::log(10.0) * std::sqrt(2.0 / static_cast<double>(n));
  double sum = 0.0;
  double worst = 0.0;
  std::vector<double> first_noise;
  for (int r = 0; r < records; ++r) {
    std::vector<double> x = tone(n, 123.4, 20000.0);
    const NoiseResult result = add_noise(x, snr, 1000 + r, false);
    sum += result.realised_snr_db;
    worst = std::max(worst, std::fabs(result.realised_snr_db - snr));
  }
  const double mean = sum / records;
  // The mean of independent records within 3 of its own deviations; each within 5.
  CHECK(std::fabs(mean - snr) <= 3.0 * deviation / std::sqrt(static_cast<double>(records)));
  CHECK(worst <= 5.0 * deviation);
  // And not all exact: the scatter is there (a test that could not fail otherwise).
  CHECK(worst > 0.5 * deviation);
  // Exact mode: the target, to rounding.
  std::vector<double> x = tone(n, 123.4, 20000.0);
  CHECK(std::fabs(add_noise(x, snr, 5, true).realised_snr_db - snr) <= 1e-12);
}

TEST_CASE("noise of two seeds is uncorrelated: |rho| < 4 / sqrt(N)") {
  constexpr std::size_t n = 20000;
  std::vector<double> zero(n, 0.0);
  zero[0] = 1.0;  // a signal of non-zero power
  std::vector<double> a = zero;
  std::vector<double> b = zero;
  add_noise(a, 0.0, 1, false);
  add_noise(b, 0.0, 2, false);
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    ab += a[i] * b[i];
    aa += a[i] * a[i];
    bb += b[i] * b[i];
  }
  CHECK(std::fabs(ab / std::sqrt(aa * bb)) < 4.0 / std::sqrt(static_cast<double>(n)));
}

TEST_CASE("sections on tones: the gain is |H(i 2 pi f)| within the held input's (2 pi f T)^2") {
  const double rate = 160000.0;
  const std::vector<SecondOrderSection> cases{
      accelerometer(30000.0, 0.05), path_mode(3000.0, 0.02, 1.0), path_mode(9000.0, 0.1, 0.5)};
  for (const SecondOrderSection& s : cases) {
    for (const double f : {500.0, 2800.0, 8000.0}) {
      CAPTURE(s.frequency_hz);
      CAPTURE(f);
      // Input: a unit tone's samples, each held over the interval ending at it (as an interval
      // average is): a zero-order hold, of transfer sinc(f T) e^{-i pi f T}.
      const std::size_t n = 64000;
      const std::vector<double> x = tone(n, f, rate);
      const std::vector<double> y = filter_sections(x, rate, {s}, "accelerometer");
      // The amplitude over the last half (transients of >= 0.02 damping long gone: 0.2 s).
      double re = 0.0, im = 0.0;
      for (std::size_t i = n / 2; i < n; ++i) {
        const double phase = 2.0 * pi * f * static_cast<double>(i) / rate;
        re += y[i] * std::cos(phase);
        im += y[i] * std::sin(phase);
      }
      const double amplitude = 2.0 * std::hypot(re, im) / static_cast<double>(n / 2);
      const double expected = gain_at(s, f) * sinc(f / rate);
      // What the held input's images (near k rate +- f) fold back onto the line: measured 0.24
      // (f T)^2. Without the hold's sinc the error would be 1 - sinc(f T) = 1.6 (f T)^2.
      const double bar = std::pow(f / rate, 2.0);
      CHECK(std::fabs(amplitude - expected) / expected <= bar);
    }
  }
}

TEST_CASE("a path's draws: seeded, within their ranges, gains summing to 1") {
  const auto a = draw_path(11, 3, 1000.0, 8000.0, 0.01, 0.05);
  const auto b = draw_path(11, 3, 1000.0, 8000.0, 0.01, 0.05);
  const auto c = draw_path(12, 3, 1000.0, 8000.0, 0.01, 0.05);
  double sum = 0.0;
  for (std::size_t r = 0; r < a.size(); ++r) {
    CHECK(a[r].frequency_hz == b[r].frequency_hz);
    CHECK(a[r].frequency_hz != c[r].frequency_hz);
    CHECK(a[r].frequency_hz >= 1000.0);
    CHECK(a[r].frequency_hz <= 8000.0);
    CHECK(a[r].damping_ratio >= 0.01);
    CHECK(a[r].damping_ratio <= 0.05);
    sum += gain_at(a[r], 0.0);  // each term's gain at 0 Hz is its g
  }
  CHECK(std::fabs(sum - 1.0) <= 1e-15);
  CHECK_THROWS_AS(draw_path(1, 0, 1000.0, 8000.0, 0.01, 0.05), InputError);
  CHECK_THROWS_AS(filter_sections({1.0, 2.0}, 20000.0, {accelerometer(6000.0, 0.05)}, "resonance"),
                  InputError);
}

TEST_CASE("the ADC: clips at its range (counted), its rounding error RMS LSB / sqrt 12") {
  std::vector<double> x = tone(100000, 37.7, 20000.0, 1.5);
  const AdcResult result = adc(x, 1.0, 12);
  // |1.5 cos| > 1 on a fraction (2/pi) acos(1/1.5) = 0.5353 of the samples.
  const double fraction = 2.0 / pi * std::acos(1.0 / 1.5);
  CHECK(std::fabs(static_cast<double>(result.clipped) / 100000.0 - fraction) <= 0.005);
  CHECK(result.lsb == 2.0 / 4096.0);
  // Below the range: rounding only, its error uniform over one LSB.
  std::vector<double> y = tone(100000, 37.7, 20000.0, 0.9);
  const std::vector<double> before = y;
  CHECK(adc(y, 1.0, 12).clipped == 0);
  double power = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) power += (y[i] - before[i]) * (y[i] - before[i]);
  const double rms = std::sqrt(power / static_cast<double>(y.size()));
  CHECK(std::fabs(rms / (result.lsb / std::sqrt(12.0)) - 1.0) <= 0.02);
  CHECK_THROWS_AS(adc(y, 0.0, 12), InputError);
  CHECK_THROWS_AS(adc(y, 1.0, 33), InputError);
}
