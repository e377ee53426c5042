#include "gearimpact/dynamics/simulate.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include "gearimpact/constants.hpp"
#include <string>
#include <thread>
#include <utility>

#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/io/schema.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

namespace {

// theta1, theta2, w1, w2, then the ledger integrals: torque work, damping loss,
// friction loss, parametric work (its continuous part).
constexpr std::size_t kStateSize = 8;
using State = std::array<double, kStateSize>;
enum : std::size_t {
  kTheta1,
  kTheta2,
  kW1,
  kW2,
  kTorqueWork,
  kDampingLoss,
  kFrictionLoss,
  kParametricWork
};

constexpr int kMaxPairs = static_cast<int>(LoadedPairs::capacity);
// Region (2) + pair bounds (4) + friction sign and force clipping per pair.
constexpr int kMaxEvents = 2 + 4 + 2 * kMaxPairs;
using EventValues = std::array<double, kMaxEvents>;

// Grazing contacts can have Vi -> 0, where D of (32) grows without bound while
// G = D delta d(delta)/dt stays finite; the floor keeps D finite.
constexpr double kSmallestImpactSpeed_m_s = 1e-9;

// Everything that is constant during a step: which side is in contact, which
// pairs are loaded, the sign of each pair's sliding speed and whether its
// normal force is clipped at zero. The right-hand side is smooth while the mode
// holds; a change of mode is an event.
struct Mode {
  Region region = Region::free;
  int k_first = 0;
  int count = 0;
  std::array<double, kMaxPairs> slip{};  // sign of Vs, +1 or -1
  std::array<bool, kMaxPairs> clipped{};
};

// Fixed at the onset of each contact, (32),(33).
struct ContactDamping {
  double per_stiffness_s_m = 0.0;  // D / K
  double frozen_stiffness_n_m = 0.0;
};

struct ContactTotals {
  double normal_force_n = 0.0;
  double friction_force_n = 0.0;
};

struct StoredEnergy {
  double hertz_j = 0.0;
  double bending_j = 0.0;
  double axial_j = 0.0;
  double total() const { return hertz_j + bending_j + axial_j; }
};

double torque_at(const Torque& torque, double t_s) {
  switch (torque.kind) {
    case Torque::Kind::constant:
      return torque.constant_n_m;
    case Torque::Kind::sinusoidal:
      return torque.amplitude_n_m *
             std::sin(torque.angular_frequency_rad_s * t_s + torque.phase_rad);
    case Torque::Kind::user:
      return torque.user(t_s);
  }
  return 0.0;
}

bool all_finite(const State& y) {
  return std::all_of(y.begin(), y.end(), [](double v) { return std::isfinite(v); });
}

class Mechanics {
 public:
  Mechanics(const SimulationCase& c, const StiffnessTable& table, const RunControl& control)
      : table_(table), case_(c) {
    const GearPair& g = c.gears;
    rb1_ = base_radius(g, Gear::one);
    rb2_ = base_radius(g, Gear::two);
    j1_ = moment_of_inertia(g, Gear::one);
    j2_ = moment_of_inertia(g, Gear::two);
    backlash_ = g.backlash_m;
    lp_ = line_of_action_length(g);
    x_pitch_ = pitch_point_position(g);
    t0_ = base_pitch(g);
    const ContactSegment segment = contact_segment(g);
    xs_ = segment.start_m;
    xe_ = segment.end_m;
    coast_offset_ = c.model.coast_phase == CoastPhase::half_base_pitch ? 0.5 * t0_ : 0.0;
    friction_ = c.model.friction_coefficient;
    kh_ = hertz_stiffness(g);
    constant_k_ = control.constant_mesh_stiffness_n_m;
    damping_on_current_pair_ = c.model.damping_stiffness == DampingStiffness::current_pair;
  }

  // T1(t), T2(t). An RK4 step asks for its middle time twice and for its end
  // time again as the next step's start: the last answer is kept, so a
  // sinusoid costs two sines a step instead of four (the same values).
  std::pair<double, double> torques(double t) const {
    if (t != torque_time_) {
      torque_time_ = t;
      torque_values_ = {torque_at(case_.torque1, t), torque_at(case_.torque2, t)};
    }
    return torque_values_;
  }

  double kinetic_energy(const State& y) const {
    return 0.5 * j1_ * y[kW1] * y[kW1] + 0.5 * j2_ * y[kW2] * y[kW2];
  }
  double s(const State& y) const { return rb1_ * y[kTheta1] - rb2_ * y[kTheta2]; }
  double s_rate(const State& y) const { return rb1_ * y[kW1] - rb2_ * y[kW2]; }
  static double side(Region r) { return r == Region::n1 ? 1.0 : -1.0; }
  // (31): delta = s - B on N1, -s - B on N2.
  double delta(Region r, const State& y) const { return side(r) * s(y) - backlash_; }
  // (42) pairs at X = reference + k t0; on N2 X' from C1', see MODEL.md.
  double reference(Region r, double theta1) const {
    return r == Region::n1 ? x_pitch_ + rb1_ * theta1 : x_pitch_ - rb1_ * theta1 + coast_offset_;
  }

