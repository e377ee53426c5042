// A spall or a chipped tip in one tooth (surface_faults.hpp;
// docs/stiffness-models.md, "A spall or a chipped tip in one tooth"): the
// sections against closed forms written here, the parallel-axis theorem
// against the expression first stated for I, a fault that removes nothing as the
// healthy tooth to the bit, the two routes on faulted teeth, monotonic loss of
// stiffness, the Hertzian length of a full-width spall and the end of contact
// of a full-width chip, and the refusals.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"
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

// The half thickness of the rack-cut involute at radius r, from
// x = r_b [(tau + theta_b) cos tau - sin tau] with tau + theta_b = L / r_b.
double involute_half_thickness(const RackGearGeometry& g, double r) {
  const double roll = std::sqrt(r * r - g.base_radius_m * g.base_radius_m) / g.base_radius_m;
  const double tau = roll - g.half_tooth_angle_base_rad;
  return g.base_radius_m * (roll * std::cos(tau) - std::sin(tau));
}

// A spall over the middle of the involute, half the face wide, `share` of
// the depth that reaches the centre line at its thinner end.
Spall middle_spall(const RackGearGeometry& g, double b, double share) {
  Spall s;
  s.start_radius_m = g.form_radius_m + 0.3 * (g.tip_radius_m - g.form_radius_m);
  s.end_radius_m = g.form_radius_m + 0.6 * (g.tip_radius_m - g.form_radius_m);
  s.width_m = 0.4 * b;
  s.depth_m = share * std::min(involute_half_thickness(g, s.start_radius_m),
                               involute_half_thickness(g, s.end_radius_m));
  return s;
}

TipChip upper_chip(const RackGearGeometry& g, double b, double width_share) {
  return {g.form_radius_m + 0.7 * (g.tip_radius_m - g.form_radius_m), width_share * b};
}

const ToothContact& contact_of(const PairContact& c, int gear_index) {
  return gear_index == 0 ? c.gear1 : c.gear2;
}

}  // namespace

TEST_CASE("sections: the spall's and the chip's against their closed forms") {
  // A pit d_s deep over b_s of the face: the slices across it span [-x, x - d_s],
  // t = 2x - d_s high, centroid at -d_s/2. About its own centroid a slice has
  // t^3/12 (as the crack layer's slices), the others (2x)^3/12. The library
  // computes the same from healthy_section(x, b - b_s), so only rounding
  // separates them: 1e-14 leaves a few ulps.
  constexpr double bound = 1e-14;
  const double b = 10e-3;
  for (double x : {0.4e-3, 1.1e-3, 2.0e-3}) {
    for (double d : {0.05e-3, 0.2e-3, 0.39e-3}) {
      for (double b_s : {1e-3, 4e-3, b}) {
        CAPTURE(x);
        CAPTURE(d);
        CAPTURE(b_s);
        const Spall spall{CrackFlank::loaded, 0.0, 0.0, b_s, d};
        const SectionProperties s = spalled_section(spall, x, b);
        const double t = 2.0 * x - d;
        const double area = 2.0 * x * b - b_s * d;
        const double inertia = 2.0 / 3.0 * x * x * x * (b - b_s) + b_s * t * t * t / 12.0;
        CHECK(relative_difference(s.area_m2, area) <= bound);
        CHECK(relative_difference(s.second_moment_m4, inertia) <= bound);
        // I -= b_s (x^3 - (x - d_s)^3) / 3, as the reading was first stated,
        // removes the pit's moment about the healthy centre line and leaves
        // the cut slices their moment about that line, b_s (x^3 + (x -
        // d_s)^3) / 3. By the parallel-axis theorem that is their moment about
        // their centroid plus t (d_s/2)^2 each: the expression overstates I by
        // b_s t d_s^2 / 4. (1e-12: x^3 - (x - d_s)^3 cancels up to x / d_s,
        // 40 here, of the last digits.)
        const double about_centre_line =
            2.0 / 3.0 * x * x * x * b - b_s * (x * x * x - (x - d) * (x - d) * (x - d)) / 3.0;
        CHECK(relative_difference(about_centre_line - b_s * t * d * d / 4.0, inertia) <= 1e-12);
        CHECK(about_centre_line > s.second_moment_m4);
      }
    }
  }
  // A full-width pit is the crack layer's uniform crack that starts at this
  // section's side (h_c = x) and reaches d_s into it: an independent path
  // through cracked_section.
  for (double x : {0.8e-3, 1.9e-3}) {
    const double d = 0.3e-3;
    const double nu = 40.0 * degree;
    RootCrack crack;
    crack.depth_m = d / std::sin(nu);
    crack.angle_rad = nu;
    const SectionProperties c = cracked_section(crack, x, x, b);
    const SectionProperties s = spalled_section({CrackFlank::loaded, 0.0, 0.0, b, d}, x, b);
    CHECK(relative_difference(s.area_m2, c.area_m2) <= 1e-14);
    CHECK(relative_difference(s.second_moment_m4, c.second_moment_m4) <= 1e-14);
  }
  // A chip leaves b - b_k of every section above r_k.
  for (double b_k : {2e-3, 7.5e-3}) {
    const double x = 0.9e-3;
    const SectionProperties s = chipped_section({20e-3, b_k}, x, b);
    CHECK(relative_difference(s.area_m2, 2.0 * x * (b - b_k)) <= bound);
    CHECK(relative_difference(s.second_moment_m4, 2.0 / 3.0 * x * x * x * (b - b_k)) <= bound);
  }
}

