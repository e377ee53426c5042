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
  // A helical pair's axial forces (along +z) and tilting moments (about +y
  // at the gears' centres) of those normal forces (HelicalThrust of
  // geometry/helical.hpp): reported, acting on nothing; 0 for a spur pair.
  double axial_force1_n = 0.0, axial_force2_n = 0.0;
  double tilting_moment1_n_m = 0.0, tilting_moment2_n_m = 0.0;
};

// One sample of a planar run at t = t0 + n / fs exactly (sample_time_s of
// simulate.hpp), from RK4's continuous extension inside the accepted step that
// holds it, as SampleRow: at an event time the left limit.
struct PlanarSample {
  double t_s = 0.0;
  PlanarState state;  // positions and velocities at t_s (dense output)
  // Accelerations (RunControl::sample): interval averages, the velocity
  // difference over [t_{n-1}, t_n] of the dense output over its length, or
  // under SampleKind::point the equations of motion at the sampled state (not
  // the interpolant's derivative, which is an order less accurate).
  double ax1_m_per_s2 = 0.0, ay1_m_per_s2 = 0.0, alpha1_rad_per_s2 = 0.0;
  double ax2_m_per_s2 = 0.0, ay2_m_per_s2 = 0.0, alpha2_rad_per_s2 = 0.0;
  double bearing_fx1_n = 0.0, bearing_fy1_n = 0.0, bearing_fx2_n = 0.0, bearing_fy2_n = 0.0;
  double dte_m = 0.0;  // s_d - B (drive line, as SampleRow::dte_m)
  double drive_force_n = 0.0, coast_force_n = 0.0;
  // The sensor's gear centre's acceleration along its direction
  // ([bearings] sensor_gear, sensor_angle).
  double sensor_acceleration_m_per_s2 = 0.0;
};

}  // namespace gearimpact
