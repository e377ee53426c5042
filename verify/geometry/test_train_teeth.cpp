// Tooth identity and periods of a train's mesh and a planetary stage's
// meshes (geometry/train_teeth.hpp) against routes of their own: every tooth's
// centre line placed and scanned here to find the one at a mesh, the periods
// found by enumerating the pairings until they repeat, the fault frequencies
// by counting a tooth's visits over a period, the mesh phases against
// geometry/planetary.hpp's gamma_sn and gamma_rn (docs/planetary.md).
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/planetary.hpp"
#include "gearimpact/geometry/train_teeth.hpp"

using namespace gearimpact;

namespace {

// x wrapped to [-pi, pi).
double wrapped(double x) {
  return x - 2.0 * pi * std::floor((x + pi) / (2.0 * pi));
}

// The tooth of a gear of z teeth (tooth j's centre line at tooth0 - 2 pi j / z)
// whose centre line lies within one pitch of `direction`: behind it (in
// [direction, direction + pitch)) for teeth moving counter-clockwise, ahead of it
// (in (direction - pitch, direction]) for teeth moving clockwise. Scanned over
// every tooth.
int scanned_tooth(int z, double tooth0, double direction, bool counter_clockwise) {
  const double pitch = 2.0 * pi / z;
  int found = -1;
  for (int j = 0; j < z; ++j) {
    const double d = wrapped(tooth0 - 2.0 * pi * j / z - direction);
    const bool in = counter_clockwise ? (d >= 0.0 && d < pitch) : (d <= 0.0 && d > -pitch);
    if (in) {
      REQUIRE(found < 0);  // one tooth per window
      found = j;
    }
  }
  REQUIRE(found >= 0);
  return found;
}

// The stage of docs/planetary.md's phasing check: Z_s, Z_p, Z_r = 22, 29, 80.
constexpr PlanetaryTeeth kStage{22, 29, 80};

// The members' angles relative to the carrier t mesh periods on, from the
// tooth-0 angles at t = 0 (the sun one sun pitch a period counter-clockwise,
// each planet one planet pitch and the ring one ring pitch clockwise).
struct StageAngles {
  double sun, planet, ring;
};
StageAngles angles_at(double t, const StageAngles& start) {
  return {start.sun + 2.0 * pi * t / kStage.sun, start.planet - 2.0 * pi * t / kStage.planet,
          start.ring - 2.0 * pi * t / kStage.ring};
}

std::vector<double> equal_angles(int n) {
  std::vector<double> psi;
  for (int i = 0; i < n; ++i) psi.push_back(2.0 * pi * i / n);
  return psi;
}

// Every planet's four teeth at its meshes, at t.
std::vector<int> stage_state(double t, const StageAngles& start, const std::vector<double>& psi) {
  const StageAngles a = angles_at(t, start);
  std::vector<int> state;
  for (double p : psi) {
    const StageMeshTeeth m = stage_mesh_teeth(kStage, p, a.sun, a.planet, a.ring);
    state.insert(state.end(), {m.sun, m.planet_at_sun, m.planet_at_ring, m.ring});
  }
  return state;
}

// The least P >= 1 with states[i + P] == states[i] for every i < states.size() / 2.
template <typename T>
long long least_period(const std::vector<T>& states) {
  const std::size_t half = states.size() / 2;
  for (std::size_t p = 1; p <= half; ++p) {
    bool repeats = true;
    for (std::size_t i = 0; i < half && repeats; ++i) repeats = states[i + p] == states[i];
    if (repeats) return static_cast<long long>(p);
  }
  return -1;
}

}  // namespace

