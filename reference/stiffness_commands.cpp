#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "case_flags.hpp"
#include "commands.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/helical_faults.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "gnuplot.hpp"
#include "mesh_stiffness_figure.hpp"
#include "program.hpp"

namespace gearimpact::cli {

namespace {

struct StiffnessOptions {
  int points = 201;
  std::string x_values;
  std::string case_file;
  // --method, --model, --flipped-moment: keys of the case's stiffness model.
  CaseOptions keys;
  int samples = 200;
  bool summary = false;
  double helix_angle_deg = 0.0;
  std::string load;    // iso6336 --load, empty: none
  std::string figure;  // mesh-stiffness --figure DIR, empty: none
  bool overwrite = false;
};

// The gear pair and the stiffness model: the paper's pair with the default model, or a case
// file's; the options that set the model's keys change it either way.
struct PairAndModel {
  GearPair pair;
  StiffnessModel model;
};

PairAndModel pair_and_model(StiffnessOptions& options) {
  SimulationCase c;
  c.gears = paper_gear_pair();
  // The pair and its model are all these commands read: a pair file ([gears], [model]) will do.
  if (!options.case_file.empty()) c = read_pair_or_run_file(options.case_file).simulation_case;
  options.keys.apply(c);
  validate(c.gears);
  validate(c.model.stiffness);
  return {c.gears, c.model.stiffness};
}

// Prints the warning to stderr when the model's foundation fit is
// extrapolated for this pair, naming each gear, parameter, value and range.
void warn_if(const std::vector<FoundationExtrapolation>& extrapolations) {
  if (!extrapolations.empty()) {
    std::fprintf(stderr, "gearimpact: warning: %s\n",
                 foundation_extrapolation_warning(extrapolations).c_str());
  }
}

// --x-values X1,X2,...: metres on the contact segment.
std::vector<double> parse_x_values(const std::string& text, const GearPair& pair) {
  const ContactSegment segment = contact_segment(pair);
  const std::string range = "comma-separated positions X1 in [" + format_number(segment.start_m) +
                            ", " + format_number(segment.end_m) + "] m, the contact segment";
  std::vector<double> values;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      throw InputError("--x-values", item, range);
    }
    if (used != item.size() || !std::isfinite(x) || x < segment.start_m || x > segment.end_m) {
      throw InputError("--x-values", item, range);
    }
    values.push_back(x);
  }
  if (values.empty()) throw InputError("--x-values", text, range);
  return values;
}

void print_stiffness_table(StiffnessOptions& options, const CLI::App& command) {
  if (options.points < 2) throw InputError("--points", std::to_string(options.points), ">= 2");
  const auto [pair, model] = pair_and_model(options);
  const std::vector<double> x = command.get_option("--x-values")->count() > 0
                                    ? parse_x_values(options.x_values, pair)
                                    : contact_positions(pair, options.points);
  const std::string csv = stiffness_csv(pair, model, x);
  warn_if(foundation_extrapolations(pair, model));
  if (!options.case_file.empty() &&
      !read_pair_or_run_file(options.case_file).simulation_case.faults.empty()) {
    std::cerr << "gearimpact: warning: " << options.case_file
              << " has [[faults]]: these are the healthy teeth's terms; mesh-stiffness "
                 "--case-file gives the faulted mesh stiffness over the true period\n";
  }
  std::fputs(csv.c_str(), stdout);
}

// A helical pair: both routes of the slice model over one mesh period.
void print_helical_mesh_stiffness(const StiffnessOptions& options, const GearPair& pair,
                                  const StiffnessModel& model) {
  if (!options.figure.empty()) {
    throw InputError("--figure", options.figure,
                     "absent for a helical pair (gears.helix_angle > 0): its figure is not drawn "
                     "yet; the CSV or --summary goes to standard output");
  }
  if (!options.case_file.empty()) {
    const std::vector<ToothFault> faults =
        read_pair_or_run_file(options.case_file).simulation_case.faults;
    if (!faults.empty()) {
      // The faulted pair over the true period, by the tables a run reads.
      TruePeriodMeshStiffness tvms;
      try {
        tvms = helical_true_period_mesh_stiffness(pair, model, faults,
                                                  static_cast<std::size_t>(options.samples));
      } catch (const InputError& e) {
        // The true period's bound on the samples, under the flag that sets them.
        if (e.field() != "samples") throw;
        throw InputError("--samples", e.value(), e.allowed());
      }
      std::fputs((options.summary ? true_period_mesh_stiffness_summary_json(
                                        tvms, helical_geometry(pair).total_contact_ratio)
                                  : true_period_mesh_stiffness_csv(tvms))
                     .c_str(),
                 stdout);
      return;
    }
  }
  const HelicalMeshStiffnessCurve curve = helical_mesh_stiffness(pair, model, options.samples);
  std::fputs((options.summary ? helical_mesh_stiffness_summary_json(curve)
                              : helical_mesh_stiffness_csv(curve))
                 .c_str(),
             stdout);
}

