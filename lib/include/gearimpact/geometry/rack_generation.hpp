// Spur gears cut by a basic rack (ISO 53 form): the whole tooth from the root
// circle, a trochoid fillet traced by the rack's tip round and then the
// involute, for any profile shift; and a pair of such gears on the centre
// distance at which they mesh without backlash, with the exact kinematics of
// the line of action. docs/stiffness-models.md, section 1. SI units, angles in rad.
//
// Tooth frame: y along the tooth centre line from the gear centre, x the half
// thickness (the loaded flank at x > 0).
#pragma once

#include <optional>

#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

// Every derived length and angle of one generated gear.
struct RackGearGeometry {
  int teeth;
  double module_m;
  double pressure_angle_rad;         // a0
  double addendum_coefficient;       // ha
  double clearance_coefficient;      // c
  double profile_shift_coefficient;  // x
  double rack_tip_radius_m;          // rho
  double pitch_radius_m;             // r_p = z m / 2 (the reference circle)
  double base_radius_m;              // r_b = r_p cos a0
  double tip_radius_m;               // r_a = r_p + (ha + x) m
  double root_radius_m;              // r_f = r_p - (ha + c - x) m
  double form_radius_m;              // r_c, where the trochoid meets the involute
  double half_tooth_angle_base_rad;  // theta_b = pi/(2z) + inv a0 + 2 x tan a0 / z
  double root_half_angle_rad;        // theta_f, where the trochoid meets the root circle
  // The round's centre in the rack, relative to the rolling line (the rack
  // line that rolls on the reference circle) and the tooth centre line:
  // a1 below the rolling line, b1 along it.
  double trochoid_a1_m;
  double trochoid_b1_m;
  double form_tau_rad;  // tau at r_c, where the involute begins
  double tip_tau_rad;   // tau at r_a
  std::optional<double> bore_diameter_m;
  double face_width_m;
  double youngs_modulus_pa;
  double poisson_ratio;
};

// The geometry of `gear` of the pair as the rack cuts it: clearance
// c = dedendum_coefficient - addendum_coefficient, the pair's rack tip round
// (absent: the full round c / (1 - sin a0), or the largest that fits the
// rack's tip land), gear 2's material where the pair gives one. The fields
// must lie in their ranges (the case schema's rows, validate(const GearPair&)
// of case/schema.hpp); this checks what follows from several of them, each an
// InputError naming the field as GearPair does (teeth2, profile_shift1, ...)
// with its limit: a negative clearance or one that leaves the rack no tip
// land; a rack tip radius that does not fit the clearance; undercut (the
// straight flank of the rack reaching below the base circle's tangent point:
// z <= 2 (ha + c - x - rho* (1 - sin a0)) / sin^2 a0, i.e. 2 (ha - x) /
// sin^2 a0 for the full round); a pointed tip; a bore not inside the root
// circle.
RackGearGeometry rack_gear_geometry(const GearPair& pair, Gear gear);

// The rack's tip radius coefficient rho* when the pair names none: the full
// round c / (1 - sin a0) where it fits the rack's tip land, else the largest
// that fits (rack_generation.cpp). A helical pair's normal rack reads it too.
double largest_rack_tip_radius_coefficient(const GearPair& pair);

// A point of a flank curve in the tooth frame with its derivative along the
// curve's own parameter.
struct ProfilePoint {
  double x_m;
  double y_m;
  double dx_m;  // dx/dparameter
  double dy_m;  // dy/dparameter
};

// The involute, parameter tau = tan(alpha) - theta_b (alpha the pressure angle
// at the point; tau is the angle between the normal there and the x axis):
// x = r_b [(tau + theta_b) cos tau - sin tau], y = r_b [(tau + theta_b) sin tau + cos tau].
ProfilePoint involute_point(const RackGearGeometry& gear, double tau_rad);

// The trochoid fillet traced by the rack's tip round, gamma from pi/2 (root
// circle) down to a0 (form radius), with phi = (a1 cot gamma + b1) / r_p:
// x = r_p sin phi - (a1 / sin gamma + rho) cos(gamma - phi),
// y = r_p cos phi - (a1 / sin gamma + rho) sin(gamma - phi).
ProfilePoint trochoid_point(const RackGearGeometry& gear, double gamma_rad);

// The arc tooth thickness on the circle of radius r (r_c <= r <= r_a), from
// the involute: 2 r (theta_b - inv(acos(r_b / r))).
double involute_arc_thickness(const RackGearGeometry& gear, double radius_m);

// The pair's two generated gears meshing without backlash. gear1 is the
// pinion (the paper's driver), whose base-circle tangent point T1 is the
// origin of s.
struct RackGearPairGeometry {
  RackGearGeometry gear1;
  RackGearGeometry gear2;
  double operating_pressure_angle_rad;  // a_w: inv a_w = inv a0 + 2 tan a0 (x1 + x2)/(z1 + z2)
  double centre_distance_m;             // a_w = (r_b1 + r_b2) / cos a_w
  double line_of_action_length_m;       // T1T2 = a_w sin a_w
  double start_of_active_profile_m;     // s_SAP = T1T2 - sqrt(r_a2^2 - r_b2^2)
  double end_of_active_profile_m;       // s_EAP = sqrt(r_a1^2 - r_b1^2)
  double base_pitch_m;                  // p_b = 2 pi r_b1 / z1
  double contact_ratio;                 // (s_EAP - s_SAP) / p_b
  double contact_width_m;               // the smaller face width
};

// Both gears (rack_gear_geometry) and the mesh: a positive operating
// pressure angle, tip clearance on both sides, contact on the involutes only
// (no tip reaching into the mating fillet), a contact ratio of at least 1.
RackGearPairGeometry rack_gear_pair_geometry(const GearPair& pair);

// The contact point of one tooth on the line of action.
struct ToothContact {
  double radius_m;
  double pressure_angle_rad;  // alpha at the point: tan alpha = distance from T / r_b
  double tau_rad;             // tan alpha - theta_b
  double x_m;                 // the point in the tooth frame
  double y_m;
};

// The contact of one tooth at `tangent_length_m` from its base circle's
// tangent point along the line of action: tan alpha = length / r_b.
ToothContact tooth_contact(const RackGearGeometry& gear, double tangent_length_m);

struct PairContact {
  ToothContact gear1;
  ToothContact gear2;
};

// Exact kinematics: the pair in contact at s (from T1, in [s_SAP, s_EAP])
// touches the pinion where tan a1 = s / r_b1 and the wheel where
// tan a2 = (T1T2 - s) / r_b2. Throws InputError for s outside the path.
PairContact pair_contact(const RackGearPairGeometry& pair, double s_m);

}  // namespace gearimpact
