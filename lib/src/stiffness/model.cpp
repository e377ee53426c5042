#include "gearimpact/stiffness/model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"

namespace gearimpact {

bool operator==(const StiffnessModel& a, const StiffnessModel& b) {
  return a.kind == b.kind && a.route == b.route && a.rule == b.rule &&
         a.moment_sign == b.moment_sign && a.relative_tolerance == b.relative_tolerance &&
         a.terms == b.terms && a.spall_reading == b.spall_reading &&
         a.face_slices == b.face_slices && a.helical_hertz == b.helical_hertz;
}

SpallReading parse_spall_reading(std::string_view name, std::string_view field) {
  return value_named(kSpallReadings, name, field);
}

std::string to_string(SpallReading reading) {
  return name_of(kSpallReadings, reading);
}

StiffnessModelKind parse_stiffness_model(std::string_view name, std::string_view field) {
  return value_named(kStiffnessModels, name, field);
}

std::string to_string(StiffnessModelKind kind) {
  return name_of(kStiffnessModels, kind);
}

AxialMomentSign parse_moment_sign(std::string_view name, std::string_view field) {
  return value_named(kMomentSigns, name, field);
}

std::string to_string(AxialMomentSign sign) {
  return name_of(kMomentSigns, sign);
}

void check_spall_reading(const StiffnessModel& model, std::string_view section) {
  if (model.spall_reading != SpallReading::effective_width ||
      model.kind != StiffnessModelKind::yang_lin_1987) {
    return;
  }
  const std::string prefix = section.empty() ? "" : std::string(section) + ".";
  throw InputError(prefix + "spall_reading", "\"" + to_string(model.spall_reading) + "\"",
                   "\"hertz-only\" with stiffness_model = \"yang-lin-1987\" (\"effective-width\" "
                   "spreads the load by the rack-cut tooth's root thickness and foundation: "
                   "potential-energy or ross-compatible)");
}

SpallReading applied_spall_reading(const StiffnessModel& model) {
  if (model.spall_reading != SpallReading::by_model) return model.spall_reading;
  return model.kind == StiffnessModelKind::yang_lin_1987 ? SpallReading::hertz_only
                                                         : SpallReading::effective_width;
}

bool provides(StiffnessModelKind kind, Term term) {
  if (kind != StiffnessModelKind::yang_lin_1987) return true;
  return term == Term::hertz || term == Term::bending || term == Term::axial;
}

void validate_terms(const StiffnessModel& model, std::string_view section) {
  std::vector<std::string_view> keys;
  for (const TermInfo& t : kTerms) {
    if (!provides(model.kind, t.term)) continue;
    if (model.terms.has(t.term)) return;
    keys.push_back(t.switch_key);
  }
  // "a, b and c"
  const auto listed = [&keys](std::size_t from) {
    std::string text;
    for (std::size_t i = from; i < keys.size(); ++i) {
      if (i > from) text += i + 1 == keys.size() ? " and " : ", ";
      text += std::string(keys[i]);
    }
    return text;
  };
  const std::string prefix = section.empty() ? "" : std::string(section) + ".";
  throw InputError(prefix + std::string(keys.front()), "\"off\"",
                   "\"on\" while " + listed(1) + " are \"off\" (" + prefix + listed(0) +
                       " are all \"off\": at least one term of (29) must stay \"on\")");
}

StiffnessModel with_method(StiffnessModel model, std::string_view name, std::string_view field) {
  std::string names;
  for (const StiffnessMethod& method : kStiffnessMethods) {
    if (method.name == name) {
      model.route = method.route;
      if (method.route == StiffnessRoute::tau_form) model.rule = method.rule;
      return model;
    }
    names += (names.empty() ? "" : ", ") + std::string(method.name);
  }
  throw InputError(std::string(field), std::string(name), "one of " + names);
}

Term term_named(std::string_view id, std::string_view field) {
  std::string ids;
  for (const TermInfo& t : kTerms) {
    if (t.id == id) return t.term;
    ids += (ids.empty() ? "" : ", ") + std::string(t.id);
  }
  throw InputError(std::string(field), std::string(id), "one of " + ids);
}

std::string method_name(const StiffnessModel& model) {
  for (const StiffnessMethod& method : kStiffnessMethods) {
    if (method.route == model.route &&
        (method.route == StiffnessRoute::x_form || method.rule == model.rule)) {
      return std::string(method.name);
    }
  }
  throw std::logic_error("a stiffness method without a name in kStiffnessMethods");
}

}  // namespace gearimpact
