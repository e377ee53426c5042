// The parts of a run that do not depend on its system: the place of a step
// in messages, the finite-state check, the caller's stop request, the impact
// book and the ledger's balance. The torsional run (run.hpp, ledger.hpp) and
// the planar run (planar.cpp) share them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

// "t = ... s, step N", for messages.
inline std::string where(double t_s, long long step) {
  return "t = " + format_number(t_s) + " s, step " + std::to_string(step);
}

// Throws where a step's state is not finite.
template <typename StateType>
void check_finite_state(double t, long long step, const StateType& y) {
  if (!std::all_of(y.begin(), y.end(), [](double v) { return std::isfinite(v); })) {
    throw SimulationError("the run diverged: the state is not finite at " + where(t, step) +
                          "; a smaller step or a tighter tolerance may resolve it");
  }
}

// Every kStepsBetweenStopChecks steps, the caller's should_stop.
inline void poll_stop_request(const RunControl& control, long long step, double t) {
  if (control.should_stop && step % kStepsBetweenStopChecks == 0 && control.should_stop()) {
    throw SimulationStopped("the run was stopped by its caller at " + where(t, step));
  }
}

// The impacts of a run: one record a contact, from its onset (where the
// contact memory is set) to its end; the summary's counts and first and last
// impact times. A line's contact is open from begin to end; a run resumed in
// contact has none open on that line (its contact was struck before).
class ImpactBook {
 public:
  void begin(Region line, double t, double impact_speed_m_s, double restitution,
             SimulationSummary& s) {
    if (line == Region::n1) {
      ++s.impacts_n1;
      s.last_n1_impact_s = t;
    } else {
      ++s.impacts_n2;
      s.last_n2_impact_s = t;
    }
    if (!s.first_impact_s) {
      s.first_impact_s = t;
      s.first_impact_speed_m_s = impact_speed_m_s;
    }
    open_[line_index(line)] = records_.size();
    records_.push_back(
        ImpactRecord{line, t, impact_speed_m_s, restitution, std::nullopt, std::nullopt});
  }
  // The contact on `line` ends at t, the teeth parting at end_speed_m_s.
  void end(Region line, double t, double end_speed_m_s) {
    std::optional<std::size_t>& open = open_[line_index(line)];
    if (!open) return;
    records_[*open].end_s = t;
    records_[*open].end_speed_m_s = end_speed_m_s;
    open.reset();
  }
  const std::vector<ImpactRecord>& records() const { return records_; }
  std::vector<ImpactRecord> take() { return std::move(records_); }

 private:
  static std::size_t line_index(Region line) { return line == Region::n1 ? 0 : 1; }
  std::vector<ImpactRecord> records_;
  std::array<std::optional<std::size_t>, 2> open_;
};

// The ledger's balance after an accepted step (docs/model.md, Energies):
// (kinetic + stored)(t) - (kinetic + stored)(0) - the drives' work + each
// loss - the parametric work - the work of the stored energy's jumps, zero
// for the exact solution; summed in that order. Updates the summary's scale,
// residual and largest residual.
inline void book_ledger_residual(double energy_j, double energy0_j, double work_j,
                                 std::initializer_list<double> losses_j, double parametric_j,
                                 double jump_work_j, SimulationSummary& s) {
  s.ledger_scale_j = std::max(s.ledger_scale_j, energy_j);
  double residual = energy_j - energy0_j - work_j;
  for (const double loss : losses_j) residual += loss;
  residual = residual - parametric_j - jump_work_j;
  s.ledger_residual_j = residual;
  s.ledger_residual_max_j = std::max(s.ledger_residual_max_j, std::fabs(residual));
}

// The Lagrangian mesh force: the stored energy jumps by jump_j where a pair
// enters or leaves, at fixed angles (and centres). The pinion's kinetic energy
// pays it, J1 (w1+^2 - w1-^2) / 2 = -jump_j, w1 keeping its sign (Ke depends
// on theta1 alone, so the impulse is on the pinion): returns w1+. Where it
// cannot, the run stops; `where_text` and `change` say where and what changed.
inline double pinion_speed_after_jump(double jump_j, double j1_kg_m2, double w1_rad_per_s,
                                      const std::string& where_text, const std::string& change) {
  const double kinetic1 = 0.5 * j1_kg_m2 * w1_rad_per_s * w1_rad_per_s;
  if (jump_j > kinetic1) {
    throw SimulationError("mesh_force = \"lagrangian\": at " + where_text + ", " + change +
                          ": the stored energy jumps by " + format_number(jump_j) +
                          " J, more than the pinion's kinetic energy J1 w1^2 / 2 = " +
                          format_number(kinetic1) + " J (w1 = " + format_number(w1_rad_per_s) +
                          " rad/s) can pay; the gears would have to turn back there. "
                          "mesh_force = \"newtonian\" books the jump as parametric work");
  }
  return std::copysign(std::sqrt(w1_rad_per_s * w1_rad_per_s - 2.0 * jump_j / j1_kg_m2),
                       w1_rad_per_s);
}

