// `gearimpact train CASE --out DIR`: runs a gear train's case file (docs/case-files.md, A gear
// train; a two-gear case file is the train of its pair) and writes its series and summary, and
// with --sample-rate its sensor's samples.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "case_flags.hpp"
#include "commands.hpp"
#include "gearimpact/dynamics/planetary_train.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/signals/order_tracking.hpp"

namespace gearimpact::cli {

namespace {

struct TrainOptions {
  std::string case_file;
  std::string out;
  bool overwrite = false;
  std::vector<std::string> sets;
  std::string sample_rate;
  std::string sample = "interval-average";
  double max_rows = static_cast<double>(kMostSeriesRows);
};

// A stage file ([stage]): the stage's train run, its summary with the Willis residual, and the
// ring-housing sensor's series and the teeth at each mesh beside the train's.
void run_stage(const TrainOptions& o) {
  const PlanetaryStage stage = read_stage_file(o.case_file, o.sets);
  const GearTrain train = planetary_train(stage);
  const TrainResult result = simulate_train(train);
  const std::string summary = stage_summary_json(train, result, planetary_willis(stage, result));
  const std::vector<double> ring = planetary_ring_sensor(stage, result);
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  write_file_atomically((dir / "series.csv").string(), train_series_csv(train, result.series));
  write_file_atomically((dir / "ring_sensor.csv").string(), ring_sensor_csv(result.series, ring));
  write_file_atomically((dir / "mesh_teeth.csv").string(),
                        stage_teeth_csv(train.bodies.size() - kFirstPlanetBody,
                                        planetary_teeth_series(stage, result)));
  write_file_atomically((dir / "summary.json").string(), summary);
  folder.commit();
  std::cout << summary;
  std::cerr << "train: wrote " << (std::filesystem::path(o.out) / "series.csv").string() << "\n";
}

void run_train(const TrainOptions& o, const CLI::App& command) {
  // Every refusal before any work: the folder, the flags, then the case.
  require_output_folder(o.out, o.overwrite, {o.case_file});
  RunControl control;
  control.most_series_rows = max_rows_flag(o.max_rows);
  const SampleFlags samples = read_sample_flags(command, o.sample_rate, o.sample);
  control.sample_rate_hz = samples.rate_hz;
  control.sample = samples.kind;
  if (is_stage_file(o.case_file)) {
    if (control.sample_rate_hz) {
      throw InputError(std::vector<Problem>{refused_problem(
          "--sample-rate", o.sample_rate,
          "not for a stage file: its ring sensor is written at every step (ring_sensor.csv)",
          "--sample-rate FS with a train file that has a [sensor]")});
    }
    run_stage(o);
    return;
  }
  const GearTrain file = read_train_file(o.case_file, o.sets);
  const TrainResult result = [&] {
    try {
      return simulate_train(file, control);
    } catch (const InputError& e) {
      if (e.field() == "sample_rate") throw_as_sample_rate_flag(e, o.sample_rate);
      throw;
    }
  }();
  // The outputs name the meshes the run ran (a helical mesh by slices: one per slice).
  const GearTrain train = dynamics_train(file);
  const std::string summary = train_summary_json(train, result);
  for (const std::string& w : train_warnings(file, result)) {
    std::cerr << "gearimpact: warning: " << w << "\n";
  }
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  write_file_atomically((dir / "series.csv").string(), train_series_csv(train, result.series));
  if (control.sample_rate_hz) {
    write_file_atomically((dir / "samples.csv").string(), train_series_csv(train, result.samples));
  }
  if (file.tacho_body >= 0) {
    // As simulate --tacho-out writes them: the true times and the emitted, jittered ones.
    write_file_atomically((dir / "tacho.csv").string(),
                          tacho_csv(result.tacho_times_s,
                                    signals::tacho_jitter(result.tacho_times_s, file.tacho.jitter_s,
                                                          file.tacho.seed)));
  }
  write_file_atomically((dir / "summary.json").string(), summary);
  folder.commit();
  std::cout << summary;
  std::cerr << "train: wrote " << (std::filesystem::path(o.out) / "series.csv").string()
            << (control.sample_rate_hz ? " and samples.csv" : "") << "\n";
}

}  // namespace

void register_train_commands(CLI::App& app) {
  auto o = std::make_shared<TrainOptions>();
  CLI::App* train = app.add_subcommand(
      "train",
      "Runs a gear train's case file ([[bodies]], [[meshes]], [[shafts]]; a two-gear case file "
      "is the train of its pair; a [stage] file is a planetary stage's, which adds "
      "ring_sensor.csv, mesh_teeth.csv and the Willis residual) by the event-cut RK4 and writes "
      "series.csv (each "
      "body's angle "
      "and speed, each mesh's s, delta, region, pairs and forces, columns named by the bodies "
      "and meshes) and summary.json (the energy ledger and its residual, per mesh its impacts "
      "and largest penetration)");
  train->add_option("case", o->case_file, "case file of a train or a planetary stage")->required();
  train
      ->add_option("--out", o->out,
                   "output folder: new or empty (else --overwrite), in a folder that exists")
      ->required();
  train->add_option(
      "--set", o->sets,
      "KEY=VALUE (repeatable), as if the file said so: bodies.NAME.KEY, "
      "meshes.NAME.SECTION.KEY (a mesh's pair key), or SECTION.KEY of the file "
      "(integrator.end_time; gears.module, every mesh's default; stage.KEY of a stage)");
  train->add_flag("--overwrite", o->overwrite, "replace a non-empty --out folder whole");
  train->add_option(
      "--sample-rate", o->sample_rate,
      "Hz, a plain number or with a unit (\"51.2 kHz\"): also write samples.csv, the series' "
      "columns at t = n / FS exactly (the steps' continuous extension), its sensor column the "
      "[sensor]'s acceleration as --sample says; a train with a [sensor] only");
  train->add_option(
      "--sample", o->sample,
      "the sensor's samples: interval-average (default: the mean acceleration over the interval "
      "ending at each sample, from n = 1 on) or point (the value at each sample's instant)");
  train->add_option("--max-rows", o->max_rows,
                    "the most samples samples.csv may have, so that a slip of the rate does not "
                    "fill a disk (default " +
                        format_number(static_cast<double>(kMostSeriesRows)) + ")");
  train->callback([o, train] { run_train(*o, *train); });
}

}  // namespace gearimpact::cli
