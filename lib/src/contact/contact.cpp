#include "gearimpact/contact/contact.hpp"

#include <cmath>

namespace gearimpact {

double restitution_coefficient(const RestitutionLaw& law, double impact_speed_m_s) {
  // (33)
  const double e =
      1.0 - law.coefficient * std::pow(impact_speed_m_s / law.speed_unit_m_s, law.exponent);
  return e < 0.0 ? 0.0 : (e > 1.0 ? 1.0 : e);
}

double damping_factor_per_stiffness(DampingForm form, double restitution, double impact_speed_m_s) {
  const double e = restitution;
  // (32) in the three forms docs/model.md lists.
  switch (form) {
    case DampingForm::herbert_mcwhannell:
      return 6.0 * (1.0 - e) / (((2.0 * e - 1.0) * (2.0 * e - 1.0) + 3.0) * impact_speed_m_s);
    case DampingForm::hunt_crossley:
      return 3.0 * (1.0 - e) / (2.0 * impact_speed_m_s);
    case DampingForm::lee_wang:
      return 3.0 * (1.0 - e) / (4.0 * impact_speed_m_s);
  }
  return 0.0;
}

}  // namespace gearimpact
