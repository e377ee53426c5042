// Meissner's equation (docs/steady-state.md section 3.4): the closed-form monodromy against Eigen's
// matrix exponential and against direct RK4 integration of Hill's equation over one period;
// Liouville's determinant; the first instability band against the perturbation result
// Omega ~ 2 (1 +- eps/4) and the damped threshold eps > 4 zeta; the multipliers found by shooting
// on the integrated period map.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/steady/meissner.hpp"
#include "gearimpact/steady/shooting.hpp"
#include "reference_oscillator.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

// The state map over one mesh period by RK4 on Hill's equation, the two-pair piece first, each
// piece with its own constant stiffness and `steps` steps.
Eigen::Vector2d integrate_hill(const RectangularStiffness& s, double zeta, double omega,
                               const Eigen::Vector2d& start, int steps) {
  verify::OscillatorParameters p;
  p.damping_ratio = zeta;
  p.frequency_ratio = omega;
  p.restoring = verify::Restoring::linear;
  const double period = 2.0 * std::numbers::pi / omega;
  const double switch_time = s.two_pair_fraction * period;
  p.stiffness_ratio = s.two_pair_ratio;
  const Eigen::Vector2d middle =
      verify::ReferenceOscillator(p).integrate(start, 0.0, switch_time, steps);
  p.stiffness_ratio = s.one_pair_ratio;
  return verify::ReferenceOscillator(p).integrate(middle, switch_time, period, steps);
}

Eigen::Matrix2d integrated_monodromy(const RectangularStiffness& s, double zeta, double omega,
                                     int steps) {
  Eigen::Matrix2d m;
  m.col(0) = integrate_hill(s, zeta, omega, Eigen::Vector2d(1.0, 0.0), steps);
  m.col(1) = integrate_hill(s, zeta, omega, Eigen::Vector2d(0.0, 1.0), steps);
  return m;
}

double max_entry_difference(const Eigen::Matrix2d& a, const Eigen::Matrix2d& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(a.cwiseAbs().maxCoeff(), 1e-300);
}

// Mean 1 and a step of `jump` between the two-pair and the one-pair stiffness: kappa_d =
// 1 + (1 - d) jump, kappa_s = 1 - d jump. Its fundamental Fourier component has the amplitude
// eps = 2 jump sin(pi d) / pi.
RectangularStiffness unit_mean(double d, double jump) {
  return {1.0 + (1.0 - d) * jump, 1.0 - d * jump, d};
}

double fundamental_amplitude(double d, double jump) {
  return 2.0 * jump * std::sin(std::numbers::pi * d) / std::numbers::pi;
}

}  // namespace

TEST_CASE("the 2x2 exponential in closed form against Eigen's matrix exponential") {
  struct Case {
    double kappa, zeta, t;
  };
  // Underdamped, overdamped and critically damped pieces.
  for (const Case c :
       {Case{1.3, 0.05, 2.7}, Case{0.8, 2.0, 1.9}, Case{1.0, 1.0, 3.1}, Case{1.0, 0.0, 10.0}}) {
    CAPTURE(c.kappa);
    CAPTURE(c.zeta);
    Eigen::Matrix2d a;
    a << 0.0, 1.0, -c.kappa, -2.0 * c.zeta;
    const Eigen::Matrix2d eigen_exp = (a * c.t).exp();
    const Eigen::Matrix2d closed = hill_transition_matrix(c.kappa, c.zeta, c.t);
    // Eigen's Pade approximant with scaling and squaring is accurate to a few ulps times the
    // number of squarings (< 10 here): 1e-13 relative to the largest entry.
    CHECK(max_entry_difference(closed, eigen_exp) <= 1e-13);
  }
}

