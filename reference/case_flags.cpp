#include "case_flags.hpp"

#include <cmath>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/named_values.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/sweep.hpp"

namespace gearimpact::cli {

namespace {

std::string help_of(const CaseFlag& flag) {
  const Field& field = *find_field(flag.key);
  if (flag.switch_value != nullptr) {
    for (const ChoiceName& choice : field.choices) {
      if (choice.name == flag.switch_value) {
        return field.name() + " = \"" + flag.switch_value + "\": " + std::string(choice.meaning);
      }
    }
  }
  std::string help = field.help + " [" + field.name() + ": " + allowed_text(field);
  if (field.kind == FieldKind::quantity) {
    help += "; a plain number in " + std::string(units_of(field.dimension).front().symbol) +
            " or with a unit: " + allowed_units(field.dimension);
  }
  return help + "]";
}

bool numeric(const Field& field) {
  return field.kind == FieldKind::quantity || field.kind == FieldKind::number ||
         field.kind == FieldKind::integer;
}

}  // namespace

SampleFlags read_sample_flags(const CLI::App& command, const std::string& rate,
                              const std::string& kind) {
  SampleFlags flags;
  if (command.get_option("--sample-rate")->count() > 0) {
    flags.rate_hz = parse_plain_or_quantity(rate, Dimension::frequency, "--sample-rate");
  }
  flags.kind = value_named(kSampleKinds, kind, "--sample");
  if (command.get_option("--sample")->count() > 0 && !flags.rate_hz) {
    throw InputError(std::vector<Problem>{
        refused_problem("--sample", kind, "needs --sample-rate, whose samples it defines",
                        "--sample KIND with --sample-rate FS")});
  }
  return flags;
}

long long max_rows_flag(double max_rows) {
  if (!(max_rows >= 1.0 && max_rows <= 9e18) || max_rows != std::floor(max_rows)) {
    throw InputError("--max-rows", format_number(max_rows), "a whole count in [1, 9e18]");
  }
  return static_cast<long long>(max_rows);
}

void throw_as_sample_rate_flag(const InputError& e, const std::string& typed) {
  std::vector<Problem> problems = e.problems();
  Problem& first = problems.front();
  const std::string lift = "lift the bound";
  if (first.allowed.size() >= lift.size() &&
      first.allowed.compare(first.allowed.size() - lift.size(), lift.size(), lift) == 0) {
    first.allowed += " (--max-rows)";
  }
  first = first.renamed("--sample-rate", typed);
  throw InputError(std::move(problems));
}

std::string command_names(unsigned commands) {
  static constexpr std::pair<CaseCommand, const char*> kNames[] = {
      {kSimulate, "simulate"},
      {kSweepFriction, "sweep-friction"},
      {kSweep, "sweep"},
      {kStiffness, "stiffness"},
      {kEnergyRatios, "energy-ratios"},
      {kMeshStiffness, "mesh-stiffness"},
      {kModes, "modes"}};
  std::string names;
  for (const auto& [bit, name] : kNames) {
    if ((commands & bit) != 0) names += (names.empty() ? "" : ", ") + std::string(name);
  }
  return names;
}

void CaseOptions::add_flags(CLI::App* command, CaseCommand command_bit) {
  for (const CaseFlag& flag : kCaseFlags) {
    if ((flag.commands & command_bit) == 0) continue;
    flags_.push_back(flag);
    if (flag.switch_value != nullptr) {
      options_.push_back(command->add_flag(std::string(flag.flag))->description(help_of(flag)));
    } else {
      options_.push_back(command->add_option(flag.flag, texts_[flag.flag], help_of(flag)));
    }
  }
}

void CaseOptions::add_reading(CLI::App* command) {
  torque_unit_ =
      command->add_option("--torque-unit", torque_unit_text_, "unit of Table 1's torques")
          ->transform([](const std::string& text) {
            return name_of(kTorqueUnits, value_named(kTorqueUnits, text, "--torque-unit"));
          });
  case3_frequency_ = command->add_option(
      "--case3-frequency", case3_frequency_text_,
      "case 3 forcing W of T1 = 200 sin(W t), rad/s or with a unit (1000 the alternative "
      "reading) [as torque1.angular_frequency: " +
          allowed_text(*find_field("torque1.angular_frequency")) + "]");
}

void CaseOptions::add_set(CLI::App* command, const std::string& help, SetNumbers numbers) {
  set_numbers_ = numbers;
  command->add_option("--set", sets_, help);
}

bool CaseOptions::reading_given() const {
  return torque_unit_->count() > 0 || case3_frequency_->count() > 0;
}

const char* CaseOptions::reading_flag() const {
  return torque_unit_->count() > 0 ? "--torque-unit" : "--case3-frequency";
}

const std::string& CaseOptions::reading_text() const {
  return torque_unit_->count() > 0 ? torque_unit_text_ : case3_frequency_text_;
}

SimulationCase CaseOptions::paper(int number) const {
  PaperReading reading;
  if (torque_unit_ != nullptr && torque_unit_->count() > 0) {
    reading.torque_unit = value_named(kTorqueUnits, torque_unit_text_, "--torque-unit");
  }
  if (case3_frequency_ != nullptr && case3_frequency_->count() > 0) {
    reading.case3_angular_frequency_rad_per_s = parse_value(
        *find_field("torque1.angular_frequency"), case3_frequency_text_, "--case3-frequency");
  }
  return paper_case(number, reading);
}

void CaseOptions::apply(SimulationCase& c) {
  given_.clear();
  const SimulationCase before = c;
  for (std::size_t i = 0; i < flags_.size(); ++i) {
    if (options_[i]->count() == 0) continue;
    const CaseFlag& flag = flags_[i];
    set(c, flag.key, flag.switch_value != nullptr ? flag.switch_value : texts_.at(flag.flag),
        flag.flag, false);
  }
  for (const std::string& assignment : sets_) {
    const std::size_t equals = assignment.find('=');
    if (equals == std::string::npos) {
      throw InputError("--set", assignment, "section.key=value, e.g. integrator.end_time=20ms");
    }
    const std::string key = assignment.substr(0, equals);
    if (find_field(key) == nullptr) {
      const std::optional<std::string> nearest = nearest_key(key);
      throw InputError(
          "--set", assignment,
          "section.key=value with a key of the case schema (`gearimpact schema` "
          "lists them)",
          nearest ? "did you mean --set " + *nearest + "=" + assignment.substr(equals + 1) + "?"
                  : std::string());
    }
    set(c, key, assignment.substr(equals + 1), "--set " + key,
        set_numbers_ == SetNumbers::as_swept_value);
  }
  require_chosen_keys(before, c);
}

void CaseOptions::require_chosen_keys(const SimulationCase& before, const SimulationCase& c) const {
  for (const auto& [key, given] : given_) {
    const Field& selector = *find_field(key);
    if (selector.kind != FieldKind::choice || selector.get(before) == selector.get(c)) continue;
    std::string missing;
    std::string syntax;
    for (const Field& field : case_schema()) {
      if (field.section != selector.section || !field.only_when ||
          field.only_when->key != selector.key || !field.required || !applies(field, c) ||
          given_.count(field.name()) > 0) {
        continue;
      }
      missing += (missing.empty() ? "" : ", ") + field.name();
      syntax += " --set '" + field.name() + "=...'";
    }
    if (missing.empty()) continue;
    throw InputError(given.option, given.text,
                     "a choice given with the keys it needs: " + missing +
                         " (the case's values for its former choice do not carry over); give "
                         "them as" +
                         syntax);
  }
}

void CaseOptions::set(SimulationCase& c, const std::string& key, const std::string& text,
                      const std::string& option, bool swept_value) {
  const auto [previous, fresh] = given_.emplace(key, Given{option, text});
  if (!fresh) {
    throw InputError(
        option, text,
        "one option per key: " + key + " is already set by " + previous->second.option);
  }
  std::string value = text;
  for (const OldSpelling& old : kOldSpellings) {
    if (key == old.key && text == old.old_text) {
      std::cerr << "gearimpact: note: " << option << " " << old.old_text
                << " is the old spelling of \"" << old.text
                << "\", the name case files use; it still works\n";
      value = old.text;
    }
  }
  const Field& field = *find_field(key);
  if (const auto warning = plain_speed_warning(field, value, option)) {
    std::cerr << "gearimpact: warning: " << *warning << "\n";
  }
  if (swept_value && numeric(field)) {
    const SimulationCase before = c;
    apply_sweep_value(c, before, key, parse_value(sweep_field(key, option), value, option));
  } else {
    set_field(c, key, value, option);
  }
}

}  // namespace gearimpact::cli