  double pair_position(const Mode& m, const State& y, int j) const {
    return reference(m.region, y[kTheta1]) + (m.k_first + j) * t0_;
  }

  // Ke and dKe/dX of one of `count` loaded pairs at X. Stage states of a step
  // that ends on a pair's entry or exit can reach a hair beyond the segment:
  // there Ke continues along its tangent, so the right-hand side stays smooth.
  void pair_stiffness(double x, int count, double& ke, double& dke) const {
    if (constant_k_ > 0.0) {
      ke = constant_k_ / count;
      dke = 0.0;
      return;
    }
    const double xc = std::clamp(x, xs_, xe_);
    const StiffnessAndDerivative k = table_.stiffness_and_derivative(xc);
    dke = k.derivative_n_per_m2;
    ke = k.stiffness_n_per_m + dke * (x - xc);
  }

  double damping_factor(const ContactDamping& d, double ke) const {
    return damping_on_current_pair_ ? d.per_stiffness_s_m * ke
                                    : d.per_stiffness_s_m * d.frozen_stiffness_n_m;
  }

  // The equations of motion (1)-(3), (43)-(45) in the mode m, and the powers
  // of the ledger.
  void rhs(double t, const State& y, const Mode& m, const ContactDamping& d, State& dydt,
           ContactTotals* totals = nullptr) const {
    const auto [t1, t2] = torques(t);
    const double w1 = y[kW1];
    const double w2 = y[kW2];
    double moment1 = t1;
    double moment2 = t2;
    double damping_power = 0.0;
    double friction_power = 0.0;
    double parametric_power = 0.0;
    if (m.region != Region::free) {
      const double sign = side(m.region);
      const double dl = delta(m.region, y);
      const double dl_rate = sign * s_rate(y);
      const double ref = reference(m.region, y[kTheta1]);
      const double x_rate = sign * rb1_ * w1;
      for (int j = 0; j < m.count; ++j) {
        const double x = ref + (m.k_first + j) * t0_;
        double ke = 0.0;
        double dke = 0.0;
        pair_stiffness(x, m.count, ke, dke);
        // (30), (34)
        const double f_elastic = ke * dl;
        const double g_damping = hertzian_damping_force(damping_factor(d, ke), dl, dl_rate);
        const double n = m.clipped[j] ? 0.0 : f_elastic + g_damping;
        const double vs = sliding_speed(w1, w2, x, lp_);
        // (35)-(38): Ff = f N sign(Vs) on N1, -f N sign(Vs') on N2.
        const double ff = sign * friction_ * n * m.slip[j];
        // (1)-(3): on N1 J1 w1' = T1 - [N Rb1 + Ff X], J2 w2' = T2 + [N Rb2 + Ff (lp - X)];
        // every sign flips on N2.
        moment1 -= sign * (n * rb1_ + ff * x);
        moment2 += sign * (n * rb2_ + ff * (lp_ - x));
        // The damping force is what N adds to F; with N clipped it is -F, so the
        // stored energy released while the tooth cannot push counts as damping loss.
        damping_power += (n - f_elastic) * dl_rate;
        friction_power += friction_ * n * m.slip[j] * vs;
        parametric_power += 0.5 * dl * dl * dke * x_rate;
        if (totals != nullptr) {
          totals->normal_force_n += n;
          totals->friction_force_n += ff;
        }
      }
    }
    dydt[kTheta1] = w1;
    dydt[kTheta2] = w2;
    dydt[kW1] = moment1 / j1_;
    dydt[kW2] = moment2 / j2_;
    dydt[kTorqueWork] = t1 * w1 + t2 * w2;
    dydt[kDampingLoss] = damping_power;
    dydt[kFrictionLoss] = friction_power;
    dydt[kParametricWork] = parametric_power;
  }

  // The mode holds while every value is >= 0; an event is a value turning negative.
  int event_values(const State& y, const Mode& m, const ContactDamping& d, EventValues& g) const {
    const double sv = s(y);
    if (m.region == Region::free) {
      g[0] = backlash_ - sv;
      g[1] = sv + backlash_;
      return 2;
    }
    const double dl = delta(m.region, y);
    g[0] = dl;
    const double ref = reference(m.region, y[kTheta1]);
    const double first = ref + m.k_first * t0_;
    const double last = ref + (m.k_first + m.count - 1) * t0_;
    g[1] = first - xs_;
    g[2] = xs_ - (first - t0_);
    g[3] = xe_ - last;
    g[4] = (last + t0_) - xe_;
    int n = 5;
    const double dl_rate = side(m.region) * s_rate(y);
    for (int j = 0; j < m.count; ++j) {
      const double x = first + j * t0_;
      g[n++] = m.slip[j] * sliding_speed(y[kW1], y[kW2], x, lp_);
      const double push = push_sign_function(x, m.count, d, dl, dl_rate);
      g[n++] = m.clipped[j] ? -push : push;
    }
    return n;
  }

