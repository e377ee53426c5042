#include "gearimpact/stiffness/mesh_stiffness.hpp"

#include <cmath>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/stiffness/tau_form.hpp"
#include "gearimpact/stiffness/x_form.hpp"

namespace gearimpact {

InvoluteTooth tooth_of(const GearPair& pair, Gear gear) {
  return {base_radius(pair, gear), half_tooth_angle(pair, gear)};
}

double hertz_stiffness(const GearPair& pair) {
  // (4)
  const double nu = pair.poisson_ratio;
  return pi * pair.youngs_modulus_pa * pair.face_width_m / (4.0 * (1.0 - nu * nu));
}

Compliances tooth_compliance(const InvoluteTooth& tooth, double contact_x_m,
                             double youngs_modulus_pa, double face_width_m,
                             const StiffnessModel& model) {
  if (!std::isfinite(contact_x_m) || contact_x_m <= 0.0) {
    throw InputError("contact position from the base-circle tangent point", contact_x_m,
                     "(0, tip] m: the contact must lie above the base circle");
  }
  return model.route == StiffnessRoute::x_form
             ? x_form_compliances(tooth, contact_x_m, youngs_modulus_pa, face_width_m, model)
             : tau_form_compliances(tooth, contact_x_m, youngs_modulus_pa, face_width_m, model);
}

double MeshStiffness::stiffness(Term term, Gear gear) const {
  if (!info(term).per_tooth) return 1.0 / pair.of(term);
  return 1.0 / (gear == Gear::one ? tooth1 : tooth2).of(term);
}

MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model) {
  validate(model);
  const double lp = line_of_action_length(pair);
  if (!std::isfinite(x1_m) || x1_m <= 0.0 || x1_m >= lp) {
    throw InputError(
        "contact position X1", x1_m,
        "(0, lp) with lp = " + format_number(lp) + " m: between the tangent points C1 and C2");
  }
  const double e = pair.youngs_modulus_pa;
  const double width = pair.face_width_m;
  MeshStiffness k{};
  k.tooth1 = tooth_compliance(tooth_of(pair, Gear::one), x1_m, e, width, model);
  // (25),(26): gear 2 sees the contact at lp - X1 from C2.
  k.tooth2 = tooth_compliance(tooth_of(pair, Gear::two), lp - x1_m, e, width, model);
  for (const TermInfo& t : kTerms) {
    k.pair.of(t.term) = t.per_tooth ? k.tooth1.of(t.term) + k.tooth2.of(t.term) : 0.0;
  }
  k.pair.of(Term::hertz) = 1.0 / hertz_stiffness(pair);
  k.included = included(k.pair, model.terms);
  // (29) 1/Ke = 1/Kh + 1/Kb1 + 1/Ka1 + 1/Kb2 + 1/Ka2 over the terms switched on.
  k.ke = 1.0 / k.included.total_m_per_n();
  return k;
}

}  // namespace gearimpact
