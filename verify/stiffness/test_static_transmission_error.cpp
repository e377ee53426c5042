// The loaded static transmission error (docs/faults.md, "Static transmission
// error"): against its closed forms without gaps and for equal constant pair
// stiffnesses with a linear tip relief, the exact solve against Boost's
// bracketing root finder, shares that sum to 1, and two-pair zones that grow
// with the load; faulted teeth, each pair on its own table: a crack of depth 0
// as the healthy pair, a missing tooth's load on the other pairs, a cracked
// pair alone against its own stiffness; the quasi-static peak force as the entry jump without
// gaps and as a spall's far edge where that is larger.
#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <memory>
#include <random>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

constexpr double kTorque = 100.0;  // N m on the pinion: F = T / Rb1, about 5.3 kN

// The pinion's linear tip relief of `c_a` starting at roll distance `s_r`.
Modifications tip_relief(const GearPair& g, double c_a, double s_r) {
  const double rb1 = base_radius(g, Gear::one);
  Modifications m;
  m.gear1.tip = {c_a, 2.0 * std::sqrt(rb1 * rb1 + s_r * s_r), ReliefShape::linear};
  return m;
}

ToothFault crack_on(int pinion_tooth, double depth_m) {
  ToothFault f;
  f.tooth = pinion_tooth;
  f.state.kind = ToothKind::root_crack;
  f.state.crack.depth_m = depth_m;
  f.state.crack.angle_rad = pi / 4.0;
  return f;
}

ToothFault missing(int pinion_tooth) {
  ToothFault f;
  f.tooth = pinion_tooth;
  f.state.kind = ToothKind::missing;
  return f;
}

}  // namespace

TEST_CASE("the exact solve and Boost's TOMS 748 agree on random pairs") {
  std::mt19937_64 random(20261124);
  std::uniform_real_distribution<double> stiffness(1e8, 5e8);
  std::uniform_real_distribution<double> gap(-20e-6, 20e-6);
  std::uniform_real_distribution<double> force(10.0, 1e5);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<PairSpring> springs(static_cast<std::size_t>(1 + trial % 4));
    for (PairSpring& s : springs) s = {stiffness(random), gap(random)};
    const double f = force(random);
    const double exact = solve_deflection(springs, f);
    const double bracketed = solve_deflection_bracketed(springs, f);
    // TOMS 748 stops at a bracket of 1e-15 of delta; the residual's own
    // rounding (a sum of four products of ~1e-5 m and ~1e8 N/m) moves the
    // root by a few ulps of the largest gap: 1e-12 of the ~1e-5 m delta.
    CHECK(std::fabs(exact - bracketed) <= 1e-12 * std::max(std::fabs(exact), 1e-5));
    // The balance itself.
    double carried = 0.0;
    for (const PairSpring& s : springs)
      carried += s.stiffness_n_per_m * std::max(0.0, exact - s.gap_m);
    CHECK(relative_difference(carried, f) < 1e-10);
  }
}

TEST_CASE("without gaps STE = F / sum k and the shares are k / sum k") {
  const GearPair g = paper_gear_pair();
  const StiffnessTable table(g);
  const StaticTransmissionError ste = static_transmission_error(g, Modifications{}, kTorque, table);
  REQUIRE(ste.mesh_periods == 1);
  REQUIRE(ste.points.size() == 200);
  CHECK(relative_difference(ste.force_n, kTorque / base_radius(g, Gear::one)) < 1e-15);
  for (const StePoint& p : ste.points) {
    double sum = 0.0;
    for (std::size_t j = 0; j < p.pairs; ++j) sum += table.stiffness(p.x_m[j]);
    // F / sum k is the exact route's own formula with every gap 0, the sum
    // taken in the same order: a rounding or two of F / K, and of k (F / K) / F
    // against k / K for the shares, within 1e-14.
    CHECK(relative_difference(p.ste_m, ste.force_n / sum) < 1e-14);
    CHECK(relative_difference(p.effective_stiffness_n_per_m, sum) < 1e-14);
    CHECK(p.kte_m == 0.0);
    for (std::size_t j = 0; j < p.pairs; ++j) {
      CHECK(relative_difference(p.share[j], table.stiffness(p.x_m[j]) / sum) < 1e-14);
    }
  }
}

