#include "gearimpact/steady/sweep.hpp"

#include <cmath>
#include <optional>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

const Field& sweep_field(const std::string& key, const std::string& flag) {
  const Field* field = find_field(key);
  if (field == nullptr || (field->kind != FieldKind::quantity && field->kind != FieldKind::number &&
                           field->kind != FieldKind::integer)) {
    throw InputError(flag, key,
                     "a quantity, number or integer key of the case schema, as section.key "
                     "(`gearimpact schema` lists them)");
  }
  return *field;
}

void set_sweep_value(SimulationCase& c, const std::string& key, double si_value) {
  // A constant torque's value is its mean: the load sweep's key for every torque kind.
  for (const char* torque : {"torque1", "torque2"}) {
    if (key == std::string(torque) + ".mean") {
      const Torque& t = std::string(torque) == "torque1" ? c.torque1 : c.torque2;
      if (t.kind == Torque::Kind::constant) {
        set_field(c, std::string(torque) + ".value", shortest_decimal(si_value), key);
        return;
      }
    }
  }
  sweep_field(key, key);
  // A plain number is read as SI, and shortest_decimal reads back to the same double.
  set_field(c, key, shortest_decimal(si_value));
}

void apply_sweep_value(SimulationCase& c, const SimulationCase& base, const std::string& key,
                       double si_value) {
  set_sweep_value(c, key, si_value);
  const double rb1 = base_radius(base.gears, Gear::one);
  const double rb2 = base_radius(base.gears, Gear::two);
  if (key == "initial.w1") {
    c.initial.w2_rad_per_s =
        base.initial.w2_rad_per_s + (si_value - base.initial.w1_rad_per_s) * rb1 / rb2;
  } else if (key == "initial.w2") {
    c.initial.w1_rad_per_s =
        base.initial.w1_rad_per_s + (si_value - base.initial.w2_rad_per_s) * rb2 / rb1;
  } else if (key == "torque1.mean") {
    set_sweep_value(c, "torque2.mean", -si_value * rb2 / rb1);
  } else if (key == "torque2.mean") {
    set_sweep_value(c, "torque1.mean", -si_value * rb1 / rb2);
  }
  if (c.torque1.kind == Torque::Kind::prescribed_speed) {
    // The driver prescribes w1(0), which a swept mean speed moves.
    c.initial.w1_rad_per_s = driver_speed_at(c.torque1, 0.0);
  }
}

std::vector<double> sweep_grid(double from, double to, int points, const char* from_key,
                               const char* to_key, const char* points_key) {
  if (!std::isfinite(from)) throw InputError(from_key, from, "a finite value");
  if (!std::isfinite(to)) throw InputError(to_key, to, "a finite value");
  if (points < 1) throw InputError(points_key, points, "at least 1 (2 or more when from != to)");
  if (points == 1 && from != to) {
    throw InputError(points_key, points, "at least 2 when from != to");
  }
  std::vector<double> grid(static_cast<std::size_t>(points));
  for (int i = 0; i < points; ++i) {
    grid[static_cast<std::size_t>(i)] =
        i + 1 == points ? to : from + (to - from) * static_cast<double>(i) / (points - 1);
  }
  return grid;
}

std::string to_string(SweepDirection direction) {
  return direction == SweepDirection::up ? "up" : "down";
}

std::vector<SweepPointResult> sweep_line(
    const SimulationCase& line_case, const TableFor& table_for, const std::string& key,
    const std::vector<double>& grid, SweepDirection direction, int line,
    const SteadySettings& settings, const std::function<void(const SweepPointResult&)>& on_point) {
  sweep_field(key, "--vary");
  const double rb1 = base_radius(line_case.gears, Gear::one);
  const double rb2 = base_radius(line_case.gears, Gear::two);
  std::vector<SweepPointResult> results;
  std::optional<RunState> carried;
  double carried_value = 0.0;
  const int n = static_cast<int>(grid.size());
  for (int step = 0; step < n; ++step) {
    const int index = direction == SweepDirection::up ? step : n - 1 - step;
    const double value = grid[static_cast<std::size_t>(index)];
    SimulationCase c = line_case;
    apply_sweep_value(c, line_case, key, value);
    std::optional<RunState> start = carried;
    if (start && (key == "initial.w1" || key == "initial.w2")) {
      // The relative motion s' = Rb1 w1 - Rb2 w2 carries over; the mean speed moves.
      const double dw = value - carried_value;
      if (key == "initial.w1") {
        start->state.w1_rad_per_s += dw;
        start->state.w2_rad_per_s += dw * rb1 / rb2;
      } else {
        start->state.w2_rad_per_s += dw;
        start->state.w1_rad_per_s += dw * rb2 / rb1;
      }
    }
    SweepPointResult r;
    r.line = line;
    r.direction = direction;
    r.index = index;
    r.value_si = value;
    try {
      const std::shared_ptr<const StiffnessTable> table = table_for(c);
      r.point = find_steady_state(c, *table, settings, start);
      carried = r.point.final_state;
    } catch (const SimulationError& e) {
      r.failure = e.what();
      r.point.explanation = e.what();
      carried.reset();
    }
    carried_value = value;
    if (on_point) on_point(r);
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace gearimpact
