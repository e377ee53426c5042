// docs/model.md, section Stiffness: (4), (10)-(12), (16)-(24), (29) and the energy
// split (5),(16),(17),(28). The heart of it is the tolerance harness: every
// compliance by five routes (GSL QAG, GSL CQUAD, Boost Gauss-Kronrod, Boost
// tanh-sinh on the tau-form (20)-(24), and the x-form (16)-(19) integrated
// over the centre line with sections from the polar involute), compared
// pairwise at many contact positions of several gear pairs.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_profile.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

struct NamedPair {
  std::string name;
  GearPair pair;
};

std::vector<NamedPair> harness_pairs() {
  std::vector<NamedPair> pairs{{"paper 20/80 at 20 deg", paper_gear_pair()}};
  GearPair p = paper_gear_pair();
  p.teeth1 = 17;
  p.teeth2 = 43;
  p.pressure_angle_rad = 25.0 * deg;
  pairs.push_back({"17/43 at 25 deg", p});
  p = paper_gear_pair();
  p.teeth1 = 30;
  p.teeth2 = 30;
  p.module_m = 3e-3;
  p.face_width_m = 25e-3;
  pairs.push_back({"30/30 at 20 deg, m 3 mm", p});
  p = paper_gear_pair();
  p.teeth1 = 28;
  p.teeth2 = 101;
  p.pressure_angle_rad = 14.5 * deg;
  p.addendum_coefficient = 0.8;
  pairs.push_back({"28/101 at 14.5 deg, ha 0.8", p});
  for (const NamedPair& named : pairs) validate(named.pair);
  return pairs;
}

// The four rules on the tau-form, and the x-form route (with GSL QAG).
constexpr std::array<const char*, 5> all_methods{"gsl", "gsl-cquad", "boost-gk", "boost-ts",
                                                 "xform"};

// Each routine is asked for 1e-12 relative and meets it by its own estimate
// (otherwise it throws). Two honest results differ by at most 2e-12; the bound
// of 1e-10 leaves a factor 50 for estimates that are optimistic, while any
// slip in an integrand, a limit, a factor or a sign of the geometry (the
// x-form shares none of the tau-form's formulas) moves the results apart by
// far more than 1e-10.
constexpr double harness_bound = 1e-10;

struct Worst {
  double difference = 0.0;
  std::string where;
};

void record(Worst& worst, double a, double b, const std::string& where) {
  const double d = relative_difference(a, b);
  if (d > worst.difference) worst = {d, where};
}

}  // namespace

TEST_CASE("(4) Hertzian stiffness of the paper's pair") {
  // pi E L / (4 (1 - nu^2)) with E = 206.8 GPa, L = 10 mm, nu = 0.3.
  const double expected = std::numbers::pi * 206.8e9 * 0.010 / (4.0 * (1.0 - 0.09));
  CHECK(relative_difference(hertz_stiffness(paper_gear_pair()), expected) < 1e-15);
}

TEST_CASE("(10),(11) contact arm equals the polar involute's h and l") {
  for (const NamedPair& named : harness_pairs()) {
    const GearPair& pair = named.pair;
    const ContactSegment segment = contact_segment(pair);
    const double lp = line_of_action_length(pair);
    for (int i = 0; i <= 40; ++i) {
      const double x1 = segment.start_m + (segment.end_m - segment.start_m) * i / 40.0;
      for (Gear gear : {Gear::one, Gear::two}) {
        const InvoluteTooth tooth = tooth_of(pair, gear);
        const double x = gear == Gear::one ? x1 : lp - x1;
        const ContactArm printed = contact_arm(tooth, contact_angle(pair, gear, x1));
        const PolarContact polar = polar_contact(tooth, x);
        CAPTURE(named.name);
        CAPTURE(x1);
        // l is a difference of two radius-sized numbers and each route rounds
        // a handful of trig calls on them: 32 ulps of the radius.
        const double bound = 32.0 * std::numeric_limits<double>::epsilon() * tooth.base_radius_m;
        CHECK(std::abs(printed.offset_h_m - polar.arm.offset_h_m) < bound);
        CHECK(std::abs(printed.height_l_m - polar.arm.height_l_m) < bound);
      }
    }
  }
}

