// The recorder's anti-alias decimator (signals/decimate.hpp): Kaiser's design meets the band
// edges and the attenuation it was asked for, measured on its own frequency response; a tone in
// the passband comes out at its response and phase (no delay), a tone that would fold is
// attenuated to the stopband's level; a ratio that is not an integer resamples as well.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/signals/decimate.hpp"

using namespace gearimpact;
using namespace gearimpact::signals;

namespace {

UniformRecord tone(double seconds, double rate, double f, double phase, double start = 0.0) {
  UniformRecord r;
  r.start_s = start;
  r.rate_hz = rate;
  const auto n = static_cast<std::size_t>(seconds * rate);
  r.values.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    r.values[i] = std::cos(2.0 * pi * f * (start + static_cast<double>(i) / rate) + phase);
  }
  return r;
}

double largest(const std::vector<double>& x) {
  double m = 0.0;
  for (const double v : x) m = std::max(m, std::fabs(v));
  return m;
}

}  // namespace

TEST_CASE("Kaiser's design: ripple and stopband within 10^(-A/20) at the asked edges") {
  for (const double a : {60.0, 100.0}) {
    for (const double ratio : {4.0, 8.0}) {
      CAPTURE(a);
      CAPTURE(ratio);
      const double rate = 160e3;
      const KaiserLowPass f = kaiser_low_pass(rate, 0.4 * rate / ratio, 0.5 * rate / ratio, a);
      // Oppenheim & Schafer (7.63): N = (A - 8) / (2.285 dw), 513 at A = 100, ratio 8 (raised to
      // the even 514).
      if (a == 100.0 && ratio == 8.0) CHECK(f.order == 514);
      const double delta = std::pow(10.0, -a / 20.0);
      double pass_error = 0.0;
      double stop_level = 0.0;
      for (int i = 0; i <= 4000; ++i) {
        const double fr = 0.5 * rate * i / 4000.0;
        const double h = response(f, fr);
        if (fr <= f.pass_hz) pass_error = std::max(pass_error, std::fabs(h - 1.0));
        if (fr >= f.stop_hz) stop_level = std::max(stop_level, std::fabs(h));
      }
      MESSAGE("A " << a << " dB, ratio " << ratio << ": order " << f.order << ", passband error "
                   << pass_error << ", stopband " << stop_level << " (delta " << delta << ")");
      // Kaiser's formulas are fits to his designs; the ripple they give is within about 1 dB
      // of the asked delta (Oppenheim & Schafer, 7.6.1), here checked at that 1 dB.
      CHECK(pass_error <= delta * std::pow(10.0, 1.0 / 20.0));
      CHECK(stop_level <= delta * std::pow(10.0, 1.0 / 20.0));
    }
  }
}

TEST_CASE("a passband tone comes out at the filter's response, on the coarser instants") {
  const double rate = 160e3;
  const double out_rate = 20e3;
  for (const double f_hz : {680.0, 3111.0, 7900.0}) {
    const UniformRecord in = tone(0.1, rate, f_hz, 0.4, 0.25);
    const UniformRecord out = anti_alias_resample(in, out_rate);
    const KaiserLowPass f = kaiser_low_pass(rate, 0.4 * out_rate, 0.5 * out_rate, 100.0);
    const double gain = response(f, f_hz);
    // The output starts on an input sample, half the span in (514 / 2 = 257 inputs rounded up
    // to a whole output interval of 8: 264).
    CHECK(out.start_s == doctest::Approx(0.25 + 264.0 / rate).epsilon(1e-14));
    REQUIRE(out.values.size() > 1500);
    double worst = 0.0;
    for (std::size_t n = 0; n < out.values.size(); ++n) {
      const double t = out.start_s + static_cast<double>(n) / out_rate;
      worst =
          std::max(worst, std::fabs(out.values[n] - gain * std::cos(2.0 * pi * f_hz * t + 0.4)));
    }
    // A symmetric filter adds no delay: the tone's own phase at t_n, to the rounding of the
    // 514-term sums (about 1e-13) and of cos's argument 2 pi f t (t up to 0.35 s: 1.7e4 rad at
    // 7.9 kHz, whose rounding, summed over the taps, gives up to a few 1e-12).
    CHECK(worst <= 1e-13 + 1e-15 * 2.0 * pi * f_hz * 0.35);
    CHECK(std::fabs(gain - 1.0) <= 1e-5);
  }
}

TEST_CASE("a tone that would fold onto the band is attenuated to the stopband's level") {
  const double rate = 160e3;
  const double out_rate = 20e3;
  // 10 kHz is the coarser grid's Nyquist frequency; each of these folds below 10 kHz.
  for (const double f_hz : {10.0e3, 12.3e3, 19.3e3, 39.7e3, 79.0e3}) {
    CAPTURE(f_hz);
    const UniformRecord out = anti_alias_resample(tone(0.05, rate, f_hz, 0.1), out_rate);
    CHECK(largest(out.values) <= 1.2e-5);  // 100 dB, within Kaiser's 1 dB
  }
}

TEST_CASE("a ratio that is not an integer: the kernel at fractional offsets, the same bands") {
  const double rate = 150e3;
  const double out_rate = 21.76e3;
  const UniformRecord pass = anti_alias_resample(tone(0.05, rate, 2000.0, 1.0), out_rate);
  double worst = 0.0;
  for (std::size_t n = 0; n < pass.values.size(); ++n) {
    const double t = pass.start_s + static_cast<double>(n) / out_rate;
    worst = std::max(worst, std::fabs(pass.values[n] - std::cos(2.0 * pi * 2000.0 * t + 1.0)));
  }
  // The passband's ripple at any offset: the window's, 1e-5, within 1 dB.
  CHECK(worst <= 1.2e-5);
  const UniformRecord stop = anti_alias_resample(tone(0.05, rate, 15000.0, 1.0), out_rate);
  CHECK(largest(stop.values) <= 1.2e-5);
}

TEST_CASE("the decimator refuses a rate it cannot reach and a record shorter than its span") {
  const UniformRecord r = tone(0.01, 80e3, 100.0, 0.0);
  CHECK_THROWS_WITH_AS(anti_alias_resample(r, 80e3), doctest::Contains("output rate"), InputError);
  CHECK_THROWS_WITH_AS(anti_alias_resample(r, 1e3), doctest::Contains("record"), InputError);
  CHECK_THROWS_WITH_AS(kaiser_low_pass(80e3, 10e3, 50e3, 100.0), doctest::Contains("stopband edge"),
                       InputError);
  CHECK_THROWS_WITH_AS(kaiser_low_pass(80e3, 10e3, 20e3, 10.0), doctest::Contains("attenuation"),
                       InputError);
}
