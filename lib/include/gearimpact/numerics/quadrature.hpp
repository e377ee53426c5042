// Adaptive quadrature behind one small interface, so that every stiffness
// integral can be computed by independent libraries and compared.
//
// Each routine integrates f over [a, b] and either returns a result whose error
// estimate meets max(absolute, relative * |integral of |f||), or throws
// QuadratureError naming the routine, the interval, the estimate and the
// requested bound. A result that missed its tolerance is never returned.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

#include "gearimpact/named_values.hpp"

namespace gearimpact {

struct QuadratureTolerance {
  double relative = 1e-13;
  double absolute = 0.0;
};

struct QuadratureResult {
  double value = 0.0;
  // The routine's own estimate of |value - exact|.
  double error_estimate = 0.0;
  std::size_t evaluations = 0;
};

using Integrand = std::function<double(double)>;

// GSL QAG with the 61-point Gauss-Kronrod rule, up to 1000 subintervals.
// Error estimate: GSL's, from the Kronrod-Gauss difference of each subinterval.
QuadratureResult integrate_gsl_qag(const Integrand& f, double a, double b,
                                   QuadratureTolerance tolerance = {});

// GSL CQUAD, doubly adaptive Clenshaw-Curtis. Error estimate: GSL's, from the
// difference of successive interpolants.
QuadratureResult integrate_gsl_cquad(const Integrand& f, double a, double b,
                                     QuadratureTolerance tolerance = {});

// Boost.Math adaptive Gauss-Kronrod, 61 points, bisection depth up to 15.
// Error estimate: Boost's, |Kronrod - Gauss| summed over the final intervals.
QuadratureResult integrate_boost_gauss_kronrod(const Integrand& f, double a, double b,
                                               QuadratureTolerance tolerance = {});

// Boost.Math tanh-sinh (double exponential), for end-point singularities.
// Error estimate: Boost's, the difference between the last two levels.
QuadratureResult integrate_boost_tanh_sinh(const Integrand& f, double a, double b,
                                           QuadratureTolerance tolerance = {});

// The rules above by name, so that a caller can choose one at run time.
enum class QuadratureRule { gsl_qag, gsl_cquad, boost_gauss_kronrod, boost_tanh_sinh };

// Integrates with `rule`; the same contract as the routine it calls.
QuadratureResult integrate(QuadratureRule rule, const Integrand& f, double a, double b,
                           QuadratureTolerance tolerance = {});

// Names used on the command line and in case files.
inline constexpr std::array<NamedValue<QuadratureRule>, 4> kQuadratureRules{{
    {QuadratureRule::gsl_qag, "gsl", "GSL QAG"},
    {QuadratureRule::gsl_cquad, "gsl-cquad", "GSL CQUAD"},
    {QuadratureRule::boost_gauss_kronrod, "boost-gk", "Boost Gauss-Kronrod"},
    {QuadratureRule::boost_tanh_sinh, "boost-ts", "Boost tanh-sinh"},
}};

// By kQuadratureRules; parse_quadrature_rule throws InputError naming `field`
// for a name it lacks.
std::string to_string(QuadratureRule rule);
QuadratureRule parse_quadrature_rule(std::string_view name, std::string_view field);

// Throws QuadratureError if a result's estimate is above the requested bound.
void check_converged(std::string_view routine, double a, double b, double error_estimate,
                     double l1_norm, QuadratureTolerance tolerance);

}  // namespace gearimpact
