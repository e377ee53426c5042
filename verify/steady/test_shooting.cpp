// Newton shooting, Floquet multipliers and pseudo-arclength continuation: on maps whose fixed
// points, multipliers and folds are known in closed form, and on the clearance oscillator,
// whose folds must sit where slow up and down sweeps of the reference integrator jump.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <iomanip>
#include <limits>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/steady/shooting.hpp"
#include "reference_oscillator.hpp"

using namespace gearimpact;

namespace {

double distance_to_one(const Eigen::VectorXcd& multipliers) {
  double d = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < multipliers.size(); ++i) {
    d = std::min(d, std::abs(multipliers[i] - 1.0));
  }
  return d;
}

double largest_modulus(const Eigen::VectorXcd& multipliers) {
  return std::abs(multipliers[0]);
}

}  // namespace

TEST_CASE("an affine map: fixed point and multipliers exact, in components of unlike scales") {
  // P(x) = x* + A (x - x*) with x* of the size of a backlash and of a speed.
  Eigen::Matrix2d a;
  a << 0.5, 2e-5, -3e3, 0.1;
  const Eigen::Vector2d fixed(3e-5, 0.2);
  const PeriodMap map = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    return fixed + a * (x - fixed);
  };
  ShootingSettings settings;
  settings.scale = Eigen::Vector2d(5e-5, 0.3);
  settings.tolerance = 1e-14;
  const PeriodicOrbit orbit = find_periodic_orbit(map, Eigen::Vector2d(0.0, 0.0), settings);
  // Newton on an affine map converges in one step up to rounding; a second step removes the
  // error of the finite-difference Jacobian (exact for affine maps up to rounding, ~1e-11).
  CHECK(orbit.iterations <= 3);
  CHECK(std::fabs(orbit.fixed_point[0] - fixed[0]) <= 1e-14 * 5e-5);
  CHECK(std::fabs(orbit.fixed_point[1] - fixed[1]) <= 1e-14 * 0.3);
  const Eigen::EigenSolver<Eigen::Matrix2d> exact(a);
  // A's eigenvalues are a complex pair of modulus sqrt(det A).
  const double modulus = std::sqrt(a.determinant());
  for (Eigen::Index i = 0; i < 2; ++i) {
    // Central differences of an affine map: rounding only, eps / step ~ 4e-11 relative.
    CHECK(std::fabs(std::abs(orbit.floquet_multipliers[i]) - modulus) <= 1e-9);
  }
  CHECK((std::abs(orbit.floquet_multipliers[0] - exact.eigenvalues()[0]) <= 1e-9 ||
         std::abs(orbit.floquet_multipliers[0] - exact.eigenvalues()[1]) <= 1e-9));
}

TEST_CASE("failures are reported, never returned") {
  ShootingSettings settings;
  SUBCASE("no fixed point and DP - I singular: P(x) = x + 1") {
    const PeriodMap map = [](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return x.array() + 1.0;
    };
    try {
      (void)find_periodic_orbit(map, Eigen::VectorXd::Zero(1), settings);
      FAIL("a map without a fixed point returned one");
    } catch (const ShootingError& e) {
      CHECK(std::string(e.what()).find("singular") != std::string::npos);
    }
  }
  SUBCASE("no fixed point, residual bounded below: P(x) = x + x^2 + 1") {
    const PeriodMap map = [](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return x.array() + x.array().square() + 1.0;
    };
    try {
      (void)find_periodic_orbit(map, Eigen::VectorXd::Constant(1, 2.0), settings);
      FAIL("a map without a fixed point returned one");
    } catch (const ShootingError& e) {
      CHECK(std::string(e.what()).find("residual") != std::string::npos);
    }
  }
  SUBCASE("too few iterations") {
    const PeriodMap map = [](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return x.array().cos();
    };
    settings.max_iterations = 1;
    CHECK_THROWS_AS((void)find_periodic_orbit(map, Eigen::VectorXd::Constant(1, 3.0), settings),
                    ShootingError);
  }
  SUBCASE("a map that returns NaN or the wrong size") {
    const PeriodMap nan_map = [](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return x.array() * std::nan("");
    };
    CHECK_THROWS_AS((void)find_periodic_orbit(nan_map, Eigen::VectorXd::Ones(2), settings),
                    ShootingError);
    const PeriodMap short_map = [](const Eigen::VectorXd&) -> Eigen::VectorXd {
      return Eigen::VectorXd::Zero(1);
    };
    CHECK_THROWS_AS((void)find_periodic_orbit(short_map, Eigen::VectorXd::Ones(2), settings),
                    ShootingError);
  }
  SUBCASE("settings out of range") {
    const PeriodMap map = [](const Eigen::VectorXd& x) -> Eigen::VectorXd { return 0.5 * x; };
    settings.scale = Eigen::VectorXd::Ones(3);
    CHECK_THROWS_AS((void)find_periodic_orbit(map, Eigen::VectorXd::Ones(2), settings), InputError);
    settings.scale = Eigen::VectorXd();
    settings.tolerance = -1.0;
    CHECK_THROWS_AS((void)find_periodic_orbit(map, Eigen::VectorXd::Ones(2), settings), InputError);
  }
}

