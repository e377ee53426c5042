#include "gearimpact/steady/shooting.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

Eigen::VectorXd checked_value(const Eigen::VectorXd& value, Eigen::Index size, const char* where) {
  if (value.size() != size) {
    throw ShootingError(std::string(where) + ": the period map returned " +
                        std::to_string(value.size()) + " components for a state of " +
                        std::to_string(size));
  }
  if (!value.allFinite()) {
    throw ShootingError(std::string(where) + ": the period map returned a non-finite state");
  }
  return value;
}

Eigen::VectorXd resolved_scale(const ShootingSettings& settings, Eigen::Index size) {
  if (settings.scale.size() == 0) return Eigen::VectorXd::Ones(size);
  if (settings.scale.size() != size) {
    throw InputError("scale", std::to_string(settings.scale.size()) + " components",
                     std::to_string(size) + " components, one per state component");
  }
  for (Eigen::Index i = 0; i < size; ++i) {
    if (!std::isfinite(settings.scale[i]) || settings.scale[i] <= 0.0) {
      throw InputError("scale[" + std::to_string(i) + "]", settings.scale[i], "a finite value > 0");
    }
  }
  return settings.scale;
}

void validate(const ShootingSettings& settings) {
  if (!std::isfinite(settings.tolerance) || settings.tolerance <= 0.0) {
    throw InputError("tolerance", settings.tolerance, "a finite value > 0 (scaled residual)");
  }
  if (settings.max_iterations < 1) {
    throw InputError("max_iterations", static_cast<double>(settings.max_iterations), ">= 1");
  }
  if (!(settings.min_damping > 0.0 && settings.min_damping <= 1.0)) {
    throw InputError("min_damping", settings.min_damping, "0 < min_damping <= 1");
  }
  if (!(settings.difference_step > 0.0 && settings.difference_step < 1.0)) {
    throw InputError("difference_step", settings.difference_step,
                     "0 < difference_step < 1 (relative to each scale)");
  }
}

double scaled_norm(const Eigen::VectorXd& v, const Eigen::VectorXd& scale) {
  return (v.cwiseAbs().array() / scale.array()).maxCoeff();
}

std::string format_vector(const Eigen::VectorXd& v) {
  std::string s = "(";
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i > 0) s += ", ";
    s += format_number(v[i]);
  }
  return s + ")";
}

// The continuation's scaled problem: z = (x / scale, parameter / parameter_scale) and
// G(z) = (P(x, parameter) - x) / scale.
class ScaledProblem {
 public:
  ScaledProblem(const ParametrizedPeriodMap& map, Eigen::VectorXd scale, double parameter_scale,
                double difference_step)
      : map_(map),
        scale_(std::move(scale)),
        parameter_scale_(parameter_scale),
        step_(difference_step),
        n_(scale_.size()) {}

  Eigen::Index size() const { return n_; }

  Eigen::VectorXd to_z(const Eigen::VectorXd& x, double parameter) const {
    Eigen::VectorXd z(n_ + 1);
    z.head(n_) = x.array() / scale_.array();
    z[n_] = parameter / parameter_scale_;
    return z;
  }
  Eigen::VectorXd state(const Eigen::VectorXd& z) const {
    return z.head(n_).array() * scale_.array();
  }
  double parameter(const Eigen::VectorXd& z) const { return z[n_] * parameter_scale_; }

  Eigen::VectorXd residual(const Eigen::VectorXd& z) const {
    const Eigen::VectorXd x = state(z);
    const Eigen::VectorXd p = checked_value(map_(x, parameter(z)), n_, "continuation");
    return (p - x).array() / scale_.array();
  }