TEST_CASE("a fault that removes nothing is the healthy tooth to the bit, on every model") {
  const GearPair paper = verify::ross_pair_a();
  const RackGearPairGeometry pair = rack_gear_pair_geometry(paper);
  const double b = pair.contact_width_m;
  for (StiffnessModelKind kind :
       {StiffnessModelKind::potential_energy, StiffnessModelKind::ross_compatible}) {
    for (StiffnessRoute route : {StiffnessRoute::tau_form, StiffnessRoute::x_form}) {
      const StiffnessModel model = model_of(kind, route);
      for (int gi = 0; gi < 2; ++gi) {
        const RackGearGeometry& g = gi == 0 ? pair.gear1 : pair.gear2;
        const Gear which = gi == 0 ? Gear::one : Gear::two;
        const Spall no_pit = middle_spall(g, b, 0.0);
        const TipChip at_tip{g.tip_radius_m, b};
        for (double s : positions(pair, 4)) {
          const ToothContact c = contact_of(pair_contact(pair, s), gi);
          const ToothCompliances healthy = tooth_compliances(g, which, c, b, model);
          for (const ToothCompliances& f :
               {spalled_tooth_compliances(g, which, c, b, model, no_pit),
                chipped_tooth_compliances(g, which, c, b, model, at_tip)}) {
            CHECK(f.bending_m_per_n == healthy.bending_m_per_n);
            CHECK(f.shear_m_per_n == healthy.shear_m_per_n);
            CHECK(f.axial_m_per_n == healthy.axial_m_per_n);
            CHECK(f.foundation_m_per_n == healthy.foundation_m_per_n);
          }
          CHECK(spall_contact_length(no_pit, CrackFlank::loaded, c.radius_m, b) == b);
          CHECK(chip_contact_length(at_tip, c.radius_m, b) == b);
          // A shallow pit, 1 nm, by the faulted path: more compliant, and by
          // no more than the largest relative loss of I in the band,
          // 3 d_s / (2 x) of the pit's share b_s / b of the face at the
          // thinner end (first order in d_s; 1 % for the higher orders and
          // the rounding of the split flank).
          Spall tiny = no_pit;
          tiny.depth_m = 1e-9;
          const double x_min = std::min(involute_half_thickness(g, tiny.start_radius_m),
                                        involute_half_thickness(g, tiny.end_radius_m));
          const ToothCompliances t = spalled_tooth_compliances(g, which, c, b, model, tiny);
          // Below the band its sections are not in the beam: the same pieces.
          if (c.radius_m > tiny.start_radius_m) {
            CHECK(t.total_m_per_n() > healthy.total_m_per_n());
          } else {
            CHECK(relative_difference(t.total_m_per_n(), healthy.total_m_per_n()) <= 1e-15);
          }
          CHECK(relative_difference(t.total_m_per_n(), healthy.total_m_per_n()) <=
                1.01 * 1.5 * tiny.depth_m / x_min * tiny.width_m / b);
        }
      }
    }
  }
  // The paper's tooth (yang-lin-1987), both routes.
  const ContactSegment segment = contact_segment(paper);
  const double lp = line_of_action_length(paper);
  for (StiffnessRoute route : {StiffnessRoute::tau_form, StiffnessRoute::x_form}) {
    StiffnessModel m;
    m.route = route;
    for (Gear which : {Gear::one, Gear::two}) {
      const InvoluteTooth tooth = tooth_of(paper, which);
      const double ra = tip_radius(paper, which);
      const Spall no_pit{CrackFlank::loaded, 0.5 * (tooth.base_radius_m + ra), ra,
                         paper.face_width_m, 0.0};
      for (int i = 0; i <= 4; ++i) {
        const double x1 = segment.start_m + (segment.end_m - segment.start_m) * i / 4.0;
        const double x = which == Gear::one ? x1 : lp - x1;
        const Compliances healthy =
            tooth_compliance(tooth, x, youngs_modulus(paper, which), paper.face_width_m, m);
        const Compliances s = spalled_paper_tooth_compliances(paper, which, x, m, no_pit);
        const Compliances c =
            chipped_paper_tooth_compliances(paper, which, x, m, {ra, paper.face_width_m});
        for (Term term : {Term::bending, Term::axial}) {
          CHECK(s.of(term) == healthy.of(term));
          CHECK(c.of(term) == healthy.of(term));
        }
      }
    }
  }
  // Hertz over the whole face is (4) to the bit.
  CHECK(hertz_stiffness(paper, paper.face_width_m) == hertz_stiffness(paper));
}

