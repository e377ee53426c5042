// A root crack in one tooth (root_crack.hpp; docs/stiffness-models.md,
// "Root crack"): the width integrals against closed forms written here from
// t(y, z) = x + min(x, h_q(z)) + max(0, x - h_c), the limits of the profiles,
// monotonic loss of stiffness, the two beam routes on cracked teeth, and the
// refusal of a crack that passes the centre line.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "rack_pairs.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::degree;
using gearimpact::verify::relative_difference;

namespace {

StiffnessModel model_of(StiffnessModelKind kind, StiffnessRoute route = StiffnessRoute::tau_form) {
  StiffnessModel m;
  m.kind = kind;
  m.route = route;
  return m;
}

RootCrack uniform_crack(double q, double nu) {
  RootCrack c;
  c.depth_m = q;
  c.angle_rad = nu;
  return c;
}

// The slice height as docs/stiffness-models.md ("A root crack in one tooth")
// writes it, literally: x + min(x, h_c - q sin nu) + max(0, x - h_c).
double slice(double x, double h_c, double q, double sin_nu) {
  const double h_q = h_c - q * sin_nu;
  return x + std::min(x, h_q) + std::max(0.0, x - h_c);
}

// The single-tooth stiffness of `gear` at `contact`: 1 / (bending + shear +
// axial + foundation).
double tooth_stiffness(const ToothCompliances& c) {
  return 1.0 / c.total_m_per_n();
}

// Positions from SAP to EAP.
std::vector<double> positions(const RackGearPairGeometry& pair, int n) {
  std::vector<double> s;
  for (int i = 0; i <= n; ++i) {
    s.push_back(pair.start_of_active_profile_m +
                (pair.end_of_active_profile_m - pair.start_of_active_profile_m) * i / n);
  }
  return s;
}

}  // namespace

TEST_CASE("width integrals: uniform and two-valued depths against their closed forms") {
  // Uniform: every slice the same, A = b t, I = b t^3 / 12. Two-valued (q1 on
  // [0, z1), q2 beyond): A = z1 t1 + (b - z1) t2, I = (z1 t1^3 + (b - z1) t2^3) / 12.
  // The quadrature of a constant is exact to rounding: 1e-14 leaves a few ulps
  // of the 61-point sum.
  constexpr double bound = 1e-14;
  const double b = 10e-3;
  const double h_c = 2e-3;
  const double s = std::sin(45.0 * degree);
  // Sections narrower than the start, as wide and wider (the involute's bulge).
  for (double x : {1.2e-3, 1.7e-3, 2e-3, 2.01e-3}) {
    for (double q : {0.3e-3, 1.0e-3, 2.5e-3}) {
      CAPTURE(x);
      CAPTURE(q);
      const double t = slice(x, h_c, q, s);
      const SectionProperties u = cracked_section(uniform_crack(q, 45.0 * degree), x, h_c, b);
      CHECK(relative_difference(u.area_m2, b * t) <= bound);
      CHECK(relative_difference(u.second_moment_m4, b * t * t * t / 12.0) <= bound);
      const double z1 = 3.7e-3;
      const double q2 = 0.4 * q;
      const double t2 = slice(x, h_c, q2, s);
      const SectionProperties two =
          cracked_section_over_width([&](double z) { return z < z1 ? q : q2; }, {z1}, s, x, h_c, b);
      CHECK(relative_difference(two.area_m2, z1 * t + (b - z1) * t2) <= bound);
      CHECK(relative_difference(two.second_moment_m4,
                                (z1 * t * t * t + (b - z1) * t2 * t2 * t2) / 12.0) <= bound);
    }
  }
}

