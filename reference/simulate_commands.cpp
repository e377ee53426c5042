#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gearimpact/batch/sweep_friction.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/simulation_case.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/paper/table1.hpp"

namespace gearimpact::cli {

namespace {

// The readings MODEL.md leaves open, as named options; defaults are MODEL.md's.
struct ReadingOptions {
  std::string torque_unit = "kgf-mm";
  double case3_frequency_rad_s = 10000.0;
  std::string damping_form = "herbert-mcwhannell";
  std::string damping_stiffness = "pair";
  double restitution_coefficient = 0.022;
  double restitution_exponent = 0.375;
  std::string speed_unit = "mm/s";
  std::string coast_phase = "half-pitch";
  bool flipped_moment = false;
};

struct SimulateOptions {
  int case_number = 1;
  std::string case_file;
  double friction = 0.04;
  double step_s = 1.0e-7;
  double end_time_s = 0.0;  // 0: the case's own
  std::string integrator = "rk4";
  double relative_tolerance = 1e-10;
  std::string out;
  int every = 1;
  ReadingOptions reading;
};

struct SweepOptions {
  double from = 0.01;
  double to = 0.09;
  double step = 0.01;
  double step_s = 1.0e-7;
  double end_time_s = 0.0;  // 0: each case's own
  unsigned threads = 0;
  ReadingOptions reading;
};

SimulationCase paper_case_with(int number, const ReadingOptions& r) {
  const std::map<std::string, DampingForm> forms{
      {"herbert-mcwhannell", DampingForm::herbert_mcwhannell},
      {"hunt-crossley", DampingForm::hunt_crossley},
      {"lee-wang", DampingForm::lee_wang}};
  const std::map<std::string, DampingStiffness> stiffnesses{
      {"pair", DampingStiffness::current_pair},
      {"pitch-pair", DampingStiffness::pitch_pair_at_impact},
      {"hertz", DampingStiffness::hertz}};
  const std::map<std::string, double> speed_units{{"mm/s", 1.0e-3}, {"in/s", 0.0254}, {"m/s", 1.0}};
  PaperReading reading;
  reading.torque_unit = r.torque_unit == "n-mm" ? TorqueUnit::n_mm : TorqueUnit::kgf_mm;
  reading.case3_angular_frequency_rad_s = r.case3_frequency_rad_s;
  reading.damping_form = forms.at(r.damping_form);
  reading.damping_stiffness = stiffnesses.at(r.damping_stiffness);
  reading.restitution.coefficient = r.restitution_coefficient;
  reading.restitution.exponent = r.restitution_exponent;
  reading.restitution.speed_unit_m_s = speed_units.at(r.speed_unit);
  reading.coast_phase =
      r.coast_phase == "in-phase" ? CoastPhase::in_phase : CoastPhase::half_base_pitch;
  reading.moment_sign = r.flipped_moment ? AxialMomentSign::flipped : AxialMomentSign::physical;
  return paper_case(number, reading);
}

void add_reading_options(CLI::App* command, ReadingOptions& r) {
  command->add_option("--torque-unit", r.torque_unit, "unit of Table 1's torques")
      ->check(CLI::IsMember({"kgf-mm", "n-mm"}))
      ->capture_default_str();
  command
      ->add_option("--case3-frequency", r.case3_frequency_rad_s,
                   "case 3 forcing W of T1 = 200 sin(W t), rad/s (1000 the alternative reading)")
      ->capture_default_str();
  command->add_option("--damping-form", r.damping_form, "form of (32)")
      ->check(CLI::IsMember({"herbert-mcwhannell", "hunt-crossley", "lee-wang"}))
      ->capture_default_str();
  command
      ->add_option("--damping-stiffness", r.damping_stiffness,
                   "K in (32): pair (each pair's Ke), pitch-pair (frozen at impact), hertz (Kh)")
      ->check(CLI::IsMember({"pair", "pitch-pair", "hertz"}))
      ->capture_default_str();
  command->add_option("--restitution-coefficient", r.restitution_coefficient, "c of (33)")
      ->capture_default_str();
  command->add_option("--restitution-exponent", r.restitution_exponent, "p of (33)")
      ->capture_default_str();
  command->add_option("--speed-unit", r.speed_unit, "unit of Vi in (33)")
      ->check(CLI::IsMember({"mm/s", "in/s", "m/s"}))
      ->capture_default_str();
  command
      ->add_option("--coast-phase", r.coast_phase,
                   "coast-line contacts: half-pitch (geometric) or in-phase (literal (9))")
      ->check(CLI::IsMember({"half-pitch", "in-phase"}))
      ->capture_default_str();
  command->add_flag("--flipped-moment", r.flipped_moment,
                    "add the axial-force moment Fa h in the bending stiffness (not physical)");
}

// A case file carries every setting; a command-line option overrides the
// file only when given explicitly.
SimulationCase case_to_run(const SimulateOptions& o, const CLI::App& command) {
  const auto given = [&](const char* name) { return command.get_option(name)->count() > 0; };
  if (o.case_file.empty()) {
    if (!given("--case")) {
      throw InputError("--case", "none", "1, 2 or 3 (Table 1), or --case-file FILE");
    }
    SimulationCase c = paper_case_with(o.case_number, o.reading);
    c.model.friction_coefficient = o.friction;
    c.integrator.step_s = o.step_s;
    if (o.end_time_s != 0.0) c.integrator.end_time_s = o.end_time_s;
    c.integrator.kind = o.integrator == "adaptive" ? IntegratorKind::adaptive : IntegratorKind::rk4;
    c.integrator.adaptive_relative_tolerance = o.relative_tolerance;
    c.integrator.output_every = o.every;
    return c;
  }
  SimulationCase c = read_case_file(o.case_file);
  if (given("--friction")) c.model.friction_coefficient = o.friction;
  if (given("--dt")) c.integrator.step_s = o.step_s;
  if (given("--t-end")) c.integrator.end_time_s = o.end_time_s;
  if (given("--integrator")) {
    c.integrator.kind = o.integrator == "adaptive" ? IntegratorKind::adaptive : IntegratorKind::rk4;
  }
  if (given("--rtol")) c.integrator.adaptive_relative_tolerance = o.relative_tolerance;
  if (given("--every")) c.integrator.output_every = o.every;
  return c;
}

void run_simulate(const SimulateOptions& o, const CLI::App& command) {
  const SimulationCase c = case_to_run(o, command);
  RunControl control;
  control.keep_series = !o.out.empty();
  const SimulationResult result = simulate(c, control);
  if (!o.out.empty()) write_file_atomically(o.out, series_csv(result.series));
  std::fputs(summary_json(result.summary).c_str(), stdout);
}

void run_sweep(const SweepOptions& o) {
  std::vector<SimulationCase> cases;
  for (int n = 1; n <= 3; ++n) {
    cases.push_back(paper_case_with(n, o.reading));
    cases.back().integrator.step_s = o.step_s;
    if (o.end_time_s != 0.0) cases.back().integrator.end_time_s = o.end_time_s;
  }
  std::fputs(friction_sweep_csv(sweep_friction(cases, o.from, o.to, o.step, o.threads)).c_str(),
             stdout);
}

}  // namespace

void register_simulate_commands(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* simulate = app.add_subcommand(
      "simulate", "run one of Table 1's cases; JSON summary on stdout, time series with --out");
  CLI::Option* paper = simulate->add_option("--case", options->case_number, "Table 1 case")
                           ->check(CLI::IsMember({1, 2, 3}));
  simulate
      ->add_option("--case-file", options->case_file,
                   "a case file (TOML, see docs/case-files.md); other options override it")
      ->excludes(paper);
  simulate->add_option("--friction", options->friction, "friction coefficient f of (35)")
      ->capture_default_str();
  simulate
      ->add_option("--dt", options->step_s, "RK4 step, s (adaptive: first step and output grid)")
      ->capture_default_str();
  simulate->add_option("--t-end", options->end_time_s,
                       "end time, s (default: 0.03 for cases 1 and 2, 0.04 for case 3)");
  simulate->add_option("--integrator", options->integrator, "rk4 (fixed step) or adaptive (dopri5)")
      ->check(CLI::IsMember({"rk4", "adaptive"}))
      ->capture_default_str();
  simulate->add_option("--rtol", options->relative_tolerance, "adaptive relative tolerance")
      ->capture_default_str();
  simulate->add_option("--out", options->out, "time series CSV file (written atomically)");
  simulate->add_option("--every", options->every, "keep every n-th row of the time series")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  add_reading_options(simulate, options->reading);
  simulate->callback([options, simulate] { run_simulate(*options, *simulate); });

  auto sweep_options = std::make_shared<SweepOptions>();
  CLI::App* sweep = app.add_subcommand(
      "sweep-friction", "Fig. 7: CSV of friction loss / damping loss of cases 1-3 against f");
  sweep->add_option("--from", sweep_options->from, "first f")->capture_default_str();
  sweep->add_option("--to", sweep_options->to, "last f")->capture_default_str();
  sweep->add_option("--step", sweep_options->step, "increment of f")->capture_default_str();
  sweep->add_option("--dt", sweep_options->step_s, "RK4 step, s")->capture_default_str();
  sweep->add_option("--t-end", sweep_options->end_time_s,
                    "end time, s (default: 0.03 for cases 1 and 2, 0.04 for case 3)");
  sweep->add_option("--threads", sweep_options->threads, "threads (0: all cores)")
      ->capture_default_str();
  add_reading_options(sweep, sweep_options->reading);
  sweep->callback([sweep_options] { run_sweep(*sweep_options); });
}

}  // namespace gearimpact::cli
