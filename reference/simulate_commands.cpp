#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "case_flags.hpp"
#include "commands.hpp"
#include "gearimpact/batch/sweep_friction.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/sliced_pair.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/signals/order_tracking.hpp"

namespace gearimpact::cli {

namespace {

// Fig. 7's default sweep of f.
constexpr const char* kSweepFrom = "0.01";
constexpr const char* kSweepTo = "0.09";
constexpr const char* kSweepStep = "0.01";

long long parse_integer_flag(const std::string& flag, const std::string& text, long long lower,
                             long long upper, const std::string& meaning) {
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size() || value < lower ||
      value > upper) {
    throw InputError(flag, text,
                     "an integer in [" + std::to_string(lower) + ", " + std::to_string(upper) +
                         "] (" + meaning + ")");
  }
  return value;
}

// A plain number; its range is checked by the function it is passed to.
double parse_number_flag(const std::string& flag, const std::string& text,
                         const std::string& meaning) {
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size()) {
    throw InputError(flag, text, "a plain number: " + meaning);
  }
  return value;
}

// A driven run's impacts and their Vi histogram, beside the --out series.
constexpr const char* kRattleImpactsFile = "rattle_impacts.csv";
constexpr const char* kRattleHistogramFile = "rattle_impacts_histogram.csv";

struct SimulateOptions {
  int case_number = 1;
  std::string case_file;
  std::string out;
  double max_rows = static_cast<double>(kMostSeriesRows);
  std::string sample_rate;
  std::string tacho_out;
  std::string sample = "interval-average";
  CaseOptions keys;
};

struct SweepOptions {
  std::string from = kSweepFrom;
  std::string to = kSweepTo;
  std::string step = kSweepStep;
  std::string threads = "0";
  CaseOptions keys;
};

// A case file carries every setting; an option overrides the file only when
// given explicitly, as it overrides Table 1's case.
SimulationCase case_to_run(SimulateOptions& o, const CLI::App& command) {
  const auto given = [&](const char* name) { return command.get_option(name)->count() > 0; };
  SimulationCase c;
  if (o.case_file.empty()) {
    if (!given("--case")) {
      throw InputError("--case", "none", "1, 2 or 3 (Table 1), or --case-file FILE");
    }
    if (o.case_number != 3 && given("--case3-frequency")) {
      throw InputError(std::vector<Problem>{refused_problem(
          "--case3-frequency", command.get_option("--case3-frequency")->as<std::string>(),
          "case " + std::to_string(o.case_number) + " has no forcing frequency",
          "only with --case 3 (or sweep-friction), whose forcing frequency it sets")});
    }
    c = o.keys.paper(o.case_number);
  } else {
    if (o.keys.reading_given()) {
      throw InputError(o.keys.reading_flag(), o.keys.reading_text(),
                       "only with --case: it chooses a reading of Table 1, and a case file "
                       "writes its torques out");
    }
    c = read_case_file(o.case_file);
  }
  o.keys.apply(c);
  if (given("--rtol") && c.integrator.kind != IntegratorKind::adaptive) {
    throw InputError(std::vector<Problem>{
        refused_problem("--rtol", command.get_option("--rtol")->as<std::string>(),
                        "not used by integrator.kind = \"" +
                            std::string(name_of(kIntegratorKinds, c.integrator.kind)) +
                            "\", which steps at the fixed step",
                        "only with --integrator adaptive, whose step it sets")});
  }
  return c;
}