void print_mesh_stiffness(StiffnessOptions& options) {
  {
    // A helical pair takes the slice model; the spur path below refuses it.
    const auto [pair, model] = pair_and_model(options);
    if (pair.helix_angle_rad != 0.0) {
      print_helical_mesh_stiffness(options, pair, model);
      return;
    }
  }
  const std::string figure_folder = options.figure;
  // Every refusal before any work: the folder, then the case and the samples.
  if (!figure_folder.empty()) {
    require_output_folder(figure_folder, options.overwrite, {options.case_file});
  }
  const auto [pair, model] = pair_and_model(options);
  // A case file's [[faults]]: the mesh repeats only after its true period.
  SimulationCase c;
  c.name = "the paper's pair";
  if (!options.case_file.empty()) c = read_pair_or_run_file(options.case_file).simulation_case;
  MeshStiffnessTexts texts;
  try {
    texts = mesh_stiffness_texts(pair, model, options.samples, c.faults);
  } catch (const InputError& e) {
    // The true period's bound on the samples, under the flag that sets them.
    if (e.field() != "samples") throw;
    throw InputError("--samples", e.value(), e.allowed());
  }
  warn_if(texts.extrapolations);
  if (!figure_folder.empty()) {
    AtomicFolder folder(figure_folder, options.overwrite, {options.case_file});
    const std::filesystem::path dir = folder.temporary();
    write_file_atomically((dir / "mesh_stiffness.csv").string(), texts.csv);
    write_file_atomically((dir / "summary.json").string(), texts.summary_json);
    render(dir, mesh_stiffness_figure(texts.tvms, c.faults, c.name));
    folder.commit();
  }
  std::fputs((options.summary ? texts.summary_json : texts.csv).c_str(), stdout);
}

void print_iso6336(StiffnessOptions& options) {
  const auto [pair, model] = pair_and_model(options);
  std::optional<double> load;
  if (!options.load.empty()) load = specific_load_of(options.load, pair);
  // A helical case's own helix angle unless --helix-angle names one.
  const double helix_deg =
      options.helix_angle_deg == 0.0 ? pair.helix_angle_rad * 180.0 / pi : options.helix_angle_deg;
  std::fputs(iso6336_text(pair, helix_deg, load).c_str(), stdout);
}

void add_pair_options(CLI::App* command, StiffnessOptions& options) {
  command->add_option("--case-file", options.case_file,
                      "take the gear pair and the stiffness model from a case file (default: "
                      "the paper's pair)");
}

void print_energy_ratios(StiffnessOptions& options) {
  const auto [pair, model] = pair_and_model(options);
  std::fputs(energy_ratios_csv(energy_ratio_cycle(pair, options.points, model)).c_str(), stdout);
}

// --points, the stiffness model's flags of kCaseFlags for `command_bit`, --case-file.
void add_model_options(CLI::App* command, StiffnessOptions& options, CaseCommand command_bit) {
  command->add_option("--points", options.points, "number of contact positions, X_start to X_end")
      ->check(CLI::Range(2, kMostSamples));
  options.keys.add_flags(command, command_bit);
  add_pair_options(command, options);
}

}  // namespace

MeshStiffnessTexts mesh_stiffness_texts(const GearPair& pair, const StiffnessModel& model,
                                        int samples, const std::vector<ToothFault>& faults) {
  if (samples < 2 || samples > kMostSamples) {
    throw InputError("samples", std::to_string(samples),
                     "an integer in [2, " + std::to_string(kMostSamples) + "] per mesh period");
  }
  const TruePeriodMeshStiffness tvms =
      true_period_mesh_stiffness(pair, model, faults, static_cast<std::size_t>(samples));
  return {true_period_mesh_stiffness_csv(tvms),
          true_period_mesh_stiffness_summary_json(tvms, contact_ratio(pair)),
          !tvms.foundation_extrapolations.empty(), tvms.foundation_extrapolations, tvms};
}

std::string iso6336_text(const GearPair& pair, double helix_angle_deg,
                         std::optional<double> specific_load_n_per_m) {
  constexpr double degree = pi / 180.0;
  Iso6336Pair iso_pair = iso6336_pair(pair, helix_angle_deg * degree);
  iso_pair.specific_load_n_per_m = specific_load_n_per_m;
  return iso6336_json(iso6336_method_b(iso_pair), pair.face_width_m, specific_load_n_per_m);
}

