// One involute tooth standing on its base circle, as the paper models it for
// the potential-energy method (Fig. 2): a cantilever along the tooth centre
// line from the base circle, loaded at the contact point along the line of
// action. Two descriptions of the same tooth live here: the paper's contact-arm
// formulas (10)-(12), and the polar involute r -> half angle, from which the
// x-form route (16)-(19) builds every section on its own.
#pragma once

namespace gearimpact {

struct InvoluteTooth {
  double base_radius_m;
  double half_tooth_angle_rad;  // theta_b of (13)
};

// The load on the tooth at contact angle phi (the angle between O1C1 and the
// tooth centre line, (9)): its offset h from the centre line (10) and its height
// l above the base-circle section (11).
struct ContactArm {
  double offset_h_m;
  double height_l_m;
};

// (10),(11) as printed.
ContactArm contact_arm(const InvoluteTooth& tooth, double phi_rad);

// The same arm from the polar involute: a contact a distance x_m from the
// tangent point along the line of action lies on radius sqrt(Rb^2 + X^2), at
// half angle psi(r) = theta_b - inv(a_r) from the centre line. Also returns
// the contact angle phi = a_r - psi(r) it implies.
struct PolarContact {
  ContactArm arm;
  double phi_rad;
};
PolarContact polar_contact(const InvoluteTooth& tooth, double x_m);

// psi(r) = theta_b - inv(acos(Rb / r)): the half angle of the tooth at radius r.
double flank_half_angle(const InvoluteTooth& tooth, double radius_m);

// Half the chordal thickness of the section that cuts the centre line at a
// height `height_m` above the base-circle section, found by solving
// r cos psi(r) = Rb cos theta_b + height for r (TOMS 748).
double section_half_thickness(const InvoluteTooth& tooth, double height_m);

}  // namespace gearimpact
