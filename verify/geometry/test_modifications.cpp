// Modifications and tooth errors as a gap per pair (docs/faults.md,
// "Modifications and errors"): the reliefs at their ends and in between by
// their closed forms, the signs of the per-tooth errors on either line, and
// the refusals across fields.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

// The diameter of a point at roll distance s on the base circle of radius rb:
// the inverse of the relief's own sqrt(r^2 - rb^2), so the ends are the ones
// the code computes to within a few ulps.
double diameter_at_roll(double rb, double s) {
  return 2.0 * std::sqrt(rb * rb + s * s);
}

// The allowed relative error of a gap near its ends: the roll distance comes
// back through sqrt(r^2 - rb^2) with a rounding of about 1e-16 of the ~1e-2 m
// positions, which a relief magnifies by (roll length)^-1 ~ 1e3 / m: well
// below 1e-9 of the amount in absolute terms.
constexpr double kEndTolerance_m = 1e-15;

}  // namespace

TEST_CASE(
    "a pinion tip relief is 0 at its start diameter and C_a at the tip, linear or parabolic") {
  const GearPair g = paper_gear_pair();
  const ContactSegment seg = contact_segment(g);
  const double rb1 = base_radius(g, Gear::one);
  const double c_a = 20e-6;
  // Start halfway along the single-pair zone's end and the tip.
  const double s_r = seg.end_m - 0.4 * (seg.end_m - seg.start_m - base_pitch(g));
  for (const ReliefShape shape : {ReliefShape::linear, ReliefShape::parabolic}) {
    Modifications m;
    m.gear1.tip = {c_a, diameter_at_roll(rb1, s_r), shape};
    REQUIRE_NOTHROW(validate_modifications(g, m));
    const ToothGaps gaps(g, m);
    CHECK(std::fabs(gaps.relief_m(Gear::one, s_r)) <= kEndTolerance_m);
    CHECK(gaps.relief_m(Gear::one, s_r - 1e-4) == 0.0);
    CHECK(relative_difference(gaps.relief_m(Gear::one, seg.end_m), c_a) < 1e-12);
    // Halfway along the relieved roll length: C/2 linear, C/4 parabolic.
    const double mid = gaps.relief_m(Gear::one, 0.5 * (s_r + seg.end_m));
    const double expected = shape == ReliefShape::linear ? 0.5 * c_a : 0.25 * c_a;
    CHECK(relative_difference(mid, expected) < 1e-9);
    // The wheel's teeth carry none of it.
    CHECK(gaps.relief_m(Gear::two, seg.end_m) == 0.0);
  }
}

TEST_CASE("a wheel tip relief is mirrored: C_a at X_start, 0 at its start diameter") {
  const GearPair g = paper_gear_pair();
  const ContactSegment seg = contact_segment(g);
  const double lp = line_of_action_length(g);
  const double rb2 = base_radius(g, Gear::two);
  const double c_a = 15e-6;
  // The wheel's roll distance at X is lp - X; its tip is at X_start.
  const double s_a2 = lp - seg.start_m;
  const double s_r2 = s_a2 - 0.3 * (seg.end_m - seg.start_m);
  Modifications m;
  m.gear2.tip = {c_a, diameter_at_roll(rb2, s_r2), ReliefShape::linear};
  REQUIRE_NOTHROW(validate_modifications(g, m));
  const ToothGaps gaps(g, m);
  CHECK(relative_difference(gaps.relief_m(Gear::two, seg.start_m), c_a) < 1e-12);
  CHECK(std::fabs(gaps.relief_m(Gear::two, lp - s_r2)) <= kEndTolerance_m * 10.0);
  CHECK(gaps.relief_m(Gear::two, lp - s_r2 + 1e-4) == 0.0);
  // The tip diameter itself lies where contact_segment puts the wheel's tip.
  CHECK(relative_difference(active_profile(g, Gear::two).tip_diameter_m,
                            diameter_at_roll(rb2, s_a2)) < 1e-14);
}

