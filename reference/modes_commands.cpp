// `gearimpact modes CASE --out DIR`: the natural modes of the case's
// linearised model (docs/vibration.md), each mode's strain-energy shares, and
// a Campbell diagram of the mesh harmonics against the pinion speed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "case_flags.hpp"
#include "commands.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/modes_files.hpp"
#include "gearimpact/io/planetary_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/modes/modes.hpp"
#include "gearimpact/modes/planetary.hpp"
#include "gearimpact/modes/train_modes.hpp"
#include "gnuplot.hpp"
#include "program.hpp"

namespace gearimpact::cli {

namespace {

constexpr double kRpm = 60.0 / (2.0 * pi);

void require_harmonics(int harmonics) {
  if (harmonics < 1 || harmonics > kMostHarmonics) {
    throw InputError("harmonics", std::to_string(harmonics),
                     "an integer in [1, " + std::to_string(kMostHarmonics) + "]");
  }
}

void require_max_speed(std::optional<double> speed) {
  if (speed && !(std::isfinite(*speed) && *speed > 0.0)) {
    throw InputError("max_speed", *speed, "a pinion speed > 0 and finite, in rad/s");
  }
}

}  // namespace

ModesTexts modes_texts(const SimulationCase& c, int harmonics,
                       std::optional<double> max_pinion_speed_rad_per_s) {
  require_harmonics(harmonics);
  require_max_speed(max_pinion_speed_rad_per_s);
  ModesTexts texts;
  texts.modes = natural_modes(c);
  double highest = 0.0;
  for (const NaturalMode& mode : texts.modes.modes)
    highest = std::max(highest, mode.angular_frequency);
  // Every crossing of every harmonic lies below the first harmonic's with the highest mode.
  const double teeth1 = static_cast<double>(c.gears.teeth1);
  texts.max_pinion_speed_rad_per_s = max_pinion_speed_rad_per_s.value_or(1.1 * highest / teeth1);
  texts.crossings =
      campbell_crossings(texts.modes, c.gears.teeth1, harmonics, texts.max_pinion_speed_rad_per_s);
  texts.csv = modes_csv(texts.modes);
  texts.campbell_csv = campbell_csv(texts.crossings);
  texts.shapes_csv = mode_shapes_csv(texts.modes);
  ModesSummary summary;
  summary.case_name = c.name;
  summary.teeth1 = c.gears.teeth1;
  summary.harmonics = harmonics;
  summary.max_pinion_speed_rad_per_s = texts.max_pinion_speed_rad_per_s;
  texts.summary_json = modes_summary_json(summary, texts.modes, texts.crossings);
  return texts;
}

namespace {

struct ModesOptions {
  std::string case_file;
  std::string out;
  int harmonics = 3;
  std::string max_speed;
  bool overwrite = false;
  bool no_plots = false;
  CaseOptions keys;
  CLI::Option* harmonics_option = nullptr;
  CLI::App* command = nullptr;  // the subcommand, whose case flags a planetary file refuses
};

// The pinion speed a run file holds (its driver's mean speed, or its initial
// w1), to mark on the Campbell diagram; nothing for a pair at rest.
std::optional<double> running_speed(const SimulationCase& c) {
  const double w = c.torque1.kind == Torque::Kind::prescribed_speed ? c.torque1.mean_speed_rad_per_s
                                                                    : c.initial.w1_rad_per_s;
  if (w == 0.0) return std::nullopt;
  return std::fabs(w);
}

// The x tics of a bar per mode, from columns 1-3 (mode, rigid, frequency_hz)
// that modes.csv and mode_shapes.csv share.
constexpr const char* kModeTics =
    ":xtic((strcol(2) eq 'true') ? sprintf('%d: rigid', int($1)) : "
    "sprintf('%d: %.5g Hz', int($1), $3))";

// Each elastic mode as a bar split into its strain-energy shares.
Figure energy_figure(const SimulationCase& c) {
  Figure f;
  f.name = "modes_energy";
  f.title = "Strain-energy shares of each mode (" + literal_key(c.name) + ")";
  f.x_label = "mode: natural frequency";
  f.y_label = "share of the mode's strain energy";
  f.setup = {"set style data histograms",
             "set style histogram rowstacked",
             "set style fill solid 0.85 border -1",
             "set boxwidth 0.7",
             "set yrange [0:1.05]",
             "set key outside right top vertical",
             "set xtics rotate by -30"};
  // modes.csv's share columns 5..9; a rigid mode's bar is empty (it stores no energy).
  const char* titles[kSpringParts] = {"mesh", "bearing 1", "bearing 2", "motor shaft",
                                      "load shaft"};
  // The bearings' and shafts' parts are drawn only where the case has them: an
  // empty series would still take a key entry and mislead.
  const bool elastic_bearings = c.bearings.kind == BearingKind::elastic;
  const bool elastic_shafts = c.shafts.kind == ShaftKind::elastic;
  for (std::size_t part = 0; part < kSpringParts; ++part) {
    if ((part == 1 || part == 2) && !elastic_bearings) continue;
    if ((part == 3 || part == 4) && !elastic_shafts) continue;
    std::string series = "'modes.csv' using " + std::to_string(5 + part);
    if (part == 0) {
      series += kModeTics;
    }
    f.series.push_back(series + " title " + gnuplot_string(titles[part]));
  }
  return f;
}

// Each mode's shape as a cluster of bars, one per DOF, in base-circle lengths
// (mode_shapes.csv): which body moves, and which way, in each mode.
Figure shapes_figure(const SimulationCase& c, const Modes& modes) {
  Figure f;
  f.name = "mode_shapes";
  f.title = "Mode shapes, rotations as Rb theta, largest component 1 (" + literal_key(c.name) + ")";
  f.x_label = "mode: natural frequency";
  f.y_label = "component of the shape";
  f.setup = {"set style data histograms",
             "set style histogram clustered gap 1",
             "set style fill solid 0.85 border -1",
             "set yrange [-1.1:1.1]",
             "set key outside right top vertical noenhanced",
             "set xtics rotate by -30",
             "set xzeroaxis lt -1"};
  for (std::size_t k = 0; k < modes.model.dofs.size(); ++k) {
    const Dof dof = modes.model.dofs[k];
    std::string label(dof_name(dof));
    if (dof == Dof::theta1 || dof == Dof::theta_motor) label = "Rb1 " + label;
    if (dof == Dof::theta2 || dof == Dof::theta_load) label = "Rb2 " + label;
    std::string series = "'mode_shapes.csv' using " + std::to_string(4 + k);
    if (k == 0) {
      series += kModeTics;
    }
    f.series.push_back(series + " title " + gnuplot_string(label));
  }
  return f;
}

// The mesh harmonics k Z1 n / 60 (n in rpm) against the natural frequencies, crossings marked.
Figure campbell_figure(const SimulationCase& c, const ModesTexts& texts, int harmonics) {
  const double max_rpm = texts.max_pinion_speed_rad_per_s * kRpm;
  double highest_hz = 0.0;
  for (const NaturalMode& mode : texts.modes.modes)
    highest_hz = std::max(highest_hz, mode.frequency_hz);
  Figure f;
  f.name = "campbell";
  f.title = "Campbell diagram: mesh harmonics k f_m and natural frequencies (" +
            literal_key(c.name) + ")";
  f.x_label = "pinion speed, rpm";
  f.y_label = "frequency, Hz";
  f.setup = {"set key outside right top vertical", "set samples 500",
             "set xrange [0:" + format_data_number(max_rpm) + "]",
             "set yrange [0:" + format_data_number(1.1 * highest_hz) + "]"};
  if (const std::optional<double> w = running_speed(c)) {
    const std::string x = format_data_number(*w * kRpm);
    f.setup.push_back("set arrow from " + x + ", graph 0 to " + x +
                      ", graph 1 nohead dt 3 lw 2 lc rgb 'gray30'");
    f.setup.push_back("set label 'running speed' at " + x + ", graph 0.97 offset 0.5, 0");
  }
  for (int k = 1; k <= harmonics; ++k) {
    f.series.push_back(std::to_string(k) + " * " + std::to_string(c.gears.teeth1) +
                       " * x / 60 with lines lw 2 title '" + std::to_string(k) + " f_m'");
  }
  bool first = true;
  const std::vector<NaturalMode>& modes = texts.modes.modes;
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const NaturalMode& mode = modes[i];
    if (mode.rigid) continue;
    f.series.push_back(format_data_number(mode.frequency_hz) + " with lines dt 2 lc rgb 'gray40' " +
                       (first ? "title 'natural frequencies'" : "notitle"));
    first = false;
    // Each line named at its right end by its mode (as modes.csv numbers them) and frequency,
    // above it, or below it where the next mode's line is closer than a label's height (4 % of
    // the axis).
    const bool crowded = i + 1 < modes.size() &&
                         modes[i + 1].frequency_hz - mode.frequency_hz < 0.04 * 1.1 * highest_hz;
    char label[160];
    std::snprintf(label, sizeof label,
                  "set label 'mode %zu: %.0f Hz' at graph 1, first %s right offset -0.5, %s "
                  "font ',9' tc rgb 'gray30'",
                  i + 1, mode.frequency_hz, format_data_number(mode.frequency_hz).c_str(),
                  crowded ? "-0.7" : "0.6");
    f.setup.emplace_back(label);
  }
  // gnuplot refuses a plot with no point: the crossings only when there are some.
  if (!texts.crossings.empty()) {
    f.series.push_back(
        "'campbell.csv' using 5:3 with points pt 7 ps 1.2 lc rgb '#d62728' title 'crossings'");
  }
  return f;
}

// The planetary modes as a table on stdout: frequency, multiplicity, type and
// the strain-energy shares by spring kind.
std::string stage_modes_table(const std::vector<StageModeRow>& rows) {
  std::string table = " mode  frequency_hz  mult  type           ";
  for (StageSpring kind : kStageSpringKinds) {
    char head[32];
    std::snprintf(head, sizeof head, " %15s", std::string(stage_spring_name(kind)).c_str());
    table += head;
  }
  table += "\n";
  for (const StageModeRow& r : rows) {
    char line[96];
    std::snprintf(line, sizeof line, "%5d  %12.3f  %4d  %-13s  ", r.number, r.frequency_hz,
                  r.multiplicity, std::string(stage_mode_type_name(r.type)).c_str());
    table += line;
    for (double share : r.share) {
      std::snprintf(line, sizeof line, " %15.3f", share);
      table += line;
    }
    table += "\n";
  }
  return table;
}

// `modes` on a planetary file: the linear stage's modes (docs/planetary.md).
void write_planetary_modes(ModesOptions& o) {
  // The pair's options have nothing to act on here: refused, not ignored.
  if (o.harmonics_option != nullptr && o.harmonics_option->count() > 0) {
    throw InputError("--harmonics", std::to_string(o.harmonics),
                     "left out on a planetary file (no Campbell diagram)");
  }
  if (!o.max_speed.empty()) {
    throw InputError("--max-speed", o.max_speed,
                     "left out on a planetary file (no Campbell diagram)");
  }
  constexpr const char* kNoKeys =
      "left out on a planetary file: its keys are [planetary]'s, set in the file";
  if (!o.keys.sets().empty()) throw InputError("--set", o.keys.sets().front(), kNoKeys);
  for (const CaseFlag& flag : kCaseFlags) {
    if ((flag.commands & kModes) == 0) continue;
    const CLI::Option* given = o.command->get_option_no_throw(flag.flag);
    if (given != nullptr && given->count() > 0) {
      throw InputError(flag.flag, given->as<std::string>(), kNoKeys);
    }
  }
  const PlanetaryCase stage = read_planetary_file(o.case_file);
  const PlanetaryModes modes = planetary_modes(planetary_model(stage.parameters));
  const std::vector<StageModeRow> rows = stage_mode_rows(modes);
  const std::string csv = csv_of(stage_modes_columns(), rows);
  const std::string summary = stage_modes_summary_json(stage.name, modes);
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  write_file_atomically((dir / "modes.csv").string(), csv);
  write_file_atomically((dir / "summary.json").string(), summary);
  folder.commit();
  std::fputs(stage_modes_table(rows).c_str(), stdout);
  std::cerr << "modes: wrote " << (std::filesystem::path(o.out) / "modes.csv").string() << "\n";
}

// The train's modes as a table on stdout: frequency and the strain-energy shares by spring.
std::string train_modes_table(const GearTrain& train, const std::vector<TrainModeRow>& rows) {
  const Columns<TrainModeRow> columns = train_modes_columns(train);
  std::string table = " mode  frequency_hz";
  // The share columns follow mode, rigid, frequency_hz and angular_frequency_rad_per_s.
  std::vector<std::size_t> shares;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (columns[c].name.rfind("share_", 0) != 0) continue;
    shares.push_back(c);
    table += "  " + columns[c].name;
  }
  table += "\n";
  for (const TrainModeRow& r : rows) {
    char line[64];
    if (r.mode.rigid) {
      std::snprintf(line, sizeof line, "%5d  %12s", r.number, "rigid");
    } else {
      std::snprintf(line, sizeof line, "%5d  %12.3f", r.number, r.mode.frequency_hz);
    }
    table += line;
    for (std::size_t c : shares) {
      // As wide as its header, which is the file's name of the mesh or shaft: any length.
      std::string cell(columns[c].name.size() + 32, '\0');
      const int written =
          std::snprintf(cell.data(), cell.size(), "  %*.3f",
                        static_cast<int>(columns[c].name.size()), columns[c].value(r));
      cell.resize(static_cast<std::size_t>(std::max(written, 0)));
      table += cell;
    }
    table += "\n";
  }
  return table;
}