TEST_CASE("continuation through the fold of P(x, l) = x + l - x^2") {
  // Fixed points x = +-sqrt(l), multiplier 1 - 2x: one fold, at l = 0, x = 0, multiplier 1.
  const ParametrizedPeriodMap map = [](const Eigen::VectorXd& x, double l) -> Eigen::VectorXd {
    return x.array() + l - x.array().square();
  };
  ContinuationSettings settings;
  settings.parameter_min = -0.5;
  settings.parameter_max = 2.0;
  settings.initial_step = 0.05;
  const Branch branch =
      continue_periodic_orbits(map, Eigen::VectorXd::Constant(1, 0.9), 1.0, -1, settings);
  REQUIRE(branch.folds.size() == 1);
  const Fold& fold = branch.folds[0];
  MESSAGE("fold at l = " << fold.parameter << ", x = " << fold.state[0]);
  // The corrector's tolerance 1e-10 on l - x^2, and the fold's stopping rule |t_l| <= 1e-9
  // (t_l = 2x / sqrt(1 + 4x^2)) on x.
  CHECK(std::fabs(fold.parameter) <= 2e-10);
  CHECK(std::fabs(fold.state[0]) <= 1e-8);
  CHECK(distance_to_one(fold.floquet_multipliers) <= 1e-8);
  // The branch turns: it goes down in l on x > 0, and back up on x < 0 until it leaves the range.
  CHECK(branch.end == BranchEnd::left_parameter_range);
  CHECK(branch.points.front().state[0] > 0.0);
  CHECK(branch.points.back().state[0] < 0.0);
  CHECK(branch.points[fold.after_point].state[0] > 0.0);
  CHECK(branch.points[fold.after_point + 1].state[0] < 0.0);
  for (const BranchPoint& p : branch.points) {
    CAPTURE(p.parameter);
    // On the branch: |l - x^2| within the corrector tolerance; multiplier 1 - 2x by central
    // differences, exact for a quadratic up to rounding.
    CHECK(std::fabs(p.parameter - p.state[0] * p.state[0]) <= 1e-10);
    CHECK(std::abs(p.floquet_multipliers[0] - (1.0 - 2.0 * p.state[0])) <= 1e-9);
    CHECK((p.tangent_parameter < 0.0) == (p.state[0] > 0.0));
  }

  settings.max_points = 5;
  const Branch short_branch =
      continue_periodic_orbits(map, Eigen::VectorXd::Constant(1, 0.9), 1.0, -1, settings);
  CHECK(short_branch.end == BranchEnd::max_points);
  CHECK(short_branch.points.size() == 5);
}

