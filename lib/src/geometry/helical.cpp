#include "gearimpact/geometry/helical.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/rack_generation.hpp"

namespace gearimpact {

namespace {

constexpr double degree = pi / 180.0;

void check_helix_angle(double beta) {
  if (!(beta >= 0.0 && beta <= 45.0 * degree)) {
    throw InputError("gears.helix_angle", format_number(beta / degree) + " deg", "[0, 45] deg");
  }
}

}  // namespace

GearPair transverse_pair(const GearPair& pair) {
  if (pair.helix_angle_rad == 0.0) return pair;
  check_helix_angle(pair.helix_angle_rad);
  const double cos_beta = std::cos(pair.helix_angle_rad);
  GearPair t = pair;
  // Heights stay, lengths along the pitch line grow by 1 / cos(beta): a
  // coefficient of m_n is that times cos(beta) of m_t.
  t.module_m = pair.module_m / cos_beta;
  t.pressure_angle_rad = std::atan(std::tan(pair.pressure_angle_rad) / cos_beta);
  t.addendum_coefficient = pair.addendum_coefficient * cos_beta;
  t.dedendum_coefficient = pair.dedendum_coefficient * cos_beta;
  t.profile_shift1 = pair.profile_shift1 * cos_beta;
  t.profile_shift2 = pair.profile_shift2 * cos_beta;
  // First version: the normal round's radius as a circle in the transverse
  // rack (the true section is an ellipse, rho / cos(beta) along the pitch line).
  t.rack_tip_radius_coefficient =
      pair.rack_tip_radius_coefficient.value_or(largest_rack_tip_radius_coefficient(pair)) *
      cos_beta;
  t.helix_angle_rad = 0.0;
  return t;
}

GearPair swept_transverse_pair(const GearPair& pair) {
  if (pair.helix_angle_rad == 0.0) return pair;
  GearPair t = transverse_pair(pair);
  // tan(beta_b) = tan(beta) cos(alpha_t), alpha_t the section's pressure angle.
  t.face_advance_m =
      pair.face_width_m * std::tan(pair.helix_angle_rad) * std::cos(t.pressure_angle_rad);
  return t;
}

HelicalGeometry helical_geometry(const HelicalInputs& in) {
  check_helix_angle(in.helix_angle_rad);
  HelicalGeometry g{};
  const double cos_beta = std::cos(in.helix_angle_rad);
  g.normal_module_m = in.normal_module_m;
  g.transverse_module_m = in.normal_module_m / cos_beta;
  g.normal_pressure_angle_rad = in.normal_pressure_angle_rad;
  g.transverse_pressure_angle_rad = std::atan(std::tan(in.normal_pressure_angle_rad) / cos_beta);
  g.helix_angle_rad = in.helix_angle_rad;
  const double cos_at = std::cos(g.transverse_pressure_angle_rad);
  g.base_helix_angle_rad = std::atan(std::tan(in.helix_angle_rad) * cos_at);
  g.pitch_radius1_m = 0.5 * in.teeth1 * g.transverse_module_m;
  g.pitch_radius2_m = 0.5 * in.teeth2 * g.transverse_module_m;
  g.base_radius1_m = g.pitch_radius1_m * cos_at;
  g.base_radius2_m = g.pitch_radius2_m * cos_at;
  if (!(in.tip_radius1_m > g.base_radius1_m)) {
    throw InputError("tip_radius1", in.tip_radius1_m,
                     "values above the base radius " + format_number(g.base_radius1_m) + " m");
  }
  if (!(in.tip_radius2_m > g.base_radius2_m)) {
    throw InputError("tip_radius2", in.tip_radius2_m,
                     "values above the base radius " + format_number(g.base_radius2_m) + " m");
  }
  const double rb_sum = g.base_radius1_m + g.base_radius2_m;
  if (!(in.centre_distance_m > rb_sum) || !std::isfinite(in.centre_distance_m)) {
    throw InputError("centre_distance", in.centre_distance_m,
                     "values above r_b1 + r_b2 = " + format_number(rb_sum) + " m");
  }
  g.tip_radius1_m = in.tip_radius1_m;
  g.tip_radius2_m = in.tip_radius2_m;
  g.transverse_base_pitch_m = pi * g.transverse_module_m * cos_at;
  g.normal_base_pitch_m = pi * in.normal_module_m * std::cos(in.normal_pressure_angle_rad);
  g.centre_distance_m = in.centre_distance_m;
  g.working_pressure_angle_rad = std::acos(rb_sum / in.centre_distance_m);
  const double ra1 = in.tip_radius1_m;
  const double ra2 = in.tip_radius2_m;
  const double rb1 = g.base_radius1_m;
  const double rb2 = g.base_radius2_m;
  g.path_of_contact_m = std::sqrt(ra1 * ra1 - rb1 * rb1) + std::sqrt(ra2 * ra2 - rb2 * rb2) -
                        in.centre_distance_m * std::sin(g.working_pressure_angle_rad);
  g.transverse_contact_ratio = g.path_of_contact_m / g.transverse_base_pitch_m;
  g.face_width_m = in.face_width_m;
  g.overlap_ratio = in.face_width_m * std::tan(g.base_helix_angle_rad) / g.transverse_base_pitch_m;
  g.total_contact_ratio = g.transverse_contact_ratio + g.overlap_ratio;
  const double cos_bb = std::cos(g.base_helix_angle_rad);
  g.virtual_teeth1 = in.teeth1 / (cos_bb * cos_bb * cos_beta);
  g.virtual_teeth2 = in.teeth2 / (cos_bb * cos_bb * cos_beta);
  g.contact_line_length_m = in.face_width_m / cos_bb;
  return g;
}

HelicalInputs helical_inputs(const GearPair& pair) {
  check_helix_angle(pair.helix_angle_rad);
  HelicalInputs in;
  in.teeth1 = pair.teeth1;
  in.teeth2 = pair.teeth2;
  in.normal_module_m = pair.module_m;
  in.normal_pressure_angle_rad = pair.pressure_angle_rad;
  in.helix_angle_rad = pair.helix_angle_rad;
  in.face_width_m = pair.face_width_m;
  in.profile_shift1 = pair.profile_shift1;
  in.profile_shift2 = pair.profile_shift2;
  const double cos_beta = std::cos(pair.helix_angle_rad);
  const double mt = pair.module_m / cos_beta;
  in.tip_radius1_m =
      0.5 * pair.teeth1 * mt + (pair.addendum_coefficient + pair.profile_shift1) * pair.module_m;
  in.tip_radius2_m =
      0.5 * pair.teeth2 * mt + (pair.addendum_coefficient + pair.profile_shift2) * pair.module_m;
  const double at = std::atan(std::tan(pair.pressure_angle_rad) / cos_beta);
  const double z_sum = static_cast<double>(pair.teeth1) + static_cast<double>(pair.teeth2);
  const double x_sum = pair.profile_shift1 + pair.profile_shift2;
  const double awt =
      x_sum == 0.0 ? at
                   : inverse_involute(involute_function(at) +
                                      2.0 * std::tan(pair.pressure_angle_rad) * x_sum / z_sum);
  in.centre_distance_m = 0.5 * z_sum * mt * std::cos(at) / std::cos(awt);
  return in;
}

HelicalGeometry helical_geometry(const GearPair& pair) {
  return helical_geometry(helical_inputs(pair));
}

int hand_sign(HelixHand hand) {
  return hand == HelixHand::right ? 1 : -1;
}

HelicalForces helical_forces(const HelicalGeometry& g, double pinion_torque_n_m) {
  HelicalForces f{};
  f.transverse_n = pinion_torque_n_m / g.base_radius1_m;
  f.tangential_n = f.transverse_n * std::cos(g.working_pressure_angle_rad);
  f.radial_n = f.transverse_n * std::sin(g.working_pressure_angle_rad);
  f.axial_n = f.transverse_n * std::tan(g.base_helix_angle_rad);
  f.normal_n = f.transverse_n / std::cos(g.base_helix_angle_rad);
  return f;
}

HelicalThrustLevers::HelicalThrustLevers(const GearPair& section) {
  if (!(section.face_advance_m > 0.0 && section.face_width_m > 0.0)) {
    throw InputError("face_advance_m", section.face_advance_m,
                     "a swept transverse section's W = b tan(beta_b) > 0 (swept_transverse_pair)");
  }
  // The flank's normal in the plane of action is perpendicular to its contact
  // line, inclined at beta_b to the axis: tan(beta_b) axial per unit of
  // transverse force; its sign by the hand and the side (docs/helical.md).
  axial_per_transverse_ =
      hand_sign(section.helix_hand) * section.face_advance_m / section.face_width_m;
  const double cos_aw = std::cos(operating_pressure_angle(section));
  pitch_radius1_m_ = base_radius(section, Gear::one) / cos_aw;
  pitch_radius2_m_ = base_radius(section, Gear::two) / cos_aw;
}

HelicalThrust HelicalThrustLevers::operator()(double drive_force_n, double coast_force_n) const {
  HelicalThrust t;
  t.axial_force1_n = axial_per_transverse_ * (drive_force_n - coast_force_n);
  t.axial_force2_n = -t.axial_force1_n;
  // r x F at the pitch point: (r_w1 e_x) x (F_a1 e_z) on the pinion,
  // (-r_w2 e_x) x (F_a2 e_z) on the wheel, both along e_y.
  t.tilting_moment1_n_m = -pitch_radius1_m_ * t.axial_force1_n;
  t.tilting_moment2_n_m = pitch_radius2_m_ * t.axial_force2_n;
  return t;
}

double normal_backlash_m(const HelicalGeometry& g, double backlash_m) {
  // The idle flanks' gap along their normal: the transverse play 2B times cos(beta_b).
  return 2.0 * backlash_m * std::cos(g.base_helix_angle_rad);
}

double backlash_from_normal_m(const HelicalGeometry& g, double normal_backlash_m) {
  return normal_backlash_m / (2.0 * std::cos(g.base_helix_angle_rad));
}

}  // namespace gearimpact