TEST_CASE("a train mesh's pairs: tooth n mod z1 against n mod z2, repeating after lcm(z1, z2)") {
  for (const auto& [z1, z2] : {std::pair{32, 80}, std::pair{48, 64}, std::pair{20, 31}}) {
    CAPTURE(z1);
    CAPTURE(z2);
    GearPair g;
    g.teeth1 = z1;
    g.teeth2 = z2;
    const long long lcm = hunting_period_mesh_periods(z1, z2);
    CHECK(lcm == std::lcm(z1, z2));
    std::vector<std::pair<int, int>> pairs;
    std::set<std::pair<int, int>> distinct;
    std::vector<std::set<int>> met(static_cast<std::size_t>(z1));
    for (long long n = 0; n < 2 * lcm; ++n) {
      // Mid-pitch: body a turned n + 0.3 pitches (and one turn back: the count is periodic).
      const double theta = 2.0 * pi * (static_cast<double>(n) + 0.3) / z1;
      const TeethInContact t = mesh_teeth_at(g, theta);
      // The pair's own rule for the n-th pair to enter.
      const TeethInContact rule = teeth_of_pair(z1, z2, Region::n1, static_cast<int>(-n));
      REQUIRE(t.pinion_tooth == rule.pinion_tooth);
      REQUIRE(t.wheel_tooth == rule.wheel_tooth);
      // Rolling: body a's tooth at the pitch point is the one scanned there, its
      // teeth moving forward (counter-clockwise in its own sense).
      REQUIRE(t.pinion_tooth == scanned_tooth(z1, theta, 0.0, true));
      pairs.emplace_back(t.pinion_tooth, t.wheel_tooth);
      distinct.insert(pairs.back());
      met[static_cast<std::size_t>(t.pinion_tooth)].insert(t.wheel_tooth);
    }
    CHECK(least_period(pairs) == lcm);
    CHECK(static_cast<long long>(distinct.size()) == lcm);
    // Each tooth of a meets z2 / gcd(z1, z2) teeth of b.
    for (const std::set<int>& m : met) CHECK(static_cast<int>(m.size()) == z2 / std::gcd(z1, z2));
  }
}

TEST_CASE("a stage's teeth at each mesh are those whose centre lines sit there") {
  const std::vector<double> psi = equal_angles(3);
  const StageAngles start{0.11, -0.05, 0.07};
  for (int i = 0; i < 400; ++i) {
    const double t = 0.173 * i;
    const StageAngles a = angles_at(t, start);
    for (double p : psi) {
      const StageMeshTeeth m = stage_mesh_teeth(kStage, p, a.sun, a.planet, a.ring);
      REQUIRE(m.sun == scanned_tooth(kStage.sun, a.sun, p, true));
      REQUIRE(m.planet_at_sun == scanned_tooth(kStage.planet, a.planet, pi, false));
      REQUIRE(m.planet_at_ring == scanned_tooth(kStage.planet, a.planet, 0.0, false));
      REQUIRE(m.ring == scanned_tooth(kStage.ring, a.ring, p, false));
    }
  }
  // One mesh period on: the sun's next tooth, the planet's and ring's previous.
  const std::vector<int> now = stage_state(0.5, start, psi);
  const std::vector<int> next = stage_state(1.5, start, psi);
  const std::array<int, 4> z{kStage.sun, kStage.planet, kStage.planet, kStage.ring};
  const std::array<int, 4> step{1, -1, -1, -1};
  for (std::size_t k = 0; k < now.size(); ++k) {
    CHECK(next[k] == (now[k] + step[k % 4] + z[k % 4]) % z[k % 4]);
  }
}

TEST_CASE("a ring-fixed stage's tooth pairings repeat after lcm(Z_s, Z_p, Z_r) mesh periods") {
  const long long period = stage_period_mesh_periods(kStage);
  CHECK(period == 25520);  // 2^4 5 11 29
  for (int planets : {3, 6}) {
    CAPTURE(planets);
    const std::vector<double> psi = equal_angles(planets);
    std::vector<std::vector<int>> states;
    for (long long i = 0; i < 2 * period; ++i) {
      // A quarter period in: the planet's sun-mesh crossings of an odd Z_p sit half a period
      // from its ring-mesh ones, and the sun's at thirds for these N; no sample on a crossing.
      states.push_back(stage_state(static_cast<double>(i) + 0.25, {0.0, 0.0, 0.0}, psi));
    }
    CHECK(least_period(states) == period);
  }
  // A stage of 2, 3 and 4 times a common count repeats at their lcm, not their product.
  CHECK(stage_period_mesh_periods({10, 15, 40}) == 120);
  CHECK_THROWS_AS(stage_period_mesh_periods({0, 15, 40}), InputError);
  CHECK_THROWS_AS(hunting_period_mesh_periods(20, 0), InputError);
}

