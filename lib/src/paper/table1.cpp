#include "gearimpact/paper/table1.hpp"

#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

SimulationCase loaded_paper_pair(double w1_rad_per_s, const PairLoad& load) {
  SimulationCase c = paper_case(1);
  c.name = "loaded-paper-pair";
  c.model.friction_coefficient = 0.0;
  c.model.mesh_damping_ratio = 0.05;
  c.model.damping_update = load.damping_update;
  c.model.damping_reference_speed_m_s = load.damping_reference_speed_m_s;
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double f = load.static_force_n;
  c.torque1 = Torque{};
  c.torque1.constant_n_m = f * rb1;
  c.torque2 = Torque{};
  c.torque2.constant_n_m = -f * rb2;
  c.initial = InitialState{(c.gears.backlash_m + f / load.deflection_stiffness_n_per_m) / rb1, 0.0,
                           w1_rad_per_s, w1_rad_per_s * rb1 / rb2};
  return c;
}

double torque_unit_n_m(TorqueUnit unit) {
  // 1 kgf = 9.80665 N (standard gravity), 1 mm = 1e-3 m.
  return unit == TorqueUnit::kgf_mm ? 9.80665e-3 : 1.0e-3;
}

SimulationCase paper_case(int number, TorqueUnit unit, double case3_angular_frequency_rad_per_s) {
  SimulationCase c;
  c.name = "case" + std::to_string(number);
  c.gears = paper_gear_pair();
  const double table_unit = torque_unit_n_m(unit);
  switch (number) {
    case 1:  // Table 1: no torques, w1(0) = 50 rad/s.
      c.initial.w1_rad_per_s = 50.0;
      break;
    case 2:  // Table 1: T1 = 50, T2 = -50, w1(0) = 50 rad/s.
      c.torque1.constant_n_m = 50.0 * table_unit;
      c.torque2.constant_n_m = -50.0 * table_unit;
      c.initial.w1_rad_per_s = 50.0;
      break;
    case 3:  // Table 1: T1 = 200 sin(W t), at rest.
      c.torque1.kind = Torque::Kind::sinusoidal;
      c.torque1.amplitude_n_m = 200.0 * table_unit;
      c.torque1.angular_frequency_rad_per_s = case3_angular_frequency_rad_per_s;
      c.integrator.end_time_s = 0.04;
      break;
    default:
      throw InputError("case", std::to_string(number), "1, 2 or 3 (Table 1 of the paper)");
  }
  return c;
}

SimulationCase paper_case(int number, const PaperReading& reading) {
  SimulationCase c =
      paper_case(number, reading.torque_unit, reading.case3_angular_frequency_rad_per_s);
  c.model.damping_form = reading.damping_form;
  c.model.damping_stiffness = reading.damping_stiffness;
  c.model.restitution = reading.restitution;
  c.model.coast_phase = reading.coast_phase;
  c.model.stiffness.moment_sign = reading.moment_sign;
  return c;
}

SimulationCase driven_loose_gear(double k_n_per_m, double mean_speed_rad_per_s, double order,
                                 double amplitude_rad_per_s, double drag_n_m) {
  SimulationCase c = paper_case(1);
  c.model.friction_coefficient = 0.0;
  c.model.damping_update = DampingUpdate::off;
  c.model.mesh_stiffness = MeshStiffnessMode::constant;
  c.model.constant_mesh_stiffness_n_per_m = k_n_per_m;
  c.torque1 = Torque{};
  c.torque1.kind = Torque::Kind::prescribed_speed;
  c.torque1.mean_speed_rad_per_s = mean_speed_rad_per_s;
  c.torque1.driver_orders = {order};
  c.torque1.driver_speed_amplitudes_rad_per_s = {amplitude_rad_per_s};
  c.torque1.harmonic_phases_rad = {pi / 2.0};
  c.torque2 = Torque{};
  c.torque2.kind = Torque::Kind::drag;
  c.torque2.drag_constant_n_m = drag_n_m;
  const GearPair& g = c.gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const double m2 = moment_of_inertia(g, Gear::two) / (rb2 * rb2);
  const double w = order * mean_speed_rad_per_s;
  const double r2 = m2 * w * w / k_n_per_m;
  c.initial.theta1_rad = 0.0;
  c.initial.theta2_rad = -(g.backlash_m + drag_n_m / (rb2 * k_n_per_m)) / rb2;
  c.initial.w1_rad_per_s = mean_speed_rad_per_s + amplitude_rad_per_s;
  c.initial.w2_rad_per_s = rb1 * (mean_speed_rad_per_s + amplitude_rad_per_s / (1.0 - r2)) / rb2;
  return c;
}

}  // namespace gearimpact