void run_simulate(SimulateOptions& o, const CLI::App& command) {
  if (command.get_option("--case-file")->count() > 0 && o.case_file.empty()) {
    throw InputError("--case-file", "\"\"", "the path of a case file");
  }
  // Refused before the run, which may take minutes.
  if (!o.out.empty()) {
    require_output_file(o.out, o.case_file.empty() ? std::vector<std::string>{}
                                                   : std::vector<std::string>{o.case_file});
  }
  const SampleFlags samples = read_sample_flags(command, o.sample_rate, o.sample);
  const std::optional<double> sample_rate = samples.rate_hz;
  if (sample_rate) {
    if (command.get_option("--every")->count() > 0) {
      throw InputError(std::vector<Problem>{
          refused_problem("--every", command.get_option("--every")->as<std::string>(),
                          "contradicts --sample-rate, whose samples are on their own grid",
                          "--every without --sample-rate")});
    }
    if (o.out.empty()) {
      throw InputError(std::vector<Problem>{
          refused_problem("--sample-rate", o.sample_rate, "needs --out, the file the samples go to",
                          "--sample-rate FS with --out FILE.csv")});
    }
  }
  const SimulationCase c = case_to_run(o, command);
  if (!o.tacho_out.empty()) {
    if (c.tacho.pulses_per_revolution == 0) {
      throw InputError(std::vector<Problem>{refused_problem(
          "--tacho-out", o.tacho_out, "needs a tacho: tacho.pulses_per_revolution is 0",
          "--tacho-out with [tacho] pulses_per_revolution >= 1 (or --set "
          "tacho.pulses_per_revolution=1)")});
    }
    std::vector<std::string> inputs;
    if (!o.out.empty()) inputs.push_back(o.out);
    if (!o.case_file.empty()) inputs.push_back(o.case_file);
    require_output_file(o.tacho_out, inputs);
  }
  // A driven run's impacts go beside the series, refused here too.
  const bool rattle_files = !o.out.empty() && c.torque1.kind == Torque::Kind::prescribed_speed;
  const std::filesystem::path out_folder = std::filesystem::path(o.out).parent_path();
  const std::string impacts_path = (out_folder / kRattleImpactsFile).string();
  const std::string histogram_path = (out_folder / kRattleHistogramFile).string();
  if (rattle_files) {
    const std::string name = std::filesystem::path(o.out).filename().string();
    if (name == kRattleImpactsFile || name == kRattleHistogramFile) {
      throw InputError("--out", o.out,
                       std::string("a file not named ") + kRattleImpactsFile + " or " +
                           kRattleHistogramFile +
                           ": a driven run writes its impacts there, beside the series");
    }
    std::vector<std::string> inputs{o.out};
    if (!o.case_file.empty()) inputs.push_back(o.case_file);
    require_output_file(impacts_path, inputs);
    require_output_file(histogram_path, inputs);
  }
  RunControl control;
  control.sample_rate_hz = sample_rate;
  control.sample = samples.kind;
  control.keep_samples = false;
  // The series goes to its file as the run makes it, a megabyte at a time,
  // so that a long run's memory does not grow with its length.
  control.keep_series = false;
  std::optional<AtomicFile> series_file;
  std::string pending;
  constexpr std::size_t kFlushBytes = std::size_t{1} << 20;
  control.most_series_rows = max_rows_flag(o.max_rows);
  // A long run says how far it is, a line per tenth, on standard error.
  constexpr double kRowsWorthProgress = 1e7;
  int tenths_done = 0;
  const auto flush = [&](double t_s, bool progress) {
    if (pending.size() < kFlushBytes) return;
    series_file->append(pending);
    pending.clear();
    const int tenths = static_cast<int>(10.0 * t_s / c.integrator.end_time_s);
    if (progress && tenths > tenths_done) {
      tenths_done = tenths;
      std::fprintf(stderr, "simulate: %d%% (t = %s of %s s)\n", 10 * tenths,
                   format_number(t_s).c_str(), format_number(c.integrator.end_time_s).c_str());
    }
  };
  if (!o.out.empty() && sample_rate) {
    // Samples instead of the integrator's rows, streamed alike. The rate is
    // checked by simulate(), before the run; a bad one gives no count here.
    const bool progress = std::isfinite(*sample_rate) && *sample_rate > 0.0 &&
                          sample_count(c.integrator.end_time_s, *sample_rate) >= kRowsWorthProgress;
    series_file.emplace(o.out);
    if (c.bearings.kind == BearingKind::elastic) {
      // The planar model's samples: its state, accelerations, bearing and
      // mesh forces and the sensor's acceleration (planar_samples_csv_header).
      pending = planar_samples_csv_header();
      control.on_planar_sample = [&, progress](const PlanarSample& row) {
        append_planar_sample(pending, row);
        flush(row.t_s, progress);
      };
    } else {
      pending = samples_csv_header();
      control.on_sample = [&, progress](const SampleRow& row) {
        append_sample_row(pending, row);
        flush(row.t_s, progress);
      };
    }
  } else if (!o.out.empty() && c.bearings.kind == BearingKind::elastic) {
    // The planar model's rows: positions and speeds of the centres, bearing
    // and mesh forces of each side (planar_series_csv_header).
    const bool progress = series_rows(c) >= kRowsWorthProgress;
    series_file.emplace(o.out);
    // A helical pair's rows add its axial forces and tilting moments.
    const bool helical = c.gears.helix_angle_rad != 0.0;
    pending = planar_series_csv_header(helical);
    control.on_planar_row = [&, progress, helical](const PlanarRow& row) {
      append_planar_row(pending, row, helical);
      flush(row.t_s, progress);
    };
  } else if (!o.out.empty()) {
    const bool progress = series_rows(c) >= kRowsWorthProgress;
    series_file.emplace(o.out);
    pending = series_csv_header();
    control.on_row = [&, progress](const SeriesRow& row) {
      append_series_row(pending, row);
      flush(row.t_s, progress);
    };
  }
  // The run is checked once (check_run), every refusal naming the option that set the key
  // (naming_options). Unbalanced torques and non-rolling speeds of a case file are said once its
  // keys, fields and gaps pass (an invalid case gets its refusal alone), before the table that
  // may take a while and a run that may take minutes; Table 1's cases are transients by design
  // and run quietly.
  const bool from_file = !o.case_file.empty();
  const auto say_warnings = [&c] {
    for (const std::string& w : run_warnings(c)) {
      std::fprintf(stderr, "gearimpact: warning: %s\n", w.c_str());
    }
  };
  SimulationResult result;
  try {
    o.keys.naming_options([&] {
      const std::function<void()> fields_checked =
          from_file ? std::function<void()>(say_warnings) : std::function<void()>();
      // A helical pair with modifications runs its slices as a train's meshes (route A).
      if (runs_by_slices(c)) {
        result = simulate_by_slices(c, control, fields_checked);
        return;
      }
      const CheckedRun run = check_run(c, control, fields_checked);
      result = simulate(run);
    });
  } catch (const InputError& e) {
    // The key is named as the user gave it (naming_options); the flags that
    // thin the series or lift the bound are the program's.
    if (e.allowed().find("rows of time series") != std::string::npos) {
      throw InputError(e.field(), e.value(),
                       e.allowed() + " (--every keeps fewer rows, --max-rows lifts the bound)");
    }
    if (e.field() == "sample_rate") throw_as_sample_rate_flag(e, o.sample_rate);
    throw;
  }
  if (series_file) {
    series_file->append(pending);
    series_file->commit();
  }
  if (!o.tacho_out.empty()) {
    write_file_atomically(
        o.tacho_out,
        tacho_csv(result.tacho_times_s,
                  signals::tacho_jitter(result.tacho_times_s, c.tacho.jitter_s, c.tacho.seed)));
  }
  if (rattle_files) {
    const std::vector<ImpactRecord> struck = struck_impacts(result);
    write_file_atomically(impacts_path, rattle_impacts_csv(struck));
    write_file_atomically(histogram_path,
                          impact_speed_histogram_csv(impact_speed_histogram(struck)));
  }
  if (result.summary.foundation_extrapolated) {
    std::fprintf(
        stderr, "gearimpact: warning: %s\n",
        foundation_extrapolation_warning(result.summary.foundation_extrapolations).c_str());
  }
  for (const std::string& w : result_warnings(c, result.summary)) {
    std::fprintf(stderr, "gearimpact: warning: %s\n", w.c_str());
  }
  std::fputs(summary_json(result.summary).c_str(), stdout);
}

