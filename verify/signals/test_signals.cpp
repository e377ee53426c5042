// The signal layer against closed forms: the amplitude of a windowed sine,
// Parseval, an order recovered through a non-uniform angle, the noise of a
// time-synchronous average, and every condition indicator of a signal whose
// moments follow from the averages of cos^n over whole periods:
// mean cos^2 = 1/2, cos^4 = 3/8, cos^6 = 5/16, cos^8 = 35/128. Over N equal
// samples of a whole number k of periods these hold exactly (to rounding)
// while n k < N, which every signal below keeps.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/signals/fft.hpp"
#include "gearimpact/signals/indicators.hpp"
#include "gearimpact/signals/resample.hpp"
#include "gearimpact/signals/spectrum.hpp"
#include "gearimpact/signals/tsa.hpp"
#include "relative.hpp"

using namespace gearimpact;
using namespace gearimpact::signals;
using gearimpact::verify::relative_difference;
using std::numbers::pi;

namespace {

// Sums of N terms of order 1 round to about N eps; 1e-11 leaves a margin for N up to 4096.
constexpr double kRounding = 1e-11;

std::vector<double> sampled(std::size_t n, const auto& f) {
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = f(static_cast<double>(i));
  return x;
}

// One revolution of P samples at angles 2 pi j / P.
std::vector<double> revolution(std::size_t p, const auto& f) {
  return sampled(p, [&](double j) { return f(2.0 * pi * j / static_cast<double>(p)); });
}

}  // namespace

TEST_CASE("a sine at a bin reads its amplitude with either window, the mean reads itself") {
  const std::size_t n = 1024;
  const double rate = 2048.0;  // Hz: bins 2 Hz apart
  const double amplitude = 2.5;
  const double mean = 0.7;
  const auto x = sampled(
      n, [&](double i) { return mean + amplitude * std::cos(2.0 * pi * 200.0 * i / rate + 0.3); });
  for (const Window w : {Window::rectangular, Window::hann}) {
    CAPTURE(to_string(w));
    const Spectrum s = amplitude_spectrum(x, rate, w);
    REQUIRE(s.frequency.size() == n / 2 + 1);
    CHECK(s.frequency[100] == 200.0);
    CHECK(relative_difference(s.amplitude[100], amplitude) < kRounding);
    CHECK(relative_difference(s.amplitude[0], mean) < kRounding);
    // The periodic Hann window's coherent gain is 1/2 exactly.
    CHECK(relative_difference(s.coherent_gain, w == Window::hann ? 0.5 : 1.0) < kRounding);
    // Rectangular: nothing elsewhere. Hann: the neighbours get half (its
    // kernel is N/2 at 0 and -N/4 at +-1 bin), nothing beyond.
    CHECK(std::abs(s.amplitude[101] - (w == Window::hann ? amplitude / 2 : 0.0)) <
          kRounding * amplitude);
    CHECK(s.amplitude[102] < kRounding * amplitude);
  }
}

TEST_CASE("a sine half-way between bins reads the stated scalloping loss") {
  // At a distance d = 1/2 bin the nearest bin reads A sin(pi d) / (pi d) with
  // the rectangular window (2/pi = 0.637 A) and A sin(pi d) / (pi d (1 - d^2))
  // with Hann (0.849 A), in the limit of large N. Finite N changes the
  // Dirichlet kernel by a relative (pi d / N)^2 / 6 (4e-8 at N = 4096). The
  // mirror at -f adds at most 1/(pi (2 k + d)) of the amplitude with the
  // rectangular window (1.6e-4 at k = 1000) and its cube with Hann.
  const std::size_t n = 4096;
  const double rate = 4096.0;
  const double k = 1000.0;
  const double d = 0.5;
  const auto x = sampled(n, [&](double i) { return std::cos(2.0 * pi * (k + d) * i / rate); });
  const Spectrum rect = amplitude_spectrum(x, rate, Window::rectangular);
  const Spectrum hann = amplitude_spectrum(x, rate, Window::hann);
  const double rect_expected = std::sin(pi * d) / (pi * d);
  const double hann_expected = std::sin(pi * d) / (pi * d * (1.0 - d * d));
  CHECK(relative_difference(rect.amplitude[1000], rect_expected) < 1.0 / (pi * (2 * k + d)));
  CHECK(relative_difference(rect.amplitude[1001], rect_expected) < 1.0 / (pi * (2 * k + d)));
  CHECK(relative_difference(hann.amplitude[1000], hann_expected) < 1e-6);
  CHECK(relative_difference(hann.amplitude[1001], hann_expected) < 1e-6);
}

