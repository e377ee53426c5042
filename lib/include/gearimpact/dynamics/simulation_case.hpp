// Everything a simulation run needs, as plain values in SI: the gear pair, the
// external torques, the initial state, the model options where the paper is
// ambiguous (MODEL.md, sections Contact, damping, friction and Readings) and
// the integrator settings. Case files (TOML) and the paper's Table 1 both
// produce one of these; the dynamics consumes it.
#pragma once

#include <functional>
#include <string>

#include "gearimpact/contact/contact.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/model.hpp"

namespace gearimpact {

// One external torque T_i(t), N m.
struct Torque {
  enum class Kind { constant, sinusoidal, user };
  Kind kind = Kind::constant;
  double constant_n_m = 0.0;   // Kind::constant: T
  double amplitude_n_m = 0.0;  // Kind::sinusoidal: A sin(W t + phase)
  double angular_frequency_rad_s = 0.0;
  double phase_rad = 0.0;
  std::function<double(double)> user;  // Kind::user: T(t_s), through the library API only
};

// theta in rad, w in rad/s. theta1 = theta2 = 0 centres the teeth in the backlash.
struct InitialState {
  double theta1_rad = 0.0;
  double theta2_rad = 0.0;
  double w1_rad_s = 0.0;
  double w2_rad_s = 0.0;
};

struct ModelOptions {
  double friction_coefficient = 0.04;  // f of (35)
  DampingForm damping_form = DampingForm::herbert_mcwhannell;
  DampingStiffness damping_stiffness = DampingStiffness::current_pair;
  RestitutionLaw restitution;
  CoastPhase coast_phase = CoastPhase::half_base_pitch;
  StiffnessModel stiffness;  // quadrature method and the sign of the Fa h moment
};

enum class IntegratorKind { rk4, adaptive };

struct IntegratorSettings {
  IntegratorKind kind = IntegratorKind::rk4;
  double step_s = 1.0e-7;  // fixed RK4 step (the adaptive one's first step)
  double end_time_s = 0.03;
  double adaptive_relative_tolerance = 1e-10;
  int output_every = 1;  // keep every n-th row of the time series
};

struct SimulationCase {
  std::string name;
  GearPair gears;
  Torque torque1;
  Torque torque2;
  InitialState initial;
  ModelOptions model;
  IntegratorSettings integrator;
};

}  // namespace gearimpact
