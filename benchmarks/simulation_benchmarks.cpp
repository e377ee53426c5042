// The cost of the simulation: nanoseconds per RK4 step with one and with two
// loaded pairs, the wall time of each paper case, of the Fig. 7 sweep and of
// the whole reproduction, and the growth of the cost with simulated time and
// with sweep size (each measured at two sizes). One iteration is one whole run.
//
// The per-step figures come from a steady rolling contact on N1 (docs/model.md,
// equations of motion): case 2's torque on gear 1, gear 2's torque balancing
// it, the gears rolling at case 2's w1 = 50 rad/s and started at the static
// deflection with an approach speed of 1 mm/s, so the teeth stay in contact.
// The run lasts 1 ms, during which the contact moves 0.94 mm along the line
// of action: it is placed inside the one-pair zone, or inside a two-pair zone,
// short of the pitch point so that no friction reversal is crossed. The pair
// count of every step is checked on a recorded run before timing.
#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "gearimpact/batch/sweep_friction.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/table.hpp"

#ifndef GEARIMPACT_CLI_PATH
#error "GEARIMPACT_CLI_PATH must name the gearimpact program"
#endif

namespace gearimpact::bench {

namespace {

// CPU seconds (user + system) of this process's threads, or of its waited-for
// children: on a machine shared with other work, the wall time a run would
// take on idle cores is at least this over the core count.
double cpu_seconds(int who) {
  rusage usage{};
  ::getrusage(who, &usage);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

constexpr double steady_run_s = 1e-3;
// Distance kept from the ends of the zone the contact runs in, m.
constexpr double zone_margin_m = 0.1e-3;
constexpr double approach_speed_m_s = 1e-3;

const StiffnessTable& paper_table() {
  static const StiffnessTable table(paper_gear_pair(), paper_case(2).model.stiffness);
  return table;
}

// The steady rolling contact with `pairs` (1 or 2) loaded pairs throughout.
SimulationCase steady_contact(int pairs) {
  SimulationCase c = paper_case(2);
  c.name = "steady-contact-" + std::to_string(pairs) + (pairs == 1 ? "-pair" : "-pairs");
  const GearPair& g = c.gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const double t0 = base_pitch(g);
  const ContactSegment segment = contact_segment(g);
  // (42): one pair in [X_end - t0, X_start + t0], two in [X_start + t0, X_end]
  // (the pair there and the one t0 behind it).
  const double x0 = (pairs == 1 ? segment.end_m - t0 : segment.start_m + t0) + zone_margin_m;
  const double torque1 = c.torque1.constant_n_m;
  c.torque2.constant_n_m = -torque1 * rb2 / rb1;
  c.initial.w1_rad_per_s = 50.0;
  c.initial.w2_rad_per_s = (rb1 * c.initial.w1_rad_per_s - approach_speed_m_s) / rb2;
  // (12),(42): the pair k = 0 at x0; (30): the static deflection under T1.
  c.initial.theta1_rad = (x0 - pitch_point_position(g)) / rb1;
  double stiffness = 0.0;
  for (int k = 0; k < pairs; ++k) stiffness += paper_table().stiffness(x0 - k * t0);
  const double deflection = torque1 / rb1 / stiffness;
  c.initial.theta2_rad = (rb1 * c.initial.theta1_rad - g.backlash_m - deflection) / rb2;
  c.integrator.end_time_s = steady_run_s;
  return c;
}

// Throws unless every recorded step of the run is on N1 with `pairs` pairs.
void check_pairs(const SimulationCase& c, int pairs) {
  const SimulationResult r = simulate(c, paper_table());
  for (const SeriesRow& row : r.series) {
    if (row.region != 1 || row.pairs != pairs) {
      throw std::runtime_error(c.name + ": at t = " + std::to_string(row.t_s) +
                               " s the region is " + std::to_string(row.region) + " with " +
                               std::to_string(row.pairs) + " pairs");
    }
  }
  if (r.summary.events != 0) {
    throw std::runtime_error(c.name + ": " + std::to_string(r.summary.events) +
                             " events, expected none");
  }
}

void report_steps(benchmark::State& state, const SimulationSummary& s, double seconds_per_run) {
  state.counters["steps"] = static_cast<double>(s.steps);
  state.counters["rhs_per_step"] =
      static_cast<double>(s.rhs_evaluations) / static_cast<double>(s.steps);
  state.counters["ns_per_step"] = seconds_per_run * 1e9 / static_cast<double>(s.steps);
  state.counters["events"] = static_cast<double>(s.events);
}

// Times whole runs of c with a prebuilt table and no time series: the
// integration alone. The wall time per run is measured here for the ns/step
// counter (Google Benchmark's own figure is the same, as the loop does
// nothing else).
void time_runs(benchmark::State& state, const SimulationCase& c, bool prebuilt_table) {
  RunControl control;
  control.keep_series = false;
  SimulationSummary summary;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    summary =
        prebuilt_table ? simulate(c, paper_table(), control).summary : simulate(c, control).summary;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(summary.damping_loss_j);
  }
  report_steps(state, summary, seconds / static_cast<double>(state.iterations()));
}

void steady_step(benchmark::State& state, int pairs) {
  const SimulationCase c = steady_contact(pairs);
  try {
    check_pairs(c, pairs);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    for (auto _ : state) {
    }
    return;
  }
  time_runs(state, c, true);
  state.counters["pairs"] = pairs;
}

// GEARpie's H501 (docs/helical.md) with friction off, rolling at 100 rad/s
// under 200 N m balanced at the wheel, started at its mean static deflection
// (mean route-B stiffness) on N1, approaching at 1 mm/s: spur (helix 0) or
// at 15 deg. The run lasts
// two mesh periods, so that each pair count and every table kink a mesh
// period holds is crossed; a helical run's kinks are events.
SimulationCase h501_rolling(double helix_angle_deg) {
  SimulationCase c;
  c.name = "h501-rolling";
  c.gears.teeth1 = 20;
  c.gears.teeth2 = 30;
  c.gears.module_m = 3.5e-3;
  c.gears.pressure_angle_rad = 20.0 * std::acos(-1.0) / 180.0;
  c.gears.helix_angle_rad = helix_angle_deg * std::acos(-1.0) / 180.0;
  c.gears.face_width_m = 23e-3;
  c.gears.profile_shift1 = 0.1809;
  c.gears.profile_shift2 = 0.0891;
  c.gears.youngs_modulus_pa = 206e9;
  c.model.friction_coefficient = 0.0;
  c.torque1.constant_n_m = 200.0;
  c.torque2.constant_n_m = -300.0;  // z2 / z1 = 1.5
  c.initial.w1_rad_per_s = 100.0;
  c.initial.w2_rad_per_s = 100.0 / 1.5;
  const SimulationCase d = dynamics_case(c);
  const std::shared_ptr<const StiffnessTable> table = run_table(c);
  const double rb1 = base_radius(d.gears, Gear::one);
  const double rb2 = base_radius(d.gears, Gear::two);
  const double mean = mean_mesh_stiffness_n_per_m(d, *table);
  c.initial.theta2_rad = -(d.gears.backlash_m + 200.0 / (rb1 * mean)) / rb2;
  // Approaching at 1 mm/s, as the paper pair's steady contact: the damping
  // the onset sets stays within RK4's reach.
  c.initial.w2_rad_per_s = (rb1 * c.initial.w1_rad_per_s - approach_speed_m_s) / rb2;
  c.integrator.end_time_s = 2.0 * 2.0 * std::acos(-1.0) / (20.0 * 100.0);
  return c;
}

// The cost of an RK4 step of H501's rolling contact, the table built
// beforehand (run_table), so that the figure is the integration's.
void h501_step(benchmark::State& state, double helix_angle_deg) {
  const SimulationCase c = h501_rolling(helix_angle_deg);
  const std::shared_ptr<const StiffnessTable> table = run_table(c);
  RunControl control;
  control.keep_series = false;
  SimulationSummary summary;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    summary = simulate(c, *table, control).summary;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    benchmark::DoNotOptimize(summary.damping_loss_j);
  }
  report_steps(state, summary, seconds / static_cast<double>(state.iterations()));
}

void paper_case_run(benchmark::State& state, int number, double end_time_factor) {
  SimulationCase c = paper_case(number);
  c.integrator.end_time_s *= end_time_factor;
  // The whole run as `simulate` does it, the table build included.
  time_runs(state, c, false);
}

// Fig. 7: f = 0.01, 0.02, ..., 0.09 for the three cases, `copies` times over.
void fig7_sweep(benchmark::State& state, int copies) {
  std::vector<SimulationCase> cases;
  for (int k = 0; k < copies; ++k) {
    for (int number = 1; number <= 3; ++number) cases.push_back(paper_case(number));
  }
  std::size_t rows = 0;
  const double cpu_start = cpu_seconds(RUSAGE_SELF);
  for (auto _ : state) {
    const std::vector<SweepRow> sweep = sweep_friction(cases, 0.01, 0.09 + 1e-9, 0.01);
    rows = sweep.size();
    benchmark::DoNotOptimize(sweep.data());
  }
  state.counters["runs"] = static_cast<double>(rows * cases.size());
  state.counters["cpu_s"] =
      (cpu_seconds(RUSAGE_SELF) - cpu_start) / static_cast<double>(state.iterations());
}

// The whole reproduction, the computation alone (no files,
// no plots): the three cases with their time series (thinned to 8000 rows as
// `reproduce` keeps them), the Fig. 7 sweep of 27 runs and Fig. 8's two
// energy cycles of 601 positions, all started at once and spread over the
// cores.
void reproduction_computation(benchmark::State& state) {
  const double cpu_start = cpu_seconds(RUSAGE_SELF);
  for (auto _ : state) {
    std::vector<std::future<SimulationResult>> cases;
    for (int number = 1; number <= 3; ++number) {
      cases.push_back(std::async(std::launch::async, [number] {
        SimulationCase c = paper_case(number);
        c.integrator.output_every =
            std::max(1, static_cast<int>(c.integrator.end_time_s / c.integrator.step_s / 8000));
        return simulate(c);
      }));
    }
    std::future<std::vector<EnergyRatios>> fig8 =
        std::async(std::launch::async, [] { return energy_ratio_cycle(paper_gear_pair(), 601); });
    std::future<std::vector<EnergyRatios>> fig8_flipped = std::async(std::launch::async, [] {
      StiffnessModel flipped;
      flipped.moment_sign = AxialMomentSign::flipped;
      return energy_ratio_cycle(paper_gear_pair(), 601, flipped);
    });
    std::vector<SimulationCase> sweep_cases;
    for (int number = 1; number <= 3; ++number) sweep_cases.push_back(paper_case(number));
    const std::vector<SweepRow> sweep = sweep_friction(sweep_cases, 0.01, 0.09 + 1e-9, 0.01);
    benchmark::DoNotOptimize(sweep.data());
    for (auto& c : cases) benchmark::DoNotOptimize(c.get().summary.damping_loss_j);
    benchmark::DoNotOptimize(fig8.get().data());
    benchmark::DoNotOptimize(fig8_flipped.get().data());
  }
  state.counters["runs"] = 30;
  state.counters["cpu_s"] =
      (cpu_seconds(RUSAGE_SELF) - cpu_start) / static_cast<double>(state.iterations());
}

// The whole reproduction as a user runs it: the program as a subprocess,
// its own report of the wall time of each part parsed from its stderr.
void reproduction(benchmark::State& state) {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / "gearimpact_bench_reproduce";
  std::map<std::string, double> parts;
  const double cpu_start = cpu_seconds(RUSAGE_CHILDREN);
  for (auto _ : state) {
    std::filesystem::remove_all(out);
    const std::string command = std::string("\"") + GEARIMPACT_CLI_PATH + "\" reproduce --out \"" +
                                out.string() + "\" 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) {
      state.SkipWithError("cannot start the reproduction");
      break;
    }
    char line[512];
    std::string text;
    while (std::fgets(line, sizeof line, pipe) != nullptr) text += line;
    if (::pclose(pipe) != 0) {
      state.SkipWithError(("the reproduction failed: " + text).c_str());
      break;
    }
    // "reproduce: <what> ... <seconds> s", one line a part.
    std::size_t at = 0;
    int index = 0;
    while ((at = text.find(" ... ", at)) != std::string::npos) {
      const std::size_t begin = text.rfind("reproduce: ", at);
      const std::string what = text.substr(begin + 11, at - begin - 11);
      const double seconds = std::strtod(text.c_str() + at + 5, nullptr);
      std::string key = "part_" + std::to_string(++index) + "_";
      for (char ch : what.substr(0, what.find(','))) {
        key += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
      }
      parts[key] = seconds;
      at += 5;
    }
  }
  std::filesystem::remove_all(out);
  for (const auto& [key, seconds] : parts) state.counters[key] = seconds;
  state.counters["cpu_s"] =
      (cpu_seconds(RUSAGE_CHILDREN) - cpu_start) / static_cast<double>(state.iterations());
}

