#include "gearimpact/dynamics/system.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

double torque_at(const Torque& torque, double t_s) {
  switch (torque.kind) {
    case Torque::Kind::constant:
      return torque.constant_n_m;
    case Torque::Kind::sinusoidal:
      return torque.mean_n_m +
             torque.amplitude_n_m *
                 std::sin(torque.angular_frequency_rad_per_s * t_s + torque.phase_rad);
    case Torque::Kind::harmonic: {
      double sum = torque.mean_n_m;
      for (std::size_t i = 0; i < torque.harmonic_amplitudes_n_m.size(); ++i) {
        sum += torque.harmonic_amplitudes_n_m[i] *
               std::sin(torque.harmonic_angular_frequencies_rad_per_s[i] * t_s +
                        torque.harmonic_phases_rad[i]);
      }
      return sum;
    }
    case Torque::Kind::user:
      return torque.user(t_s);
    case Torque::Kind::profile:
      return profile_at(torque.profile_times_s, torque.profile_torques_n_m, t_s).value;
    case Torque::Kind::prescribed_speed:
    case Torque::Kind::drag:
    case Torque::Kind::speed_controlled:
    case Torque::Kind::induction_motor:
      // The driver's torque depends on the mesh force, the drag on w2, the
      // controller's and the motor's on the driven body's motion: the
      // systems' right-hand sides compute them from the state.
      break;
  }
  throw std::logic_error("torque_at of a torque that depends on the state");
}

double drag_torque_n_m(const Torque& drag, double w_rad_per_s) {
  return -(drag.drag_constant_n_m * std::tanh(w_rad_per_s / drag.drag_speed_scale_rad_per_s) +
           drag.drag_viscous_n_m_s * w_rad_per_s);
}

double mean_torque_n_m(const Torque& torque, const char* field) {
  switch (torque.kind) {
    case Torque::Kind::constant:
      return torque.constant_n_m;
    case Torque::Kind::sinusoidal:
    case Torque::Kind::harmonic:
      return torque.mean_n_m;
    case Torque::Kind::user:
      throw InputError(
          std::string(field) + ".kind", "user",
          "constant, sinusoidal or harmonic: the mean of a torque function is not known");
    case Torque::Kind::prescribed_speed:
    case Torque::Kind::drag:
    case Torque::Kind::speed_controlled:
    case Torque::Kind::induction_motor:
    case Torque::Kind::profile:
      break;
  }
  const char* kind = torque.kind == Torque::Kind::drag               ? "drag"
                     : torque.kind == Torque::Kind::speed_controlled ? "speed-controlled"
                     : torque.kind == Torque::Kind::induction_motor  ? "induction-motor"
                     : torque.kind == Torque::Kind::profile          ? "profile"
                                                                     : "prescribed-speed";
  throw InputError(std::string(field) + ".kind", kind,
                   "constant, sinusoidal or harmonic: a driver's, a controller's or a motor's "
                   "torque and a drag follow the motion, and a profile's mean depends on the "
                   "run's length, so their mean is not known before the run");
}

GearSystem::GearSystem(const SimulationCase& c, const StiffnessTable& table,
                       const RunControl& control)
    : case_(c), mesh_(c, table) {
  const GearPair& g = c.gears;
  j1_ = moment_of_inertia(g, Gear::one);
  j2_ = moment_of_inertia(g, Gear::two);
  driven_ = c.torque1.kind == Torque::Kind::prescribed_speed;
  const bool controlled = c.torque1.kind == Torque::Kind::speed_controlled;
  induction_ = c.torque1.kind == Torque::Kind::induction_motor;
  if ((driven_ || controlled) && control.resume) {
    // A continued run carries theta1 on from where it stopped, whatever time
    // it restarts at (the steady state's runs restart theirs at 0).
    driver_theta0_ = control.resume->state.theta1_rad -
                     driver_motion(c.torque1, 0.0, control.resume->time_s).theta_rad;
  } else {
    driver_theta0_ = c.initial.theta1_rad;
  }
  if (controlled) controller_ = std::make_shared<const SpeedController>(c, driver_theta0_);
  drag_ = c.torque2.kind == Torque::Kind::drag;
  constant_torques_ =
      c.torque1.kind == Torque::Kind::constant && c.torque2.kind == Torque::Kind::constant;
  if (constant_torques_) torque_values_ = {c.torque1.constant_n_m, c.torque2.constant_n_m};
}

std::pair<double, double> GearSystem::torques(double t) const {
  if (!constant_torques_ && t != torque_time_) {
    torque_time_ = t;
    // The driver's torque and the drag are set by rhs from the state.
    torque_values_ = {driven_ || controller_ || induction_ ? 0.0 : torque_at(case_.torque1, t),
                      drag_ ? 0.0 : torque_at(case_.torque2, t)};
  }
  return torque_values_;
}

void GearSystem::impose_driver(double t, State& y) const {
  if (!driven_) return;
  const DriverMotion m = driver_motion(case_.torque1, driver_theta0_, t);
  y[kTheta1] = m.theta_rad;
  y[kW1] = m.speed_rad_per_s;
}

void GearSystem::rhs(double t, const State& y_in, const Mode& m, const ContactMemory& d,
                     State& dydt, ContactTotals* totals) const {
  auto [t1, t2] = torques(t);
  // A driven pinion is where its closed form puts it, whatever the stage
  // state an integrator passes.
  State driven_state;
  DriverMotion driver;
  if (driven_) {
    driver = driver_motion(case_.torque1, driver_theta0_, t);
    driven_state = y_in;
    driven_state[kTheta1] = driver.theta_rad;
    driven_state[kW1] = driver.speed_rad_per_s;
  }
  const State& y = driven_ ? driven_state : y_in;
  if (drag_) t2 = drag_torque_n_m(case_.torque2, y[kW2]);
  if (controller_) t1 = controller_->torque_n_m(t, y[kTheta1], y[kW1]);
  if (induction_) t1 = induction_motor_torque_n_m(case_.torque1, y[kW1]);
  const double w1 = y[kW1];
  const double w2 = y[kW2];
  double moment1 = t1;
  double moment2 = t2;
  // The mesh's forces: (1),(3), (43),(45); in free flight, (2),(44): J w' = T.
  MeshPowers powers;
  mesh_.add_forces({y[kTheta1], y[kTheta2], w1, w2}, m, d, moment1, moment2, powers, totals);
  if (driven_) {
    // The driver applies the torque that gives the pinion its prescribed
    // acceleration against the mesh (moment1 holds the mesh's moments, t1 = 0):
    // J1 w1' = T_driver + moment1. Its work is the ledger's torque work.
    t1 = j1_ * driver.acceleration_rad_per_s2 - moment1;
    moment1 += t1;
  }
  dydt[kTheta1] = w1;
  dydt[kTheta2] = w2;
  dydt[kW1] = moment1 / j1_;
  dydt[kW2] = moment2 / j2_;
  dydt[kTorqueWork] = t1 * w1 + t2 * w2;
  dydt[kDampingLoss] = powers.damping_w;
  dydt[kFrictionLoss] = powers.friction_w;
  dydt[kParametricWork] = powers.parametric_w;
  dydt[kMeshDampingLoss] = powers.mesh_damping_w;
}

bool GearSystem::mode_holds(const State& y, const Mode& m, const ContactMemory& d) const {
  // Not zeroed: only the n values set are read.
  EventValues g;
  const int n = event_values(y, m, d, g);
  for (int i = 0; i < n; ++i) {
    if (g[i] < 0.0) return false;
  }
  return true;
}

}  // namespace gearimpact
