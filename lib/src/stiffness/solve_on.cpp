#include "solve_on.hpp"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cstdint>

namespace gearimpact {

double solve_on(const std::function<double(double)>& f, double p0, double p1) {
  double a = std::min(p0, p1);
  double b = std::max(p0, p1);
  std::uintmax_t iterations = 200;
  const auto bracket = boost::math::tools::toms748_solve(
      f, a, b, f(a), f(b), boost::math::tools::eps_tolerance<double>(), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

}  // namespace gearimpact
