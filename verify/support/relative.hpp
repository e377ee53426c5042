// Relative comparison for SI quantities of any size (doctest's default Approx
// passes every compliance of order 1e-9 m/N: its margin is absolute at scale 1).
#pragma once

#include <algorithm>
#include <cmath>

namespace gearimpact::verify {

inline double relative_difference(double a, double b) {
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale == 0.0 ? 0.0 : std::abs(a - b) / scale;
}

}  // namespace gearimpact::verify
