#include "gearimpact/stiffness/model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

bool operator==(const StiffnessModel& a, const StiffnessModel& b) {
  return a.kind == b.kind && a.route == b.route && a.rule == b.rule &&
         a.moment_sign == b.moment_sign && a.relative_tolerance == b.relative_tolerance &&
         a.terms == b.terms;
}

StiffnessModelKind parse_stiffness_model(std::string_view name, std::string_view field) {
  if (name == "yang-lin-1987") return StiffnessModelKind::yang_lin_1987;
  if (name == "potential-energy") return StiffnessModelKind::potential_energy;
  if (name == "ross-compatible") return StiffnessModelKind::ross_compatible;
  throw InputError(std::string(field), std::string(name),
                   "one of yang-lin-1987, potential-energy, ross-compatible");
}

std::string to_string(StiffnessModelKind kind) {
  switch (kind) {
    case StiffnessModelKind::yang_lin_1987:
      return "yang-lin-1987";
    case StiffnessModelKind::potential_energy:
      return "potential-energy";
    case StiffnessModelKind::ross_compatible:
      return "ross-compatible";
  }
  throw std::logic_error("unknown StiffnessModelKind");
}

bool provides(StiffnessModelKind kind, Term term) {
  if (kind != StiffnessModelKind::yang_lin_1987) return true;
  return term == Term::hertz || term == Term::bending || term == Term::axial;
}

void validate(const StiffnessModel& model) {
  bool any = false;
  for (const TermInfo& t : kTerms)
    any = any || (provides(model.kind, t.term) && model.terms.has(t.term));
  if (!any) {
    throw InputError("stiffness terms", "none",
                     model.kind == StiffnessModelKind::yang_lin_1987
                         ? "at least one of the Hertzian, bending and axial terms of (29)"
                         : "at least one of the hertz, bending, shear, axial, foundation terms");
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