TEST_CASE("equal constant pair stiffness with a linear tip relief: STE and shares by hand") {
  const GearPair g = paper_gear_pair();
  const ContactSegment seg = contact_segment(g);
  const double t0 = base_pitch(g);
  const double rb1 = base_radius(g, Gear::one);
  const double k = 3e8;  // N/m, every pair, everywhere
  const double c_a = 20e-6;
  // The relief starts inside the exit's two-pair zone [X_start + t0, X_end],
  // 0.3 of its length before the tip: the single pair and the entering pair
  // of a two-pair zone are never relieved.
  const double s_r = seg.end_m - 0.3 * (seg.end_m - seg.start_m - t0);
  const Modifications m = tip_relief(g, c_a, s_r);
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 400;
  const StaticTransmissionError ste = static_transmission_error(
      g, m, kTorque, [k](int, double) { return k; }, options);
  const double f = kTorque / rb1;
  int single = 0;
  int both = 0;
  int one_of_two = 0;
  for (const StePoint& p : ste.points) {
    // The positions by (9) with (12) and (42): X_pitch + Rb1 theta1 + k t0.
    for (std::size_t j = 0; j < p.pairs; ++j) {
      const double x = pitch_point_position(g) + rb1 * p.theta1_rad + p.k[j] * t0;
      CHECK(std::fabs(x - p.x_m[j]) < 1e-15);
    }
    double total = 0.0;
    for (std::size_t j = 0; j < p.pairs; ++j) total += p.share[j];
    CHECK(std::fabs(total - 1.0) < 1e-13);
    if (p.pairs == 1) {
      // One pair, never relieved: delta = F / k.
      ++single;
      CHECK(relative_difference(p.ste_m, f / k) < 1e-14);
      CHECK(std::fabs(p.share[0] - 1.0) < 1e-15);
      continue;
    }
    REQUIRE(p.pairs == 2);
    // The leaving pair (larger X) is relieved by e = C_a (X - s_r) / (X_end - s_r) beyond s_r.
    const double x_out = p.x_m[1];
    const double e = x_out > s_r ? c_a * (x_out - s_r) / (seg.end_m - s_r) : 0.0;
    CHECK(std::fabs(p.gap_m[1] - e) < 1e-15);
    CHECK(p.gap_m[0] == 0.0);
    if (f / k <= e) {
      // The relieved pair is not reached: delta = F / k on the entering pair alone.
      ++one_of_two;
      CHECK(relative_difference(p.ste_m, f / k) < 1e-14);
      CHECK(p.share[1] == 0.0);
      CHECK(p.effective_stiffness_n_per_m == k);
    } else {
      // k delta + k (delta - e) = F: delta = F / (2k) + e / 2, shares 1/2 +- k e / (2F).
      ++both;
      CHECK(relative_difference(p.ste_m, f / (2.0 * k) + 0.5 * e) < 1e-13);
      CHECK(std::fabs(p.share[0] - (0.5 + k * e / (2.0 * f))) < 1e-13);
      CHECK(std::fabs(p.share[1] - (0.5 - k * e / (2.0 * f))) < 1e-13);
      CHECK(p.effective_stiffness_n_per_m == 2.0 * k);
    }
    CHECK(p.kte_m == 0.0);
  }
  // Each zone is visited: F / k = 18 um < C_a = 20 um, so the tip is not reached.
  CHECK(single > 0);
  CHECK(both > 0);
  CHECK(one_of_two > 0);
}

