// The periodicity verdict on constructed Poincare sequences whose answer is known by
// construction: periodic orbits of periods 1 to 8 with noise below the tolerance, chaotic and
// quasi-periodic sequences, slowly converging ones, and records too short to judge.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/steady/periodicity.hpp"

using namespace gearimpact;

namespace {

// Deterministic noise in [-1, 1] (a linear congruential generator), so that the suite is
// reproducible.
class Noise {
 public:
  double next() {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state_ >> 11) / static_cast<double>(1ULL << 52) * 2.0 - 1.0;
  }

 private:
  unsigned long long state_ = 12345;
};

// A sequence in two components with the scales (B, B w_n) = (5e-5, 0.3): the i-th orbit point
// is placed at distinct positions of order the scales, plus noise of `noise` scaled units.
std::vector<Eigen::VectorXd> periodic_sequence(int period, std::size_t count, double noise) {
  Noise n;
  std::vector<Eigen::VectorXd> s;
  for (std::size_t k = 0; k < count; ++k) {
    const double phase = static_cast<double>(k % static_cast<std::size_t>(period));
    Eigen::VectorXd v(2);
    v << 5e-5 * (1.0 + 0.37 * phase + noise * n.next()),
        0.3 * (-0.5 + 0.21 * phase * phase + noise * n.next());
    s.push_back(v);
  }
  return s;
}

const Eigen::VectorXd scale = (Eigen::VectorXd(2) << 5e-5, 0.3).finished();

}  // namespace

TEST_CASE("periods 1 to 8 are found, the minimal one, with noise below the tolerance") {
  for (int period = 1; period <= 8; ++period) {
    CAPTURE(period);
    // Noise of 2e-7 scaled units on each sample: differences up to 4e-7 < tolerance 1e-6.
    const auto samples = periodic_sequence(period, 200, 2e-7);
    const PeriodicityResult r = classify_poincare_samples(samples, scale);
    CHECK(r.verdict == PeriodicityVerdict::periodic);
    CHECK(r.period == period);
    CHECK(r.residual <= 1e-6);
    CHECK(r.window_samples.size() == 32);
    CHECK(r.window_samples.back() == samples.back());
    CHECK(r.explanation.find("period " + std::to_string(period)) != std::string::npos);
  }
}

TEST_CASE("noise above the tolerance is not a period") {
  // Noise of 1e-5 scaled units, ten times the tolerance, and stationary: aperiodic.
  const auto samples = periodic_sequence(2, 300, 1e-5);
  const PeriodicityResult r = classify_poincare_samples(samples, scale);
  CHECK(r.verdict == PeriodicityVerdict::aperiodic);
  CHECK(r.closest_period == 2);
  CHECK(r.residual > 1e-6);
}

TEST_CASE("orbit points closer than the tolerance are one point") {
  // A period-2 orbit whose two points differ by 5e-7 scaled units: period 1 at tolerance 1e-6,
  // period 2 at tolerance 1e-7.
  std::vector<Eigen::VectorXd> samples;
  for (int k = 0; k < 100; ++k) {
    samples.push_back((Eigen::VectorXd(2) << 5e-5 * (1.0 + (k % 2) * 5e-7), 0.1).finished());
  }
  CHECK(classify_poincare_samples(samples, scale).period == 1);
  PeriodicitySettings tight;
  tight.tolerance = 1e-7;
  CHECK(classify_poincare_samples(samples, scale, tight).period == 2);
}

TEST_CASE("a transient that has died out: the converged orbit is reported") {
  // x_n = orbit_n + 0.5^n: after 60 periods the transient is 1e-18, far below tolerance.
  auto samples = periodic_sequence(4, 80, 0.0);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    samples[k] += std::pow(0.5, static_cast<double>(k)) * scale;
  }
  const PeriodicityResult r = classify_poincare_samples(samples, scale);
  CHECK(r.verdict == PeriodicityVerdict::periodic);
  CHECK(r.period == 4);
}

TEST_CASE("a slowly converging sequence is not converged, and its rate is measured") {
  // Period 2 approached as 0.97^n: after 200 periods the period-2 residual is still
  // 0.97^198 (1 - 0.97^2) ~ 1.5e-4 scaled units.
  const double rho = 0.97;
  auto samples = periodic_sequence(2, 200, 0.0);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    samples[k] += std::pow(rho, static_cast<double>(k)) * scale;
  }
  const PeriodicityResult r = classify_poincare_samples(samples, scale);
  CHECK(r.verdict == PeriodicityVerdict::not_converged);
  // The period-1 residual does not decrease (the orbit's two points stay apart); the first
  // candidate whose residual does is period 2.
  CHECK(r.closest_period == 2);
  // The residual is exactly geometric, so the fitted rate is rho up to rounding of the logs.
  CHECK(std::fabs(r.contraction_per_period - rho) <= 1e-9);
  CHECK(r.explanation.find("not converged") != std::string::npos);
}

