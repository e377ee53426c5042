// docs/stiffness-models.md section 1: teeth cut by a rack, shifted or not, and a
// pair of them on the line of action. The shifted trochoid is derived in
// rack_generation.cpp; these checks prove it against the involute (whose
// shift enters only through theta_b), against the root circle and against a
// textbook example.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "rack_pairs.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::check_refused;
using gearimpact::verify::degree;
using gearimpact::verify::relative_difference;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

// One gear of a pair: the pair's fields and which gear.
struct NamedGear {
  std::string name;
  GearPair pair;
  Gear gear;
  RackGearGeometry geometry() const { return rack_gear_geometry(pair, gear); }
  double shift() const { return profile_shift(pair, gear); }
};

std::vector<NamedGear> varied_gears() {
  std::vector<NamedGear> gears;
  for (const auto& named : verify::varied_rack_pairs()) {
    gears.push_back({named.name + ", gear 1", named.pair, Gear::one});
    gears.push_back({named.name + ", gear 2", named.pair, Gear::two});
  }
  GearPair p;
  p.teeth1 = 12;
  p.module_m = 3e-3;
  p.profile_shift1 = 0.6;
  p.dedendum_coefficient = 1.0 + 0.37667;
  p.rack_tip_radius_coefficient = 0.3;
  gears.push_back({"12 teeth, x +0.6, c 0.377, rho* 0.3", p, Gear::one});
  p = GearPair{};
  p.teeth1 = 60;
  p.profile_shift1 = -0.2;
  p.pressure_angle_rad = 14.5 * degree;
  p.rack_tip_radius_coefficient = 0.0;
  gears.push_back({"60 teeth, 14.5 deg, x -0.2, sharp rack corner", p, Gear::one});
  return gears;
}

// The unit tangent of a profile in the direction of rising height.
struct Direction {
  double x;
  double y;
};
Direction upward(const ProfilePoint& p) {
  const double sign = p.dy_m > 0.0 ? 1.0 : -1.0;
  const double norm = std::hypot(p.dx_m, p.dy_m);
  return {sign * p.dx_m / norm, sign * p.dy_m / norm};
}

}  // namespace

TEST_CASE("trochoid: meets the root circle at gamma = pi/2, tangent to it") {
  for (const NamedGear& named : varied_gears()) {
    const RackGearGeometry g = named.geometry();
    const ProfilePoint p = trochoid_point(g, 0.5 * pi);
    CAPTURE(named.name);
    // A few trig calls on radius-sized numbers: 8 ulps of the radius.
    CHECK(std::fabs(std::hypot(p.x_m, p.y_m) - g.root_radius_m) <= 8.0 * eps * g.root_radius_m);
    // theta_f is the point's angle from the centre line.
    CHECK(std::fabs(std::atan2(p.x_m, p.y_m) - g.root_half_angle_rad) <= 8.0 * eps);
    // Tangent to the root circle: the radius is perpendicular to the curve,
    // cos of the angle between them within rounding of the dot product.
    const double cos_angle =
        (p.x_m * p.dx_m + p.y_m * p.dy_m) / (std::hypot(p.x_m, p.y_m) * std::hypot(p.dx_m, p.dy_m));
    CHECK(std::fabs(cos_angle) <= 1e-13);
  }
}

