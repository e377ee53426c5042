#include "gearimpact/paper/table1.hpp"

#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

double torque_unit_n_m(TorqueUnit unit) {
  // 1 kgf = 9.80665 N (standard gravity), 1 mm = 1e-3 m.
  return unit == TorqueUnit::kgf_mm ? 9.80665e-3 : 1.0e-3;
}

SimulationCase paper_case(int number, TorqueUnit unit, double case3_angular_frequency_rad_s) {
  SimulationCase c;
  c.name = "case" + std::to_string(number);
  c.gears = paper_gear_pair();
  const double table_unit = torque_unit_n_m(unit);
  switch (number) {
    case 1:  // Table 1: no torques, w1(0) = 50 rad/s.
      c.initial.w1_rad_s = 50.0;
      break;
    case 2:  // Table 1: T1 = 50, T2 = -50, w1(0) = 50 rad/s.
      c.torque1.constant_n_m = 50.0 * table_unit;
      c.torque2.constant_n_m = -50.0 * table_unit;
      c.initial.w1_rad_s = 50.0;
      break;
    case 3:  // Table 1: T1 = 200 sin(W t), at rest.
      c.torque1.kind = Torque::Kind::sinusoidal;
      c.torque1.amplitude_n_m = 200.0 * table_unit;
      c.torque1.angular_frequency_rad_s = case3_angular_frequency_rad_s;
      c.integrator.end_time_s = 0.04;
      break;
    default:
      throw InputError("case", std::to_string(number), "1, 2 or 3 (Table 1 of the paper)");
  }
  return c;
}

SimulationCase paper_case(int number, const PaperReading& reading) {
  SimulationCase c = paper_case(number, reading.torque_unit, reading.case3_angular_frequency_rad_s);
  c.model.damping_form = reading.damping_form;
  c.model.damping_stiffness = reading.damping_stiffness;
  c.model.restitution = reading.restitution;
  c.model.coast_phase = reading.coast_phase;
  c.model.stiffness.moment_sign = reading.moment_sign;
  return c;
}

}  // namespace gearimpact