TEST_CASE("Meissner monodromy against direct integration of Hill's equation over one period") {
  const RectangularStiffness paper_like{1.2, 0.85, 0.69};
  for (const double zeta : {0.0, 0.05}) {
    for (const double omega : {0.7, 1.9, 3.0}) {
      CAPTURE(zeta);
      CAPTURE(omega);
      const Eigen::Matrix2d closed = meissner_monodromy(paper_like, zeta, omega);
      const Eigen::Matrix2d integrated = integrated_monodromy(paper_like, zeta, omega, 4000);
      const double difference = max_entry_difference(closed, integrated);
      MESSAGE("zeta " << zeta << ", Omega " << omega << ": max entry difference " << difference);
      // RK4, 4000 steps a piece of at most 9 time units: h^4 < 3e-11, times an error constant
      // below 1; 1e-8 leaves a margin of orders of magnitude over that.
      CHECK(difference <= 1e-8);

      // Liouville: det M = exp(trace A T) = e^{-2 zeta T}, whatever kappa does.
      const double period = 2.0 * std::numbers::pi / omega;
      CHECK(relative_difference(closed.determinant(), std::exp(-2.0 * zeta * period)) <= 1e-13);
    }
  }
}

TEST_CASE("undamped first band near Omega = 2 (1 +- eps/4), to second order in eps") {
  const double d = 0.69;
  double previous_error = 0.0;
  for (const double eps : {0.02, 0.01}) {
    CAPTURE(eps);
    const double jump = eps * std::numbers::pi / (2.0 * std::sin(std::numbers::pi * d));
    const RectangularStiffness s = unit_mean(d, jump);
    REQUIRE(relative_difference(fundamental_amplitude(d, jump), eps) <= 1e-15);

    const std::vector<FrequencyBand> bands = meissner_unstable_bands(s, 0.0, 1.9, 2.1, 2001);
    REQUIRE(bands.size() == 1);
    const double lower = 2.0 * (1.0 - eps / 4.0);
    const double upper = 2.0 * (1.0 + eps / 4.0);
    const double error =
        std::max(std::fabs(bands[0].lower - lower), std::fabs(bands[0].upper - upper));
    MESSAGE("eps " << eps << ": band [" << bands[0].lower << ", " << bands[0].upper
                   << "], first order [" << lower << ", " << upper << "], error " << error);
    // First-order perturbation theory: the edges are right to O(eps^2) (for the Mathieu
    // equation the next term shifts both edges by about eps^2 / 8 in Omega^2 / 4).
    CHECK(error <= eps * eps);
    // The error is second order: it falls by about 4 when eps halves.
    if (previous_error > 0.0) {
      CHECK(previous_error / error > 3.0);
      CHECK(previous_error / error < 5.0);
    }
    previous_error = error;

    // Inside the band the spectral radius exceeds 1; outside it is 1 (undamped).
    const double centre = 0.5 * (bands[0].lower + bands[0].upper);
    CHECK(spectral_radius(meissner_monodromy(s, 0.0, centre)) > 1.0);
    CHECK(meissner_instability_margin(s, 0.0, centre) > 0.0);
    CHECK(meissner_instability_margin(s, 0.0, bands[0].lower - 1e-3) < 0.0);
    CHECK(meissner_instability_margin(s, 0.0, bands[0].upper + 1e-3) < 0.0);
  }
}

TEST_CASE("damped first band exists only for eps > 4 zeta") {
  const double d = 0.69;
  const double eps = 0.02;
  const double jump = eps * std::numbers::pi / (2.0 * std::sin(std::numbers::pi * d));
  const RectangularStiffness s = unit_mean(d, jump);
  // The threshold is 4 zeta to first order; its correction is O(eps) relative, 2 % here, so
  // +-10 % of it is decisive.
  CHECK(meissner_unstable_bands(s, 0.9 * eps / 4.0, 1.9, 2.1, 2001).size() == 1);
  CHECK(meissner_unstable_bands(s, 1.1 * eps / 4.0, 1.9, 2.1, 2001).empty());
}