  // A function with the sign and the zeros of F + G of one pair. With D
  // proportional to the pair's own Ke, F + G = Ke delta (1 + (D/K) d(delta)/dt)
  // and the positive factor Ke need not be evaluated.
  double push_sign_function(double x, int count, const ContactDamping& d, double dl,
                            double dl_rate) const {
    if (damping_on_current_pair_) {
      return dl * (1.0 + d.per_stiffness_s_m * dl_rate);
    }
    double ke = 0.0;
    double dke = 0.0;
    pair_stiffness(x, count, ke, dke);
    return ke * dl + hertzian_damping_force(damping_factor(d, ke), dl, dl_rate);
  }

  bool mode_holds(const State& y, const Mode& m, const ContactDamping& d) const {
    EventValues g{};
    const int n = event_values(y, m, d, g);
    for (int i = 0; i < n; ++i) {
      if (g[i] < 0.0) return false;
    }
    return true;
  }

  // Region and loaded pairs of y, with the same tests as event_values.
  Mode classify_geometry(const State& y) const {
    Mode m;
    const double sv = s(y);
    if (sv - backlash_ > 0.0) {
      m.region = Region::n1;
    } else if (-sv - backlash_ > 0.0) {
      m.region = Region::n2;
    } else {
      return m;
    }
    const double ref = reference(m.region, y[kTheta1]);
    int k = static_cast<int>(std::ceil((xs_ - ref) / t0_));
    while (ref + k * t0_ - xs_ < 0.0) ++k;
    while (xs_ - (ref + (k - 1) * t0_) < 0.0) --k;
    m.k_first = k;
    m.count = 0;
    while (m.count < kMaxPairs && xe_ - (ref + (k + m.count) * t0_) >= 0.0) ++m.count;
    return m;
  }

  // Friction signs and clipping of the pairs of m at y.
  void classify_forces(const State& y, const ContactDamping& d, Mode& m) const {
    if (m.region == Region::free) return;
    const double dl = delta(m.region, y);
    const double dl_rate = side(m.region) * s_rate(y);
    for (int j = 0; j < m.count; ++j) {
      const double x = pair_position(m, y, j);
      m.slip[j] = sliding_speed(y[kW1], y[kW2], x, lp_) >= 0.0 ? 1.0 : -1.0;
      m.clipped[j] = push_sign_function(x, m.count, d, dl, dl_rate) < 0.0;
    }
  }

  // (32),(33) at the onset of a contact in mode m (geometry already classified).
  ContactDamping damping_at_onset(const State& y, const Mode& m, double& vi, double& e) const {
    vi = std::max(side(m.region) * s_rate(y), kSmallestImpactSpeed_m_s);
    e = restitution_coefficient(case_.model.restitution, vi);
    ContactDamping d;
    d.per_stiffness_s_m = damping_factor_per_stiffness(case_.model.damping_form, e, vi);
    if (case_.model.damping_stiffness == DampingStiffness::hertz) {
      d.frozen_stiffness_n_m = kh_;
    } else if (m.count > 0) {
      int nearest = 0;
      for (int j = 1; j < m.count; ++j) {
        if (std::fabs(pair_position(m, y, j) - x_pitch_) <
            std::fabs(pair_position(m, y, nearest) - x_pitch_)) {
          nearest = j;
        }
      }
      double ke = 0.0;
      double dke = 0.0;
      pair_stiffness(pair_position(m, y, nearest), m.count, ke, dke);
      d.frozen_stiffness_n_m = ke;
    }
    return d;
  }

  // (5),(16),(17),(28): F^2/(2K) per term and pair, F = Ke delta.
  StoredEnergy stored_energy(const State& y, const Mode& m) const {
    StoredEnergy u;
    if (m.region == Region::free) return u;
    const double dl = delta(m.region, y);
    for (int j = 0; j < m.count; ++j) {
      const double x = pair_position(m, y, j);
      if (constant_k_ > 0.0) {
        u.hertz_j += 0.5 * constant_k_ / m.count * dl * dl;
        continue;
      }
      const PairCompliance c = table_.compliance(std::clamp(x, xs_, xe_));
      const double f = dl / c.total_m_per_n();
      u.hertz_j += 0.5 * f * f * c.hertz_m_per_n;
      u.bending_j += 0.5 * f * f * c.bending_m_per_n;
      u.axial_j += 0.5 * f * f * c.axial_m_per_n;
    }
    return u;
  }

