// The period map of the gear model in its relative coordinates: (s, s') at the start of an
// excitation period to (s, s') one period later, by simulate() - what shooting.hpp's
// find_periodic_orbit, period_map_jacobian and continue_periodic_orbits take.
//
// Coordinates along the line of action: u1 = Rb1 theta1, u2 = Rb2 theta2, m_i = J_i / Rb_i^2,
//   s = u1 - u2,                          the relative (mesh) coordinate,
//   X = (m1 u1 + m2 u2) / (m1 + m2),      the centre of mass,
//   P = m1 u1' + m2 u2' = J1 w1/Rb1 + J2 w2/Rb2, its momentum,
// so that u1 = X + (m_e/m1) s and u2 = X - (m_e/m2) s with m_e = m1 m2 / (m1 + m2).
// The rigid coordinates are not unknowns of the map: every period starts from the X and P of
// the case's initial state, at t = 0 (the forcing's phase 0). This is the dynamics' own map:
// - P obeys P' = T1/Rb1 + T2/Rb2 (the mesh forces cancel), whose mean is 0 for a steady case,
//   so after a whole forcing period P is back at its start;
// - X matters only through the mesh position u1 when the stiffness varies (42); the map then
//   needs constant torques, so that the period is the mesh period t0 / V (V = P / (m1 + m2),
//   steady_timing), X advances by exactly one base pitch t0 a period and the mesh is where it
//   started. With faulted teeth the period is their true period N t0 / V (steady_timing), X
//   advances N base pitches and the same teeth are back in mesh. With a constant mesh
//   stiffness X does not enter the forces at all.
// So the 4x4 map of the full state is block triangular, [[DP, C], [0, R]], R the rigid block
// (X, P) with the double multiplier 1 of a free rigid motion, and the multipliers of DP are the
// other two of the full map.
#pragma once

#include <Eigen/Dense>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

class GearPeriodMap {
 public:
  // The case must be accepted by steady_timing (require_steady_case: constant, sinusoidal or
  // harmonic torques, balanced means, no friction), and beyond it:
  // - rigid bearings and no shafts (refuse_planar, naming bearings.kind and shafts.kind): the
  //   planar model's centres and shafts are not part of (s, s');
  // - model.damping_update off or frozen: under each_impact the Hertzian D of the last impact
  //   is part of the state, which (s, s') does not carry;
  // - with DampingUpdate::frozen, a damping stiffness other than the pitch pair at impact,
  //   whose Ke is remembered from the impact;
  // - model.mesh_stiffness constant, or constant torques (see above).
  // steps_per_period = 0 takes the step of steady_timing(c, table, settings); > 0 cuts the
  // period into that many RK4 steps (simulate() refuses a step that does not resolve the
  // contact). `table` must outlive the map. Throws InputError naming the key otherwise.
  GearPeriodMap(const SimulationCase& c, const StiffnessTable& table,
                const SteadySettings& settings = {}, long long steps_per_period = 0);

  // (s_m, s_rate_m_s) one period after `relative`. A run that starts in contact counts that
  // contact as an impact (DampingUpdate frozen sets its D from the case, off leaves it 0).
  // Throws InputError for a state that is not two finite numbers, SimulationError from the run.
  Eigen::VectorXd operator()(const Eigen::VectorXd& relative) const;

  // The full state at the start of a period with these relative coordinates.
  InitialState full_state(double s_m, double s_rate_m_s) const;
  // (s, s') of a full state.
  Eigen::Vector2d relative_state(const InitialState& state) const;

  // state_scale of steady_state.hpp: (B, B w_n) for a pair with backlash, w_n = sqrt(k_mean /
  // m_e), the scales of s and s' in docs/steady-state.md section 2.
  Eigen::Vector2d scale() const { return scale_; }
  double period_s() const { return period_s_; }
  double step_s() const { return step_s_; }
  long long steps_per_period() const { return steps_per_period_; }

 private:
  SimulationCase case_;
  const StiffnessTable* table_;
  double rb1_ = 0.0;
  double rb2_ = 0.0;
  double relative_share1_ = 0.0;   // m_e / m1
  double relative_share2_ = 0.0;   // m_e / m2
  double centre_m_ = 0.0;          // X at the start of every period
  double centre_speed_m_s_ = 0.0;  // P / (m1 + m2)
  Eigen::Vector2d scale_;
  double period_s_ = 0.0;
  double step_s_ = 0.0;
  long long steps_per_period_ = 0;
};

}  // namespace gearimpact
