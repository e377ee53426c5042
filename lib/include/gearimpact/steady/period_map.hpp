// The period map of the gear model in its relative coordinates: the state at the start of an
// excitation period to the state one period later, by simulate() - what shooting.hpp's
// find_periodic_orbit, period_map_jacobian and continue_periodic_orbits take. Its state is the
// Poincare sample of find_steady_state (poincare_state of steady_state.hpp): (s, s') on rigid
// bearings; on elastic bearings (the planar model, dynamics/planar.hpp) (s, s') followed by the
// centres x1, y1, x2, y2 (and with shafts the twists as lengths) and their speeds.
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
//
// The planar model reduces its rigid rotation the same way. With shafts the motor and the load
// join the rotation: u_m = Rb1 theta_m and u_l = Rb2 theta_l with m_m = J_m / Rb1^2 and
// m_l = J_l / Rb2^2, the twists q_m = u_m - u1 and q_l = u_l - u2, and
//   X = (m1 u1 + m2 u2 + m_m u_m + m_l u_l) / M,  M = m1 + m2 + m_m + m_l,
//   u1 = X + ((m2 + m_l) s - m_m q_m - m_l q_l) / M,  u2 = u1 - s,  u_m = u1 + q_m,
//   u_l = u2 + q_l,
// the same for the speeds with P / M. The bearings' forces act at the centres and exert no
// torque about them, and each line's mesh force acts on the base circles with the arms Rb1 and
// Rb2, so that P = J1 w1/Rb1 + J2 w2/Rb2 + J_m w_m/Rb1 + J_l w_l/Rb2 again obeys
// P' = T1/Rb1 + T2/Rb2 and X advances one base pitch a mesh period (steady_timing's mean speed
// counts the motor's and the load's inertias). The centres' coordinates are unknowns of the
// map: their rest positions under load are part of the orbit. The full map is again block
// triangular, with the rigid block's double multiplier 1 left out.
#pragma once

#include <Eigen/Dense>
#include <array>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/dynamics/planar_state.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

class GearPeriodMap {
 public:
  // The case must be accepted by steady_timing (require_steady_case: constant, sinusoidal or
  // harmonic torques, balanced means, no friction), and beyond it:
  // - on elastic bearings, what a planar run takes (check_run: the mounting, a step that
  //   resolves the bearings and the shafts);
  // - model.damping_update off or frozen: under each_impact the Hertzian D of the last impact
  //   is part of the state, which the map's coordinates do not carry;
  // - with DampingUpdate::frozen, a damping stiffness other than the pitch pair at impact,
  //   whose Ke is remembered from the impact;
  // - model.mesh_stiffness constant, or constant torques (see above).
  // steps_per_period = 0 takes the step of steady_timing(c, table, settings); > 0 cuts the
  // period into that many RK4 steps (simulate() refuses a step that does not resolve the
  // contact). `table` must outlive the map. Throws InputError naming the key otherwise.
  GearPeriodMap(const SimulationCase& c, const StiffnessTable& table,
                const SteadySettings& settings = {}, long long steps_per_period = 0);

  // The state one period after `relative` (dimension() coordinates, poincare_state's). A run
  // that starts in contact counts that contact as an impact (DampingUpdate frozen sets its D
  // from the case, off leaves it 0), on each line of action of the planar model. Throws
  // InputError for a state that is not dimension() finite numbers, SimulationError from the run.
  // Its Jacobian and Floquet multipliers are shooting.hpp's: central differences, 2 dimension()
  // maps (period_map_jacobian), of error ~eps^(2/3) relative to |DP| on a smooth map.
  Eigen::VectorXd operator()(const Eigen::VectorXd& relative) const;

  // 2 on rigid bearings; 10 on elastic bearings, 14 with shafts (poincare_state).
  Eigen::Index dimension() const { return scale_.size(); }
  bool planar() const { return planar_; }

  // The full state at the start of a period with these relative coordinates (the gears'
  // angles and speeds; on elastic bearings the gears' part of planar_state with its centres at
  // rest and no twist).
  InitialState full_state(double s_m, double s_rate_m_s) const;
  // (s, s') of a full state.
  Eigen::Vector2d relative_state(const InitialState& state) const;
  // The planar state at the start of a period with these map coordinates (a planar map only;
  // throws InputError otherwise, or for coordinates of another size).
  PlanarState planar_state(const Eigen::VectorXd& relative) const;
  // The map's coordinates of a run's state: poincare_state of steady_state.hpp.
  Eigen::VectorXd map_state(const RunState& state) const;

  // poincare_scale of steady_state.hpp: (B, B w_n) for a pair with backlash, w_n = sqrt(k_mean /
  // m_e), the scales of s and s' in docs/steady-state.md section 2; B for each centre's
  // displacement and twist, B w_n for their speeds.
  Eigen::VectorXd scale() const { return scale_; }
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
  Eigen::VectorXd scale_;
  // The planar model's (on elastic bearings): its mounting, and the masses m1, m2, m_m, m_l of
  // the rotation along the line of action with X and P / M of the motor and the load too.
  bool planar_ = false;
  PlanarMounting mounting_;
  std::array<double, 4> rotation_mass_kg_{};
  double planar_centre_m_ = 0.0;
  double planar_centre_speed_m_s_ = 0.0;
  double period_s_ = 0.0;
  double step_s_ = 0.0;
  long long steps_per_period_ = 0;
};

}  // namespace gearimpact
