#include "gearimpact/stiffness/tau_form.hpp"

#include <cmath>
#include <optional>

namespace gearimpact {

namespace {

// 2 h sin phi / Rb with h from (11).
std::optional<double> flipped_arm(double theta_b, double phi, double cos_phi, double sin_phi,
                                  AxialMomentSign sign) {
  if (sign != AxialMomentSign::flipped) return std::nullopt;
  return 2.0 * sin_phi * ((theta_b + phi) * cos_phi - sin_phi);
}

}  // namespace

TauFormContact tau_form_contact(double theta_b, double phi, AxialMomentSign sign) {
  const double cos_phi = std::cos(phi);
  const double sin_phi = std::sin(phi);
  return {theta_b, cos_phi, sin_phi, flipped_arm(theta_b, phi, cos_phi, sin_phi, sign)};
}

double bending_integrand(const TauFormContact& contact, double tau, double sin_tau,
                         double cos_tau) {
  const double theta_b = contact.theta_b;
  // (22) over Rb: [(l - x) cos phi -/+ h sin phi] / Rb with l, h from (10),(11)
  // and x(tau) from the involute. The printed sign simplifies to
  // 1 + cos phi [(theta_b - tau) sin tau - cos tau]; the flipped one keeps
  // 2 h sin phi / Rb more.
  double arm = 1.0 + contact.cos_phi * ((theta_b - tau) * sin_tau - cos_tau);
  if (contact.flipped_arm) arm += *contact.flipped_arm;
  const double s = section_factor(theta_b, tau, sin_tau, cos_tau);
  // (20) with (23)
  return 3.0 * arm * arm * (theta_b - tau) * cos_tau / (2.0 * s * s * s);
}

double axial_integrand(const TauFormContact& contact, double tau, double sin_tau, double cos_tau) {
  const double theta_b = contact.theta_b;
  // (21) with (24)
  return (theta_b - tau) * cos_tau * contact.sin_phi * contact.sin_phi /
         (2.0 * section_factor(theta_b, tau, sin_tau, cos_tau));
}

// One tau of the healthy tooth's integrals: only the functions of phi each
// integrand uses.
double bending_integrand(double theta_b, double phi, double tau, AxialMomentSign sign) {
  const double cos_phi = std::cos(phi);
  const double sin_phi = sign == AxialMomentSign::flipped ? std::sin(phi) : 0.0;
  return bending_integrand(
      {theta_b, cos_phi, sin_phi, flipped_arm(theta_b, phi, cos_phi, sin_phi, sign)}, tau,
      std::sin(tau), std::cos(tau));
}

double axial_integrand(double theta_b, double phi, double tau) {
  return axial_integrand({theta_b, 0.0, std::sin(phi), std::nullopt}, tau, std::sin(tau),
                         std::cos(tau));
}

Compliances tau_form_compliances(const InvoluteTooth& tooth, double contact_x_m,
                                 double youngs_modulus_pa, double face_width_m,
                                 const StiffnessModel& model) {
  const double theta_b = tooth.half_tooth_angle_rad;
  // (12) phi = X / Rb - theta_b; the section angle tau runs from the load
  // (tau = -phi) down to the base circle (tau = theta_b).
  const double phi = contact_x_m / tooth.base_radius_m - theta_b;
  const double scale = 1.0 / (youngs_modulus_pa * face_width_m);
  const QuadratureTolerance tolerance{model.relative_tolerance, 0.0};
  Compliances c;
  for (const TermInfo& t : kTerms) {
    switch (t.term) {
      case Term::bending:
        c.of(t.term) = scale * integrate(
                                   model.rule,
                                   [&](double tau) {
                                     return bending_integrand(theta_b, phi, tau, model.moment_sign);
                                   },
                                   -phi, theta_b, tolerance)
                                   .value;
        break;
      case Term::axial:
        c.of(t.term) =
            scale * integrate(
                        model.rule, [&](double tau) { return axial_integrand(theta_b, phi, tau); },
                        -phi, theta_b, tolerance)
                        .value;
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
