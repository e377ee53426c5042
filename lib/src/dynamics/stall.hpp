// The run's watch on event location that stalls, and the sticking fallback:
// one behaviour for every system and integrator.
//
// An event that advances time by less than a millionth of the step h is the
// contact's chatter, not the motion: with an exact friction switch, a loaded
// pair whose sliding turns back at once after its reversal (the friction's
// jump exceeds what drives the sliding through zero: the contact would stick)
// ends step after step on a reversal that advances by round-off or a few
// 1e-14 s. After two such events in a row, and without a smoothed sign
// (model.friction_smoothing_speed), the run's mode takes each stage's own
// friction signs (Mode::slip_per_stage), unlocated: the steps cross the
// sticking with an error O(h) there, and once every pair slid one way through
// a whole step its reversals are events again. Events that keep stalling
// all the same (kMostStalledEvents in a row) stop the run with an error.
#pragma once

#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

// Consecutive events that advance time by almost nothing: event location has stalled.
inline constexpr int kMostStalledEvents = 10000;

class StallWatch {
 public:
  // h: the run's step; smoothing: model.friction_smoothing_speed (0: the exact switch).
  StallWatch(double step_s, double friction_smoothing_speed_m_s)
      : least_advance_s_(1e-6 * step_s), exact_switch_(friction_smoothing_speed_m_s == 0.0) {}

  // After a step from t_from to t_to, which ended on an event or not; `where`
  // names the place for the error. Returns whether the steps that follow take
  // each stage's own friction signs (the contact sticks); throws once events
  // have stalled kMostStalledEvents times in a row.
  template <typename Where>
  bool after_step(bool event, double t_from, double t_to, const Where& where) {
    stalled_ = event && t_to - t_from <= least_advance_s_ ? stalled_ + 1 : 0;
    if (stalled_ > kMostStalledEvents) {
      std::string text = "event location stalled at " + where() +
                         ": the mode changes back and forth without time advancing";
      if (exact_switch_) {
        text +=
            ". Under load with friction this is the friction's reversal: its jump turns the "
            "sliding back. model.friction_smoothing_speed (e.g. \"1e-3 m/s\") replaces the exact "
            "switch by tanh(Vs / v_s) (docs/model.md, \"Smoothed reversal\")";
      }
      throw SimulationError(text);
    }
    return stalled_ >= 2 && exact_switch_;
  }

 private:
  double least_advance_s_;
  bool exact_switch_;
  int stalled_ = 0;
};

// After a step: a mesh's mode taken with each stage's own friction signs
// classifies its signs again at the step's end (`classify`, which writes them
// into the mode) and keeps them per stage while one changed; not after an
// event, which classified the mode anew. Returns whether it classified.
template <typename ModeT, typename Classify>
bool classify_stage_signs(bool event, ModeT& mode, Classify classify) {
  if (event || !mode.slip_per_stage) return false;
  const auto slip = mode.slip;
  classify(mode);
  mode.slip_per_stage = slip != mode.slip;
  return true;
}

// The sticking fallback (StallWatch::after_step true): the mode takes each
// stage's own friction signs. Returns whether that changed it.
template <typename ModeT>
bool take_stage_signs(ModeT& mode) {
  const bool changed = !mode.slip_per_stage;
  mode.slip_per_stage = true;
  return changed;
}

}  // namespace gearimpact