TEST_CASE("width integrals: the Chen-Shao profiles against the route over z") {
  // cracked_section integrates over the depth (polynomials); the route over z
  // integrates q(z) itself between the points where the cut begins, so the
  // two share only t. Both meet 1e-13; 1e-12 leaves a factor 10.
  constexpr double bound = 1e-12;
  const double b = 10e-3;
  const double h_c = 2e-3;
  const double nu = 40.0 * degree;
  const double s = std::sin(nu);
  for (double x : {1.5e-3, 1.9e-3}) {
    CAPTURE(x);
    const double delta = h_c - x;
    RootCrack partial;
    partial.profile = CrackProfile::partial_width;
    partial.depth_m = 2.4e-3;
    partial.width_m = 6e-3;
    partial.angle_rad = nu;
    // Cut where s q0 sqrt((W_c - z) / W_c) > delta.
    const double w0 = delta / (s * partial.depth_m);
    const double z_cut = partial.width_m * (1.0 - w0 * w0);
    const SectionProperties a = cracked_section(partial, x, h_c, b);
    const SectionProperties a_z =
        cracked_section_over_width([&](double z) { return crack_depth_at(partial, z, b); },
                                   {z_cut, partial.width_m}, s, x, h_c, b);
    CHECK(relative_difference(a.area_m2, a_z.area_m2) <= bound);
    CHECK(relative_difference(a.second_moment_m4, a_z.second_moment_m4) <= bound);
    CHECK(a.area_m2 < 2.0 * x * b);  // something is cut

    RootCrack full;
    full.profile = CrackProfile::full_width;
    full.depth_m = 0.3e-3;
    full.end_depth_m = 2.6e-3;
    full.angle_rad = nu;
    // Cut where s q(z) > delta: z > b ((delta/s)^2 - q0^2) / (q2^2 - q0^2).
    const double v = delta / s;
    const double z_start = b * (v * v - full.depth_m * full.depth_m) /
                           (full.end_depth_m * full.end_depth_m - full.depth_m * full.depth_m);
    std::vector<double> breaks;
    if (z_start > 0.0 && z_start < b) breaks.push_back(z_start);
    const SectionProperties f = cracked_section(full, x, h_c, b);
    const SectionProperties f_z = cracked_section_over_width(
        [&](double z) { return crack_depth_at(full, z, b); }, breaks, s, x, h_c, b);
    CHECK(relative_difference(f.area_m2, f_z.area_m2) <= bound);
    CHECK(relative_difference(f.second_moment_m4, f_z.second_moment_m4) <= bound);
  }
}

TEST_CASE("full width with q0 = q2 is the uniform crack, and q2 -> q0 tends to it") {
  const double b = 10e-3;
  RootCrack full;
  full.profile = CrackProfile::full_width;
  full.depth_m = 1.1e-3;
  full.end_depth_m = 1.1e-3;
  full.angle_rad = 45.0 * degree;
  const RootCrack uniform = uniform_crack(1.1e-3, 45.0 * degree);
  for (double x : {1.4e-3, 2.0e-3}) {
    const SectionProperties f = cracked_section(full, x, 2e-3, b);
    const SectionProperties u = cracked_section(uniform, x, 2e-3, b);
    CHECK(f.area_m2 == u.area_m2);
    CHECK(f.second_moment_m4 == u.second_moment_m4);
    // Through the substituted integral: q2 = q0 (1 + 1e-7) moves A and I by
    // about 1e-7 of the cut, well under 1e-6 of the section.
    RootCrack near = full;
    near.end_depth_m = full.depth_m * (1.0 + 1e-7);
    const SectionProperties n = cracked_section(near, x, 2e-3, b);
    CHECK(relative_difference(n.area_m2, u.area_m2) <= 1e-6);
    CHECK(relative_difference(n.second_moment_m4, u.second_moment_m4) <= 1e-6);
    CHECK(n.area_m2 != u.area_m2);
  }
}

TEST_CASE("a crack of depth 0 is the healthy tooth to the bit; a tiny one is close") {
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  for (StiffnessModelKind kind :
       {StiffnessModelKind::potential_energy, StiffnessModelKind::ross_compatible}) {
    for (StiffnessRoute route : {StiffnessRoute::tau_form, StiffnessRoute::x_form}) {
      const StiffnessModel model = model_of(kind, route);
      for (double s : positions(pair, 4)) {
        const PairContact c = pair_contact(pair, s);
        const ToothCompliances healthy =
            tooth_compliances(pair.gear1, Gear::one, c.gear1, pair.contact_width_m, model);
        const ToothCompliances zero =
            cracked_tooth_compliances(pair.gear1, Gear::one, c.gear1, pair.contact_width_m, model,
                                      uniform_crack(0.0, 45.0 * degree));
        CHECK(zero.bending_m_per_n == healthy.bending_m_per_n);
        CHECK(zero.shear_m_per_n == healthy.shear_m_per_n);
        CHECK(zero.axial_m_per_n == healthy.axial_m_per_n);
        CHECK(zero.foundation_m_per_n == healthy.foundation_m_per_n);
        // 1 nm: the split flank and the cut sections by the cracked path,
        // within 1e-8 of the healthy tooth (the loss is first order in q,
        // about 1e-6 per um here).
        const ToothCompliances tiny =
            cracked_tooth_compliances(pair.gear1, Gear::one, c.gear1, pair.contact_width_m, model,
                                      uniform_crack(1e-9, 45.0 * degree));
        CHECK(relative_difference(tiny.total_m_per_n(), healthy.total_m_per_n()) <= 1e-8);
        CHECK(tiny.total_m_per_n() > healthy.total_m_per_n());
      }
    }
  }
}