  // dG/dz, n x (n + 1), by central differences with step h_j = step * max(1, |z_j|).
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& z) const {
    Eigen::MatrixXd j(n_, n_ + 1);
    for (Eigen::Index c = 0; c <= n_; ++c) {
      const double h = step_ * std::max(1.0, std::fabs(z[c]));
      Eigen::VectorXd plus = z;
      Eigen::VectorXd minus = z;
      plus[c] += h;
      minus[c] -= h;
      j.col(c) = (residual(plus) - residual(minus)) / (plus[c] - minus[c]);
    }
    return j;
  }

 private:
  const ParametrizedPeriodMap& map_;
  Eigen::VectorXd scale_;
  double parameter_scale_;
  double step_;
  Eigen::Index n_;
};

// The unit null vector of dG/dz oriented along `previous`: the solution of the bordered system
// [dG/dz; previous^T] t = [0; 1], normalised.
Eigen::VectorXd tangent(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& previous) {
  const Eigen::Index n = jacobian.rows();
  Eigen::MatrixXd bordered(n + 1, n + 1);
  bordered.topRows(n) = jacobian;
  bordered.row(n) = previous.transpose();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
  rhs[n] = 1.0;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(bordered);
  if (!lu.isInvertible()) {
    throw ShootingError(
        "continuation: the tangent is not unique (the Jacobian [DP - I, dP/dparameter] has "
        "rank < n: a branch point)");
  }
  const Eigen::VectorXd t = lu.solve(rhs);
  return t / t.norm();
}

Eigen::VectorXcd multipliers_from(const Eigen::MatrixXd& jacobian) {
  const Eigen::Index n = jacobian.rows();
  return floquet_multipliers(jacobian.leftCols(n) + Eigen::MatrixXd::Identity(n, n));
}

struct Corrected {
  bool converged = false;
  Eigen::VectorXd z;
  int iterations = 0;
  double residual = 0.0;
  // Why the period map could not be evaluated at an iterate; empty when it always could.
  std::string map_failure;
};

// Newton on {G(z) = 0, t . (z - predicted) = 0} from c.z.
void newton_iterations(const ScaledProblem& problem, const Eigen::VectorXd& predicted,
                       const Eigen::VectorXd& t, int max_iterations, double tolerance,
                       Corrected& c) {
  const Eigen::Index n = problem.size();
  for (int k = 0;; ++k) {
    const Eigen::VectorXd g = problem.residual(c.z);
    c.residual = g.cwiseAbs().maxCoeff();
    c.iterations = k;
    if (c.residual <= tolerance) {
      c.converged = true;
      return;
    }
    if (k == max_iterations) return;
    Eigen::MatrixXd h(n + 1, n + 1);
    h.topRows(n) = problem.jacobian(c.z);
    h.row(n) = t.transpose();
    Eigen::VectorXd rhs(n + 1);
    rhs.head(n) = -g;
    rhs[n] = -t.dot(c.z - predicted);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(h);
    if (!lu.isInvertible()) return;
    const Eigen::VectorXd dz = lu.solve(rhs);
    if (!dz.allFinite()) return;
    c.z += dz;
  }
}

// The corrector: newton_iterations from the predicted point. A predictor or a Newton iterate can
// land where the period map is not defined (beyond a fold, a negative frequency; a state the model
// refuses): that is a corrector that did not converge, answered by a shorter step, not the end of
// the continuation. Only a stop request passes through.
Corrected correct(const ScaledProblem& problem, const Eigen::VectorXd& predicted,
                  const Eigen::VectorXd& t, int max_iterations, double tolerance) {
  Corrected c;
  c.z = predicted;
  try {
    newton_iterations(problem, predicted, t, max_iterations, tolerance, c);
  } catch (const SimulationStopped&) {
    throw;
  } catch (const std::exception& e) {
    c.converged = false;
    c.map_failure = e.what();
  }
  return c;
}

BranchPoint make_point(const ScaledProblem& problem, const Eigen::VectorXd& z,
                       const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& t) {
  BranchPoint p;
  p.state = problem.state(z);
  p.parameter = problem.parameter(z);
  p.floquet_multipliers = multipliers_from(jacobian);
  p.tangent_parameter = t[problem.size()];
  return p;
}

