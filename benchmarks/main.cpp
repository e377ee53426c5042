// The benchmark program: Google Benchmark's flags, plus
//   --accuracy-positions=N  positions of the accuracy checks (default 10000,
//                           0 skips them); they run once, before any timing
//   --markdown=FILE         also write the run as a markdown table, with the
//                           ratios to GSL QAG and the speed targets
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "bench_support.hpp"

namespace {

using gearimpact::bench::Accuracy;

// The console output, plus a record of every run for the markdown.
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  struct Row {
    std::string name;
    double ns_per_iteration;  // CPU time of this process
    double real_ns_per_iteration;
    double iterations;
    std::map<std::string, double> counters;
  };

  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      // With repetitions only the median is kept; without, the single run.
      const bool single = run.run_type == Run::RT_Iteration && run.repetitions <= 1;
      const bool median = run.run_type == Run::RT_Aggregate && run.aggregate_name == "median";
      if ((!single && !median) || run.error_occurred) continue;
      Row row{run.run_name.function_name,
              run.GetAdjustedCPUTime() * to_ns(run.time_unit),
              run.GetAdjustedRealTime() * to_ns(run.time_unit),
              static_cast<double>(run.iterations),
              {}};
      for (const auto& [key, counter] : run.counters) row.counters[key] = counter.value;
      rows_.push_back(std::move(row));
    }
    ConsoleReporter::ReportRuns(runs);
  }

  const std::vector<Row>& rows() const { return rows_; }

  // The Figures lookup of bench_support.hpp: "name", "name:real", "name:key".
  double ns_of(std::string_view query) const {
    const std::size_t colon = query.find(':');
    const std::string_view name = query.substr(0, colon);
    for (const Row& row : rows_) {
      if (row.name != name) continue;
      if (colon == std::string_view::npos) return row.ns_per_iteration;
      const std::string key(query.substr(colon + 1));
      if (key == "real") return row.real_ns_per_iteration;
      const auto found = row.counters.find(key);
      return found == row.counters.end() ? std::nan("") : found->second;
    }
    return std::nan("");
  }

 private:
  static double to_ns(benchmark::TimeUnit unit) {
    switch (unit) {
      case benchmark::kNanosecond:
        return 1.0;
      case benchmark::kMicrosecond:
        return 1e3;
      case benchmark::kMillisecond:
        return 1e6;
      case benchmark::kSecond:
        return 1e9;
    }
    return 1.0;
  }
  std::vector<Row> rows_;
};

std::string human_time(double ns) {
  char text[40];
  if (ns < 1e3) {
    std::snprintf(text, sizeof text, "%.1f ns", ns);
  } else if (ns < 1e6) {
    std::snprintf(text, sizeof text, "%.2f us", ns / 1e3);
  } else if (ns >= 1e9) {
    std::snprintf(text, sizeof text, "%.3f s", ns / 1e9);
  } else {
    std::snprintf(text, sizeof text, "%.2f ms", ns / 1e6);
  }
  return text;
}

std::string scientific(double value) {
  if (std::isnan(value)) return "";
  char text[40];
  std::snprintf(text, sizeof text, "%.1e", value);
  return text;
}

std::string counter(const RecordingReporter::Row& row, const std::string& key) {
  const auto found = row.counters.find(key);
  return found == row.counters.end() ? "" : scientific(found->second);
}

bool is_simulation(const RecordingReporter::Row& row) {
  return row.name.starts_with("simulation/");
}

// A counter's value with `digits` significant digits, or "" when absent.
std::string counter_text(const RecordingReporter::Row& row, const std::string& key,
                         int digits = 4) {
  const auto found = row.counters.find(key);
  if (found == row.counters.end()) return "";
  char text[40];
  std::snprintf(text, sizeof text, "%.*g", digits, found->second);
  return text;
}

