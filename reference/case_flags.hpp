// The command-line flags that set keys of the case schema, shared by every
// command that reads a case and by `schema --flags` (the table in
// docs/case-files.md), and CaseOptions, which reads them (and --set) through
// the schema's rows.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact::cli {

// The most worker threads a command's --threads accepts: more only cost memory
// and, under a cluster's process limit, threads that cannot start.
inline constexpr long long kMostThreads = 1024;

// The commands a flag of kCaseFlags belongs to, one bit each.
enum CaseCommand : unsigned {
  kSimulate = 1u << 0,
  kSweepFriction = 1u << 1,
  kSweep = 1u << 2,
  kStiffness = 1u << 3,
  kEnergyRatios = 1u << 4,
  kMeshStiffness = 1u << 5,
  kModes = 1u << 6,
};

// "simulate, sweep-friction": the commands of a mask, in the order above.
std::string command_names(unsigned commands);

// --sample-rate (absent: none; Hz, a plain number or with a unit) and --sample of a command
// that samples a run: RunControl's sample_rate_hz and sample. --sample without --sample-rate is
// refused by name, as is a value neither takes.
struct SampleFlags {
  std::optional<double> rate_hz;
  SampleKind kind = SampleKind::interval_average;
};
SampleFlags read_sample_flags(const CLI::App& command, const std::string& rate,
                              const std::string& kind);

// --max-rows as a count of rows (RunControl::most_series_rows): a whole count in [1, 9e18],
// else InputError naming the flag.
long long max_rows_flag(double max_rows);

// The library's refusal of sample_rate (e) as the program's: --sample-rate as the user typed
// it (`typed`), the library's bound on the samples named as --max-rows.
[[noreturn]] void throw_as_sample_rate_flag(const InputError& e, const std::string& typed);

// A flag that sets one key of the case. Its value is read and checked by the
// key's schema row (a plain number is SI, "20 ms" carries its unit); the
// default is the case's own. A switch (`switch_value` set) takes no value and
// sets that one.
struct CaseFlag {
  const char* flag;
  const char* key;
  // CaseCommand bits: sweep-friction sets f itself and runs RK4, the stiffness
  // commands read only the stiffness model's keys.
  unsigned commands;
  const char* switch_value = nullptr;
};

inline constexpr unsigned kBothSimulations = kSimulate | kSweepFriction;
inline constexpr CaseFlag kCaseFlags[] = {
    {"--friction", "model.friction_coefficient", kSimulate},
    {"--dt", "integrator.step", kBothSimulations},
    {"--t-end", "integrator.end_time", kBothSimulations},
    {"--integrator", "integrator.kind", kSimulate},
    {"--rtol", "integrator.relative_tolerance", kSimulate},
    {"--every", "integrator.output_every", kSimulate},
    {"--damping-form", "model.damping_form", kBothSimulations},
    {"--damping-stiffness", "model.damping_stiffness", kBothSimulations},
    {"--restitution-coefficient", "model.restitution_coefficient", kBothSimulations},
    {"--restitution-exponent", "model.restitution_exponent", kBothSimulations},
    {"--speed-unit", "model.restitution_speed_unit", kBothSimulations},
    {"--coast-phase", "model.coast_phase", kBothSimulations},
    {"--flipped-moment", "model.moment_sign",
     kBothSimulations | kStiffness | kEnergyRatios | kModes, "flipped"},
    {"--method", "model.stiffness_method", kStiffness | kEnergyRatios | kMeshStiffness | kModes},
    {"--model", "model.stiffness_model", kStiffness | kMeshStiffness | kModes},
    {"--mesh-stiffness", "model.mesh_stiffness", kSweep | kModes},
    {"--damping-update", "model.damping_update", kSweep},
};

// Values the command line used to spell otherwise than case files; they are
// still read, with a notice naming the case-file spelling.
struct OldSpelling {
  const char* key;
  const char* old_text;
  const char* text;
};

inline constexpr OldSpelling kOldSpellings[] = {
    {"model.damping_stiffness", "pair", "current-pair"},
    {"model.damping_stiffness", "pitch-pair", "pitch-pair-at-impact"},
    {"model.coast_phase", "half-pitch", "half-base-pitch"},
    {"model.restitution_speed_unit", "mm/s", "1 mm/s"},
    {"model.restitution_speed_unit", "in/s", "1 in/s"},
    {"model.restitution_speed_unit", "m/s", "1 m/s"},
};

// How --set gives a numeric key its value: as a case file does (set_field),
// or as a swept value (apply_sweep_value: a speed moves the other speed, a
// mean torque the other mean torque).
enum class SetNumbers { as_case_file, as_swept_value };

// The options that set case keys on one command: its flags of kCaseFlags, the
// paper's reading of Table 1 (--torque-unit, --case3-frequency) and --set,
// each read by the key's schema row.
class CaseOptions {
 public:
  // The flags of kCaseFlags whose commands include `command_bit`.
  void add_flags(CLI::App* command, CaseCommand command_bit);
  void add_reading(CLI::App* command);
  void add_set(CLI::App* command, const std::string& help,
               SetNumbers numbers = SetNumbers::as_case_file);

  // The --set texts as given, "section.key=value".
  const std::vector<std::string>& sets() const { return sets_; }

  bool reading_given() const;
  const char* reading_flag() const;
  const std::string& reading_text() const;

  // Table 1's case under the reading of --torque-unit and --case3-frequency,
  // the library's defaults where they are not given.
  SimulationCase paper(int number) const;

  // Sets the keys of the given options on `c`, flags in table order, then
  // --set in command-line order; the keys so set are remembered with the
  // option that set them, to name it in later errors. A key may be set by
  // one option only.
  void apply(SimulationCase& c);

  // Runs `work`; an InputError about a key an option set names that option.
  template <typename Work>
  void naming_options(Work work) const {
    try {
      work();
    } catch (const InputError& e) {
      std::vector<Problem> problems = e.problems();
      bool renamed = false;
      for (Problem& p : problems) {
        const auto found = given_.find(p.field);
        if (found == given_.end()) continue;
        p = p.renamed(found->second.option, found->second.text);
        renamed = true;
      }
      if (!renamed) throw;
      throw InputError(std::move(problems));
    }
  }

 private:
  void set(SimulationCase& c, const std::string& key, const std::string& text,
           const std::string& option, bool swept_value);
  // A choice changed by an option (torque1.kind = "sinusoidal") must come with
  // the required keys of its new choice (torque1.amplitude, ...): the case
  // holds their defaults, not values the user meant. Throws InputError naming
  // the option and the keys otherwise.
  void require_chosen_keys(const SimulationCase& before, const SimulationCase& c) const;

  std::vector<CaseFlag> flags_;
  std::vector<CLI::Option*> options_;
  std::map<std::string, std::string> texts_;
  CLI::Option* torque_unit_ = nullptr;
  std::string torque_unit_text_;
  CLI::Option* case3_frequency_ = nullptr;
  std::string case3_frequency_text_;
  std::vector<std::string> sets_;
  SetNumbers set_numbers_ = SetNumbers::as_case_file;
  // section.key -> the option that set it and its text as typed.
  struct Given {
    std::string option;
    std::string text;
  };
  std::map<std::string, Given> given_;
};

}  // namespace gearimpact::cli
