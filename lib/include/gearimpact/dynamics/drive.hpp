// The drive and the load of a run (docs/vibration.md, section Drive and
// load): the torque of a speed controller and of an induction motor on the
// driven body (the motor with [shafts], the pinion otherwise), the gains of
// the controller from the train's inertia, and the check of a run's mean
// speed against its reference.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"

namespace gearimpact {

// Kloss's torque-speed law of an induction motor (its equivalent circuit
// without stator resistance): T = 2 T_b / (s / s_b + s_b / s) with the slip
// s = 1 - w / w_s, computed as 2 T_b s s_b / (s^2 + s_b^2), which is 0 at
// s = 0 rather than 0 / 0. Motoring for 0 < s, braking above w_s.
double induction_motor_torque_n_m(const Torque& motor, double w_rad_per_s);

// The slip at which Kloss's law carries the load torque 0 < T_L <= T_b on the
// stable branch (s* <= s_b): 2 beta = s/s_b + s_b/s with beta = T_b / T_L, the
// smaller root s* = s_b (beta - sqrt(beta^2 - 1)).
double induction_motor_steady_slip(double breakdown_torque_n_m, double breakdown_slip,
                                   double load_torque_n_m);

// The inertia of the train reflected to the driven shaft, turning with the
// pinion: J1 + J2 (Rb1/Rb2)^2, and with [shafts] (elastic bearings) the
// motor's J_m and the load's J_L (Rb1/Rb2)^2 added.
double reflected_inertia_kg_m2(const SimulationCase& c);

// The gains of a speed controller on a train of reflected inertia J_eq:
// K_p = 2 zeta_c w_c J_eq, K_i = w_c^2 J_eq, w_c = 2 pi f_c, so that a rigid
// train's speed error obeys e'' + 2 zeta_c w_c e' + w_c^2 e = 0.
struct SpeedControllerGains {
  double inertia_kg_m2 = 0.0;  // J_eq
  double proportional_n_m_s = 0.0;
  double integral_n_m = 0.0;
};
SpeedControllerGains speed_controller_gains(const SimulationCase& c);

// The torque of torque1.kind = "speed-controlled" on the driven body:
//   T = T_ff + K_p (W_ref(t) - w) + K_i (theta_ref(t) - theta),
// theta_ref(t) = theta0 + Int W_ref dt (driver_motion), so that the integral
// of the speed error is the angle error and needs no state of its own; the
// feed-forward T_ff = -T2 Rb1/Rb2 + J_eq W_ref' holds the load (torque2 at t,
// a drag at the reference's wheel speed) and the reference's acceleration.
// A load the controller's feed-forward holds: a torque on a body turning at
// `ratio` times the driven body's speed when the train rolls without slip.
struct ReflectedLoad {
  const Torque* torque = nullptr;
  double ratio = 0.0;
};
class SpeedController {
 public:
  // theta0: the reference's angle at t = 0 (the driven body's initial angle).
  SpeedController(const SimulationCase& c, double theta0_rad);
  // A train's: the controller `drive` on a body whose train has the
  // reflected inertia J_eq, against `loads` (the train's other torques, each
  // the caller keeps alive), whose sum T_i ratio_i the feed-forward holds.
  SpeedController(const Torque& drive, double inertia_kg_m2, double theta0_rad,
                  std::vector<ReflectedLoad> loads);
  double torque_n_m(double t_s, double theta_rad, double w_rad_per_s) const;
  const SpeedControllerGains& gains() const { return gains_; }

 private:
  const Torque* drive_;
  SpeedControllerGains gains_;
  double theta0_ = 0.0;
  std::vector<ReflectedLoad> loads_;
};

// The gains of a speed controller `drive` on a train of reflected inertia J_eq.
SpeedControllerGains speed_controller_gains(const Torque& drive, double inertia_kg_m2);

// The drift check: over each whole revolution of a body (the pinion, a train's first body)
// from its start that begins at or after settle_s (drive.settle), the mean speed 2 pi / dt
// against the reference's mean over that interval (the angle change over dt of the body's
// torque `drive` where it has a speed reference, else of its initial speed under torques).
// observe() takes the end of each accepted step, and places each crossing of theta(0) + 2 pi k
// between two steps' ends by linear interpolation (the step is a small fraction of a revolution).
class SpeedDriftMonitor {
 public:
  SpeedDriftMonitor(const Torque& drive, double settle_s, double t0_s, double theta0_rad,
                    double w0_rad_per_s);
  void observe(double t_s, double theta_rad);
  // max |mean / reference mean - 1| over the whole revolutions; none before one.
  std::optional<double> max_relative_drift() const { return max_; }

 private:
  double reference_angle(double t_s) const;
  const Torque* reference_ = nullptr;
  double w0_ = 0.0;
  double settle_s_ = 0.0;
  double last_t_ = 0.0, last_theta_ = 0.0;
  double crossing_t_ = 0.0;  // the last crossing (the start at first)
  double next_level_ = 0.0;
  std::optional<double> max_;
};

// A tacho's edges (Tacho): each upward crossing of offset + 2 pi k / PPR by
// the shaft's angle, located inside the accepted step that holds it by TOMS
// 748 on the step's continuous extension (or a driver's closed form), to the
// event location's tolerance, 4 eps of the step.
class TachoEdges {
 public:
  TachoEdges(const Tacho& tacho, double theta0_rad);
  // The step from (t_a, theta_a) to (t_b, theta_b); angle_at(t) inside it.
  void step(double t_a, double theta_a, double t_b, double theta_b,
            const std::function<double(double)>& angle_at);
  const std::vector<double>& times() const { return times_; }

 private:
  double level(long long k) const { return offset_ + spacing_ * static_cast<double>(k); }
  double spacing_ = 0.0;
  double offset_ = 0.0;
  long long next_ = 0;
  std::vector<double> times_;
};

}  // namespace gearimpact