TEST_CASE("trochoid: meets the involute at the form radius, continuously, with a common tangent") {
  // The trochoid knows the shift through the round's depth a1 and the
  // involute only through theta_b: they meet only if both are right.
  double worst_gap = 0.0;
  double worst_cross = 0.0;
  for (const NamedGear& named : varied_gears()) {
    const RackGearGeometry g = named.geometry();
    const ProfilePoint t = trochoid_point(g, g.pressure_angle_rad);
    const ProfilePoint i = involute_point(g, g.form_tau_rad);
    CAPTURE(named.name);
    // Positions by two unrelated formulas: 16 ulps of the radius.
    CHECK(std::fabs(t.x_m - i.x_m) <= 16.0 * eps * g.form_radius_m);
    CHECK(std::fabs(t.y_m - i.y_m) <= 16.0 * eps * g.form_radius_m);
    CHECK(std::fabs(std::hypot(t.x_m, t.y_m) - g.form_radius_m) <= 16.0 * eps * g.form_radius_m);
    // Tangents: the involute's at the form point and the trochoid's at
    // gamma = a0 (where the rack's round meets its straight flank) point the
    // same way; the cross product of the unit tangents is rounding.
    const Direction dt = upward(t);
    const Direction di = upward(i);
    worst_gap = std::max(worst_gap, std::hypot(t.x_m - i.x_m, t.y_m - i.y_m) / g.form_radius_m);
    worst_cross = std::max(worst_cross, std::fabs(dt.x * di.y - dt.y * di.x));
    CHECK(std::fabs(dt.x * di.y - dt.y * di.x) <= 1e-12);
    CHECK(dt.x * di.x + dt.y * di.y > 0.0);
    // The height rises along the whole fillet (the section route needs it).
    for (int k = 1; k < 100; ++k) {
      const double gamma = g.pressure_angle_rad + (0.5 * pi - g.pressure_angle_rad) * k / 100.0;
      CHECK(trochoid_point(g, gamma).dy_m < 0.0);
    }
  }
  MESSAGE("trochoid/involute junction: worst gap "
          << worst_gap << " of r_c, worst sine between tangents " << worst_cross);
}

TEST_CASE("tooth thickness on the reference circle is pi m / 2 + 2 x m tan a0") {
  // The rack's space on its rolling line (ISO 21771), against the involute's
  // arc thickness 2 r (theta_b - inv a) at r = r_p.
  for (const NamedGear& named : varied_gears()) {
    const RackGearGeometry g = named.geometry();
    const double m = named.pair.module_m;
    const double expected =
        0.5 * pi * m + 2.0 * named.shift() * m * std::tan(named.pair.pressure_angle_rad);
    CAPTURE(named.name);
    // A difference of two angles of order 0.1 times the radius: 64 ulps.
    CHECK(std::fabs(involute_arc_thickness(g, g.pitch_radius_m) - expected) <=
          64.0 * eps * g.pitch_radius_m);
  }
}

TEST_CASE("a shifted pair meshes without backlash on a_w") {
  // On the operating pitch circles (r_w = r_b / cos a_w) the two tooth
  // thicknesses fill the circular pitch 2 pi r_w1 / z1: the zero-backlash
  // condition from which inv a_w is derived, checked by the involute itself.
  for (const auto& named : verify::varied_rack_pairs()) {
    const RackGearPairGeometry g = rack_gear_pair_geometry(named.pair);
    const double cos_aw = std::cos(g.operating_pressure_angle_rad);
    const double rw1 = g.gear1.base_radius_m / cos_aw;
    const double rw2 = g.gear2.base_radius_m / cos_aw;
    CAPTURE(named.name);
    CHECK(relative_difference(rw1 + rw2, g.centre_distance_m) <= 4.0 * eps);
    const double pitch = 2.0 * pi * rw1 / g.gear1.teeth;
    const double filled =
        involute_arc_thickness(g.gear1, rw1) + involute_arc_thickness(g.gear2, rw2);
    // Each thickness is a difference of angles of order 0.1: 256 ulps of the pitch.
    CHECK(std::fabs(filled - pitch) <= 256.0 * eps * pitch);
    // a_w^2 = (r_b1 + r_b2)^2 + T1T2^2.
    CHECK(relative_difference(
              std::hypot(g.gear1.base_radius_m + g.gear2.base_radius_m, g.line_of_action_length_m),
              g.centre_distance_m) <= 4.0 * eps);
  }
}