TEST_CASE("two routes: spalled and chipped rack-cut teeth agree to 1e-10 as healthy ones do") {
  // As for the crack (test_root_crack): each route meets 1e-12 by its own
  // estimate and they share only the flank's points and the sections; the
  // flank is cut where the section jumps (the band's ends, r_k), so both
  // integrate smooth pieces and 1e-10 holds with room.
  constexpr double bound = 1e-10;
  double worst = 0.0;
  for (const auto& named : verify::varied_rack_pairs()) {
    const RackGearPairGeometry pair = rack_gear_pair_geometry(named.pair);
    const double b = pair.contact_width_m;
    for (int gi = 0; gi < 2; ++gi) {
      const RackGearGeometry& g = gi == 0 ? pair.gear1 : pair.gear2;
      const Gear which = gi == 0 ? Gear::one : Gear::two;
      const Spall spall = middle_spall(g, b, 0.5);
      const TipChip chip = upper_chip(g, b, 0.5);
      const TipChip fillet_chip{0.5 * (g.root_radius_m + g.form_radius_m), 0.3 * b};
      const std::vector<double> s_all = positions(pair, 6);
      for (std::size_t i = 0; i < s_all.size(); ++i) {
        const double s = s_all[i];
        const ToothContact c = contact_of(pair_contact(pair, s), gi);
        // The two models share the beam: each on every other position.
        const StiffnessModelKind kind =
            i % 2 == 0 ? StiffnessModelKind::potential_energy : StiffnessModelKind::ross_compatible;
        const StiffnessModel tau = model_of(kind);
        const StiffnessModel xf = model_of(kind, StiffnessRoute::x_form);
        const ToothCompliances a[3] = {spalled_tooth_compliances(g, which, c, b, tau, spall),
                                       chipped_tooth_compliances(g, which, c, b, tau, chip),
                                       chipped_tooth_compliances(g, which, c, b, tau, fillet_chip)};
        const ToothCompliances x[3] = {spalled_tooth_compliances(g, which, c, b, xf, spall),
                                       chipped_tooth_compliances(g, which, c, b, xf, chip),
                                       chipped_tooth_compliances(g, which, c, b, xf, fillet_chip)};
        CAPTURE(named.name);
        CAPTURE(gi);
        CAPTURE(s);
        for (int k = 0; k < 3; ++k) {
          CAPTURE(k);
          for (double d : {relative_difference(a[k].bending_m_per_n, x[k].bending_m_per_n),
                           relative_difference(a[k].shear_m_per_n, x[k].shear_m_per_n),
                           relative_difference(a[k].axial_m_per_n, x[k].axial_m_per_n)}) {
            CHECK(d <= bound);
            worst = std::max(worst, d);
          }
        }
      }
    }
  }
  MESSAGE("two routes on spalled and chipped rack-cut teeth: worst relative difference " << worst);
}