TEST_CASE("(23),(24) the tau-parametrised section equals the polar involute's section") {
  // At section angle tau the tau-form puts the section at height
  // Rb [cos tau - (theta_b - tau) sin tau] - Rb cos theta_b with half
  // thickness Rb [sin tau + (theta_b - tau) cos tau]; section_half_thickness
  // solves the polar involute for the same height.
  const GearPair pair = paper_gear_pair();
  for (Gear gear : {Gear::one, Gear::two}) {
    const InvoluteTooth tooth = tooth_of(pair, gear);
    const double rb = tooth.base_radius_m;
    const double theta_b = tooth.half_tooth_angle_rad;
    for (int i = 1; i <= 50; ++i) {
      const double tau = theta_b - 0.6 * i / 50.0;
      const double height =
          rb * (std::cos(tau) - (theta_b - tau) * std::sin(tau)) - rb * std::cos(theta_b);
      const double half_thickness = rb * (std::sin(tau) + (theta_b - tau) * std::cos(tau));
      CAPTURE(tau);
      // The root r is solved to 4 ulps; y = r sin psi(r) amplifies that by
      // r psi'(r) / tan psi, up to ~100 near the pointed tip where psi -> 0.
      CHECK(relative_difference(section_half_thickness(tooth, height), half_thickness) < 1e-12);
    }
  }
}

TEST_CASE("harness: (20),(21) by four quadratures and (16)-(19) by the x-form agree") {
  int compared = 0;
  for (const NamedPair& named : harness_pairs()) {
    const GearPair& pair = named.pair;
    const ContactSegment segment = contact_segment(pair);
    const double lp = line_of_action_length(pair);
    std::array<Worst, all_methods.size()> worst_vs_qag{};
    for (int i = 0; i <= 24; ++i) {
      const double x1 = segment.start_m + (segment.end_m - segment.start_m) * i / 24.0;
      for (Gear gear : {Gear::one, Gear::two}) {
        const double x = gear == Gear::one ? x1 : lp - x1;
        std::array<Compliances, all_methods.size()> c{};
        for (std::size_t m = 0; m < all_methods.size(); ++m) {
          const StiffnessModel model = with_method(StiffnessModel{}, all_methods[m], "method");
          c[m] = tooth_compliance(tooth_of(pair, gear), x, pair.youngs_modulus_pa,
                                  pair.face_width_m, model);
        }
        const std::string where = named.name + ", gear " + (gear == Gear::one ? "1" : "2") +
                                  ", X1 = " + format_number(x1) + " m";
        for (std::size_t a = 0; a < all_methods.size(); ++a) {
          for (std::size_t b = a + 1; b < all_methods.size(); ++b) {
            CAPTURE(where);
            CAPTURE(all_methods[a]);
            CAPTURE(all_methods[b]);
            CHECK(relative_difference(c[a].of(Term::bending), c[b].of(Term::bending)) <
                  harness_bound);
            CHECK(relative_difference(c[a].of(Term::axial), c[b].of(Term::axial)) < harness_bound);
            ++compared;
          }
          record(worst_vs_qag[a], c[a].of(Term::bending), c[0].of(Term::bending),
                 where + " bending");
          record(worst_vs_qag[a], c[a].of(Term::axial), c[0].of(Term::axial), where + " axial");
        }
      }
    }
    for (std::size_t m = 1; m < all_methods.size(); ++m) {
      MESSAGE(named.name << ": worst |" << all_methods[m] << " - gsl| / max = "
                         << worst_vs_qag[m].difference << " at " << worst_vs_qag[m].where);
    }
  }
  CHECK(compared > 1000);
}