TEST_CASE("Parseval: the mean square equals the sum of the single-sided powers") {
  // Rectangular window: mean x^2 = A_0^2 + sum_{0<k<N/2} A_k^2 / 2 + A_{N/2}^2
  // (the last term for even N only), from sum |x|^2 = (1/N) sum |X_k|^2.
  std::mt19937_64 random(20261124);
  std::uniform_real_distribution<double> uniform(-1.0, 3.0);
  for (const std::size_t n : {std::size_t{1000}, std::size_t{999}}) {
    CAPTURE(n);
    std::vector<double> x(n);
    double mean_square = 0.0;
    for (double& v : x) {
      v = uniform(random);
      mean_square += v * v / static_cast<double>(n);
    }
    const Spectrum s = amplitude_spectrum(x, 1.0, Window::rectangular);
    double power = 0.0;
    for (std::size_t k = 0; k < s.amplitude.size(); ++k) {
      const bool own_mirror = k == 0 || 2 * k == n;
      power += s.amplitude[k] * s.amplitude[k] * (own_mirror ? 1.0 : 0.5);
    }
    CHECK(relative_difference(power, mean_square) < kRounding);
  }
}

TEST_CASE("the inverse transforms undo the forward one") {
  const auto x = sampled(30, [](double i) { return std::sin(0.37 * i * i) + 0.1 * i; });
  const std::vector<double> back = inverse_real_dft(real_dft(x), x.size());
  for (std::size_t i = 0; i < x.size(); ++i) CHECK(std::abs(back[i] - x[i]) < kRounding);
}

TEST_CASE("cubic interpolation reproduces a cubic on uneven nodes") {
  const auto cubic = [](double u) { return 2.0 - u + 0.5 * u * u - 0.25 * u * u * u; };
  const std::vector<double> nodes{-1.0, -0.3, 0.1, 0.15, 0.9, 1.7, 2.0};
  std::vector<double> values;
  for (double u : nodes) values.push_back(cubic(u));
  for (double u = -1.0; u <= 2.0; u += 0.0625) {
    CHECK(std::abs(interpolate_cubic(nodes, values, u) - cubic(u)) < kRounding);
  }
  // Uniform resampling of the same cubic in time is exact too.
  const std::vector<double> out = resample_uniform(nodes, values, 4.0);
  REQUIRE(out.size() == 13);  // -1, -0.75, ..., 2
  for (std::size_t k = 0; k < out.size(); ++k) {
    CHECK(std::abs(out[k] - cubic(-1.0 + 0.25 * static_cast<double>(k))) < kRounding);
  }
}

TEST_CASE(
    "an order spectrum recovers the orders of a signal periodic in an unevenly turning angle") {
  // theta(t) = W t + e sin(v t), dtheta/dt = W + e v cos(v t) > 0; sampled at
  // uneven instants; x = cos(7 theta) + 0.3 cos(23 theta). On equal angle
  // steps over whole revolutions the orders 7 and 23 fall exactly on bins.
  // What remains is the interpolation error: for the cubic through four
  // nodes within 2 h_max of the point, |error| <= 4 h_max^4 max|x''''| / 24,
  // and the spectrum's amplitude at most doubles it.
  const double w = 2.0 * pi * 10.0;
  const double e = 0.4;
  const double v = 2.0 * pi * 3.0;
  const std::size_t samples = 40000;
  std::vector<double> angle, x;
  for (std::size_t i = 0; i < samples; ++i) {
    const double t = (static_cast<double>(i) + 0.4 * std::sin(0.7 * static_cast<double>(i))) * 5e-5;
    const double theta = w * t + e * std::sin(v * t);
    angle.push_back(theta);
    x.push_back(std::cos(7.0 * theta) + 0.3 * std::cos(23.0 * theta));
  }
  double h = 0.0;
  for (std::size_t i = 1; i < samples; ++i) h = std::max(h, angle[i] - angle[i - 1]);
  const double fourth = std::pow(7.0, 4) + 0.3 * std::pow(23.0, 4);
  const double bound = 2.0 * 4.0 * std::pow(h, 4) * fourth / 24.0;
  const std::size_t p = 128;
  const AngleSignal a = resample_on_angle(angle, x, p);
  REQUIRE(a.revolutions >= 10);
  const Spectrum s = amplitude_spectrum(a.values, static_cast<double>(p), Window::rectangular);
  const std::size_t r = a.revolutions;
  CHECK(s.frequency[7 * r] == doctest::Approx(7.0).epsilon(1e-15));
  CHECK(std::abs(s.amplitude[7 * r] - 1.0) <= bound);
  CHECK(std::abs(s.amplitude[23 * r] - 0.3) <= bound);
  for (std::size_t k = 0; k < s.amplitude.size(); ++k) {
    if (k != 7 * r && k != 23 * r) CHECK(s.amplitude[k] <= bound);
  }
  CHECK(bound < 1e-3);  // the test means something
}

