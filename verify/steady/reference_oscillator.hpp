// A reference integrator for the steady-state suites only: classical RK4 for the dimensionless
// clearance oscillator of docs/steady-state.md section 2,
//   x'' + 2 zeta x' + kappa f(x) = F_m + F_a W cos(Omega tau),
// with f(x) = x - 1 (x > 1), 0 (|x| <= 1), x + 1 (x < -1) (or f(x) = x, Hill's equation when
// the forces are 0), W = 1 or Omega^2 and a stiffness ratio kappa held constant over a call.
// It is not the gear model: it is the independent system the steady-state numerics are tested
// on.
//
// f has corners at x = +-1, where a fixed RK4 step loses its order. Each step is therefore taken
// with the branch of f of its starting region (a linear, smooth right-hand side); when the step
// ends outside that region the crossing is located by bisection on the step length, the step is
// cut there, the region switches, and the rest of the step follows. The RK4 order is kept, and
// the regions visited are exact up to grazing excursions shorter than a step.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "gearimpact/steady/closed_forms.hpp"

namespace gearimpact::verify {

enum class Restoring { clearance, linear };

struct OscillatorParameters {
  double damping_ratio = 0.0;
  double mean_force = 0.0;
  double alternating_force = 0.0;
  ExcitationForm form = ExcitationForm::torque_fluctuation;
  double frequency_ratio = 1.0;
  double stiffness_ratio = 1.0;
  Restoring restoring = Restoring::clearance;
};

// What one integration saw: the regions entered and the extremes of x at the grid points and
// crossings.
struct OscillatorRecord {
  bool lost_drive_contact = false;  // entered |x| <= 1
  bool reached_coast = false;       // entered x < -1
  double min_x = std::numeric_limits<double>::infinity();
  double max_x = -std::numeric_limits<double>::infinity();
  void see(double x) {
    min_x = std::min(min_x, x);
    max_x = std::max(max_x, x);
  }
};

class ReferenceOscillator {
 public:
  explicit ReferenceOscillator(const OscillatorParameters& p) : p_(p) {}

  double period() const { return 2.0 * std::numbers::pi / p_.frequency_ratio; }

  // Integrates (x, x') from tau0 to tau1 in `steps` equal steps (plus the cuts at crossings).
  Eigen::Vector2d integrate(Eigen::Vector2d y, double tau0, double tau1, int steps,
                            OscillatorRecord* record = nullptr) const {
    const double h = (tau1 - tau0) / steps;
    int region = region_of(y);
    if (record != nullptr) record->see(y[0]);
    for (int i = 0; i < steps; ++i) {
      double tau = tau0 + i * h;
      const double step_end = i + 1 == steps ? tau1 : tau0 + (i + 1) * h;
      while (tau < step_end) {
        double remaining = step_end - tau;
        Eigen::Vector2d next = rk4(y, tau, remaining, region);
        const double boundary = crossed_boundary(next[0], region);
        if (std::isnan(boundary)) {
          y = next;
          tau = step_end;
        } else {
          // The crossing inside (0, remaining): bisection on the step length to a few ulps of
          // tau, so that the cut lands on x = boundary to rounding.
          double inside = 0.0;
          double outside = remaining;
          while (outside - inside > 1e-15 * std::max(1.0, std::fabs(tau))) {
            const double middle = 0.5 * (inside + outside);
            const double x = rk4(y, tau, middle, region)[0];
            (std::isnan(crossed_boundary(x, region)) ? inside : outside) = middle;
          }
          y = rk4(y, tau, outside, region);
          tau += outside;
          region = region_entered(region, boundary);
          if (record != nullptr) {
            record->lost_drive_contact |= region != 1;
            record->reached_coast |= region == -1;
          }
        }
        if (record != nullptr) record->see(y[0]);
      }
    }
    return y;
  }

  // One excitation period from tau = 0 (the excitation's phase zero), `steps` steps.
  Eigen::Vector2d period_map(const Eigen::Vector2d& y, int steps,
                             OscillatorRecord* record = nullptr) const {
    return integrate(y, 0.0, period(), steps, record);
  }

 private:
  int region_of(const Eigen::Vector2d& y) const {
    if (p_.restoring == Restoring::linear) return 1;
    if (y[0] > 1.0 || (y[0] == 1.0 && y[1] >= 0.0)) return 1;
    if (y[0] < -1.0 || (y[0] == -1.0 && y[1] <= 0.0)) return -1;
    return 0;
  }

  // The boundary left when a step of the region's branch ends at x, or NaN if it stays inside.
  double crossed_boundary(double x, int region) const {
    if (p_.restoring == Restoring::linear) return std::numeric_limits<double>::quiet_NaN();
    if (region == 1) return x < 1.0 ? 1.0 : std::numeric_limits<double>::quiet_NaN();
    if (region == -1) return x > -1.0 ? -1.0 : std::numeric_limits<double>::quiet_NaN();
    if (x > 1.0) return 1.0;
    if (x < -1.0) return -1.0;
    return std::numeric_limits<double>::quiet_NaN();
  }

  static int region_entered(int region, double boundary) {
    if (region != 0) return 0;
    return boundary > 0.0 ? 1 : -1;
  }

  double restoring(double x, int region) const {
    if (p_.restoring == Restoring::linear) return x;
    return region == 1 ? x - 1.0 : region == -1 ? x + 1.0 : 0.0;
  }

  Eigen::Vector2d rhs(const Eigen::Vector2d& y, double tau, int region) const {
    const double omega = p_.frequency_ratio;
    const double weight = p_.form == ExcitationForm::torque_fluctuation ? 1.0 : omega * omega;
    const double force = p_.mean_force + p_.alternating_force * weight * std::cos(omega * tau);
    return {y[1],
            force - 2.0 * p_.damping_ratio * y[1] - p_.stiffness_ratio * restoring(y[0], region)};
  }

  Eigen::Vector2d rk4(const Eigen::Vector2d& y, double tau, double h, int region) const {
    const Eigen::Vector2d k1 = rhs(y, tau, region);
    const Eigen::Vector2d k2 = rhs(y + 0.5 * h * k1, tau + 0.5 * h, region);
    const Eigen::Vector2d k3 = rhs(y + 0.5 * h * k2, tau + 0.5 * h, region);
    const Eigen::Vector2d k4 = rhs(y + h * k3, tau + h, region);
    return y + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }

  OscillatorParameters p_;
};

// One point of a slow sweep: the steady period recorded after the transient.
struct SweepPoint {
  double frequency_ratio = 0.0;
  OscillatorRecord last_period;
  double half_peak_to_peak() const { return 0.5 * (last_period.max_x - last_period.min_x); }
};

// A slow sweep over `grid` in the given order: each point starts from the state the previous
// one ended in (the first from `start`), runs `transient_periods` periods, and records one more.
inline std::vector<SweepPoint> slow_sweep(OscillatorParameters p, const std::vector<double>& grid,
                                          Eigen::Vector2d start, int transient_periods,
                                          int steps_per_period) {
  std::vector<SweepPoint> points;
  Eigen::Vector2d y = start;
  for (double omega : grid) {
    p.frequency_ratio = omega;
    const ReferenceOscillator oscillator(p);
    for (int i = 0; i < transient_periods; ++i) y = oscillator.period_map(y, steps_per_period);
    SweepPoint point;
    point.frequency_ratio = omega;
    y = oscillator.period_map(y, steps_per_period, &point.last_period);
    points.push_back(point);
  }
  return points;
}

}  // namespace gearimpact::verify
