// The tau-form route: the bending and axial compliances of one involute tooth
// as integrals over the involute parameter tau, (20)-(24).
#pragma once

#include <optional>

#include "gearimpact/geometry/tooth_profile.hpp"
#include "gearimpact/stiffness/model.hpp"

namespace gearimpact {

// The integrands without the 1/(E L) factor, at section angle tau for a tooth
// of half angle theta_b loaded at contact angle phi.
// (20),(22),(23): 3 C(tau) (theta_b - tau) cos tau / (2 [sin tau + (theta_b - tau) cos tau]^3).
double bending_integrand(double theta_b, double phi, double tau, AxialMomentSign sign);
// (21),(24): (theta_b - tau) cos tau sin^2 phi / (2 [sin tau + (theta_b - tau) cos tau]).
double axial_integrand(double theta_b, double phi, double tau);

// The same integrands for one contact at many tau: the contact's functions of
// phi computed once, and each tau's sine and cosine once for both integrands
// and the section (what a cracked tooth's integrals evaluate at every point).
// bending_integrand and axial_integrand are these, to the bit.
struct TauFormContact {
  double theta_b;
  double cos_phi;
  double sin_phi;
  // 2 h sin phi / Rb of the flipped moment sign; not added for the physical one.
  std::optional<double> flipped_arm;
};
TauFormContact tau_form_contact(double theta_b, double phi, AxialMomentSign sign);
// sin tau + (theta_b - tau) cos tau: the half thickness of the section at tau
// over Rb, (23),(24).
inline double section_factor(double theta_b, double tau, double sin_tau, double cos_tau) {
  return sin_tau + (theta_b - tau) * cos_tau;
}
double bending_integrand(const TauFormContact& contact, double tau, double sin_tau, double cos_tau);
double axial_integrand(const TauFormContact& contact, double tau, double sin_tau, double cos_tau);

// The per-tooth terms of one tooth loaded a distance contact_x_m from the
// tangent point of its base circle along the line of action (> 0). Terms the
// model switches off are computed all the same (tables report them).
Compliances tau_form_compliances(const InvoluteTooth& tooth, double contact_x_m,
                                 double youngs_modulus_pa, double face_width_m,
                                 const StiffnessModel& model);

}  // namespace gearimpact