TEST_CASE("a TSA recovers a periodic part from noise with an error of sigma / sqrt(N)") {
  // Gaussian noise of deviation sigma, independent between revolutions,
  // averages to sigma / sqrt(R) at each of the P angles; the RMS of the error
  // over P angles is then sigma / sqrt(R) times sqrt(chi^2_P / P), whose
  // deviation is 1 / sqrt(2 P) = 0.044 for P = 256: the bounds [0.8, 1.2]
  // sit 4.5 deviations out.
  const std::size_t p = 256;
  const std::size_t revolutions = 400;
  const double sigma = 0.5;
  const auto periodic = [](double u) { return std::sin(3.0 * u) + 0.5 * std::cos(17.0 * u); };
  std::mt19937_64 random(12345);
  std::normal_distribution<double> noise(0.0, sigma);
  AngleSignal a;
  a.samples_per_revolution = p;
  a.revolutions = revolutions;
  for (std::size_t r = 0; r < revolutions; ++r) {
    for (double value : revolution(p, periodic)) a.values.push_back(value + noise(random));
  }
  const std::vector<double> tsa = time_synchronous_average(a);
  const std::vector<double> truth = revolution(p, periodic);
  double square = 0.0;
  for (std::size_t j = 0; j < p; ++j) square += (tsa[j] - truth[j]) * (tsa[j] - truth[j]);
  const double ratio = std::sqrt(square / static_cast<double>(p)) /
                       (sigma / std::sqrt(static_cast<double>(revolutions)));
  CAPTURE(ratio);
  CHECK(ratio > 0.8);
  CHECK(ratio < 1.2);
}

TEST_CASE("a pure sine: kurtosis 3/2, crest factor sqrt 2, M6A 5/2, M8A 35/8") {
  // Normalised moments of A cos: (3/8)/(1/2)^2, (5/16)/(1/2)^3, (35/128)/(1/2)^4.
  const auto x = revolution(1024, [](double u) { return 3.0 * std::cos(5.0 * u); });
  CHECK(relative_difference(*normalised_moment(x, 4), 1.5) < kRounding);
  CHECK(relative_difference(*normalised_moment(x, 6), 2.5) < kRounding);
  CHECK(relative_difference(*normalised_moment(x, 8), 35.0 / 8.0) < kRounding);
  const Indicators i = record_indicators(x);
  CHECK(relative_difference(i.rms, 3.0 / std::sqrt(2.0)) < kRounding);
  CHECK(relative_difference(i.peak, 3.0) < kRounding);
  CHECK(relative_difference(*i.crest_factor, std::sqrt(2.0)) < kRounding);
  // A constant record has no normalised moment (0/0), not a number of rounding.
  CHECK_FALSE(normalised_moment(std::vector<double>(16, 2.0), 4).has_value());
}

TEST_CASE("Gaussian noise: kurtosis 3 within its sampling deviation") {
  // The sample kurtosis of n Gaussian values has deviation sqrt(24 / n)
  // (4.9e-3 for n = 1e6); the bound is 5 of them.
  const std::size_t n = 1000000;
  std::mt19937_64 random(4242);
  std::normal_distribution<double> normal(0.0, 2.0);
  std::vector<double> x(n);
  for (double& v : x) v = normal(random);
  const double kurtosis = *normalised_moment(x, 4);
  CAPTURE(kurtosis);
  CHECK(std::abs(kurtosis - 3.0) < 5.0 * std::sqrt(24.0 / static_cast<double>(n)));
}

