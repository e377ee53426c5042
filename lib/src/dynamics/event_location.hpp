// Locating the end of a mode inside a step: the earliest time at which an
// event value of the mode turns negative, by TOMS 748 on the least of the
// values that change sign, given the value as a function of time (from the step of the
// integrator or its dense output). Every system shares it, through
// earliest_event_of (step_methods.hpp).
#pragma once

#include <functional>

namespace gearimpact {

// The earliest time in (a, b] at which one of n event values turns negative.
// g_a and g_b hold the values at a and b, some negative at b; value(t, i) is
// value i at time t. The time returned has the value negative, so that the
// new mode is unambiguous, and no other value crossing in the step is
// exactly zero there.
double earliest_event(double a, double b, const double* g_a, const double* g_b, int n,
                      const std::function<double(double, int)>& value);

}  // namespace gearimpact