// `modes` on a train file: the torsional train's modes at each mesh's mean mesh stiffness
// (docs/planetary.md, "Modes of a torsional train").
void write_train_modes(ModesOptions& o) {
  // The pair's options have nothing to act on here: refused, not ignored.
  if (o.harmonics_option != nullptr && o.harmonics_option->count() > 0) {
    throw InputError("--harmonics", std::to_string(o.harmonics),
                     "left out on a train file (no Campbell diagram)");
  }
  if (!o.max_speed.empty()) {
    throw InputError("--max-speed", o.max_speed, "left out on a train file (no Campbell diagram)");
  }
  for (const CaseFlag& flag : kCaseFlags) {
    if ((flag.commands & kModes) == 0) continue;
    const CLI::Option* given = o.command->get_option_no_throw(flag.flag);
    if (given != nullptr && given->count() > 0) {
      throw InputError(flag.flag, given->as<std::string>(),
                       "left out on a train file: set a mesh's key with --set "
                       "meshes.NAME.SECTION.KEY=VALUE, or every mesh's with SECTION.KEY=VALUE");
    }
  }
  const GearTrain train = read_train_file(o.case_file, o.keys.sets());
  const TrainModes modes = train_modes(train);
  const std::vector<TrainModeRow> rows = train_mode_rows(modes);
  const std::string csv = csv_of(train_modes_columns(train), rows);
  const std::string summary =
      train_modes_summary_json(std::filesystem::path(o.case_file).stem().string(), train, modes);
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  write_file_atomically((dir / "modes.csv").string(), csv);
  write_file_atomically((dir / "summary.json").string(), summary);
  folder.commit();
  std::fputs(train_modes_table(train, rows).c_str(), stdout);
  std::cerr << "modes: wrote " << (std::filesystem::path(o.out) / "modes.csv").string() << "\n";
}