TEST_CASE("a sequence leaving an unstable orbit is not converged, and its growth is measured") {
  // A period-1 orbit with a multiplier 1.03: a perturbation of 1e-6 scaled units grows as
  // 1.03^n, so the period-1 residual 1e-6 * 1.03^n * 0.03 starts below the tolerance 1e-6 and is
  // about 1e-5 after 200 periods: not periodic, and not aperiodic either (it is not stationary
  // but rising steadily), still moving.
  const double mu = 1.03;
  auto samples = periodic_sequence(1, 200, 0.0);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    samples[k] += 1e-6 * std::pow(mu, static_cast<double>(k)) * scale;
  }
  const PeriodicityResult r = classify_poincare_samples(samples, scale);
  CHECK(r.verdict == PeriodicityVerdict::not_converged);
  CHECK(r.closest_period == 1);
  // Exactly geometric again: the fitted factor is mu up to rounding of the logs.
  CHECK(std::fabs(r.contraction_per_period - mu) <= 1e-9);
  CHECK(r.explanation.find("grows") != std::string::npos);
}

TEST_CASE("a growing flip below the tolerance is not called period 2") {
  // A period-1 orbit with a multiplier -1.03: samples x* + 2e-9 (-1.03)^n. After 200 of them the
  // period-1 residual 2e-9 * 1.03^n * 2.03 is about 1.5e-6 (> tolerance 1e-6), the period-2
  // one 2e-9 * 1.03^n * (1.03^2 - 1) only 4.4e-8: within the tolerance, yet the samples are
  // leaving the orbit, not repeating with period 2.
  const double mu = -1.03;
  auto samples = periodic_sequence(1, 200, 0.0);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    samples[k] += 2e-9 * std::pow(mu, static_cast<double>(k)) * scale;
  }
  const PeriodicityResult r = classify_poincare_samples(samples, scale);
  CHECK(r.verdict == PeriodicityVerdict::not_converged);
  CHECK(r.closest_period == 2);
  // The period-2 residual grows as mu^2 every two samples: |mu| per sample.
  CHECK(std::fabs(r.contraction_per_period - std::fabs(mu)) <= 1e-9);
}

TEST_CASE("chaotic and quasi-periodic sequences are aperiodic") {
  SUBCASE("the logistic map at r = 4, as (x_n, x_n+1)") {
    std::vector<Eigen::VectorXd> samples;
    double x = 0.1234;
    for (int k = 0; k < 400; ++k) {
      const double next = 4.0 * x * (1.0 - x);
      samples.push_back((Eigen::VectorXd(2) << x, next).finished());
      x = next;
    }
    const Eigen::VectorXd unit = Eigen::VectorXd::Ones(2);
    const PeriodicityResult r = classify_poincare_samples(samples, unit);
    CHECK(r.verdict == PeriodicityVerdict::aperiodic);
    CHECK(r.period == 0);
    CHECK(r.window_samples.size() == 32);
  }
  SUBCASE("a rotation by the golden angle") {
    const double angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
    std::vector<Eigen::VectorXd> samples;
    for (int k = 0; k < 400; ++k) {
      samples.push_back(
          (Eigen::VectorXd(2) << std::cos(angle * k), std::sin(angle * k)).finished());
    }
    const PeriodicityResult r = classify_poincare_samples(samples, Eigen::VectorXd::Ones(2));
    CHECK(r.verdict == PeriodicityVerdict::aperiodic);
  }
}

TEST_CASE("a record too short to judge is not converged") {
  const auto samples = periodic_sequence(1, 39, 0.0);
  const PeriodicityResult r = classify_poincare_samples(samples, scale);
  CHECK(r.verdict == PeriodicityVerdict::not_converged);
  CHECK(r.period == 0);
  CHECK(std::isinf(r.residual));
  CHECK(r.window_samples.size() == 32);
  // One more sample (window 32 + max_period 8 = 40) is enough.
  CHECK(classify_poincare_samples(periodic_sequence(1, 40, 0.0), scale).period == 1);
}

TEST_CASE("bad samples and settings are refused with their name") {
  auto samples = periodic_sequence(1, 50, 0.0);
  samples[7][1] = std::nan("");
  try {
    (void)classify_poincare_samples(samples, scale);
    FAIL("a NaN sample was accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "poincare sample 7");
  }
  samples[7] = Eigen::VectorXd::Zero(3);
  CHECK_THROWS_AS((void)classify_poincare_samples(samples, scale), InputError);
  samples = periodic_sequence(1, 50, 0.0);
  CHECK_THROWS_AS((void)classify_poincare_samples(samples, Eigen::Vector2d(1.0, 0.0)), InputError);
  PeriodicitySettings bad;
  bad.window = 10;  // < 2 max_period
  CHECK_THROWS_AS((void)classify_poincare_samples(samples, scale, bad), InputError);
  bad = {};
  bad.tolerance = 0.0;
  CHECK_THROWS_AS((void)classify_poincare_samples(samples, scale, bad), InputError);
}
