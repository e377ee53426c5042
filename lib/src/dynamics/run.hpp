// The bookkeeping shared by both integrators: the state and mode, mode
// changes, impacts, the energy ledger, the output grid and the summary.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "ledger.hpp"
#include "run_parts.hpp"
#include "stall.hpp"

namespace gearimpact {

// The torsional run: the books of run_fixed_grid (step_methods.hpp) and of
// the adaptive integrator for the GearSystem.
class Run {
 public:
  using System = GearSystem;
  // The evaluations of the step taken again to an event are left out of
  // rhs_evaluations, as this run has always counted them.
  static constexpr bool kCountsCutStep = false;

  Run(const SimulationCase& c, const StiffnessTable& table, const RunControl& control)
      : c_(c), control_(control), system_(c, table, control), ledger_(make_ledger()) {
    last_t_ = start_time_;
    last_w2_ = y_[kW2];
    book_keep(start_time_);
    if (records()) {
      if (control_.keep_series) {
        // The rows of the output grid up front, so that a long series is not
        // copied as it grows; capped, as a guess must not fail a run.
        constexpr double most_reserved_rows = 4e6;
        const double rows =
            c.integrator.end_time_s / (c.integrator.step_s * c.integrator.output_every);
        result_.series.reserve(static_cast<std::size_t>(std::min(rows + 2.0, most_reserved_rows)));
      }
      record(start_time_);
    }
    if (clock_.on()) {
      if (control_.keep_samples) result_.samples.reserve(clock_.reserve_rows());
      emit_samples(start_time_, y_, mode_, [](double, State&) {});
    }
  }

  const GearSystem& system() const { return system_; }
  State& y() { return y_; }
  const Mode& mode() const { return mode_; }
  const ContactMemory& damping() const { return damping_; }
  long long& steps() { return result_.summary.steps; }
  long long& rhs_evaluations() { return result_.summary.rhs_evaluations; }
  double start_time() const { return start_time_; }
  // The grid's steps, the last one ending at the run's end.
  long long grid_steps() const {
    return static_cast<long long>(
        std::ceil(c_.integrator.end_time_s / c_.integrator.step_s * (1.0 - 1e-12)));
  }
  // Whether a step keeps what its dense output needs: for the samples.
  bool wants_dense() const { return sampling(); }
  // f(t, y) in the mode: the step's first stage.
  const State& first_stage(double t) {
    system_.rhs(t, y_, mode_, damping_, k1_);
    ++result_.summary.rhs_evaluations;
    return k1_;
  }
  // What a step from (t_a, y_a) to (t_b, y_b) shows beyond its samples: nothing here.
  template <typename Dense>
  void observe_step(double, const State&, double, const State&, const Dense&) {}
  // Whether the output grid is wanted: kept as the series or observed.
  bool records() const { return control_.keep_series || static_cast<bool>(control_.on_row); }
  // Whether the run is sampled (RunControl::sample_rate_hz).
  bool sampling() const { return clock_.on(); }

  void check_finite(double t, const State& y) const {
    check_finite_state(t, result_.summary.steps, y);
  }

  // After a step from t_from to t_to, which ended on an event or not (the
  // mode then classified again): the stall watch and the sticking fallback
  // (stall.hpp). A step taken with each stage's friction signs classifies the
  // signs again, and keeps them per stage while one of them changed. Returns
  // whether the mode's friction signs changed without an event.
  bool check_progress(double t_from, double t_to, bool event) {
    bool changed = classify_stage_signs(event, mode_,
                                        [&](Mode& m) { system_.classify_forces(y_, damping_, m); });
    if (stall_.after_step(event, t_from, t_to,
                          [&] { return where(t_from, result_.summary.steps); })) {
      changed = take_stage_signs(mode_) || changed;
    }
    return changed;
  }

  // Every kStepsBetweenStopChecks steps, the caller's should_stop.
  void poll_stop(double t) const { poll_stop_request(control_, result_.summary.steps, t); }