// The simulation rows: wall time is the measure (the sweeps and the
// reproduction run on every core), CPU time of the main thread beside it.
void write_simulation_table(std::ofstream& out, const RecordingReporter& reporter) {
  bool header = false;
  for (const RecordingReporter::Row& row : reporter.rows()) {
    if (!is_simulation(row)) continue;
    if (!header) {
      out << "\nSimulation (`simulation/*`): one iteration is one whole run (or sweep, or "
             "reproduction). Wall time per iteration; CPU time of the calling thread beside it "
             "(worker threads not included). `ns/step` is wall time over the RK4 steps of the "
             "run (steps cut at events included), `rhs/step` the right-hand-side evaluations per "
             "step, `pairs` the loaded pairs of every step of the run (checked on a recorded "
             "run before timing), `runs` the simulations of a sweep; a reproduction row lists "
             "the wall time of its parts in s. `CPU (s)`: user + system time of every thread "
             "(and, for the reproduction, of the program and its gnuplot children) per "
             "iteration; on a machine shared with other work, the wall time on idle cores is at "
             "least this over the core count.\n\n"
             "| benchmark | wall time | CPU time (calling thread) | CPU (s) | steps | ns/step | "
             "rhs/step | pairs | runs | parts (s) |\n"
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
      header = true;
    }
    std::string parts;
    for (const auto& [key, value] : row.counters) {
      if (!key.starts_with("part_")) continue;
      char text[80];
      std::snprintf(text, sizeof text, "%s%s %.3g", parts.empty() ? "" : ", ",
                    key.substr(5).c_str(), value);
      parts += text;
    }
    out << "| `" << row.name << "` | " << human_time(row.real_ns_per_iteration) << " | "
        << human_time(row.ns_per_iteration) << " | " << counter_text(row, "cpu_s", 3) << " | "
        << counter_text(row, "steps", 7) << " | " << counter_text(row, "ns_per_step", 4) << " | "
        << counter_text(row, "rhs_per_step", 3) << " | " << counter_text(row, "pairs") << " | "
        << counter_text(row, "runs") << " | " << parts << " |\n";
  }
}

void write_markdown(const std::string& path, const RecordingReporter& reporter,
                    std::size_t accuracy_positions) {
  std::ofstream out(path);
  const double baseline = reporter.ns_of("stiffness/gsl_qag");
  out << "One iteration is one evaluation at one contact position (Ke and the four "
         "compliances; the table rows Ke alone unless named otherwise), except "
         "`table_build` (one whole build). Time: CPU time of the benchmark process per "
         "iteration (wall time beside it: on a shared machine it includes time the "
         "process waited). Errors: worst relative error over "
      << accuracy_positions
      << " evenly spread positions against GSL QAG at 1e-13 (not timed). "
         "Speed-up: CPU time of `stiffness/gsl_qag` over the row's, same run.\n\n";
  out << "| benchmark | CPU time per iteration | wall time | worst rel. error Ke | worst rel. "
         "error compliances | speed-up vs GSL QAG |\n";
  out << "|---|---:|---:|---:|---:|---:|\n";
  for (const RecordingReporter::Row& row : reporter.rows()) {
    if (is_simulation(row)) continue;
    char ratio[40] = "";
    if (!std::isnan(baseline)) {
      std::snprintf(ratio, sizeof ratio, "%.3g", baseline / row.ns_per_iteration);
    }
    out << "| `" << row.name << "` | " << human_time(row.ns_per_iteration) << " | "
        << human_time(row.real_ns_per_iteration) << " | " << counter(row, "ke_rel_err") << " | "
        << counter(row, "compliance_rel_err") << " | " << ratio << " |\n";
  }
  write_simulation_table(out, reporter);
  out << "\nTargets, from this run:\n\n";
  const auto figures = [&](std::string_view name) { return reporter.ns_of(name); };
  for (const std::string& line : gearimpact::bench::evaluate_targets(figures)) {
    out << "- " << line << "\n";
  }
  const auto timed = [&](const std::string& name) { return !std::isnan(reporter.ns_of(name)); };
  bool header = false;
  for (const auto& [name, accuracy] : gearimpact::bench::accuracy_results()) {
    if (timed(name)) continue;
    if (!header) {
      out << "\nAccuracy checks without a timing row (same positions and reference; the "
             "reference check is an independent rule at the reference's tolerance):\n\n"
             "| check | worst rel. error Ke | worst rel. error compliances |\n"
             "|---|---:|---:|\n";
      header = true;
    }
    out << "| " << name << " | " << scientific(accuracy.ke) << " | "
        << scientific(accuracy.compliances) << " |\n";
  }
}

// Removes --name=value from argv, returning the value (or `fallback`).
std::string take_flag(int& argc, char** argv, std::string_view name, std::string fallback) {
  const std::string prefix = "--" + std::string(name) + "=";
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.substr(0, prefix.size()) == prefix) {
      std::string value(arg.substr(prefix.size()));
      for (int j = i; j + 1 < argc; ++j) argv[j] = argv[j + 1];
      --argc;
      return value;
    }
  }
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string markdown = take_flag(argc, argv, "markdown", "");
  const std::string positions_text = take_flag(argc, argv, "accuracy-positions", "10000");
  char* end = nullptr;
  const long positions = std::strtol(positions_text.c_str(), &end, 10);
  if (*end != '\0' || positions < 0 || positions == 1) {
    std::fprintf(stderr, "--accuracy-positions = %s: allowed 0 (skip) or an integer >= 2\n",
                 positions_text.c_str());
    return 2;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  if (positions > 0) gearimpact::bench::run_accuracy_checks(static_cast<std::size_t>(positions));
  RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  if (!markdown.empty()) write_markdown(markdown, reporter, static_cast<std::size_t>(positions));
  return 0;
}
