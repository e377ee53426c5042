// Route A (a helical mesh by slices, docs/helical.md, Dynamics) on elastic bearings: each slice
// a line between the same two bodies, its transverse force on their centres. References: the
// torsional route-A run, which stiff bearings approach as their static deflection 2 F / k (each
// centre yields F / k along the transverse line of action, and the turning makes up the
// approach); the mirror symmetry of a face crowned symmetrically about mid-face, exact at every
// instant where kappa_t is uniform along the path and eps_alpha an integer (each slice then
// carries the same number of pairs of the same stiffness at every instant, so the mirrored
// slices see equal stiffness and equal gaps); the energy ledger, whose residual falls with the
// step at RK4's order.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/sliced_pair.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/helical_ste.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

using namespace gearimpact;

namespace {

// GEARpie's H501 (examples/helical_h501_run.toml): m_n 3.5 mm, alpha_n 20 deg, beta 15 deg,
// z 20/30, b 23 mm; crowned 10 um on the pinion, 4 slices.
SimulationCase crowned_h501() {
  SimulationCase c = paper_case(2);
  c.name = "h501-crowned";
  GearPair& p = c.gears;
  p = GearPair{};
  p.teeth1 = 20;
  p.teeth2 = 30;
  p.module_m = 3.5e-3;
  p.pressure_angle_rad = 20.0 * pi / 180.0;
  p.helix_angle_rad = 15.0 * pi / 180.0;
  p.face_width_m = 23e-3;
  p.profile_shift1 = 0.1809;
  p.profile_shift2 = 0.0891;
  p.youngs_modulus_pa = 206e9;
  p.poisson_ratio = 0.3;
  p.density_kg_m3 = 7830.0;
  p.backlash_m = 0.05e-3;
  c.model.friction_coefficient = 0.0;
  c.model.stiffness.face_slices = 4;
  c.modifications.gear1.lead.crowning_m = 10e-6;
  c.torque1.constant_n_m = 200.0;
  c.torque2.constant_n_m = -300.0;
  c.initial.w1_rad_per_s = 6000.0 * 2.0 * pi / 60.0;
  c.initial.w2_rad_per_s = c.initial.w1_rad_per_s * 20.0 / 30.0;
  c.integrator.step_s = 0.1e-6;
  c.integrator.end_time_s = 1e-3;
  return c;
}

// Both gears on isotropic bearings of stiffness k, damped at 0.6 of critical for the gear's
// mass on them (the planar model's disc of the transverse section).
SimulationCase on_bearings(SimulationCase c, double k) {
  c.bearings.kind = BearingKind::elastic;
  const PlanarMounting m = planar_mounting(dynamics_case(c));
  c.bearings.gear1.stiffness_x_n_per_m = k;
  c.bearings.gear2.stiffness_x_n_per_m = k;
  c.bearings.gear1.damping_x_n_s_per_m = 0.6 * std::sqrt(k * m.mass_kg[0]);
  c.bearings.gear2.damping_x_n_s_per_m = 0.6 * std::sqrt(k * m.mass_kg[1]);
  return c;
}

}  // namespace

