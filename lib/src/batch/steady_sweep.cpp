#include "gearimpact/batch/steady_sweep.hpp"

#include <algorithm>
#include <exception>
#include <future>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/error.hpp"

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
  return shard_units(lines, spec.directions, spec.shard).size() *
         static_cast<std::size_t>(spec.points);
}

SteadySweep run_steady_sweep(const SteadySweepSpec& spec, RunPool& pool,
                             const std::function<void(const SweepPointResult&)>& on_point) {
  sweep_field(spec.vary, "vary");
  const std::vector<double> grid =
      sweep_grid(spec.from_si, spec.to_si, spec.points, "from", "to", "points");
  std::vector<double> grid2{0.0};
  if (!spec.vary2.empty()) {
    sweep_field(spec.vary2, "vary2");
    grid2 = sweep_grid(spec.from2_si, spec.to2_si, spec.points2, "from2", "to2", "points2");
  }
  if (spec.shard.n < 1 || spec.shard.k < 0 || spec.shard.k >= spec.shard.n) {
    throw InputError("shard", std::to_string(spec.shard.k) + "/" + std::to_string(spec.shard.n),
                     "K/N with 0 <= K < N");
  }
  if (spec.directions.empty()) throw InputError("directions", "none", "up, down or both");
  const SimulationCase& base = spec.base;
  // Refuse a case without a steady state before any work, naming the key.
  {
    SimulationCase probe = base;
    if (!spec.vary2.empty()) apply_sweep_value(probe, base, spec.vary2, grid2.front());
    apply_sweep_value(probe, SimulationCase(probe), spec.vary, grid.front());
    validate(probe);
    require_steady_case(probe);
  }
  SteadySweep sweep;
  SteadySweepRecord& record = sweep.spec;
  record.case_name = base.name;
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
  if (spec.vary == "initial.w1") record.iso = iso_scale(base, *pool.table_for(base));
  record.tolerance = spec.settings.tolerance;
  record.steps_per_contact_period = spec.settings.steps_per_contact_period;
  record.max_periods = spec.settings.max_periods;
  record.damping_update = base.model.damping_update;
  sweep.shard = spec.shard;

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
