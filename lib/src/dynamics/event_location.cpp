#include "event_location.hpp"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace gearimpact {

double earliest_event(double a, double b, const double* g_a, const double* g_b, int n,
                      const std::function<double(double, int)>& value_at) {
  // The values that turn negative in the step. A value already zero at a has
  // no bracket: the change then counts at the end of the step (a tie of
  // measure zero, not worth a cut).
  std::vector<int> crossing;
  for (int i = 0; i < n; ++i) {
    if (g_b[i] < 0.0 && g_a[i] > 0.0) crossing.push_back(i);
  }
  if (crossing.empty()) return b;
  // One search for all of them: the least of the crossing values, positive at
  // a, negative at b, turns negative where the first of them does. A time
  // tried is a state found once (value_at keeps it) with every value read
  // from it, where a search per value would step to its own times again.
  // With one value crossing, or several crossing at the same time to the bit
  // (identical, equally spaced planets), the least is that value itself.
  const auto least = [&](double t) {
    double g = value_at(t, crossing.front());
    for (std::size_t k = 1; k < crossing.size(); ++k) g = std::min(g, value_at(t, crossing[k]));
    return g;
  };
  const double width = b - a;
  // Late in a run 4 eps of the step is below the spacing of doubles near t:
  // once the bracket is two neighbouring doubles it cannot shrink, and
  // iterating on (up to the limit) would only repeat the same evaluations.
  const auto close_enough = [width](double lo, double hi) {
    return hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * width ||
           std::nextafter(lo, hi) >= hi;
  };
  double g_start = g_a[crossing.front()];
  for (const int i : crossing) g_start = std::min(g_start, g_a[i]);
  const double g_end = least(b);
  if (!(g_end < 0.0)) return b;  // the state at b found again is not the step's end
  std::uintmax_t iterations = 200;
  const std::pair<double, double> bracket =
      boost::math::tools::toms748_solve(least, a, b, g_start, g_end, close_enough, iterations);
  // The solver may stop on an exact zero; the step must end where the value
  // is negative, so that the new mode is unambiguous. Nor may another value
  // that crosses in this step be exactly zero there (two crossings within a
  // few ulps, as a leaving pair's end and the next pair's kink with an integer
  // overlap ratio): the next step, starting at zero, would have no bracket for
  // it and would change its mode only at its own end.
  const auto settled = [&](double t) {
    if (!(least(t) < 0.0)) return false;
    return std::none_of(crossing.begin(), crossing.end(),
                        [&](int i) { return value_at(t, i) == 0.0; });
  };
  double after = bracket.second;
  for (double bump = 4.0 * std::numeric_limits<double>::epsilon() * width;
       after < b && !settled(after); bump *= 2.0) {
    after = std::min(after + bump, b);
  }
  return after;
}

}  // namespace gearimpact