void run_sweep(SweepOptions& o) {
  const Field& friction = *find_field("model.friction_coefficient");
  const double from = parse_value(friction, o.from, "--from");
  const double to = parse_value(friction, o.to, "--to");
  const double step = parse_number_flag("--step", o.step, "the increment of f, > 0");
  const auto threads = static_cast<unsigned>(
      parse_integer_flag("--threads", o.threads, 0, kMostThreads, "0: all cores"));
  // The sweep sets f itself: a --set of it would do nothing.
  for (const std::string& set : o.keys.sets()) {
    const std::string key = set.substr(0, set.find('='));
    if (key.find("model.friction_coefficient") != std::string::npos) {
      throw InputError("--set", set,
                       "a key other than model.friction_coefficient: sweep-friction sets f "
                       "itself (--from, --to, --step)");
    }
  }
  std::vector<SimulationCase> cases;
  for (int n = 1; n <= 3; ++n) {
    cases.push_back(o.keys.paper(n));
    o.keys.apply(cases.back());
  }
  std::vector<SweepRow> rows;
  try {
    o.keys.naming_options([&] { rows = sweep_friction(cases, from, to, step, threads); });
  } catch (const InputError& e) {
    // sweep_friction names its own arguments from, to, step.
    for (const char* argument : {"from", "to", "step"}) {
      if (e.field() == argument) throw InputError("--" + e.field(), e.value(), e.allowed());
    }
    throw;
  }
  std::fputs(friction_sweep_csv(rows).c_str(), stdout);
}

}  // namespace

