// A data set's pipeline against the bare simulation (docs/datasets.md, "Speed"): six records of
// the cracked rig of examples/rig_17_38_cracked.toml (two crack depths x three replicates), 1 s
// each after 0.1 s of settling, at 20 kHz with noise at 30 dB, made by run_shard on one thread
// (simulation with the sensor sampled, recorder chain, truth, HDF5 image, sha256, atomic writes
// of the file and its sidecar), and the same six runs by simulate() without any sample: the
// simulation alone. Both are timed in the same iteration, one after the other, by std::clock
// (this process's CPU time), so that they see the same machine. Two integrators: the example's
// own (RK4 at 1 us) and the step policy's Dormand-Prince at 4 us (docs/vibration.md), set by
// one-level factors on integrator.kind and integrator.step.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>

#include "bench_support.hpp"
#include "gearimpact/dataset/run.hpp"
#include "gearimpact/dataset/spec.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace {

using namespace gearimpact;
namespace fs = std::filesystem;

std::string spec_text(bool dopri5) {
  std::string t =
      "[dataset]\nname = \"rig-speed\"\nseed = 1\nduration = \"1 s\"\nsettle = \"0.1 s\"\n"
      "replicates = 3\nsample_rate = \"20 kHz\"\n\n[base]\ncase = \"rig_17_38_cracked.toml\"\n\n"
      "[recorder]\nnoise_snr = \"30 dB\"\n\n";
  if (dopri5) {
    t += "[[factors]]\nkey = \"integrator.kind\"\nlevels = [\"dopri5\"]\n\n"
         "[[factors]]\nkey = \"integrator.step\"\nlevels = [\"4 us\"]\n\n";
  }
  return t + "[[factors]]\nkey = \"faults[0].depth\"\nlevels = [\"0.5 mm\", \"1 mm\"]\n";
}

double cpu_now() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

void rig_pipeline(benchmark::State& state, bool dopri5) {
  const dataset::Plan plan = dataset::make_plan(
      dataset::parse_spec(spec_text(dopri5), GEARIMPACT_EXAMPLES_DIR, "rig-speed.toml"));
  const fs::path root =
      fs::temp_directory_path() / ("gearimpact-bench-dataset-" + std::to_string(::getpid()));
  double pipeline_cpu = 0.0;
  double bare_cpu = 0.0;
  for (auto _ : state) {
    fs::remove_all(root);
    fs::create_directories(root);
    double start = cpu_now();
    const dataset::Progress p = dataset::run_shard(plan, root.string(), {0, 1}, 1);
    pipeline_cpu += cpu_now() - start;
    benchmark::DoNotOptimize(p.done);
    // The simulation alone: each record's case (its start angle aside), no samples, the table
    // built once as the pipeline's pool builds it.
    start = cpu_now();
    const StiffnessTable table(plan.conditions[0].simulation_case.gears,
                               plan.conditions[0].simulation_case.model.stiffness);
    for (const dataset::Record& r : plan.records) {
      RunControl control;
      control.keep_series = false;
      control.keep_samples = false;
      benchmark::DoNotOptimize(
          simulate(plan.conditions[r.condition].simulation_case, table, control).summary.steps);
    }
    bare_cpu += cpu_now() - start;
  }
  fs::remove_all(root);
  const auto n = static_cast<double>(state.iterations());
  const double signal_s = plan.spec.duration_s * static_cast<double>(plan.records.size());
  state.counters["signal_s"] = signal_s;
  state.counters["pipeline_cpu_s"] = pipeline_cpu / n;
  state.counters["bare_cpu_s"] = bare_cpu / n;
  state.counters["pipeline_rate"] = signal_s * n / pipeline_cpu;
  state.counters["bare_rate"] = signal_s * n / bare_cpu;
  state.counters["ratio"] = bare_cpu / pipeline_cpu;
}

const bool registered = [] {
  for (const bool dopri5 : {false, true}) {
    benchmark::RegisterBenchmark(
        dopri5 ? "dataset/rig_pipeline_dopri5_4us" : "dataset/rig_pipeline_rk4_1us",
        [dopri5](benchmark::State& s) { rig_pipeline(s, dopri5); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  }
  return true;
}();

const bool target =
    gearimpact::bench::register_target([](const gearimpact::bench::Figures& figure) {
      std::string text =
          "Data set pipeline (rig, cracked, 1-s records at 20 kHz, noise, HDF5), at least 5.5 s of "
          "recorded signal per CPU second and 0.55 of the bare simulation's rate: ";
      bool any = false;
      for (const char* name : {"dataset/rig_pipeline_rk4_1us", "dataset/rig_pipeline_dopri5_4us"}) {
        const double rate = figure(std::string(name) + ":pipeline_rate");
        const double bare = figure(std::string(name) + ":bare_rate");
        if (std::isnan(rate) || std::isnan(bare)) continue;
        char line[256];
        std::snprintf(line, sizeof line, "%s%s: %.2f s per CPU s, bare %.2f, ratio %.2f (%s)",
                      any ? "; " : "", name + 8, rate, bare, rate / bare,
                      rate >= 5.5 && rate / bare >= 0.55 ? "**met**" : "**not met**");
        text += line;
        any = true;
      }
      return any ? text : text + "not measured in this run";
    });

}  // namespace