TEST_CASE("a root relief is C_f at the start of the active profile and 0 at its end diameter") {
  const GearPair g = paper_gear_pair();
  const ContactSegment seg = contact_segment(g);
  const double rb1 = base_radius(g, Gear::one);
  const double c_f = 8e-6;
  const double s_f = seg.start_m + 0.25 * (seg.end_m - seg.start_m);
  Modifications m;
  m.gear1.root = {c_f, diameter_at_roll(rb1, s_f), ReliefShape::parabolic};
  REQUIRE_NOTHROW(validate_modifications(g, m));
  const ToothGaps gaps(g, m);
  CHECK(relative_difference(gaps.relief_m(Gear::one, seg.start_m), c_f) < 1e-12);
  CHECK(std::fabs(gaps.relief_m(Gear::one, s_f)) <= kEndTolerance_m);
  CHECK(relative_difference(gaps.relief_m(Gear::one, 0.5 * (seg.start_m + s_f)), 0.25 * c_f) <
        1e-9);
}

TEST_CASE("a pitch deviation opens the drive flank and closes the coast flank") {
  const GearPair g = paper_gear_pair();
  const ContactSegment seg = contact_segment(g);
  const double x = 0.5 * (seg.start_m + seg.end_m);
  Modifications m;
  m.gear1.pitch_m.assign(static_cast<std::size_t>(g.teeth1), 0.0);
  m.gear1.pitch_m[3] = 5e-6;
  m.gear2.thickness_m.assign(static_cast<std::size_t>(g.teeth2), 0.0);
  m.gear2.thickness_m[7] = 2e-6;
  const ToothGaps gaps(g, m);
  for (const Region line : {Region::n1, Region::n2}) {
    for (int k = -100; k <= 100; ++k) {
      const TeethInContact t = teeth_of_pair(g, line, k);
      const double pitch = t.pinion_tooth == 3 ? (line == Region::n1 ? 5e-6 : -5e-6) : 0.0;
      const double thickness = t.wheel_tooth == 7 ? 2e-6 : 0.0;
      CHECK(gaps.gap_m(line, k, x) == pitch + thickness);
    }
  }
}

TEST_CASE("a profile slope deviation runs from -f/2 at the start of the active profile to +f/2") {
  const GearPair g = paper_gear_pair();
  const ContactSegment seg = contact_segment(g);
  const double f = 6e-6;
  Modifications m;
  m.gear1.profile_slope_m.assign(static_cast<std::size_t>(g.teeth1), f);
  const ToothGaps gaps(g, m);
  // The pinion's active profile runs from X_start (its SAP) to X_end (its tip).
  CHECK(relative_difference(gaps.tooth_m(Gear::one, 0, Region::n1, seg.start_m), -0.5 * f) < 1e-12);
  CHECK(relative_difference(gaps.tooth_m(Gear::one, 0, Region::n1, seg.end_m), 0.5 * f) < 1e-12);
  CHECK(std::fabs(gaps.tooth_m(Gear::one, 0, Region::n2, 0.5 * (seg.start_m + seg.end_m))) < 1e-20);
  // All teeth alike: the mesh repeats every mesh period.
  CHECK(true_period_mesh_periods(g, distinct_teeth(m)) == 1);
  m.gear1.profile_slope_m[0] = 0.0;
  CHECK(true_period_mesh_periods(g, distinct_teeth(m)) == g.teeth1);
}