double specific_load_of(const std::string& text, const GearPair& pair) {
  const std::string allowed = "a load per face width F_t K_A / b > 0 (" +
                              allowed_units(Dimension::stiffness) + ") or the pinion's torque (" +
                              allowed_units(Dimension::torque) + "), not 0";
  try {
    // A torque acts at the pinion's reference circle, K_A = 1.
    const double torque = parse_quantity(text, Dimension::torque, "--load");
    if (torque == 0.0) throw InputError("--load", text, allowed);
    return std::fabs(torque) / pitch_radius(pair, Gear::one) / pair.face_width_m;
  } catch (const InputError&) {
  }
  double load = 0.0;
  try {
    load = parse_quantity(text, Dimension::stiffness, "--load");
  } catch (const InputError&) {
    throw InputError("--load", text, allowed);
  }
  if (!(load > 0.0)) throw InputError("--load", text, allowed);
  return load;
}

void register_stiffness_commands(CLI::App& app) {
  auto options = std::make_shared<StiffnessOptions>();
  CLI::App* stiffness = app.add_subcommand(
      "stiffness",
      "CSV of every term's stiffness (kb, ka, kh, ke, then ks, kf; N/m, inf for a term switched "
      "off or absent) over the contact segment");
  add_model_options(stiffness, *options, kStiffness);
  CLI::Option* x_values =
      stiffness->add_option("--x-values", options->x_values,
                            "comma-separated contact positions X1, m, instead of --points");
  x_values->excludes(stiffness->get_option("--points"));
  stiffness->callback([options, stiffness] { print_stiffness_table(*options, *stiffness); });

  auto ratio_options = std::make_shared<StiffnessOptions>();
  ratio_options->points = 121;
  CLI::App* ratios = app.add_subcommand(
      "energy-ratios", "CSV of the elastic energy ratios of Fig. 8 over one meshing cycle");
  add_model_options(ratios, *ratio_options, kEnergyRatios);
  ratios->callback([ratio_options] { print_energy_ratios(*ratio_options); });

  auto mesh_options = std::make_shared<StiffnessOptions>();
  CLI::App* mesh = app.add_subcommand(
      "mesh-stiffness",
      "CSV of the mesh stiffness over the true period of the teeth (one mesh period when every "
      "tooth is alike; a pinion or wheel revolution or the hunting period with [[faults]]) from "
      "pinion tooth 0 entering against wheel tooth 0: fraction,theta1_rad,pairs,ke_n_m,"
      "healthy_ke_n_m and the teeth and Ke of each pair; with --summary its min, max and exact "
      "time mean as JSON");
  add_pair_options(mesh, *mesh_options);
  mesh_options->keys.add_flags(mesh, kMeshStiffness);
  mesh->add_option("--samples", mesh_options->samples,
                   "samples per mesh period (the true period's N mesh periods get N times as "
                   "many), 2 to " +
                       std::to_string(kMostSamples))
      ->check(CLI::Range(2, kMostSamples));
  mesh->add_flag("--summary", mesh_options->summary,
                 "print min, max, exact mean over the true period as JSON instead");
  CLI::Option* figure = mesh->add_option(
      "--figure", mesh_options->figure,
      "also write DIR/mesh_stiffness.csv, DIR/summary.json and the figure "
      "DIR/mesh_stiffness.png (.svg, .gp): the stiffness against the same pairs all "
      "healthy, the faulted teeth's contact shaded; DIR new or empty");
  mesh->add_flag("--overwrite", mesh_options->overwrite, "replace a non-empty --figure folder")
      ->needs(figure);
  mesh->callback([mesh_options] { print_mesh_stiffness(*mesh_options); });

  auto iso_options = std::make_shared<StiffnessOptions>();
  CLI::App* iso = app.add_subcommand(
      "iso6336", "JSON of the ISO 6336-1 method B stiffnesses c', c_gamma_alpha of the pair");
  add_pair_options(iso, *iso_options);
  iso->add_option("--helix-angle", iso_options->helix_angle_deg,
                  "helix angle, deg, in [0, 45] (default: the case's gears.helix_angle, 0 for a "
                  "spur pair)")
      ->check(CLI::Range(0.0, 45.0));
  iso->add_option("--load", iso_options->load,
                  "F_t K_A / b (\"50 N/mm\") or the pinion's torque (\"150 N*m\", K_A = 1): "
                  "below 100 N/mm c' takes ISO 6336-1's low-load factor (F_t K_A / b / 100)^0.25");
  iso->callback([iso_options] { print_iso6336(*iso_options); });
}

}  // namespace gearimpact::cli