TEST_CASE("two routes: the paper's spalled and chipped tooth agree to 1e-10") {
  // The tau-form (over the involute parameter, cut at tau = theta_b - L/Rb) and
  // the x-form (over the centre line, cut at the heights r cos psi(r) - Rb cos
  // theta_b) share only the sections; 1e-10 as for the healthy harness.
  constexpr double bound = 1e-10;
  const GearPair pair = paper_gear_pair();
  const ContactSegment segment = contact_segment(pair);
  const double lp = line_of_action_length(pair);
  const double b = pair.face_width_m;
  double worst = 0.0;
  for (Gear which : {Gear::one, Gear::two}) {
    const InvoluteTooth tooth = tooth_of(pair, which);
    const double rb = tooth.base_radius_m;
    const double ra = tip_radius(pair, which);
    Spall spall{CrackFlank::loaded, rb + 0.35 * (ra - rb), rb + 0.65 * (ra - rb), 0.5 * b, 0.0};
    spall.depth_m =
        0.5 * spall.end_radius_m * std::sin(flank_half_angle(tooth, spall.end_radius_m));
    const TipChip chip{rb + 0.75 * (ra - rb), 0.4 * b};
    for (int i = 0; i <= 8; ++i) {
      const double x1 = segment.start_m + (segment.end_m - segment.start_m) * i / 8.0;
      const double x = which == Gear::one ? x1 : lp - x1;
      StiffnessModel tau;
      StiffnessModel xf;
      xf.route = StiffnessRoute::x_form;
      const Compliances healthy = tooth_compliance(tooth, x, pair.youngs_modulus_pa, b, tau);
      const Compliances sa = spalled_paper_tooth_compliances(pair, which, x, tau, spall);
      const Compliances sx = spalled_paper_tooth_compliances(pair, which, x, xf, spall);
      const Compliances ca = chipped_paper_tooth_compliances(pair, which, x, tau, chip);
      const Compliances cx = chipped_paper_tooth_compliances(pair, which, x, xf, chip);
      CAPTURE(x1);
      CHECK(sa.of(Term::bending) >= healthy.of(Term::bending));
      for (double d : {relative_difference(sa.of(Term::bending), sx.of(Term::bending)),
                       relative_difference(sa.of(Term::axial), sx.of(Term::axial)),
                       relative_difference(ca.of(Term::bending), cx.of(Term::bending)),
                       relative_difference(ca.of(Term::axial), cx.of(Term::axial))}) {
        CHECK(d <= bound);
        worst = std::max(worst, d);
      }
    }
  }
  MESSAGE("paper's tooth, two routes on spalled and chipped teeth: worst relative difference "
          << worst);
}

TEST_CASE("the paper's tooth: deeper pits and lower chips weaken it; a full chip ends it") {
  const GearPair pair = paper_gear_pair();
  const InvoluteTooth tooth = tooth_of(pair, Gear::one);
  const double rb = tooth.base_radius_m;
  const double ra = tip_radius(pair, Gear::one);
  const double b = pair.face_width_m;
  const double x_tip = contact_segment(pair).end_m;
  StiffnessModel m;
  Spall spall{CrackFlank::loaded, rb + 0.3 * (ra - rb), rb + 0.6 * (ra - rb), 0.5 * b, 0.0};
  const double x_end = spall.end_radius_m * std::sin(flank_half_angle(tooth, spall.end_radius_m));
  double previous = tooth_compliance(tooth, x_tip, pair.youngs_modulus_pa, b, m).total_m_per_n();
  for (int i = 1; i <= 4; ++i) {
    spall.depth_m = 0.2 * i * x_end;
    const double c =
        spalled_paper_tooth_compliances(pair, Gear::one, x_tip, m, spall).total_m_per_n();
    CAPTURE(i);
    CHECK(c > previous);
    previous = c;
  }
  previous = tooth_compliance(tooth, x_tip, pair.youngs_modulus_pa, b, m).total_m_per_n();
  for (int i = 9; i >= 1; --i) {
    const TipChip chip{rb + 0.1 * i * (ra - rb), 0.5 * b};
    const double c =
        chipped_paper_tooth_compliances(pair, Gear::one, x_tip, m, chip).total_m_per_n();
    CAPTURE(i);
    CHECK(c > previous);
    previous = c;
  }
  const TipChip full{rb + 0.5 * (ra - rb), b};
  const std::optional<ContactSegment> seg = chipped_contact_segment(pair, Gear::one, full);
  REQUIRE(seg);
  CHECK(std::isfinite(
      chipped_paper_tooth_compliances(pair, Gear::one, seg->end_m, m, full).total_m_per_n()));
  verify::check_refused([&] { chipped_paper_tooth_compliances(pair, Gear::one, x_tip, m, full); },
                        "contact radius", std::string("<= r_k = ") + format_number(full.radius_m));
}