 private:
  const StiffnessTable& table_;
  const SimulationCase& case_;
  double rb1_ = 0.0, rb2_ = 0.0, j1_ = 0.0, j2_ = 0.0, backlash_ = 0.0, lp_ = 0.0;
  double x_pitch_ = 0.0, t0_ = 0.0, xs_ = 0.0, xe_ = 0.0, coast_offset_ = 0.0;
  double friction_ = 0.0, kh_ = 0.0, constant_k_ = 0.0;
  bool damping_on_current_pair_ = true;
  // Mechanics belongs to one run, so one thread.
  mutable double torque_time_ = std::numeric_limits<double>::quiet_NaN();
  mutable std::pair<double, double> torque_values_{0.0, 0.0};
};

std::string where(double t_s, long long step) {
  return "t = " + format_number(t_s) + " s, step " + std::to_string(step);
}

// The bookkeeping shared by both integrators: mode changes, impacts, energy
// maxima, the ledger and the time series.
class Run {
 public:
  Run(const SimulationCase& c, const StiffnessTable& table, const RunControl& control)
      : c_(c), control_(control), mech_(c, table, control) {
    y_ = State{c.initial.theta1_rad,
               c.initial.theta2_rad,
               c.initial.w1_rad_s,
               c.initial.w2_rad_s,
               0.0,
               0.0,
               0.0,
               0.0};
    mode_ = mech_.classify_geometry(y_);
    if (mode_.region != Region::free) begin_contact(0.0);
    mech_.classify_forces(y_, damping_, mode_);
    energy0_ = mech_.kinetic_energy(y_) + mech_.stored_energy(y_, mode_).total();
    result_.summary.kinetic_energy_initial_j = mech_.kinetic_energy(y_);
    result_.summary.stored_energy_initial_j = energy0_ - mech_.kinetic_energy(y_);
    book_keep();
    if (control_.keep_series) {
      // The rows of the output grid up front, so that a long series is not
      // copied as it grows; capped, as a guess must not fail a run.
      constexpr double most_reserved_rows = 4e6;
      const double rows =
          c.integrator.end_time_s / (c.integrator.step_s * c.integrator.output_every);
      result_.series.reserve(static_cast<std::size_t>(std::min(rows + 2.0, most_reserved_rows)));
      record(0.0);
    }
  }

  const Mechanics& mech() const { return mech_; }
  State& y() { return y_; }
  const Mode& mode() const { return mode_; }
  const ContactDamping& damping() const { return damping_; }
  long long& steps() { return result_.summary.steps; }
  long long& rhs_evaluations() { return result_.summary.rhs_evaluations; }

  void check_finite(double t, const State& y) const {
    if (!all_finite(y)) {
      throw SimulationError("the run diverged: the state is not finite at " +
                            where(t, result_.summary.steps) +
                            "; a smaller step or a tighter tolerance may resolve it");
    }
  }

  // The mode changed at (t, y_): classify again, book impacts and jumps.
  void change_mode(double t) {
    ++result_.summary.events;
    const Mode old = mode_;
    Mode next = mech_.classify_geometry(y_);
    if (old.region != Region::free && next.region != old.region) end_contact(t, old);
    const double before = mech_.stored_energy(y_, old).total();
    mode_ = next;
    if (old.region != next.region && next.region != Region::free) begin_contact(t);
    mech_.classify_forces(y_, damping_, mode_);
    if (next.region == old.region) {
      // Keep the friction sign and clipping of pairs that stay loaded, unless
      // this event is theirs (then classify_forces has the new value).
      const int shift = next.k_first - old.k_first;
      EventValues g{};
      Mode probe = mode_;
      for (int j = 0; j < next.count; ++j) {
        const int i = j + shift;
        if (i >= 0 && i < old.count) {
          probe.slip[j] = old.slip[i];
          probe.clipped[j] = old.clipped[i];
        }
      }
      const int n = mech_.event_values(y_, probe, damping_, g);
      if (std::all_of(g.begin(), g.begin() + n, [](double v) { return v >= 0.0; })) mode_ = probe;
    }
    // Stored energy appears or vanishes with a pair entering or leaving under load.
    jump_work_ += mech_.stored_energy(y_, mode_).total() - before;
  }

  // After an accepted step ending at t.
  void book_keep() {
    SimulationSummary& s = result_.summary;
    const StoredEnergy u = mech_.stored_energy(y_, mode_);
    s.hertz_energy_max_j = std::max(s.hertz_energy_max_j, u.hertz_j);
    s.bending_energy_max_j = std::max(s.bending_energy_max_j, u.bending_j);
    s.axial_energy_max_j = std::max(s.axial_energy_max_j, u.axial_j);
    if (mode_.region != Region::free) {
      s.max_penetration_m = std::max(s.max_penetration_m, mech_.delta(mode_.region, y_));
    }
    const double energy = mech_.kinetic_energy(y_) + u.total();
    s.ledger_scale_j = std::max(s.ledger_scale_j, energy);
    const double residual = energy - energy0_ - y_[kTorqueWork] + y_[kDampingLoss] +
                            y_[kFrictionLoss] - y_[kParametricWork] - jump_work_;
    s.ledger_residual_j = residual;
    s.ledger_residual_max_j = std::max(s.ledger_residual_max_j, std::fabs(residual));
  }

  // Ends the run when the caller's should_stop asks for it.
  void check_stop(double t) const {
    if (control_.should_stop && result_.summary.steps % kStepsBetweenStopChecks == 0 &&
        control_.should_stop()) {
      throw SimulationStopped("the run was stopped by its caller at " +
                              where(t, result_.summary.steps));
    }
  }

  void record(double t) { record(t, y_, mode_); }
  void record(double t, const State& y, const Mode& m) {
    ContactTotals totals;
    State dydt{};
    mech_.rhs(t, y, m, damping_, dydt, &totals);
    const double delta = m.region == Region::free ? 0.0 : mech_.delta(m.region, y);
    result_.series.push_back(SeriesRow{t, y[kTheta1], y[kTheta2], y[kW1], y[kW2], mech_.s(y), delta,
                                       static_cast<int>(m.region), m.count, totals.normal_force_n,
                                       totals.friction_force_n});
  }