  // The mode changed at (t, y_): classify again, book impacts and jumps.
  void change_mode(double t) {
    ++result_.summary.events;
    const Mode old = mode_;
    Mode next = system_.classify_geometry(y_);
    if (old.region != Region::free && next.region != old.region) end_contact(t, old);
    const double before = system_.stored_energy(y_, old).total_j();
    mode_ = next;
    const double after = system_.stored_energy(y_, mode_).total_j();
    if (system_.lagrangian()) pay_stored_energy_jump(t, old, before, after);
    if (old.region != next.region && next.region != Region::free) begin_contact(t);
    system_.classify_forces(y_, damping_, mode_);
    if (next.region == old.region) {
      mode_ = system_.mesh().carry_pair_signs(GearSystem::motion(y_), old, mode_, damping_);
    }
    if (!system_.lagrangian()) ledger_.mode_changed(before, after);
  }

  // After an accepted step, which ends at t.
  void book_keep(double t) {
    SimulationSummary& s = result_.summary;
    if (system_.driven() && t > last_t_) {
      // The step's mean w2' is its change of w2 over its length: exact at
      // impacts, which end steps, where w2' jumps.
      const double dw2 = y_[kW2] - last_w2_;
      acceleration2_squared_integral_ += dw2 * dw2 / (t - last_t_);
      last_t_ = t;
      last_w2_ = y_[kW2];
    }
    if (c_.model.friction_law != FrictionLaw::constant) observe_friction(t);
    drift_.observe(t, y_[kTheta1]);
    ledger_.observe(y_, mode_, s);
    if (mode_.region != Region::free) {
      s.max_penetration_m = std::max(s.max_penetration_m, system_.delta(mode_.region, y_));
      check_overlap(t);
    }
  }

  // A deflection on the line of action of half a base pitch means the teeth
  // have passed through each other by about a tooth's thickness: the contact
  // on the line of action no longer describes them (a pinion with a missing
  // tooth under load runs ahead into the next pair), and what follows would be
  // numbers without a meaning.
  void check_overlap(double t) const {
    const double overlap = result_.summary.max_penetration_m;
    if (!(overlap > half_base_pitch_m_)) return;
    std::string cause =
        "with a missing tooth the load drives the pinion ahead while no pair carries it, so lower "
        "the load or the backlash, or raise the speed";
    // A contact that began near rest carries a damping whose fixed step
    // diverges (check_start_damping): say so rather than blame the load. A
    // frozen damping is checked before the run.
    const double rate =
        damping_rate_per_step(c_, damping_.damping_per_stiffness_s_m, peak_tooth_load_n(c_));
    const IntegratorKind kind = c_.integrator.kind;
    if (kind != IntegratorKind::adaptive && rate > real_stability_limit(kind)) {
      cause = "the Hertzian damping of (32)-(33) that the last impact set is D = " +
              format_number(damping_.damping_per_stiffness_s_m) +
              " s/m, and its rate per step h D F / m_e = " + format_number(rate) + " exceeds " +
              format_number(real_stability_limit(kind)) + ", where fixed-step " +
              fixed_method_name(kind) +
              " diverges (an impact near rest sets a D without bound): set "
              "model.damping_update = \"frozen\", or integrator.kind = \"adaptive\", or a "
              "smaller integrator.step";
    }
    throw SimulationError("the teeth overlap by " + format_number(overlap) +
                          " m on the line of action at " + where(t, result_.summary.steps) +
                          ", more than half a base pitch (" + format_number(half_base_pitch_m_) +
                          " m): the model's contact on the line of action no longer holds; " +
                          cause);
  }

  // The line's coefficient sum(f N) / sum(N) at the end of a step under a law
  // whose f varies, weighted by the step's length: an extra evaluation of the
  // forces per loaded step, only under those laws.
  void observe_friction(double t) {
    const double step = t - friction_last_t_;
    friction_last_t_ = t;
    if (mode_.region == Region::free || !(step > 0.0)) return;
    ContactTotals totals;
    State dydt{};
    system_.rhs(t, y_, mode_, damping_, dydt, &totals);
    if (!(totals.normal_force_n > 0.0)) return;
    const double f = totals.friction_load_n / totals.normal_force_n;
    friction_time_integral_ += f * step;
    friction_loaded_time_ += step;
    friction_max_ = std::max(friction_max_, f);
  }

