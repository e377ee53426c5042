// The planar nonlinear dynamics of docs/vibration.md, section "The planar
// dynamics": x, y, theta per gear on elastic bearings (and a motor and a load
// behind torsional shafts), both lines of action with the centres' motion in
// their deflections (the backlash breathes), each side an independent contact
// with its own pairs, Hertzian damping and friction, whose forces act on the
// centres too. simulate() runs it for a case with [bearings] kind = "elastic";
// simulate_planar() lets a library caller set the mounting and the initial
// state directly (bearing stiffness 0: free centres).
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// How the gears are held, in SI; index 0 the pinion, 1 the wheel.
struct PlanarMounting {
  std::array<double, 2> mass_kg{};  // > 0
  // Per direction (x along O1 -> O2, y across it), >= 0: 0 leaves the centre free.
  std::array<double, 2> stiffness_x_n_per_m{};
  std::array<double, 2> stiffness_y_n_per_m{};
  std::array<double, 2> damping_x_n_s_per_m{};
  std::array<double, 2> damping_y_n_s_per_m{};
  // A motor behind the pinion and a load behind the wheel, each on a torsional
  // shaft; the torques then act on them, not on the gears.
  bool shafts = false;
  double motor_inertia_kg_m2 = 0.0;
  double motor_stiffness_n_m_per_rad = 0.0;
  double motor_damping_n_m_s_per_rad = 0.0;
  double load_inertia_kg_m2 = 0.0;
  double load_stiffness_n_m_per_rad = 0.0;
  double load_damping_n_m_s_per_rad = 0.0;
};

// The mounting of a case with [bearings] kind = "elastic": its [bearings] and
// [shafts] (an absent mass the disc of moment_of_inertia, absent y values the x ones).
PlanarMounting planar_mounting(const SimulationCase& c);

// The state of a case: its initial angles and speeds, the centres at rest on
// their bearings' unloaded positions, the motor and load with their gears.
PlanarState planar_initial_state(const SimulationCase& c);

// Linear momentum of both gears, and angular momentum about O1 (the pinion's
// unloaded centre, z up; theta2 turns about -z) of every body.
std::array<double, 2> planar_linear_momentum(const PlanarMounting& m, const PlanarState& s);
double planar_angular_momentum(const SimulationCase& c, const PlanarMounting& m,
                               const PlanarState& s);

// Throws InputError naming the mounting's field (mass1, stiffness_x2, ...)
// unless every mass is finite and > 0, every bearing stiffness and damping
// finite and >= 0 (the shafts' values as [shafts]' rows); and naming resume
// unless a continued run's state (RunControl::resume) holds a finite planar
// state (RunState::planar, the final_state of a planar run). simulate()
// calls it for an elastic case before it builds the stiffness table.
void validate_planar(const SimulationCase& c, const PlanarMounting& mounting,
                     const RunControl& control);

// Throws InputError naming integrator.step when the step exceeds
// 1/steps_per_contact_period(integrator.kind) of the shortest period the
// planar system can have (a bound from its stiffest springs: the mesh on both
// sides, the bearings, the shafts, and a drag's relaxation of the load). It is
// tighter than the torsional contact's bound (validate_step), so simulate()
// checks it first for a planar case: the message gives the step that runs.
void check_planar_step(const SimulationCase& c, const StiffnessTable& table,
                       const PlanarMounting& mounting);
// The largest step of `kind` within that bound (for "adaptive", RK4's count
// of steps): the adaptive integrator's largest step on the planar system.
double planar_largest_step_s(const SimulationCase& c, const StiffnessTable& table,
                             const PlanarMounting& mounting, IntegratorKind kind);

// The run of c on `mounting` from `initial`: fixed-step RK4 or Dormand-Prince
// 5(4) (integrator.kind) at integrator.step, or the adaptive Dormand-Prince
// (steps of its error's size, each ending at the mode's first event on its
// dense output), each step cut at a side's events (contact onset and
// end, a pair's entry and exit, with [modifications] its touching or letting go and a relief's
// kink, a fault's edges, a friction reversal, a clipping; docs/vibration.md, "Integration"), after
// validate_planar and validate_sampling; with RunControl::sample_rate_hz it samples (PlanarSample)
// at sample_time_s(0, n, rate) from each accepted step's continuous extension, the left limit at an
// event time. It throws check_planar_step's InputError. A kinematic driver's angle starts from the
// initial state's (the pinion's, the motor's with shafts). With RunControl::resume
// the run continues from its planar state and both lines' contact memories at
// its time (a contact in progress is no new impact), and `initial` is not used.
SimulationResult simulate_planar(const SimulationCase& c, const StiffnessTable& table,
                                 const PlanarMounting& mounting, const PlanarState& initial,
                                 const RunControl& control = {});

}  // namespace gearimpact
