#include "gearimpact/numerics/quadrature.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <memory>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// GSL's default handler aborts the process; its statuses are checked instead.
const bool gsl_handler_disabled = [] {
  gsl_set_error_handler_off();
  return true;
}();

// Counts evaluations and remembers the first non-finite value: CQUAD, for
// one, treats NaN as a singularity to step around, and a stiffness integrand
// that returns NaN is a bug to report, not to integrate around.
struct CountedIntegrand {
  const Integrand* f;
  std::size_t evaluations = 0;
  bool non_finite_seen = false;
  double non_finite_at = 0.0;

  double operator()(double x) {
    ++evaluations;
    const double value = (*f)(x);
    if (!std::isfinite(value) && !non_finite_seen) {
      non_finite_seen = true;
      non_finite_at = x;
    }
    return value;
  }

  void require_finite(std::string_view routine) const {
    if (non_finite_seen) {
      throw QuadratureError(std::string(routine) +
                            ": the integrand is not finite at x = " + format_number(non_finite_at));
    }
  }
};

double call_counted(double x, void* params) {
  return (*static_cast<CountedIntegrand*>(params))(x);
}

void require_finite_interval(std::string_view routine, double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) {
    throw QuadratureError(std::string(routine) + ": interval [" + format_number(a) + ", " +
                          format_number(b) + "] is not finite");
  }
}

void throw_gsl(std::string_view routine, int status, double a, double b, double error_estimate) {
  throw QuadratureError(std::string(routine) + " failed on [" + format_number(a) + ", " +
                        format_number(b) + "]: " + gsl_strerror(status) + " (error estimate " +
                        format_number(error_estimate) + ")");
}

}  // namespace

void check_converged(std::string_view routine, double a, double b, double error_estimate,
                     double l1_norm, QuadratureTolerance tolerance) {
  if (!std::isfinite(l1_norm)) {
    throw QuadratureError(std::string(routine) + " on [" + format_number(a) + ", " +
                          format_number(b) + "]: the integrand is not finite or not integrable");
  }
  const double bound = std::max(tolerance.absolute, tolerance.relative * std::abs(l1_norm));
  if (!(error_estimate <= bound)) {
    throw QuadratureError(std::string(routine) + " did not converge on [" + format_number(a) +
                          ", " + format_number(b) + "]: error estimate " +
                          format_number(error_estimate) + " above the requested " +
                          format_number(bound));
  }
}

QuadratureResult integrate_gsl_qag(const Integrand& f, double a, double b,
                                   QuadratureTolerance tolerance) {
  (void)gsl_handler_disabled;
  require_finite_interval("gsl_qag", a, b);
  constexpr std::size_t subinterval_limit = 1000;
  const std::unique_ptr<gsl_integration_workspace, decltype(&gsl_integration_workspace_free)>
      workspace(gsl_integration_workspace_alloc(subinterval_limit),
                &gsl_integration_workspace_free);
  CountedIntegrand counted{&f};
  gsl_function function{&call_counted, &counted};
  QuadratureResult result;
  const int status = gsl_integration_qag(&function, a, b, tolerance.absolute, tolerance.relative,
                                         subinterval_limit, GSL_INTEG_GAUSS61, workspace.get(),
                                         &result.value, &result.error_estimate);
  counted.require_finite("gsl_qag");
  if (status != GSL_SUCCESS) throw_gsl("gsl_qag", status, a, b, result.error_estimate);
  check_converged("gsl_qag", a, b, result.error_estimate, result.value, tolerance);
  result.evaluations = counted.evaluations;
  return result;
}

