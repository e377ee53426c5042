// Helical gears: the transverse section of a helical pair as a spur pair, and
// the helical pair's geometry (docs/helical.md, section Geometry). SI units,
// angles in radians.
#pragma once

#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

// The spur pair of a helical pair's transverse section: the normal rack keeps
// its heights and its lengths along the pitch line grow by 1 / cos(beta), so
// m = m_n / cos(beta), a0 = alpha_t, and ha, ha + c, x and rho* (in units of
// m_n) times cos(beta) in units of m_t. The rack's tip round stays the normal
// section's circle of radius rho* m_n (absent: the normal rack's full round,
// or the largest that fits its tip land). helix_angle 0 on the result; a spur
// pair (beta = 0) comes back unchanged, to the bit.
GearPair transverse_pair(const GearPair& pair);
// The transverse section as the dynamics run a helical pair: transverse_pair
// with face_advance_m = W = b tan(beta_b), so that MeshLayout places each
// tooth pair by its mid-face contact over the widened segment. A spur pair
// comes back unchanged, to the bit.
GearPair swept_transverse_pair(const GearPair& pair);

// What fixes a helical pair's geometry, normal-section values; the tips and
// the centre distance as given (a published pair prints them rounded).
struct HelicalInputs {
  int teeth1 = 20;
  int teeth2 = 30;
  double normal_module_m = 3.5e-3;
  double normal_pressure_angle_rad = 0.3490658503988659;
  double helix_angle_rad = 0.0;
  double face_width_m = 0.0;
  double profile_shift1 = 0.0;
  double profile_shift2 = 0.0;
  double tip_radius1_m = 0.0;
  double tip_radius2_m = 0.0;
  double centre_distance_m = 0.0;  // a_w
};

struct HelicalGeometry {
  double normal_module_m;                // m_n
  double transverse_module_m;            // m_t = m_n / cos(beta)
  double normal_pressure_angle_rad;      // alpha_n
  double transverse_pressure_angle_rad;  // tan(alpha_t) = tan(alpha_n) / cos(beta)
  double helix_angle_rad;                // beta
  double base_helix_angle_rad;           // tan(beta_b) = tan(beta) cos(alpha_t)
  double pitch_radius1_m;                // r = z m_t / 2
  double pitch_radius2_m;
  double base_radius1_m;  // r_b = r cos(alpha_t)
  double base_radius2_m;
  double tip_radius1_m;
  double tip_radius2_m;
  double transverse_base_pitch_m;     // p_bt = pi m_t cos(alpha_t)
  double normal_base_pitch_m;         // p_bn = pi m_n cos(alpha_n)
  double working_pressure_angle_rad;  // alpha_wt: cos = (r_b1 + r_b2) / a_w
  double centre_distance_m;           // a_w
  double path_of_contact_m;           // g_alpha
  double transverse_contact_ratio;    // eps_alpha = g_alpha / p_bt
  double overlap_ratio;               // eps_beta = b tan(beta_b) / p_bt
  double total_contact_ratio;         // eps_gamma = eps_alpha + eps_beta
  double virtual_teeth1;              // zn = z / (cos^2(beta_b) cos(beta))
  double virtual_teeth2;
  double face_width_m;           // b
  double contact_line_length_m;  // b / cos(beta_b), a line across the whole face
};

// Throws InputError naming the field for a helix angle outside [0, 45] deg,
// tips inside their base circles or a centre distance the base circles do not fit.
HelicalGeometry helical_geometry(const HelicalInputs& inputs);
// The pair's: tips r + (ha + x) m_n, a_w from the shifts (inv alpha_wt =
// inv alpha_t + 2 tan(alpha_n) (x1 + x2) / (z1 + z2)).
HelicalInputs helical_inputs(const GearPair& pair);
HelicalGeometry helical_geometry(const GearPair& pair);

// sigma of the slice model: +1 for a right-hand pinion, -1 for a left-hand one.
int hand_sign(HelixHand hand);

// The forces of a transverse load F_bt = T1 / r_b1 along the line of action:
// tangential F_bt cos(alpha_wt) and radial F_bt sin(alpha_wt) at the working
// circle, axial F_bt tan(beta_b), and the normal load F_bt / cos(beta_b).
struct HelicalForces {
  double transverse_n;  // F_bt
  double tangential_n;  // F_t
  double radial_n;      // F_r
  double axial_n;       // F_a
  double normal_n;      // F_bn
};
HelicalForces helical_forces(const HelicalGeometry& geometry, double pinion_torque_n_m);

// The axial force and the tilting moments that come with a helical pair's
// transverse mesh forces (docs/helical.md, "The planar model"), on the section
// the dynamics run (swept_transverse_pair: tan(beta_b) = W / b, the hand
// kept), in the frame of docs/vibration.md (O1 the origin, e_x towards O2,
// the pinion turning about +z). From the drive line's force F_d (N1) and the
// coast line's F_c (N2), both transverse and >= 0:
//   F_a1 = sigma tan(beta_b) (F_d - F_c) on the pinion along +z, F_a2 = -F_a1,
//   M1 = -r_w1 F_a1 and M2 = -r_w2 F_a1 about +y at the gears' centres,
// the axial force taken at the pitch point (r_w = r_b / cos(alpha_wt), the
// operating pitch radius: both lines of action cross the centre line there).
// Reported only: the planar model has no axial or tilting freedom.
struct HelicalThrust {
  double axial_force1_n = 0.0;
  double axial_force2_n = 0.0;
  double tilting_moment1_n_m = 0.0;
  double tilting_moment2_n_m = 0.0;
};
class HelicalThrustLevers {
 public:
  // `section` a swept transverse section (face_advance_m > 0).
  explicit HelicalThrustLevers(const GearPair& section);
  HelicalThrust operator()(double drive_force_n, double coast_force_n) const;

 private:
  double axial_per_transverse_;  // sigma tan(beta_b)
  double pitch_radius1_m_;       // r_w1
  double pitch_radius2_m_;       // r_w2
};

// Backlash: B, half the play along the transverse line of action, and the
// normal backlash between idle flanks j_bn = 2 B cos(beta_b).
double normal_backlash_m(const HelicalGeometry& geometry, double backlash_m);
double backlash_from_normal_m(const HelicalGeometry& geometry, double normal_backlash_m);

}  // namespace gearimpact