void write_modes(ModesOptions& o) {
  // Every refusal before any work: the folder, the options, the case.
  require_output_folder(o.out, o.overwrite, {o.case_file});
  if (is_planetary_file(o.case_file)) {
    write_planetary_modes(o);
    return;
  }
  if (is_train_file(o.case_file)) {
    write_train_modes(o);
    return;
  }
  require_harmonics(o.harmonics);
  std::optional<double> max_speed;
  if (!o.max_speed.empty()) {
    max_speed = parse_quantity(o.max_speed, Dimension::angular_velocity, "--max-speed");
    if (!(*max_speed > 0.0)) {
      throw InputError("--max-speed", o.max_speed,
                       "a pinion speed > 0 (" + allowed_units(Dimension::angular_velocity) + ")");
    }
  }
  SimulationCase c = read_pair_or_run_file(o.case_file).simulation_case;
  o.keys.apply(c);
  ModesTexts texts;
  o.keys.naming_options([&] { texts = modes_texts(c, o.harmonics, max_speed); });
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  write_file_atomically((dir / "modes.csv").string(), texts.csv);
  write_file_atomically((dir / "campbell.csv").string(), texts.campbell_csv);
  write_file_atomically((dir / "mode_shapes.csv").string(), texts.shapes_csv);
  write_file_atomically((dir / "summary.json").string(), texts.summary_json);
  if (!o.no_plots) {
    render(dir, energy_figure(c));
    render(dir, shapes_figure(c, texts.modes));
    render(dir, campbell_figure(c, texts, o.harmonics));
  }
  folder.commit();
  std::fputs(texts.summary_json.c_str(), stdout);
  std::cerr << "modes: wrote " << (std::filesystem::path(o.out) / "modes.csv").string() << "\n";
}

}  // namespace

