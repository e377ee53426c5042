#include "gearimpact/geometry/rack_generation.hpp"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// Root of a function that changes sign on [lower, upper], to full double
// precision (TOMS 748). The callers bracket the root themselves.
template <class F>
double bracketed_root(F f, double lower, double upper) {
  std::uintmax_t iterations = 200;
  const auto bracket = boost::math::tools::toms748_solve(
      f, lower, upper, boost::math::tools::eps_tolerance<double>(), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// theta_b = pi / (2 z) + inv a0 + 2 x tan a0 / z: half the tooth's angle on
// the base circle, from the tooth thickness pi m / 2 + 2 x m tan a0 on the
// reference circle (the rack's space on its rolling line).
double base_half_angle(double teeth, double a0, double x) {
  return pi / (2.0 * teeth) + involute_function(a0) + 2.0 * x * std::tan(a0) / teeth;
}

// r_a = r_p + (ha + x) m: the shift moves the tip out with the rack.
double tip_radius(double teeth, double module, double ha, double x) {
  return 0.5 * teeth * module + (ha + x) * module;
}

// Half angle of the involute tooth at its tip, theta_b - inv(alpha_a): zero or
// less is a pointed tooth.
double tip_half_angle(double teeth, double module, double a0, double ha, double x) {
  const double rb = 0.5 * teeth * module * std::cos(a0);
  return base_half_angle(teeth, a0, x) -
         involute_function(std::acos(rb / tip_radius(teeth, module, ha, x)));
}

}  // namespace

// The rack's tip round when the pair names none: the full round c / (1 -
// sin a0) of ISO 53 profile A where it fits the rack's tip land (at 20 deg it
// does), else the largest that fits, rho* (1 - sin a0) / cos a0 = pi/4 -
// (ha + c) tan a0 (above about 22 deg the full round of c = 0.25 is wider
// than the tip land).
double largest_rack_tip_radius_coefficient(const GearPair& pair) {
  const double a0 = pair.pressure_angle_rad;
  const double c = pair.dedendum_coefficient - pair.addendum_coefficient;
  const double full_round = c / (1.0 - std::sin(a0));
  const double land =
      (pi / 4.0 - pair.dedendum_coefficient * std::tan(a0)) * std::cos(a0) / (1.0 - std::sin(a0));
  return std::min(full_round, land);
}

RackGearGeometry rack_gear_geometry(const GearPair& pair, Gear gear) {
  const bool first = gear == Gear::one;
  const int teeth_count = teeth(pair, gear);
  const double z = teeth_count;
  const double a0 = pair.pressure_angle_rad;
  const double ha = pair.addendum_coefficient;
  const double c = pair.dedendum_coefficient - pair.addendum_coefficient;
  if (c < 0.0) {
    throw InputError("dedendum_coefficient", pair.dedendum_coefficient,
                     "values >= addendum_coefficient = " + format_number(ha) +
                         ": the rack's clearance c = dedendum - addendum is not negative");
  }
  const double x = profile_shift(pair, gear);
  const char* shift_field = first ? "profile_shift1" : "profile_shift2";

  const double m = pair.module_m;
  const double sin_a0 = std::sin(a0);
  const double cos_a0 = std::cos(a0);
  const double tan_a0 = std::tan(a0);
  // The rack tooth, pi m / 2 thick on its datum line, narrows by 2 tan a0 per
  // unit depth; at the depth (ha + c) m of its tip it must still be thick.
  const double tip_land_half_width = pi / 4.0 - (ha + c) * tan_a0;  // in modules
  if (tip_land_half_width <= 0.0) {
    throw InputError("dedendum_coefficient", pair.dedendum_coefficient,
                     "values below pi / (4 tan a0) = " + format_number(pi / (4.0 * tan_a0)) +
                         ", so that the rack tooth keeps a tip land");
  }
  // The tip round, tangent to the tip line and the flank, reaches up the
  // flank by rho (1 - sin a0): more than the clearance c m and it cuts into
  // the working flank (ISO 53's full round c / (1 - sin a0) is the limit);
  // along the tip line it takes rho (1 - sin a0) / cos a0 of the half land.
  const double rho_full_round = c / (1.0 - sin_a0);
  const double rho_limit = std::min(rho_full_round, tip_land_half_width * cos_a0 / (1.0 - sin_a0));
  const double rho_star = pair.rack_tip_radius_coefficient
                              ? *pair.rack_tip_radius_coefficient
                              : largest_rack_tip_radius_coefficient(pair);
  if (!std::isfinite(rho_star) || rho_star < 0.0 || rho_star > rho_limit) {
    throw InputError("rack_tip_radius_coefficient", rho_star,
                     "[0, " + format_number(rho_limit) +
                         "]: the rack's tip round must fit the clearance, rho* <= c / (1 - sin a0) "
                         "= " +
                         format_number(rho_full_round) +
                         ", and the rack's tip land, rho* (1 - sin a0) / cos a0 <= pi/4 - (ha + "
                         "c) tan a0");
  }
  const double rho = rho_star * m;

  if (tip_half_angle(z, m, a0, ha, x) <= 0.0) {
    // The tip half angle falls with x (for ha + x > 0) and is positive at
    // x = -ha, where the tip is the reference circle and (ha + c) tan a0 <
    // pi/4 holds: the limit lies between.
    const double x_max =
        bracketed_root([&](double shift) { return tip_half_angle(z, m, a0, ha, shift); }, -ha, x);
    throw InputError(shift_field, x,
                     "values below " + format_number(x_max) +
                         ", the shift at which the tooth tip becomes pointed");
  }

  RackGearGeometry g{};
  g.teeth = teeth_count;
  g.module_m = m;
  g.pressure_angle_rad = a0;
  g.addendum_coefficient = ha;
  g.clearance_coefficient = c;
  g.profile_shift_coefficient = x;
  g.rack_tip_radius_m = rho;
  g.pitch_radius_m = 0.5 * z * m;
  g.base_radius_m = g.pitch_radius_m * cos_a0;
  g.tip_radius_m = tip_radius(z, m, ha, x);
  g.root_radius_m = g.pitch_radius_m - (ha + c - x) * m;
  g.half_tooth_angle_base_rad = base_half_angle(z, a0, x);

  // Depth below the rolling line of the point where the rack's straight flank
  // meets its tip round; that point generates the involute's first point, the
  // form point, a distance depth / sin a0 from the pitch point along the line
  // of action towards T (for the full round, depth = (ha - x) m).
  const double form_depth = (ha + c - x) * m - rho * (1.0 - sin_a0);
  if (form_depth <= 0.0) {
    throw InputError(shift_field, x,
                     "values below ha + c - rho* (1 - sin a0) = " +
                         format_number(ha + c - rho_star * (1.0 - sin_a0)) +
                         ", where the rack's straight flank still crosses the reference circle");
  }
  const double form_tangent_length = g.base_radius_m * tan_a0 - form_depth / sin_a0;
  if (form_tangent_length <= 0.0) {
    const double limit = 2.0 * (ha + c - x - rho_star * (1.0 - sin_a0)) / (sin_a0 * sin_a0);
    throw InputError(
        first ? "teeth1" : "teeth2", std::to_string(teeth_count),
        "more than 2 (ha + c - x - rho* (1 - sin a0)) / sin^2 a0 = " + format_number(limit) +
            " teeth (2 (ha - x) / sin^2 a0 for the full round), below which the rack "
            "undercuts the involute");
  }
  g.form_radius_m = std::hypot(g.base_radius_m, form_tangent_length);
  g.form_tau_rad = form_tangent_length / g.base_radius_m - g.half_tooth_angle_base_rad;

  // Round centre: depth a1 below the rolling line; along it, the space half
  // width there, pi m / 4 + x m tan a0, plus the flank's run over a1 and the
  // offset rho / cos a0 of a circle tangent to the flank. The shift cancels:
  // b1 = pi m / 4 + (ha + c) m tan a0 + rho (1 - sin a0) / cos a0, which is
  // docs/stiffness-models.md's pi m / 4 + ha m tan a0 + rho cos a0 for the full round.
  g.trochoid_a1_m = (ha + c - x) * m - rho;
  g.trochoid_b1_m = pi * m / 4.0 + (ha + c) * m * tan_a0 + rho * (1.0 - sin_a0) / cos_a0;
  // At gamma = pi/2 the trochoid point lies at r_p - a1 - rho = r_f, at the
  // angle phi = b1 / r_p from the centre line.
  g.root_half_angle_rad = g.trochoid_b1_m / g.pitch_radius_m;

  if (g.tip_radius_m <= g.form_radius_m) {
    throw InputError(shift_field, x,
                     "values with the tip radius r_p + (ha + x) m above the form radius " +
                         format_number(g.form_radius_m) + " m, so that the tooth has an involute");
  }
  const double tip_tangent_length =
      std::sqrt((g.tip_radius_m - g.base_radius_m) * (g.tip_radius_m + g.base_radius_m));
  g.tip_tau_rad = tip_tangent_length / g.base_radius_m - g.half_tooth_angle_base_rad;

  const std::optional<double>& bore_diameter =
      first ? pair.bore_diameter1_m : pair.bore_diameter2_m;
  if (bore_diameter) {
    const double bore = *bore_diameter;
    if (!std::isfinite(bore) || bore <= 0.0 || bore >= 2.0 * g.root_radius_m) {
      throw InputError(first ? "bore_diameter1" : "bore_diameter2", bore,
                       "(0, " + format_number(2.0 * g.root_radius_m) +
                           ") m: inside the root circle, diameter 2 r_f");
    }
  }
  g.bore_diameter_m = bore_diameter;
  g.face_width_m = pair.face_width_m;
  g.youngs_modulus_pa = youngs_modulus(pair, gear);
  g.poisson_ratio = poisson_ratio(pair, gear);
  return g;
}

ProfilePoint involute_point(const RackGearGeometry& gear, double tau_rad) {
  const double rb = gear.base_radius_m;
  const double roll = tau_rad + gear.half_tooth_angle_base_rad;
  const double c = std::cos(tau_rad);
  const double s = std::sin(tau_rad);
  // docs/stiffness-models.md section 1, the involute in the tooth frame, and its
  // derivatives: dx/dtau = -r_b roll sin tau, dy/dtau = r_b roll cos tau.
  return {rb * (roll * c - s), rb * (roll * s + c), -rb * roll * s, rb * roll * c};
}

ProfilePoint trochoid_point(const RackGearGeometry& gear, double gamma_rad) {
  const double rp = gear.pitch_radius_m;
  const double a1 = gear.trochoid_a1_m;
  const double sin_g = std::sin(gamma_rad);
  const double cos_g = std::cos(gamma_rad);
  // docs/stiffness-models.md section 1, the trochoid, with the shifted a1 and b1
  // of rack_gear_geometry. phi is the gear's rotation from the position in
  // which the rack's rolling line touches the reference circle on the tooth's
  // centre line; the contact normal through the instantaneous pitch point
  // r_p (sin phi, cos phi) makes the angle gamma with the rolling line and
  // meets the round's centre a1 / sin gamma from it.
  const double phi = (a1 * cos_g / sin_g + gear.trochoid_b1_m) / rp;
  const double dphi = -a1 / (rp * sin_g * sin_g);
  const double reach = a1 / sin_g + gear.rack_tip_radius_m;
  const double dreach = -a1 * cos_g / (sin_g * sin_g);
  const double c = std::cos(gamma_rad - phi);
  const double s = std::sin(gamma_rad - phi);
  return {rp * std::sin(phi) - reach * c, rp * std::cos(phi) - reach * s,
          rp * std::cos(phi) * dphi - dreach * c + reach * s * (1.0 - dphi),
          -rp * std::sin(phi) * dphi - dreach * s - reach * c * (1.0 - dphi)};
}

double involute_arc_thickness(const RackGearGeometry& gear, double radius_m) {
  const double alpha = std::acos(gear.base_radius_m / radius_m);
  return 2.0 * radius_m * (gear.half_tooth_angle_base_rad - involute_function(alpha));
}

RackGearPairGeometry rack_gear_pair_geometry(const GearPair& pair) {
  RackGearPairGeometry g{};
  g.gear1 = rack_gear_geometry(pair, Gear::one);
  g.gear2 = rack_gear_geometry(pair, Gear::two);
  const RackGearGeometry& g1 = g.gear1;
  const RackGearGeometry& g2 = g.gear2;
  g.operating_pressure_angle_rad = operating_pressure_angle(
      g1.pressure_angle_rad, g1.teeth, g2.teeth, pair.profile_shift1, pair.profile_shift2);
  g.centre_distance_m =
      (g1.base_radius_m + g2.base_radius_m) / std::cos(g.operating_pressure_angle_rad);
  // T1T2 = a_w sin a_w, written with the base radii.
  g.line_of_action_length_m =
      (g1.base_radius_m + g2.base_radius_m) * std::tan(g.operating_pressure_angle_rad);

  const std::pair<const RackGearGeometry*, const RackGearGeometry*> sides[] = {{&g1, &g2},
                                                                               {&g2, &g1}};
  for (const auto& [tip_gear, root_gear] : sides) {
    const double clearance =
        g.centre_distance_m - tip_gear->tip_radius_m - root_gear->root_radius_m;
    if (clearance <= 0.0) {
      const std::string tip_name = tip_gear == &g1 ? "gear1" : "gear2";
      throw InputError("addendum_coefficient", pair.addendum_coefficient,
                       "values for which the tip of " + tip_name +
                           " clears the mating root circle on the operating centre distance (a_w "
                           "- r_a - r_f = " +
                           format_number(clearance) + " m, must be > 0)");
    }
  }

  const double rb1 = g1.base_radius_m;
  const double rb2 = g2.base_radius_m;
  const double ra1 = g1.tip_radius_m;
  const double ra2 = g2.tip_radius_m;
  g.start_of_active_profile_m = g.line_of_action_length_m - std::sqrt((ra2 - rb2) * (ra2 + rb2));
  g.end_of_active_profile_m = std::sqrt((ra1 - rb1) * (ra1 + rb1));
  // The contact must stay on each tooth's involute, between its form point
  // (form_tau + theta_b = tan alpha_c along the line from T) and its tip.
  const double pinion_form_s = rb1 * (g1.form_tau_rad + g1.half_tooth_angle_base_rad);
  const double wheel_form_s =
      g.line_of_action_length_m - rb2 * (g2.form_tau_rad + g2.half_tooth_angle_base_rad);
  if (g.start_of_active_profile_m < pinion_form_s) {
    throw InputError("addendum_coefficient", pair.addendum_coefficient,
                     "values for which the tip of gear2 meets gear1 on its involute, above its "
                     "form radius " +
                         format_number(g1.form_radius_m) +
                         " m (contact starts at s = " + format_number(g.start_of_active_profile_m) +
                         " m from T1, the form point is at " + format_number(pinion_form_s) +
                         " m): interference with the fillet");
  }
  if (g.end_of_active_profile_m > wheel_form_s) {
    throw InputError("addendum_coefficient", pair.addendum_coefficient,
                     "values for which the tip of gear1 meets gear2 on its involute, above its "
                     "form radius " +
                         format_number(g2.form_radius_m) +
                         " m (contact ends at s = " + format_number(g.end_of_active_profile_m) +
                         " m from T1, the form point is at " + format_number(wheel_form_s) +
                         " m): interference with the fillet");
  }
  g.base_pitch_m = 2.0 * pi * rb1 / g1.teeth;
  g.contact_ratio = (g.end_of_active_profile_m - g.start_of_active_profile_m) / g.base_pitch_m;
  if (!(g.contact_ratio >= 1.0)) {
    throw InputError("contact_ratio", g.contact_ratio,
                     "[1, inf): below 1 the gears lose contact between pairs");
  }
  g.contact_width_m = std::min(g1.face_width_m, g2.face_width_m);
  return g;
}

ToothContact tooth_contact(const RackGearGeometry& gear, double tangent_length_m) {
  const double rb = gear.base_radius_m;
  const double tau = tangent_length_m / rb - gear.half_tooth_angle_base_rad;
  const ProfilePoint point = involute_point(gear, tau);
  return {std::hypot(rb, tangent_length_m), std::atan2(tangent_length_m, rb), tau, point.x_m,
          point.y_m};
}

PairContact pair_contact(const RackGearPairGeometry& pair, double s_m) {
  if (!(s_m >= pair.start_of_active_profile_m && s_m <= pair.end_of_active_profile_m)) {
    throw InputError("contact position s", s_m,
                     "[" + format_number(pair.start_of_active_profile_m) + ", " +
                         format_number(pair.end_of_active_profile_m) +
                         "] m from T1: the path of contact");
  }
  return {tooth_contact(pair.gear1, s_m),
          tooth_contact(pair.gear2, pair.line_of_action_length_m - s_m)};
}

}  // namespace gearimpact
