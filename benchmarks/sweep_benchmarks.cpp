// The cost of a steady-state sweep: the paper's pair with its time-varying stiffness, loaded with
// 160 N on the line of action (T1 = 3 N m, T2 balancing it), rolling, viscous mesh damper
// zeta = 0.05, D frozen at 0.1 m/s, no friction, swept over w1 = 500 to 12000 rad/s with 201
// points up and 201 down, the two directions in parallel on a RunPool of two threads; one
// iteration is the whole sweep.
//
// Beside it, the same sweep at the fixed 0.1 us step of the paper's runs: too long to run whole,
// it is estimated from the cost per simulated second of that step on the same loaded pair
// (measured on 2 ms runs at w1 = 500, 6000 and 12000 rad/s) times the simulated time the sweep
// needed (every excitation period of every point).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "gearimpact/batch/pool.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/sweep.hpp"

namespace gearimpact::bench {

namespace {

constexpr int kPoints = 201;

// CPU seconds (user + system) of this process, all threads: on a machine shared with other work
// the wall time is inflated, the CPU time is not.
double process_cpu_s() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

SimulationCase loaded_pair() {
  PairLoad load;
  load.static_force_n = 3.0 / base_radius(paper_gear_pair(), Gear::one);
  load.damping_update = DampingUpdate::frozen;
  load.damping_reference_speed_m_s = 0.1;
  return loaded_paper_pair(500.0, load);
}

struct SweepFigures {
  double simulated_s = 0.0;
  double periods = 0.0;
  double converged = 0.0;
};

SweepFigures steady_sweep(RunPool& pool) {
  const SimulationCase base = loaded_pair();
  const std::vector<double> grid = sweep_grid(500.0, 12000.0, kPoints, "from", "to", "points");
  std::vector<std::future<std::vector<SweepPointResult>>> lines;
  for (SweepDirection d : {SweepDirection::up, SweepDirection::down}) {
    lines.push_back(pool.run([&pool, &base, &grid, d] {
      return sweep_line(base, [&pool](const SimulationCase& c) { return pool.table_for(c); },
                        "initial.w1", grid, d, 0, SteadySettings{}, {});
    }));
  }
  SweepFigures f;
  for (auto& line : lines) {
    for (const SweepPointResult& r : line.get()) {
      f.periods += r.point.periods_run;
      f.simulated_s += r.point.periods_run * r.point.timing.excitation_period_s;
      f.converged += r.point.converged ? 1.0 : 0.0;
    }
  }
  return f;
}

void sweep_benchmark(benchmark::State& state) {
  RunPool pool(2);
  SweepFigures f;
  const double cpu_start = process_cpu_s();
  for (auto _ : state) f = steady_sweep(pool);
  state.counters["cpu_s"] = (process_cpu_s() - cpu_start) / static_cast<double>(state.iterations());
  state.counters["points"] = 2.0 * kPoints;
  state.counters["converged"] = f.converged;
  state.counters["periods"] = f.periods;
  state.counters["simulated_s"] = f.simulated_s;
}

// CPU seconds per simulated second of one RK4 run of the loaded pair at the fixed 0.1 us step.
void fixed_step_cost(benchmark::State& state) {
  const auto table =
      std::make_shared<const StiffnessTable>(paper_gear_pair(), loaded_pair().model.stiffness);
  double cpu = 0.0;
  double simulated = 0.0;
  for (auto _ : state) {
    for (double w1 : {500.0, 6000.0, 12000.0}) {
      SimulationCase c = loaded_pair();
      c.initial.w1_rad_per_s = w1;
      c.initial.w2_rad_per_s =
          w1 * base_radius(c.gears, Gear::one) / base_radius(c.gears, Gear::two);
      c.integrator.step_s = 1e-7;
      c.integrator.end_time_s = 2e-3;
      RunControl control;
      control.keep_series = false;
      const double start = process_cpu_s();
      benchmark::DoNotOptimize(simulate(c, *table, control));
      cpu += process_cpu_s() - start;
      simulated += c.integrator.end_time_s;
    }
  }
  state.counters["cpu_per_simulated_s"] = cpu / simulated;
}

const bool registered = [] {
  benchmark::RegisterBenchmark("sweep/steady_w1_201_up_down", sweep_benchmark)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  benchmark::RegisterBenchmark("sweep/fixed_step_cost", fixed_step_cost)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  register_target([](const Figures& figure) {
    const double wall_ns = figure("sweep/steady_w1_201_up_down:real");
    const double simulated = figure("sweep/steady_w1_201_up_down:simulated_s");
    const double fixed = figure("sweep/fixed_step_cost:cpu_per_simulated_s");
    const double cpu = figure("sweep/steady_w1_201_up_down:cpu_s");
    if (std::isnan(wall_ns)) {
      return std::string(
          "Steady sweep, 201 points up and 201 down, under 10 s on 2 cores: not "
          "measured in this run");
    }
    char text[600];
    std::snprintf(text, sizeof text,
                  "Steady sweep of the loaded paper pair, w1 = 500 to 12000 rad/s, 201 points up "
                  "and 201 down, under 10 s on 2 cores: %.2f s wall, %.2f s CPU (%.3f s "
                  "simulated); the same simulated time at the fixed 0.1 us step: about %.1f s "
                  "CPU, %.1f s on 2 idle cores: %s",
                  wall_ns / 1e9, cpu, simulated, simulated * fixed, 0.5 * simulated * fixed,
                  wall_ns < 1e10 ? "**met**" : "**not met**");
    return std::string(text);
  });
  return true;
}();

}  // namespace

}  // namespace gearimpact::bench
