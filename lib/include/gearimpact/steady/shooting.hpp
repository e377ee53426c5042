// Periodic orbits as fixed points of a period map, and their continuation in a parameter.
//
// A period map P: R^n -> R^n takes the state at one excitation phase to the state one period
// later (the caller's integrator: the gear model, or any test system). A periodic orbit is a
// fixed point x* = P(x*); its Floquet multipliers are the eigenvalues of the Jacobian DP(x*):
// stable when all lie inside the unit circle, a fold (saddle-node, turning point) where one
// crosses +1, a period doubling where one crosses -1.
//
// Every component is measured in its own scale (the backlash for a displacement, ...): the
// residual max_i |P(x)_i - x_i| / scale_i, the finite-difference steps and the continuation's
// arclength are all in scaled units.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"

namespace gearimpact {

// A Newton iteration or a continuation that did not reach its tolerance, or a period map that
// returned something unusable. The message says which, where, and the residual reached.
class ShootingError : public Error {
 public:
  using Error::Error;
};

using PeriodMap = std::function<Eigen::VectorXd(const Eigen::VectorXd& state)>;
using ParametrizedPeriodMap =
    std::function<Eigen::VectorXd(const Eigen::VectorXd& state, double parameter)>;

// The central-difference step, relative to each component's scale: the cube root of the machine
// epsilon balances the truncation error, O(h^2), against the rounding error of the period map,
// O(eps / h), for an error of about eps^(2/3) ~ 4e-11 relative on a smooth map.
inline constexpr double default_difference_step = 6.0554544523933395e-06;

struct ShootingSettings {
  // Per-component scales; empty means 1 for every component.
  Eigen::VectorXd scale;
  // Converged when the scaled residual max_i |P(x)_i - x_i| / scale_i <= tolerance.
  double tolerance = 1e-10;
  int max_iterations = 40;
  // The damped Newton step is halved until the scaled residual decreases, down to this factor.
  double min_damping = 1.0 / 1024.0;
  // Central differences with step h_i = difference_step * max(scale_i, |x_i|).
  double difference_step = default_difference_step;
};

// DP(x) by central differences, 2n evaluations of the map. Throws ShootingError when the map
// returns a vector of another size or with non-finite components.
Eigen::MatrixXd period_map_jacobian(const PeriodMap& map, const Eigen::VectorXd& state,
                                    const Eigen::VectorXd& scale, double difference_step);

// Eigenvalues of the Jacobian of the period map, by decreasing modulus.
Eigen::VectorXcd floquet_multipliers(const Eigen::MatrixXd& jacobian);

struct PeriodicOrbit {
  Eigen::VectorXd fixed_point;
  // DP at the fixed point, recomputed there after convergence.
  Eigen::MatrixXd jacobian;
  Eigen::VectorXcd floquet_multipliers;
  // The scaled residual reached (<= tolerance).
  double residual = 0.0;
  int iterations = 0;
  std::size_t map_evaluations = 0;
};

// Damped Newton on F(x) = P(x) - x from `guess`: solve (DP - I) dx = -F, take the largest of
// dx, dx/2, dx/4, ... (down to min_damping) that lowers the scaled residual. Throws
// ShootingError when the residual cannot be lowered, when DP - I is singular to the accuracy of
// the difference Jacobian (smallest singular value of the scaled DP - I below
// 1e-8 max(1, |DP|): a multiplier at 1, at a fold or on a family of orbits), after
// max_iterations, or for an unusable map value; throws
// InputError for settings out of range or a scale of the wrong size.
PeriodicOrbit find_periodic_orbit(const PeriodMap& map, const Eigen::VectorXd& guess,
                                  const ShootingSettings& settings = {});

// Continuation of the fixed point of P(., parameter) by pseudo-arclength (Keller), in the scaled
// unknowns z = (x / scale, parameter / parameter_scale):
//   predictor  z + h t, t the unit tangent (null vector of [DP - I, dP/dparameter]) oriented
//              along the previous one;
//   corrector  Newton on {P(x) - x = 0, t . (z - z_predicted) = 0};
//   step       h grows by 1.5 after a corrector that converged in 3 iterations or fewer, and is
//              halved after one that did not converge, moved farther than 2 h from the
//              prediction, or reached a point where the map throws (a parameter or state the
//              map refuses, e.g. beyond a fold); only SimulationStopped ends the continuation.
// Pseudo-arclength rather than stepping the parameter: at a fold the branch turns back, so a
// fixed parameter step has no solution beyond it (and DP - I is singular at it), whereas the
// arclength parametrisation passes through and on to the other side. A fold is where the
// parameter component of the tangent changes sign; it is then located by regula falsi (Illinois)
// on that component along the arclength, and a smooth fold has a multiplier at +1 there
// (det(DP - I) changes sign with it). A corner of the branch (a grazing contact, where the map is
// not smooth) turns the branch too and is reported the same way; its multipliers are then not
// near 1.
struct ContinuationSettings {
  double parameter_min = 0.0;
  double parameter_max = 0.0;
  // Scale of the parameter in the arclength and its finite-difference step.
  double parameter_scale = 1.0;
  // Arclength steps, scaled units.
  double initial_step = 1e-2;
  double min_step = 1e-7;
  double max_step = 1e-1;
  std::size_t max_points = 2000;
  int corrector_max_iterations = 8;
  // scale, tolerance, difference step; its max_iterations and min_damping apply to the
  // shooting of the first point.
  ShootingSettings newton;
};

struct BranchPoint {
  Eigen::VectorXd state;
  double parameter = 0.0;
  Eigen::VectorXcd floquet_multipliers;
  // d(parameter / parameter_scale) / ds along the unit tangent: > 0 while the branch runs
  // towards larger parameter values.
  double tangent_parameter = 0.0;
};

struct Fold {
  Eigen::VectorXd state;
  double parameter = 0.0;
  Eigen::VectorXcd floquet_multipliers;
  // The fold lies between points[after_point] and points[after_point + 1].
  std::size_t after_point = 0;
};

enum class BranchEnd { left_parameter_range, max_points, step_too_small };

struct Branch {
  std::vector<BranchPoint> points;
  std::vector<Fold> folds;
  BranchEnd end = BranchEnd::max_points;
  // Why the branch ends, with the last parameter value and step.
  std::string end_reason;
};

// Traces the branch through the fixed point found by shooting from `guess` at
// `start_parameter`, first towards larger parameter values when direction > 0, smaller when < 0,
// until it leaves [parameter_min, parameter_max], has max_points points, or the step falls below
// min_step (a corner it cannot turn, or the end of the branch) - the end and its reason are
// reported, every point returned is converged. Throws ShootingError when the first point cannot
// be found, a fold cannot be located, or the tangent is not unique (a branch point, where
// [DP - I, dP/dparameter] loses rank); InputError for settings out of range.
Branch continue_periodic_orbits(const ParametrizedPeriodMap& map, const Eigen::VectorXd& guess,
                                double start_parameter, int direction,
                                const ContinuationSettings& settings);

}  // namespace gearimpact
