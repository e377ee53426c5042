#include "gearimpact/stiffness/x_form.hpp"

#include <cmath>

namespace gearimpact {

// (16),(17),(18),(19): U = Int M^2/(2 E I) dx + Int Fa^2/(2 E A) dx over the
// centre line, x from the base-circle section (0) to the load (l), with the
// moment of (14) M = Fb (l - x) -/+ Fa h.
Compliances x_form_compliances(const InvoluteTooth& tooth, double contact_x_m, double e,
                               double width, const StiffnessModel& model) {
  const PolarContact contact = polar_contact(tooth, contact_x_m);
  const double l = contact.arm.height_l_m;
  const double h = contact.arm.offset_h_m;
  // (6),(7) per unit force.
  const double fb = std::cos(contact.phi_rad);
  const double fa = std::sin(contact.phi_rad);
  const double axial_arm = model.moment_sign == AxialMomentSign::physical ? -fa * h : fa * h;
  // x = l s^2 smooths the square-root behaviour of the sections at the base
  // circle (x ~ (theta_b - tau)^2 there), so that every rule converges fast.
  const auto bending = [&](double s) {
    const double x = l * s * s;
    const double y = section_half_thickness(tooth, x);
    const double moment = fb * (l - x) + axial_arm;
    const double second_moment = 2.0 / 3.0 * width * y * y * y;
    return moment * moment / (e * second_moment) * 2.0 * l * s;
  };
  const auto axial = [&](double s) {
    const double x = l * s * s;
    const double area = 2.0 * width * section_half_thickness(tooth, x);
    return fa * fa / (e * area) * 2.0 * l * s;
  };
  const QuadratureTolerance tolerance{model.relative_tolerance, 0.0};
  Compliances c;
  for (const TermInfo& t : kTerms) {
    switch (t.term) {
      case Term::bending:
        c.of(t.term) = integrate(model.rule, bending, 0.0, 1.0, tolerance).value;
        break;
      case Term::axial:
        c.of(t.term) = integrate(model.rule, axial, 0.0, 1.0, tolerance).value;
        break;
      case Term::hertz:
        break;  // per pair: mesh_stiffness adds it
      case Term::shear:
      case Term::foundation:
        break;  // not in the paper's tooth (the cantilever from the base circle): 0
    }
  }
  return c;
}

}  // namespace gearimpact
