// The steady-state sweep of a case (docs/steady-state.md section 4): one key along a grid,
// optionally one line per value of a second key, each line up and/or down, the lines run in
// parallel on a RunPool and split into shards K/N for separate processes. The rows come back keyed
// (line, direction, index) and sorted by key, so that shards merged by key (io/sweep_files.hpp)
// give the same rows as one run.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/batch/pool.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/steady/iso_resonance.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/steady/sweep.hpp"

namespace gearimpact {

// The lines u = line x direction (in that order, directions inner) with u % n == k.
struct SweepShard {
  int k = 0;
  int n = 1;
};

// The most points (grid points x lines x directions) a sweep runs unless its spec lifts the
// bound (SteadySweepSpec::max_points): a typing slip of --points must not start a run of days.
inline constexpr double kMostSweepPoints = 100000;
// The bounds of SteadySettings a sweep accepts: fewer steps than kLeastStepsPerContactPeriod do
// not resolve an impact (RK4 is then not stable on the stiffest contact), more than
// kMostStepsPerContactPeriod only cost time; a tolerance is a fraction of the backlash.
inline constexpr double kLeastStepsPerContactPeriod = 20;
inline constexpr double kMostStepsPerContactPeriod = 1e4;
inline constexpr int kMostMaxPeriods = 1000000;
inline constexpr double kMostTolerance = 0.1;

struct SteadySweepSpec {
  SimulationCase base;  // the case every point starts from, before the swept keys are set
  std::string vary;     // section.key (sweep_field): swept along each line
  double from_si = 0.0;
  double to_si = 0.0;
  int points = 0;
  std::string vary2;  // empty: one line (line 0) of the base case
  // The units the user gave the grids in (a symbol of the key's dimension, as in case files), for
  // the figures; empty: none given.
  std::string unit;
  std::string unit2;
  double from2_si = 0.0;
  double to2_si = 0.0;
  int points2 = 1;
  std::vector<SweepDirection> directions{SweepDirection::up, SweepDirection::down};
  SweepShard shard;
  SteadySettings settings;
  unsigned threads = 0;  // for the pool run_steady_sweep makes itself; 0: one per core
  double max_points = kMostSweepPoints;  // the most points of the whole sweep (all shards)
};

// What every shard of one sweep shares (summary.json's "spec"): the merge checks that the shards
// agree on it and keeps it.
struct SteadySweepRecord {
  std::string case_name;
  // FNV-1a (64 bits, hex) of case_key(base): every input of the base case (the damping ratio and
  // reference speed among them), so that shards of differently set cases do not merge.
  std::string case_key_hash;
  std::string vary;
  double from_si = 0.0;  // the grid's ends
  double to_si = 0.0;
  int points = 0;
  std::string vary2;  // empty: one line, and no from2_si, to2_si
  std::optional<double> from2_si;
  std::optional<double> to2_si;
  int lines = 1;
  std::vector<SweepDirection> directions;
  double backlash_m = 0.0;  // of the base case
  std::string unit;         // SteadySweepSpec's, for the figures
  std::string unit2;
  // For a sweep of a speed: the teeth of that gear, whose mesh frequency is z w / (2 pi); else 0.
  int mesh_teeth = 0;
  // For a sweep of initial.w1 of a loaded pair: ISO's N axis of the base case's pair and load (a
  // second key that changes them is not seen).
  std::optional<IsoScale> iso;
  double tolerance = 0.0;
  double steps_per_contact_period = 0.0;
  int max_periods = 0;
  DampingUpdate damping_update = DampingUpdate::each_impact;
  // The Poincare period (SteadyTiming) at the first and the last point of the sweep (line 0's
  // first value, the last line's last value): what it is the common period of, its length and
  // its mesh periods (0: not tied to the mesh).
  std::string poincare_period_kind;
  std::array<double, 2> poincare_period_s{};
  std::array<long long, 2> poincare_mesh_periods{};
};

struct SteadySweep {
  SteadySweepRecord spec;
  std::optional<SweepShard> shard;  // the shard a run computed; empty for a merged set
  std::vector<SweepPointResult> rows;
  // What the user should know of the results (sweep_warnings), shared by every shard.
  std::vector<std::string> warnings;
};

// The warnings of a sweep, from its spec alone: a damper-free sweep (zeta = 0) whose Hertzian D
// is updated at every impact (its no-impact points carry the D of an earlier point's last impact,
// so up and down differ where they should not); a sweep of a key other than a speed on a case
// whose speeds do not roll (the points run at the momentum's mean speed, named).
std::vector<std::string> sweep_warnings(const SteadySweepSpec& spec);

// (line, direction (up before down), index): the order rows are kept and written in.
bool sweep_key_less(const SweepPointResult& a, const SweepPointResult& b);

// The points the spec's shard runs: its lines and directions times the points of a line (0 for
// a grid run_steady_sweep refuses).
std::size_t shard_point_count(const SteadySweepSpec& spec);

// Runs the spec's shard on `pool`. Before any work, throws InputError naming the key when a grid
// is empty or outside the key's range, from_si > to_si (a downward sweep is a direction), the
// whole sweep has more than max_points points, a setting is outside its bounds above, vary2 is
// vary, vary and vary2 are both speeds (each sets the other: the pair rolls), the run does not read
// a swept key (integrator.*: the steady state sets its own step and duration; a key whose condition
// does not hold), the shard is not 0 <= k < n, there is no direction, or the case (with the first
// and with the last values of both keys) fails validation or has no steady state
// (require_steady_case). A case on elastic bearings sweeps the planar model (steady_state.hpp).
// `on_point` (may be empty) is called after each point, from the pool's worker threads, possibly at
// once.
SteadySweep run_steady_sweep(const SteadySweepSpec& spec, RunPool& pool,
                             const std::function<void(const SweepPointResult&)>& on_point = {});

// The same on a pool of spec.threads workers of its own.
SteadySweep run_steady_sweep(const SteadySweepSpec& spec,
                             const std::function<void(const SweepPointResult&)>& on_point = {});

}  // namespace gearimpact