// The fold between z (tangent t) and the point the corrector reaches from z + step t, where the
// parameter component of the tangent changes sign: regula falsi (Illinois) on that component as
// a function of the predictor step sigma in (0, step).
Fold locate_fold(const ScaledProblem& problem, const Eigen::VectorXd& z, const Eigen::VectorXd& t,
                 double step, double end_tangent_parameter, const ContinuationSettings& settings) {
  const Eigen::Index n = problem.size();
  struct Sample {
    double sigma;
    double g;
  };
  Sample a{0.0, t[n]};
  Sample b{step, end_tangent_parameter};
  int retained_side = 0;
  Eigen::VectorXd z_fold = z;
  Eigen::MatrixXd j_fold;
  for (int i = 0; i < 100; ++i) {
    const double sigma = b.sigma - b.g * (b.sigma - a.sigma) / (b.g - a.g);
    const Corrected c = correct(problem, z + sigma * t, t, settings.corrector_max_iterations,
                                settings.newton.tolerance);
    if (!c.converged) {
      throw ShootingError(
          "continuation: the corrector failed at " +
          format_number(problem.parameter(z + sigma * t)) + " while locating a fold (residual " +
          format_number(c.residual) +
          (c.map_failure.empty() ? std::string() : "; the period map failed: " + c.map_failure) +
          ")");
    }
    z_fold = c.z;
    j_fold = problem.jacobian(c.z);
    const double g = tangent(j_fold, t)[n];
    if (std::fabs(g) <= 1e-9 || std::fabs(b.sigma - a.sigma) <= 1e-10 * step) {
      Fold f;
      f.state = problem.state(z_fold);
      f.parameter = problem.parameter(z_fold);
      f.floquet_multipliers = multipliers_from(j_fold);
      return f;
    }
    // Keep the bracket: the new point replaces the end whose g has its sign; Illinois halves
    // the other end's g when the same end is retained twice in a row.
    if ((g > 0.0) == (b.g > 0.0)) {
      b = {sigma, g};
      if (retained_side == -1) a.g *= 0.5;
      retained_side = -1;
    } else {
      a = {sigma, g};
      if (retained_side == 1) b.g *= 0.5;
      retained_side = 1;
    }
  }
  throw ShootingError("continuation: a fold near parameter " +
                      format_number(problem.parameter(z_fold)) +
                      " was not located in 100 regula falsi steps");
}

}  // namespace

Eigen::MatrixXd period_map_jacobian(const PeriodMap& map, const Eigen::VectorXd& state,
                                    const Eigen::VectorXd& scale, double difference_step) {
  const Eigen::Index n = state.size();
  Eigen::MatrixXd j(n, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    const double h = difference_step * std::max(scale[c], std::fabs(state[c]));
    Eigen::VectorXd plus = state;
    Eigen::VectorXd minus = state;
    plus[c] += h;
    minus[c] -= h;
    j.col(c) =
        (checked_value(map(plus), n, "jacobian") - checked_value(map(minus), n, "jacobian")) /
        (plus[c] - minus[c]);
  }
  return j;
}

Eigen::VectorXcd floquet_multipliers(const Eigen::MatrixXd& jacobian) {
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(jacobian, false);
  if (solver.info() != Eigen::Success) {
    throw ShootingError("floquet multipliers: the eigenvalue iteration did not converge");
  }
  Eigen::VectorXcd values = solver.eigenvalues();
  std::sort(values.data(), values.data() + values.size(),
            [](const std::complex<double>& a, const std::complex<double>& b) {
              return std::abs(a) > std::abs(b);
            });
  return values;
}