  SimulationResult finish(double t, const char* integrator) {
    SimulationSummary& s = result_.summary;
    s.case_name = c_.name;
    s.integrator = integrator;
    s.friction_coefficient = c_.model.friction_coefficient;
    s.end_time_s = t;
    s.step_s = c_.integrator.step_s;
    s.kinetic_energy_final_j = mech_.kinetic_energy(y_);
    s.stored_energy_final_j = mech_.stored_energy(y_, mode_).total();
    s.torque_work_j = y_[kTorqueWork];
    s.damping_loss_j = y_[kDampingLoss];
    s.friction_loss_j = y_[kFrictionLoss];
    s.parametric_jump_work_j = jump_work_;
    s.parametric_work_j = y_[kParametricWork] + jump_work_;
    s.final_w1_rad_s = y_[kW1];
    s.final_w2_rad_s = y_[kW2];
    result_.impacts = impacts_;
    return std::move(result_);
  }

  // Sets mode_ and damping_ directly (the integrator without event location).
  void set_mode_without_events(double t) {
    Mode next = mech_.classify_geometry(y_);
    if (mode_.region != Region::free && next.region != mode_.region) end_contact(t, mode_);
    const Mode old = mode_;
    mode_ = next;
    if (old.region != next.region && next.region != Region::free) begin_contact(t);
    mech_.classify_forces(y_, damping_, mode_);
  }

 private:
  void begin_contact(double t) {
    double vi = 0.0;
    double e = 0.0;
    damping_ = mech_.damping_at_onset(y_, mode_, vi, e);
    SimulationSummary& s = result_.summary;
    if (mode_.region == Region::n1) {
      ++s.impacts_n1;
      s.last_n1_impact_s = t;
    } else {
      ++s.impacts_n2;
      s.last_n2_impact_s = t;
    }
    if (!s.first_impact_s) {
      s.first_impact_s = t;
      s.first_impact_speed_m_s = vi;
    }
    impacts_.push_back(ImpactRecord{mode_.region, t, vi, e, std::nullopt, std::nullopt});
  }

  void end_contact(double t, const Mode& old) {
    if (impacts_.empty()) return;
    impacts_.back().end_s = t;
    impacts_.back().end_speed_m_s = -Mechanics::side(old.region) * mech_.s_rate(y_);
  }

