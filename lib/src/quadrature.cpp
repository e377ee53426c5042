#include "gearimpact/quadrature.hpp"

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

struct CountedIntegrand {
  const Integrand* f;
  std::size_t evaluations = 0;
};

double call_counted(double x, void* params) {
  auto* counted = static_cast<CountedIntegrand*>(params);
  ++counted->evaluations;
  return (*counted->f)(x);
}

void require_finite_interval(std::string_view routine, double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) {
    throw QuadratureError(std::string(routine) + ": interval [" + format_number(a) + ", " +
                          format_number(b) + "] is not finite");
  }
}

void throw_gsl(std::string_view routine, int status, double a, double b, double error_estimate) {
  throw QuadratureError(std::string(routine) + " failed on [" + format_number(a) + ", " +
                        format_number(b) + "]: " + gsl_strerror(status) +
                        " (error estimate " + format_number(error_estimate) + ")");
}

}  // namespace

void check_converged(std::string_view routine, double a, double b, double error_estimate,
                     double l1_norm, QuadratureTolerance tolerance) {
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
  if (status != GSL_SUCCESS) throw_gsl("gsl_qag", status, a, b, result.error_estimate);
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
  std::size_t evaluations = 0;
  auto counted = [&](double x) {
    ++evaluations;
    return f(x);
  };
  QuadratureResult result;
  double l1 = 0.0;
  result.value = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      counted, a, b, max_depth, tolerance.relative, &result.error_estimate, &l1);
  check_converged("boost_gauss_kronrod", a, b, result.error_estimate, l1, tolerance);
  result.evaluations = evaluations;
  return result;
}

QuadratureResult integrate_boost_tanh_sinh(const Integrand& f, double a, double b,
                                           QuadratureTolerance tolerance) {
  require_finite_interval("boost_tanh_sinh", a, b);
  // Building the abscissa tables is the expensive part; keep one per thread.
  thread_local boost::math::quadrature::tanh_sinh<double> integrator(15);
  std::size_t evaluations = 0;
  auto counted = [&](double x) {
    ++evaluations;
    return f(x);
  };
  QuadratureResult result;
  double l1 = 0.0;
  std::size_t levels = 0;
  // Boost stops refining on a criterion of its own that can leave the reported
  // level difference above the tolerance it was given; asking for a hundred
  // times less makes it take the next level, and the estimate is then checked
  // against what the caller asked.
  constexpr double refinement_margin = 1e-2;
  try {
    result.value = integrator.integrate(counted, a, b, tolerance.relative * refinement_margin,
                                        &result.error_estimate, &l1, &levels);
  } catch (const std::exception& e) {
    throw QuadratureError(std::string("boost_tanh_sinh failed on [") + format_number(a) + ", " +
                          format_number(b) + "]: " + e.what());
  }
  check_converged("boost_tanh_sinh", a, b, result.error_estimate, l1, tolerance);
  result.evaluations = evaluations;
  return result;
}

}  // namespace gearimpact