TEST_CASE("pure mesh harmonics: FM0 by hand, no difference signal") {
  // f = cos(z u) + 0.25 cos(2 z u): f' = -sin(zu) (1 + cos(zu)) vanishes at zu
  // = 0 and pi, f = 1.25 and -0.75: peak-to-peak 2, both reached at samples
  // (P = 512 is a multiple of 2 z). FM0 = 2 / (1 + 0.25) = 1.6.
  const std::size_t z = 16;
  const auto tsa =
      revolution(512, [&](double u) { return std::cos(z * u) + 0.25 * std::cos(2.0 * z * u); });
  const OrderSets sets{z, 1, 1};
  const TsaParts parts = tsa_parts(tsa, sets);
  const Indicators i = gear_indicators(tsa, parts, sets);
  CHECK(relative_difference(*i.fm0, 1.6) < kRounding);
  // Nothing outside the regular orders: the difference and residual signals
  // are zero to rounding and their moments absent, the energy ratio zero.
  CHECK_FALSE(i.fm4.has_value());
  CHECK_FALSE(i.m6a.has_value());
  CHECK_FALSE(i.na4.has_value());
  CHECK(*i.energy_ratio < kRounding);
  CHECK(*i.sideband_level < kRounding);
}

TEST_CASE("a TSA of shaft, mesh, sideband and damage orders: each part and indicator") {
  // TSA = s cos u + cos z u + 0.25 cos 2 z u + b cos (z + 1) u + c cos 5 u,
  // z = 16, one shaft order, first-order sidebands. Then
  //   regular = all but c cos 5u; residual = b cos (z+1) u + c cos 5u;
  //   difference = c cos 5u: FM4 = 3/2, M6A = 5/2, M8A = 35/8;
  //   NA4 = (3/8 (b^4 + c^4) + 6 b^2 c^2 / 4) / ((b^2 + c^2) / 2)^2 (cross
  //   terms of distinct orders average to zero): 9/4 for b = c;
  //   energy ratio = (c / sqrt 2) / sqrt((s^2 + 1 + 0.0625 + b^2) / 2);
  //   sideband level = (A_15 + A_17) / std = b / sqrt((s^2 + 1.0625 + b^2 + c^2) / 2).
  const std::size_t z = 16;
  const double s = 0.4;
  const double b = 0.2;
  const double c = 0.2;
  const auto tsa = revolution(512, [&](double u) {
    return s * std::cos(u) + std::cos(z * u) + 0.25 * std::cos(2.0 * z * u) +
           b * std::cos((z + 1.0) * u) + c * std::cos(5.0 * u);
  });
  const OrderSets sets{z, 1, 1};
  const TsaParts parts = tsa_parts(tsa, sets);
  const auto difference = revolution(512, [&](double u) { return c * std::cos(5.0 * u); });
  const auto residual = revolution(
      512, [&](double u) { return b * std::cos((z + 1.0) * u) + c * std::cos(5.0 * u); });
  for (std::size_t j = 0; j < 512; ++j) {
    CHECK(std::abs(parts.difference[j] - difference[j]) < kRounding);
    CHECK(std::abs(parts.residual[j] - residual[j]) < kRounding);
    CHECK(std::abs(parts.regular[j] + difference[j] - tsa[j]) < kRounding);
  }
  CHECK(relative_difference(parts.order_amplitude[z + 1], b) < kRounding);
  const Indicators i = gear_indicators(tsa, parts, sets);
  CHECK(relative_difference(*i.fm4, 1.5) < kRounding);
  CHECK(relative_difference(*i.m6a, 2.5) < kRounding);
  CHECK(relative_difference(*i.m8a, 35.0 / 8.0) < kRounding);
  CHECK(relative_difference(*i.na4, 2.25) < kRounding);
  CHECK(relative_difference(*i.energy_ratio, c / std::sqrt(s * s + 1.0625 + b * b)) < kRounding);
  CHECK(relative_difference(*i.sideband_level,
                            b / std::sqrt((s * s + 1.0625 + b * b + c * c) / 2.0)) < kRounding);
}

