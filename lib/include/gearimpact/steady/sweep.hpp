// Sweeps of the steady state along a line of one parameter (docs/steady-state.md section 4): each
// point starts from the previous point's steady state (continuation), so a line is sequential;
// lines (a second parameter's values, the two directions) are independent and are the unit of
// parallel work and of sharding. Rows are keyed (line, direction, index), index the position of
// the value in the ascending grid, whatever the direction.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// The schema row of a key a sweep can vary: any quantity, number or integer key of the case
// schema (case/schema.hpp), or one element of a list key as "section.key[i]" (a row of its own,
// with the list's unit and range; set_sweep_value refuses an index past the case's list, naming
// the index range). Throws InputError naming `flag` and the key otherwise.
const Field& sweep_field(const std::string& key, const std::string& flag);

// Sets the key to an SI value through the schema (set_field: its range, and a key used only with
// another key's choice, such as torque1.amplitude with kind = "sinusoidal", needs that choice
// first). torqueN.mean also sets a constant torque's value, its mean.
void set_sweep_value(SimulationCase& c, const std::string& key, double si_value);

// set_sweep_value, and what keeps a swept case comparable to `base`: a speed sets the other speed
// so that the pair rolls, Rb1 w1 = Rb2 w2, whatever base's other speed (without fluctuating
// torques the mean speed is the momentum's, so a pair that does not roll would run at another
// speed than the one set); a torque's mean moves the other torque's mean so that they stay
// balanced, T1/Rb1 + T2/Rb2 = 0 (a load sweep).
void apply_sweep_value(SimulationCase& c, const SimulationCase& base, const std::string& key,
                       double si_value);

// points values from `from` to `to`, the last exactly `to`. Throws InputError naming `points_key`
// unless points >= 1 (and from == to when points == 1), `from_key`/`to_key` unless finite.
std::vector<double> sweep_grid(double from, double to, int points, const char* from_key,
                               const char* to_key, const char* points_key);

enum class SweepDirection { up, down };
std::string to_string(SweepDirection direction);

struct SweepPointResult {
  int line = 0;
  SweepDirection direction = SweepDirection::up;
  int index = 0;
  double value_si = 0.0;
  SteadyPoint point;
  // A run that failed (SimulationError): its message; the point is not converged and the next
  // starts afresh from the case's initial state.
  std::string failure;
};

// A jump of a line: two neighbouring converged points in the order the line ran (a point not
// converged between them is passed over) whose DTE amplitudes (half peak-to-peak of s), both
// positive, differ by more than kJumpRatio either way. A smooth response changes by far less
// between neighbouring points of a grid that resolves it; a jump onto another branch (a
// resonance's fold, contact lost or regained) changes by several times.
inline constexpr double kJumpRatio = 2.0;

struct SweepJump {
  int line = 0;
  SweepDirection direction = SweepDirection::up;
  double from_si = 0.0;  // the swept value before the jump, in the direction's order
  double to_si = 0.0;
  double amplitude_before_m = 0.0;
  double amplitude_after_m = 0.0;
  Regime regime_before = Regime::no_impact;
  Regime regime_after = Regime::no_impact;
};

// Where the loaded flank's contact is lost (NI to SS or DS) or regained (SS or DS to NI) between
// neighbouring converged points of a line, in the order it ran.
struct ContactChange {
  int line = 0;
  SweepDirection direction = SweepDirection::up;
  bool lost = true;  // NI to SS/DS; false: SS/DS to NI
  double from_si = 0.0;
  double to_si = 0.0;
  Regime regime_before = Regime::no_impact;
  Regime regime_after = Regime::no_impact;
};

// The jumps and contact changes of rows in any order, listed by (line, direction (up before
// down)) and, within a line, in the order it ran.
std::vector<SweepJump> sweep_jumps(const std::vector<SweepPointResult>& rows);
std::vector<ContactChange> contact_changes(const std::vector<SweepPointResult>& rows);

using TableFor = std::function<std::shared_ptr<const StiffnessTable>(const SimulationCase&)>;

// One line: line_case with `key` set to each grid value (apply_sweep_value) in the direction's
// order, each point
// started from the previous one's final state (the first from line_case's initial state). When
// the key is a speed (initial.w1 or initial.w2) the case rolls at it (apply_sweep_value) and the
// carried state's speeds move with it so that the relative motion carries over: w1 += dw1 and
// w2 += dw1 Rb1/Rb2 (or w2 += dw2, w1 += dw2 Rb2/Rb1). `on_point` (may be empty) is called
// after each point.
std::vector<SweepPointResult> sweep_line(
    const SimulationCase& line_case, const TableFor& table_for, const std::string& key,
    const std::vector<double>& grid, SweepDirection direction, int line,
    const SteadySettings& settings, const std::function<void(const SweepPointResult&)>& on_point);

}  // namespace gearimpact
