// Locating the end of a mode inside a step: the earliest time at which an
// event value of the mode turns negative, by TOMS 748 on each value that
// changes sign, given the state as a function of time (the step of the
// integrator or its dense output).
#pragma once

#include <functional>

#include "gearimpact/dynamics/system.hpp"

namespace gearimpact {

// The earliest time in (a, b] at which an event value of mode m turns
// negative. g_a and g_b hold the n values at a and b, some negative at b.
// The time returned has the value negative, so that the new mode is
// unambiguous.
double earliest_event(const GearSystem& system, const Mode& m, const ContactMemory& d, double a,
                      double b, const EventValues& g_a, const EventValues& g_b, int n,
                      const std::function<void(double, State&)>& state_at);

}  // namespace gearimpact