TEST_CASE("a relief starting outside the active profile is refused naming the key and the limit") {
  const GearPair g = paper_gear_pair();
  const ActiveProfile active = active_profile(g, Gear::one);
  Modifications m;
  m.gear1.tip = {10e-6, active.tip_diameter_m, ReliefShape::linear};
  try {
    validate_modifications(g, m);
    FAIL("a relief starting at the tip was accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "modifications.tip_relief_start1");
    CHECK(e.allowed().find(format_number(active.start_diameter_m * 1e3) + " mm") !=
          std::string::npos);
    CHECK(e.allowed().find(format_number(active.tip_diameter_m * 1e3) + " mm)") !=
          std::string::npos);
  }
  Modifications lists;
  lists.gear2.pitch_m = {1e-6, 2e-6};
  try {
    validate_modifications(g, lists);
    FAIL("a pitch list of 2 values for 80 teeth was accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "modifications.pitch_deviations2");
    CHECK(e.allowed().find("teeth2 = 80") != std::string::npos);
  }
}

TEST_CASE("a gap's slope is its central difference; the kinks are where linear reliefs begin") {
  // Every kind of deviation on both gears, then de_k/dX against the central
  // difference (e(X + h) - e(X - h)) / 2h with h = 1e-7 m: exact for the
  // linear parts, off by C h^2 / L^3 ~ 1e-9 of the slope for a parabolic
  // relief (L ~ 1 mm), so the bound 1e-6 of the largest slope leaves room
  // for the rounding of e (1e-21 m / 1e-7 m).
  const GearPair g = paper_gear_pair();
  const ContactSegment seg = contact_segment(g);
  Modifications m;
  m.gear1.tip = {10e-6, 43.2e-3, ReliefShape::linear};
  m.gear2.tip = {8e-6, 163.2e-3, ReliefShape::parabolic};
  m.gear1.root = {3e-6, 41.0e-3, ReliefShape::parabolic};
  m.gear2.root = {2e-6, 158.5e-3, ReliefShape::linear};
  m.gear1.profile_slope_m.assign(20, 1e-6);
  m.gear2.pitch_m.assign(80, 0.0);
  m.gear2.pitch_m[1] = 4e-6;
  REQUIRE_NOTHROW(validate_modifications(g, m));
  const ToothGaps gaps(g, m);
  const std::vector<double> kinks = gaps.kinks_m();
  // The linear ones: the pinion's tip relief start and the wheel's root
  // relief end, on the line of action X = s1 and X = lp - s2.
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const double lp = line_of_action_length(g);
  REQUIRE(kinks.size() == 2);
  const double pinion_tip = std::sqrt(0.25 * 43.2e-3 * 43.2e-3 - rb1 * rb1);
  const double wheel_root = lp - std::sqrt(0.25 * 158.5e-3 * 158.5e-3 - rb2 * rb2);
  CHECK(std::fabs(kinks[0] - std::min(pinion_tip, wheel_root)) < 1e-15);
  CHECK(std::fabs(kinks[1] - std::max(pinion_tip, wheel_root)) < 1e-15);
  for (const Region line : {Region::n1, Region::n2}) {
    for (int k = -2; k <= 1; ++k) {
      for (int i = 1; i < 100; ++i) {
        const double x = seg.start_m + (seg.end_m - seg.start_m) * i / 100.0;
        // Away from the kinks, where the difference would straddle one.
        if (std::fabs(x - kinks[0]) < 1e-6 || std::fabs(x - kinks[1]) < 1e-6) continue;
        const double h = 1e-7;
        const double difference =
            (gaps.gap_m(line, k, x + h) - gaps.gap_m(line, k, x - h)) / (2 * h);
        const ToothGaps::GapAndSlope e = gaps.gap_and_slope(line, k, x);
        CHECK(e.gap_m == gaps.gap_m(line, k, x));
        CHECK(std::fabs(e.slope - difference) < 1e-6 * 0.02);
      }
    }
  }
}

TEST_CASE("the least gap bound lies below every pair's gap on its line") {
  // Thicker and thinner teeth, pitch and profile slope deviations: the bound
  // by hand is the pinion's least (-f_t + the line's pitch - |f_Ha|/2) plus
  // the wheel's, and every gap on the line of action lies at or above it.
  const GearPair g = paper_gear_pair();
  const ContactSegment seg = contact_segment(g);
  Modifications m;
  m.gear1.thickness_m.assign(20, 0.0);
  m.gear1.thickness_m[2] = -5e-6;
  m.gear1.pitch_m.assign(20, 0.0);
  m.gear1.pitch_m[2] = 2e-6;
  m.gear2.profile_slope_m.assign(80, 4e-6);
  // N1: tooth 2 gives -5 + 2 = -3 um, the wheel -2 um: -5 um. N2: -5 - 2 - 2 = -9 um.
  CHECK(std::fabs(least_gap_bound_m(g, m, Region::n1) - -5e-6) < 1e-18);
  CHECK(std::fabs(least_gap_bound_m(g, m, Region::n2) - -9e-6) < 1e-18);
  const ToothGaps gaps(g, m);
  for (const Region line : {Region::n1, Region::n2}) {
    for (int k = -100; k <= 100; ++k) {
      for (int i = 0; i <= 20; ++i) {
        const double x = seg.start_m + (seg.end_m - seg.start_m) * i / 20.0;
        CHECK(gaps.gap_m(line, k, x) >= least_gap_bound_m(g, m, line) - 1e-18);
      }
    }
  }
}