TEST_CASE("route A on stiff bearings is the torsional route-A run offset by 2 F / k") {
  // The pinion driven at a constant 40 rad/s against the wheel's brake of 300 N*m, started at
  // the loaded STE's mean deflection and damped by the viscous mesh damper (zeta 0.3: the
  // start's transient e-folds in 0.16 ms, compared from 1 ms on). Quasi-static, the mesh
  // carries F = T2 / Rb2 plus the wheel's inertia force on both runs; on bearings each centre
  // yields F / k along the transverse line (the mesh force is along it, the bearings isotropic),
  // the centres approach by 2 F / k, and the wheel turns back by that much more: the turning s
  // = Rb1 theta1 - Rb2 theta2 of the planar run exceeds the torsional one's by 2 F / k.
  SimulationCase c = crowned_h501();
  c.model.damping_update = DampingUpdate::off;
  c.model.mesh_damping_ratio = 0.3;
  const double speed = 40.0;
  c.torque1 = Torque{};
  c.torque1.kind = Torque::Kind::prescribed_speed;
  c.torque1.mean_speed_rad_per_s = speed;
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 16;
  options.mesh_periods = 1;
  const HelicalStaticTransmissionError ste = helical_static_transmission_error(
      c.gears, c.modifications, 200.0, c.model.stiffness, options);
  const GearPair transverse = transverse_pair(c.gears);
  const double rb1 = base_radius(transverse, Gear::one);
  const double rb2 = base_radius(transverse, Gear::two);
  c.initial.w1_rad_per_s = speed;
  c.initial.w2_rad_per_s = speed * rb1 / rb2;
  c.initial.theta2_rad = -(c.gears.backlash_m + ste.ste_mean_m) / rb2;
  c.integrator.end_time_s = 1.25e-3;
  c.integrator.output_every = 5;
  double stiffest = 0.0;
  for (const auto& point : ste.points) {
    stiffest = std::max(stiffest, point.effective_stiffness_n_per_m);
  }
  // A kinematic driver: the train's run (simulate refuses it by route A for its rattle summary).
  const TrainResult rigid = simulate_train(two_gear_train(c));
  const PlanarMounting mounting = planar_mounting(dynamics_case(c));
  for (const double k : {1e11, 1e12}) {
    CAPTURE(k);
    GearTrain train = two_gear_train(c);
    for (std::size_t i = 0; i < 2; ++i) {
      GearBearing b;
      b.stiffness_x_n_per_m = k;
      b.damping_x_n_s_per_m = 0.6 * std::sqrt(k * mounting.mass_kg[i]);
      b.mass_kg = mounting.mass_kg[i];
      train.bodies[i].bearing = b;
    }
    // Within the planar train's step bound (check_planar_train_step) at each stiffness, the
    // rows at the torsional run's times.
    const int finer = k > 5e11 ? 4 : 2;
    train.integrator.step_s = c.integrator.step_s / finer;
    train.integrator.output_every = c.integrator.output_every * finer;
    const TrainResult planar = simulate_train(train);
    REQUIRE(planar.series.size() == rigid.series.size());
    double worst_s = 0.0;
    double worst_force = 0.0;
    double worst_speed = 0.0;
    double worst_held = 0.0;
    int compared = 0;
    for (std::size_t i = 0; i < rigid.series.size(); ++i) {
      const TrainRow& r = rigid.series[i];
      const TrainRow& p = planar.series[i];
      REQUIRE(std::fabs(r.t_s - p.t_s) < 1e-12);
      if (r.t_s < 1e-3) continue;
      double force = 0.0;
      double force_rigid = 0.0;
      for (const TrainMeshRow& m : p.meshes) force += m.line_force_n[0] + m.line_force_n[1];
      for (const TrainMeshRow& m : r.meshes) force_rigid += m.normal_force_n;
      // Each centre yields by its bearing's force over k (the contact's force and the mesh
      // damper's, both along the line); their sum over k is the approach along the line.
      const double expected = (std::hypot(p.centres[0].bearing_fx_n, p.centres[0].bearing_fy_n) +
                               std::hypot(p.centres[1].bearing_fx_n, p.centres[1].bearing_fy_n)) /
                              k;
      const double excess = (rb1 * p.theta_rad[0] - rb2 * p.theta_rad[1]) -
                            (rb1 * r.theta_rad[0] - rb2 * r.theta_rad[1]);
      worst_s = std::max(worst_s, std::fabs(excess - expected) / expected);
      worst_force = std::max(worst_force, std::fabs(force - force_rigid) / force_rigid);
      worst_speed =
          std::max(worst_speed, std::fabs(p.w_rad_per_s[1] - r.w_rad_per_s[1]) / r.w_rad_per_s[1]);
      // The bearings hold each centre against the mesh force: |F_bearing| = F.
      const double held = std::hypot(p.centres[0].bearing_fx_n, p.centres[0].bearing_fy_n);
      worst_held = std::max(worst_held, std::fabs(held - force) / force);
      ++compared;
    }
    MESSAGE("k = " << k << ": rows " << compared << ", |excess - 2F/k| / (2F/k) <= " << worst_s
                   << ", |F - F_rigid| / F <= " << worst_force << ", |w2 - w2_rigid| / w2 <= "
                   << worst_speed << ", ||F_bearing| - F| / F <= " << worst_held);
    REQUIRE(compared > 20);
    // The bearings in series with the mesh change its compliance by eps = 2 K / k (K the
    // loaded mesh's largest stiffness): the force and the wheel's speed, set by the torques and
    // the STE's ripple, move by at most eps of themselves (measured: 5.5e-6 and 8.6e-7 at
    // 1e11, a tenth of that at 1e12, where eps is 9e-3 and 9e-4).
    const double eps = 2.0 * stiffest / k;
    CHECK(worst_force < eps);
    CHECK(worst_speed < eps);
    // What the bearings' static deflection leaves: their dampers' share c u' and the centres'
    // inertia, u following F's ripple (measured 1.9e-4 and 1.6e-4 of the approach); 1e-3 of
    // it. Forces left off the centres would leave the whole approach.
    CHECK(worst_s < 1e-3);
    // The bearing holds the contact's force and the mesh damper's on the STE's ripple
    // (measured 2.2e-4 of F at both stiffnesses); 1e-3 of F.
    CHECK(worst_held < 1e-3);
  }
}