  // The samples not yet taken up to t_b, the end of an accepted step in mode m
  // at y_b (before any change of mode at t_b): a sample at t_b is y_b itself,
  // one inside the step comes from `state_at` (its dense output). At the start,
  // t_b = the start time takes the sample there.
  template <typename StateAt>
  void emit_samples(double t_b, const State& y_b, const Mode& m, StateAt state_at) {
    clock_.emit_states(
        t_b, y_b,
        [&](double t, State& x) {
          state_at(t, x);
          system_.impose_driver(t, x);
        },
        [&](double t, const State& y) { sample(t, y, m); });
  }

  void record(double t) { record(t, y_, mode_); }
  void record(double t, const State& y, const Mode& m) {
    ContactTotals totals;
    State dydt{};
    system_.rhs(t, y, m, damping_, dydt, &totals);
    const double delta = m.region == Region::free ? 0.0 : system_.delta(m.region, y);
    const SeriesRow row{t,
                        y[kTheta1],
                        y[kTheta2],
                        y[kW1],
                        y[kW2],
                        system_.s(y),
                        delta,
                        static_cast<int>(m.region),
                        m.count,
                        totals.normal_force_n,
                        totals.friction_force_n};
    if (control_.keep_series) result_.series.push_back(row);
    if (control_.on_row) control_.on_row(row);
  }

  void sample(double t, const State& y, const Mode& m) {
    const bool average = control_.sample == SampleKind::interval_average;
    const auto w = [&](std::size_t i) { return y[kW1 + i]; };
    if (average && clock_.first()) {
      average_.start(t, w);
      return;
    }
    ContactTotals totals;
    State dydt{};
    system_.rhs(t, y, m, damping_, dydt, &totals);
    if (average) average_.next(t, w, [&](std::size_t i) -> double& { return dydt[kW1 + i]; });
    const double sv = system_.s(y);
    const SampleRow row{t,
                        y[kTheta1],
                        y[kTheta2],
                        y[kW1],
                        y[kW2],
                        dydt[kW1],
                        dydt[kW2],
                        sv,
                        sv - c_.gears.backlash_m,
                        m.region == Region::n1 ? totals.normal_force_n : 0.0,
                        m.region == Region::n2 ? totals.normal_force_n : 0.0,
                        static_cast<int>(m.region),
                        m.count};
    if (control_.keep_samples) result_.samples.push_back(row);
    if (control_.on_sample) control_.on_sample(row);
  }

  SimulationResult finish(double t, const char* integrator) {
    SimulationSummary& s = result_.summary;
    s.case_name = c_.name;
    s.integrator = integrator;
    s.damping_update = resolved_damping_update(c_);
    s.speed_drift_max_rel = drift_.max_relative_drift();
    s.stiffness_model = c_.model.stiffness.kind;
    s.friction_coefficient = c_.model.friction_coefficient;
    s.friction_law = c_.model.friction_law;
    s.mesh_damper = c_.model.mesh_damping_ratio > 0.0;
    if (friction_loaded_time_ > 0.0) {
      s.friction_coefficient_mean = friction_time_integral_ / friction_loaded_time_;
      s.friction_coefficient_max = friction_max_;
    }
    s.end_time_s = t;
    s.step_s = c_.integrator.step_s;
    ledger_.finish(y_, mode_, s);
    if (system_.lagrangian()) s.stored_energy_jumps_j = stored_energy_jumps_;
    s.final_w1_rad_per_s = y_[kW1];
    s.final_w2_rad_per_s = y_[kW2];
    if (system_.driven()) s.rattle = rattle_summary(t);
    result_.impacts = impacts_.take();
    result_.start_time_s = start_time_;
    result_.final_state.time_s = t;
    result_.final_state.state = {y_[kTheta1], y_[kTheta2], y_[kW1], y_[kW2]};
    result_.final_state.contact = damping_;
    return std::move(result_);
  }

  // Sets mode_ and damping_ directly (the integrator without event location).
  void set_mode_without_events(double t) {
    Mode next = system_.classify_geometry(y_);
    if (mode_.region != Region::free && next.region != mode_.region) end_contact(t, mode_);
    const Mode old = mode_;
    mode_ = next;
    if (system_.lagrangian()) {
      pay_stored_energy_jump(t, old, system_.stored_energy(y_, old).total_j(),
                             system_.stored_energy(y_, mode_).total_j());
    }
    if (old.region != next.region && next.region != Region::free) begin_contact(t);
    system_.classify_forces(y_, damping_, mode_);
  }