  const SimulationCase& c_;
  const RunControl& control_;
  Mechanics mech_;
  State y_{};
  Mode mode_;
  ContactDamping damping_;
  double energy0_ = 0.0;
  double jump_work_ = 0.0;
  std::vector<ImpactRecord> impacts_;
  SimulationResult result_;
};

// The classical RK4 step from (t, y) with k1 = f(t, y) already evaluated:
// event location tries many step sizes from the same start.
void rk4_step_from(const Mechanics& mech, double t, const State& y, const State& k1, double h,
                   const Mode& m, const ContactDamping& d, State& out) {
  // Not zeroed: rhs writes every component.
  State k2, k3, k4, tmp;
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
  mech.rhs(t + 0.5 * h, tmp, m, d, k2);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
  mech.rhs(t + 0.5 * h, tmp, m, d, k3);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + h * k3[i];
  mech.rhs(t + h, tmp, m, d, k4);
  for (std::size_t i = 0; i < kStateSize; ++i) {
    out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
}

void rk4_step(const Mechanics& mech, double t, const State& y, double h, const Mode& m,
              const ContactDamping& d, State& out, State& k1) {
  mech.rhs(t, y, m, d, k1);
  rk4_step_from(mech, t, y, k1, h, m, d, out);
}

// The classical RK4 step with the mode re-evaluated at every stage: what a
// fixed-step integration without event location does.
void rk4_step_unlocated(const Mechanics& mech, double t, const State& y, double h,
                        const ContactDamping& d, State& out) {
  State k1{}, k2{}, k3{}, k4{}, tmp{};
  const auto f = [&](double tt, const State& x, State& dx) {
    Mode m = mech.classify_geometry(x);
    mech.classify_forces(x, d, m);
    mech.rhs(tt, x, m, d, dx);
  };
  f(t, y, k1);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
  f(t + 0.5 * h, tmp, k2);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
  f(t + 0.5 * h, tmp, k3);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + h * k3[i];
  f(t + h, tmp, k4);
  for (std::size_t i = 0; i < kStateSize; ++i) {
    out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
}

// The earliest time in (a, b] at which an event value of the mode turns
// negative, given the state as a function of time (a step of the integrator or
// its dense output). g_b holds the values at b, some negative.
double earliest_event(const Mechanics& mech, const Mode& m, const ContactDamping& d, double a,
                      double b, const EventValues& g_a, const EventValues& g_b, int n,
                      const std::function<void(double, State&)>& state_at) {
  double earliest = b;
  const double width = b - a;
  for (int i = 0; i < n; ++i) {
    // A value already zero at a has no bracket: the change then counts at the
    // end of the step (a tie of measure zero, not worth a cut).
    if (!(g_b[i] < 0.0) || g_a[i] <= 0.0) continue;
    const auto value = [&](double t) {
      State x{};
      state_at(t, x);
      EventValues g{};
      mech.event_values(x, m, d, g);
      return g[i];
    };
    std::uintmax_t iterations = 200;
    // Late in a run 4 eps of the step is below the spacing of doubles near t:
    // once the bracket is two neighbouring doubles it cannot shrink, and
    // iterating on (up to the limit) would only repeat the same evaluations.
    const auto close_enough = [width](double lo, double hi) {
      return hi - lo <= 4.0 * std::numeric_limits<double>::epsilon() * width ||
             std::nextafter(lo, hi) >= hi;
    };
    const double g_end = value(earliest);
    if (!(g_end < 0.0)) continue;  // this one comes after an earlier event
    const std::pair<double, double> bracket = boost::math::tools::toms748_solve(
        value, a, earliest, g_a[i], g_end, close_enough, iterations);
    // The solver may stop on an exact zero; the step must end where the value
    // is negative, so that the new mode is unambiguous.
    double after = bracket.second;
    for (double bump = 4.0 * std::numeric_limits<double>::epsilon() * width;
         after < earliest && !(value(after) < 0.0); bump *= 2.0) {
      after = std::min(after + bump, earliest);
    }
    earliest = std::min(earliest, after);
  }
  return earliest;
}

// Consecutive events that advance time by almost nothing: event location has stalled.
constexpr int kMostStalledEvents = 10000;

SimulationResult run_rk4(const SimulationCase& c, const StiffnessTable& table,
                         const RunControl& control) {
  Run run(c, table, control);
  const Mechanics& mech = run.mech();
  const double h = c.integrator.step_s;
  const double end = c.integrator.end_time_s;
  const auto grid_steps = static_cast<long long>(std::ceil(end / h * (1.0 - 1e-12)));
  const long long every = c.integrator.output_every;
  double t = 0.0;
  long long k = 0;
  int stalled = 0;
  State next{};
  while (k < grid_steps) {
    const double target = k + 1 == grid_steps ? end : static_cast<double>(k + 1) * h;
    const double step = target - t;
    const State& y = run.y();
    if (!control.locate_events) {
      rk4_step_unlocated(mech, t, y, step, run.damping(), next);
      run.rhs_evaluations() += 4;
      run.check_finite(target, next);
      run.y() = next;
      t = target;
      ++k;
      ++run.steps();
      run.set_mode_without_events(t);
    } else {
      State k1;
      rk4_step(mech, t, y, step, run.mode(), run.damping(), next, k1);
      run.rhs_evaluations() += 4;
      run.check_finite(target, next);
      if (mech.mode_holds(next, run.mode(), run.damping())) {
        run.y() = next;
        t = target;
        ++k;
        ++run.steps();
        stalled = 0;
      } else {
        EventValues g_a{}, g_b{};
        const int n = mech.event_values(y, run.mode(), run.damping(), g_a);
        mech.event_values(next, run.mode(), run.damping(), g_b);
        const State start = y;
        const Mode mode = run.mode();
        const ContactDamping damping = run.damping();
        long long evaluations = 0;
        const auto state_at = [&](double tau, State& x) {
          rk4_step_from(mech, t, start, k1, tau - t, mode, damping, x);
          evaluations += 3;
        };
        const double t_event =
            earliest_event(mech, mode, damping, t, target, g_a, g_b, n, state_at);
        run.rhs_evaluations() += evaluations;
        if (t_event < target) {
          state_at(t_event, next);
          run.check_finite(t_event, next);
        }
        stalled = t_event - t <= 1e-9 * h ? stalled + 1 : 0;
        if (stalled > kMostStalledEvents) {
          throw SimulationError("event location stalled at " + where(t, run.steps()) +
                                ": the mode changes back and forth without time advancing");
        }
        run.y() = next;
        ++run.steps();
        if (t_event >= target) {
          t = target;
          ++k;
        } else {
          t = t_event;
        }
        run.change_mode(t);
      }
    }
    run.book_keep();
    run.check_stop(t);
    if (control.keep_series && t == target && (k % every == 0 || k == grid_steps)) run.record(t);
  }
  return run.finish(t, "rk4");
}

SimulationResult run_adaptive(const SimulationCase& c, const StiffnessTable& table,
                              const RunControl& control) {
  namespace odeint = boost::numeric::odeint;
  Run run(c, table, control);
  const Mechanics& mech = run.mech();
  const double h = c.integrator.step_s;
  const double end = c.integrator.end_time_s;
  const double output_step = h * c.integrator.output_every;
  const auto outputs = static_cast<long long>(std::floor(end / output_step * (1.0 + 1e-12)));
  long long next_output = 1;
  Mode mode = run.mode();
  ContactDamping damping = run.damping();
  long long evaluations = 0;
  const auto system = [&](const State& x, State& dxdt, double tt) {
    mech.rhs(tt, x, mode, damping, dxdt);
    ++evaluations;
  };
  const double rtol = c.integrator.adaptive_relative_tolerance;
  // Angles are of order 1 rad and penetrations of 1e-6 m on a 0.02 m radius:
  // an absolute tolerance 1e-4 of the relative one keeps delta resolved.
  auto stepper = odeint::make_dense_output(rtol * 1e-4, rtol, largest_resolving_step_s(c),
                                           odeint::runge_kutta_dopri5<State>());
  stepper.initialize(run.y(), 0.0, h);
  double t = 0.0;
  int stalled = 0;
  const auto emit_until = [&](double upto) {
    while (control.keep_series && next_output <= outputs &&
           static_cast<double>(next_output) * output_step <= upto) {
      const double to = static_cast<double>(next_output) * output_step;
      State x{};
      stepper.calc_state(to, x);
      run.record(to, x, mode);
      ++next_output;
    }
  };
  while (t < end) {
    std::pair<double, double> span;
    try {
      span = stepper.do_step(system);
    } catch (const std::exception& e) {
      throw SimulationError("the adaptive integrator failed at " + where(t, run.steps()) + ": " +
                            e.what());
    }
    const double a = span.first;
    const double b = span.second;
    State yb = stepper.current_state();
    run.check_finite(b, yb);
    double t_next = b;
    bool event = false;
    if (!mech.mode_holds(yb, mode, damping)) {
      EventValues g_a{}, g_b{};
      State ya{};
      stepper.calc_state(a, ya);
      const int n = mech.event_values(ya, mode, damping, g_a);
      mech.event_values(yb, mode, damping, g_b);
      const auto state_at = [&](double tau, State& x) { stepper.calc_state(tau, x); };
      t_next = earliest_event(mech, mode, damping, a, b, g_a, g_b, n, state_at);
      stepper.calc_state(t_next, yb);
      event = true;
    }
    if (t_next >= end) {
      emit_until(end);
      stepper.calc_state(end, yb);
      run.y() = yb;
      ++run.steps();
      t = end;
      run.book_keep();
      break;
    }
    emit_until(t_next);
    run.y() = yb;
    ++run.steps();
    stalled = t_next - t <= 1e-9 * h ? stalled + 1 : 0;
    if (stalled > kMostStalledEvents) {
      throw SimulationError("event location stalled at " + where(t, run.steps()) +
                            ": the mode changes back and forth without time advancing");
    }
    t = t_next;
    if (event) {
      run.change_mode(t);
      mode = run.mode();
      damping = run.damping();
      stepper.initialize(run.y(), t, std::max(stepper.current_time_step(), 1e-3 * h));
    }
    run.book_keep();
    run.check_stop(t);
  }
  run.rhs_evaluations() = evaluations;
  return run.finish(t, "adaptive");
}

}  // namespace

void validate(const SimulationCase& c) {
  validate_fields(c);
  validate_step(c, largest_resolving_step_s(c));
}

SimulationResult simulate(const SimulationCase& c, const RunControl& control) {
  validate_fields(c);
  const StiffnessTable table(c.gears, c.model.stiffness);
  return simulate(c, table, control);
}

SimulationResult simulate(const SimulationCase& c, const StiffnessTable& table,
                          const RunControl& control) {
  // The step bound from the table: the same Ke to round-off, without the
  // adaptive quadrature that would otherwise cost more than a short run.
  validate_fields(c);
  validate_step(c, largest_resolving_step_s(c, table));
  if (!std::isfinite(control.constant_mesh_stiffness_n_m) ||
      control.constant_mesh_stiffness_n_m < 0.0) {
    throw InputError("constant_mesh_stiffness", control.constant_mesh_stiffness_n_m,
                     "0 (off) or a finite value > 0 N/m");
  }
  return c.integrator.kind == IntegratorKind::rk4 ? run_rk4(c, table, control)
                                                  : run_adaptive(c, table, control);
}

std::string series_csv(const std::vector<SeriesRow>& rows) {
  std::string out =
      "t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,s_m,delta_m,region,pairs,normal_force_N,"
      "friction_force_N\n";
  out.reserve(out.size() + rows.size() * 220);
  char line[512];
  for (const SeriesRow& r : rows) {
    const int n = std::snprintf(line, sizeof line,
                                "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d,%.17g,%.17g\n",
                                r.t_s, r.theta1_rad, r.theta2_rad, r.w1_rad_s, r.w2_rad_s, r.s_m,
                                r.delta_m, r.region, r.pairs, r.normal_force_n, r.friction_force_n);
    out.append(line, static_cast<std::size_t>(n));
  }
  return out;
}

namespace {

void json_number(std::string& out, const char* key, double value, bool last = false) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "  \"%s\": %.17g%s\n", key, value, last ? "" : ",");
  out += buffer;
}

// A JSON string literal: quotes, backslashes and control characters escaped.
std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(ch));
      out += buffer;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