namespace {

// A pair whose transverse contact ratio is 2 (the addendum found by bisection), as the static
// test of the symmetric crowning has it (verify/stiffness/test_helical.cpp).
GearPair integer_eps_alpha_pair() {
  GearPair p;
  p.teeth1 = 30;
  p.teeth2 = 45;
  p.module_m = 3e-3;
  p.pressure_angle_rad = 20.0 * pi / 180.0;
  p.helix_angle_rad = 15.0 * pi / 180.0;
  p.face_width_m = 30e-3;
  p.youngs_modulus_pa = 206e9;
  p.poisson_ratio = 0.3;
  p.backlash_m = 0.05e-3;
  double low = 1.0;
  double high = 1.4;
  for (int i = 0; i < 200 && high - low > 0.0; ++i) {
    p.addendum_coefficient = 0.5 * (low + high);
    (helical_geometry(p).transverse_contact_ratio < 2.0 ? low : high) = p.addendum_coefficient;
  }
  p.dedendum_coefficient = p.addendum_coefficient + 0.25;
  return p;
}

}  // namespace

TEST_CASE("route A on bearings: a crowning symmetric about mid-face loads mirrored slices alike") {
  // With the stiffness of a real tooth the helix shift puts slices j and N-1-j at different
  // points of the path, where kappa_t differs, so their loads differ at an instant (and over a
  // mesh period too, s(t) not being constant). With kappa_t uniform along the path and
  // eps_alpha = 2, every slice carries two pairs of the same stiffness at every instant: the
  // mirrored slices then see equal stiffness and equal gaps (the crowning's y_j and y_{N-1-j}
  // mirrored about b/2), and their forces, contacts and impacts must be equal to round-off.
  // The run starts in the backlash: the driven pinion strikes, the centres move on their
  // bearings.
  SimulationCase c;
  c.name = "symmetric-crowning";
  c.gears = integer_eps_alpha_pair();
  c.model.friction_coefficient = 0.0;
  c.model.stiffness.face_slices = 8;
  c.modifications.gear1.lead.crowning_m = 6e-6;
  c.modifications.gear2.lead.crowning_m = 2e-6;
  c.torque1.constant_n_m = 150.0;
  c.torque2.constant_n_m = -225.0;
  c.initial.w1_rad_per_s = 300.0;
  c.initial.w2_rad_per_s = 0.98 * 300.0 * 30.0 / 45.0;
  c.integrator.step_s = 1e-7;
  c.integrator.end_time_s = 0.5e-3;
  GearTrain train = dynamics_train(two_gear_train(c));
  const int n = c.model.stiffness.face_slices;
  REQUIRE(static_cast<int>(train.meshes.size()) == n);
  // The slices' table of a uniform kappa_t (8.5e9 N/m^2, the static test's), each term over the
  // slice's width as helical_slice_meshes builds it.
  const auto face = std::make_shared<const FaceStiffness>(FaceStiffness::uniform(c.gears, 8.5e9));
  const double db = c.gears.face_width_m / n;
  const auto table =
      std::make_shared<const StiffnessTable>(face->start_m(), face->end_m(), [face, db](double x) {
        Compliances k = face->compliance_per_width(x);
        for (double& term : k.m_per_n) term /= db;
        return k;
      });
  for (TrainMesh& m : train.meshes) m.table = table;
  const GearPair transverse = transverse_pair(c.gears);
  for (std::size_t i = 0; i < 2; ++i) {
    GearBearing b;
    b.stiffness_x_n_per_m = 3e8;
    b.damping_x_n_s_per_m = 150.0;
    b.mass_kg = disc_mass(transverse, i == 0 ? Gear::one : Gear::two);
    train.bodies[i].bearing = b;
  }
  const TrainResult r = simulate_train(train);
  const double nominal = c.torque1.constant_n_m / base_radius(transverse, Gear::one) / n;
  double worst = 0.0;
  double largest = 0.0;
  for (const TrainRow& row : r.series) {
    REQUIRE(row.meshes.size() == static_cast<std::size_t>(n));
    for (int j = 0; j < n / 2; ++j) {
      const TrainMeshRow& a = row.meshes[static_cast<std::size_t>(j)];
      const TrainMeshRow& b = row.meshes[static_cast<std::size_t>(n - 1 - j)];
      worst = std::max(worst, std::fabs(a.normal_force_n - b.normal_force_n));
      largest = std::max(largest, a.normal_force_n);
      CHECK(a.region == b.region);
    }
  }
  MESSAGE("largest slice force " << largest << " N (nominal " << nominal
                                 << " N), largest mirrored difference " << worst << " N");
  REQUIRE(largest > nominal);
  // Round-off of the mirrored gaps and of the events each slice locates at its own instants
  // (measured 5e-13 of the nominal slice force); 1e-9 of it, where a slice's gap off its
  // mirror's by 1 nm would leave its two pairs' stiffness (6.4e7 N/m) times 1 nm, 1.5e-4.
  CHECK(worst < 1e-9 * nominal);
  // A slice may book a contact begun twice at one located instant (it touches, leaves and
  // touches again within the event's round-off, measured on slice 2 at 0.264 ms); the
  // distinct instants are compared.
  const auto distinct = [](const std::vector<ImpactRecord>& all) {
    std::vector<ImpactRecord> kept;
    for (const ImpactRecord& x : all) {
      if (kept.empty() || std::fabs(x.start_s - kept.back().start_s) > 1e-12) kept.push_back(x);
    }
    return kept;
  };
  for (int j = 0; j < n / 2; ++j) {
    CAPTURE(j);
    const std::vector<ImpactRecord> a = distinct(r.impacts[static_cast<std::size_t>(j)]);
    const std::vector<ImpactRecord> b = distinct(r.impacts[static_cast<std::size_t>(n - 1 - j)]);
    REQUIRE(!a.empty());
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      CHECK(a[i].line == b[i].line);
      // The event location's resolution (a step of 1e-7 s cut to round-off of its length).
      CHECK(std::fabs(a[i].start_s - b[i].start_s) < 1e-12);
      CHECK(std::fabs(a[i].impact_speed_m_s - b[i].impact_speed_m_s) <
            1e-9 * std::fabs(a[i].impact_speed_m_s));
    }
    CHECK(std::fabs(r.meshes[static_cast<std::size_t>(j)].damping_loss_j -
                    r.meshes[static_cast<std::size_t>(n - 1 - j)].damping_loss_j) <
          1e-9 * r.summary.damping_loss_j);
  }
}