PeriodicOrbit find_periodic_orbit(const PeriodMap& map, const Eigen::VectorXd& guess,
                                  const ShootingSettings& settings) {
  validate(settings);
  const Eigen::Index n = guess.size();
  if (n == 0 || !guess.allFinite()) {
    throw InputError("guess", format_vector(guess), "a non-empty state with finite components");
  }
  const Eigen::VectorXd scale = resolved_scale(settings, n);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(n, n);

  PeriodicOrbit orbit;
  Eigen::VectorXd x = guess;
  Eigen::VectorXd f = checked_value(map(x), n, "shooting") - x;
  ++orbit.map_evaluations;
  double residual = scaled_norm(f, scale);
  for (int iteration = 0;; ++iteration) {
    if (residual <= settings.tolerance) {
      orbit.fixed_point = x;
      orbit.residual = residual;
      orbit.iterations = iteration;
      orbit.jacobian = period_map_jacobian(map, x, scale, settings.difference_step);
      orbit.map_evaluations += 2 * static_cast<std::size_t>(n);
      orbit.floquet_multipliers = floquet_multipliers(orbit.jacobian);
      return orbit;
    }
    if (iteration == settings.max_iterations) {
      throw ShootingError("shooting: no convergence in " + std::to_string(iteration) +
                          " Newton iterations; scaled residual " + format_number(residual) +
                          " > tolerance " + format_number(settings.tolerance) + " at " +
                          format_vector(x));
    }
    // Newton in the scaled unknowns x / scale, so that the pivoting sees comparable columns.
    const Eigen::MatrixXd j = period_map_jacobian(map, x, scale, settings.difference_step);
    orbit.map_evaluations += 2 * static_cast<std::size_t>(n);
    const Eigen::MatrixXd scaled_dp = scale.cwiseInverse().asDiagonal() * j * scale.asDiagonal();
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled_dp - identity,
                                                Eigen::ComputeThinU | Eigen::ComputeThinV);
    // Singular to the accuracy of the difference Jacobian (~4e-11 of |DP|, with a margin).
    const double noise = 1e-8 * std::max(1.0, scaled_dp.norm());
    if (svd.singularValues()[n - 1] <= noise) {
      throw ShootingError("shooting: DP - I is singular at " + format_vector(x) +
                          " (smallest singular value " +
                          format_number(svd.singularValues()[n - 1]) +
                          ": a Floquet multiplier at 1, i.e. a fold or a family of orbits)");
    }
    const Eigen::VectorXd dx =
        scale.asDiagonal() * svd.solve(Eigen::VectorXd(-(f.array() / scale.array())));
    double damping = 1.0;
    for (;;) {
      const Eigen::VectorXd trial = x + damping * dx;
      const Eigen::VectorXd trial_f = checked_value(map(trial), n, "shooting") - trial;
      ++orbit.map_evaluations;
      const double trial_residual = scaled_norm(trial_f, scale);
      if (trial_residual < residual) {
        x = trial;
        f = trial_f;
        residual = trial_residual;
        break;
      }
      damping *= 0.5;
      if (damping < settings.min_damping) {
        throw ShootingError("shooting: the Newton step does not lower the scaled residual " +
                            format_number(residual) + " even damped to " +
                            format_number(2.0 * damping) + ", at " + format_vector(x));
      }
    }
  }
}

