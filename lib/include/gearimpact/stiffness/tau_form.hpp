// The tau-form route: the bending and axial compliances of one involute tooth
// as integrals over the involute parameter tau, (20)-(24).
#pragma once

#include "gearimpact/geometry/tooth_profile.hpp"
#include "gearimpact/stiffness/model.hpp"

namespace gearimpact {

// The integrands without the 1/(E L) factor, at section angle tau for a tooth
// of half angle theta_b loaded at contact angle phi.
// (20),(22),(23): 3 C(tau) (theta_b - tau) cos tau / (2 [sin tau + (theta_b - tau) cos tau]^3).
double bending_integrand(double theta_b, double phi, double tau, AxialMomentSign sign);
// (21),(24): (theta_b - tau) cos tau sin^2 phi / (2 [sin tau + (theta_b - tau) cos tau]).
double axial_integrand(double theta_b, double phi, double tau);

// The per-tooth terms of one tooth loaded a distance contact_x_m from the
// tangent point of its base circle along the line of action (> 0). Terms the
// model switches off are computed all the same (tables report them).
Compliances tau_form_compliances(const InvoluteTooth& tooth, double contact_x_m,
                                 double youngs_modulus_pa, double face_width_m,
                                 const StiffnessModel& model);

}  // namespace gearimpact
