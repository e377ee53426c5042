// The folds of the gear model's single-sided-impact branch, found by pseudo-arclength
// continuation on its own period map (steady/period_map.hpp), against where slow up and down
// sweeps of the gear model jump (steady/sweep.hpp), and against the folds of the reference
// oscillator (reference_oscillator.hpp) with the same dimensionless parameters.
//
// The case is the clearance oscillator built from the paper's pair (steady_cases.hpp): constant
// mesh stiffness k, viscous damper zeta, no Hertzian damping or friction, T1 = T_m + dT1
// sin(w t + phase), balanced. With x = s / B and tau = w_n t its relative coordinate obeys
//   x'' + 2 zeta x' + f(x) = F_m + F_a sin(Omega tau + phase),
// the reference oscillator's equation for the phase pi/2 used here. zeta = 0.1, F_m = 0.1, F_a =
// 0.05 (r = 0.5): losing contact softens the mesh, the single-sided-impact branch bends towards low
// Omega and folds twice.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <iomanip>
#include <limits>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "gearimpact/steady/period_map.hpp"
#include "gearimpact/steady/shooting.hpp"
#include "gearimpact/steady/sweep.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "reference_oscillator.hpp"
#include "steady_cases.hpp"

using namespace gearimpact;

namespace {

constexpr double kDamping = 0.1;
constexpr double kMeanForce = 0.1;
constexpr double kAlternatingForce = 0.05;
// RK4 steps a forcing period in both continuations: the same grid for the two integrators.
constexpr int kStepsPerPeriod = 400;

double distance_to_one(const Eigen::VectorXcd& multipliers) {
  double d = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < multipliers.size(); ++i) {
    d = std::min(d, std::abs(multipliers[i] - 1.0));
  }
  return d;
}

ContinuationSettings omega_range() {
  ContinuationSettings settings;
  settings.parameter_min = 0.6;
  settings.parameter_max = 1.3;
  return settings;
}

// The branch of the gear model from the large-amplitude orbit at Omega = 1 (the only one
// there) down in Omega: unknowns (s, s') in SI, scaled by (B, B w_n); parameter Omega.
Branch gear_branch(const steady_test::ClearanceCase& cc, const StiffnessTable& table) {
  const double w_n = cc.w_rad_per_s;  // clearance_case(..., omega = 1) puts w at w_n
  const ParametrizedPeriodMap map = [&](const Eigen::VectorXd& y, double omega) -> Eigen::VectorXd {
    SimulationCase c = cc.c;
    c.torque1.angular_frequency_rad_per_s = omega * w_n;
    return GearPeriodMap(c, table, SteadySettings{}, kStepsPerPeriod)(y);
  };
  ContinuationSettings settings = omega_range();
  const double b = cc.c.gears.backlash_m;
  settings.newton.scale = Eigen::Vector2d(b, b * w_n);
  return continue_periodic_orbits(map, Eigen::Vector2d(1.1 * b, 0.0), 1.0, -1, settings);
}

Branch reference_branch() {
  verify::OscillatorParameters p;
  p.damping_ratio = kDamping;
  p.mean_force = kMeanForce;
  p.alternating_force = kAlternatingForce;
  const ParametrizedPeriodMap map = [p](const Eigen::VectorXd& y, double omega) -> Eigen::VectorXd {
    verify::OscillatorParameters q = p;
    q.frequency_ratio = omega;
    return verify::ReferenceOscillator(q).period_map(Eigen::Vector2d(y[0], y[1]), kStepsPerPeriod);
  };
  return continue_periodic_orbits(map, Eigen::Vector2d(1.1, 0.0), 1.0, -1, omega_range());
}

// Where a sweep jumps: the indices i (in the order the sweep visits its points) across which,
// from point i - 1 to point i, the steady half peak-to-peak of s changes by more than 0.1 B:
// the branches differ by about 0.2 B there, and along a branch it changes by less than 0.02 B
// a grid step.
std::vector<std::size_t> jumps(const std::vector<SweepPointResult>& sweep, double b) {
  std::vector<std::size_t> found;
  for (std::size_t i = 1; i < sweep.size(); ++i) {
    REQUIRE(sweep[i].point.converged);
    REQUIRE(sweep[i - 1].point.converged);
    if (std::fabs(*sweep[i].point.dte_amplitude_m - *sweep[i - 1].point.dte_amplitude_m) >
        0.1 * b) {
      found.push_back(i);
    }
  }
  return found;
}

}  // namespace