const bool registered = [] {
  benchmark::RegisterBenchmark("simulation/rk4_step_one_pair",
                               [](benchmark::State& s) { steady_step(s, 1); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("simulation/rk4_step_two_pairs",
                               [](benchmark::State& s) { steady_step(s, 2); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("simulation/rk4_step_h501_spur",
                               [](benchmark::State& s) { h501_step(s, 0.0); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("simulation/rk4_step_h501_helical",
                               [](benchmark::State& s) { h501_step(s, 15.0); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  for (int number = 1; number <= 3; ++number) {
    benchmark::RegisterBenchmark(("simulation/case" + std::to_string(number)).c_str(),
                                 [number](benchmark::State& s) { paper_case_run(s, number, 1.0); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::RegisterBenchmark("simulation/case3_2T",
                               [](benchmark::State& s) { paper_case_run(s, 3, 2.0); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("simulation/fig7_sweep",
                               [](benchmark::State& s) { fig7_sweep(s, 1); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("simulation/fig7_sweep_2N",
                               [](benchmark::State& s) { fig7_sweep(s, 2); })
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark("simulation/reproduction_computation", reproduction_computation)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  benchmark::RegisterBenchmark("simulation/reproduction", reproduction)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime()
      ->Iterations(1);
  return true;
}();

std::string format(const char* pattern, double a, double b = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b);
  return text;
}

const char* verdict(bool met) {
  return met ? "**met**" : "**not met**";
}

const bool targets_registered = [] {
  register_target([](const Figures& figure) {
    const double two = figure("simulation/rk4_step_two_pairs:ns_per_step");
    const double one = figure("simulation/rk4_step_one_pair:ns_per_step");
    if (std::isnan(two))
      return std::string("RK4 step with two loaded pairs at most 150 ns: not measured in this run");
    return format("RK4 step with two loaded pairs at most 150 ns: %.0f ns (one pair: %.0f ns): ",
                  two, one) +
           verdict(two <= 150.0);
  });
  register_target([](const Figures& figure) {
    const double helical = figure("simulation/rk4_step_h501_helical:ns_per_step");
    const double spur = figure("simulation/rk4_step_h501_spur:ns_per_step");
    if (std::isnan(helical) || std::isnan(spur)) {
      return std::string(
          "A helical pair's RK4 step at most 3 times the spur pair's (H501): not measured in "
          "this run");
    }
    return format(
               "A helical pair's RK4 step at most 3 times the spur pair's (H501, route B): "
               "%.0f ns against %.0f ns, ",
               helical, spur) +
           format("ratio %.2f: ", helical / spur) + verdict(helical <= 3.0 * spur);
  });
  register_target([](const Figures& figure) {
    const double reproduction_ns = figure("simulation/reproduction_computation:real");
    if (std::isnan(reproduction_ns)) {
      return std::string(
          "Reproduction, computation only (three cases, Fig. 7 sweep, Fig. 8) under 3 s "
          "wall: not measured in this run");
    }
    return format(
               "Reproduction, computation only (three cases, the 27-run Fig. 7 sweep, Fig. "
               "8; computation only) under 3 s wall: %.2f s: ",
               reproduction_ns / 1e9) +
           verdict(reproduction_ns < 3e9);
  });
  register_target([](const Figures& figure) {
    const double wall_ns = figure("simulation/reproduction:real");
    if (std::isnan(wall_ns)) {
      return std::string("Whole `gearimpact reproduce` under 3 s wall: not measured in this run");
    }
    return format(
               "Whole `gearimpact reproduce` (also the readings comparison, 77 runs asked for, "
               "and the case 3 ensemble, 16 runs with series; files and plots) under 3 s wall: "
               "%.2f s: ",
               wall_ns / 1e9) +
           verdict(wall_ns < 3e9);
  });
  register_target([](const Figures& figure) {
    const double t = figure("simulation/case3:real");
    const double t2 = figure("simulation/case3_2T:real");
    const double n = figure("simulation/fig7_sweep:real");
    const double n2 = figure("simulation/fig7_sweep_2N:real");
    if (std::isnan(t) || std::isnan(t2) || std::isnan(n) || std::isnan(n2)) {
      return std::string(
          "Cost linear in simulated time and in sweep size: not measured in this run");
    }
    // Linear within 20 %: the second half of a case is not the same motion
    // as the first, and the machine is shared.
    const bool linear = std::abs(t2 / t - 2.0) <= 0.4 && std::abs(n2 / n - 2.0) <= 0.4;
    return format(
               "Cost linear in simulated time and in sweep size: case 3 over 2T / over T = "
               "%.2f, sweep of 54 runs / of 27 = %.2f (2 for linear, within 20 %%): ",
               t2 / t, n2 / n) +
           verdict(linear);
  });
  return true;
}();

}  // namespace

}  // namespace gearimpact::bench