TEST_CASE("stiffness falls monotonically with d_s, with b_s, and as r_k falls") {
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  const RackGearGeometry& g = pair.gear1;
  const double b = pair.contact_width_m;
  const StiffnessModel model = model_of(StiffnessModelKind::potential_energy);
  // Contacts above the band (its sections are in the beam) and the tip.
  const Spall probe = middle_spall(g, b, 0.0);
  int above_band = 0;
  for (double s : positions(pair, 8)) {
    const ToothContact c = pair_contact(pair, s).gear1;
    if (!(c.radius_m > probe.end_radius_m)) continue;
    ++above_band;
    CAPTURE(s);
    double previous = tooth_stiffness(tooth_compliances(g, Gear::one, c, b, model));
    for (int i = 1; i <= 9; ++i) {
      const double k = tooth_stiffness(
          spalled_tooth_compliances(g, Gear::one, c, b, model, middle_spall(g, b, 0.1 * i)));
      CAPTURE(i);
      CHECK(k < previous);
      previous = k;
    }
    Spall wide = middle_spall(g, b, 0.5);
    previous = tooth_stiffness(tooth_compliances(g, Gear::one, c, b, model));
    for (int i = 1; i <= 5; ++i) {
      wide.width_m = 0.2 * i * b;
      const double k = tooth_stiffness(spalled_tooth_compliances(g, Gear::one, c, b, model, wide));
      CAPTURE(i);
      CHECK(k < previous);
      previous = k;
    }
  }
  CHECK(above_band >= 3);
  // Inside the band the Hertzian length falls with b_s too, to 0 at b_s = b.
  const Spall mid = middle_spall(g, b, 0.5);
  const double r_in = 0.5 * (mid.start_radius_m + mid.end_radius_m);
  double previous_length = b;
  for (int i = 1; i <= 5; ++i) {
    Spall w = mid;
    w.width_m = 0.2 * i * b;
    const double length = spall_contact_length(w, CrackFlank::loaded, r_in, b);
    CHECK(length < previous_length);
    previous_length = length;
  }
  CHECK(previous_length == 0.0);
  // The pinion's tip contact (EAP) lies above every r_k: a lower chip takes
  // more sections away from its beam.
  const ToothContact tip = pair_contact(pair, pair.end_of_active_profile_m).gear1;
  double previous = tooth_stiffness(tooth_compliances(g, Gear::one, tip, b, model));
  for (int i = 9; i >= 1; --i) {
    const TipChip chip{g.root_radius_m + 0.1 * i * (g.tip_radius_m - g.root_radius_m), 0.5 * b};
    const double k = tooth_stiffness(chipped_tooth_compliances(g, Gear::one, tip, b, model, chip));
    CAPTURE(i);
    CHECK(k < previous);
    previous = k;
  }
}