TEST_CASE("unstable bands of a paper-like stiffness: spectral radius of the integrated monodromy") {
  // kappa_d / kappa_s = 1.3 / 0.8 for 69 % of the period: bands near Omega = 2 sqrt(mean) / n.
  const RectangularStiffness s{1.3, 0.8, 0.69};
  const double zeta = 0.005;
  const double mean =
      s.two_pair_fraction * s.two_pair_ratio + (1.0 - s.two_pair_fraction) * s.one_pair_ratio;
  const std::vector<FrequencyBand> bands = meissner_unstable_bands(s, zeta, 0.3, 3.0, 5401);
  REQUIRE(bands.size() >= 3);
  for (std::size_t i = 0; i < bands.size(); ++i) {
    const FrequencyBand& b = bands[i];
    const double centre = 0.5 * (b.lower + b.upper);
    const int n = static_cast<int>(std::lround(2.0 * std::sqrt(mean) / centre));
    MESSAGE("band [" << b.lower << ", " << b.upper << "], order n = " << n);
    // A large modulation (kappa varies by +-25 %) moves the bands by O(eps^2) ~ 5 %: 8 % is a
    // loose placement check; the radius checks below are the exact ones.
    CHECK(std::fabs(centre - 2.0 * std::sqrt(mean) / n) <= 0.08 * centre);
    // Direct integration (RK4, 4000 steps a piece) agrees: the spectral radius exceeds 1 at the
    // band's centre, and is below 1 halfway to the next band.
    CHECK(spectral_radius(integrated_monodromy(s, zeta, centre, 4000)) > 1.0);
    if (i + 1 < bands.size()) {
      const double gap = 0.5 * (b.upper + bands[i + 1].lower);
      CHECK(spectral_radius(integrated_monodromy(s, zeta, gap, 4000)) < 1.0);
    }
  }
}

TEST_CASE("shooting's Floquet multipliers of Hill's equation against the Meissner monodromy") {
  const RectangularStiffness s{1.3, 0.8, 0.69};
  const double zeta = 0.02;
  // Inside the first band (real multipliers, one outside the unit circle) and between bands
  // (a complex pair).
  for (const double omega : {2.14, 1.6}) {
    CAPTURE(omega);
    const PeriodMap map = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
      return integrate_hill(s, zeta, omega, Eigen::Vector2d(y[0], y[1]), 4000);
    };
    ShootingSettings settings;
    settings.tolerance = 1e-14;
    const PeriodicOrbit orbit = find_periodic_orbit(map, Eigen::Vector2d(0.3, -0.2), settings);
    // The fixed point of a linear homogeneous map is 0: the residual bound 1e-14 divided by
    // |1 - multiplier| >= 0.5 here.
    CHECK(orbit.fixed_point.cwiseAbs().maxCoeff() <= 1e-13);
    const Eigen::EigenSolver<Eigen::Matrix2d> exact(meissner_monodromy(s, zeta, omega));
    std::vector<std::complex<double>> expected{exact.eigenvalues()[0], exact.eigenvalues()[1]};
    std::sort(expected.begin(), expected.end(),
              [](auto a, auto b) { return std::abs(a) > std::abs(b); });
    for (std::size_t i = 0; i < 2; ++i) {
      const double difference =
          std::abs(orbit.floquet_multipliers[static_cast<Eigen::Index>(i)] - expected[i]);
      MESSAGE("multiplier " << i << ": " << orbit.floquet_multipliers[static_cast<Eigen::Index>(i)]
                            << " vs " << expected[i] << ", difference " << difference);
      // RK4's error (~1e-11) plus the central differences' rounding (~1e-10): 1e-8 leaves
      // two orders of margin.
      CHECK(difference <= 1e-8);
    }
  }
}

TEST_CASE("Meissner inputs out of range are refused") {
  CHECK_THROWS_AS((void)meissner_monodromy({1.2, 0.8, 1.5}, 0.0, 1.0), InputError);
  CHECK_THROWS_AS((void)meissner_monodromy({0.0, 0.8, 0.5}, 0.0, 1.0), InputError);
  CHECK_THROWS_AS((void)meissner_monodromy({1.2, 0.8, 0.5}, -0.1, 1.0), InputError);
  CHECK_THROWS_AS((void)meissner_monodromy({1.2, 0.8, 0.5}, 0.0, 0.0), InputError);
  CHECK_THROWS_AS((void)meissner_unstable_bands({1.2, 0.8, 0.5}, 0.0, 2.0, 1.0, 10), InputError);
  CHECK_THROWS_AS((void)meissner_unstable_bands({1.2, 0.8, 0.5}, 0.0, 1.0, 2.0, 1), InputError);
}