void json_optional(std::string& out, const char* key, const std::optional<double>& value) {
  if (value) {
    json_number(out, key, *value);
  } else {
    out += std::string("  \"") + key + "\": null,\n";
  }
}

}  // namespace

std::string summary_json(const SimulationSummary& s) {
  std::string out = "{\n";
  out += "  \"case\": " + json_string(s.case_name) + ",\n";
  out += "  \"integrator\": " + json_string(s.integrator) + ",\n";
  json_number(out, "friction_coefficient", s.friction_coefficient);
  json_number(out, "end_time_s", s.end_time_s);
  json_number(out, "step_s", s.step_s);
  out += "  \"impacts_n1\": " + std::to_string(s.impacts_n1) + ",\n";
  out += "  \"impacts_n2\": " + std::to_string(s.impacts_n2) + ",\n";
  json_optional(out, "first_impact_s", s.first_impact_s);
  json_optional(out, "first_impact_speed_m_s", s.first_impact_speed_m_s);
  json_optional(out, "last_n1_impact_s", s.last_n1_impact_s);
  json_optional(out, "last_n2_impact_s", s.last_n2_impact_s);
  json_number(out, "max_penetration_m", s.max_penetration_m);
  json_number(out, "kinetic_energy_initial_J", s.kinetic_energy_initial_j);
  json_number(out, "kinetic_energy_final_J", s.kinetic_energy_final_j);
  json_number(out, "stored_energy_initial_J", s.stored_energy_initial_j);
  json_number(out, "stored_energy_final_J", s.stored_energy_final_j);
  json_number(out, "torque_work_J", s.torque_work_j);
  json_number(out, "damping_loss_J", s.damping_loss_j);
  json_number(out, "friction_loss_J", s.friction_loss_j);
  json_number(out, "parametric_work_J", s.parametric_work_j);
  json_number(out, "parametric_jump_work_J", s.parametric_jump_work_j);
  json_number(out, "hertz_energy_max_J", s.hertz_energy_max_j);
  json_number(out, "bending_energy_max_J", s.bending_energy_max_j);
  json_number(out, "axial_energy_max_J", s.axial_energy_max_j);
  json_number(out, "ledger_residual_J", s.ledger_residual_j);
  json_number(out, "ledger_residual_max_J", s.ledger_residual_max_j);
  json_number(out, "ledger_scale_J", s.ledger_scale_j);
  json_number(out, "final_w1_rad_s", s.final_w1_rad_s);
  json_number(out, "final_w2_rad_s", s.final_w2_rad_s);
  out += "  \"steps\": " + std::to_string(s.steps) + ",\n";
  out += "  \"events\": " + std::to_string(s.events) + ",\n";
  out += "  \"rhs_evaluations\": " + std::to_string(s.rhs_evaluations) + "\n";
  out += "}\n";
  return out;
}