void register_modes_commands(CLI::App& app) {
  auto o = std::make_shared<ModesOptions>();
  CLI::App* modes = app.add_subcommand(
      "modes",
      "The natural modes of the case's linearised model at its mean mesh stiffness "
      "(docs/vibration.md): torsional, or planar with [bearings] kind = \"elastic\", with a "
      "motor and a load with [shafts] kind = \"elastic\". Writes modes.csv (frequencies, "
      "strain-energy shares, mass-normalised shapes), campbell.csv (where the mesh harmonics "
      "cross them), mode_shapes.csv, summary.json and the figures modes_energy.png, "
      "mode_shapes.png and campbell.png. On a planetary file ([planetary], docs/planetary.md): the "
      "linear stage's modes, modes.csv (frequency, multiplicity, type, strain-energy shares by "
      "spring kind) and summary.json, the table printed. On a train file ([[bodies]], "
      "docs/planetary.md, \"Modes of a torsional train\"): the torsional train's modes at each "
      "mesh's mean mesh stiffness, modes.csv (frequency, strain-energy share per mesh and "
      "torsional shaft, the shape per body) and summary.json, the table printed");
  modes
      ->add_option("case", o->case_file,
                   "case file: a pair file, a run file, a planetary file or a train file")
      ->required();
  modes
      ->add_option("--out", o->out,
                   "output folder: new or empty (else --overwrite), in a folder that exists")
      ->required();
  o->harmonics_option = modes->add_option("--harmonics", o->harmonics,
                                          "mesh harmonics k f_m on the Campbell diagram, 1 to " +
                                              std::to_string(kMostHarmonics) + " (default 3)");
  modes->add_option("--max-speed", o->max_speed,
                    "the Campbell diagram's largest pinion speed with its unit (\"6000 rpm\"); "
                    "default: 1.1 times where the first harmonic meets the highest mode");
  o->keys.add_flags(modes, kModes);
  o->command = modes;
  o->keys.add_set(modes, "KEY=VALUE for any key of the case schema (repeatable), after the flags");
  modes->add_flag("--overwrite", o->overwrite, "replace a non-empty --out folder whole");
  modes->add_flag("--no-plots", o->no_plots, "write the CSV and JSON files only");
  modes->callback([o] { write_modes(*o); });
}

}  // namespace gearimpact::cli
