#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact::cli {

namespace {

struct StiffnessOptions {
  int points = 201;
  std::string method = "gsl";
  bool flipped_moment = false;
  std::string case_file;
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
  if (options.case_file.empty() || command.get_option("--method")->count() > 0) {
    chosen.model = with_method(chosen.model, options.method, "--method");
  }
  if (options.flipped_moment) chosen.model.moment_sign = AxialMomentSign::flipped;
  validate(chosen.pair);
  return chosen;
}

void print_stiffness_table(const StiffnessOptions& options, const CLI::App& command) {
  if (options.points < 2) throw InputError("--points", std::to_string(options.points), ">= 2");
  const auto [pair, model] = pair_and_model(options, command);
  std::fputs(stiffness_csv(pair, model, contact_positions(pair, options.points)).c_str(), stdout);
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
  command->add_option("--case-file", options.case_file,
                      "take the gear pair and the stiffness model from a case file (default: "
                      "the paper's pair)");
}

}  // namespace

void register_stiffness_commands(CLI::App& app) {
  auto options = std::make_shared<StiffnessOptions>();
  CLI::App* stiffness = app.add_subcommand(
      "stiffness", "CSV of Kb, Ka of both gears, Kh and Ke (N/m) over the contact segment");
  add_model_options(stiffness, *options);
  stiffness->callback([options, stiffness] { print_stiffness_table(*options, *stiffness); });

  auto ratio_options = std::make_shared<StiffnessOptions>();
  ratio_options->points = 121;
  CLI::App* ratios = app.add_subcommand(
      "energy-ratios", "CSV of the elastic energy ratios of Fig. 8 over one meshing cycle");
  add_model_options(ratios, *ratio_options);
  ratios->callback([ratio_options, ratios] { print_energy_ratios(*ratio_options, *ratios); });
}

}  // namespace gearimpact::cli
