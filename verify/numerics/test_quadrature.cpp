// The quadrature wrappers on integrals with closed forms, and their failure
// reporting. These exercise the harness itself before it is trusted with the
// stiffness integrals (18)-(24).
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/numerics/quadrature.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

using Routine =
    std::function<QuadratureResult(const Integrand&, double, double, QuadratureTolerance)>;

struct NamedRoutine {
  std::string name;
  Routine routine;
};

std::vector<NamedRoutine> routines() {
  return {{"gsl_qag", integrate_gsl_qag},
          {"gsl_cquad", integrate_gsl_cquad},
          {"boost_gauss_kronrod", integrate_boost_gauss_kronrod},
          {"boost_tanh_sinh", integrate_boost_tanh_sinh}};
}

// Requested 1e-12; a converged rule on these smooth integrands is good to a
// few ulps, so 1e-12 is also the bound on the true error.
constexpr QuadratureTolerance requested{1e-12, 0.0};

}  // namespace

TEST_CASE("uniform cantilever: tip compliance l^3 / (3 E I) from Int (l - x)^2 / (E I) dx") {
  // The bending energy of (16) for a beam of constant section is the
  // textbook tip compliance: the same integral the x-form route evaluates.
  const double e = 206.8e9;
  const double width = 10e-3;
  const double thickness = 4e-3;
  const double length = 4.5e-3;
  const double second_moment = width * thickness * thickness * thickness / 12.0;
  const double exact = length * length * length / (3.0 * e * second_moment);
  const Integrand integrand = [&](double x) {
    return (length - x) * (length - x) / (e * second_moment);
  };
  for (const auto& [name, routine] : routines()) {
    CAPTURE(name);
    const QuadratureResult r = routine(integrand, 0.0, length, requested);
    CHECK(relative_difference(r.value, exact) < 1e-12);
    CHECK(r.evaluations > 0);
    CHECK(r.error_estimate <= 1e-12 * std::abs(r.value));
  }
}

TEST_CASE("smooth and end-point-singular integrals with closed forms") {
  struct Case {
    std::string what;
    Integrand f;
    double a, b, exact;
  };
  const std::vector<Case> cases{
      {"sin on [0, pi] = 2", [](double x) { return std::sin(x); }, 0.0, std::numbers::pi, 2.0},
      {"exp on [0, 1] = e - 1", [](double x) { return std::exp(x); }, 0.0, 1.0,
       std::numbers::e - 1.0},
      {"1/(1+x^2) on [0, 1] = pi/4", [](double x) { return 1.0 / (1.0 + x * x); }, 0.0, 1.0,
       std::numbers::pi / 4.0},
  };
  for (const auto& c : cases) {
    for (const auto& [name, routine] : routines()) {
      CAPTURE(c.what);
      CAPTURE(name);
      const QuadratureResult r = routine(c.f, c.a, c.b, requested);
      // A routine that claims convergence must be right to its tolerance,
      // with a factor 10 for estimates that are slightly optimistic.
      CHECK(relative_difference(r.value, c.exact) < 1e-11);
    }
  }
}

TEST_CASE("an end-point singularity: right to tolerance or reported, never silently wrong") {
  // sqrt(x) on [0, 1] = 2/3. Gauss-Kronrod bisection cannot reach 1e-12 within
  // its depth limit; it must then throw rather than return a poorer value.
  // Tanh-sinh is built for this and must converge.
  const Integrand f = [](double x) { return std::sqrt(x); };
  for (const auto& [name, routine] : routines()) {
    CAPTURE(name);
    try {
      const QuadratureResult r = routine(f, 0.0, 1.0, requested);
      CHECK(relative_difference(r.value, 2.0 / 3.0) < 1e-11);
    } catch (const QuadratureError&) {
      CHECK(name != "boost_tanh_sinh");
    }
  }
}

TEST_CASE("a divergent integral is reported, never returned") {
  // Int_0^1 dx / x diverges: every routine must throw QuadratureError.
  const Integrand divergent = [](double x) { return 1.0 / x; };
  for (const auto& [name, routine] : routines()) {
    CAPTURE(name);
    CHECK_THROWS_AS(routine(divergent, 0.0, 1.0, requested), QuadratureError);
  }
}

TEST_CASE("a NaN integrand and a non-finite interval are reported") {
  const Integrand not_a_number = [](double) { return std::numeric_limits<double>::quiet_NaN(); };
  for (const auto& [name, routine] : routines()) {
    CAPTURE(name);
    CHECK_THROWS_AS(routine(not_a_number, 0.0, 1.0, requested), QuadratureError);
    CHECK_THROWS_AS(routine([](double x) { return x; }, 0.0,
                            std::numeric_limits<double>::infinity(), requested),
                    QuadratureError);
  }
}

TEST_CASE("an unreachable tolerance is reported with the estimate and the bound") {
  // 1e-17 relative is below double precision, and the kink at 0.3 keeps every
  // rule's estimate away from zero.
  const QuadratureTolerance impossible{1e-17, 0.0};
  const Integrand f = [](double x) { return std::abs(x - 0.3); };
  for (const auto& [name, routine] : routines()) {
    CAPTURE(name);
    try {
      routine(f, 0.0, 1.0, impossible);
      FAIL("no error for a tolerance of 1e-17");
    } catch (const QuadratureError& e) {
      const std::string message = e.what();
      CHECK(message.find(name) != std::string::npos);
    }
  }
}
