// Everything a simulation run needs, as plain values in SI: the gear pair, the
// external torques, the initial state, the model options where the paper is
// ambiguous (MODEL.md, sections Contact, damping, friction and Readings) and
// the integrator settings. Case files (TOML) and the paper's Table 1 both
// produce one of these; the dynamics consumes it.
#pragma once

#include <functional>
#include <string>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

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

// (32): the three published forms of the damping factor D.
enum class DampingForm {
  herbert_mcwhannell,  // D = 6 K (1 - e) / {[(2e - 1)^2 + 3] Vi}  (default)
  hunt_crossley,       // D = 3 K (1 - e) / (2 Vi)
  lee_wang,            // D = 3 K (1 - e) / (4 Vi)
};

// Which stiffness K enters (32).
enum class DampingStiffness {
  current_pair,          // each loaded pair's current Ke (default)
  pitch_pair_at_impact,  // Ke of the pair nearest the pitch point, frozen at impact
  hertz,                 // Kh of (4)
};

// (33) e = 1 - c (Vi / speed_unit)^p.
struct RestitutionLaw {
  double coefficient = 0.022;
  double exponent = 0.375;         // 3/8; 0.36 is the alternative reading
  double speed_unit_m_s = 1.0e-3;  // Vi in mm/s (default); 0.0254 for in/s, 1 for m/s
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
