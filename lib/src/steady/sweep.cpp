#include "gearimpact/steady/sweep.hpp"

#include <cmath>
#include <optional>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

namespace {

struct KeyEntry {
  SweepKey key;
  std::function<void(SimulationCase&, double)> set;
};

void make_sinusoidal(Torque& t) {
  if (t.kind == Torque::Kind::constant) {
    t.kind = Torque::Kind::sinusoidal;
    t.mean_n_m = t.constant_n_m;
  }
}

std::vector<KeyEntry> make_keys() {
  std::vector<KeyEntry> keys;
  const auto quantity = [](const char* name, Dimension d) { return SweepKey{name, false, d}; };
  for (int gear = 1; gear <= 2; ++gear) {
    const std::string prefix = gear == 1 ? "torque1." : "torque2.";
    const auto torque = [gear](SimulationCase& c) -> Torque& {
      return gear == 1 ? c.torque1 : c.torque2;
    };
    keys.push_back({quantity((prefix + "mean").c_str(), Dimension::torque),
                    [torque](SimulationCase& c, double v) {
                      Torque& t = torque(c);
                      if (t.kind == Torque::Kind::constant) {
                        t.constant_n_m = v;
                      } else {
                        t.mean_n_m = v;
                      }
                    }});
    keys.push_back({quantity((prefix + "amplitude").c_str(), Dimension::torque),
                    [torque](SimulationCase& c, double v) {
                      make_sinusoidal(torque(c));
                      torque(c).amplitude_n_m = v;
                    }});
    keys.push_back({quantity((prefix + "angular_frequency").c_str(), Dimension::angular_frequency),
                    [torque](SimulationCase& c, double v) {
                      make_sinusoidal(torque(c));
                      torque(c).angular_frequency_rad_s = v;
                    }});
    keys.push_back({quantity((prefix + "phase").c_str(), Dimension::angle),
                    [torque](SimulationCase& c, double v) {
                      make_sinusoidal(torque(c));
                      torque(c).phase_rad = v;
                    }});
  }
  keys.push_back({quantity("initial.w1", Dimension::angular_velocity),
                  [](SimulationCase& c, double v) { c.initial.w1_rad_s = v; }});
  keys.push_back({quantity("initial.w2", Dimension::angular_velocity),
                  [](SimulationCase& c, double v) { c.initial.w2_rad_s = v; }});
  keys.push_back({quantity("gears.backlash", Dimension::length),
                  [](SimulationCase& c, double v) { c.gears.backlash_m = v; }});
  keys.push_back({SweepKey{"model.friction_coefficient", true, Dimension::length},
                  [](SimulationCase& c, double v) { c.model.friction_coefficient = v; }});
  keys.push_back({SweepKey{"model.mesh_damping_ratio", true, Dimension::length},
                  [](SimulationCase& c, double v) { c.model.mesh_damping_ratio = v; }});
  // N/m has no Dimension of its own in io/units: a force per length is a pressure times a
  // length, so the key is read as a plain number in N/m.
  keys.push_back({SweepKey{"model.constant_mesh_stiffness", true, Dimension::length},
                  [](SimulationCase& c, double v) {
                    c.model.mesh_stiffness = MeshStiffnessMode::constant;
                    c.model.constant_mesh_stiffness_n_m = v;
                  }});
  keys.push_back({quantity("model.damping_reference_speed", Dimension::speed),
                  [](SimulationCase& c, double v) { c.model.damping_reference_speed_m_s = v; }});
  return keys;
}

const std::vector<KeyEntry>& keys() {
  static const std::vector<KeyEntry> table = make_keys();
  return table;
}

const KeyEntry& entry(const std::string& name) {
  for (const KeyEntry& e : keys()) {
    if (e.key.name == name) return e;
  }
  std::string list;
  for (const KeyEntry& e : keys()) list += (list.empty() ? "" : ", ") + e.key.name;
  throw InputError("--vary", name, "a numeric case-file key as section.key: " + list);
}

}  // namespace

const SweepKey& sweep_key(const std::string& name) {
  return entry(name).key;
}

std::vector<std::string> sweep_key_names() {
  std::vector<std::string> names;
  for (const KeyEntry& e : keys()) names.push_back(e.key.name);
  return names;
}

void set_sweep_value(SimulationCase& c, const std::string& key, double si_value) {
  entry(key).set(c, si_value);
}

void apply_sweep_value(SimulationCase& c, const SimulationCase& base, const std::string& key,
                       double si_value) {
  set_sweep_value(c, key, si_value);
  const double rb1 = base_radius(base.gears, Gear::one);
  const double rb2 = base_radius(base.gears, Gear::two);
  if (key == "initial.w1") {
    c.initial.w2_rad_s = base.initial.w2_rad_s + (si_value - base.initial.w1_rad_s) * rb1 / rb2;
  } else if (key == "initial.w2") {
    c.initial.w1_rad_s = base.initial.w1_rad_s + (si_value - base.initial.w2_rad_s) * rb2 / rb1;
  } else if (key == "torque1.mean") {
    set_sweep_value(c, "torque2.mean", -si_value * rb2 / rb1);
  } else if (key == "torque2.mean") {
    set_sweep_value(c, "torque1.mean", -si_value * rb1 / rb2);
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
  sweep_key(key);
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
        start->state.w1_rad_s += dw;
        start->state.w2_rad_s += dw * rb1 / rb2;
      } else {
        start->state.w2_rad_s += dw;
        start->state.w1_rad_s += dw * rb2 / rb1;
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
