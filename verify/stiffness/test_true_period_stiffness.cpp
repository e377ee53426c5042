// The mesh stiffness over the true period (time_varying_stiffness.hpp, docs/faults.md): one
// origin with the healthy mesh period (the healthy CSV to the bit), its mean against an
// independent sum of per-pair means from the dynamics' tables, the teeth of each pair.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/numerics/quadrature.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

ToothFault crack_on(Gear gear, int tooth, double depth_m) {
  ToothFault f;
  f.gear = gear;
  f.tooth = tooth;
  f.state.kind = ToothKind::root_crack;
  f.state.crack.depth_m = depth_m;
  f.state.crack.angle_rad = pi / 4.0;
  return f;
}

ToothFault missing_on(Gear gear, int tooth) {
  ToothFault f;
  f.gear = gear;
  f.tooth = tooth;
  f.state.kind = ToothKind::missing;
  return f;
}

// (1 / t0) Int Ke dX over the contact segment of one table: the mean a pair of these teeth
// adds to the mesh over one mesh period, since each position of the segment is passed once a
// base pitch (Boost's Gauss-Kronrod, a route the command does not take, on the fitted table
// the dynamics reads rather than mesh_stiffness itself).
double pair_mean(const GearPair& g, const StiffnessTable* table) {
  if (table == nullptr) return 0.0;
  const ContactSegment segment = contact_segment(g);
  return integrate_boost_gauss_kronrod([&](double x) { return table->stiffness(x); },
                                       segment.start_m, segment.end_m, {1e-10, 0.0})
             .value /
         base_pitch(g);
}