// Which pairs entered or left a mesh between the modes `old` and `now`, for
// messages: pair k is the one at X = X_pitch + k t0 (+ Rb1 theta1) of its
// line; position(m, j) gives the X of the j-th loaded pair of mode m.
template <typename ModeT, typename Position>
std::string pair_change_text(const ModeT& old, const ModeT& now, Position position) {
  if (old.region != now.region) {
    return now.region == Region::free ? "the contact ends" : "a contact begins";
  }
  std::string text;
  const auto describe = [&](const ModeT& m, int j, const char* what) {
    if (!text.empty()) text += " and ";
    text += "pair k = " + std::to_string(m.k_first + j) + " of " +
            (m.region == Region::n1 ? "N1" : "N2") + " " + what +
            " at X = " + format_number(position(m, j)) + " m";
  };
  for (int j = 0; j < old.count; ++j) {
    const int k = old.k_first + j;
    if (k < now.k_first || k >= now.k_first + now.count) describe(old, j, "leaves");
  }
  for (int j = 0; j < now.count; ++j) {
    const int k = now.k_first + j;
    if (k < old.k_first || k >= old.k_first + old.count) describe(now, j, "enters");
  }
  return text.empty() ? "the loaded pairs change" : text;
}

// The ledger's totals at the end of a run: the final energies, the drives'
// work, the losses (Hertzian damping, friction, mesh damper) and the
// parametric work, the jumps' share of it named on its own.
inline void book_ledger_totals(double kinetic_j, double stored_j, double work_j,
                               double damping_loss_j, double friction_loss_j,
                               double mesh_damping_loss_j, double parametric_j, double jump_work_j,
                               SimulationSummary& s) {
  s.kinetic_energy_final_j = kinetic_j;
  s.stored_energy_final_j = stored_j;
  s.torque_work_j = work_j;
  s.damping_loss_j = damping_loss_j;
  s.friction_loss_j = friction_loss_j;
  s.mesh_damping_loss_j = mesh_damping_loss_j;
  s.parametric_jump_work_j = jump_work_j;
  s.parametric_work_j = parametric_j + jump_work_j;
}

// The sample grid of a run (RunControl::sample_rate_hz): t = t0 + n / fs
// exactly (sample_time_s), up to the run's end (sample_count); none without a
// rate. `emit` takes the samples not yet taken up to t_b, the end of an
// accepted step (before any change of mode there): one at t_b from the step's
// end state, one before it from the step's dense output.
class SampleClock {
 public:
  SampleClock(double end_time_s, const RunControl& control, double t0_s)
      : t0_s_(t0_s), rate_hz_(control.sample_rate_hz.value_or(0.0)) {
    if (control.sample_rate_hz) {
      total_ = static_cast<long long>(sample_count(end_time_s, rate_hz_, t0_s));
    }
  }
  bool on() const { return total_ > 0; }
  // The first sample (n = 0) is the one taken now.
  bool first() const { return next_ == 0; }
  // The rows to reserve for the samples kept: capped, as a guess must not fail a run.
  std::size_t reserve_rows() const {
    constexpr long long most_reserved_samples = 4'000'000;
    return static_cast<std::size_t>(std::min(total_, most_reserved_samples));
  }

  // at_end(t): the sample at t = t_b; inside(t): one at t_a < t < t_b (the
  // steps before took every sample up to t_a).
  template <typename AtEnd, typename Inside>
  void emit(double t_b, AtEnd at_end, Inside inside) {
    while (next_ < total_) {
      const double t = sample_time_s(t0_s_, next_, rate_hz_);
      if (t > t_b) return;
      if (t == t_b) {
        at_end(t);
      } else {
        inside(t);
      }
      ++next_;
    }
  }
  // emit with states: sample(t, y) at each sample up to t_b, y the step's end
  // state y_b at t_b, else the step's continuous extension state_at(t, x).
  template <typename State, typename StateAt, typename Sample>
  void emit_states(double t_b, const State& y_b, StateAt state_at, Sample sample) {
    emit(
        t_b, [&](double t) { sample(t, y_b); },
        [&](double t) {
          State x{};
          state_at(t, x);
          sample(t, x);
        });
  }

 private:
  double t0_s_;
  double rate_hz_;
  long long total_ = 0;
  long long next_ = 0;
};

// The mean accelerations over a sample's interval (SampleKind::interval_average):
// the velocity differences of the bodies over [t_{n-1}, t_n]. The first sample
// ends no interval: its velocities begin the first.
template <std::size_t Bodies>
class IntervalAverage {
 public:
  // At the first sample: remembers t and the velocities v[i].
  template <typename Velocity>
  void start(double t, Velocity v) {
    last_t_ = t;
    for (std::size_t i = 0; i < Bodies; ++i) last_[i] = v(i);
  }
  // At a later sample: a[i] receives (v[i] - v_{n-1}[i]) / (t - t_{n-1}); t
  // and v then begin the next interval.
  template <typename Velocity, typename Acceleration>
  void next(double t, Velocity v, Acceleration a) {
    const double interval = t - last_t_;
    for (std::size_t i = 0; i < Bodies; ++i) {
      const double now = v(i);
      a(i) = (now - last_[i]) / interval;
      last_[i] = now;
    }
    last_t_ = t;
  }

 private:
  double last_t_ = 0.0;
  std::array<double, Bodies> last_{};
};

}  // namespace gearimpact
