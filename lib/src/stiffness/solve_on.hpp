// The root finder the faulted teeth (root_crack.cpp, surface_faults.cpp)
// share to find where a tooth's section changes along its flank. Not installed.
#pragma once

#include <functional>

namespace gearimpact {

// The point between p0 and p1 (either order) where f changes sign; f(p0) and
// f(p1) of opposite signs (TOMS 748 to full precision).
double solve_on(const std::function<double(double)>& f, double p0, double p1);

}  // namespace gearimpact