bool has_tooth(const TruePeriodSample& s, Gear gear, int tooth) {
  for (const TeethInContact& t : s.teeth) {
    if ((gear == Gear::one ? t.pinion_tooth : t.wheel_tooth) == tooth) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("without faults: one mesh period, the healthy CSV's samples and summary to the bit") {
  const GearPair g = paper_gear_pair();
  const StiffnessModel model;
  const TimeVaryingMeshStiffness healthy = time_varying_mesh_stiffness(g, model, 60);
  const TruePeriodMeshStiffness t = true_period_mesh_stiffness(g, model, {}, 60);
  CHECK(t.mesh_periods == 1);
  CHECK(t.period_kind == "mesh");
  REQUIRE(t.samples.size() == healthy.samples.size());
  for (std::size_t i = 0; i < t.samples.size(); ++i) {
    CHECK(t.samples[i].fraction == healthy.samples[i].fraction);
    CHECK(t.samples[i].theta1_rad == healthy.samples[i].theta1_rad);
    CHECK(t.samples[i].teeth.size() == static_cast<std::size_t>(healthy.samples[i].pairs));
    CHECK(t.samples[i].ke_n_per_m == healthy.samples[i].stiffness_n_per_m);
    CHECK(t.samples[i].healthy_ke_n_per_m == healthy.samples[i].stiffness_n_per_m);
  }
  CHECK(t.min_n_per_m == healthy.min_n_per_m);
  CHECK(t.max_n_per_m == healthy.max_n_per_m);
  CHECK(t.mean_n_per_m == healthy.mean_n_per_m);
  CHECK(t.min_at_fraction == healthy.min_at_fraction);
  // The origin: pair 0/0 at X_start, which the simulation reaches at theta1 = (X_start -
  // X_pitch) / Rb1 (MeshLayout: X = X_pitch + Rb1 theta1 on N1).
  const double expected =
      (contact_segment(g).start_m - pitch_point_position(g)) / base_radius(g, Gear::one);
  CHECK(relative_difference(t.simulation_theta1_offset_rad, expected) < 1e-14);
  CHECK(t.samples[0].teeth[0].pinion_tooth == 0);
  CHECK(t.samples[0].teeth[0].wheel_tooth == 0);
}

TEST_CASE("one origin: a faulted mesh equals the healthy one wherever the faulted tooth is out") {
  const GearPair g = paper_gear_pair();
  const StiffnessModel model;
  const std::size_t n = 40;
  const TimeVaryingMeshStiffness healthy = time_varying_mesh_stiffness(g, model, n);
  const int z1 = g.teeth1;
  SUBCASE("a crack of zero depth is the healthy mesh over the whole revolution") {
    // The paper's route returns the healthy tooth's compliances for q = 0, to the bit.
    const TruePeriodMeshStiffness t =
        true_period_mesh_stiffness(g, model, {crack_on(Gear::one, 5, 0.0)}, n);
    REQUIRE(t.samples.size() == n * static_cast<std::size_t>(z1));
    for (std::size_t i = 0; i < t.samples.size(); ++i) {
      CHECK(t.samples[i].ke_n_per_m == healthy.samples[i % n].stiffness_n_per_m);
    }
  }
  SUBCASE("a cracked and a missing tooth: the other teeth's samples are the healthy ones") {
    for (const ToothFault& fault : {crack_on(Gear::one, 5, 0.8e-3), missing_on(Gear::one, 5)}) {
      CAPTURE(to_string(fault.state.kind));
      const TruePeriodMeshStiffness t = true_period_mesh_stiffness(g, model, {fault}, n);
      CHECK(t.period_kind == "pinion-revolution");
      REQUIRE(t.samples.size() == n * static_cast<std::size_t>(z1));
      int with_fault = 0;
      for (std::size_t i = 0; i < t.samples.size(); ++i) {
        const TruePeriodSample& s = t.samples[i];
        // The theta1 of sample i: the healthy one of its place in the mesh period, plus whole
        // mesh periods.
        const double mesh_period_rad = 2.0 * pi / z1;
        CHECK(std::fabs(s.theta1_rad - healthy.samples[i % n].theta1_rad -
                        static_cast<double>(i / n) * mesh_period_rad) < 1e-13);
        CHECK(s.teeth.size() == static_cast<std::size_t>(healthy.samples[i % n].pairs));
        if (has_tooth(s, Gear::one, 5)) {
          ++with_fault;
          CHECK(s.ke_n_per_m < healthy.samples[i % n].stiffness_n_per_m);
        } else {
          CHECK(s.ke_n_per_m == healthy.samples[i % n].stiffness_n_per_m);
        }
      }
      // Pinion tooth 5 enters at the start of mesh period 5 (the origin is tooth 0 entering) and
      // stays eps_alpha mesh periods.
      CHECK(t.samples[5 * n].teeth[0].pinion_tooth == 5);
      CHECK(!has_tooth(t.samples[5 * n - 1], Gear::one, 5));
      const double eps_alpha = contact_ratio(g);
      CHECK(std::fabs(with_fault / static_cast<double>(n) - eps_alpha) <= 1.0 / n);
    }
  }
}

TEST_CASE("the mean over the true period is (z-1)/z healthy plus 1/z faulted pair means") {
  // Over a pinion revolution every pinion tooth's pair passes the contact segment once, so the
  // mean is the sum of the z1 pairs' means over z1: (z1 - 1) healthy pairs and the faulted one.
  // Reference: each pair's mean from the dynamics' fitted tables (relative error <= 1e-12 of
  // Ke) by Gauss-Kronrod at 1e-10 (the tables' pieces join with a kink at rounding level, which
  // 1e-12 cannot resolve); the command integrates mesh_stiffness itself by GSL QAG at 1e-10 on
  // each piece, so they agree to 1e-9 (five times the sum of the two).
  const GearPair g = paper_gear_pair();
  const StiffnessModel model;
  const double z1 = g.teeth1;
  for (const ToothFault& fault : {crack_on(Gear::one, 7, 1.0e-3), missing_on(Gear::one, 7)}) {
    CAPTURE(to_string(fault.state.kind));
    const MeshTables tables(g, model, {fault});
    const double healthy = pair_mean(g, &tables.healthy());
    const double faulted = pair_mean(g, tables.table_of_teeth(7, 7));
    const double expected = (z1 - 1.0) / z1 * healthy + faulted / z1;
    const TruePeriodMeshStiffness t = true_period_mesh_stiffness(g, model, {fault}, 8);
    MESSAGE("mean " << t.mean_n_per_m << " against " << expected << ": "
                    << relative_difference(t.mean_n_per_m, expected));
    CHECK(relative_difference(t.mean_n_per_m, expected) < 1e-9);
    CHECK(relative_difference(t.healthy_mean_n_per_m, healthy) < 1e-9);
    CHECK(t.mean_n_per_m < t.healthy_mean_n_per_m);
    if (fault.state.kind == ToothKind::missing) CHECK(faulted == 0.0);
  }
}

TEST_CASE("a wheel tooth and a pinion tooth: the hunting period, every pair named") {
  const GearPair g = paper_gear_pair();
  const TruePeriodMeshStiffness t = true_period_mesh_stiffness(
      g, {}, {crack_on(Gear::one, 1, 0.5e-3), missing_on(Gear::two, 2)}, 4);
  const long long hunting =
      std::lcm(static_cast<long long>(g.teeth1), static_cast<long long>(g.teeth2));
  CHECK(t.period_kind == "hunting");
  CHECK(t.mesh_periods == hunting);
  REQUIRE(t.samples.size() == 4u * static_cast<std::size_t>(hunting));
  for (std::size_t i = 0; i < t.samples.size(); ++i) {
    // Pair j of sample i entered in mesh period i / 4 - j: the n-th pair to enter is pinion
    // tooth n mod z1 against wheel tooth n mod z2 (tooth_identity.hpp).
    for (std::size_t j = 0; j < t.samples[i].teeth.size(); ++j) {
      const long long entered = static_cast<long long>(i / 4) - static_cast<long long>(j);
      const long long pinion = ((entered % g.teeth1) + g.teeth1) % g.teeth1;
      const long long wheel = ((entered % g.teeth2) + g.teeth2) % g.teeth2;
      CHECK(t.samples[i].teeth[j].pinion_tooth == pinion);
      CHECK(t.samples[i].teeth[j].wheel_tooth == wheel);
      if (wheel == 2) CHECK(t.samples[i].pair_ke_n_per_m[j] == 0.0);
    }
  }
}

TEST_CASE("samples beyond the true period's bound are refused naming samples") {
  const GearPair g = paper_gear_pair();
  try {
    true_period_mesh_stiffness(g, {}, {missing_on(Gear::one, 0)}, kMostTruePeriodSamples);
    FAIL("accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "samples");
    CHECK(e.allowed().find("per mesh period") != std::string::npos);
  }
}