TEST_CASE("a heavier load lengthens the two-pair zones of a relieved pair") {
  const GearPair g = paper_gear_pair();
  const ContactSegment seg = contact_segment(g);
  const double t0 = base_pitch(g);
  const double rb1 = base_radius(g, Gear::one);
  const double k = 3e8;
  const double c_a = 30e-6;
  const double s_r = seg.end_m - 0.8 * (seg.end_m - seg.start_m - t0);
  const Modifications m = tip_relief(g, c_a, s_r);
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 2000;
  double last = -1.0;
  // F / k = 3.5, 10.6, 17.7 and 26.6 um, all below C_a: the zone never reaches the tip.
  for (const double torque : {20.0, 60.0, 100.0, 150.0}) {
    const StaticTransmissionError ste = static_transmission_error(
        g, m, torque, [k](int, double) { return k; }, options);
    int loaded_two = 0;
    for (const StePoint& p : ste.points) loaded_two += p.effective_stiffness_n_per_m > 1.5 * k;
    const double fraction =
        static_cast<double>(loaded_two) / static_cast<double>(ste.points.size());
    // By hand: the leaving pair carries load while e(X) < F / k, i.e. up to
    // X_lim = s_r + (F / k / C_a)(X_end - s_r) (capped at X_end); the two-pair
    // zone per mesh period is then (X_lim - X_start - t0) / t0.
    const double x_lim = std::min(seg.end_m, s_r + (torque / rb1 / k / c_a) * (seg.end_m - s_r));
    const double expected = (x_lim - seg.start_m - t0) / t0;
    // Counting 2000 angles resolves a zone to 1/2000 at each of its two ends.
    CHECK(std::fabs(fraction - expected) <= 2.0 / 2000.0);
    CHECK(fraction > last);
    last = fraction;
  }
}

TEST_CASE("errors on pinion teeth: the true period is z1 mesh periods and the peak grows") {
  const GearPair g = paper_gear_pair();
  const StiffnessTable table(g);
  Modifications m;
  m.gear1.pitch_m.assign(static_cast<std::size_t>(g.teeth1), 0.0);
  m.gear1.pitch_m[0] = 10e-6;
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 50;
  const StaticTransmissionError healthy =
      static_transmission_error(g, Modifications{}, kTorque, table, options);
  const StaticTransmissionError ste = static_transmission_error(g, m, kTorque, table, options);
  CHECK(ste.mesh_periods == g.teeth1);
  CHECK(ste.points.size() == static_cast<std::size_t>(50 * g.teeth1));
  CHECK(relative_difference(ste.period_rad, 2.0 * pi) < 1e-15);
  CHECK(ste.ste_peak_to_peak_m > healthy.ste_peak_to_peak_m);
  // Where tooth 0's pair is alone in contact the whole error adds to the deflection.
  bool seen = false;
  for (const StePoint& p : ste.points) {
    if (p.pairs == 1 && p.teeth[0].pinion_tooth == 0) {
      seen = true;
      CHECK(relative_difference(p.ste_m, 10e-6 + ste.force_n / p.stiffness_n_per_m[0]) < 1e-14);
      CHECK(p.kte_m == 10e-6);
    }
  }
  CHECK(seen);
}

TEST_CASE("a bad torque or number of points is refused naming it") {
  const GearPair g = paper_gear_pair();
  const auto constant = [](int, double) { return 3e8; };
  for (const double torque : {0.0, -5.0, std::nan("")}) {
    try {
      static_transmission_error(g, Modifications{}, torque, constant);
      FAIL("a torque of " << torque << " was accepted");
    } catch (const InputError& e) {
      CHECK(e.field() == "torque");
      CHECK(e.allowed().find("> 0 N*m") != std::string::npos);
    }
  }
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 1;
  CHECK_THROWS_AS(static_transmission_error(g, Modifications{}, 1.0, constant, options),
                  InputError);
}

