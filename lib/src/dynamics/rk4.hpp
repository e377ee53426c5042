// The integrators of a run: fixed-step RK4 with event location (rk4.cpp) and
// Boost.Odeint's dense-output Dormand-Prince method (order 5, with an embedded
// order-4 error estimate) with the same event location
// (adaptive.cpp).
#pragma once

#include <array>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "rk4_dense.hpp"
#include "step_methods.hpp"

namespace gearimpact {

// k1 ... k4 of a classical RK4 step, for its dense output (rk4_dense).
using Rk4Stages = Rk4StagesFor<GearSystem>;

// The classical RK4 step; k1 receives f(t, y) (rk4_step_from of step_methods.hpp
// takes it evaluated).
void rk4_step(const GearSystem& system, double t, const State& y, double h, const Mode& m,
              const ContactMemory& d, State& out, State& k1, Rk4Stages* stages = nullptr);
// The classical RK4 step with the mode re-evaluated at every stage: what a
// fixed-step integration without event location does.
void rk4_step_unlocated(const GearSystem& system, double t, const State& y, double h,
                        const ContactMemory& d, State& out);

// The runs; the case and the table are validated by simulate().
// At the fixed step: RK4 or, with integrator.kind = "dopri5", Dormand-Prince
// 5(4) (FixedStepper of step_methods.hpp).
SimulationResult run_fixed_step(const SimulationCase& c, const StiffnessTable& table,
                                const RunControl& control);
SimulationResult run_adaptive(const SimulationCase& c, const StiffnessTable& table,
                              const RunControl& control);

}  // namespace gearimpact
