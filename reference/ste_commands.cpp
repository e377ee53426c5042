// `gearimpact ste CASE --torque T --out DIR`: the loaded static transmission
// error of a case's pair with its [modifications], beside the same pair
// unmodified (docs/faults.md, "Static transmission error").
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/stiffness/helical_faults.hpp"
#include "gearimpact/stiffness/helical_ste.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"
#include "gnuplot.hpp"
#include "program.hpp"

namespace gearimpact::cli {

DistinctTeeth faulted_teeth(const SimulationCase& c) {
  std::vector<int> classes;
  return {tooth_classes(c.faults, Gear::one, c.gears.teeth1, classes).size() > 1,
          tooth_classes(c.faults, Gear::two, c.gears.teeth2, classes).size() > 1};
}

namespace {

// A static deflection of half a base pitch, about a tooth's thickness, has
// passed the teeth through each other: no STE describes it.
void refuse_overlap(const SimulationCase& c, const StaticTransmissionError& ste,
                    double torque1_n_m) {
  const double half_pitch = 0.5 * base_pitch(c.gears);
  double largest = 0.0;
  for (const auto& point : ste.points) {
    if (point.carried) largest = std::max(largest, point.ste_m);
  }
  if (!(largest > half_pitch)) return;
  throw InputError("torque", format_number(torque1_n_m) + " N*m",
                   "a torque whose static deflection stays below half a base pitch (" +
                       format_number(half_pitch) + " m; this one reaches " +
                       format_number(largest) + " m)");
}

}  // namespace

SteTexts ste_texts(const SimulationCase& c, double torque1_n_m, int points_per_mesh_period) {
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = points_per_mesh_period;
  options.faulted = faulted_teeth(c);
  // Every refusal before the tables' quadrature. These are the spur pair's texts (its pairs'
  // shares and tables); a helical pair's STE is helical_static_transmission_error's.
  if (c.gears.helix_angle_rad != 0.0) {
    throw_helical_not_taken(c.gears.helix_angle_rad, "the spur STE's tables (ste_texts)");
  }
  validate_static_transmission_error(c.gears, c.modifications, torque1_n_m, options);
  check_tooth_faults(c.gears, c.model.stiffness, c.faults);
  const auto healthy = std::make_shared<const StiffnessTable>(c.gears, c.model.stiffness);
  // Each pair reads its own teeth's table; without faults every pair reads the healthy one.
  const MeshTables tables(c.gears, c.model.stiffness, c.faults, healthy);
  SteTexts texts;
  texts.modified =
      static_transmission_error(c.gears, c.modifications, torque1_n_m, tables, options);
  refuse_overlap(c, texts.modified, torque1_n_m);
  // The healthy pair without modifications over the same angles, so that the two curves share
  // one axis.
  StaticTransmissionErrorOptions same = options;
  same.mesh_periods = texts.modified.mesh_periods;
  texts.unmodified =
      static_transmission_error(c.gears, Modifications{}, torque1_n_m, *healthy, same);
  const StaticTransmissionError& unmodified = texts.unmodified;
  texts.csv = ste_csv(texts.modified);
  texts.unmodified_csv = ste_csv(unmodified);
  texts.pairs_csv = ste_pairs_csv(texts.modified);
  texts.unmodified_pairs_csv = ste_pairs_csv(unmodified);
  texts.modified_differs = texts.csv != texts.unmodified_csv;
  texts.quasi_static_force_ratio =
      quasi_static_peak_force_ratio(c.gears, c.modifications, torque1_n_m, tables);
  texts.unmodified_quasi_static_force_ratio = quasi_static_peak_force_ratio(
      c.gears, Modifications{}, torque1_n_m, MeshTables(c.gears, c.model.stiffness, {}, healthy));
  texts.summary_json = ste_summary_json(texts.modified, unmodified, texts.quasi_static_force_ratio,
                                        texts.unmodified_quasi_static_force_ratio);
  return texts;
}

void check_helical_ste(const SimulationCase& c, double torque1_n_m, int points_per_mesh_period) {
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = points_per_mesh_period;
  if (!c.faults.empty()) {
    // A faulted pair reads the run's tables (route B): no gap varies along its lines.
    if (!is_unmodified(c.modifications)) {
      throw InputError("[[faults]]", std::to_string(c.faults.size()) + " faults",
                       "none with modifications on a helical pair: a faulted helical pair's STE "
                       "is the face integral of its tables (docs/helical.md, Faults), which "
                       "takes no gap; remove the modification keys or the [[faults]]");
    }
    check_tooth_faults(swept_transverse_pair(c.gears), c.model.stiffness, c.faults);
    options.mesh_periods = true_period_mesh_periods(c.gears, faulted_teeth(c));
  }
  validate_helical_static_transmission_error(c.gears, c.modifications, torque1_n_m,
                                             c.model.stiffness.face_slices, options);
}

HelicalSteFiles helical_ste_of(const SimulationCase& c, double torque1_n_m,
                               int points_per_mesh_period) {
  check_helical_ste(c, torque1_n_m, points_per_mesh_period);
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = points_per_mesh_period;
  HelicalSteFiles files;
  if (c.faults.empty()) {
    const FaceStiffness face(c.gears, c.model.stiffness, c.model.stiffness.helical_hertz);
    const int slices = c.model.stiffness.face_slices;
    files.modified = helical_static_transmission_error(c.gears, c.modifications, torque1_n_m, face,
                                                       slices, options);
    StaticTransmissionErrorOptions same = options;
    same.mesh_periods = files.modified.mesh_periods;
    files.unmodified = helical_static_transmission_error(c.gears, Modifications{}, torque1_n_m,
                                                         face, slices, same);
  } else {
    // The faulted pair by the tables a run reads, beside the healthy pair by the same route
    // over the same angles.
    const MeshTables faulted = helical_mesh_tables(c.gears, c.model.stiffness, c.faults);
    const MeshTables healthy(
        swept_transverse_pair(c.gears), c.model.stiffness, {},
        std::shared_ptr<const StiffnessTable>(&faulted.healthy(), [](const StiffnessTable*) {}));
    files.modified = helical_static_transmission_error(c.gears, torque1_n_m, c.model.stiffness,
                                                       faulted, options);
    StaticTransmissionErrorOptions same = options;
    same.mesh_periods = files.modified.mesh_periods;
    files.unmodified =
        helical_static_transmission_error(c.gears, torque1_n_m, c.model.stiffness, healthy, same);
  }
  // A static deflection of half a transverse base pitch has passed the teeth through each other.
  const double half_pitch = 0.5 * helical_geometry(c.gears).transverse_base_pitch_m;
  for (const HelicalStaticTransmissionError* ste : {&files.modified, &files.unmodified}) {
    double largest = 0.0;
    for (const HelicalStePoint& p : ste->points) largest = std::max(largest, p.ste_m);
    if (largest > half_pitch) {
      throw InputError("torque", format_number(torque1_n_m) + " N*m",
                       "a torque whose static deflection stays below half a transverse base "
                       "pitch (" +
                           format_number(half_pitch) + " m; this one reaches " +
                           format_number(largest) + " m)");
    }
  }
  files.summary_json = helical_ste_summary_json(files.modified, files.unmodified);
  return files;
}

HelicalSteFiles write_helical_ste_files(const SimulationCase& c, double torque1_n_m,
                                        int points_per_mesh_period,
                                        const std::filesystem::path& dir, bool plots,
                                        const std::string& summary_name) {
  HelicalSteFiles files = helical_ste_of(c, torque1_n_m, points_per_mesh_period);
  const int slices = c.model.stiffness.face_slices;
  write_file_atomically((dir / "ste.csv").string(), helical_ste_csv(files.modified));
  write_file_atomically((dir / "ste_unmodified.csv").string(), helical_ste_csv(files.unmodified));
  write_file_atomically((dir / "ste_face_load.csv").string(),
                        helical_face_load_csv(files.modified, files.unmodified));
  write_file_atomically((dir / summary_name).string(), files.summary_json);
  if (!plots) return files;
  // A faulted pair's curves: the faulted teeth against the healthy ones.
  const bool faulted = !c.faults.empty();
  const std::string own = faulted ? "faulted" : "with the modifications";
  const std::string reference = faulted ? "healthy" : "unmodified";
  const double period_deg = files.modified.period_rad * 180.0 / pi;
  const std::string load = " (" + literal_key(c.name) + ", T_1 = " + format_number(torque1_n_m) +
                           " N m, " + std::to_string(slices) + " slices)";
  Figure f;
  f.name = "ste";
  f.title = "Loaded static transmission error of the helical pair" + load;
  f.x_label = "pinion angle {/Symbol q}_1, deg";
  f.y_label = "transmission error on the transverse line of action, {/Symbol m}m";
  f.setup = {"set key outside right top vertical",
             "set xrange [0:" + format_data_number(period_deg) + "]"};
  f.series = {
      "'ste_unmodified.csv' using 2:($3 * 1e6) with lines lw 2 lc rgb 'gray50' title 'STE " +
          reference + "'",
      std::string("'ste.csv' using 2:($3 * 1e6) with lines lw 2 lc rgb '#1f77b4' title '") +
          (faulted ? "STE faulted" : "STE") + "'",
      "'ste.csv' using 2:($4 * 1e6) with lines lw 1 dt 2 lc rgb '#d62728' title 'KTE "
      "(min gap)'"};
  render(dir, f);
  Figure w;
  w.name = "ste_face_load";
  w.title = "Mean load across the face over F_{bt} / b" + load;
  w.x_label = "y across the face, mm";
  w.y_label = "w / (F_{bt} / b)";
  w.setup = {"set key outside right top vertical",
             "set xrange [0:" + format_data_number(c.gears.face_width_m * 1e3) + "]",
             "set yrange [0:*]"};
  w.series = {
      "'ste_face_load.csv' using ($1 * 1e3):5 with linespoints lw 2 lc rgb 'gray50' title '" +
          reference + "'",
      "'ste_face_load.csv' using ($1 * 1e3):4 with linespoints lw 2 lc rgb '#1f77b4' title '" +
          own + "'"};
  render(dir, w);
  return files;
}

namespace {

struct SteOptions {
  std::string case_file;
  std::string torque;
  int points = 200;
  std::string out;
  bool overwrite = false;
  bool no_plots = false;
};

// What the case's curve is, and the reference curve beside it: "modified", "faulted" or
// "faulted, modified" against "unmodified" or "healthy, unmodified".
struct CurveNames {
  std::string own;
  std::string reference;
};
CurveNames curve_names(const SimulationCase& c) {
  const bool modified = !is_unmodified(c.modifications);
  if (c.faults.empty()) return {"modified", "unmodified"};
  return {modified ? "faulted, modified" : "faulted", "healthy, unmodified"};
}

// STE of both pairs over the case's true period, and its KTE; where no pair carries the load
// (missing teeth) ste.csv leaves ste_m empty, and NaN breaks the curve there (gnuplot skips a
// row whose $3 is empty and joins its neighbours; strcol reads the row).
constexpr const char* kCarriedSteMicrons = "(strcol(3) eq \"\" ? NaN : real(strcol(3)) * 1e6)";

}  // namespace

Figure ste_figure(const SimulationCase& c, const SteTexts& texts) {
  const double period_deg = texts.modified.period_rad * 180.0 / pi;
  Figure f;
  f.name = "ste";
  f.title = "Loaded static transmission error, T_1 = " + format_number(texts.modified.torque1_n_m) +
            " N m (" + literal_key(c.name) + ")";
  f.x_label = "pinion angle {/Symbol q}_1, deg";
  f.y_label = "transmission error on the line of action, {/Symbol m}m";
  f.setup = {"set key outside right top vertical",
             "set xrange [0:" + format_data_number(period_deg) + "]"};
  if (!texts.modified_differs) {
    f.title += ", no modifications";
    f.series = {"'ste.csv' using 2:($3 * 1e6) with lines lw 2 lc rgb '#1f77b4' title 'STE'",
                "'ste.csv' using 2:($4 * 1e6) with lines lw 1 dt 2 lc rgb '#d62728' title 'KTE "
                "(min gap)'"};
    return f;
  }
  const CurveNames names = curve_names(c);
  f.series = {"'ste_unmodified.csv' using 2:($3 * 1e6) with lines lw 2 lc rgb 'gray50' title " +
                  gnuplot_string("STE " + names.reference),
              std::string("'ste.csv' using 2:") + kCarriedSteMicrons +
                  " with lines lw 2 lc rgb '#1f77b4' title " + gnuplot_string("STE " + names.own),
              "'ste.csv' using 2:($4 * 1e6) with lines lw 1 dt 2 lc rgb '#d62728' title " +
                  gnuplot_string("KTE " + names.own + " (min gap)")};
  return f;
}

Figure ste_sharing_figure(const SimulationCase& c, const SteTexts& texts) {
  const double period_deg = texts.modified.period_rad * 180.0 / pi;
  Figure f;
  f.name = "ste_load_sharing";
  f.title = "Load share F_k / F of each pair in contact, T_1 = " +
            format_number(texts.modified.torque1_n_m) + " N m (" + literal_key(c.name) + ")";
  f.x_label = "pinion angle {/Symbol q}_1, deg";
  f.y_label = "share of the mesh force";
  f.setup = {"set key outside right top vertical", "set yrange [-0.02:1.05]",
             "set xrange [0:" + format_data_number(period_deg) + "]"};
  // One curve per pair of teeth, from its entry to its exit (ste_pairs.csv holds a data set per
  // pair; column(-2) is the data set's number, so neighbouring pairs differ in colour).
  if (texts.modified_differs) {
    f.series.push_back(
        "'ste_unmodified_pairs.csv' using 4:5 with lines lw 1 dt 2 lc rgb 'gray50' title " +
        gnuplot_string(curve_names(c).reference));
  } else {
    f.title += ", no modifications";
  }
  f.series.push_back(
      "'ste_pairs.csv' using 4:5:(column(-2) % 4 + 1) with lines lw 2 lc variable title "
      "'each pair of teeth'");
  return f;
}

namespace {

// A helical pair (docs/helical.md, "Loaded STE and the load across the face"): its own files
// and figures beside the same pair unmodified, `summary_name` for its summary.
void write_helical_ste(const SteOptions& o, const SimulationCase& c, double torque) {
  try {
    check_helical_ste(c, torque, o.points);
  } catch (const InputError& e) {
    if (e.field() == "points") throw InputError("--points", e.value(), e.allowed());
    if (e.field() == "torque") throw InputError("--torque", o.torque, e.allowed());
    throw;
  }
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  std::string summary;
  try {
    summary = write_helical_ste_files(c, torque, o.points, folder.temporary(), !o.no_plots,
                                      "summary.json")
                  .summary_json;
  } catch (const InputError& e) {
    if (e.field() != "torque") throw;
    throw InputError("--torque", o.torque, e.allowed());
  }
  folder.commit();
  std::fputs(summary.c_str(), stdout);
  std::cerr << "ste: wrote " << (std::filesystem::path(o.out) / "ste.csv").string() << "\n";
}

void write_ste(const SteOptions& o) {
  // Every refusal before any work: the folder, the torque, the points, the case.
  require_output_folder(o.out, o.overwrite, {o.case_file});
  const double torque = parse_quantity(o.torque, Dimension::torque, "--torque");
  if (!(torque > 0.0)) {
    throw InputError("--torque", o.torque,
                     "a pinion torque > 0 (" + allowed_units(Dimension::torque) +
                         "): it loads the drive flanks");
  }
  const SimulationCase c = read_pair_or_run_file(o.case_file).simulation_case;
  if (c.gears.helix_angle_rad != 0.0) {
    write_helical_ste(o, c, torque);
    return;
  }
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = o.points;
  options.faulted = faulted_teeth(c);
  try {
    validate_static_transmission_error(c.gears, c.modifications, torque, options);
  } catch (const InputError& e) {
    throw InputError(e.field() == "points" ? "--points" : "--torque", e.value(), e.allowed());
  }
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  SteTexts texts;
  try {
    texts = ste_texts(c, torque, o.points);
  } catch (const InputError& e) {
    if (e.field() != "torque") throw;
    throw InputError("--torque", o.torque, e.allowed());
  }
  write_file_atomically((dir / "ste.csv").string(), texts.csv);
  write_file_atomically((dir / "ste_unmodified.csv").string(), texts.unmodified_csv);
  write_file_atomically((dir / "ste_pairs.csv").string(), texts.pairs_csv);
  write_file_atomically((dir / "ste_unmodified_pairs.csv").string(), texts.unmodified_pairs_csv);
  write_file_atomically((dir / "summary.json").string(), texts.summary_json);
  if (!o.no_plots) {
    render(dir, ste_figure(c, texts));
    render(dir, ste_sharing_figure(c, texts));
  }
  folder.commit();
  std::fputs(texts.summary_json.c_str(), stdout);
  if (texts.modified.uncarried_points > 0) {
    std::cerr << "ste: warning: at " << texts.modified.uncarried_points << " of "
              << texts.modified.points.size()
              << " angles every pair in the contact segment has a missing tooth: no pair on the "
                 "line of action carries the load, and ste.csv leaves ste_m empty there\n";
  }
  std::cerr << "ste: wrote " << (std::filesystem::path(o.out) / "ste.csv").string() << "\n";
}

}  // namespace

void register_ste_commands(CLI::App& app) {
  auto o = std::make_shared<SteOptions>();
  CLI::App* ste = app.add_subcommand(
      "ste",
      "The loaded static transmission error of a case's pair with its [modifications] over the "
      "true period of its teeth, beside the same pair unmodified: ste.csv, ste_unmodified.csv, "
      "ste_pairs.csv and ste_unmodified_pairs.csv (pair by pair), summary.json, and the figures "
      "ste.png and ste_load_sharing.png");
  ste->add_option("case", o->case_file,
                  "case file: a pair file ([gears], [model], "
                  "[modifications]) or a run file")
      ->required();
  ste->add_option("--torque", o->torque,
                  "the pinion's torque T1 > 0 with its unit (\"100 N*m\"): F = T1 / Rb1 "
                  "on the drive flanks")
      ->required();
  ste->add_option("--points", o->points, "pinion angles per mesh period, 2 to 100000")
      ->check(CLI::Range(2, 100000));
  ste->add_option("--out", o->out,
                  "output folder: new or empty (else --overwrite), in a folder that exists")
      ->required();
  ste->add_flag("--overwrite", o->overwrite, "replace a non-empty --out folder whole");
  ste->add_flag("--no-plots", o->no_plots, "write the CSV and JSON files only");
  ste->callback([o] { write_ste(*o); });
}

}  // namespace gearimpact::cli