Branch continue_periodic_orbits(const ParametrizedPeriodMap& map, const Eigen::VectorXd& guess,
                                double start_parameter, int direction,
                                const ContinuationSettings& settings) {
  validate(settings.newton);
  if (!std::isfinite(settings.parameter_min) || !std::isfinite(settings.parameter_max) ||
      settings.parameter_max <= settings.parameter_min) {
    throw InputError("parameter_max", settings.parameter_max,
                     "finite and > parameter_min = " + format_number(settings.parameter_min));
  }
  if (!std::isfinite(start_parameter) || start_parameter < settings.parameter_min ||
      start_parameter > settings.parameter_max) {
    throw InputError("start_parameter", start_parameter,
                     "within [" + format_number(settings.parameter_min) + ", " +
                         format_number(settings.parameter_max) + "]");
  }
  if (!std::isfinite(settings.parameter_scale) || settings.parameter_scale <= 0.0) {
    throw InputError("parameter_scale", settings.parameter_scale, "a finite value > 0");
  }
  if (!(settings.min_step > 0.0 && settings.min_step <= settings.initial_step &&
        settings.initial_step <= settings.max_step && std::isfinite(settings.max_step))) {
    throw InputError("initial_step", settings.initial_step,
                     "0 < min_step <= initial_step <= max_step, finite");
  }
  if (settings.max_points < 1) throw InputError("max_points", 0.0, ">= 1");
  if (settings.corrector_max_iterations < 1) {
    throw InputError("corrector_max_iterations",
                     static_cast<double>(settings.corrector_max_iterations), ">= 1");
  }
  if (direction == 0) throw InputError("direction", 0.0, "> 0 (increasing) or < 0 (decreasing)");

  const Eigen::Index n = guess.size();
  const Eigen::VectorXd scale = resolved_scale(settings.newton, n);
  const PeriodicOrbit first = find_periodic_orbit(
      [&](const Eigen::VectorXd& x) { return map(x, start_parameter); }, guess, settings.newton);

  const ScaledProblem problem(map, scale, settings.parameter_scale,
                              settings.newton.difference_step);
  Eigen::VectorXd z = problem.to_z(first.fixed_point, start_parameter);
  Eigen::MatrixXd j = problem.jacobian(z);
  Eigen::VectorXd start_direction = Eigen::VectorXd::Zero(n + 1);
  start_direction[n] = direction > 0 ? 1.0 : -1.0;
  Eigen::VectorXd t = tangent(j, start_direction);

  Branch branch;
  branch.points.push_back(make_point(problem, z, j, t));
  double step = settings.initial_step;
  for (;;) {
    if (branch.points.size() >= settings.max_points) {
      branch.end = BranchEnd::max_points;
      branch.end_reason = std::to_string(branch.points.size()) +
                          " points (max_points) reached at " + format_number(problem.parameter(z));
      return branch;
    }
    const Eigen::VectorXd predicted = z + step * t;
    const Corrected c = correct(problem, predicted, t, settings.corrector_max_iterations,
                                settings.newton.tolerance);
    if (!c.converged || (c.z - predicted).norm() > 2.0 * step) {
      step *= 0.5;
      if (step < settings.min_step) {
        branch.end = BranchEnd::step_too_small;
        branch.end_reason =
            "the corrector fails at every step down to " + format_number(settings.min_step) +
            " beyond parameter " + format_number(problem.parameter(z)) +
            " (a corner or an end of the branch); last residual " + format_number(c.residual) +
            (c.map_failure.empty() ? std::string()
                                   : "; the period map failed there: " + c.map_failure);
        return branch;
      }
      continue;
    }
    const double parameter = problem.parameter(c.z);
    if (parameter < settings.parameter_min || parameter > settings.parameter_max) {
      branch.end = BranchEnd::left_parameter_range;
      branch.end_reason = "the branch leaves [" + format_number(settings.parameter_min) + ", " +
                          format_number(settings.parameter_max) + "] after " +
                          format_number(problem.parameter(z));
      return branch;
    }
    const Eigen::MatrixXd j_new = problem.jacobian(c.z);
    const Eigen::VectorXd t_new = tangent(j_new, t);
    if (t_new[n] * t[n] < 0.0) {
      Fold fold = locate_fold(problem, z, t, step, t_new[n], settings);
      fold.after_point = branch.points.size() - 1;
      branch.folds.push_back(fold);
    }
    z = c.z;
    t = t_new;
    branch.points.push_back(make_point(problem, z, j_new, t));
    if (c.iterations <= 3) step = std::min(1.5 * step, settings.max_step);
  }
}

}  // namespace gearimpact
