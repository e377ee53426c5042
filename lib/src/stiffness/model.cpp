#include "gearimpact/stiffness/model.hpp"

#include <cmath>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

bool operator==(const StiffnessModel& a, const StiffnessModel& b) {
  return a.route == b.route && a.rule == b.rule && a.moment_sign == b.moment_sign &&
         a.relative_tolerance == b.relative_tolerance && a.terms == b.terms;
}

void validate(const StiffnessModel& model) {
  if (!model.terms.any()) {
    throw InputError("stiffness terms", "none",
                     "at least one of the Hertzian, bending and axial terms of (29)");
  }
  if (!std::isfinite(model.relative_tolerance) || model.relative_tolerance < 1e-14 ||
      model.relative_tolerance > 1e-2) {
    throw InputError("stiffness tolerance", model.relative_tolerance, "[1e-14, 1e-2]");
  }
}

StiffnessModel with_method(StiffnessModel model, std::string_view name, std::string_view field) {
  if (name == "xform") {
    model.route = StiffnessRoute::x_form;
    return model;
  }
  try {
    model.rule = parse_quadrature_rule(name, field);
  } catch (const InputError&) {
    throw InputError(std::string(field), std::string(name),
                     "one of gsl, gsl-cquad, boost-gk, boost-ts, xform");
  }
  model.route = StiffnessRoute::tau_form;
  return model;
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
  return model.route == StiffnessRoute::x_form ? "xform" : to_string(model.rule);
}

}  // namespace gearimpact
