#include "gearimpact/paper/table1.hpp"

#include <string>

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

}  // namespace gearimpact