TEST_CASE("a full-width spall: no Hertzian length inside its band, on its flank only") {
  const GearPair paper = verify::ross_pair_a();
  const RackGearPairGeometry pair = rack_gear_pair_geometry(paper);
  const double b = pair.contact_width_m;
  Spall spall = middle_spall(pair.gear1, b, 0.3);
  spall.width_m = b;
  const double r1 = spall.start_radius_m;
  const double r2 = spall.end_radius_m;
  // Inside: L = 0, so Kh = 0 and the pair carries nothing; outside: the face.
  for (double r : {r1, 0.5 * (r1 + r2), r2}) {
    CHECK(spall_contact_length(spall, CrackFlank::loaded, r, b) == 0.0);
    CHECK(hertz_stiffness(paper, spall_contact_length(spall, CrackFlank::loaded, r, b)) == 0.0);
  }
  for (double r : {0.999 * r1, 1.001 * r2})
    CHECK(spall_contact_length(spall, CrackFlank::loaded, r, b) == b);
  // Half the face: half of (4).
  Spall half = spall;
  half.width_m = 0.5 * b;
  CHECK(relative_difference(
            hertz_stiffness(paper, spall_contact_length(half, CrackFlank::loaded, r1, b)),
            0.5 * hertz_stiffness(paper)) <= 1e-15);
  // A contact on the other flank meets no pit; the beam still loses it.
  Spall other = spall;
  other.flank = CrackFlank::unloaded;
  CHECK(spall_contact_length(other, CrackFlank::loaded, 0.5 * (r1 + r2), b) == b);
  CHECK(spall_contact_length(other, CrackFlank::unloaded, 0.5 * (r1 + r2), b) == 0.0);
  CHECK(spall_contact_length(spall, CrackFlank::unloaded, 0.5 * (r1 + r2), b) == b);
  const ToothContact c = pair_contact(pair, pair.end_of_active_profile_m).gear1;
  const StiffnessModel model = model_of(StiffnessModelKind::potential_energy);
  CHECK(spalled_tooth_compliances(pair.gear1, Gear::one, c, b, model, other).total_m_per_n() ==
        spalled_tooth_compliances(pair.gear1, Gear::one, c, b, model, spall).total_m_per_n());
}

TEST_CASE("a full-width chip ends the contact at r_k; a partial one keeps the segment") {
  const GearPair paper = verify::ross_pair_a();
  const RackGearPairGeometry pair = rack_gear_pair_geometry(paper);
  const double b = pair.contact_width_m;
  const ContactSegment healthy = contact_segment(paper);
  const StiffnessModel model = model_of(StiffnessModelKind::potential_energy);
  for (int gi = 0; gi < 2; ++gi) {
    const Gear which = gi == 0 ? Gear::one : Gear::two;
    const RackGearGeometry& g = gi == 0 ? pair.gear1 : pair.gear2;
    const TipChip chip{g.tip_radius_m - 0.6e-3, b};
    const PlacedChip placed = place_chip(chip, g, b);
    CHECK(placed.contact_end_radius_m == chip.radius_m);
    const std::optional<ContactSegment> seg = chipped_contact_segment(paper, which, chip);
    REQUIRE(seg);
    // The pinion leaves early, the wheel enters late; the other end stays.
    const double s_end = gi == 0 ? seg->end_m : seg->start_m;
    CHECK((gi == 0 ? seg->start_m == healthy.start_m : seg->end_m == healthy.end_m));
    CHECK((gi == 0 ? seg->end_m < healthy.end_m : seg->start_m > healthy.start_m));
    // There the tooth's contact point lies on r_k (exact kinematics of the
    // rack pair, an independent computation of the same point).
    const ToothContact at_end = contact_of(pair_contact(pair, s_end), gi);
    CHECK(relative_difference(at_end.radius_m, chip.radius_m) <= 1e-14);
    CHECK(chip_contact_length(chip, at_end.radius_m, b) == b);
    CHECK(
        std::isfinite(chipped_tooth_compliances(g, which, at_end, b, model, chip).total_m_per_n()));
    // Beyond it no tooth is left.
    const double beyond = gi == 0 ? pair.end_of_active_profile_m : pair.start_of_active_profile_m;
    const ToothContact past = contact_of(pair_contact(pair, beyond), gi);
    CHECK(chip_contact_length(chip, past.radius_m, b) == 0.0);
    verify::check_refused([&] { chipped_tooth_compliances(g, which, past, b, model, chip); },
                          "contact radius",
                          std::string("<= r_k = ") + format_number(chip.radius_m));
    // Half the face: the segment stays, the contact above r_k has half the length.
    const TipChip half{chip.radius_m, 0.5 * b};
    CHECK(place_chip(half, g, b).contact_end_radius_m == g.tip_radius_m);
    const std::optional<ContactSegment> whole = chipped_contact_segment(paper, which, half);
    REQUIRE(whole);
    CHECK(whole->start_m == healthy.start_m);
    CHECK(whole->end_m == healthy.end_m);
    CHECK(chip_contact_length(half, past.radius_m, b) == 0.5 * b);
    // Chipped below the base circle over the whole face: no contact at all.
    if (g.root_radius_m < g.base_radius_m) {
      CHECK(!chipped_contact_segment(paper, which, {0.5 * (g.root_radius_m + g.base_radius_m), b}));
    }
  }
}

