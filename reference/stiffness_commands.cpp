#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"

namespace gearimpact::cli {

namespace {

struct StiffnessOptions {
  int points = 201;
  std::string method = "gsl";
  std::string model;  // empty: the case file's, else yang-lin-1987
  std::string x_values;
  bool flipped_moment = false;
  std::string case_file;
  int samples = 200;
  bool summary = false;
  double helix_angle_deg = 0.0;
};

// The gear pair and the stiffness model: the paper's, or a case file's; the
// command-line options change the model either way.
struct PairAndModel {
  GearPair pair;
  StiffnessModel model;
};

PairAndModel pair_and_model(const StiffnessOptions& options, const CLI::App& command) {
  PairAndModel chosen{paper_gear_pair(), {}};
  if (!options.case_file.empty()) {
    const SimulationCase c = read_case_file(options.case_file);
    chosen = {c.gears, c.model.stiffness};
  }
  const CLI::Option* method = command.get_option_no_throw("--method");
  if (options.case_file.empty() || (method != nullptr && method->count() > 0)) {
    chosen.model = with_method(chosen.model, options.method, "--method");
  }
  if (!options.model.empty()) chosen.model.kind = parse_stiffness_model(options.model, "--model");
  if (options.flipped_moment) chosen.model.moment_sign = AxialMomentSign::flipped;
  validate(chosen.pair);
  validate(chosen.model);
  return chosen;
}

// Prints the warning to stderr when the model's foundation fit is
// extrapolated for this pair, and says whether it is.
bool warn_if_extrapolated(const GearPair& pair, const StiffnessModel& model) {
  if (!provides(model.kind, Term::foundation) || !model.terms.has(Term::foundation)) return false;
  // The fit's inputs h_f and theta_f are the gears' own, the same at every
  // position.
  const bool extrapolated =
      mesh_stiffness(pair, contact_segment(pair).start_m, model).foundation_extrapolated;
  if (extrapolated) {
    std::fprintf(stderr, "gearimpact: warning: %s\n", foundation_extrapolation_warning().c_str());
  }
  return extrapolated;
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

void print_stiffness_table(const StiffnessOptions& options, const CLI::App& command) {
  if (options.points < 2) throw InputError("--points", std::to_string(options.points), ">= 2");
  const auto [pair, model] = pair_and_model(options, command);
  const std::vector<double> x = command.get_option("--x-values")->count() > 0
                                    ? parse_x_values(options.x_values, pair)
                                    : contact_positions(pair, options.points);
  const std::string csv = stiffness_csv(pair, model, x);
  warn_if_extrapolated(pair, model);
  std::fputs(csv.c_str(), stdout);
}

void print_mesh_stiffness(const StiffnessOptions& options, const CLI::App& command) {
  const auto [pair, model] = pair_and_model(options, command);
  const TimeVaryingMeshStiffness tvms =
      time_varying_mesh_stiffness(pair, model, static_cast<std::size_t>(options.samples));
  const bool extrapolated = warn_if_extrapolated(pair, model);
  const std::string text =
      options.summary ? mesh_stiffness_summary_json(tvms, contact_ratio(pair), extrapolated)
                      : mesh_stiffness_csv(tvms);
  std::fputs(text.c_str(), stdout);
}

void print_iso6336(const StiffnessOptions& options, const CLI::App& command) {
  const auto [pair, model] = pair_and_model(options, command);
  constexpr double degree = pi / 180.0;
  const Iso6336Stiffness iso =
      iso6336_method_b(iso6336_pair(pair, options.helix_angle_deg * degree));
  std::fputs(iso6336_json(iso, pair.face_width_m).c_str(), stdout);
}

void add_pair_options(CLI::App* command, StiffnessOptions& options) {
  command->add_option("--case-file", options.case_file,
                      "take the gear pair and the stiffness model from a case file (default: "
                      "the paper's pair)");
}

void add_named_model_option(CLI::App* command, StiffnessOptions& options) {
  command->add_option("--model", options.model,
                      "stiffness model: yang-lin-1987 (the paper's; default without a case "
                      "file), potential-energy, ross-compatible");
}

void print_energy_ratios(const StiffnessOptions& options, const CLI::App& command) {
  const auto [pair, model] = pair_and_model(options, command);
  std::fputs(energy_ratios_csv(energy_ratio_cycle(pair, options.points, model)).c_str(), stdout);
}

void add_model_options(CLI::App* command, StiffnessOptions& options) {
  command->add_option("--points", options.points, "number of contact positions, X_start to X_end")
      ->check(CLI::Range(2, 1000000));
  command
      ->add_option("--method", options.method,
                   "quadrature: gsl (QAG), gsl-cquad, boost-gk, boost-ts, xform (x-form route)")
      ->check(CLI::IsMember({"gsl", "gsl-cquad", "boost-gk", "boost-ts", "xform"}));
  command->add_flag("--flipped-moment", options.flipped_moment,
                    "add the axial-force moment Fa h instead of subtracting it (not physical)");
  add_pair_options(command, options);
}

}  // namespace

void register_stiffness_commands(CLI::App& app) {
  auto options = std::make_shared<StiffnessOptions>();
  CLI::App* stiffness = app.add_subcommand(
      "stiffness",
      "CSV of every term's stiffness (kb, ka, kh, ke, then ks, kf; N/m, inf for a term switched "
      "off or absent) over the contact segment");
  add_model_options(stiffness, *options);
  add_named_model_option(stiffness, *options);
  CLI::Option* x_values =
      stiffness->add_option("--x-values", options->x_values,
                            "comma-separated contact positions X1, m, instead of --points");
  x_values->excludes(stiffness->get_option("--points"));
  stiffness->callback([options, stiffness] { print_stiffness_table(*options, *stiffness); });

  auto ratio_options = std::make_shared<StiffnessOptions>();
  ratio_options->points = 121;
  CLI::App* ratios = app.add_subcommand(
      "energy-ratios", "CSV of the elastic energy ratios of Fig. 8 over one meshing cycle");
  add_model_options(ratios, *ratio_options);
  ratios->callback([ratio_options, ratios] { print_energy_ratios(*ratio_options, *ratios); });

  auto mesh_options = std::make_shared<StiffnessOptions>();
  CLI::App* mesh = app.add_subcommand(
      "mesh-stiffness",
      "CSV of the mesh stiffness over one mesh period (fraction,theta1_rad,pairs,ke_n_m), or "
      "with --summary its min, max and exact time mean as JSON");
  add_pair_options(mesh, *mesh_options);
  add_named_model_option(mesh, *mesh_options);
  mesh->add_option("--method", mesh_options->method,
                   "quadrature: gsl (QAG), gsl-cquad, boost-gk, boost-ts, xform (x-form route)")
      ->check(CLI::IsMember({"gsl", "gsl-cquad", "boost-gk", "boost-ts", "xform"}));
  mesh->add_option("--samples", mesh_options->samples, "samples over the period, 2 to 1000000")
      ->check(CLI::Range(2, 1000000));
  mesh->add_flag("--summary", mesh_options->summary, "print min, max, mean as JSON instead");
  mesh->callback([mesh_options, mesh] { print_mesh_stiffness(*mesh_options, *mesh); });

  auto iso_options = std::make_shared<StiffnessOptions>();
  CLI::App* iso = app.add_subcommand(
      "iso6336", "JSON of the ISO 6336-1 method B stiffnesses c', c_gamma_alpha of the pair");
  add_pair_options(iso, *iso_options);
  iso->add_option("--helix-angle", iso_options->helix_angle_deg,
                  "helix angle, deg, in [0, 45) (default 0: the spur pair)")
      ->check(CLI::Range(0.0, 44.999999));
  iso->callback([iso_options, iso] { print_iso6336(*iso_options, *iso); });
}

}  // namespace gearimpact::cli