void register_simulate_commands(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* simulate = app.add_subcommand(
      "simulate",
      "run one of Table 1's cases or a case file; JSON summary on stdout, time series with --out");
  CLI::Option* paper = simulate->add_option("--case", options->case_number, "Table 1 case")
                           ->check(CLI::IsMember({1, 2, 3}));
  simulate
      ->add_option("--case-file", options->case_file,
                   "a case file (TOML, see docs/case-files.md); other options override it")
      ->excludes(paper);
  simulate->add_option("--out", options->out,
                       "time series CSV file (written atomically); a driven run also writes "
                       "rattle_impacts.csv and rattle_impacts_histogram.csv beside it");
  simulate->add_option(
      "--sample-rate", options->sample_rate,
      "Hz, a plain number or with a unit (\"80 kHz\"): with --out, write samples at t = n / FS "
      "exactly (the integrator's dense output; "
      "accelerations, DTE, mesh force per side; with elastic bearings the centres' "
      "accelerations and the sensor's, [bearings] sensor_gear and sensor_angle) instead of the "
      "integrator's steps; not with --every");
  simulate->add_option("--tacho-out", options->tacho_out,
                       "with [tacho] pulses_per_revolution >= 1: the tacho's edge times, CSV "
                       "pulse,t_s,t_emitted_s (true; with the seeded jitter), written atomically");
  simulate->add_option(
      "--sample", options->sample,
      "the samples' accelerations: interval-average (default: the mean over the interval ending "
      "at each sample, the velocity difference over T, from n = 1 on; transfer sinc(f T) with a "
      "delay of T / 2) or point (the value at each sample's instant, which folds the steps of the "
      "acceleration back into the band)");
  simulate->add_option("--max-rows", options->max_rows,
                       "the most rows the time series may have, so that a slip of --t-end does "
                       "not fill a disk (default " +
                           format_number(static_cast<double>(kMostSeriesRows)) + ")");
  options->keys.add_flags(simulate, kSimulate);
  options->keys.add_reading(simulate);
  options->keys.add_set(simulate,
                        "section.key=value: set any key of the case schema (`gearimpact schema` "
                        "lists them); repeatable");
  simulate->callback([options, simulate] { run_simulate(*options, *simulate); });

  auto sweep_options = std::make_shared<SweepOptions>();
  CLI::App* sweep = app.add_subcommand(
      "sweep-friction", "Fig. 7: CSV of friction loss / damping loss of cases 1-3 against f");
  const std::string f_range = " in " + allowed_text(*find_field("model.friction_coefficient"));
  sweep->add_option("--from", sweep_options->from, "first f" + f_range)->capture_default_str();
  sweep->add_option("--to", sweep_options->to, "last f, at least --from," + f_range)
      ->capture_default_str();
  sweep->add_option("--step", sweep_options->step, "increment of f, > 0")->capture_default_str();
  sweep
      ->add_option(
          "--threads", sweep_options->threads,
          "threads, an integer in [0, " + std::to_string(kMostThreads) + "] (0: all cores)")
      ->capture_default_str();
  sweep_options->keys.add_flags(sweep, kSweepFriction);
  sweep_options->keys.add_reading(sweep);
  sweep_options->keys.add_set(sweep,
                              "section.key=value: set any key of the case schema of cases 1-3 "
                              "but f, which the sweep sets; repeatable");
  sweep->callback([sweep_options] { run_sweep(*sweep_options); });
}

}  // namespace gearimpact::cli