TEST_CASE("NB4: the envelope of an amplitude-modulated mesh tone") {
  // (1 + m cos u) cos z u lies in the band z - 1 .. z + 1; its analytic
  // signal is (1 + m cos u) exp(i z u), whose modulus is the envelope
  // 1 + m cos u: NB4 = kurtosis of m cos u = 3/2.
  const std::size_t z = 20;
  const double m = 0.5;
  const auto tsa =
      revolution(256, [&](double u) { return (1.0 + m * std::cos(u)) * std::cos(z * u); });
  const OrderSets sets{z, 1, 1};
  const TsaParts parts = tsa_parts(tsa, sets);
  const auto envelope = revolution(256, [&](double u) { return 1.0 + m * std::cos(u); });
  for (std::size_t j = 0; j < 256; ++j) {
    CHECK(std::abs(parts.mesh_band_envelope[j] - envelope[j]) < kRounding);
  }
  CHECK(relative_difference(*gear_indicators(tsa, parts, sets).nb4, 1.5) < kRounding);
}

TEST_CASE("the low-pass keeps the tones below its cutoff and removes those above") {
  // 1000 samples at 1 kHz: bins every 1 Hz. Tones on bins 50 and 300 Hz and a
  // mean; a cutoff at 100 Hz keeps the mean and the 50 Hz tone to rounding and
  // leaves nothing of 300 Hz. A cutoff on a bin removes that bin.
  const double rate = 1000.0;
  const auto x = sampled(1000, [&](double n) {
    const double t = n / rate;
    return 0.5 + std::cos(2.0 * pi * 50.0 * t) + 0.75 * std::sin(2.0 * pi * 300.0 * t);
  });
  const std::vector<double> kept = low_pass(x, rate, 100.0);
  const std::vector<double> on_bin = low_pass(x, rate, 50.0);
  double off = 0.0;
  double bin = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = static_cast<double>(i) / rate;
    off = std::max(off, std::fabs(kept[i] - (0.5 + std::cos(2.0 * pi * 50.0 * t))));
    bin = std::max(bin, std::fabs(on_bin[i] - 0.5));
  }
  CHECK(off < kRounding);
  CHECK(bin < kRounding);
  CHECK_THROWS_WITH_AS(low_pass(x, rate, 0.0), doctest::Contains("cutoff"), InputError);
  CHECK_THROWS_WITH_AS(low_pass(x, -1.0, 10.0), doctest::Contains("sample rate"), InputError);
  CHECK_THROWS_WITH_AS(low_pass({1.0}, rate, 10.0), doctest::Contains("at least 2 samples"),
                       InputError);
  CHECK_THROWS_WITH_AS(low_pass({1.0, NAN}, rate, 10.0), doctest::Contains("signal (sample 2)"),
                       InputError);
}

TEST_CASE("the uniform grid: t0 + n / rate inside the record, the last kept against rounding") {
  const std::vector<double> grid = uniform_times(0.25, 0.5, 2000.0);
  REQUIRE(grid.size() == 501);
  for (std::size_t n = 0; n < grid.size(); ++n) {
    CHECK(grid[n] == std::min(0.25 + static_cast<double>(n) / 2000.0, 0.5));
  }
  CHECK(grid.back() == 0.5);
  CHECK_THROWS_WITH_AS(uniform_times(0.0, 1e-4, 1000.0), doctest::Contains("2 to 50000000"),
                       InputError);
  // The count is known before a grid is made: one below the bound passes, one over it is refused
  // with the estimate (a rate of 1e9 Hz over a second once ended in std::bad_alloc).
  CHECK(uniform_sample_count(0.0, 1.0, 5e7 - 1.0) == 50000000);
  CHECK_THROWS_WITH_AS(uniform_sample_count(0.0, 1.0, 5e7), doctest::Contains("5e+07 samples"),
                       InputError);
  CHECK_THROWS_WITH_AS(uniform_times(0.0, 1.0, 1e9), doctest::Contains("1e+09 samples, 8 GB"),
                       InputError);
}