TEST_CASE("stiffness falls monotonically with the depth q and with the width W_c") {
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  const StiffnessModel model = model_of(StiffnessModelKind::potential_energy);
  const double nu = 45.0 * degree;
  const PlacedCrack probe =
      place_crack(uniform_crack(0.0, nu), pair.gear1, model.kind, pair.contact_width_m);
  const double q_limit = probe.start_half_thickness_m / std::sin(nu);
  const double b = pair.contact_width_m;
  for (double s : positions(pair, 3)) {
    const PairContact c = pair_contact(pair, s);
    double previous = tooth_stiffness(tooth_compliances(pair.gear1, Gear::one, c.gear1, b, model));
    for (int i = 1; i <= 9; ++i) {
      const double k = tooth_stiffness(cracked_tooth_compliances(
          pair.gear1, Gear::one, c.gear1, b, model, uniform_crack(0.1 * i * q_limit, nu)));
      CAPTURE(i);
      CHECK(k < previous);
      previous = k;
    }
    RootCrack partial;
    partial.profile = CrackProfile::partial_width;
    partial.depth_m = 0.6 * q_limit;
    partial.angle_rad = nu;
    previous = tooth_stiffness(tooth_compliances(pair.gear1, Gear::one, c.gear1, b, model));
    for (int i = 1; i <= 5; ++i) {
      partial.width_m = 0.2 * i * b;
      const double k = tooth_stiffness(
          cracked_tooth_compliances(pair.gear1, Gear::one, c.gear1, b, model, partial));
      CAPTURE(i);
      CHECK(k < previous);
      previous = k;
    }
  }
}

TEST_CASE("two routes: the cracked beam integrals agree to 1e-10 as the healthy ones do") {
  // As for the healthy tooth (test_tooth_beam): each route meets 1e-12 by its
  // own estimate and they share only the flank's points and the section
  // function; the flank is split at r_s and at the cut's kinks, so both
  // integrate smooth pieces and 1e-10 holds with room.
  constexpr double bound = 1e-10;
  double worst = 0.0;
  for (const auto& named : verify::varied_rack_pairs()) {
    const RackGearPairGeometry pair = rack_gear_pair_geometry(named.pair);
    const double b = pair.contact_width_m;
    for (int gear_index = 0; gear_index < 2; ++gear_index) {
      const RackGearGeometry& gear = gear_index == 0 ? pair.gear1 : pair.gear2;
      const PlacedCrack probe = place_crack(uniform_crack(0.0, 45.0 * degree), gear,
                                            StiffnessModelKind::potential_energy, b);
      const double q_limit = probe.start_half_thickness_m / std::sin(45.0 * degree);
      RootCrack partial;
      partial.profile = CrackProfile::partial_width;
      partial.depth_m = 0.7 * q_limit;
      partial.width_m = 0.5 * b;
      partial.angle_rad = 45.0 * degree;
      RootCrack full;
      full.profile = CrackProfile::full_width;
      full.depth_m = 0.2 * q_limit;
      full.end_depth_m = 0.8 * q_limit;
      full.angle_rad = 45.0 * degree;
      for (const RootCrack& crack : {uniform_crack(0.5 * q_limit, 45.0 * degree), partial, full}) {
        const PlacedCrack placed =
            place_crack(crack, gear, StiffnessModelKind::potential_energy, b);
        for (double s : positions(pair, 4)) {
          const PairContact pc = pair_contact(pair, s);
          const ToothContact& c = gear_index == 0 ? pc.gear1 : pc.gear2;
          const BeamMaterial material{gear.youngs_modulus_pa,
                                      gear.youngs_modulus_pa / (2.0 * (1.0 + gear.poisson_ratio)),
                                      b};
          const std::vector<FlankPiece> flank = flank_to_contact(gear, c.tau_rad);
          const BeamCompliance a = cracked_beam_compliance(
              flank, {c.x_m, c.y_m, c.tau_rad}, material, placed, StiffnessRoute::tau_form);
          const BeamCompliance x = cracked_beam_compliance(
              flank, {c.x_m, c.y_m, c.tau_rad}, material, placed, StiffnessRoute::x_form);
          CAPTURE(named.name);
          CAPTURE(gear_index);
          CAPTURE(static_cast<int>(crack.profile));
          CAPTURE(s);
          for (double d : {relative_difference(a.bending_m_per_n, x.bending_m_per_n),
                           relative_difference(a.shear_m_per_n, x.shear_m_per_n),
                           relative_difference(a.axial_m_per_n, x.axial_m_per_n)}) {
            CHECK(d <= bound);
            worst = std::max(worst, d);
          }
        }
      }
    }
  }
  MESSAGE("two routes on cracked teeth: worst relative difference " << worst);
}

