// Locating the end of a mode inside a step: the earliest time at which an
// event value of the mode turns negative, by TOMS 748 on each value that
// changes sign, given the value as a function of time (from the step of the
// integrator or its dense output). The torsional system (GearSystem, Mode)
// and the planar one (planar.cpp) share it.
#pragma once

#include <functional>

#include "gearimpact/dynamics/system.hpp"

namespace gearimpact {

// The earliest time in (a, b] at which one of n event values turns negative.
// g_a and g_b hold the values at a and b, some negative at b; value(t, i) is
// value i at time t. The time returned has the value negative, so that the
// new mode is unambiguous.
double earliest_event(double a, double b, const double* g_a, const double* g_b, int n,
                      const std::function<double(double, int)>& value);

// The same for the event values of the torsional mode m, given the state as a
// function of time.
double earliest_event(const GearSystem& system, const Mode& m, const ContactMemory& d, double a,
                      double b, const EventValues& g_a, const EventValues& g_b, int n,
                      const std::function<void(double, State&)>& state_at);

}  // namespace gearimpact