TEST_CASE("textbook: KHK's profile-shifted spur pair (m 3, z 12/24, x 0.6/0.36)") {
  // KHK Gear Technical Reference, profile-shifted spur gear example, as
  // reproduced at bolsover.com/utilitiesforalibre/profile-shifted-external-
  // spur-gears.html: working pressure angle 26.0888 deg, centre distance
  // 56.500 (KHK: 56.4999) mm, outside diameters 44.840 / 79.400 mm, root
  // diameters 32.100 / 66.660 mm, contact ratio 1.202. KHK shortens both tips
  // by (x1 + x2 - y) m = 0.38 mm; here that is ha = 1 - 0.12667 with the
  // clearance c = 0.25 + 0.12667 keeping KHK's root.
  GearPair p;
  p.module_m = 3e-3;
  p.addendum_coefficient = 1.0 - 0.12667;
  p.dedendum_coefficient = 1.25;  // (ha + c): KHK's root
  p.rack_tip_radius_coefficient = 0.38;
  p.teeth1 = 12;
  p.teeth2 = 24;
  p.profile_shift1 = 0.6;
  p.profile_shift2 = 0.36;
  const RackGearPairGeometry g = rack_gear_pair_geometry(p);
  // The example derives x1 + x2 = 0.960 from a = 56.5 mm and prints it to
  // three digits; 0.0005 in the sum moves a_w by 0.0024 deg and 1.2 um.
  CHECK(std::fabs(g.operating_pressure_angle_rad / degree - 26.0888) <= 0.0025);
  CHECK(std::fabs(g.centre_distance_m - 56.4999e-3) <= 1.3e-6);
  // The diameters to the example's printed 0.001 mm (half a unit).
  CHECK(std::fabs(2.0 * g.gear1.tip_radius_m - 44.840e-3) <= 0.5e-6);
  CHECK(std::fabs(2.0 * g.gear2.tip_radius_m - 79.400e-3) <= 0.5e-6);
  CHECK(std::fabs(2.0 * g.gear1.root_radius_m - 32.100e-3) <= 0.5e-6);
  CHECK(std::fabs(2.0 * g.gear2.root_radius_m - 66.660e-3) <= 0.5e-6);
  // The contact ratio to its printed 0.001.
  CHECK(std::fabs(g.contact_ratio - 1.202) <= 0.0005);
  MESSAGE("KHK example: a_w = " << g.operating_pressure_angle_rad / degree << " deg, "
                                << g.centre_distance_m * 1e3 << " mm, contact ratio "
                                << g.contact_ratio);
}

TEST_CASE("the undercut limit is where the form radius reaches the base circle") {
  // z = 14 at 20 deg with the full round: 2 (ha - x) / sin^2 a0 = 14 at
  // x = 1 - 7 sin^2 a0.
  GearPair pair;
  pair.teeth1 = 14;
  const double s = std::sin(pair.pressure_angle_rad);
  const double x_limit = 1.0 - 7.0 * s * s;
  for (double above : {1e-3, 1e-6, 1e-9}) {
    pair.profile_shift1 = x_limit + above;
    const RackGearGeometry g = rack_gear_geometry(pair, Gear::one);
    // The form point's distance from the base-circle tangent point is
    // (x - x_limit) m / sin a0: it vanishes at the limit.
    const double tangent_length = g.base_radius_m * (g.form_tau_rad + g.half_tooth_angle_base_rad);
    const double expected = above * pair.module_m / s;
    CAPTURE(above);
    // tangent_length is a difference of radius-sized numbers: 64 ulps of r_b.
    CHECK(std::fabs(tangent_length - expected) <= 64.0 * eps * g.base_radius_m);
    // The trochoid, a separate formula, ends there too.
    const ProfilePoint end = trochoid_point(g, g.pressure_angle_rad);
    CHECK(std::fabs(std::hypot(end.x_m, end.y_m) - std::hypot(g.base_radius_m, expected)) <=
          64.0 * eps * g.base_radius_m);
  }
  pair.profile_shift1 = x_limit - 1e-9;
  check_refused([&] { rack_gear_geometry(pair, Gear::one); }, "teeth1",
                "more than 2 (ha + c - x - rho* (1 - sin a0)) / sin^2 a0 = 14");
}