TEST_CASE("refusals name the field and its limit") {
  const GearPair paper = verify::ross_pair_a();
  const RackGearPairGeometry pair = rack_gear_pair_geometry(paper);
  const RackGearGeometry& g = pair.gear1;
  const double b = pair.contact_width_m;
  const Spall ok = middle_spall(g, b, 0.5);
  Spall s = ok;
  s.start_radius_m = 0.5 * (g.root_radius_m + g.form_radius_m);
  verify::check_refused([&] { place_spall(s, g, b); }, "spall start radius",
                        std::string("[") + format_number(g.form_radius_m) + ", ");
  s = ok;
  s.end_radius_m = g.tip_radius_m + 1e-4;
  verify::check_refused([&] { place_spall(s, g, b); }, "spall end radius",
                        format_number(g.tip_radius_m) + "] m");
  s = ok;
  s.end_radius_m = s.start_radius_m;
  verify::check_refused([&] { place_spall(s, g, b); }, "spall end radius",
                        "above the spall's start");
  for (double w : {0.0, 1.01 * b}) {
    s = ok;
    s.width_m = w;
    verify::check_refused([&] { place_spall(s, g, b); }, "spall width b_s",
                          "(0, " + format_number(b) + "] m");
  }
  // The thinner end of the band is the limit of the depth.
  const double x_min = std::min(involute_half_thickness(g, ok.start_radius_m),
                                involute_half_thickness(g, ok.end_radius_m));
  s = ok;
  s.depth_m = x_min;
  verify::check_refused([&] { place_spall(s, g, b); }, "spall depth d_s",
                        std::string("d_s < x = ") + format_number(x_min));
  s.depth_m = -1e-6;
  verify::check_refused([&] { place_spall(s, g, b); }, "spall depth d_s", ">= 0 m");
  s.depth_m = 0.999 * x_min;
  CHECK_NOTHROW(place_spall(s, g, b));
  verify::check_refused(
      [&] {
        place_chip({g.root_radius_m, 0.5 * b}, g, b);
      },
      "chip radius r_k", std::string("(") + format_number(g.root_radius_m) + ", ");
  verify::check_refused(
      [&] {
        place_chip({g.tip_radius_m * 1.001, 0.5 * b}, g, b);
      },
      "chip radius r_k", format_number(g.tip_radius_m) + "] m");
  verify::check_refused(
      [&] {
        place_chip({g.form_radius_m, 1.5 * b}, g, b);
      },
      "chip width b_k", "(0, " + format_number(b) + "] m");
  // The paper's tooth starts at its base circle.
  const double rb = base_radius(paper, Gear::one);
  verify::check_refused(
      [&] {
        place_chip({0.99 * rb, 0.5 * b}, paper, Gear::one);
      },
      "chip radius r_k", std::string("(") + format_number(rb) + ", ");
  verify::check_refused(
      [&] {
        place_spall({CrackFlank::loaded, 0.99 * rb, tip_radius(paper, Gear::one), 0.5 * b, 1e-5},
                    paper, Gear::one);
      },
      "spall start radius", std::string("[") + format_number(rb) + ", ");
  // The paper's model has no rack-cut tooth.
  const ToothContact c = pair_contact(pair, pair.end_of_active_profile_m).gear1;
  verify::check_refused(
      [&] {
        spalled_tooth_compliances(g, Gear::one, c, b, model_of(StiffnessModelKind::yang_lin_1987),
                                  ok);
      },
      "stiffness_model", "potential-energy");
  verify::check_refused([&] { hertz_stiffness(paper, 1.1 * paper.face_width_m); }, "contact length",
                        "within the face width");
}

