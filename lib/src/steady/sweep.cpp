#include "gearimpact/steady/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"

namespace gearimpact {

namespace {

// "section.key[i]": an element of a list key.
struct ListElement {
  std::string list;
  std::size_t index;
};

std::optional<ListElement> list_element(const std::string& key) {
  const std::size_t open = key.rfind('[');
  if (open == std::string::npos || key.back() != ']') return std::nullopt;
  const std::string digits = key.substr(open + 1, key.size() - open - 2);
  // Six digits are far beyond any list's length and cannot overflow.
  if (digits.empty() || digits.size() > 6 ||
      !std::all_of(digits.begin(), digits.end(), [](char d) { return d >= '0' && d <= '9'; })) {
    return std::nullopt;
  }
  return ListElement{key.substr(0, open), static_cast<std::size_t>(std::stoul(digits))};
}

// The list a case holds at an element key, refused when the index is past its end.
std::vector<double> list_holding(const SimulationCase& c, const Field& list, const std::string& key,
                                 std::size_t index) {
  std::vector<double> values = list.get_list(c);
  if (index >= values.size()) {
    throw InputError(key, "element " + std::to_string(index),
                     values.empty() ? "no index: the case's " + list.name() + " is empty"
                                    : "an index in [0, " + std::to_string(values.size() - 1) +
                                          "]: the case's " + list.name() + " has " +
                                          std::to_string(values.size()) + " element" +
                                          (values.size() == 1 ? "" : "s"));
  }
  return values;
}

// A schema row for one element of a list row, made once per key and kept (sweep_field hands out
// references), its section and key held beside it.
struct ElementRow {
  std::string section;
  std::string key;
  Field field;
};

const Field& element_field(const std::string& key, const Field& list, std::size_t index) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<ElementRow>> rows;
  const std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<ElementRow>& row = rows[key];
  if (!row) {
    row = std::make_unique<ElementRow>();
    row->section = std::string(list.section);
    row->key = std::string(list.key) + "[" + std::to_string(index) + "]";
    Field& f = row->field;
    f = list;
    f.section = row->section;
    f.key = row->key;
    f.kind = list.kind == FieldKind::quantity_list ? FieldKind::quantity : FieldKind::number;
    f.help = "element " + std::to_string(index) + " of " + list.name() + ": " + list.help;
    const Field* whole = &list;
    f.get = [whole, key, index](const SimulationCase& c) {
      return list_holding(c, *whole, key, index)[index];
    };
    f.set = [whole, key, index](SimulationCase& c, double value) {
      std::vector<double> values = list_holding(c, *whole, key, index);
      values[index] = value;
      whole->set_list(c, values);
    };
    f.get_list = nullptr;
    f.set_list = nullptr;
    f.most_values = 0;
  }
  return row->field;
}

}  // namespace

