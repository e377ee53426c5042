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
//
// The cost a fault-diagnosis user pays is signal length: the test-rig-like
// pair of examples/rig_17_38.toml (its values copied below, so that tuning the
// example does not move this figure) on elastic bearings, 6 DOF, with a root
// crack of q = 0.5 h_c in pinion tooth 0, at the step policy of
// docs/vibration.md (2.5 us), against the same run with rigid bearings (the
// torsional model): seconds of signal per CPU second, set-up included.
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
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

// examples/rig_17_38.toml (its values copied, so that tuning the example does
// not move this figure): the load torque balances the mean friction power at
// 40 Hz, so that every run turns at the rig's speed.
constexpr const char* kRigCase = R"(name = "rig_17_38"
[gears]
teeth1 = 17
teeth2 = 38
module = "3 mm"
pressure_angle = "20 deg"
face_width = "15 mm"
youngs_modulus = "206 GPa"
poisson_ratio = 0.3
density = "7850 kg/m^3"
backlash = "0.05 mm"
bore_diameter1 = "20 mm"
bore_diameter2 = "40 mm"
profile_shift1 = 0.1
profile_shift2 = -0.1
[torque1]
kind = "constant"
value = "10 N*m"
[torque2]
kind = "constant"
value = "-22.196478760533587 N*m"
[initial]
w1 = "2400 rpm"
w2 = "1073.6842105263158 rpm"
[model]
stiffness_model = "potential-energy"
[bearings]
kind = "elastic"
stiffness_x1 = "1.9e8 N/m"
stiffness_x2 = "1.9e8 N/m"
damping_x1 = "500 N*s/m"
damping_x2 = "500 N*s/m"
[integrator]
step = "1 us"
end_time = "1 s"
)";

// The rig case with a root crack of q = 0.5 h_c at 45 deg in pinion tooth 0
// (h_c where the crack starts, as reproduce_faults places it), on elastic or
// rigid bearings.
SimulationCase rig_cracked(bool elastic) {
  SimulationCase c = parse_case(kRigCase, "rig_17_38 (fault_benchmarks.cpp)");
  ToothFault crack = pinion_crack(0, 0.0);
  const PlacedCrack placed = place_crack(crack.state.crack, rack_gear_pair_geometry(c.gears).gear1,
                                         c.model.stiffness.kind, c.gears.face_width_m);
  crack.state.crack.depth_m = 0.5 * placed.start_half_thickness_m;
  c.faults = {crack};
  if (!elastic) c.bearings.kind = BearingKind::rigid;
  return c;
}

// The runs of the rig: the planar model by Dormand-Prince and by RK4, each at
// the largest step of the step policy (docs/vibration.md: halving it moves the
// sensor's RMS acceleration by less than 1e-4, asserted in
// verify/dynamics/test_planar_step_policy.cpp), and the torsional model at
// RK4's step. Each samples its signal at 51.2 kHz (a vibration recorder's
// rate) through the callback a data set's writer would take.
struct RigRun {
  const char* name;
  bool elastic;
  IntegratorKind kind;
  double step_s;
};
constexpr double kRigSampleRateHz = 51200.0;
constexpr RigRun kRigRuns[] = {
    {"planar_dopri5", true, IntegratorKind::dopri5, 4e-6},
    {"planar_rk4", true, IntegratorKind::rk4, 1.75e-6},
    {"torsional_rk4", false, IntegratorKind::rk4, 1.75e-6},
};

// One whole run an iteration (the fault's tables and the mean stiffness
// included, the healthy table built once before).
void rig_run(benchmark::State& state, const RigRun& run, double signal_s) {
  SimulationCase c = rig_cracked(run.elastic);
  c.integrator.kind = run.kind;
  c.integrator.step_s = run.step_s;
  c.integrator.end_time_s = signal_s;
  const StiffnessTable table(c.gears, c.model.stiffness);
  RunControl control;
  control.keep_series = false;
  control.keep_samples = false;
  control.sample_rate_hz = kRigSampleRateHz;
  double sum = 0.0;
  control.on_planar_sample = [&sum](const PlanarSample& p) {
    sum += p.sensor_acceleration_m_per_s2;
  };
  control.on_sample = [&sum](const SampleRow& r) { sum += r.acceleration1_rad_per_s2; };
  SimulationSummary summary;
  for (auto _ : state) {
    summary = simulate(c, table, control).summary;
    benchmark::DoNotOptimize(sum);
  }
  state.counters["signal_s"] = c.integrator.end_time_s;
  state.counters["steps"] = static_cast<double>(summary.steps);
  state.counters["events"] = static_cast<double>(summary.events);
  state.counters["rhs_per_step"] =
      static_cast<double>(summary.rhs_evaluations) / static_cast<double>(summary.steps);
}

// The band-limited sample's cost: the same 0.5 s rig run (dopri5 at 4 us, 20 kHz, the data
// sets' rate) sampled by point values and by interval averages, alternated within each iteration
// so that both see the same machine state; CPU seconds by std::clock (one thread).
void rig_sample_kinds(benchmark::State& state) {
  SimulationCase c = rig_cracked(true);
  c.integrator.kind = IntegratorKind::dopri5;
  c.integrator.step_s = 4e-6;
  c.integrator.end_time_s = 0.5;
  const StiffnessTable table(c.gears, c.model.stiffness);
  double sum = 0.0;
  RunControl control;
  control.keep_series = false;
  control.keep_samples = false;
  control.sample_rate_hz = 20000.0;
  control.on_planar_sample = [&sum](const PlanarSample& p) {
    sum += p.sensor_acceleration_m_per_s2;
  };
  double cpu[2] = {0.0, 0.0};
  const SampleKind kinds[2] = {SampleKind::point, SampleKind::interval_average};
  for (auto _ : state) {
    for (int k = 0; k < 2; ++k) {
      control.sample = kinds[k];
      const std::clock_t start = std::clock();
      benchmark::DoNotOptimize(simulate(c, table, control).summary.steps);
      cpu[k] += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    }
    benchmark::DoNotOptimize(sum);
  }
  const auto n = static_cast<double>(state.iterations());
  state.counters["point_cpu_s"] = cpu[0] / n;
  state.counters["average_cpu_s"] = cpu[1] / n;
  state.counters["ratio"] = cpu[1] / cpu[0];
}

