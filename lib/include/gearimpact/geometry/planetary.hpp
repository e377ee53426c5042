// The geometry and kinematics of a planetary stage (docs/planetary.md): the
// internal (ring-planet) mesh's active segment and contact ratio, the ties
// between the carrier radius and the working pressure angles, the planets'
// positions and assembly conditions, the Willis relations of the three
// arrangements, the mesh phases and the type of each mesh harmonic.
//
// Sign rule: every angle and speed about +z. The planets sit at psi_n
// counter-clockwise from the carrier axis e1, psi_1 = 0. Standard (unshifted)
// involute teeth of one module and one basic rack on every member.
#pragma once

#include <vector>

namespace gearimpact {

// The tooth counts of a stage: sun, planet and ring (internal).
struct PlanetaryTeeth {
  int sun = 0;
  int planet = 0;
  int ring = 0;
};

// The rack and the size the teeth are cut with, shared by the three members.
struct PlanetaryToothing {
  double module_m = 0.0;
  double pressure_angle_rad = 0.0;    // a0 of the basic rack
  double addendum_coefficient = 1.0;  // h_a: tip at r + h_a m (external), r - h_a m (ring)
};

// The internal mesh of the ring (a) with one planet (b) at the working centre
// distance a_w. Lengths along the line of action from the planet's tangent
// point T_b; the ring's tangent point T_a lies on the same side of the pitch
// point, at a_w sin(a_w') further.
struct InternalMesh {
  double working_pressure_angle_rad = 0.0;  // cos a_w' = (Rb_a - Rb_b) / a_w
  double ring_base_radius_m = 0.0;
  double planet_base_radius_m = 0.0;
  double ring_tip_radius_m = 0.0;    // r_a - h_a m, inside its pitch circle
  double planet_tip_radius_m = 0.0;  // r_b + h_a m
  double segment_start_m = 0.0;      // where the ring's tip circle cuts the line, from T_b
  double segment_end_m = 0.0;        // where the planet's tip circle cuts it, from T_b
  double pitch_point_m = 0.0;        // Rb_b tan a_w', from T_b
  double base_pitch_m = 0.0;         // 2 pi Rb_b / Z_b
  double contact_ratio = 0.0;        // (end - start) / base pitch
};

// The ring-planet mesh at the centre distance centre_distance_m (> 0). Throws
// InputError naming the condition: a ring tip circle inside its base circle,
// Rb_a - Rb_b outside (0, a_w), a segment starting inside T_b (involute
// interference), a contact ratio below 1.
InternalMesh internal_mesh(const PlanetaryTeeth& teeth, const PlanetaryToothing& toothing,
                           double centre_distance_m);

// The working pressure angles of the sun and ring meshes at the carrier
// radius R_c (the planets' centre circle), by the geometry ties
// R_c cos(alpha_s) = Rb_s + Rb_p and R_c cos(alpha_r) = Rb_r - Rb_p.
struct WorkingAngles {
  double carrier_radius_m = 0.0;
  double sun_rad = 0.0;
  double ring_rad = 0.0;
  double sun_base_radius_m = 0.0;
  double planet_base_radius_m = 0.0;
  double ring_base_radius_m = 0.0;
};
// Throws InputError naming the tie that has no angle in (0, pi/2).
WorkingAngles working_angles(const PlanetaryTeeth& teeth, const PlanetaryToothing& toothing,
                             double carrier_radius_m);
// The standard carrier radius m (Z_s + Z_p) / 2; throws InputError unless the
// ring's own standard centre distance m (Z_r - Z_p) / 2 equals it, that is
// Z_r = Z_s + 2 Z_p (the two meshes at one working centre distance).
double standard_carrier_radius(const PlanetaryTeeth& teeth, const PlanetaryToothing& toothing);

// Planet n at 2 pi (n - 1) / N. Throws InputError naming the assembly
// condition unless (Z_s + Z_r) / N is an integer, and the tip clearance
// unless 2 R_c sin(pi / N) > d_a,p (as checked_planet_angles).
std::vector<double> equal_planet_angles(const PlanetaryTeeth& teeth,
                                        const PlanetaryToothing& toothing, int planets);
// Unequal spacing: psi_1 = 0 < psi_2 < ... < 2 pi, each with
// (Z_s + Z_r) psi_n / (2 pi) an integer (to 1e-9), neighbours (the last and
// the first included) with 2 R_c sin(dpsi / 2) > d_a,p, R_c = m (Z_s + Z_p) / 2
// and d_a,p = m (Z_p + 2 h_a). Returns the angles;
// throws InputError naming the planet and the condition.
std::vector<double> checked_planet_angles(const PlanetaryTeeth& teeth,
                                          const PlanetaryToothing& toothing,
                                          const std::vector<double>& angles_rad);

// Rigid speeds about +z (rad/s): the central members' and each planet's
// absolute spin.
struct StageSpeeds {
  double sun = 0.0;
  double ring = 0.0;
  double carrier = 0.0;
  double planet = 0.0;
};
enum class HeldMember { ring, carrier, sun };
// The Willis relations (w_s - w_c) / (w_r - w_c) = -Z_r / Z_s and
// w_p - w_c = -(Z_s / Z_p)(w_s - w_c), with `held` at rest and the input
// member (the sun, or the ring when the sun is held) at input_rad_per_s.
StageSpeeds willis_speeds(const PlanetaryTeeth& teeth, HeldMember held, double input_rad_per_s);

// Phases in mesh periods, in [0, 1), for the sun turning counter-clockwise
// relative to the carrier (sun_ahead = true); for the other sense each
// becomes frac(-gamma).
// gamma_sn = frac(Z_s psi_n / 2 pi): planet n's sun mesh lags planet 1's.
double sun_mesh_phase(int sun_teeth, double psi_rad, bool sun_ahead = true);
// gamma_rn = frac(-Z_r psi_n / 2 pi): planet n's ring mesh lags planet 1's.
double ring_mesh_phase(int ring_teeth, double psi_rad, bool sun_ahead = true);
// gamma_rs = frac(Z_p (2 theta_bp - inv a_s - inv a_r - pi) / 2 pi): one
// planet's sun mesh follows its ring mesh (pitch-point crossings), theta_bp
// the planet's base half-angle (13).
double sun_ring_phase(const PlanetaryTeeth& teeth, const PlanetaryToothing& toothing,
                      double sun_angle_rad, double ring_angle_rad, bool sun_ahead = true);

// Which modes the l-th mesh harmonic excites (N equally spaced identical
// planets), by k = l Z_s mod N: 0 in phase (rotational: torques add, net
// forces cancel); 1 or N - 1 sequential (translational); otherwise
// counter-phase (planet modes).
enum class HarmonicType { rotational, translational, planet };
HarmonicType harmonic_type(int harmonic, int sun_teeth, int planets);

}  // namespace gearimpact
