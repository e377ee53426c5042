#include "gearimpact/dynamics/drive.hpp"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

// Kloss's law, docs/vibration.md (Drive and load).
double induction_motor_torque_n_m(const Torque& motor, double w_rad_per_s) {
  const double s = 1.0 - w_rad_per_s / motor.synchronous_speed_rad_per_s;
  const double sb = motor.breakdown_slip;
  return 2.0 * motor.breakdown_torque_n_m * s * sb / (s * s + sb * sb);
}

double induction_motor_steady_slip(double breakdown_torque_n_m, double breakdown_slip,
                                   double load_torque_n_m) {
  const double beta = breakdown_torque_n_m / load_torque_n_m;
  // beta - sqrt(beta^2 - 1) = 1 / (beta + sqrt(beta^2 - 1)), without the
  // cancellation at large beta (a light load).
  return breakdown_slip / (beta + std::sqrt(beta * beta - 1.0));
}

double reflected_inertia_kg_m2(const SimulationCase& c) {
  const double ratio = base_radius(c.gears, Gear::one) / base_radius(c.gears, Gear::two);
  double j1 = moment_of_inertia(c.gears, Gear::one);
  double j2 = moment_of_inertia(c.gears, Gear::two);
  if (c.shafts.kind == ShaftKind::elastic) {
    j1 += c.shafts.motor_inertia_kg_m2;
    j2 += c.shafts.load_inertia_kg_m2;
  }
  return j1 + j2 * ratio * ratio;
}

SpeedControllerGains speed_controller_gains(const Torque& drive, double inertia_kg_m2) {
  SpeedControllerGains g;
  g.inertia_kg_m2 = inertia_kg_m2;
  const double wc = drive.controller_bandwidth_rad_per_s;
  g.proportional_n_m_s = 2.0 * drive.controller_damping_ratio * wc * g.inertia_kg_m2;
  g.integral_n_m = wc * wc * g.inertia_kg_m2;
  return g;
}

SpeedControllerGains speed_controller_gains(const SimulationCase& c) {
  return speed_controller_gains(c.torque1, reflected_inertia_kg_m2(c));
}

SpeedController::SpeedController(const SimulationCase& c, double theta0_rad)
    : SpeedController(
          c.torque1, reflected_inertia_kg_m2(c), theta0_rad,
          {{&c.torque2, base_radius(c.gears, Gear::one) / base_radius(c.gears, Gear::two)}}) {}

SpeedController::SpeedController(const Torque& drive, double inertia_kg_m2, double theta0_rad,
                                 std::vector<ReflectedLoad> loads)
    : drive_(&drive),
      gains_(speed_controller_gains(drive, inertia_kg_m2)),
      theta0_(theta0_rad),
      loads_(std::move(loads)) {}

double SpeedController::torque_n_m(double t_s, double theta_rad, double w_rad_per_s) const {
  const DriverMotion ref = driver_motion(*drive_, theta0_, t_s);
  // Each load at the reference (a drag at its body's speed there), reflected
  // to the driven shaft by the power balance: T_i w_i = T_i ratio_i w.
  double load = 0.0;
  for (std::size_t i = 0; i < loads_.size(); ++i) {
    const Torque& t = *loads_[i].torque;
    const double ratio = loads_[i].ratio;
    const double value = t.kind == Torque::Kind::drag
                             ? drag_torque_n_m(t, ref.speed_rad_per_s * ratio)
                             : torque_at(t, t_s);
    load = i == 0 ? value * ratio : load + value * ratio;
  }
  const double feed_forward = -load + gains_.inertia_kg_m2 * ref.acceleration_rad_per_s2;
  return feed_forward + gains_.proportional_n_m_s * (ref.speed_rad_per_s - w_rad_per_s) +
         gains_.integral_n_m * (ref.theta_rad - theta_rad);
}

SpeedDriftMonitor::SpeedDriftMonitor(const Torque& drive, double settle_s, double t0_s,
                                     double theta0_rad, double w0_rad_per_s)
    : reference_(has_speed_reference(drive) ? &drive : nullptr),
      w0_(w0_rad_per_s),
      settle_s_(settle_s),
      last_t_(t0_s),
      last_theta_(theta0_rad),
      crossing_t_(t0_s),
      next_level_(theta0_rad + 2.0 * pi) {}

double SpeedDriftMonitor::reference_angle(double t_s) const {
  return reference_ != nullptr ? driver_motion(*reference_, 0.0, t_s).theta_rad : w0_ * t_s;
}

void SpeedDriftMonitor::observe(double t_s, double theta_rad) {
  while (theta_rad >= next_level_ && theta_rad > last_theta_) {
    const double t =
        last_t_ + (next_level_ - last_theta_) / (theta_rad - last_theta_) * (t_s - last_t_);
    const double span = t - crossing_t_;
    if (span > 0.0 && crossing_t_ >= settle_s_) {
      const double reference = (reference_angle(t) - reference_angle(crossing_t_)) / span;
      const double drift = std::fabs(2.0 * pi / span / reference - 1.0);
      max_ = std::max(max_.value_or(0.0), drift);
    }
    crossing_t_ = t;
    next_level_ += 2.0 * pi;
  }
  last_t_ = t_s;
  last_theta_ = theta_rad;
}

TachoEdges::TachoEdges(const Tacho& tacho, double theta0_rad)
    : spacing_(2.0 * pi / tacho.pulses_per_revolution), offset_(tacho.offset_rad) {
  next_ = static_cast<long long>(std::floor((theta0_rad - offset_) / spacing_)) + 1;
}

void TachoEdges::step(double t_a, double theta_a, double t_b, double theta_b,
                      const std::function<double(double)>& angle_at) {
  const double width = t_b - t_a;
  while (theta_b >= level(next_)) {
    const double target = level(next_);
    double at = t_b;
    if (theta_a >= target) {
      // Reached at the step's start already (the angle turned back within a
      // step and came again): the edge is at the start.
      at = t_a;
    } else if (theta_b > target) {
      const auto value = [&](double t) { return angle_at(t) - target; };
      std::uintmax_t iterations = 200;
      const auto close_enough = [width](double lo, double hi) {
        return hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * width ||
               std::nextafter(lo, hi) >= hi;
      };
      const std::pair<double, double> bracket = boost::math::tools::toms748_solve(
          value, t_a, t_b, theta_a - target, theta_b - target, close_enough, iterations);
      at = 0.5 * (bracket.first + bracket.second);
    }
    times_.push_back(at);
    ++next_;
    // A further edge in this step lies after this one.
    t_a = at;
    theta_a = target;
  }
}

}  // namespace gearimpact