namespace {

// The crowned H501 on damped bearings of 3e8 N/m, the wheel started in the backlash: impacts on
// every slice, the centres moving.
SimulationCase impacting_on_bearings(double step) {
  SimulationCase c = on_bearings(crowned_h501(), 3e8);
  c.integrator.step_s = step;
  c.integrator.end_time_s = 0.5e-3;
  c.integrator.output_every = 1000;
  return c;
}

}  // namespace

TEST_CASE("route A on bearings closes its ledger at RK4's order, bearings included") {
  const SimulationResult coarse = simulate(impacting_on_bearings(4e-7));
  // The fine run streams its planar rows as the program does (keep_series off): the start,
  // every 1000th of its 2500 steps and the end.
  RunControl streamed;
  streamed.keep_series = false;
  std::vector<PlanarRow> rows;
  streamed.on_planar_row = [&rows](const PlanarRow& row) { rows.push_back(row); };
  const SimulationResult fine = simulate(impacting_on_bearings(2e-7), streamed);
  CHECK(fine.planar_series.empty());
  REQUIRE(rows.size() == 4);
  // The grid time 2000 h and the end, to their rounding.
  CHECK(std::fabs(rows[2].t_s - 4e-4) < 1e-15);
  CHECK(std::fabs(rows[3].t_s - 5e-4) < 1e-15);
  REQUIRE(coarse.planar_series.size() == coarse.series.size());
  for (std::size_t i = 0; i < coarse.series.size(); ++i) {
    const PlanarRow& p = coarse.planar_series[i];
    // The two series' forces are the same slices' sums, added in another order.
    CHECK(std::fabs(p.drive_force_n + p.coast_force_n - coarse.series[i].normal_force_n) <=
          1e-12 * std::max(1.0, coarse.series[i].normal_force_n));
    CHECK(p.state.theta1_rad == coarse.series[i].theta1_rad);
  }
  for (const SimulationResult* r : {&coarse, &fine}) {
    REQUIRE(r->summary.slices.size() == 4);
    for (const SliceSummary& s : r->summary.slices) REQUIRE(s.impacts_n1 + s.impacts_n2 >= 1);
    REQUIRE(r->summary.planar.has_value());
    REQUIRE(r->summary.planar->bearing_damping_loss_j > 0.0);
    REQUIRE(r->summary.damping_loss_j > 0.0);
  }
  const double scale = coarse.summary.ledger_scale_j;
  MESSAGE("ledger residual " << coarse.summary.ledger_residual_max_j << " J (h = 4e-7 s), "
                             << fine.summary.ledger_residual_max_j << " J (h = 2e-7 s) of " << scale
                             << " J");
  // As the train on bearings: RK4's (omega h)^4 per period of exchange, most of it
  // cancelling; 1e-7 of the scale bounds it.
  CHECK(coarse.summary.ledger_residual_max_j / scale < 1e-7);
  // Fourth order: halving h divides it by about 16; events cut steps: 8.
  CHECK(fine.summary.ledger_residual_max_j < coarse.summary.ledger_residual_max_j / 8.0);
}