TEST_CASE("the meshes' tooth crossings lag planet 1's by gamma_sn and gamma_rn") {
  // Equal spacing (N = 3) and an unequal set with (Z_s + Z_r) psi / 2 pi whole (102 psi / 2 pi).
  for (const std::vector<double>& psi :
       {equal_angles(3), std::vector<double>{0.0, 2.0 * pi * 35 / 102, 2.0 * pi * 70 / 102}}) {
    for (std::size_t n = 0; n < psi.size(); ++n) {
      CAPTURE(n);
      // The first t in [0, 1) where mesh n's sun (ring) tooth changes, by bisection on
      // the tooth index, from the members' tooth 0 at planet 1's mesh at t = 0.
      const auto first_change = [&](bool sun) {
        const auto tooth = [&](double t) {
          const StageAngles a = angles_at(t, {0.0, 0.0, 0.0});
          const StageMeshTeeth m = stage_mesh_teeth(kStage, psi[n], a.sun, a.planet, a.ring);
          return sun ? m.sun : m.ring;
        };
        // The change lies in (0, 1]: just after t = 0 the tooth is the one of t = 1 - 0.
        double lo = 1e-9;
        double hi = 1.0 - 1e-9;
        const int before = tooth(lo);
        if (tooth(hi) == before) return 0.0;  // it changed at t = 0 (a whole phase)
        for (int i = 0; i < 60; ++i) {
          const double mid = 0.5 * (lo + hi);
          (tooth(mid) == before ? lo : hi) = mid;
        }
        return hi;
      };
      // A crossing at 0 reads as lag 0; the bisection's bracket is 1e-9 wide at the ends.
      const double sun_lag = first_change(true);
      const double ring_lag = first_change(false);
      const double gamma_s = sun_mesh_phase(kStage.sun, psi[n]);
      const double gamma_r = ring_mesh_phase(kStage.ring, psi[n]);
      CHECK(std::fabs(sun_lag - gamma_s) < 1e-8);
      CHECK(std::fabs(ring_lag - gamma_r) < 1e-8);
      // Equal by assembly.
      CHECK(std::fabs(gamma_s - gamma_r) < 1e-9);
    }
  }
}

TEST_CASE("a faulted tooth's visits over a period give the stage's fault frequencies") {
  const long long period = stage_period_mesh_periods(kStage);
  for (int planets : {3, 6}) {
    CAPTURE(planets);
    const std::vector<double> psi = equal_angles(planets);
    const double carrier_hz = 7.5;
    const StageFaultFrequencies f = stage_fault_frequencies(kStage, planets, carrier_hz);
    const double mesh_hz = kStage.ring * carrier_hz;  // f_m = Z_r f_c, ring fixed
    CHECK(f.mesh_hz == mesh_hz);
    // Each mesh period a tooth sits at each mesh: count tooth 0's periods at a mesh.
    long long sun = 0;
    long long planet_sun = 0;
    long long planet_ring = 0;
    long long ring = 0;
    for (long long i = 0; i < period; ++i) {
      const std::vector<int> s = stage_state(static_cast<double>(i) + 0.25, {0.0, 0.0, 0.0}, psi);
      for (int n = 0; n < planets; ++n) {
        const auto at = static_cast<std::size_t>(4 * n);
        sun += s[at] == 0 ? 1 : 0;
        ring += s[at + 3] == 0 ? 1 : 0;
      }
      planet_sun += s[1] == 0 ? 1 : 0;  // planet 1's tooth 0
      planet_ring += s[2] == 0 ? 1 : 0;
    }
    const double seconds = static_cast<double>(period) / mesh_hz;
    const auto close = [](double counted, double formula) {
      return std::fabs(counted - formula) <= 1e-12 * formula;
    };
    CHECK(close(static_cast<double>(sun) / seconds, f.sun_tooth_hz));
    CHECK(close(static_cast<double>(planet_sun) / seconds, f.planet_tooth_hz));
    CHECK(close(static_cast<double>(planet_ring) / seconds, f.planet_tooth_hz));
    CHECK(close(static_cast<double>(ring) / seconds, f.ring_tooth_hz));
    // The formulas of docs/planetary.md written out.
    CHECK(close(f.sun_tooth_hz, planets * mesh_hz / kStage.sun));
    CHECK(close(f.planet_tooth_hz, mesh_hz / kStage.planet));
    CHECK(close(f.ring_tooth_hz, planets * carrier_hz));
  }
  CHECK_THROWS_AS(stage_fault_frequencies(kStage, 0, 1.0), InputError);
  CHECK_THROWS_AS(stage_fault_frequencies(kStage, 3, std::nan("")), InputError);
}
