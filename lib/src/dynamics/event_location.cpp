#include "event_location.hpp"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace gearimpact {

double earliest_event(double a, double b, const double* g_a, const double* g_b, int n,
                      const std::function<double(double, int)>& value_at) {
  double earliest = b;
  const double width = b - a;
  for (int i = 0; i < n; ++i) {
    // A value already zero at a has no bracket: the change then counts at the
    // end of the step (a tie of measure zero, not worth a cut).
    if (!(g_b[i] < 0.0) || g_a[i] <= 0.0) continue;
    const auto value = [&](double t) { return value_at(t, i); };
    std::uintmax_t iterations = 200;
    // Late in a run 4 eps of the step is below the spacing of doubles near t:
    // once the bracket is two neighbouring doubles it cannot shrink, and
    // iterating on (up to the limit) would only repeat the same evaluations.
    const auto close_enough = [width](double lo, double hi) {
      return hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * width ||
             std::nextafter(lo, hi) >= hi;
    };
    const double g_end = value(earliest);
    if (!(g_end < 0.0)) continue;  // this one comes after an earlier event
    const std::pair<double, double> bracket = boost::math::tools::toms748_solve(
        value, a, earliest, g_a[i], g_end, close_enough, iterations);
    // The solver may stop on an exact zero; the step must end where the value
    // is negative, so that the new mode is unambiguous.
    double after = bracket.second;
    for (double bump = 4.0 * std::numeric_limits<double>::epsilon() * width;
         after < earliest && !(value(after) < 0.0); bump *= 2.0) {
      after = std::min(after + bump, earliest);
    }
    earliest = std::min(earliest, after);
  }
  return earliest;
}

}  // namespace gearimpact