 private:
  RattleSummary rattle_summary(double t) const {
    RattleSummary r;
    const double duration = t - start_time_;
    if (!(duration > 0.0)) return r;
    int n1 = 0;
    int n2 = 0;
    double speeds = 0.0;
    for (const ImpactRecord& impact : impacts_.records()) {
      // A contact the run starts in was not struck.
      if (impact.start_s == start_time_) continue;
      (impact.line == Region::n1 ? n1 : n2) += 1;
      speeds += impact.impact_speed_m_s;
      r.impact_speed_max_m_s = std::max(r.impact_speed_max_m_s, impact.impact_speed_m_s);
    }
    r.impacts_per_s_n1 = n1 / duration;
    r.impacts_per_s_n2 = n2 / duration;
    if (n1 + n2 > 0) r.impact_speed_mean_m_s = speeds / (n1 + n2);
    r.impact_power_w = y_[kDampingLoss] / duration;
    r.rms_acceleration2_rad_s2 = std::sqrt(acceleration2_squared_integral_ / duration);
    r.regime = n1 > 0 && n2 > 0   ? RattleRegime::double_sided
               : n1 > 0 || n2 > 0 ? RattleRegime::single_sided
                                  : RattleRegime::no_impact;
    return r;
  }

  // The start: the case's initial state at t = 0 (a contact there counts as an
  // impact), or where a previous run ended (its contact goes on).
  EnergyLedger make_ledger() {
    const InitialState& start = control_.resume ? control_.resume->state : c_.initial;
    start_time_ = control_.resume ? control_.resume->time_s : 0.0;
    friction_last_t_ = start_time_;
    y_ = State{start.theta1_rad,
               start.theta2_rad,
               start.w1_rad_per_s,
               start.w2_rad_per_s,
               0.0,
               0.0,
               0.0,
               0.0};
    system_.impose_driver(start_time_, y_);
    mode_ = system_.classify_geometry(y_);
    if (control_.resume) {
      damping_ = control_.resume->contact;
    } else if (mode_.region != Region::free) {
      begin_contact(start_time_);
      check_start_damping();
    }
    system_.classify_forces(y_, damping_, mode_);
    return EnergyLedger(system_, y_, mode_, result_.summary);
  }

  // The fixed-step method's name as the messages give it.
  static const char* fixed_method_name(IntegratorKind kind) {
    return kind == IntegratorKind::dopri5 ? "Dormand-Prince (dopri5)" : "RK4";
  }

  // A run that starts in contact takes its Hertzian damping from the approach
  // speed at t = 0. Near rest (Vi floored) the damping that each impact sets by
  // (32)-(33) grows without bound, and under the tooth load a fixed step (RK4
  // or Dormand-Prince, each past its real stability interval) would diverge
  // within a few steps into an overlap that says nothing of the cause; this
  // names it and the keys that avoid it before any step is taken.
  void check_start_damping() const {
    const IntegratorKind kind = c_.integrator.kind;
    if (kind == IntegratorKind::adaptive) return;
    ContactTotals totals;
    State dydt{};
    system_.rhs(start_time_, y_, mode_, damping_, dydt, &totals);
    const double load = std::max(totals.normal_force_n, peak_tooth_load_n(c_));
    const double d = damping_.damping_per_stiffness_s_m;
    const double rate = damping_rate_per_step(c_, d, load);
    if (!(rate > real_stability_limit(kind))) return;
    const ImpactRecord& start = impacts_.records().back();
    const std::string side = mode_.region == Region::n1 ? "drive (N1)" : "coast (N2)";
    throw InputError(
        "initial.theta1", format_number(c_.initial.theta1_rad) + " rad",
        "a start with the teeth apart, or in contact and approaching fast enough: this start "
        "presses the " +
            side + " flanks by " + format_number(system_.delta(mode_.region, y_)) +
            " m at an approach speed Vi = " + format_number(start.impact_speed_m_s) +
            " m/s, for which the Hertzian damping that each impact sets by (32)-(33) is D = " +
            format_number(d) +
            " s/m (it grows without bound as Vi falls to 0); with the tooth load " +
            format_number(load) + " N its damping rate per step h D F / m_e = " +
            format_number(rate) + " exceeds " + format_number(real_stability_limit(kind)) +
            ", where fixed-step " + fixed_method_name(kind) + " diverges",
        "start inside the backlash (|Rb1 theta1 - Rb2 theta2| < gears.backlash), or set "
        "model.damping_update = \"frozen\" (D from model.damping_reference_speed), or "
        "integrator.kind = \"adaptive\"");
  }

