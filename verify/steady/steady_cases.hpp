// Cases for the steady-state suites: the clearance oscillator of docs/steady-state.md section 2
// built from the paper's pair with a constant mesh stiffness, and the paper's pair loaded and
// running.
#pragma once

#include <cmath>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"

namespace gearimpact::steady_test {

struct ClearanceCase {
  SimulationCase c;
  double stiffness_n_per_m = 0.0;
  double static_force_n = 0.0;     // T_m / Rb1
  double force_amplitude_n = 0.0;  // m_e Rb1 dT1 / J1
  double w_rad_per_s = 0.0;
};

// The paper's pair with k = 2e8 N/m constant, viscous damping zeta and no Hertzian damping or
// friction, loaded with F_m = mean_force (in k B) and a fluctuation dT1 sin(w t) on gear 1 with
// F_a = alternating_force at Omega = w / w_n; at rest on the drive flank at the static deflection.
inline ClearanceCase clearance_case(double mean_force, double alternating_force, double zeta,
                                    double omega) {
  ClearanceCase cc;
  SimulationCase& c = cc.c;
  c = paper_case(1);
  c.name = "clearance-oscillator";
  c.model.friction_coefficient = 0.0;
  c.model.mesh_stiffness = MeshStiffnessMode::constant;
  c.model.constant_mesh_stiffness_n_per_m = 2.0e8;
  c.model.mesh_damping_ratio = zeta;
  c.model.damping_update = DampingUpdate::off;
  const GearPair& g = c.gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const double j1 = moment_of_inertia(g, Gear::one);
  const double me = effective_mass_kg(g);
  const double k = c.model.constant_mesh_stiffness_n_per_m;
  const double b = g.backlash_m;
  cc.stiffness_n_per_m = k;
  cc.static_force_n = mean_force * k * b;
  cc.force_amplitude_n = alternating_force * k * b;
  cc.w_rad_per_s = omega * std::sqrt(k / me);
  c.torque1.kind = Torque::Kind::sinusoidal;
  c.torque1.mean_n_m = cc.static_force_n * rb1;
  // F_a k B = m_e Rb1 dT1 / J1.
  c.torque1.amplitude_n_m = cc.force_amplitude_n * j1 / (me * rb1);
  c.torque1.angular_frequency_rad_per_s = cc.w_rad_per_s;
  c.torque1.phase_rad = 0.0;
  c.torque2 = Torque{};
  c.torque2.constant_n_m = -cc.static_force_n * rb2;
  c.initial = InitialState{(b + cc.static_force_n / k) / rb1, 0.0, 0.0, 0.0};
  return cc;
}

// The paper's pair with its time-varying stiffness, loaded with a static force of
// 1000 N on the line of action, balanced, rolling at w1, zeta = 0.05, D frozen at 0.1 m/s, no
// friction.
inline SimulationCase loaded_paper_pair(double w1_rad_per_s) {
  PairLoad load;
  load.static_force_n = 1000.0;
  load.damping_update = DampingUpdate::frozen;
  load.damping_reference_speed_m_s = 0.1;
  load.deflection_stiffness_n_per_m = 4e8;
  return gearimpact::loaded_paper_pair(w1_rad_per_s, load);
}

// The bearings' damping ratio of on_bearings: each centre's mode on its own bearing decays as
// exp(-zeta_b w_b t), w_b = sqrt(k_b / m).
inline constexpr double kBearingDamping = 0.05;

// The case on elastic bearings of k_b per direction (the planar model), each damped at
// kBearingDamping with the gear's mass (the disc's): c = 2 zeta_b sqrt(k_b m).
inline SimulationCase on_bearings(const SimulationCase& c, double kb) {
  SimulationCase planar = c;
  planar.bearings.kind = BearingKind::elastic;
  planar.bearings.gear1.stiffness_x_n_per_m = kb;
  planar.bearings.gear2.stiffness_x_n_per_m = kb;
  const PlanarMounting mounting = planar_mounting(planar);
  planar.bearings.gear1.damping_x_n_s_per_m =
      2.0 * kBearingDamping * std::sqrt(kb * mounting.mass_kg[0]);
  planar.bearings.gear2.damping_x_n_s_per_m =
      2.0 * kBearingDamping * std::sqrt(kb * mounting.mass_kg[1]);
  return planar;
}

}  // namespace gearimpact::steady_test