const Field& sweep_field(const std::string& key, const std::string& flag) {
  if (const std::optional<ListElement> element = list_element(key)) {
    const Field* list = find_field(element->list);
    if (list != nullptr &&
        (list->kind == FieldKind::quantity_list || list->kind == FieldKind::number_list)) {
      if (element->index >= list->most_values) {
        throw InputError(flag, key,
                         "an index in [0, " + std::to_string(list->most_values - 1) +
                             "]: " + list->name() + " holds at most " +
                             std::to_string(list->most_values) + " elements");
      }
      return element_field(key, *list, element->index);
    }
  }
  const Field* field = find_field(key);
  if (field == nullptr || (field->kind != FieldKind::quantity && field->kind != FieldKind::number &&
                           field->kind != FieldKind::integer)) {
    // The nearest key, when the key is a typo rather than a key of another kind.
    const std::optional<std::string> nearest = field == nullptr ? nearest_key(key) : std::nullopt;
    throw InputError(
        flag, key,
        "a quantity, number or integer key of the case schema, as section.key, or an element "
        "of a list key, as section.key[i] "
        "(`gearimpact schema` lists them)",
        nearest ? "did you mean " + *nearest + "?" : std::string());
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
  if (const std::optional<ListElement> element = list_element(key)) {
    // The whole list through the schema, so that its row checks the element's range.
    std::vector<double> values = list_holding(c, *find_field(element->list), key, element->index);
    values[element->index] = si_value;
    std::string text;
    for (double v : values) text += (text.empty() ? "" : ", ") + shortest_decimal(v);
    // Named as the list's element, which is the key as swept.
    set_field(c, element->list, text, element->list);
    return;
  }
  // A plain number is read as SI, and shortest_decimal reads back to the same double.
  set_field(c, key, shortest_decimal(si_value));
}

void apply_sweep_value(SimulationCase& c, const SimulationCase& base, const std::string& key,
                       double si_value) {
  set_sweep_value(c, key, si_value);
  // A helical pair's base radii are its transverse section's.
  const GearPair pair = swept_transverse_pair(base.gears);
  const double rb1 = base_radius(pair, Gear::one);
  const double rb2 = base_radius(pair, Gear::two);
  // A speed sets the pair rolling at it (Rb1 w1 = Rb2 w2), whatever base's other speed: without
  // fluctuating torques the mean speed follows from the momentum J1 w1/Rb1 + J2 w2/Rb2, so a
  // pair that does not roll would run at another speed than the one set. The other speed is
  // written as base's rolling speed moved by the change, equal to si_value Rb1/Rb2 to rounding
  // and exactly base's own speed for a base that rolls.
  if (key == "initial.w1") {
    const double rolling_w2 = base.initial.w1_rad_per_s * rb1 / rb2;
    c.initial.w2_rad_per_s = rolling_w2 + (si_value - base.initial.w1_rad_per_s) * rb1 / rb2;
  } else if (key == "initial.w2") {
    const double rolling_w1 = base.initial.w2_rad_per_s * rb2 / rb1;
    c.initial.w1_rad_per_s = rolling_w1 + (si_value - base.initial.w2_rad_per_s) * rb2 / rb1;
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

namespace {

// The converged points of each line and direction, in the order the line ran.
std::vector<std::vector<const SweepPointResult*>> runs_of(
    const std::vector<SweepPointResult>& rows) {
  std::vector<const SweepPointResult*> sorted;
  for (const SweepPointResult& r : rows) {
    if (r.point.converged) sorted.push_back(&r);
  }
  const auto key = [](const SweepPointResult* r) {
    const bool up = r->direction == SweepDirection::up;
    return std::make_tuple(r->line, up ? 0 : 1, up ? r->index : -r->index);
  };
  std::sort(sorted.begin(), sorted.end(),
            [&](const SweepPointResult* a, const SweepPointResult* b) { return key(a) < key(b); });
  std::vector<std::vector<const SweepPointResult*>> runs;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    if (i == 0 || sorted[i]->line != sorted[i - 1]->line ||
        sorted[i]->direction != sorted[i - 1]->direction) {
      runs.emplace_back();
    }
    runs.back().push_back(sorted[i]);
  }
  return runs;
}

}  // namespace

std::vector<SweepJump> sweep_jumps(const std::vector<SweepPointResult>& rows) {
  std::vector<SweepJump> jumps;
  for (const auto& run : runs_of(rows)) {
    for (std::size_t i = 1; i < run.size(); ++i) {
      const SweepPointResult& a = *run[i - 1];
      const SweepPointResult& b = *run[i];
      const double before = a.point.dte_amplitude_m.value_or(0.0);
      const double after = b.point.dte_amplitude_m.value_or(0.0);
      if (!(before > 0.0 && after > 0.0) ||
          std::max(before / after, after / before) <= kJumpRatio) {
        continue;
      }
      jumps.push_back({a.line, a.direction, a.value_si, b.value_si, before, after, a.point.regime,
                       b.point.regime});
    }
  }
  return jumps;
}

std::vector<ContactChange> contact_changes(const std::vector<SweepPointResult>& rows) {
  const auto impacting = [](Regime r) {
    return r == Regime::single_sided || r == Regime::double_sided;
  };
  std::vector<ContactChange> changes;
  for (const auto& run : runs_of(rows)) {
    for (std::size_t i = 1; i < run.size(); ++i) {
      const SweepPointResult& a = *run[i - 1];
      const SweepPointResult& b = *run[i];
      const Regime before = a.point.regime;
      const Regime after = b.point.regime;
      const bool lost = before == Regime::no_impact && impacting(after);
      const bool regained = impacting(before) && after == Regime::no_impact;
      if (lost || regained) {
        changes.push_back({a.line, a.direction, lost, a.value_si, b.value_si, before, after});
      }
    }
  }
  return changes;
}

std::vector<SweepPointResult> sweep_line(
    const SimulationCase& line_case, const TableFor& table_for, const std::string& key,
    const std::vector<double>& grid, SweepDirection direction, int line,
    const SteadySettings& settings, const std::function<void(const SweepPointResult&)>& on_point) {
  sweep_field(key, "--vary");
  const GearPair pair = swept_transverse_pair(line_case.gears);
  const double rb1 = base_radius(pair, Gear::one);
  const double rb2 = base_radius(pair, Gear::two);
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
      const double dw1 = key == "initial.w1" ? dw : dw * rb2 / rb1;
      const double dw2 = key == "initial.w1" ? dw * rb1 / rb2 : dw;
      if (key == "initial.w1") {
        start->state.w1_rad_per_s += dw;
        start->state.w2_rad_per_s += dw * rb1 / rb2;
      } else {
        start->state.w2_rad_per_s += dw;
        start->state.w1_rad_per_s += dw * rb2 / rb1;
      }
      if (start->planar) {
        // The planar state's gears, and the motor and the load turning with them.
        PlanarState& p = *start->planar;
        p.w1_rad_per_s = start->state.w1_rad_per_s;
        p.w2_rad_per_s = start->state.w2_rad_per_s;
        p.w_motor_rad_per_s += dw1;
        p.w_load_rad_per_s += dw2;
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