QuadratureResult integrate_gsl_cquad(const Integrand& f, double a, double b,
                                     QuadratureTolerance tolerance) {
  (void)gsl_handler_disabled;
  require_finite_interval("gsl_cquad", a, b);
  constexpr std::size_t interval_limit = 200;
  const std::unique_ptr<gsl_integration_cquad_workspace,
                        decltype(&gsl_integration_cquad_workspace_free)>
      workspace(gsl_integration_cquad_workspace_alloc(interval_limit),
                &gsl_integration_cquad_workspace_free);
  CountedIntegrand counted{&f};
  gsl_function function{&call_counted, &counted};
  QuadratureResult result;
  std::size_t evaluations = 0;
  const int status =
      gsl_integration_cquad(&function, a, b, tolerance.absolute, tolerance.relative,
                            workspace.get(), &result.value, &result.error_estimate, &evaluations);
  counted.require_finite("gsl_cquad");
  if (status != GSL_SUCCESS) throw_gsl("gsl_cquad", status, a, b, result.error_estimate);
  // CQUAD returns success with its best estimate when the tolerance is out of
  // reach, so the bound is checked here as well.
  check_converged("gsl_cquad", a, b, result.error_estimate, result.value, tolerance);
  result.evaluations = evaluations;
  return result;
}

QuadratureResult integrate_boost_gauss_kronrod(const Integrand& f, double a, double b,
                                               QuadratureTolerance tolerance) {
  require_finite_interval("boost_gauss_kronrod", a, b);
  constexpr unsigned max_depth = 15;
  CountedIntegrand counted{&f};
  QuadratureResult result;
  double l1 = 0.0;
  result.value = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      [&counted](double x) { return counted(x); }, a, b, max_depth, tolerance.relative,
      &result.error_estimate, &l1);
  counted.require_finite("boost_gauss_kronrod");
  check_converged("boost_gauss_kronrod", a, b, result.error_estimate, l1, tolerance);
  result.evaluations = counted.evaluations;
  return result;
}

QuadratureResult integrate_boost_tanh_sinh(const Integrand& f, double a, double b,
                                           QuadratureTolerance tolerance) {
  require_finite_interval("boost_tanh_sinh", a, b);
  // Building the abscissa tables is the expensive part; keep one per thread.
  thread_local boost::math::quadrature::tanh_sinh<double> integrator(15);
  CountedIntegrand counted{&f};
  QuadratureResult result;
  double l1 = 0.0;
  std::size_t levels = 0;
  // Boost stops refining on a criterion of its own that can leave the reported
  // level difference above the tolerance it was given; asking for a hundred
  // times less makes it take the next level, and the estimate is then checked
  // against what the caller asked.
  constexpr double refinement_margin = 1e-2;
  try {
    result.value = integrator.integrate([&counted](double x) { return counted(x); }, a, b,
                                        tolerance.relative * refinement_margin,
                                        &result.error_estimate, &l1, &levels);
  } catch (const std::exception& e) {
    throw QuadratureError(std::string("boost_tanh_sinh failed on [") + format_number(a) + ", " +
                          format_number(b) + "]: " + e.what());
  }
  counted.require_finite("boost_tanh_sinh");
  check_converged("boost_tanh_sinh", a, b, result.error_estimate, l1, tolerance);
  result.evaluations = counted.evaluations;
  return result;
}

QuadratureResult integrate(QuadratureRule rule, const Integrand& f, double a, double b,
                           QuadratureTolerance tolerance) {
  switch (rule) {
    case QuadratureRule::gsl_qag:
      return integrate_gsl_qag(f, a, b, tolerance);
    case QuadratureRule::gsl_cquad:
      return integrate_gsl_cquad(f, a, b, tolerance);
    case QuadratureRule::boost_gauss_kronrod:
      return integrate_boost_gauss_kronrod(f, a, b, tolerance);
    case QuadratureRule::boost_tanh_sinh:
      return integrate_boost_tanh_sinh(f, a, b, tolerance);
  }
  throw QuadratureError("unknown quadrature rule " + std::to_string(static_cast<int>(rule)));
}

std::string to_string(QuadratureRule rule) {
  return name_of(kQuadratureRules, rule);
}

QuadratureRule parse_quadrature_rule(std::string_view name, std::string_view field) {
  return value_named(kQuadratureRules, name, field);
}

}  // namespace gearimpact