TEST_CASE("faulted teeth: each pair on its own table over a pinion revolution") {
  const GearPair g = paper_gear_pair();
  const StiffnessModel model;
  const auto healthy = std::make_shared<const StiffnessTable>(g, model);
  const double force = kTorque / base_radius(g, Gear::one);
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 40;

  SUBCASE("a crack of depth 0 gives the healthy STE, to the bit") {
    const MeshTables tables(g, model, {crack_on(5, 0.0)}, healthy);
    const StaticTransmissionError faulted =
        static_transmission_error(g, Modifications{}, kTorque, tables, options);
    // A pinion tooth differs: the true period is a pinion revolution.
    REQUIRE(faulted.mesh_periods == g.teeth1);
    options.mesh_periods = faulted.mesh_periods;
    const StaticTransmissionError plain =
        static_transmission_error(g, Modifications{}, kTorque, *healthy, options);
    REQUIRE(plain.points.size() == faulted.points.size());
    for (std::size_t i = 0; i < plain.points.size(); ++i) {
      CHECK(faulted.points[i].carried);
      CHECK(faulted.points[i].ste_m == plain.points[i].ste_m);
      CHECK(faulted.points[i].effective_stiffness_n_per_m ==
            plain.points[i].effective_stiffness_n_per_m);
    }
    CHECK(faulted.ste_mean_m == plain.ste_mean_m);
  }

  SUBCASE("a missing tooth: the other pairs carry F, and alone no pair does") {
    constexpr int gone = 7;
    const MeshTables tables(g, model, {missing(gone)}, healthy);
    const StaticTransmissionError ste =
        static_transmission_error(g, Modifications{}, kTorque, tables, options);
    REQUIRE(ste.mesh_periods == g.teeth1);
    int shared = 0;
    std::size_t alone = 0;
    for (const StePoint& p : ste.points) {
      double others = 0.0;  // by hand: the healthy table's Ke of every other pair
      bool has_gone = false;
      for (std::size_t j = 0; j < p.pairs; ++j) {
        if (p.teeth[j].pinion_tooth == gone) {
          has_gone = true;
          CHECK(p.share[j] == 0.0);
          CHECK(p.stiffness_n_per_m[j] == 0.0);
        } else {
          others += healthy->stiffness(p.x_m[j]);
        }
      }
      if (!has_gone) continue;
      if (p.pairs == 1) {
        // The missing tooth's pair alone in the segment: nothing on the line of action.
        CHECK_FALSE(p.carried);
        ++alone;
        continue;
      }
      REQUIRE(p.carried);
      CAPTURE(p.theta1_rad);
      // STE = F / sum Ke of the remaining pairs: the same quotient up to a rounding or two.
      CHECK(relative_difference(p.ste_m, force / others) < 1e-14);
      CHECK(p.effective_stiffness_n_per_m == others);
      ++shared;
    }
    // Over its pass (the contact ratio eps ~ 1.6 mesh periods) the pair spends eps - 1
    // of a mesh period beside the pair behind or ahead and 2 - eps alone.
    CHECK(shared > 0);
    CHECK(alone > 0);
    CHECK(ste.uncarried_points == alone);
    const double eps = contact_ratio(g);
    CHECK(std::fabs(static_cast<double>(alone) / options.points_per_mesh_period - (2.0 - eps)) <=
          1.0 / options.points_per_mesh_period);
    // The mean is over the carried points only.
    double sum = 0.0;
    for (const StePoint& p : ste.points) sum += p.carried ? p.ste_m : 0.0;
    CHECK(relative_difference(ste.ste_mean_m,
                              sum / static_cast<double>(ste.points.size() - alone)) < 1e-13);
  }

  SUBCASE("where the cracked pair is alone, STE = F / ke of that pair") {
    constexpr int cracked = 3;
    const ToothFault crack = crack_on(cracked, 0.8e-3);
    const MeshTables tables(g, model, {crack}, healthy);
    const StaticTransmissionError ste =
        static_transmission_error(g, Modifications{}, kTorque, tables, options);
    int alone = 0;
    for (const StePoint& p : ste.points) {
      if (p.pairs != 1 || p.teeth[0].pinion_tooth != cracked) continue;
      CAPTURE(p.x_m[0]);
      // Ke of the cracked pair directly (not the fitted table, which agrees to ~1e-12): the
      // tolerance is the table's fit, well below the crack's effect (several %).
      const double ke = mesh_stiffness(g, p.x_m[0], model, crack.state, ToothState{}).ke;
      CHECK(relative_difference(p.ste_m, force / ke) < 1e-9);
      CHECK(relative_difference(p.ste_m, force / healthy->stiffness(p.x_m[0])) > 1e-3);
      ++alone;
    }
    CHECK(alone >= 10);
  }
}