TEST_CASE("clearance oscillator: the folds found by shooting are where slow sweeps jump") {
  // Softening through separation: with zeta = 0.1, F_m = 0.1, F_a = 0.05 (r = 0.5, W = 1) the
  // single-sided-impact branch bends towards low Omega and folds twice.
  verify::OscillatorParameters p;
  p.damping_ratio = 0.1;
  p.mean_force = 0.1;
  p.alternating_force = 0.05;
  const auto branch_with = [&](int steps) {
    const ParametrizedPeriodMap map = [&, steps](const Eigen::VectorXd& y,
                                                 double omega) -> Eigen::VectorXd {
      verify::OscillatorParameters q = p;
      q.frequency_ratio = omega;
      return verify::ReferenceOscillator(q).period_map(Eigen::Vector2d(y[0], y[1]), steps);
    };
    ContinuationSettings settings;
    settings.parameter_min = 0.6;
    settings.parameter_max = 1.3;
    // Start on the only orbit at Omega = 1 (the large-amplitude one) and go down in Omega.
    return continue_periodic_orbits(map, Eigen::Vector2d(1.1, 0.0), 1.0, -1, settings);
  };
  const Branch branch = branch_with(400);
  REQUIRE(branch.folds.size() == 2);
  const Fold& lower_fold = branch.folds[0];
  const Fold& upper_fold = branch.folds[1];
  MESSAGE(std::setprecision(12) << "folds at Omega = " << lower_fold.parameter << " and "
                                << upper_fold.parameter);
  CHECK(lower_fold.parameter < upper_fold.parameter);

  // Smooth folds (saddle-nodes): a multiplier at +1, to the accuracy of central differences on
  // the RK4 map (~1e-10; the event location's bisection adds rounding of the same order).
  CHECK(distance_to_one(lower_fold.floquet_multipliers) <= 1e-7);
  CHECK(distance_to_one(upper_fold.floquet_multipliers) <= 1e-7);
  // Stable outside the folds, a saddle between them (the middle branch).
  for (std::size_t i = 0; i < branch.points.size(); ++i) {
    CAPTURE(branch.points[i].parameter);
    const bool middle = i > lower_fold.after_point && i <= upper_fold.after_point;
    CHECK((largest_modulus(branch.points[i].floquet_multipliers) > 1.0) == middle);
  }

  // The folds are converged in the integration step: 400 and 800 RK4 steps a period agree to
  // 1e-8 (RK4's fourth order: the 400-step error is about 16/15 of this difference).
  const Branch fine = branch_with(800);
  REQUIRE(fine.folds.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    MESSAGE(std::setprecision(12) << "fold " << i << ": 400 steps " << branch.folds[i].parameter
                                  << ", 800 steps " << fine.folds[i].parameter);
    CHECK(std::fabs(branch.folds[i].parameter - fine.folds[i].parameter) <= 1e-8);
  }

  // Slow sweeps over a grid of step 0.01, each point continuing from the previous one's state.
  std::vector<double> up;
  for (int i = 0; i <= 30; ++i) up.push_back(0.6003 + 0.01 * i);
  const std::vector<double> down(up.rbegin(), up.rend());
  // 300 periods a point: the slowest decay on the grid (next to a fold, multiplier ~0.9) leaves
  // a transient below 1e-13.
  const auto sweep_up = verify::slow_sweep(p, up, {1.0 + p.mean_force, 0.0}, 300, 400);
  const auto sweep_down = verify::slow_sweep(p, down, {1.0 + p.mean_force, 0.0}, 300, 400);
  // A jump: the half peak-to-peak changes by more than 0.1 between neighbours (the branches
  // differ by about 0.2 there; along a branch it changes by less than 0.02 a step).
  const auto jumps = [](const std::vector<verify::SweepPoint>& sweep) {
    std::vector<std::pair<double, double>> found;
    for (std::size_t i = 1; i < sweep.size(); ++i) {
      if (std::fabs(sweep[i].half_peak_to_peak() - sweep[i - 1].half_peak_to_peak()) > 0.1) {
        found.emplace_back(sweep[i - 1].frequency_ratio, sweep[i].frequency_ratio);
      }
    }
    return found;
  };
  const auto up_jumps = jumps(sweep_up);
  const auto down_jumps = jumps(sweep_down);
  REQUIRE(up_jumps.size() == 1);
  REQUIRE(down_jumps.size() == 1);
  MESSAGE("up sweep jumps between " << up_jumps[0].first << " and " << up_jumps[0].second
                                    << ", down sweep between " << down_jumps[0].first << " and "
                                    << down_jumps[0].second);
  // Up the small-amplitude branch ends at the upper fold; down, the large one at the lower fold.
  CHECK(up_jumps[0].first < upper_fold.parameter);
  CHECK(upper_fold.parameter < up_jumps[0].second);
  CHECK(down_jumps[0].second < lower_fold.parameter);
  CHECK(lower_fold.parameter < down_jumps[0].first);
  // Hysteresis: the two sweeps jump at different Omega, seven grid steps apart.
  CHECK(up_jumps[0].first - down_jumps[0].first > 0.05);
  // The jumps go up on the way up and down on the way down.
  const auto amplitude_at = [](const std::vector<verify::SweepPoint>& sweep, double omega) {
    for (const auto& s : sweep) {
      if (s.frequency_ratio == omega) return s.half_peak_to_peak();
    }
    return std::nan("");
  };
  CHECK(amplitude_at(sweep_up, up_jumps[0].second) > amplitude_at(sweep_up, up_jumps[0].first));
  CHECK(amplitude_at(sweep_down, down_jumps[0].second) <
        amplitude_at(sweep_down, down_jumps[0].first));
}

TEST_CASE("a predictor beyond the map's domain shortens the step instead of ending the branch") {
  // The fold map again, now undefined below l = -0.05 (as a period map refuses a negative
  // frequency). Long steps put predictors there before the fold: from (x, l) = (0.5, 0.25) a
  // step of 0.5 along the tangent, proportional to (1, 2x), lands near l = -0.1.
  int refusals = 0;
  const ParametrizedPeriodMap map = [&refusals](const Eigen::VectorXd& x,
                                                double l) -> Eigen::VectorXd {
    if (l < -0.05) {
      ++refusals;
      throw InputError("l", l, ">= -0.05");
    }
    return x.array() + l - x.array().square();
  };
  ContinuationSettings settings;
  settings.parameter_min = -0.05;
  settings.parameter_max = 2.0;
  settings.initial_step = 0.5;
  settings.max_step = 0.5;
  const Branch branch =
      continue_periodic_orbits(map, Eigen::VectorXd::Constant(1, 0.9), 1.0, -1, settings);
  MESSAGE(refusals << " evaluations refused by the map");
  // The path this test is about was taken: the map refused some corrector iterates.
  CHECK(refusals > 0);
  REQUIRE(branch.folds.size() == 1);
  // The same fold as with short steps, to the corrector's and the fold rule's tolerances.
  CHECK(std::fabs(branch.folds[0].parameter) <= 2e-10);
  CHECK(branch.end == BranchEnd::left_parameter_range);
  CHECK(branch.points.back().state[0] < 0.0);
}