// The cracked rig as a train (two_gear_train: its bearings on the pinion and
// the wheel) against the planar model, RK4 at the policy's 1.75 us, 0.2 s,
// the sensor sampled at 51.2 kHz as a record's, each a whole run with its own
// tables; alternated within each iteration so that both see the same machine
// state; CPU seconds of the calling thread. The two give the same numbers to
// the bit, samples included (verify/dynamics/test_planar_train.cpp).
void rig_as_train(benchmark::State& state) {
  SimulationCase c = rig_cracked(true);
  c.integrator.kind = IntegratorKind::rk4;
  c.integrator.step_s = 1.75e-6;
  c.integrator.end_time_s = 0.2;
  const GearTrain train = two_gear_train(c);
  RunControl control;
  control.keep_series = false;
  control.sample_rate_hz = 51200.0;
  long long steps = 0;
  const auto [cpu_model, cpu_train] = alternated_cpu_s(
      state, [&] { steps = simulate(c, control).summary.steps; },
      [&] { benchmark::DoNotOptimize(simulate_train(train, control).summary.steps); });
  const auto n = static_cast<double>(state.iterations());
  state.counters["model_signal_per_cpu_s"] = c.integrator.end_time_s / (cpu_model / n);
  state.counters["train_signal_per_cpu_s"] = c.integrator.end_time_s / (cpu_train / n);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["ratio"] = cpu_train / cpu_model;
}

std::string rig_name(const RigRun& run, int signal_ms) {
  return std::string("faults/rig_") + run.name + "_cracked_" + std::to_string(signal_ms) + "ms";
}

const bool registered = [] {
  for (const RigRun& run : kRigRuns) {
    for (const int signal_ms : {500, 1000}) {
      benchmark::RegisterBenchmark(rig_name(run, signal_ms).c_str(), [&run, signal_ms](
                                                                         benchmark::State& s) {
        rig_run(s, run, 1e-3 * signal_ms);
      })->Unit(benchmark::kMillisecond);
    }
  }
  benchmark::RegisterBenchmark("faults/rig_cracked_as_train", rig_as_train)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(3);
  benchmark::RegisterBenchmark("faults/rig_sample_kinds", rig_sample_kinds)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(3);
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
  register_target([](const Figures& figure) {
    const double point = figure("faults/rig_sample_kinds:point_cpu_s");
    const double average = figure("faults/rig_sample_kinds:average_cpu_s");
    if (std::isnan(point) || std::isnan(average)) {
      return std::string(
          "Interval-average samples at most 10 % over point samples: not measured in this run");
    }
    return two_figures(
               "Interval-average samples at most 10 %% over point samples (rig, dopri5 "
               "at 4 us, 0.5 s at 20 kHz): ratio %.3f (point %.3f s a run): ",
               average / point, point) +
           (average <= 1.1 * point ? "**met**" : "**not met**");
  });
  register_target([](const Figures& figure) {
    // Seconds of signal per CPU second: of the 1 s run whole, and from the
    // difference of the 1 s and 0.5 s runs (what a run does once cancels).
    const auto cpu_s = [&](const RigRun& run, int signal_ms) {
      return figure(rig_name(run, signal_ms)) * 1e-9;
    };
    const auto whole = [&](const RigRun& run) { return 1.0 / cpu_s(run, 1000); };
    const auto beyond = [&](const RigRun& run) {
      return 0.5 / (cpu_s(run, 1000) - cpu_s(run, 500));
    };
    const RigRun& dopri5 = kRigRuns[0];
    const RigRun& rk4 = kRigRuns[1];
    const RigRun& torsional = kRigRuns[2];
    if (std::isnan(beyond(dopri5)) || std::isnan(beyond(rk4)) || std::isnan(beyond(torsional))) {
      return std::string(
          "Rig pair on elastic bearings, cracked pinion, at least 10 s of signal per CPU "
          "second: not measured in this run");
    }
    char text[720];
    std::snprintf(text, sizeof text,
                  "Rig pair (17/38) on elastic bearings, 6 DOF, cracked pinion (q = 0.5 h_c), "
                  "sampled at 51.2 kHz, at least 10 s of signal per CPU second at the step "
                  "policy's step: dopri5 at 4 us %.2f s a 1 s run, set-up included, %.2f s "
                  "beyond it; rk4 at 1.75 us %.2f s, %.2f s; the torsional model (bearings "
                  "rigid) by rk4 at 1.75 us %.2f s, %.2f s (planar by dopri5 / torsional %.2f, "
                  "%.2f; planar by rk4 / torsional %.2f, %.2f): ",
                  whole(dopri5), beyond(dopri5), whole(rk4), beyond(rk4), whole(torsional),
                  beyond(torsional), whole(dopri5) / whole(torsional),
                  beyond(dopri5) / beyond(torsional), whole(rk4) / whole(torsional),
                  beyond(rk4) / beyond(torsional));
    // Judged on the rate of signal beyond a record's set-up (its fault's
    // table), the cost of the seconds a data set's records are long.
    return std::string(text) +
           (beyond(dopri5) >= 10.0 ? "**met** beyond the set-up" : "**not met**");
  });
  return true;
}();

}  // namespace

}  // namespace gearimpact::bench
