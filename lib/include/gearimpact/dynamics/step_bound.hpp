// The largest fixed step that resolves the contact, and the check of a case's
// step against it.
#pragma once

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// 1/20 of the period of the stiffest contact, sqrt(K (Rb1^2/J1 + Rb2^2/J2))
// with K the largest sum of Ke over the loaded pairs (sampled along one base
// pitch), Ke by adaptive quadrature.
double largest_resolving_step_s(const SimulationCase& c);
// The same from a table built for c: Ke to round-off, without the quadrature.
double largest_resolving_step_s(const SimulationCase& c, const StiffnessTable& table);

// The bounds a torsional run of c is held to on its step, for a person to read before a run
// (check-case, report), each as validate_implied applies it: the contact's and, for a case with
// speeds, the mesh period's. The planar model (elastic bearings) is held to a tighter bound of
// its own springs as well (check_planar_step).
struct StepBounds {
  double contact_period_s = 0.0;  // 2 pi sqrt(m_e / K), K the stiffest total mesh stiffness
  double rk4_step_s = 0.0;        // contact_period / kStepsPerContactPeriod; adaptive's first step
  double dopri5_step_s = 0.0;     // contact_period / kDopri5StepsPerContactPeriod
  // The mesh period 2 pi / (z1 |w1|) at the case's initial pinion speed and the largest step with
  // kStepsPerMeshPeriod steps in it, for every method; 0 and infinity at rest.
  double mesh_period_s = 0.0;
  double mesh_step_s = 0.0;
};
StepBounds step_bounds(const SimulationCase& c);

// The largest step with kStepsPerMeshPeriod steps per mesh period 2 pi / (z |w|) of a gear of z
// teeth at w; infinity at rest.
double largest_mesh_step_s(int teeth, double w_rad_per_s);

// Throws InputError unless step <= largest_step_s (the schema holds the
// step's other bounds and the most steps of a run). The message names the
// contact period and the keys that set it; a period too short for any step
// (a density or module far too small) is said so, never as an empty range.
void validate_step(const SimulationCase& c, double largest_step_s);

// The checks of what the inputs imply together, before a run; each throws
// InputError naming the key as section.key, its value and the bound with its
// reason:
// - the static deflection: each torque's peak |T| (constant, or mean plus the
//   amplitudes) over its base radius, over the smallest total mesh stiffness
//   (the constant one of MeshStiffnessMode::constant), at most
//   kMostStaticDeflectionPerModule module; names torqueN.value, .amplitude(s)
//   or .mean, whichever sets most of the peak (a user function is not checked);
// - the step against the stiffest contact (validate_step);
// - initial.w1, initial.w2: at least kStepsPerMeshPeriod steps of
//   integrator.step per mesh period 2 pi / (z |w|);
// - the torques' angular frequencies: as many steps per forcing period 2 pi / W;
// - torque2.drag_speed_scale: as many steps per 2 pi of the drag's relaxation time;
// - model.friction_smoothing_speed v_s > 0 under a fixed step h, with friction
//   on: v_s >= (kStepsPerContactPeriod / 2) h Rb1 |w1| (|w1| + |w2|), so that
//   the band 2 v_s of tanh(Vs / v_s) spans as many steps of the sliding speed's
//   sweep by the rolling at the initial speeds (the driver's fastest).
// The mesh stiffness is sampled as largest_resolving_step_s samples it, by
// quadrature or from the table.
// The largest tooth load the case's torques imply, max over the gears of the
// peak |T(t)| / Rb (0 for a driver or a torque given as a function).
double peak_tooth_load_n(const SimulationCase& c);

// The damping rate of one fixed step, h c / m_e, of a contact whose Hertzian
// damping (32) is D (s/m) under the tooth load F: the damper's coefficient is
// D K delta with delta about F / K, so D F. Fixed-step RK4 diverges on a decay
// whose h c / m_e exceeds kRk4RealStabilityLimit; m_e is the pair's effective
// mass, or the wheel's J2 / Rb2^2 behind a driver.
double damping_rate_per_step(const SimulationCase& c, double damping_per_stiffness_s_m,
                             double load_n);
// The classical RK4's stability interval on the negative real axis, [-2.785, 0].
inline constexpr double kRk4RealStabilityLimit = 2.785;
// Dormand-Prince 5(4)'s (its order-5 solution, whose stability polynomial is
// sum z^k / k! to k = 5 plus z^6 / 600): [-3.3066, 0].
inline constexpr double kDopri5RealStabilityLimit = 3.3066;
// The interval of a fixed-step method (integrator.kind rk4 or dopri5).
inline constexpr double real_stability_limit(IntegratorKind kind) {
  return kind == IntegratorKind::dopri5 ? kDopri5RealStabilityLimit : kRk4RealStabilityLimit;
}

void validate_implied(const SimulationCase& c);
void validate_implied(const SimulationCase& c, const StiffnessTable& table);

}  // namespace gearimpact