std::vector<SweepRow> sweep_friction(const std::vector<SimulationCase>& cases, double from,
                                     double to, double step, unsigned threads,
                                     const std::function<bool()>& should_stop) {
  if (!std::isfinite(from) || from < 0.0) throw InputError("from", from, "a finite value >= 0");
  if (!std::isfinite(to) || to < from) {
    throw InputError("to", to, "a finite value >= from = " + format_number(from));
  }
  if (!std::isfinite(step) || step <= 0.0) throw InputError("step", step, "a finite value > 0");
  const double intervals = (to - from) / step;
  if (intervals > 1e5) throw InputError("step", step, "at least (to - from) / 1e5");
  // The last value is `to` when (to - from)/step is an integer up to rounding.
  const auto count = static_cast<std::size_t>(std::floor(intervals + 1e-9)) + 1;
  std::vector<double> frictions(count);
  for (std::size_t i = 0; i < count; ++i) frictions[i] = from + static_cast<double>(i) * step;
  // One table a base case, built once (friction does not change it) and
  // shared read-only by the runs: a build costs as much as 3 ms of simulation.
  std::vector<StiffnessTable> tables;
  for (const SimulationCase& c : cases) {
    validate(c);
    tables.emplace_back(c.gears, c.model.stiffness);
  }

  const std::size_t runs = count * cases.size();
  std::vector<double> ratio(runs, 0.0);
  std::vector<std::exception_ptr> errors(runs);
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    for (std::size_t i = next++; i < runs; i = next++) {
      try {
        SimulationCase c = cases[i % cases.size()];
        c.model.friction_coefficient = frictions[i / cases.size()];
        RunControl control;
        control.keep_series = false;
        control.should_stop = should_stop;
        const SimulationSummary s = simulate(c, tables[i % cases.size()], control).summary;
        if (!(s.damping_loss_j > 0.0)) {
          throw SimulationError("no damping loss in " + c.name +
                                " at f = " + format_number(c.model.friction_coefficient) +
                                ": the ratio friction loss / damping loss is undefined");
        }
        ratio[i] = s.friction_loss_j / s.damping_loss_j;
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  unsigned n = threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
  n = static_cast<unsigned>(std::min<std::size_t>(n, runs));
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < n; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  std::vector<SweepRow> rows;
  for (std::size_t i = 0; i < count; ++i) {
    SweepRow row{frictions[i], {}};
    for (std::size_t j = 0; j < cases.size(); ++j) row.ratio.push_back(ratio[i * cases.size() + j]);
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace gearimpact
