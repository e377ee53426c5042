// Tooth identity (docs/faults.md): the numbering of the teeth in each pair and
// the true period of the mesh, checked by counting over whole revolutions.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <set>
#include <utility>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"

using namespace gearimpact;

namespace {

GearPair pair_of(int z1, int z2) {
  GearPair g = paper_gear_pair();
  g.teeth1 = z1;
  g.teeth2 = z2;
  return g;
}

}  // namespace

TEST_CASE("over one pinion revolution every pinion tooth enters once on each line") {
  const GearPair g = pair_of(23, 67);
  for (const Region line : {Region::n1, Region::n2}) {
    std::set<int> seen;
    // The next 23 pairs to enter: k = 0, -1, ... on N1; k = 0, 1, ... on N2.
    for (int n = 0; n < 23; ++n) {
      const int k = line == Region::n1 ? -n : n;
      seen.insert(teeth_of_pair(g, line, k).pinion_tooth);
    }
    CHECK(seen.size() == 23);
    CHECK(*seen.begin() == 0);
    CHECK(*seen.rbegin() == 22);
  }
}

TEST_CASE("the tooth pairs repeat after the hunting period and not before") {
  for (const auto& [z1, z2] : {std::pair{23, 67}, std::pair{20, 30}, std::pair{17, 38}}) {
    CAPTURE(z1);
    CAPTURE(z2);
    const GearPair g = pair_of(z1, z2);
    const long long hunting = std::lcm(z1, z2);
    std::set<std::pair<int, int>> met;
    for (long long n = 0; n < hunting; ++n) {
      const TeethInContact t = teeth_of_pair(g, Region::n1, static_cast<int>(-n));
      met.insert({t.pinion_tooth, t.wheel_tooth});
      // A tooth meets only the teeth of its own residue class mod gcd(z1, z2).
      CHECK((t.pinion_tooth - t.wheel_tooth) % std::gcd(z1, z2) == 0);
    }
    CHECK(met.size() == static_cast<std::size_t>(hunting));
    const TeethInContact again = teeth_of_pair(g, Region::n1, static_cast<int>(-hunting));
    CHECK(again.pinion_tooth == 0);
    CHECK(again.wheel_tooth == 0);
  }
}

TEST_CASE("a pinion tooth's coast flank faces the wheel tooth the next pinion tooth drives") {
  const GearPair g = pair_of(20, 30);
  for (int i = -45; i <= 45; ++i) {
    const TeethInContact coast = teeth_of_pair(g, Region::n2, i);
    // The drive pair of the same pinion tooth, and of the tooth behind it.
    const TeethInContact drive = teeth_of_pair(g, Region::n1, -i);
    const TeethInContact next = teeth_of_pair(g, Region::n1, -(i + 1));
    CHECK(coast.pinion_tooth == drive.pinion_tooth);
    CHECK(coast.wheel_tooth == next.wheel_tooth);
  }
}

TEST_CASE("the true period in mesh periods") {
  const GearPair g = pair_of(23, 67);
  CHECK(true_period_mesh_periods(g, {}) == 1);
  CHECK(true_period_mesh_periods(g, {true, false}) == 23);
  CHECK(true_period_mesh_periods(g, {false, true}) == 67);
  CHECK(true_period_mesh_periods(g, {true, true}) == 23 * 67);
  CHECK(true_period_mesh_periods(pair_of(20, 30), {true, true}) == 60);
}

TEST_CASE("a tooth's passage is where the layout's loaded pairs hold it") {
  // Another route than tooth_passage's closed form: at each angle the layout's loaded pairs
  // on N1 and teeth_of_pair's numbering say which teeth carry; away from the passage's ends
  // (1e-9 rad, far above the rounding of X) the two must agree.
  const GearPair g = pair_of(23, 67);
  const MeshLayout layout(g, CoastPhase::half_base_pitch);
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const auto inside = [](const ToothPassage& p, double theta) {
    double d = theta - p.entry_rad;
    d -= 2.0 * pi * std::floor(d / (2.0 * pi));
    if (std::fabs(d) < 1e-9 || std::fabs(d - p.span_rad) < 1e-9) return -1;  // an end
    return d < p.span_rad ? 1 : 0;
  };
  for (const Gear gear : {Gear::one, Gear::two}) {
    const int z = teeth(g, gear);
    for (const int tooth : {0, 5, z - 1}) {
      const ToothPassage p = tooth_passage(g, gear, tooth);
      CHECK(p.entry_rad >= 0.0);
      CHECK(p.entry_rad < 2.0 * pi);
      int carried = 0;
      for (int i = 0; i < 2000; ++i) {
        const double theta = 2.0 * pi * i / 2000.0;  // the gear's own angle
        const double theta1 = gear == Gear::one ? theta : theta * rb2 / rb1;
        const LoadedRange range = layout.loaded(layout.reference_m(Region::n1, theta1));
        bool held = false;
        for (int j = 0; j < range.count; ++j) {
          const TeethInContact t = teeth_of_pair(g, Region::n1, range.k_first + j);
          held = held || (gear == Gear::one ? t.pinion_tooth : t.wheel_tooth) == tooth;
        }
        const int expected = inside(p, theta);
        if (expected < 0) continue;
        CHECK(held == (expected == 1));
        carried += held ? 1 : 0;
      }
      // The span is the contact ratio's share of a pitch: eps t0 / Rb = eps 2 pi / z.
      CHECK(std::fabs(p.span_rad * z / (2.0 * pi) - contact_ratio(g)) < 1e-12);
      CHECK(carried > 0);
    }
  }
  CHECK_THROWS_WITH_AS(tooth_passage(g, Gear::one, 23), doctest::Contains("[0, 22]"), InputError);
}