TEST_CASE("record: single-tooth stiffness loss of the paper's pinion, spall and chip") {
  // Potential-energy model, the paper's pair with bores 20/60 mm; the tooth
  // stiffness 1 / (bending + shear + axial + foundation) of pinion tooth 1 and
  // the pair's 1 / (1/Kh(L) + both teeth) against the healthy ones.
  const GearPair paper = verify::ross_pair_a();
  const RackGearPairGeometry pair = rack_gear_pair_geometry(paper);
  const RackGearGeometry& g = pair.gear1;
  const double b = pair.contact_width_m;
  const StiffnessModel model = model_of(StiffnessModelKind::potential_energy);
  const double rb = g.base_radius_m;
  const double s_pitch = rb * std::tan(pair.operating_pressure_angle_rad);
  const double s_tip = pair.end_of_active_profile_m;
  const auto healthy_tooth = [&](double s) {
    return tooth_compliances(g, Gear::one, pair_contact(pair, s).gear1, b, model).total_m_per_n();
  };
  const auto wheel = [&](double s) {
    return tooth_compliances(pair.gear2, Gear::two, pair_contact(pair, s).gear2, b, model)
        .total_m_per_n();
  };
  const double kh = hertz_stiffness(paper);
  // The spall: pitch point +- 0.5 mm of roll distance, half the face wide.
  Spall spall{CrackFlank::loaded, radius_at_roll_distance(rb, s_pitch - 0.5e-3),
              radius_at_roll_distance(rb, s_pitch + 0.5e-3), 0.5 * b, 0.0};
  MESSAGE("spall: r " << spall.start_radius_m << " .. " << spall.end_radius_m << " m, b_s = b/2");
  double previous = 0.0;
  for (double d : {0.05e-3, 0.1e-3, 0.2e-3, 0.4e-3}) {
    spall.depth_m = d;
    const auto tooth = [&](double s) {
      return spalled_tooth_compliances(g, Gear::one, pair_contact(pair, s).gear1, b, model, spall)
          .total_m_per_n();
    };
    const double loss_pitch = 1.0 - healthy_tooth(s_pitch) / tooth(s_pitch);
    const double loss_tip = 1.0 - healthy_tooth(s_tip) / tooth(s_tip);
    const double pair_h = 1.0 / (1.0 / kh + healthy_tooth(s_pitch) + wheel(s_pitch));
    const double length = spall_contact_length(spall, CrackFlank::loaded,
                                               pair_contact(pair, s_pitch).gear1.radius_m, b);
    const double pair_f =
        1.0 / (1.0 / hertz_stiffness(paper, length) + tooth(s_pitch) + wheel(s_pitch));
    MESSAGE("spall d_s = " << d * 1e3 << " mm: tooth loss at the pitch point " << 100.0 * loss_pitch
                           << " %, at the tip " << 100.0 * loss_tip
                           << " %; pair loss at the pitch point " << 100.0 * (1.0 - pair_f / pair_h)
                           << " %");
    CHECK(loss_tip > previous);
    previous = loss_tip;
  }
  previous = 0.0;
  for (double below_tip : {0.25e-3, 0.5e-3, 1.0e-3}) {
    const TipChip chip{g.tip_radius_m - below_tip, 0.5 * b};
    const double chipped =
        chipped_tooth_compliances(g, Gear::one, pair_contact(pair, s_tip).gear1, b, model, chip)
            .total_m_per_n();
    const double loss = 1.0 - healthy_tooth(s_tip) / chipped;
    const double pair_h = 1.0 / (1.0 / kh + healthy_tooth(s_tip) + wheel(s_tip));
    const double pair_f = 1.0 / (1.0 / hertz_stiffness(paper, 0.5 * b) + chipped + wheel(s_tip));
    const TipChip full{chip.radius_m, b};
    const std::optional<ContactSegment> seg = chipped_contact_segment(paper, Gear::one, full);
    MESSAGE("chip r_a - r_k = " << below_tip * 1e3 << " mm, b_k = b/2: tooth loss at the tip "
                                << 100.0 * loss << " %, pair loss there "
                                << 100.0 * (1.0 - pair_f / pair_h)
                                << " %; full width: the contact ends "
                                << (pair.end_of_active_profile_m - seg->end_m) * 1e3
                                << " mm before EAP");
    CHECK(loss > previous);
    previous = loss;
  }
}