TEST_CASE(
    "gear model: the folds found by shooting are where slow sweeps jump, and the reference "
    "oscillator's") {
  steady_test::ClearanceCase cc =
      steady_test::clearance_case(kMeanForce, kAlternatingForce, kDamping, 1.0);
  // sin(w t + pi/2) = cos(w t): the reference oscillator's forcing, so that the two period maps
  // share their Poincare section and their fixed points are the same x = s / B.
  cc.c.torque1.phase_rad = 0.5 * std::numbers::pi;
  const auto table = std::make_shared<const StiffnessTable>(cc.c.gears, cc.c.model.stiffness);
  const double w_n = cc.w_rad_per_s;
  const double b = cc.c.gears.backlash_m;

  const Branch branch = gear_branch(cc, *table);
  REQUIRE(branch.folds.size() == 2);
  const Fold& lower_fold = branch.folds[0];
  const Fold& upper_fold = branch.folds[1];
  CHECK(lower_fold.parameter < upper_fold.parameter);
  MESSAGE(std::setprecision(12) << "gear model folds at Omega = " << lower_fold.parameter << " and "
                                << upper_fold.parameter << ", w = " << lower_fold.parameter * w_n
                                << " and " << upper_fold.parameter * w_n << " rad/s (w_n = " << w_n
                                << " rad/s)");
  // Smooth folds: a multiplier at +1 to the accuracy of central differences on the RK4 map.
  CHECK(distance_to_one(lower_fold.floquet_multipliers) <= 1e-7);
  CHECK(distance_to_one(upper_fold.floquet_multipliers) <= 1e-7);
  // Stable outside the folds, a saddle between them.
  for (std::size_t i = 0; i < branch.points.size(); ++i) {
    CAPTURE(branch.points[i].parameter);
    const bool middle = i > lower_fold.after_point && i <= upper_fold.after_point;
    CHECK((std::abs(branch.points[i].floquet_multipliers[0]) > 1.0) == middle);
  }

  // The same equation by the reference oscillator, on the same number of RK4 steps a period.
  const Branch reference = reference_branch();
  REQUIRE(reference.folds.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    const double difference = std::fabs(branch.folds[i].parameter - reference.folds[i].parameter);
    MESSAGE(std::setprecision(12) << "fold " << i << ": gear model " << branch.folds[i].parameter
                                  << ", reference oscillator " << reference.folds[i].parameter
                                  << ", difference " << difference);
    // One equation, one discretisation: both are RK4 on the same 400 steps a period with the
    // step cut where the contact begins or ends (located to rounding, by events in the gear
    // model and by bisection in the reference) and the same Poincare section. What may differ
    // is rounding (the gear model's s is Rb1 theta1 - Rb2 theta2) and where the fold's regula
    // falsi stops (|t_Omega| <= 1e-9 on either). 1e-9 is below the discretisation error
    // itself (the folds move by 2e-9 from 400 to 800 steps, test_shooting.cpp), so another
    // mass, stiffness or force scaling in the gear model would fail it.
    CHECK(difference <= 1e-9);
    const Eigen::VectorXd& gear_state = branch.folds[i].state;
    const Eigen::VectorXd& reference_state = reference.folds[i].state;
    const double state_difference =
        std::max(std::fabs(gear_state[0] / b - reference_state[0]),
                 std::fabs(gear_state[1] / (b * w_n) - reference_state[1]));
    MESSAGE(std::setprecision(12) << "fold " << i << " at x = " << gear_state[0] / b
                                  << ", x' = " << gear_state[1] / (b * w_n)
                                  << "; differs from the reference's by " << state_difference);
    // Along the branch the state moves as the square root of the parameter near a fold, so a
    // fold's state is fixed less tightly than its parameter: sqrt(1e-11), the parameters'
    // difference, is 3e-6; 1e-5 in units of B and B w_n.
    CHECK(state_difference <= 1e-5);
  }

  // Slow sweeps of the gear model over a grid of step 0.01 in Omega, each point from the
  // previous one's steady state.
  const std::vector<double> grid =
      sweep_grid(0.6003 * w_n, 0.9003 * w_n, 31, "from", "to", "points");
  const TableFor table_for = [&](const SimulationCase&) { return table; };
  const std::vector<SweepPointResult> up =
      sweep_line(cc.c, table_for, "torque1.angular_frequency", grid, SweepDirection::up, 0, {}, {});
  const std::vector<SweepPointResult> down = sweep_line(
      cc.c, table_for, "torque1.angular_frequency", grid, SweepDirection::down, 0, {}, {});
  const std::vector<std::size_t> up_jumps = jumps(up, b);
  const std::vector<std::size_t> down_jumps = jumps(down, b);
  REQUIRE(up_jumps.size() == 1);
  REQUIRE(down_jumps.size() == 1);
  const SweepPointResult& up_before = up[up_jumps[0] - 1];
  const SweepPointResult& up_after = up[up_jumps[0]];
  const SweepPointResult& down_before = down[down_jumps[0] - 1];
  const SweepPointResult& down_after = down[down_jumps[0]];
  MESSAGE(std::setprecision(6) << "up sweep jumps between Omega " << up_before.value_si / w_n
                               << " and " << up_after.value_si / w_n << ", down sweep between "
                               << down_before.value_si / w_n << " and "
                               << down_after.value_si / w_n);
  // Up, the small-amplitude branch ends at the upper fold; down, the large one at the lower.
  CHECK(up_before.value_si < upper_fold.parameter * w_n);
  CHECK(upper_fold.parameter * w_n < up_after.value_si);
  CHECK(down_after.value_si < lower_fold.parameter * w_n);
  CHECK(lower_fold.parameter * w_n < down_before.value_si);
  // Up jumps up, down jumps down.
  CHECK(*up_after.point.dte_amplitude_m > *up_before.point.dte_amplitude_m);
  CHECK(*down_after.point.dte_amplitude_m < *down_before.point.dte_amplitude_m);
}