TEST_CASE("the default start: the 30 deg fillet point, in the fillet") {
  for (const auto& named : verify::varied_rack_pairs()) {
    const RackGearPairGeometry pair = rack_gear_pair_geometry(named.pair);
    const RackGearGeometry& g = pair.gear1;
    const double r_s = default_crack_start_radius(g, StiffnessModelKind::potential_energy);
    CAPTURE(named.name);
    CHECK(r_s > g.root_radius_m);
    CHECK(r_s < g.form_radius_m);
    // The tangent there, by a central difference of the trochoid at the
    // gamma whose point has height r_s (found by bisection here).
    double lo = g.pressure_angle_rad;
    double hi = 0.5 * pi;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      // y falls as gamma rises towards the root circle.
      (trochoid_point(g, mid).y_m > r_s ? lo : hi) = mid;
    }
    const double gamma = 0.5 * (lo + hi);
    const double h = 1e-6;
    const ProfilePoint p1 = trochoid_point(g, gamma - h);
    const ProfilePoint p2 = trochoid_point(g, gamma + h);
    const double angle = std::atan(std::abs((p2.x_m - p1.x_m) / (p2.y_m - p1.y_m)));
    CHECK(std::abs(angle - 30.0 * degree) <= 1e-6);
    CHECK(default_crack_start_radius(g, StiffnessModelKind::yang_lin_1987) == g.base_radius_m);
  }
}

TEST_CASE("a crack at or past the centre line is refused with the limit q sin nu < h_c") {
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  const double b = pair.contact_width_m;
  const double nu = 45.0 * degree;
  const PlacedCrack probe =
      place_crack(uniform_crack(0.0, nu), pair.gear1, StiffnessModelKind::potential_energy, b);
  const double q_limit = probe.start_half_thickness_m / std::sin(nu);
  verify::check_refused(
      [&] {
        place_crack(uniform_crack(q_limit, nu), pair.gear1, StiffnessModelKind::potential_energy,
                    b);
      },
      "crack depth q", "q sin nu < h_c");
  RootCrack full;
  full.profile = CrackProfile::full_width;
  full.depth_m = 0.1 * q_limit;
  full.end_depth_m = 1.01 * q_limit;
  full.angle_rad = nu;
  verify::check_refused(
      [&] { place_crack(full, pair.gear1, StiffnessModelKind::potential_energy, b); },
      "crack end depth q2", "q sin nu < h_c");
  // Just inside the limit it is a crack.
  CHECK_NOTHROW(place_crack(uniform_crack(0.999 * q_limit, nu), pair.gear1,
                            StiffnessModelKind::potential_energy, b));
}

TEST_CASE("record: single-tooth stiffness loss of the paper's pinion, nu = 45 deg") {
  // Potential-energy model, the paper's pair with bores 20/60 mm; the tooth
  // stiffness 1 / (bending + shear + axial + foundation) of pinion tooth 1,
  // cracked at the 30 deg fillet point, against the healthy one.
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  const StiffnessModel model = model_of(StiffnessModelKind::potential_energy);
  const double b = pair.contact_width_m;
  const double nu = 45.0 * degree;
  const PlacedCrack probe = place_crack(uniform_crack(0.0, nu), pair.gear1, model.kind, b);
  const double h_c = probe.start_half_thickness_m;
  MESSAGE("r_s = " << probe.start_radius_m << " m, h_c = " << h_c << " m");
  const std::vector<double> s_all = positions(pair, 40);
  const double s_pitch = pair.gear1.base_radius_m * std::tan(pair.gear1.pressure_angle_rad);
  double previous_mean = 0.0;
  for (double ratio : {0.25, 0.5, 0.75}) {
    const RootCrack crack = uniform_crack(ratio * h_c, nu);
    double loss_sum = 0.0;
    double loss_min = 1.0;
    double loss_max = 0.0;
    for (double s : s_all) {
      const PairContact c = pair_contact(pair, s);
      const double k0 =
          tooth_stiffness(tooth_compliances(pair.gear1, Gear::one, c.gear1, b, model));
      const double k = tooth_stiffness(
          cracked_tooth_compliances(pair.gear1, Gear::one, c.gear1, b, model, crack));
      const double loss = 1.0 - k / k0;
      loss_sum += loss;
      loss_min = std::min(loss_min, loss);
      loss_max = std::max(loss_max, loss);
    }
    const PairContact cp = pair_contact(pair, s_pitch);
    const double k0p =
        tooth_stiffness(tooth_compliances(pair.gear1, Gear::one, cp.gear1, b, model));
    const double kp = tooth_stiffness(
        cracked_tooth_compliances(pair.gear1, Gear::one, cp.gear1, b, model, crack));
    const double mean = loss_sum / static_cast<double>(s_all.size());
    MESSAGE("q/h_c = " << ratio << ": tooth stiffness loss at the pitch point "
                       << 100.0 * (1.0 - kp / k0p) << " %, over SAP..EAP mean " << 100.0 * mean
                       << " %, min " << 100.0 * loss_min << " %, max " << 100.0 * loss_max << " %");
    CHECK(mean > previous_mean);
    CHECK(loss_max < 1.0);
    previous_mean = mean;
  }
}