TEST_CASE("harness: the flipped Fa h moment, tau-form integrand against the x-form") {
  // The flipped integrand is algebra of its own in bending_integrand; the
  // x-form applies the sign to M = Fb (l - x) + Fa h directly.
  const GearPair pair = paper_gear_pair();
  const ContactSegment segment = contact_segment(pair);
  const double lp = line_of_action_length(pair);
  for (int i = 0; i <= 12; ++i) {
    const double x1 = segment.start_m + (segment.end_m - segment.start_m) * i / 12.0;
    for (Gear gear : {Gear::one, Gear::two}) {
      const double x = gear == Gear::one ? x1 : lp - x1;
      StiffnessModel tau_form;
      tau_form.moment_sign = AxialMomentSign::flipped;
      StiffnessModel x_form = tau_form;
      x_form.route = StiffnessRoute::x_form;
      const InvoluteTooth tooth = tooth_of(pair, gear);
      const Compliances a =
          tooth_compliance(tooth, x, pair.youngs_modulus_pa, pair.face_width_m, tau_form);
      const Compliances b =
          tooth_compliance(tooth, x, pair.youngs_modulus_pa, pair.face_width_m, x_form);
      CAPTURE(x1);
      CHECK(relative_difference(a.of(Term::bending), b.of(Term::bending)) < harness_bound);
      // Adding Fa h where phi > 0 (h > 0 everywhere on the flank) can only
      // raise the moment's magnitude near the root: more compliant.
      const Compliances physical =
          tooth_compliance(tooth, x, pair.youngs_modulus_pa, pair.face_width_m);
      if (contact_angle(pair, gear, x1) > 0.0) {
        CHECK(a.of(Term::bending) > physical.of(Term::bending));
      }
      CHECK(a.of(Term::axial) == physical.of(Term::axial));
    }
  }
}

TEST_CASE(
    "limit: a contact just above the base circle, 1/Kb -> 3 X^2 sin 2theta_b / (8 E L Rb^2)") {
  // As X -> 0: l -> X^2 cos theta_b / (2 Rb), phi -> -theta_b, h -> Rb sin theta_b,
  // so the moment tends to F Rb sin^2 theta_b over a section of half thickness
  // Rb sin theta_b: 1/Kb -> M^2 l / (E I) = 3 X^2 sin theta_b cos theta_b / (4 E L Rb^2)
  // and, with sin^2 phi -> sin^2 theta_b, 1/Ka -> X^2 sin theta_b cos theta_b / (4 E L Rb^2).
  const GearPair pair = paper_gear_pair();
  for (Gear gear : {Gear::one, Gear::two}) {
    const InvoluteTooth tooth = tooth_of(pair, gear);
    const double rb = tooth.base_radius_m;
    const double theta_b = tooth.half_tooth_angle_rad;
    const double x = 1e-7;
    const double axial_limit = x * x * std::sin(theta_b) * std::cos(theta_b) /
                               (4.0 * pair.youngs_modulus_pa * pair.face_width_m * rb * rb);
    const Compliances c = tooth_compliance(tooth, x, pair.youngs_modulus_pa, pair.face_width_m);
    // Leading-order limits; the first correction is of order X / (Rb theta_b),
    // 6e-5 for gear 1, times coefficients of a few.
    CHECK(relative_difference(c.of(Term::bending), 3.0 * axial_limit) < 1e-3);
    CHECK(relative_difference(c.of(Term::axial), axial_limit) < 1e-3);
  }
  CHECK_THROWS_AS(
      tooth_compliance(tooth_of(pair, Gear::one), 0.0, pair.youngs_modulus_pa, pair.face_width_m),
      InputError);
}