  void begin_contact(double t) {
    const GearSystem::Onset onset = system_.damping_at_onset(y_, mode_);
    damping_ = onset.damping;
    impacts_.begin(mode_.region, t, onset.impact_speed_m_s, onset.restitution, result_.summary);
  }

  // The Lagrangian mesh force: V = 1/2 Ke(theta1) delta^2 jumps from `before`
  // to `after` where a pair enters or leaves, at fixed theta1, theta2. The
  // pinion's kinetic energy pays the jump, J1 (w1+^2 - w1-^2) / 2 = -(after -
  // before), w1 keeping its sign (Ke depends on theta1 alone, so the impulse
  // is on the pinion); where it cannot, the run stops.
  void pay_stored_energy_jump(double t, const Mode& old, double before, double after) {
    const double jump = after - before;
    if (jump == 0.0) return;
    stored_energy_jumps_ += std::fabs(jump);
    if (system_.driven()) {
      // A kinematic driver keeps w1: it pays the jump, as work of its torque.
      y_[kTorqueWork] += jump;
      return;
    }
    // The message's text only where the pinion cannot pay.
    const double j1 = system_.pinion_inertia();
    const double w1 = y_[kW1];
    const bool pays = jump <= 0.5 * j1 * w1 * w1;
    y_[kW1] = pinion_speed_after_jump(jump, j1, w1, where(t, result_.summary.steps),
                                      pays ? std::string() : pair_change(old));
  }

  // Which pairs entered or left between `old` and mode_, for messages.
  std::string pair_change(const Mode& old) const {
    return pair_change_text(old, mode_,
                            [&](const Mode& m, int j) { return system_.pair_position(m, y_, j); });
  }

  void end_contact(double t, const Mode& old) {
    impacts_.end(old.region, t, -line_sign(old.region) * system_.s_rate(y_));
  }

  const SimulationCase& c_;
  const double half_base_pitch_m_ = 0.5 * base_pitch(c_.gears);
  const RunControl& control_;
  GearSystem system_;
  State y_{};
  State k1_{};
  Mode mode_;
  ContactMemory damping_;
  double start_time_ = 0.0;
  StallWatch stall_{c_.integrator.step_s, c_.model.friction_smoothing_speed_m_s};
  SimulationResult result_;
  ImpactBook impacts_;
  // Under a kinematic driver: Int w2'^2 dt, and the end of the last step.
  double acceleration2_squared_integral_ = 0.0;
  double last_t_ = 0.0;
  double last_w2_ = 0.0;
  // Under a friction law whose f varies: Int f dt and the time over loaded
  // steps, the largest f, and the end of the last step.
  double friction_time_integral_ = 0.0;
  double friction_loaded_time_ = 0.0;
  double friction_max_ = 0.0;
  double friction_last_t_ = 0.0;
  // Under the Lagrangian mesh force: the sum of |dU| of the jumps paid.
  double stored_energy_jumps_ = 0.0;
  // The velocities w1, w2 of the last sample, where an interval average's interval begins.
  IntervalAverage<2> average_;
  // Last: its construction sets the start state above (make_ledger).
  EnergyLedger ledger_;
  // After ledger_, whose construction sets the start it begins from.
  SpeedDriftMonitor drift_{c_.torque1, c_.drive.settle_s, start_time_, y_[kTheta1], y_[kW1]};
  // The sample grid, from the start time make_ledger set.
  SampleClock clock_{c_.integrator.end_time_s, control_, start_time_};
};

}  // namespace gearimpact