TEST_CASE("kinematics: contact points of a pair on the line of action") {
  for (const auto& named : verify::varied_rack_pairs()) {
    const RackGearPairGeometry g = rack_gear_pair_geometry(named.pair);
    const double t1t2 = g.line_of_action_length_m;
    for (int i = 0; i <= 20; ++i) {
      const double s = g.start_of_active_profile_m +
                       (g.end_of_active_profile_m - g.start_of_active_profile_m) * i / 20.0;
      const PairContact c = pair_contact(g, s);
      CAPTURE(named.name);
      CAPTURE(s);
      // Each tooth's contact point lies at the distance of the point s on the
      // line of action from its own centre.
      CHECK(relative_difference(std::hypot(c.gear1.x_m, c.gear1.y_m),
                                std::hypot(g.gear1.base_radius_m, s)) <= 16.0 * eps);
      CHECK(relative_difference(std::hypot(c.gear2.x_m, c.gear2.y_m),
                                std::hypot(g.gear2.base_radius_m, t1t2 - s)) <= 16.0 * eps);
      // The involute's normal there is the load line: at tau to the x axis.
      for (const auto& [gear, contact] :
           {std::pair{&g.gear1, c.gear1}, std::pair{&g.gear2, c.gear2}}) {
        const ProfilePoint p = involute_point(*gear, contact.tau_rad);
        const double dot =
            (p.dx_m * std::cos(contact.tau_rad) + p.dy_m * std::sin(contact.tau_rad)) /
            std::hypot(p.dx_m, p.dy_m);
        // Zero near the base circle is a ratio of small numbers: 1e-12.
        CHECK(std::fabs(dot) <= 1e-12);
      }
    }
    // The path of contact ends on the tips.
    CHECK(relative_difference(pair_contact(g, g.end_of_active_profile_m).gear1.radius_m,
                              g.gear1.tip_radius_m) <= 16.0 * eps);
    CHECK(relative_difference(pair_contact(g, g.start_of_active_profile_m).gear2.radius_m,
                              g.gear2.tip_radius_m) <= 16.0 * eps);
    MESSAGE(named.name << ": a_w = " << g.centre_distance_m * 1e3 << " mm, contact ratio "
                       << g.contact_ratio);
  }
}

TEST_CASE("bad input is refused naming the field and its allowed range") {
  GearPair pair;
  // A pointed tip from a shift: for 10 teeth the limit lies between 0.5 and
  // 0.8 (the tip half angle falls through zero there).
  pair.teeth1 = 10;
  pair.profile_shift1 = 0.8;
  check_refused([&] { rack_gear_geometry(pair, Gear::one); }, "profile_shift1",
                "the shift at which the tooth tip becomes pointed");
  // The limit it names is the root of the tip half angle: a shift just
  // below it passes, just above it fails.
  try {
    rack_gear_geometry(pair, Gear::one);
  } catch (const InputError& e) {
    const std::string message = e.what();
    const std::size_t at = message.find("values below ") + 13;
    const double x_max = std::stod(message.substr(at));
    CHECK(x_max > 0.5);
    CHECK(x_max < 0.8);
    pair.profile_shift1 = x_max - 1e-9;
    CHECK_NOTHROW(rack_gear_geometry(pair, Gear::one));
    pair.profile_shift1 = x_max + 1e-9;
    CHECK_THROWS_AS(rack_gear_geometry(pair, Gear::one), InputError);
  }

  pair = GearPair{};
  pair.teeth2 = 20;
  // Root diameter 2 r_f = 20 * 2 mm - 2 * 1.25 * 2 mm = 35 mm.
  pair.bore_diameter2_m = 35e-3;
  check_refused([&] { rack_gear_geometry(pair, Gear::two); }, "bore_diameter2",
                "(0, " + format_number(35e-3) + ") m");

  pair = GearPair{};
  // The full round of c = 0.25 at 20 deg: 0.25 / (1 - sin 20 deg).
  pair.rack_tip_radius_coefficient = 0.4;
  check_refused([&] { rack_gear_geometry(pair, Gear::one); }, "rack_tip_radius_coefficient",
                "[0, " + format_number(0.25 / (1.0 - std::sin(20.0 * degree))) + "]");

  // One module for both gears: the pair has one field, and its range is the
  // case schema's row.
  pair = GearPair{};
  pair.module_m = -2.5e-3;
  check_refused([&] { validate(pair); }, "module", "[1e-6, 1] m");

  pair = GearPair{};
  pair.poisson_ratio = 0.5;
  check_refused([&] { validate(pair); }, "poisson_ratio", "(-1, 0.5)");
}