TEST_CASE("route A on elastic bearings refuses what the planar train does not run, by its key") {
  SimulationCase c = on_bearings(crowned_h501(), 3e8);
  c.integrator.end_time_s = 1e-5;
  REQUIRE(runs_by_slices(c));
  const auto field_of = [](const SimulationCase& e) {
    try {
      (void)simulate(e);
    } catch (const InputError& error) {
      return error.problems().front().field;
    }
    return std::string("none");
  };
  SUBCASE("a motor and a load behind shafts") {
    c.shafts.kind = ShaftKind::elastic;
    c.shafts.motor_inertia_kg_m2 = 1e-3;
    c.shafts.load_inertia_kg_m2 = 1e-3;
    c.shafts.motor_stiffness_n_m_per_rad = 1e4;
    c.shafts.load_stiffness_n_m_per_rad = 1e4;
    CHECK(field_of(c) == "shafts.kind");
  }
  SUBCASE("a tacho, whose edges the train's loop does not locate") {
    c.tacho.pulses_per_revolution = 1;
    CHECK(field_of(c) == "tacho.pulses_per_revolution");
  }
  SUBCASE("a speed controller") {
    c.torque1 = Torque{};
    c.torque1.kind = Torque::Kind::speed_controlled;
    c.torque1.mean_speed_rad_per_s = c.initial.w1_rad_per_s;
    CHECK(field_of(c) == "torque1.kind");
  }
  SUBCASE("the Lagrangian mesh force") {
    c.model.mesh_force = MeshForce::lagrangian;
    CHECK(field_of(c) == "model.mesh_force");
  }
  SUBCASE("friction together with a fault (a fault alone runs: its bands laid across the slices)") {
    ToothFault missing;
    missing.state.kind = ToothKind::missing;
    c.faults.push_back(missing);
    CHECK(field_of(c) == "none");
    c.model.friction_coefficient = 0.05;
    CHECK(field_of(c) == "model.friction_coefficient");
  }
  SUBCASE("the adaptive integrator") {
    c.integrator.kind = IntegratorKind::adaptive;
    CHECK(field_of(c) == "integrator.kind");
  }
  SUBCASE("a bearing's negative stiffness, named as the pair's key") {
    c.bearings.gear2.stiffness_x_n_per_m = -1.0;
    CHECK(field_of(c).find("stiffness_x2") != std::string::npos);
  }
  SUBCASE("a step the bearings do not let through") {
    c.bearings.gear1.stiffness_x_n_per_m = 1e13;
    CHECK(field_of(c) == "integrator.step");
  }
}
