#include "gearimpact/io/schema.hpp"

#include <cmath>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

void require_finite(const char* field, double value, const std::string& allowed) {
  if (!std::isfinite(value)) throw InputError(field, value, allowed);
}

void validate_torque(const char* field, const Torque& torque) {
  const std::string name(field);
  switch (torque.kind) {
    case Torque::Kind::constant:
      require_finite((name + ".constant").c_str(), torque.constant_n_m, "a finite torque in N m");
      break;
    case Torque::Kind::sinusoidal:
      require_finite((name + ".amplitude").c_str(), torque.amplitude_n_m, "a finite torque in N m");
      require_finite((name + ".angular_frequency").c_str(), torque.angular_frequency_rad_s,
                     "a finite value in rad/s");
      require_finite((name + ".phase").c_str(), torque.phase_rad, "a finite value in rad");
      break;
    case Torque::Kind::harmonic:  // checked with the model options (dynamics/simulate.cpp)
      break;
    case Torque::Kind::user:
      if (!torque.user) throw InputError(name + ".user", "empty", "a callable T(t_s) in N m");
      break;
  }
}

}  // namespace

void validate_fields(const SimulationCase& c) {
  validate(c.gears);
  validate_torque("torque1", c.torque1);
  validate_torque("torque2", c.torque2);
  require_finite("theta1", c.initial.theta1_rad, "a finite angle in rad");
  require_finite("theta2", c.initial.theta2_rad, "a finite angle in rad");
  require_finite("w1", c.initial.w1_rad_s, "a finite speed in rad/s");
  require_finite("w2", c.initial.w2_rad_s, "a finite speed in rad/s");
  const ModelOptions& m = c.model;
  if (!std::isfinite(m.friction_coefficient) || m.friction_coefficient < 0.0) {
    throw InputError("friction", m.friction_coefficient, "a finite value >= 0");
  }
  if (!std::isfinite(m.restitution.coefficient) || m.restitution.coefficient < 0.0) {
    throw InputError("restitution_coefficient", m.restitution.coefficient,
                     "a finite value >= 0 (c of (33) e = 1 - c Vi^p)");
  }
  if (!std::isfinite(m.restitution.exponent) || m.restitution.exponent <= 0.0 ||
      m.restitution.exponent > 1.0) {
    throw InputError("restitution_exponent", m.restitution.exponent,
                     "(0, 1] (p of (33) e = 1 - c Vi^p)");
  }
  if (!std::isfinite(m.restitution.speed_unit_m_s) || m.restitution.speed_unit_m_s <= 0.0) {
    throw InputError("restitution_speed_unit", m.restitution.speed_unit_m_s,
                     "a finite value > 0 in m/s (the unit of Vi in (33))");
  }
  const IntegratorSettings& s = c.integrator;
  if (!std::isfinite(s.end_time_s) || s.end_time_s <= 0.0) {
    throw InputError("end_time", s.end_time_s, "a finite value > 0 s");
  }
  if (s.output_every < 1) {
    throw InputError("output_every", std::to_string(s.output_every), "an integer >= 1");
  }
  if (!std::isfinite(s.adaptive_relative_tolerance) || s.adaptive_relative_tolerance < 1e-14 ||
      s.adaptive_relative_tolerance > 1e-3) {
    throw InputError("adaptive_relative_tolerance", s.adaptive_relative_tolerance, "[1e-14, 1e-3]");
  }
  if (!std::isfinite(s.step_s) || s.step_s <= 0.0) {
    throw InputError("step", s.step_s, "a finite value > 0 s");
  }
}

}  // namespace gearimpact