TEST_CASE("the paper's tooth: depth 0 is healthy to the bit, the two routes agree when cracked") {
  // The paper's pair, both teeth along the path of contact. The tau-form
  // (over the involute parameter) and the x-form (over the centre line, each
  // section root-found from the polar involute) share only cracked_section;
  // each meets 1e-12 on pieces between the cut's kinks, so 1e-10 is the
  // bound of the healthy harness (test_stiffness) with the same reasoning.
  constexpr double bound = 1e-10;
  const GearPair pair = paper_gear_pair();
  const ContactSegment segment = contact_segment(pair);
  const double lp = line_of_action_length(pair);
  const double e = pair.youngs_modulus_pa;
  const double b = pair.face_width_m;
  double worst = 0.0;
  for (Gear gear : {Gear::one, Gear::two}) {
    const InvoluteTooth tooth = tooth_of(pair, gear);
    const double h_c = tooth.base_radius_m * std::sin(tooth.half_tooth_angle_rad);
    const double nu = 45.0 * degree;
    RootCrack partial;
    partial.profile = CrackProfile::partial_width;
    partial.depth_m = 0.6 * h_c / std::sin(nu);
    partial.width_m = 0.5 * b;
    partial.angle_rad = nu;
    for (int i = 0; i <= 8; ++i) {
      const double x1 = segment.start_m + (segment.end_m - segment.start_m) * i / 8.0;
      const double x = gear == Gear::one ? x1 : lp - x1;
      for (StiffnessRoute route : {StiffnessRoute::tau_form, StiffnessRoute::x_form}) {
        StiffnessModel m;
        m.route = route;
        const Compliances healthy = tooth_compliance(tooth, x, e, b, m);
        const Compliances zero =
            cracked_paper_tooth_compliances(tooth, x, e, b, m, uniform_crack(0.0, nu));
        CHECK(zero.of(Term::bending) == healthy.of(Term::bending));
        CHECK(zero.of(Term::axial) == healthy.of(Term::axial));
        const Compliances cracked =
            cracked_paper_tooth_compliances(tooth, x, e, b, m, uniform_crack(0.5 * h_c, nu));
        CHECK(cracked.of(Term::bending) > healthy.of(Term::bending));
      }
      StiffnessModel tau;
      StiffnessModel xf;
      xf.route = StiffnessRoute::x_form;
      for (const RootCrack& crack : {uniform_crack(0.5 * h_c, nu), partial}) {
        const Compliances a = cracked_paper_tooth_compliances(tooth, x, e, b, tau, crack);
        const Compliances c = cracked_paper_tooth_compliances(tooth, x, e, b, xf, crack);
        CAPTURE(x1);
        for (double d : {relative_difference(a.of(Term::bending), c.of(Term::bending)),
                         relative_difference(a.of(Term::axial), c.of(Term::axial))}) {
          CHECK(d <= bound);
          worst = std::max(worst, d);
        }
      }
    }
    verify::check_refused(
        [&] {
          StiffnessModel m;
          cracked_paper_tooth_compliances(tooth, 0.5 * (segment.start_m + segment.end_m), e, b, m,
                                          uniform_crack(h_c / std::sin(nu), nu));
        },
        "crack depth q", "q sin nu < h_c");
  }
  MESSAGE("paper's tooth, two routes on cracked teeth: worst relative difference " << worst);
}