TEST_CASE("(29) series stiffness and (5),(16),(17),(28) energies: U = F^2 / (2 Ke)") {
  const GearPair pair = paper_gear_pair();
  const MeshStiffness k = mesh_stiffness(pair, pitch_point_position(pair));
  CHECK(k.ke < k.stiffness(Term::hertz));
  CHECK(k.ke < k.stiffness(Term::bending, Gear::one));
  CHECK(k.ke < k.stiffness(Term::bending, Gear::two));
  const double force = 123.0;
  const ElasticEnergy u = pair_energy(k.included, force);
  // (28): the terms add up to the energy of the series spring of (29).
  CHECK(relative_difference(u.total_j(), force * force / (2.0 * k.ke)) < 1e-14);
  CHECK(relative_difference(u.of(Term::hertz), force * force / (2.0 * k.stiffness(Term::hertz))) <
        1e-15);
  // (30) F = Ke delta: the stored energy is also Ke delta^2 / 2.
  const double delta = force / k.ke;
  CHECK(relative_difference(u.total_j(), 0.5 * k.ke * delta * delta) < 1e-14);
}

TEST_CASE("pairs in parallel share a load by equal deflection") {
  const GearPair pair = paper_gear_pair();
  const ContactSegment segment = contact_segment(pair);
  const MeshStiffness a = mesh_stiffness(pair, segment.start_m + 1e-4);
  const MeshStiffness b = mesh_stiffness(pair, segment.start_m + 1e-4 + base_pitch(pair));
  const double total_force = 500.0;
  // Parallel springs under one deflection: delta = W / (Ka + Kb), and each
  // pair stores Ke_j delta^2 / 2.
  const double delta = total_force / (a.ke + b.ke);
  const ElasticEnergy shared = shared_load_energy({a, b}, total_force);
  CHECK(relative_difference(shared.total_j(), 0.5 * (a.ke + b.ke) * delta * delta) < 1e-14);
}

TEST_CASE("contact positions outside (0, lp) are refused with the allowed range") {
  const GearPair pair = paper_gear_pair();
  try {
    mesh_stiffness(pair, line_of_action_length(pair));
    FAIL("no error for X1 = lp");
  } catch (const InputError& e) {
    CHECK(e.field() == "contact position X1");
    CHECK(std::string(e.what()).find("(0, lp)") != std::string::npos);
  }
  CHECK_THROWS_AS(mesh_stiffness(pair, std::nan("")), InputError);
  CHECK_THROWS_AS(with_method(StiffnessModel{}, "simpson", "method"), InputError);
}

TEST_CASE("(29) with terms switched off: Ke is the series of the terms left on") {
  const GearPair pair = paper_gear_pair();
  const double x1 = pitch_point_position(pair);
  const MeshStiffness all = mesh_stiffness(pair, x1);
  StiffnessModel no_bending;
  no_bending.terms.set(Term::bending, false);
  const MeshStiffness k = mesh_stiffness(pair, x1, no_bending);
  // The individual stiffnesses do not depend on which enter (29).
  CHECK(k.stiffness(Term::bending, Gear::one) == all.stiffness(Term::bending, Gear::one));
  CHECK(k.stiffness(Term::axial, Gear::two) == all.stiffness(Term::axial, Gear::two));
  CHECK(relative_difference(k.ke, 1.0 / (1.0 / k.stiffness(Term::hertz) +
                                         1.0 / k.stiffness(Term::axial, Gear::one) +
                                         1.0 / k.stiffness(Term::axial, Gear::two))) < 1e-15);
  StiffnessModel hertz_only;
  hertz_only.terms.set(Term::bending, false);
  hertz_only.terms.set(Term::axial, false);
  CHECK(mesh_stiffness(pair, x1, hertz_only).ke == all.stiffness(Term::hertz));
  StiffnessModel none = hertz_only;
  none.terms.set(Term::hertz, false);
  try {
    mesh_stiffness(pair, x1, none);
    FAIL("no error with every term off");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("at least one") != std::string::npos);
  }
}
