// The cost of teeth that differ (docs/faults.md): building the stiffness
// tables of a pinion with five distinct cracked teeth against building one
// healthy table, and the cost per RK4 step of a run over the true period of a
// cracked pair against the healthy pair's run over the same time.
//
// The tables of MeshTables are built one per distinct pair of tooth states;
// given the healthy table, the five cracks cost five tables, so the target is
// that the five cost no more than five healthy tables (a cracked tooth is the
// healthy tooth, taken from the healthy table's nodes, plus what the crack
// changes over the sections it cuts). The runs are the paper's case 2 over one pinion
// revolution, the true period of the paper's pair with one cracked pinion
// tooth, and over two; the cost per step is the difference of the two run
// lengths over the difference of their steps, so that what a run does once
// (its tables, the mean stiffness over the true period) cancels.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

namespace gearimpact::bench {

namespace {

ToothFault pinion_crack(int tooth, double depth_m) {
  ToothFault f;
  f.gear = Gear::one;
  f.tooth = tooth;
  f.state.kind = ToothKind::root_crack;
  f.state.crack.depth_m = depth_m;
  f.state.crack.angle_rad = pi / 4;
  return f;
}

// Five pinion teeth with cracks of 0.2, 0.4, ..., 1.0 mm at 45 deg: five
// distinct states, each meeting the healthy wheel.
std::vector<ToothFault> five_cracks() {
  std::vector<ToothFault> faults;
  for (int k = 1; k <= 5; ++k) faults.push_back(pinion_crack(2 * k, 0.2e-3 * k));
  return faults;
}

void healthy_table(benchmark::State& state) {
  const SimulationCase c = paper_case(2);
  for (auto _ : state) {
    const StiffnessTable table(c.gears, c.model.stiffness);
    benchmark::DoNotOptimize(&table);
  }
}

void five_crack_tables(benchmark::State& state) {
  const SimulationCase c = paper_case(2);
  const auto healthy = std::make_shared<const StiffnessTable>(c.gears, c.model.stiffness);
  std::size_t built = 0;
  for (auto _ : state) {
    const MeshTables tables(c.gears, c.model.stiffness, five_cracks(), healthy);
    built = tables.fault_table_count();
    benchmark::DoNotOptimize(&tables);
  }
  state.counters["fault_tables"] = static_cast<double>(built);
}

// Case 2 over `revolutions` pinion revolutions, cracked (0.6 mm at 45 deg on
// pinion tooth 0) or healthy.
void revolution_run(benchmark::State& state, bool cracked, int revolutions) {
  SimulationCase c = paper_case(2);
  c.integrator.end_time_s = revolutions * 2 * pi / c.initial.w1_rad_per_s;
  if (cracked) c.faults = {pinion_crack(0, 0.6e-3)};
  RunControl control;
  control.keep_series = false;
  SimulationSummary summary;
  for (auto _ : state) {
    summary = simulate(c, control).summary;
    benchmark::DoNotOptimize(summary.damping_loss_j);
  }
  state.counters["steps"] = static_cast<double>(summary.steps);
  state.counters["events"] = static_cast<double>(summary.events);
}

const bool registered = [] {
  benchmark::RegisterBenchmark("faults/healthy_table", healthy_table)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("faults/five_crack_tables", five_crack_tables)
      ->Unit(benchmark::kMillisecond);
  for (const bool cracked : {false, true}) {
    for (const int revolutions : {1, 2}) {
      const std::string name = std::string("faults/") + (cracked ? "cracked" : "healthy") +
                               "_revolutions_" + std::to_string(revolutions);
      benchmark::RegisterBenchmark(
          name.c_str(),
          [cracked, revolutions](benchmark::State& s) { revolution_run(s, cracked, revolutions); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  return true;
}();

std::string two_figures(const char* pattern, double a, double b) {
  char text[320];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

const bool targets_registered = [] {
  register_target([](const Figures& figure) {
    const double one = figure("faults/healthy_table");
    const double five = figure("faults/five_crack_tables");
    if (std::isnan(one) || std::isnan(five)) {
      return std::string(
          "Tables of five distinct cracked teeth at most five healthy tables: "
          "not measured in this run");
    }
    return two_figures(
               "Tables of five distinct cracked teeth at most five healthy tables: "
               "%.2f healthy tables (one healthy table %.2f ms): ",
               five / one, one / 1e6) +
           (five <= 5.0 * one ? "**met**" : "**not met**");
  });
  register_target([](const Figures& figure) {
    // ns per step from the difference of two run lengths.
    const auto per_step = [&](const char* kind) {
      const std::string one = std::string("faults/") + kind + "_revolutions_1";
      const std::string two = std::string("faults/") + kind + "_revolutions_2";
      return (figure(two + ":real") - figure(one + ":real")) /
             (figure(two + ":steps") - figure(one + ":steps"));
    };
    const double healthy = per_step("healthy");
    const double cracked = per_step("cracked");
    if (std::isnan(healthy) || std::isnan(cracked)) {
      return std::string(
          "Cost per step of a cracked pair equal to the healthy pair's: "
          "not measured in this run");
    }
    const double ratio = cracked / healthy;
    // Within 10 %: the machine is shared.
    return two_figures(
               "Cost per step over pinion revolutions, cracked / healthy (case 2), "
               "the same within 10 %%: %.3f (healthy %.0f ns a step): ",
               ratio, healthy) +
           (std::abs(ratio - 1.0) <= 0.1 ? "**met**" : "**not met**");
  });
  return true;
}();

}  // namespace

}  // namespace gearimpact::bench
