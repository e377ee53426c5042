// The integrators of a run: fixed-step RK4 with event location (rk4.cpp) and
// Boost.Odeint's dense-output Dormand-Prince method (order 5, with an embedded
// order-4 error estimate) with the same event location
// (adaptive.cpp).
#pragma once

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/system.hpp"

namespace gearimpact {

// The classical RK4 step from (t, y) with k1 = f(t, y) already evaluated:
// event location tries many step sizes from the same start.
void rk4_step_from(const GearSystem& system, double t, const State& y, const State& k1, double h,
                   const Mode& m, const ContactMemory& d, State& out);
// The classical RK4 step; k1 receives f(t, y).
void rk4_step(const GearSystem& system, double t, const State& y, double h, const Mode& m,
              const ContactMemory& d, State& out, State& k1);
// The classical RK4 step with the mode re-evaluated at every stage: what a
// fixed-step integration without event location does.
void rk4_step_unlocated(const GearSystem& system, double t, const State& y, double h,
                        const ContactMemory& d, State& out);

// The runs; the case and the table are validated by simulate().
SimulationResult run_rk4(const SimulationCase& c, const StiffnessTable& table,
                         const RunControl& control);
SimulationResult run_adaptive(const SimulationCase& c, const StiffnessTable& table,
                              const RunControl& control);

}  // namespace gearimpact
