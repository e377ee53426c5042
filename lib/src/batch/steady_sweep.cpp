#include "gearimpact/batch/steady_sweep.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <future>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"

namespace gearimpact {

namespace {

struct LineOfWork {
  int line;
  SweepDirection direction;
};

std::vector<LineOfWork> shard_units(std::size_t lines,
                                    const std::vector<SweepDirection>& directions,
                                    const SweepShard& shard) {
  std::vector<LineOfWork> units;
  int u = 0;
  for (int line = 0; line < static_cast<int>(lines); ++line) {
    for (SweepDirection d : directions) {
      if (u++ % shard.n == shard.k) units.push_back({line, d});
    }
  }
  return units;
}

// Refuses, naming `flag`, a swept key that no point of the run reads.
void require_read_key(const std::string& key, const SimulationCase& c, const char* flag) {
  const Field& field = sweep_field(key, flag);
  if (field.section == "integrator") {
    throw InputError(flag, key,
                     "a key the steady state reads: it sets the integrator itself (RK4, the step "
                     "from the steps per contact period, a run per excitation period)");
  }
  // The condition as the run resolves it: damping_update = "auto" reads as the reading the
  // bearings give it (each-impact on rigid bearings, frozen on elastic ones), which a frozen D's
  // reference speed does not enter under each-impact.
  SimulationCase resolved = c;
  resolved.model.damping_update = resolved_damping_update(c);
  if (!applies(field, resolved)) {
    throw InputError(
        flag, key,
        "a key this case reads: " + key + " applies only when " + field.only_when->text() +
            (c.model.damping_update == DampingUpdate::automatic &&
                     field.only_when->key == "damping_update"
                 ? " (here damping_update = \"auto\" resolves to \"" +
                       std::string(name_of(kDampingUpdates, resolved.model.damping_update)) +
                       "\" by the bearings)"
                 : std::string()));
  }
}

// Refuses, naming `points_key`, a grid of an integer key with a value that is not whole: the
// point there would fail after the points before it ran.
void require_whole_grid(const std::string& key, const std::vector<double>& grid,
                        const char* points_key) {
  if (sweep_field(key, points_key).kind != FieldKind::integer) return;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    if (grid[i] != std::round(grid[i])) {
      throw InputError(points_key,
                       std::to_string(grid.size()) + " (" + key + " = " +
                           shortest_decimal(grid[i]) + " at index " + std::to_string(i) + ")",
                       "a count that puts every value of the integer key " + key +
                           " on a whole number: (to - from) / (points - 1) whole");
    }
  }
}

// The settings' bounds (steady_sweep.hpp), before any work.
void require_settings(const SteadySettings& s) {
  if (!(s.steps_per_contact_period >= kLeastStepsPerContactPeriod &&
        s.steps_per_contact_period <= kMostStepsPerContactPeriod)) {
    throw InputError("steps_per_contact_period", s.steps_per_contact_period,
                     "[" + shortest_decimal(kLeastStepsPerContactPeriod) + ", " +
                         shortest_decimal(kMostStepsPerContactPeriod) + "]");
  }
  if (s.max_periods < 1 || s.max_periods > kMostMaxPeriods) {
    throw InputError("max_periods", std::to_string(s.max_periods),
                     "an integer in [1, " + std::to_string(kMostMaxPeriods) + "]");
  }
  if (!(s.tolerance > 0.0 && s.tolerance <= kMostTolerance)) {
    throw InputError("tolerance", s.tolerance, "(0, " + shortest_decimal(kMostTolerance) + "]");
  }
}

std::string fnv1a_hex(const std::string& text) {
  std::uint64_t hash = 14695981039346656037ull;
  for (unsigned char ch : text) {
    hash ^= ch;
    hash *= 1099511628211ull;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016" PRIx64, hash);
  return hex;
}

}  // namespace

bool sweep_key_less(const SweepPointResult& a, const SweepPointResult& b) {
  const auto key = [](const SweepPointResult& r) {
    return std::make_tuple(r.line, r.direction == SweepDirection::up ? 0 : 1, r.index);
  };
  return key(a) < key(b);
}

std::size_t shard_point_count(const SteadySweepSpec& spec) {
  if (spec.points < 1 || spec.shard.n < 1 || spec.shard.k < 0 || spec.shard.k >= spec.shard.n) {
    return 0;
  }
  const std::size_t lines = spec.vary2.empty() ? 1 : static_cast<std::size_t>(spec.points2);
  // A sweep over its bound is refused by run_steady_sweep; its units are not
  // listed here (a billion lines are gigabytes).
  if (!(static_cast<double>(lines) * static_cast<double>(spec.points) *
            static_cast<double>(std::max<std::size_t>(1, spec.directions.size())) <=
        spec.max_points)) {
    return 0;
  }
  return shard_units(lines, spec.directions, spec.shard).size() *
         static_cast<std::size_t>(spec.points);
}

std::vector<std::string> sweep_warnings(const SteadySweepSpec& spec) {
  std::vector<std::string> warnings;
  const SimulationCase& c = spec.base;
  const auto swept = [&](const char* key) { return spec.vary == key || spec.vary2 == key; };
  if (c.model.mesh_damping_ratio == 0.0 &&
      resolved_damping_update(c) == DampingUpdate::each_impact &&
      !swept("model.mesh_damping_ratio")) {
    warnings.push_back(
        "model.mesh_damping_ratio = 0 with model.damping_update = \"each-impact\": nothing damps "
        "a no-impact point but the Hertzian D, which it carries from an earlier point's last "
        "impact, so up and down sweeps differ there (by percents) as an artefact of the history; "
        "set a mesh damper and a D without history, e.g. --set model.mesh_damping_ratio=0.05 "
        "--damping-update frozen --set 'model.damping_reference_speed=0.1 m/s' (docs/sweep.md)");
  }
  // A kinematic driver holds w1 whatever w2 starts at: no momentum mean speed to warn of.
  if (!swept("initial.w1") && !swept("initial.w2") &&
      c.torque1.kind != Torque::Kind::prescribed_speed) {
    // A helical pair's base radii are its transverse section's.
    const GearPair pair = swept_transverse_pair(c.gears);
    const double rb1 = base_radius(pair, Gear::one);
    const double rb2 = base_radius(pair, Gear::two);
    const double v1 = rb1 * c.initial.w1_rad_per_s;
    const double v2 = rb2 * c.initial.w2_rad_per_s;
    // The speeds as typed round a rolling pair by a few ulps.
    if (std::fabs(v1 - v2) > 1e-12 * std::max(std::fabs(v1), std::fabs(v2))) {
      double j1 = moment_of_inertia(c.gears, Gear::one);
      double j2 = moment_of_inertia(c.gears, Gear::two);
      if (c.bearings.kind == BearingKind::elastic && c.shafts.kind == ShaftKind::elastic) {
        // The motor and the load turn with their gears (as the steady state's mean speed).
        j1 += c.shafts.motor_inertia_kg_m2;
        j2 += c.shafts.load_inertia_kg_m2;
      }
      const double w1_mean =
          (j1 * c.initial.w1_rad_per_s / rb1 + j2 * c.initial.w2_rad_per_s / rb2) /
          (j1 / rb1 + j2 * rb1 / (rb2 * rb2));
      warnings.push_back(
          "initial.w1 = " + shortest_decimal(c.initial.w1_rad_per_s) +
          " rad/s and initial.w2 = " + shortest_decimal(c.initial.w2_rad_per_s) +
          " rad/s do not roll (Rb1 w1 != Rb2 w2): the points run at the momentum's mean speed, "
          "w1 = " +
          format_number(w1_mean) + " rad/s (" + format_number(w1_mean * 60.0 / (2.0 * pi)) +
          " rpm); set initial.w2 = initial.w1 Rb1/Rb2 = " +
          format_number(c.initial.w1_rad_per_s * rb1 / rb2) +
          " rad/s for the pinion speed the case gives (w1_mean_rad_s in sweep.csv is what ran)");
    }
  }
  return warnings;
}

SteadySweep run_steady_sweep(const SteadySweepSpec& spec, RunPool& pool,
                             const std::function<void(const SweepPointResult&)>& on_point) {
  // A helical pair sweeps as simulate runs it (its transverse section with
  // its pair table); what its run refuses is refused here, by name.
  validate_absent_run_keys(spec.base);
  refuse_helical_run(spec.base);
  sweep_field(spec.vary, "vary");
  if (!spec.vary2.empty()) {
    sweep_field(spec.vary2, "vary2");
    if (spec.vary2 == spec.vary) {
      throw InputError("vary2", spec.vary2, "a key other than the first swept key " + spec.vary);
    }
    // A swept speed sets the other so that the pair rolls: the two cannot vary apart.
    const auto speed = [](const std::string& key) {
      return key == "initial.w1" || key == "initial.w2";
    };
    if (speed(spec.vary) && speed(spec.vary2)) {
      throw InputError("vary2", spec.vary2,
                       "a key other than the other speed: a sweep of " + spec.vary +
                           " sets the other speed so that the pair rolls (Rb1 w1 = Rb2 w2); "
                           "sweep one speed, or the relative motion through another key");
    }
  }
  if (!(spec.max_points >= 1.0)) {
    throw InputError("max_points", shortest_decimal(spec.max_points),
                     "a count >= 1 (a finite bound on the points of the whole sweep)");
  }
  if (std::isfinite(spec.from_si) && std::isfinite(spec.to_si) &&
      !std::isfinite(spec.to_si - spec.from_si)) {
    throw InputError("to", shortest_decimal(spec.to_si),
                     "a value whose distance from the first value (from, " +
                         shortest_decimal(spec.from_si) + ") is a finite number");
  }
  // The bound on the work before the grids are made: a grid of a billion values is gigabytes.
  if (spec.points >= 1 && (spec.vary2.empty() || spec.points2 >= 1)) {
    const double lines = spec.vary2.empty() ? 1.0 : static_cast<double>(spec.points2);
    const double total = static_cast<double>(spec.points) * lines *
                         static_cast<double>(std::max<std::size_t>(1, spec.directions.size()));
    if (total > spec.max_points) {
      throw InputError("max_points",
                       shortest_decimal(total) + " points (" + std::to_string(spec.points) +
                           " points x " + shortest_decimal(lines) + " lines x " +
                           std::to_string(spec.directions.size()) + " directions)",
                       "at most " + shortest_decimal(spec.max_points) + " points a sweep");
    }
  }
  if (spec.points > 1 && spec.from_si > spec.to_si) {
    throw InputError("from", spec.from_si,
                     "at most the last value (to, " + format_number(spec.to_si) +
                         "): a sweep runs up from the lower end, and its down direction back");
  }
  require_settings(spec.settings);
  const std::vector<double> grid =
      sweep_grid(spec.from_si, spec.to_si, spec.points, "from", "to", "points");
  std::vector<double> grid2{0.0};
  if (!spec.vary2.empty()) {
    grid2 = sweep_grid(spec.from2_si, spec.to2_si, spec.points2, "from2", "to2", "points2");
  }
  require_whole_grid(spec.vary, grid, "points");
  if (!spec.vary2.empty()) require_whole_grid(spec.vary2, grid2, "points2");
  if (spec.shard.n < 1 || spec.shard.k < 0 || spec.shard.k >= spec.shard.n) {
    throw InputError("shard", std::to_string(spec.shard.k) + "/" + std::to_string(spec.shard.n),
                     "K/N with 0 <= K < N");
  }
  if (spec.directions.empty()) throw InputError("directions", "none", "up, down or both");
  const SimulationCase& base = spec.base;
  // Refuse, before any work and naming the key, a swept key the run does not read and a case
  // without a steady state at either end of each grid (a key's range may hold at one end only).
  require_read_key(spec.vary, base, "vary");
  if (!spec.vary2.empty()) require_read_key(spec.vary2, base, "vary2");
  // The Poincare period at the first and the last point of the sweep, for its record.
  SteadyTiming first_timing;
  SteadyTiming last_timing;
  for (const double value2 : {grid2.front(), grid2.back()}) {
    for (const double value : {grid.front(), grid.back()}) {
      // The end named in the message: a key derived from the swept one (the step) is not a
      // key the user wrote.
      const std::string end =
          spec.vary + " = " + shortest_decimal(value) +
          (spec.vary2.empty() ? std::string()
                              : ", " + spec.vary2 + " = " + shortest_decimal(value2));
      // Every problem at this end at once; the steady-state checks only on a valid case,
      // the step only when both passed.
      Problems problems;
      SimulationCase probe = base;
      if (problems.collect([&] {
            if (!spec.vary2.empty()) apply_sweep_value(probe, base, spec.vary2, value2);
            apply_sweep_value(probe, SimulationCase(probe), spec.vary, value);
            validate(probe);
          })) {
        problems.collect([&] { require_steady_case(probe); });
      }
      if (problems.empty()) {
        problems.collect([&] {
          // The step the run would take there: a value far out (a speed of 1e308 rad/s)
          // leaves no finite step, which validate cannot see without the mesh stiffness.
          const SteadyTiming timing = steady_timing(probe, *pool.table_for(probe), spec.settings);
          if (!(std::isfinite(timing.step_s) && timing.step_s > 0.0 &&
                timing.steps_per_period >= 1)) {
            throw InputError(spec.vary2.empty() ? spec.vary : spec.vary + ", " + spec.vary2,
                             std::isfinite(timing.step_s)
                                 ? "the step " + shortest_decimal(timing.step_s) + " s"
                                 : std::string("no finite step"),
                             "values at which the steady state's RK4 step is a positive time");
          }
          if (value2 == grid2.front() && value == grid.front()) first_timing = timing;
          if (value2 == grid2.back() && value == grid.back()) last_timing = timing;
        });
      }
      if (!problems.empty()) {
        std::vector<Problem> at_end;
        for (const Problem& p : problems.list()) {
          at_end.push_back(p.renamed(p.field, p.value + " (at " + end + ", an end of the sweep)"));
        }
        throw InputError(std::move(at_end));
      }
    }
  }
  SteadySweep sweep;
  SteadySweepRecord& record = sweep.spec;
  record.case_name = base.name;
  record.case_key_hash = fnv1a_hex(case_key(base));
  record.vary = spec.vary;
  record.from_si = grid.front();
  record.to_si = grid.back();
  record.points = static_cast<int>(grid.size());
  record.vary2 = spec.vary2;
  if (!spec.vary2.empty()) {
    record.from2_si = grid2.front();
    record.to2_si = grid2.back();
  }
  record.lines = static_cast<int>(grid2.size());
  record.directions = spec.directions;
  record.backlash_m = base.gears.backlash_m;
  record.unit = spec.unit;
  record.unit2 = spec.unit2;
  if (spec.vary == "initial.w1") record.mesh_teeth = base.gears.teeth1;
  if (spec.vary == "initial.w2") record.mesh_teeth = base.gears.teeth2;
  // ISO 6336's resonance scale is that of a spur pair here: none for a helical one.
  if (spec.vary == "initial.w1" && base.gears.helix_angle_rad == 0.0) {
    record.iso = iso_scale(base, *pool.table_for(base));
  }
  record.tolerance = spec.settings.tolerance;
  record.steps_per_contact_period = spec.settings.steps_per_contact_period;
  record.max_periods = spec.settings.max_periods;
  record.damping_update = resolved_damping_update(base);
  record.poincare_period_kind = first_timing.kind;
  record.poincare_period_s = {first_timing.excitation_period_s, last_timing.excitation_period_s};
  record.poincare_mesh_periods = {first_timing.mesh_periods, last_timing.mesh_periods};
  sweep.shard = spec.shard;
  sweep.warnings = sweep_warnings(spec);

  std::vector<std::future<std::vector<SweepPointResult>>> futures;
  for (const LineOfWork& unit : shard_units(grid2.size(), spec.directions, spec.shard)) {
    futures.push_back(pool.run([&, unit] {
      SimulationCase line_case = base;
      if (!spec.vary2.empty()) {
        apply_sweep_value(line_case, base, spec.vary2, grid2[static_cast<std::size_t>(unit.line)]);
      }
      return sweep_line(
          line_case, [&pool](const SimulationCase& c) { return pool.table_for(c); }, spec.vary,
          grid, unit.direction, unit.line, spec.settings, on_point);
    }));
  }
  // Every future is waited for before an error leaves, so that no task outlives what it refers to.
  std::exception_ptr error;
  for (auto& f : futures) {
    try {
      for (SweepPointResult& r : f.get()) sweep.rows.push_back(std::move(r));
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  std::sort(sweep.rows.begin(), sweep.rows.end(), sweep_key_less);
  return sweep;
}

SteadySweep run_steady_sweep(const SteadySweepSpec& spec,
                             const std::function<void(const SweepPointResult&)>& on_point) {
  RunPool pool(spec.threads);
  return run_steady_sweep(spec, pool, on_point);
}

}  // namespace gearimpact
