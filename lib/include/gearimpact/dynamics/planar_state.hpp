// The state and the time-series row of the planar dynamics
// (gearimpact/dynamics/planar.hpp), which a SimulationResult carries.
#pragma once

namespace gearimpact {

// The planar state. The motor and load angles are read with shafts only
// (theta measured as the gear's own: the motor's as theta1, the load's as theta2).
struct PlanarState {
  double x1_m = 0.0, y1_m = 0.0, theta1_rad = 0.0;
  double x2_m = 0.0, y2_m = 0.0, theta2_rad = 0.0;
  double theta_motor_rad = 0.0, theta_load_rad = 0.0;
  double vx1_m_s = 0.0, vy1_m_s = 0.0, w1_rad_per_s = 0.0;
  double vx2_m_s = 0.0, vy2_m_s = 0.0, w2_rad_per_s = 0.0;
  double w_motor_rad_per_s = 0.0, w_load_rad_per_s = 0.0;
};

// One row of the planar time series (every integrator.output_every-th step).
struct PlanarRow {
  double t_s = 0.0;
  PlanarState state;
  // The force each bearing exerts on its gear, -k u - c u'.
  double bearing_fx1_n = 0.0, bearing_fy1_n = 0.0;
  double bearing_fx2_n = 0.0, bearing_fy2_n = 0.0;
  // The normal forces summed over the loaded pairs of each side, and the
  // side's penetration delta_d = s_d - B, delta_c = -s_c - B (docs/vibration.md).
  double drive_force_n = 0.0, coast_force_n = 0.0;
  double drive_penetration_m = 0.0, coast_penetration_m = 0.0;
};

}  // namespace gearimpact
