// `sweep`: the steady state of a case along one parameter (and optionally over a second), in
// both directions, lines in parallel, shardable (batch/steady_sweep.hpp); `merge`: shards into one
// output (io/sweep_files.hpp). This file reads the options, prints the progress and draws the
// figures.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "case_flags.hpp"
#include "commands.hpp"
#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/io/sweep_files.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/iso_resonance.hpp"
#include "gearimpact/steady/sweep.hpp"
#include "gnuplot.hpp"
#include "iso_plot.hpp"
#include "program.hpp"

namespace gearimpact::cli {

namespace {

struct SweepCommandOptions {
  std::string case_source;
  std::string vary, from, to;
  int points = 0;
  std::string direction = "both";
  std::string vary2, from2, to2;
  int points2 = 1;
  std::string out = "sweep-out";
  std::string shard;
  CLI::Option* shard_flag = nullptr;  // to tell --shard "" from no --shard
  unsigned threads = 0;
  bool plots = true;
  bool overwrite = false;
  double max_points = kMostSweepPoints;
  SteadySettings settings;
  CaseOptions keys;
};

// A value of a numeric key as the user wrote it: with a unit as in case files, or a plain number
// (SI for a quantity), checked against the key's range.
double sweep_value(const std::string& key, const std::string& text, const std::string& flag) {
  return gearimpact::parse_value(sweep_field(key, flag), text, flag + " (" + key + ")");
}

bool is_paper_case(const std::string& source) {
  return source == "1" || source == "2" || source == "3";
}

SimulationCase read_case(const std::string& source) {
  if (is_paper_case(source)) return paper_case(std::stoi(source));
  return read_case_file(source);
}

// A whole number of at most 9 digits, for the shard's parts.
bool is_digits(const std::string& part) {
  return !part.empty() && part.size() <= 9 &&
         std::all_of(part.begin(), part.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

// SLURM's variable `name` as a whole number, or none when unset; throws InputError naming it
// when it is set but not one.
std::optional<long> slurm_number(const char* name) {
  const char* text = std::getenv(name);
  if (text == nullptr) return std::nullopt;
  if (!is_digits(text)) {
    throw InputError(name, std::string("\"") + text + "\"",
                     "a whole number, as SLURM sets it for an array job");
  }
  return std::stol(text);
}

SweepShard parse_shard(const std::string& text, bool given) {
  if (given && text.empty()) {
    throw InputError("--shard", "\"\"", "K/N with 0 <= K < N (leave --shard out to run all)");
  }
  std::string spec = text;
  if (spec.empty()) {
    const std::optional<long> id = slurm_number("SLURM_ARRAY_TASK_ID");
    const std::optional<long> count = slurm_number("SLURM_ARRAY_TASK_COUNT");
    const std::optional<long> min = slurm_number("SLURM_ARRAY_TASK_MIN");
    if (!id || !count) return {};
    spec = std::to_string(*id - min.value_or(0)) + "/" + std::to_string(*count);
  }
  // K/N: two runs of at most 9 digits around one slash.
  const std::size_t slash = spec.find('/');
  const auto digits = is_digits;
  const std::string k_text = slash == std::string::npos ? spec : spec.substr(0, slash);
  const std::string n_text = slash == std::string::npos ? "" : spec.substr(slash + 1);
  if (!digits(k_text) || !digits(n_text) || std::stoi(n_text) < 1 ||
      std::stoi(k_text) >= std::stoi(n_text)) {
    throw InputError("--shard", spec,
                     "K/N with 0 <= K < N (or SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT and "
                     "SLURM_ARRAY_TASK_MIN)");
  }
  return {std::stoi(k_text), std::stoi(n_text)};
}

// The spec of the options, on `base` with the case options applied.
SteadySweepSpec sweep_spec(SweepCommandOptions& o, SimulationCase base) {
  o.keys.apply(base);
  SteadySweepSpec spec;
  spec.base = std::move(base);
  spec.vary = o.vary;
  sweep_field(o.vary, "--vary");
  spec.from_si = sweep_value(o.vary, o.from, "--from");
  spec.to_si = sweep_value(o.vary, o.to, "--to");
  spec.points = o.points;
  if (!o.vary2.empty()) {
    spec.vary2 = o.vary2;
    sweep_field(o.vary2, "--vary2");
    spec.from2_si = sweep_value(o.vary2, o.from2, "--from2");
    spec.to2_si = sweep_value(o.vary2, o.to2, "--to2");
    spec.points2 = o.points2;
  }
  spec.directions.clear();
  if (o.direction != "down") spec.directions.push_back(SweepDirection::up);
  if (o.direction != "up") spec.directions.push_back(SweepDirection::down);
  spec.shard = parse_shard(o.shard, o.shard_flag != nullptr && o.shard_flag->count() > 0);
  spec.settings = o.settings;
  spec.threads = o.threads;
  if (!(o.max_points >= 1.0 && o.max_points <= 9e18)) {
    throw InputError("--max-points", shortest_decimal(o.max_points),
                     "a count in [1, 9e18]: the most points of the whole sweep");
  }
  spec.max_points = o.max_points;
  return spec;
}

// run_steady_sweep with its arguments' errors under the flags that set them.
SteadySweep run_naming_flags(const SteadySweepSpec& spec,
                             const std::function<void(const SweepPointResult&)>& on_point) {
  try {
    return run_steady_sweep(spec, on_point);
  } catch (const InputError& e) {
    if (e.field() == "max_points") {
      throw InputError("--points", e.value(), e.allowed() + " (--max-points lifts the bound)");
    }
    for (const char* argument :
         {"vary", "from", "to", "points", "vary2", "from2", "to2", "points2", "shard", "directions",
          "steps_per_contact_period", "max_periods", "tolerance"}) {
      if (e.field() == argument) {
        std::string flag = "--" + e.field();
        std::replace(flag.begin(), flag.end(), '_', '-');
        throw InputError(flag, e.value(), e.allowed());
      }
    }
    throw;
  }
}

// How many different values `xs` holds: gnuplot refuses a plot with no point ("x range is
// invalid"), and a plot of one value says nothing.
std::size_t distinct(std::vector<double> xs) {
  std::sort(xs.begin(), xs.end());
  return static_cast<std::size_t>(std::unique(xs.begin(), xs.end()) - xs.begin());
}

// True when the figure has two values or more to draw; else says on stderr why it is skipped, so
// that a valid run (one point, one shard of a few lines) never fails in its plots.
bool worth_plotting(const char* figure, std::size_t values) {
  if (values >= 2) return true;
  std::cerr << "gearimpact: note: no " << figure
            << " plot: " << (values == 0 ? "nothing" : "a single value") << " to draw\n";
  return false;
}

// dynamic_factor_vs_iso_n.csv from the rows (the swept value is w1) and its figure.
void render_iso_plot(const std::filesystem::path& dir, const IsoScale& iso,
                     const std::vector<SweepPointResult>& rows) {
  std::string data =
      "line,direction,index,w1_rad_s,iso_resonance_ratio,iso_resonance_ratio_iso_stiffness,"
      "dynamic_factor\n";
  double n_max = 0.0;
  for (const SweepPointResult& r : rows) {
    const double n = iso_resonance_ratio(r.value_si, iso.resonance_speed_rad_per_s);
    n_max = std::max(n_max, n);
    const std::optional<double>& df = r.point.dynamic_factor;
    data += std::to_string(r.line) + "," + to_string(r.direction) + "," + std::to_string(r.index) +
            "," + format_data_number(r.value_si) + "," + format_data_number(n) + "," +
            format_data_number(
                iso_resonance_ratio(r.value_si, iso.resonance_speed_iso_stiffness_rad_per_s)) +
            "," + (df ? format_data_number(*df) : "") + "\n";
  }
  write_file_atomically((dir / "dynamic_factor_vs_iso_n.csv").string(), data);
  write_iso_kv_band(dir / "iso_kv_band.csv", iso, std::max(2.0, 1.1 * n_max));
  render(dir, dynamic_factor_vs_iso_n("dynamic_factor_vs_iso_n", iso, "dynamic_factor_vs_iso_n.csv",
                                      2, 5, 7, "iso_kv_band.csv"));
}

// The plots of a sweep folder: amplitude up and down, the bifurcation diagram, the regime map.
void render_plots(const std::filesystem::path& dir, const SteadySweep& sweep) {
  const SteadySweepRecord& spec = sweep.spec;
  const std::string& vary = spec.vary;
  std::vector<double> amplitude_x, poincare_x, iso_x, map_x, map_lines;
  for (const SweepPointResult& r : sweep.rows) {
    if (r.point.dte_amplitude_m) amplitude_x.push_back(r.value_si);
    if (!r.point.poincare.empty()) poincare_x.push_back(r.value_si);
    if (r.point.dynamic_factor) iso_x.push_back(r.value_si);
    if (r.direction == SweepDirection::up) {
      map_x.push_back(r.value_si);
      map_lines.push_back(r.line);
    }
  }
  Figure amplitude;
  amplitude.name = "amplitude";
  amplitude.title = "Steady DTE amplitude, sweeps up and down";
  amplitude.x_label = vary + " (SI)";
  amplitude.y_label = "half peak-to-peak of s (m)";
  amplitude.setup = {"set key outside right"};
  for (const char* d : {"up", "down"}) {
    amplitude.series.push_back(std::string("for [l=0:") + std::to_string(spec.lines - 1) +
                               "] 'sweep.csv' using (($1 == l && strcol(2) eq \"" + d +
                               "\") ? $4 : NaN):9 with linespoints title sprintf('line %d " + d +
                               "', l)");
  }
  if (worth_plotting("amplitude", distinct(amplitude_x))) render(dir, amplitude);
  Figure bifurcation;
  bifurcation.name = "bifurcation";
  bifurcation.title = "Bifurcation diagram: Poincare samples of s";
  bifurcation.x_label = vary + " (SI)";
  bifurcation.y_label = "s at the excitation phase (m)";
  bifurcation.series = {
      "'poincare.csv' using (strcol(2) eq \"up\" ? $4 : NaN):5 with points pt 7 ps 0.4 title 'up'",
      "'poincare.csv' using (strcol(2) eq \"down\" ? $4 : NaN):5 with points pt 6 ps 0.6 title "
      "'down'"};
  if (worth_plotting("bifurcation", distinct(poincare_x))) render(dir, bifurcation);
  if (spec.iso && worth_plotting("dynamic_factor_vs_iso_n", distinct(iso_x))) {
    render_iso_plot(dir, *spec.iso, sweep.rows);
  }
  if (spec.vary2.empty() || spec.lines < 2) return;
  // The map needs up rows spread over two values of each key.
  if (!worth_plotting("regime-map", std::min(distinct(map_x), distinct(map_lines)))) return;
  const double from2 = spec.from2_si.value_or(0.0);
  const double to2 = spec.to2_si.value_or(0.0);
  const std::string step2 = format_data_number((to2 - from2) / (spec.lines - 1));
  Figure map;
  map.name = "regime-map";
  map.title = "Regimes (up sweeps): NI 0, SS 1, DS 2, NC 3";
  map.x_label = vary + " (SI)";
  map.y_label = spec.vary2 + " (SI)";
  map.setup = {"set cbrange [0:3]", "set palette maxcolors 4",
               "set cbtics ('NI' 0, 'SS' 1, 'DS' 2, 'NC' 3)"};
  map.series = {
      "'sweep.csv' using (strcol(2) eq \"up\" ? $4 : NaN):(" + format_data_number(from2) +
      " + $1 * " + step2 +
      "):(strcol(5) eq \"NI\" ? 0 : strcol(5) eq \"SS\" ? 1 : strcol(5) eq \"DS\" ? 2 : 3) "
      "with points pt 5 ps 1.5 palette notitle"};
  render(dir, map);
}

// The options of `sweep` after CASE.
void add_sweep_options(CLI::App* sweep, SweepCommandOptions& o) {
  sweep
      ->add_option("--vary", o.vary,
                   "the key to sweep, section.key: any quantity, number or integer key of the "
                   "case schema (`gearimpact schema`)")
      ->required();
  sweep->add_option("--from", o.from, "first value, with its unit as in case files")->required();
  sweep->add_option("--to", o.to, "last value")->required();
  sweep
      ->add_option("--points", o.points,
                   "number of values (>= 1); points x points2 x directions at most --max-points")
      ->required();
  sweep->add_option("--direction", o.direction, "up, down or both")
      ->check(CLI::IsMember({"up", "down", "both"}));
  sweep->add_option("--vary2", o.vary2, "a second key: one line per value");
  sweep->add_option("--from2", o.from2, "first value of the second key");
  sweep->add_option("--to2", o.to2, "last value of the second key");
  sweep->add_option("--points2", o.points2, "number of values of the second key");
  sweep->add_option("--max-points", o.max_points,
                    "the most points (points x points2 x directions) the sweep may run, so that a "
                    "slip of --points does not start a run of days (default " +
                        shortest_decimal(kMostSweepPoints) + ")");
  sweep->add_option("--out", o.out,
                    "output folder: new or empty (else --overwrite), in a folder that exists; "
                    "written beside it and renamed into place when complete");
  sweep->add_flag("--overwrite", o.overwrite, "replace a non-empty --out folder whole");
  o.shard_flag =
      sweep->add_option("--shard", o.shard,
                        "K/N: the lines u with u % N == K (default: SLURM_ARRAY_TASK_ID - "
                        "SLURM_ARRAY_TASK_MIN of SLURM_ARRAY_TASK_COUNT, else all)");
  o.keys.add_flags(sweep, kSweep);
  o.keys.add_set(sweep,
                 "KEY=VALUE for any key of the case schema, before the sweep, in order, after "
                 "the flags that set keys (repeatable); a numeric key as a swept value: a "
                 "speed moves the other speed, a mean torque the other mean torque (balance)",
                 SetNumbers::as_swept_value);
  sweep->add_option("--tolerance", o.settings.tolerance,
                    "samples repeat within this fraction of B and B w_n, in (0, " +
                        shortest_decimal(kMostTolerance) + "]");
  sweep->add_option("--steps-per-contact-period", o.settings.steps_per_contact_period,
                    "RK4 steps per period of the stiffest contact, in [" +
                        shortest_decimal(kLeastStepsPerContactPeriod) + ", " +
                        shortest_decimal(kMostStepsPerContactPeriod) + "]");
  sweep->add_option("--max-periods", o.settings.max_periods,
                    "excitation periods a point may run before it is not converged, in [1, " +
                        std::to_string(kMostMaxPeriods) + "]");
  sweep
      ->add_option("--threads", o.threads,
                   "worker threads, in [0, " + std::to_string(kMostThreads) + "] (0: one per core)")
      ->check(CLI::Range(0u, static_cast<unsigned>(kMostThreads)));
  sweep->add_flag("!--no-plots", o.plots, "skip the gnuplot figures");
}

void run_sweep(SweepCommandOptions& o) {
  const std::vector<std::string> inputs = is_paper_case(o.case_source)
                                              ? std::vector<std::string>{}
                                              : std::vector<std::string>{o.case_source};
  require_output_folder(o.out, o.overwrite, inputs);
  const SteadySweepSpec spec = sweep_spec(o, read_case(o.case_source));
  AtomicFolder folder(o.out, o.overwrite, inputs);
  std::mutex progress_mutex;
  std::size_t done = 0;
  const std::size_t total = shard_point_count(spec);
  const SteadySweep sweep = run_naming_flags(spec, [&](const SweepPointResult& r) {
    const std::lock_guard lock(progress_mutex);
    ++done;
    std::cerr << "sweep: " << done << "/" << total << "  line " << r.line << " "
              << to_string(r.direction) << " " << spec.vary << " = " << format_number(r.value_si)
              << ": "
              << (r.point.converged
                      ? to_string(r.point.regime) + " period " + std::to_string(r.point.period)
                      : std::string("not converged"))
              << " after " << r.point.periods_run << " periods"
              << (r.failure.empty() ? "" : " (" + r.failure + ")") << '\n';
  });
  write_sweep_folder(folder.temporary(), sweep);
  if (o.plots) render_plots(folder.temporary(), sweep);
  folder.commit();
}

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string out;
  bool plots = true;
  bool overwrite = false;
};

void run_merge(const MergeOptions& o) {
  AtomicFolder folder(o.out, o.overwrite, o.inputs);
  const SteadySweep merged =
      merge_sweep_folders(std::vector<std::filesystem::path>(o.inputs.begin(), o.inputs.end()));
  write_sweep_folder(folder.temporary(), merged);
  if (o.plots) render_plots(folder.temporary(), merged);
  folder.commit();
}

}  // namespace

SteadySweep sweep_with_options(const SimulationCase& c, const std::vector<std::string>& options) {
  CLI::App app{"sweep"};
  SweepCommandOptions o;
  add_sweep_options(&app, o);
  std::vector<std::string> reversed(options.rbegin(), options.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    throw InputError("options", e.what(), "options of gearimpact sweep after CASE");
  }
  return run_naming_flags(sweep_spec(o, c), {});
}

void register_sweep_commands(CLI::App& app) {
  auto o = std::make_shared<SweepCommandOptions>();
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "steady state along a parameter, up and down, continued from point to point: DIR/sweep.csv, "
      "poincare.csv, summary.json and plots");
  sweep->add_option("CASE", o->case_source, "case file, or 1, 2, 3 for Table 1")->required();
  add_sweep_options(sweep, *o);
  sweep->callback([o] { run_sweep(*o); });

  auto m = std::make_shared<MergeOptions>();
  CLI::App* merge = app.add_subcommand(
      "merge", "merge sweep shards by (line, direction, index); fails naming a missing key");
  merge->add_option("DIR", m->inputs, "shard output folders")->required();
  merge
      ->add_option("--out", m->out,
                   "merged output folder: new or empty (else --overwrite), not a shard's, in a "
                   "folder that exists; written beside it and renamed into place when complete")
      ->required();
  merge->add_flag("--overwrite", m->overwrite, "replace a non-empty --out folder whole");
  merge->add_flag("!--no-plots", m->plots, "skip the gnuplot figures");
  merge->callback([m] { run_merge(*m); });
}

}  // namespace gearimpact::cli