TEST_CASE("no angle carried: every pinion tooth missing is refused, naming [[faults]]") {
  const GearPair g = paper_gear_pair();
  const StiffnessModel model;
  std::vector<ToothFault> all;
  for (int i = 0; i < g.teeth1; ++i) all.push_back(missing(i));
  const MeshTables tables(g, model, all);
  try {
    static_transmission_error(g, Modifications{}, kTorque, tables, {10, 0});
    FAIL("not refused");
  } catch (const InputError& e) {
    CHECK(e.field() == "[[faults]]");
  }
}

TEST_CASE(
    "quasi-static peak: the entry jump without gaps, and a spall's far edge where it is larger") {
  const GearPair g = paper_gear_pair();
  const StiffnessModel model;
  const auto healthy = std::make_shared<const StiffnessTable>(g, model);
  const ContactSegment seg = contact_segment(g);
  const double t0 = base_pitch(g);
  const double rb1 = base_radius(g, Gear::one);
  // Without gaps or faults: (K_before + k_in) / K_before at the entry, the pairs a base pitch on
  // before, with the entering one after; the route solves and sums, a few roundings apart.
  double before = 0.0;
  for (int j = 1; seg.start_m + j * t0 <= seg.end_m; ++j) {
    before += healthy->stiffness(seg.start_m + j * t0);
  }
  const double entry = (before + healthy->stiffness(seg.start_m)) / before;
  const MeshTables plain(g, model, {}, healthy);
  CHECK(relative_difference(quasi_static_peak_force_ratio(g, Modifications{}, kTorque, plain),
                            entry) <= 1e-14);

  // A spall across 90 % of the face on pinion tooth 0's drive flank, between the contacts at 42 %
  // and 55 % of the path, both inside the single-pair zone [X_end - t0, X_start + t0]: where the
  // contact leaves it the lone pair's stiffness jumps from the spalled k_- to the healthy k_+ at
  // the deflection F / k_-, so the force jumps to k_+ / k_- times F. k on either side of the edge
  // from the quadrature of mesh_stiffness, 1e-9 m inside each part (Ke moves by ~1e-7 of itself
  // over that).
  const auto x_at = [&](double f) { return seg.start_m + f * (seg.end_m - seg.start_m); };
  REQUIRE(x_at(0.42) > seg.end_m - t0);
  REQUIRE(x_at(0.55) < seg.start_m + t0);
  ToothFault spalled;
  spalled.tooth = 0;
  spalled.state.kind = ToothKind::spall;
  spalled.state.spall.start_radius_m = std::hypot(rb1, x_at(0.42));
  spalled.state.spall.end_radius_m = std::hypot(rb1, x_at(0.55));
  spalled.state.spall.width_m = 0.9 * g.face_width_m;
  spalled.state.spall.depth_m = 0.2e-3;
  const double edge = x_at(0.55);
  const double k_below = mesh_stiffness(g, edge - 1e-9, model, spalled.state, ToothState{}).ke;
  const double k_above = mesh_stiffness(g, edge + 1e-9, model, spalled.state, ToothState{}).ke;
  const MeshTables tables(g, model, {spalled}, healthy);
  const double ratio = quasi_static_peak_force_ratio(g, Modifications{}, kTorque, tables);
  MESSAGE("entry jump " << entry << ", spall edge k+/k- " << k_above / k_below << ", peak "
                        << ratio);
  REQUIRE(k_above / k_below > entry);
  CHECK(relative_difference(ratio, k_above / k_below) <= 1e-6);
}