TEST_CASE("the planar model's branch on stiff bearings folds where the torsional one does") {
  // The case above on bearings of k_b = 1e11 N/m per direction (the planar model, its map of 10
  // coordinates): a short branch from the large-amplitude orbit near Omega = 0.70 down through
  // the lower fold, against the fold of the torsional model in the bearings' quasi-static limit.
  steady_test::ClearanceCase cc =
      steady_test::clearance_case(kMeanForce, kAlternatingForce, kDamping, 1.0);
  cc.c.torque1.phase_rad = 0.5 * std::numbers::pi;
  const auto table = std::make_shared<const StiffnessTable>(cc.c.gears, cc.c.model.stiffness);
  const double w_n = cc.w_rad_per_s;
  const double k = cc.stiffness_n_per_m;
  const double kb = 1e11;
  const SimulationCase planar = steady_test::on_bearings(cc.c, kb);

  // Quasi-statically the bearings' springs are in series with the mesh's along the line of
  // action: k' = k / (1 + eps), eps = k (1/k_b1 + 1/k_b2). The damper the contact sees changes
  // too: (k + i w c) in series with the bearings is k' + i w c (1 - 2 eps) at first order for
  // the drive line's half, and the coast line's half (docs/vibration.md) sees the centres'
  // motion along its own line, by at most as much: c' within c (1 +- 2 eps). The references are
  // the torsional model with k' and c (1 - 2 eps), and with k' and c (1 + 2 eps) (zeta' = zeta
  // (1 -+ 2 eps) sqrt(1 + eps)), whose folds bracket the planar one; Omega stays w / w_n of the
  // rigid pair.
  const double eps = 2.0 * k / kb;
  std::vector<Fold> references;
  for (const double sign : {-1.0, 1.0}) {
    steady_test::ClearanceCase series = cc;
    series.c.model.constant_mesh_stiffness_n_per_m = k / (1.0 + eps);
    series.c.model.mesh_damping_ratio = kDamping * (1.0 + sign * 2.0 * eps) * std::sqrt(1.0 + eps);
    const Branch torsional = gear_branch(series, *table);
    REQUIRE(torsional.folds.size() == 2);
    references.push_back(torsional.folds[0]);
  }
  const Branch rigid = gear_branch(cc, *table);
  REQUIRE(rigid.folds.size() == 2);
  // The start: the rigid branch's last point above Omega = 0.70 before its lower fold.
  std::size_t start = 0;
  for (std::size_t i = 0; i <= rigid.folds[0].after_point; ++i) {
    if (rigid.points[i].parameter >= 0.70) start = i;
  }
  const BranchPoint& from = rigid.points[start];

  ContinuationSettings settings;
  settings.parameter_min = 0.6;
  settings.parameter_max = 0.75;
  settings.max_points = 12;
  // One step count for every Omega, the one that resolves the bearings at the slowest
  // forcing's period (a shorter period then has a shorter step), so that the map keeps its
  // discretisation along the branch. 32 RK4 steps a period of the stiffest bearing mode: the
  // mesh's contact period then has over 100, its phase error a period below 1e-6.
  SteadySettings steady;
  steady.steps_per_contact_period = 32.0;
  SimulationCase slowest = planar;
  slowest.torque1.angular_frequency_rad_per_s = settings.parameter_min * w_n;
  const long long steps = GearPeriodMap(slowest, *table, steady).steps_per_period();
  const ParametrizedPeriodMap map = [&](const Eigen::VectorXd& y, double omega) -> Eigen::VectorXd {
    SimulationCase c = planar;
    c.torque1.angular_frequency_rad_per_s = omega * w_n;
    return GearPeriodMap(c, *table, SteadySettings{}, steps)(y);
  };
  settings.newton.scale = GearPeriodMap(planar, *table).scale();
  Eigen::VectorXd guess = Eigen::VectorXd::Zero(10);
  guess.head(2) = from.state;
  const Branch branch = continue_periodic_orbits(map, guess, from.parameter, -1, settings);
  MESSAGE(std::setprecision(12) << "planar branch from Omega " << from.parameter << ": "
                                << branch.points.size() << " points, " << branch.folds.size()
                                << " folds; " << branch.end_reason << "; " << steps
                                << " steps a period");
  REQUIRE(branch.folds.size() == 1);
  const Fold& fold = branch.folds[0];
  // What the quasi-static series spring leaves out: the centres' inertia, relative (w / w_b)^2
  // of the bearings' share eps (w_b = sqrt(k_b / m2), the heavier wheel's, the lower), and the
  // second order eps^2; twice their sum, as a margin on the bracket.
  const PlanarMounting mounting = planar_mounting(planar);
  const double w_b = std::sqrt(kb / mounting.mass_kg[1]);
  const double lower = std::min(references[0].parameter, references[1].parameter);
  const double upper = std::max(references[0].parameter, references[1].parameter);
  const double w = lower * w_n;
  const double margin = 2.0 * (eps * (w / w_b) * (w / w_b) + eps * eps) * lower;
  MESSAGE(std::setprecision(12) << "lower fold: planar " << fold.parameter
                                << "; torsional with the series stiffness between " << lower
                                << " and " << upper << " (margin " << margin
                                << "); on rigid bearings " << rigid.folds[0].parameter);
  CHECK(fold.parameter >= lower - margin);
  CHECK(fold.parameter <= upper + margin);
  // (The bearings move the fold by 0.3 % from the rigid pair's, less than the bracket's width of
  // 0.8 %, which the damper's uncertain share sets: the test bounds the planar fold, it does not
  // resolve the bearings' effect; test_gear_floquet's rigid-limit case does.)
  // A smooth fold: one multiplier at +1 to the accuracy of central differences; the bearings'
  // modes are far inside the unit circle.
  MESSAGE("the planar fold's multipliers: nearest +1 by "
          << distance_to_one(fold.floquet_multipliers) << ", largest modulus "
          << std::abs(fold.floquet_multipliers[0]));
  CHECK(distance_to_one(fold.floquet_multipliers) <= 1e-6);
}