TEST_CASE("bad inputs are refused naming the input and its range") {
  const auto tsa = revolution(64, [](double u) { return std::cos(u); });
  try {
    tsa_parts(tsa, OrderSets{40, 1, 1});
    FAIL("teeth above the Nyquist order accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "teeth");
    CHECK(e.allowed().find("3 to 30") != std::string::npos);
  }
  CHECK_THROWS_AS(
      tsa_parts(revolution(64, [](double u) { return std::cos(u); }), OrderSets{10, 5, 5}),
      InputError);
  try {
    resample_on_angle({0.0, 1.0, 1.0, 2.0, 8.0}, {1, 2, 3, 4, 5}, 16, "theta1_rad");
    FAIL("a non-increasing angle accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "theta1_rad (sample 3)");
  }
  try {
    resample_on_angle({0.0, 1.0, 2.0, 3.0}, {1, 2, 3, 4}, 16, "theta1_rad");
    FAIL("less than a revolution accepted");
  } catch (const InputError& e) {
    CHECK(e.allowed().find("whole revolution") != std::string::npos);
  }
  CHECK_THROWS_AS(amplitude_spectrum({1.0, 2.0}, 0.0), InputError);
  CHECK_THROWS_AS(amplitude_spectrum({1.0, std::nan("")}, 1.0), InputError);
  CHECK_THROWS_AS(parse_window("hamming", "--window"), InputError);
}

TEST_CASE("decimating a revolution keeps the orders below the new Nyquist order and no alias") {
  // cos(3u) + cos(300u) on 1024 samples, reduced to 256: order 300 lies
  // above 128 and would fold onto 300 - 256 = 44 if the samples were simply
  // taken one in four; the filter removes it and keeps cos(3u) exactly.
  const auto fine =
      revolution(1024, [](double u) { return std::cos(3.0 * u) + std::cos(300.0 * u); });
  const std::vector<double> coarse = decimate_periodic(fine, 256);
  const auto expected = revolution(256, [](double u) { return std::cos(3.0 * u); });
  REQUIRE(coarse.size() == 256);
  for (std::size_t j = 0; j < 256; ++j) CHECK(std::abs(coarse[j] - expected[j]) < kRounding);
  // What plain one-in-four sampling gives instead: the alias at order 44.
  std::vector<double> naive;
  for (std::size_t j = 0; j < 1024; j += 4) naive.push_back(fine[j]);
  const Spectrum s = amplitude_spectrum(naive, 256.0, Window::rectangular);
  CHECK(relative_difference(s.amplitude[44], 1.0) < kRounding);
  CHECK_THROWS_AS(decimate_periodic(fine, 2048), InputError);
}

TEST_CASE("order analysis: a grid as fine as the record, a TSA free of aliases") {
  // 1000 rows a revolution over 4 revolutions of a steadily advancing angle:
  // the grid is the record's own 1000 rows a revolution, whatever P.
  // x = cos(3 theta) + cos(100 theta): order 100 lies above P/2 = 32, and a
  // TSA of 64 samples taken straight from the record would show it at
  // 128 - 100 = 28. The reduced TSA keeps cos(3 theta) alone, up to the
  // interpolation's error on the fine grid: 4 h^4 max|x''''| / 24 with
  // h = 2 pi / 1000 and max|x''''| = 100^4 + 3^4, below 3e-2; its share in
  // the TSA after the low-pass is far less, and 1e-3 is asserted.
  std::vector<double> angle, x;
  for (int i = 0; i <= 4000; ++i) {
    const double theta = 2.0 * pi * i / 1000.0;
    angle.push_back(theta);
    x.push_back(std::cos(3.0 * theta) + std::cos(100.0 * theta));
  }
  const OrderAnalysis a = analyse_orders(angle, x, 64, Window::rectangular, std::nullopt);
  CHECK(a.grid == 1000);
  CHECK(a.revolutions == 4);
  REQUIRE(a.tsa.size() == 64);
  const auto expected = revolution(64, [](double u) { return std::cos(3.0 * u); });
  for (std::size_t j = 0; j < 64; ++j) CHECK(std::abs(a.tsa[j] - expected[j]) < 1e-3);
  // The order spectrum on the fine grid holds order 100 where it belongs.
  CHECK(std::abs(a.orders.amplitude[100 * 4] - 1.0) < 3e-2);
}
