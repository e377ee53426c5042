// The torsional gear train (dynamics/train.hpp): bodies, meshes and shafts
// through the run loop of the two-gear model. References: the two-gear
// torsional run itself where the train is that model written another way (a
// two-body train, two discs on one rigid shaft), which must agree bit for bit;
// the closed forms of a linear three-body train (kinematic ratio, reflected
// inertia, the natural frequencies and shapes of the 3-DOF M, K); the energy
// balance, whose residual falls with the step at the integrator's order.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "speed_cases.hpp"

using namespace gearimpact;

namespace {

// The table of a run, shared with a train's mesh without owning it.
std::shared_ptr<const StiffnessTable> borrowed(const StiffnessTable& table) {
  return {&table, [](const StiffnessTable*) {}};
}

// Every column of every row, and the run's counts and ledger, the same bits.
void require_same_run(const SimulationResult& two_gear, const TrainResult& train, int wheel_body) {
  REQUIRE(train.series.size() == two_gear.series.size());
  for (std::size_t i = 0; i < two_gear.series.size(); ++i) {
    const SeriesRow& a = two_gear.series[i];
    const TrainRow& b = train.series[i];
    const TrainMeshRow& m = b.meshes[0];
    const auto wheel = static_cast<std::size_t>(wheel_body);
    const bool same =
        a.t_s == b.t_s && a.theta1_rad == b.theta_rad[0] && a.theta2_rad == b.theta_rad[wheel] &&
        a.w1_rad_per_s == b.w_rad_per_s[0] && a.w2_rad_per_s == b.w_rad_per_s[wheel] &&
        a.s_m == m.s_m && a.delta_m == m.delta_m && a.region == m.region && a.pairs == m.pairs &&
        a.normal_force_n == m.normal_force_n && a.friction_force_n == m.friction_force_n;
    if (!same) {
      INFO("row " << i << " at t = " << a.t_s);
      REQUIRE(same);
    }
  }
  const SimulationSummary& s = two_gear.summary;
  const SimulationSummary& t = train.summary;
  CHECK(t.steps == s.steps);
  CHECK(t.events == s.events);
  CHECK(t.rhs_evaluations == s.rhs_evaluations);
  CHECK(t.damping_loss_j == s.damping_loss_j);
  CHECK(t.friction_loss_j == s.friction_loss_j);
  CHECK(t.torque_work_j == s.torque_work_j);
  CHECK(t.parametric_work_j == s.parametric_work_j);
  CHECK(t.ledger_residual_max_j == s.ledger_residual_max_j);
  CHECK(t.stored_energy_final_j == s.stored_energy_final_j);
  CHECK(t.kinetic_energy_final_j == s.kinetic_energy_final_j);
  CHECK(t.mesh_damping_loss_j == s.mesh_damping_loss_j);
  CHECK(t.stored_energy_jumps_j == s.stored_energy_jumps_j);
  CHECK(t.mesh_damper == s.mesh_damper);
  CHECK(t.kinetic_energy_initial_j == s.kinetic_energy_initial_j);
  CHECK(t.stored_energy_initial_j == s.stored_energy_initial_j);
  CHECK(t.energy_max_j == s.energy_max_j);
  // The impacts, booked by the same book: their counts, times and records.
  CHECK(t.impacts_n1 == s.impacts_n1);
  CHECK(t.impacts_n2 == s.impacts_n2);
  CHECK(t.first_impact_s == s.first_impact_s);
  CHECK(t.first_impact_speed_m_s == s.first_impact_speed_m_s);
  CHECK(t.last_n1_impact_s == s.last_n1_impact_s);
  CHECK(t.last_n2_impact_s == s.last_n2_impact_s);
  REQUIRE(train.impacts.size() == 1);
  REQUIRE(train.impacts[0].size() == two_gear.impacts.size());
  CHECK(train.meshes[0].impacts == static_cast<int>(two_gear.impacts.size()));
  for (std::size_t i = 0; i < two_gear.impacts.size(); ++i) {
    const ImpactRecord& a = two_gear.impacts[i];
    const ImpactRecord& b = train.impacts[0][i];
    const bool same = a.line == b.line && a.start_s == b.start_s &&
                      a.impact_speed_m_s == b.impact_speed_m_s && a.restitution == b.restitution &&
                      a.end_s == b.end_s && a.end_speed_m_s == b.end_speed_m_s;
    if (!same) {
      INFO("impact " << i << " at t = " << a.start_s);
      REQUIRE(same);
    }
  }
  CHECK(train.meshes[0].max_penetration_m == s.max_penetration_m);
  // The one mesh's own losses are the train's, and the two-gear run's, to the bit; its bodies'
  // final speeds the two gears'.
  CHECK(train.meshes[0].damping_loss_j == s.damping_loss_j);
  CHECK(train.meshes[0].friction_loss_j == s.friction_loss_j);
  CHECK(train.meshes[0].mesh_damping_loss_j == s.mesh_damping_loss_j);
  CHECK(train.bodies[0].final_w_rad_per_s == s.final_w1_rad_per_s);
  CHECK(train.bodies[static_cast<std::size_t>(wheel_body)].final_w_rad_per_s ==
        s.final_w2_rad_per_s);
  CHECK(train.summary.speed_drift_max_rel == s.speed_drift_max_rel);
}

// Both tips relieved linearly (examples/tip_relief_20_80.toml's start diameters).
Modifications tip_relief(double amount_m) {
  Modifications m;
  m.gear1.tip = {amount_m, 43.2e-3, ReliefShape::linear};
  m.gear2.tip = {amount_m, 163.2e-3, ReliefShape::linear};
  return m;
}

}  // namespace

namespace {

// The case as a two-body train (the two-gear run's table lent to its mesh) runs the two-gear run
// bit for bit: its series, summary and impacts (require_same_run), over more than 10 events.
void require_train_runs_as_two_gear(const SimulationCase& c, const StiffnessTable& table) {
  CAPTURE(c.name);
  const SimulationResult two_gear = simulate(c, table);
  GearTrain train = two_gear_train(c);
  train.meshes[0].table = borrowed(table);
  const TrainResult result = simulate_train(train);
  REQUIRE(two_gear.summary.events > 10);
  CHECK(result.summary.integrator == two_gear.summary.integrator);
  require_same_run(two_gear, result, 1);
}

}  // namespace

TEST_CASE("a two-body train is the two-gear torsional run, bit for bit") {
  // Case 2 (torques, impacts, friction reversals, pairs entering and
  // leaving); case 1 with tip relief (each pair's gap, touching and kinks);
  // case 2 again by the fixed-step Dormand-Prince, which both take through
  // the same FixedStepper.
  SimulationCase loaded = paper_case(2);
  loaded.integrator.end_time_s = 2e-3;
  SimulationCase relieved = paper_case(1);
  relieved.modifications = tip_relief(10e-6);
  relieved.integrator.end_time_s = 2e-3;
  SimulationCase dopri5 = loaded;
  dopri5.integrator.kind = IntegratorKind::dopri5;
  const StiffnessTable table(loaded.gears, loaded.model.stiffness);
  for (const SimulationCase* c : {&loaded, &relieved, &dopri5}) {
    require_train_runs_as_two_gear(*c, table);
  }
}

TEST_CASE("a two-body train takes every integrator, mesh force, damper and drive bit for bit") {
  // Each of what a train once refused, on the two-body train of a case that
  // the two-gear torsional run takes: the same numbers, row by row.
  const StiffnessTable table(paper_gear_pair(), paper_case(2).model.stiffness);
  SimulationCase loaded = paper_case(2);
  loaded.integrator.end_time_s = 2e-3;
  SimulationCase adaptive = loaded;
  adaptive.name = "adaptive";
  adaptive.integrator.kind = IntegratorKind::adaptive;
  SimulationCase lagrangian = loaded;
  lagrangian.name = "lagrangian";
  lagrangian.model.mesh_force = MeshForce::lagrangian;
  SimulationCase lagrangian_adaptive = lagrangian;
  lagrangian_adaptive.name = "lagrangian-adaptive";
  lagrangian_adaptive.integrator.kind = IntegratorKind::adaptive;
  SimulationCase damper = loaded;
  damper.name = "mesh-damper";
  damper.model.mesh_damping_ratio = 0.05;
  // A driver with a speed harmonic against a drag: the wheel rattles.
  SimulationCase driven = verify::driven_with_harmonic(paper_case(1));
  driven.name = "driver-drag";
  driven.integrator.end_time_s = 2e-3;
  driven.torque2 = Torque{};
  driven.torque2.kind = Torque::Kind::drag;
  driven.torque2.drag_constant_n_m = 2.0;
  driven.torque2.drag_viscous_n_m_s = 1e-3;
  SimulationCase driven_lagrangian = driven;
  driven_lagrangian.name = "driver-lagrangian";
  driven_lagrangian.model.mesh_force = MeshForce::lagrangian;
  driven_lagrangian.model.mesh_damping_ratio = 0.05;
  // A speed controller and an induction motor against the case's load.
  SimulationCase controlled = loaded;
  controlled.name = "speed-controller";
  controlled.torque1 = Torque{};
  controlled.torque1.kind = Torque::Kind::speed_controlled;
  controlled.torque1.mean_speed_rad_per_s = loaded.initial.w1_rad_per_s;
  controlled.torque1.controller_bandwidth_rad_per_s = 2.0 * pi * 50.0;
  controlled.torque1.controller_damping_ratio = 1.0;
  SimulationCase motor = loaded;
  motor.name = "induction-motor";
  motor.torque1 = Torque{};
  motor.torque1.kind = Torque::Kind::induction_motor;
  motor.torque1.breakdown_torque_n_m = 3.0 * std::fabs(loaded.torque1.constant_n_m);
  motor.torque1.breakdown_slip = 0.1;
  motor.torque1.synchronous_speed_rad_per_s = 1.02 * loaded.initial.w1_rad_per_s;
  for (const SimulationCase* c : {&adaptive, &lagrangian, &lagrangian_adaptive, &damper, &driven,
                                  &driven_lagrangian, &controlled, &motor}) {
    require_train_runs_as_two_gear(*c, table);
  }
  // The drift check over whole revolutions of the pinion (the train's first body): the
  // controller at 500 rad/s from the start (drive.settle 0), 2.2 revolutions.
  SimulationCase drift = verify::held_at_speed(controlled, 500.0, 2.2);
  drift.name = "speed-drift";
  require_train_runs_as_two_gear(drift, table);
  // Each feature did what it does.
  REQUIRE(simulate(drift, table).summary.speed_drift_max_rel.has_value());
  CHECK(simulate(lagrangian, table).summary.stored_energy_jumps_j > 0.0);
  CHECK(simulate(damper, table).summary.mesh_damping_loss_j > 0.0);
}

TEST_CASE("two discs on one rigid shaft are one wheel of their summed inertia, bit for bit") {
  SimulationCase c = paper_case(2);
  c.integrator.end_time_s = 4e-4;
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SimulationResult two_gear = simulate(c, table);
  GearTrain train = two_gear_train(c);
  train.meshes[0].table = borrowed(table);
  // The wheel's inertia split between the wheel and a disc on its shaft: J2 = J2a + J2b exactly.
  const double j2 = train.bodies[1].inertia_kg_m2;
  TrainBody disc;
  disc.name = "disc";
  disc.inertia_kg_m2 = 0.375 * j2;
  disc.theta_rad = c.initial.theta2_rad;
  disc.w_rad_per_s = c.initial.w2_rad_per_s;
  train.bodies[1].inertia_kg_m2 = j2 - disc.inertia_kg_m2;
  REQUIRE(train.bodies[1].inertia_kg_m2 + disc.inertia_kg_m2 == j2);
  // The disc first, so that the shaft's body is not the mesh's own index.
  train.bodies.insert(train.bodies.begin() + 1, disc);
  train.meshes[0].body_b = 2;
  TrainShaft shaft;
  shaft.kind = TrainShaft::Kind::rigid;
  shaft.body_a = 2;
  shaft.body_b = 1;
  train.shafts = {shaft};
  const TrainResult result = simulate_train(train);
  require_same_run(two_gear, result, 2);
  for (const TrainRow& row : result.series) {
    REQUIRE(row.theta_rad[1] == row.theta_rad[2]);
    REQUIRE(row.w_rad_per_s[1] == row.w_rad_per_s[2]);
  }
}

TEST_CASE("a rigid second stage reduces a two-stage train to one pair") {
  // The rigid form: the countershaft (wheel 1 and pinion 2) with stage 2's wheel reflected onto
  // it, J4 (Rb3/Rb4)^2 and its load T4 Rb3/Rb4, is a pair whose wheel has
  // J_2eff = J_w1 + J3 + J4 (Rb3/Rb4)^2 (docs/planetary.md, Multi-stage parallel trains). The
  // two-gear run of the paper's case 2 is that pair when J_2eff is its wheel's disc and the
  // reflected load its torque2: bit for bit. Then the intermediate shaft made a torsional spring:
  // as it stiffens, the train tends to the rigid form with a gap falling as 1/k.
  SimulationCase c = paper_case(2);
  c.integrator.end_time_s = 4e-4;
  // A step that resolves the stiffest spring's own mode below (w h ~ 0.3: stage 2's mesh at
  // 1e15 N/m, Rb3^2 k34 ~ 5e11 N m/rad against J3 ~ 1e-3 kg m^2).
  c.integrator.step_s = 1.25e-8;
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SimulationResult two_gear = simulate(c, table);
  const double j2eff = moment_of_inertia(c.gears, Gear::two);
  // Stage 2: 24 teeth driving 36 (Rb3/Rb4 = 2/3), its discs a quarter and a ninth of J_2eff's
  // share each, in binary fractions so that the three inertias sum to J_2eff exactly.
  const double rb_ratio = 24.0 / 36.0;
  const double j3 = 0.25 * j2eff;
  const double j4_reflected = 0.125 * j2eff;  // J4 (Rb3/Rb4)^2: J4 = 0.28125 J_2eff
  const double jw1 = j2eff - j3 - j4_reflected;
  REQUIRE(jw1 + j3 + j4_reflected == j2eff);
  REQUIRE(std::fabs(j4_reflected / (rb_ratio * rb_ratio) - 0.28125 * j2eff) < 1e-15 * j2eff);
  const auto rigid_form = [&](const TrainShaft::Kind intermediate, double stiffness) {
    GearTrain train = two_gear_train(c);
    train.meshes[0].table = borrowed(table);
    train.bodies[1].inertia_kg_m2 = jw1;
    train.bodies[1].torque = Torque{};
    TrainBody pinion2 = train.bodies[1];
    pinion2.name = "pinion2";
    pinion2.inertia_kg_m2 = j3;
    TrainBody wheel4 = pinion2;
    wheel4.name = "wheel4-reflected";
    wheel4.inertia_kg_m2 = j4_reflected;
    wheel4.torque = c.torque2;  // T4 Rb3/Rb4, the load reflected to the countershaft
    train.bodies.push_back(pinion2);
    train.bodies.push_back(wheel4);
    TrainShaft shaft;
    shaft.kind = intermediate;
    shaft.body_a = 1;
    shaft.body_b = 2;
    shaft.stiffness_n_m_per_rad = stiffness;
    TrainShaft reflected;
    reflected.body_a = 2;
    reflected.body_b = 3;
    train.shafts = {shaft, reflected};
    return train;
  };
  const TrainResult rigid = simulate_train(rigid_form(TrainShaft::Kind::rigid, 0.0));
  require_same_run(two_gear, rigid, 1);
  // The intermediate shaft as a spring of k: the pinion's speed against the rigid form's.
  std::vector<double> gaps;
  for (double k : {1e9, 1e10, 1e11}) {
    CAPTURE(k);
    const TrainResult r = simulate_train(rigid_form(TrainShaft::Kind::torsional, k));
    REQUIRE(r.series.size() == rigid.series.size());
    REQUIRE(r.meshes[0].impacts == rigid.meshes[0].impacts);
    double gap = 0.0;
    for (std::size_t i = 0; i < r.series.size(); ++i) {
      gap = std::max(gap, std::fabs(r.series[i].w_rad_per_s[0] - rigid.series[i].w_rad_per_s[0]));
    }
    gaps.push_back(gap);
  }
  CAPTURE(gaps[0]);
  CAPTURE(gaps[1]);
  CAPTURE(gaps[2]);
  // The spring's twist, and so the gap, ~1/k once k is well above the mesh's torsional
  // stiffness at the wheel (Rb2^2 k_mesh ~ 2e6 N m/rad; at 1e7 and 1e8 the impacts still
  // differ: ratios 11 and 24 were measured there). The shaft's own mode,
  // sqrt(k (1/J_w1 + 1/(J3 + J4r))) ~ 9e6 rad/s at 1e11, is resolved by the step (w h ~ 0.12);
  // 5 to 20 a decade leaves room for the impacts' timing moving with k (measured: 11.3, 10.0).
  CHECK(gaps[0] / gaps[1] > 5.0);
  CHECK(gaps[0] / gaps[1] < 20.0);
  CHECK(gaps[1] / gaps[2] > 5.0);
  CHECK(gaps[1] / gaps[2] < 20.0);

  // The second stage's own mesh made stiff: wheel 4 a body of J4 behind a mesh of k34 without
  // backlash or friction (both flanks held), the countershaft rigid; as k34 grows the train
  // tends to the rigid form, the gap ~1/k34 once Rb3^2 k34 is well above the mesh's torsional
  // stiffness at the wheel as for the shaft (measured over 1e13 to 1e15 N/m: 8.6, 10.2; at
  // 1e12 to 1e13 still 1.9).
  SimulationCase stage2 = c;
  stage2.gears.teeth1 = 24;
  stage2.gears.teeth2 = 36;
  stage2.gears.backlash_m = 0.0;
  stage2.model.friction_coefficient = 0.0;
  stage2.model.mesh_stiffness = MeshStiffnessMode::constant;
  const StiffnessTable table34(stage2.gears, stage2.model.stiffness);
  const double rb34 = base_radius(stage2.gears, Gear::one) / base_radius(stage2.gears, Gear::two);
  std::vector<double> mesh_gaps;
  for (double k34 : {1e13, 1e14, 1e15}) {
    CAPTURE(k34);
    stage2.model.constant_mesh_stiffness_n_per_m = k34;
    GearTrain train = rigid_form(TrainShaft::Kind::rigid, 0.0);
    TrainBody& wheel4 = train.bodies[3];
    wheel4.inertia_kg_m2 = j4_reflected / (rb34 * rb34);
    wheel4.torque.constant_n_m = c.torque2.constant_n_m / rb34;
    // Rolling with stage 2 undeflected: Rb3 theta3 = Rb4 theta4.
    wheel4.theta_rad = train.bodies[2].theta_rad * rb34;
    wheel4.w_rad_per_s = train.bodies[2].w_rad_per_s * rb34;
    train.shafts.pop_back();
    train.meshes.push_back(TrainMesh{"stage2", 2, 3, stage2, borrowed(table34)});
    const TrainResult r = simulate_train(train);
    REQUIRE(r.series.size() == rigid.series.size());
    REQUIRE(r.meshes[0].impacts == rigid.meshes[0].impacts);
    double gap = 0.0;
    for (std::size_t i = 0; i < r.series.size(); ++i) {
      gap = std::max(gap, std::fabs(r.series[i].w_rad_per_s[0] - rigid.series[i].w_rad_per_s[0]));
    }
    mesh_gaps.push_back(gap);
  }
  CAPTURE(mesh_gaps[0]);
  CAPTURE(mesh_gaps[1]);
  CAPTURE(mesh_gaps[2]);
  CHECK(mesh_gaps[0] / mesh_gaps[1] > 5.0);
  CHECK(mesh_gaps[0] / mesh_gaps[1] < 20.0);
  CHECK(mesh_gaps[1] / mesh_gaps[2] > 5.0);
  CHECK(mesh_gaps[1] / mesh_gaps[2] < 20.0);
}

namespace {

// A pinion (20 teeth), an idler (30) and a wheel (60) of one module and
// pressure angle, each mesh of constant stiffness k without friction and
// Hertzian damping: a linear system while both meshes stay pressed.
struct LinearTrain {
  double k = 3e8;
  GearPair pinion_idler;
  GearPair idler_wheel;
  double rp = 0.0, ri = 0.0, rw = 0.0;  // base radii
  double jp = 0.0, ji = 0.0, jw = 0.0;  // inertias of the gears' discs

  LinearTrain() {
    pinion_idler.teeth1 = 20;
    pinion_idler.teeth2 = 30;
    idler_wheel.teeth1 = 30;
    idler_wheel.teeth2 = 60;
    rp = base_radius(pinion_idler, Gear::one);
    ri = base_radius(pinion_idler, Gear::two);
    rw = base_radius(idler_wheel, Gear::two);
    jp = moment_of_inertia(pinion_idler, Gear::one);
    ji = moment_of_inertia(pinion_idler, Gear::two);
    jw = moment_of_inertia(idler_wheel, Gear::two);
  }

  SimulationCase pair(const GearPair& g) const {
    SimulationCase c;
    c.gears = g;
    c.model.mesh_stiffness = MeshStiffnessMode::constant;
    c.model.constant_mesh_stiffness_n_per_m = k;
    c.model.friction_coefficient = 0.0;
    c.model.damping_update = DampingUpdate::off;
    return c;
  }

  // The bodies at theta_p = 0 with the speeds w_p, w_p rp/ri, w_p rp/rw and
  // the meshes pressed by s1 - B1 and s2 - B2 (s = Rb_a theta_a - Rb_b theta_b).
  GearTrain train(double torque_p, double torque_w, double w_p, double s1, double s2, double step,
                  double end) const {
    GearTrain t;
    TrainBody p{"pinion", jp, {}, 0.0, w_p};
    TrainBody i{"idler", ji, {}, (rp * 0.0 - s1) / ri, w_p * rp / ri};
    TrainBody w{"wheel", jw, {}, 0.0, w_p * rp / rw};
    w.theta_rad = (ri * i.theta_rad - s2) / rw;
    p.torque.constant_n_m = torque_p;
    w.torque.constant_n_m = torque_w;
    t.bodies = {p, i, w};
    t.meshes = {TrainMesh{"pinion-idler", 0, 1, pair(pinion_idler), nullptr},
                TrainMesh{"idler-wheel", 1, 2, pair(idler_wheel), nullptr}};
    t.integrator.step_s = step;
    t.integrator.end_time_s = end;
    return t;
  }
};

}  // namespace

TEST_CASE("a pinion-idler-wheel train accelerates by its reflected inertia at the ratio of teeth") {
  const LinearTrain l;
  // T on the pinion, no load: every body accelerates at its kinematic ratio,
  // the pinion at alpha = T / J_eq with the reflected inertia
  // J_eq = Jp + Ji (rp/ri)^2 + Jw (rp/rw)^2, and the meshes carry the
  // constant forces that accelerate what lies behind them. Started pressed by
  // exactly those forces, the motion is this uniform acceleration: RK4
  // integrates its polynomials exactly, to round-off.
  const double torque = 20.0;
  const double j_eq = l.jp + l.ji * std::pow(l.rp / l.ri, 2) + l.jw * std::pow(l.rp / l.rw, 2);
  const double alpha = torque / j_eq;
  const double f1 = (torque - l.jp * alpha) / l.rp;
  const double f2 = f1 - l.ji * (alpha * l.rp / l.ri) / l.ri;
  const double b1 = l.pinion_idler.backlash_m;
  const double b2 = l.idler_wheel.backlash_m;
  const double w0 = 100.0;
  const double end = 2e-3;
  const TrainResult r =
      simulate_train(l.train(torque, 0.0, w0, b1 + f1 / l.k, b2 + f2 / l.k, 1e-6, end));
  const TrainRow& last = r.series.back();
  REQUIRE(last.t_s == end);
  // Both meshes stayed pressed on N1.
  for (const TrainRow& row : r.series) {
    REQUIRE(row.meshes[0].region == static_cast<int>(Region::n1));
    REQUIRE(row.meshes[1].region == static_cast<int>(Region::n1));
  }
  // Round-off of theta (~1 rad) against deflections of ~1e-6 m on radii of
  // ~2e-2 m: ~1e-11 relative in the forces; 1e-9 leaves room.
  const double w_p = w0 + alpha * end;
  CHECK(std::fabs(last.w_rad_per_s[0] - w_p) / w_p < 1e-9);
  // The kinematic ratio, the teeth's: z_p / z_i and z_p / z_w.
  CHECK(std::fabs(last.w_rad_per_s[1] / last.w_rad_per_s[0] - 20.0 / 30.0) < 1e-9);
  CHECK(std::fabs(last.w_rad_per_s[2] / last.w_rad_per_s[0] - 20.0 / 60.0) < 1e-9);
  // The idler passes on what the wheel's inertia takes: F2 Rw = Jw alpha_w.
  CHECK(std::fabs(last.meshes[1].normal_force_n - f2) / f2 < 1e-9);
  CHECK(std::fabs(f2 * l.rw - l.jw * alpha * l.rp / l.rw) / (f2 * l.rw) < 1e-12);
}

namespace {

// The pinion-idler-wheel train with a kinematic driver at W on the pinion and
// a constant drag T_d on the wheel, each mesh with the viscous mesh damper
// zeta: the idler and the wheel start at 0.95 of their rolling speeds, the
// meshes centred in their backlash, so that the driver's teeth strike theirs.
GearTrain driven_train(const LinearTrain& l, double w, double drag, double zeta, double step,
                       double end) {
  GearTrain t = l.train(0.0, 0.0, w, 0.0, 0.0, step, end);
  t.bodies[0].torque.kind = Torque::Kind::prescribed_speed;
  t.bodies[0].torque.mean_speed_rad_per_s = w;
  t.bodies[1].w_rad_per_s *= 0.95;
  t.bodies[2].w_rad_per_s *= 0.95;
  t.bodies[2].torque.kind = Torque::Kind::drag;
  t.bodies[2].torque.drag_constant_n_m = drag;
  for (TrainMesh& m : t.meshes) m.pair.model.mesh_damping_ratio = zeta;
  return t;
}

}  // namespace

TEST_CASE(
    "a driven pinion-idler-wheel train settles at the driver's speed and the ratio of teeth") {
  const LinearTrain l;
  const double w = 100.0;
  const double drag = 5.0;
  const double end = 40e-3;
  const TrainResult r = simulate_train(driven_train(l, w, drag, 0.2, 1e-6, end));
  REQUIRE(r.meshes[0].impacts >= 1);
  REQUIRE(r.meshes[1].impacts >= 1);
  REQUIRE(r.summary.mesh_damping_loss_j > 0.0);
  const TrainRow& last = r.series.back();
  REQUIRE(last.t_s == end);
  // The driver holds the pinion at W exactly (its closed form each step).
  CHECK(last.w_rad_per_s[0] == w);
  // The dampers take the strikes' vibration, which ends in contact on both
  // meshes within 4 ms; its least damped mode decays by ~10 every 3 ms (its
  // envelope in this run: 5e-3 of the idler's speed at 2 ms, 3e-7 at 14 ms),
  // so by 40 ms to ~1e-16: what remains is round-off of theta (~4 rad) in
  // deflections of ~3e-7 m, ~1e-10 of the forces: 1e-9 leaves room.
  CHECK(std::fabs(last.w_rad_per_s[1] / w - 20.0 / 30.0) < 1e-9);
  CHECK(std::fabs(last.w_rad_per_s[2] / w - 20.0 / 60.0) < 1e-9);
  // Both meshes pressed on N1 by the drag, the idler passing it on: F2 Rw =
  // T_d, and F1 = F2 (the idler's moments F1 Ri - F2 Ri = 0 at constant speed).
  CHECK(last.meshes[0].region == static_cast<int>(Region::n1));
  CHECK(last.meshes[1].region == static_cast<int>(Region::n1));
  const double f2 = drag / l.rw;
  CHECK(std::fabs(last.meshes[1].normal_force_n - f2) / f2 < 1e-9);
  CHECK(std::fabs(last.meshes[0].normal_force_n - f2) / f2 < 1e-9);
}

TEST_CASE("a driven train's energy ledger closes to its integrator's order") {
  // The driver's work against the kinetic and stored energy, the dampers'
  // loss and the drag's work, each integrated or evaluated on its own.
  const LinearTrain l;
  const TrainResult coarse = simulate_train(driven_train(l, 100.0, 5.0, 0.05, 4e-6, 5e-3));
  const TrainResult fine = simulate_train(driven_train(l, 100.0, 5.0, 0.05, 1e-6, 5e-3));
  CAPTURE(coarse.summary.ledger_residual_max_j);
  CAPTURE(fine.summary.ledger_residual_max_j);
  CAPTURE(coarse.summary.ledger_scale_j);
  REQUIRE(coarse.meshes[0].impacts >= 1);
  REQUIRE(coarse.summary.mesh_damping_loss_j > 0.0);
  // RK4 errs per unit time by ~(w_n h)^4 of the energy exchanged: w_n ~ 2e4
  // rad/s at h = 4e-6 s gives ~4e-5 per period's exchange, most of which
  // cancels over the oscillation: 1e-5 of the scale bounds it.
  CHECK(coarse.summary.ledger_residual_max_j / coarse.summary.ledger_scale_j < 1e-5);
  // Fourth order: a quarter of the step divides the residual by about 256;
  // the strikes fall at other times and cut the steps, so 8 per halving, 64, is asked.
  CHECK(fine.summary.ledger_residual_max_j < coarse.summary.ledger_residual_max_j / 64.0);
}

TEST_CASE("a disc behind a torsional shaft spring is accelerated by the spring's twist") {
  const LinearTrain l;
  // The pinion drives the 30-tooth gear, on whose shaft a spring kt turns a
  // disc: under T on the pinion everything accelerates at the kinematic
  // ratio, the pinion at T / J_eq, J_eq = Jp + (Ji + Jd) (rp/ri)^2, and the
  // spring carries the disc's Jd alpha_i at the twist Jd alpha_i / kt. Started
  // in that state, the motion is this uniform acceleration.
  const double torque = 20.0;
  const double jd = 2.0 * l.ji;
  const double kt = 1e3;
  const double j_eq = l.jp + (l.ji + jd) * std::pow(l.rp / l.ri, 2);
  const double alpha = torque / j_eq;
  const double alpha_i = alpha * l.rp / l.ri;
  const double force = (torque - l.jp * alpha) / l.rp;
  const double twist = jd * alpha_i / kt;
  const double w0 = 100.0;
  const double end = 2e-3;
  GearTrain t;
  TrainBody p{"pinion", l.jp, {}, 0.0, w0};
  p.torque.constant_n_m = torque;
  const double s1 = l.pinion_idler.backlash_m + force / l.k;
  TrainBody g{"gear", l.ji, {}, -s1 / l.ri, w0 * l.rp / l.ri};
  TrainBody d{"disc", jd, {}, g.theta_rad - twist, g.w_rad_per_s};
  t.bodies = {p, g, d};
  t.meshes = {TrainMesh{"pinion-gear", 0, 1, l.pair(l.pinion_idler), nullptr}};
  TrainShaft shaft;
  shaft.kind = TrainShaft::Kind::torsional;
  shaft.body_a = 1;
  shaft.body_b = 2;
  shaft.stiffness_n_m_per_rad = kt;
  t.shafts = {shaft};
  t.integrator.step_s = 1e-6;
  t.integrator.end_time_s = end;
  const TrainResult r = simulate_train(t);
  const TrainRow& last = r.series.back();
  // As above: round-off of angles of ~1 rad against a twist of ~1e-2 rad and
  // deflections of ~1e-6 m, ~1e-12 relative; 1e-9 leaves room.
  CHECK(std::fabs(last.w_rad_per_s[0] - (w0 + alpha * end)) / (w0 + alpha * end) < 1e-9);
  CHECK(std::fabs((last.theta_rad[1] - last.theta_rad[2]) - twist) / twist < 1e-9);
  CHECK(std::fabs(last.w_rad_per_s[2] / last.w_rad_per_s[0] - 20.0 / 30.0) < 1e-9);
  // The spring's energy counts with the stored energy: the ledger closes to
  // round-off, RK4 integrating the polynomial motion exactly.
  CHECK(r.summary.ledger_residual_max_j / r.summary.ledger_scale_j < 1e-12);
}

TEST_CASE("a pinion-idler-wheel train vibrates at the eigenvalues of its 3-DOF M, K") {
  const LinearTrain l;
  // In the relative displacements s1, s2 the two elastic modes solve
  // s'' = -A s with, for a = rp^2/Jp, b = ri^2/Ji, c = rw^2/Jw,
  // A = [[k (a + b), -k b], [-k b, k (b + c)]].
  const double a = l.rp * l.rp / l.jp;
  const double b = l.ri * l.ri / l.ji;
  const double c = l.rw * l.rw / l.jw;
  const double half_trace = 0.5 * l.k * (a + 2.0 * b + c);
  const double det = l.k * l.k * (a * b + a * c + b * c);
  const std::array<double, 2> lambda{half_trace - std::sqrt(half_trace * half_trace - det),
                                     half_trace + std::sqrt(half_trace * half_trace - det)};
  // Balanced torques: T on the pinion, -T rw/rp on the wheel, both meshes
  // carrying F = T / rp at constant speeds.
  const double torque = 200.0;
  const double f = torque / l.rp;
  const double b1 = l.pinion_idler.backlash_m;
  const double b2 = l.idler_wheel.backlash_m;
  const double w0 = 100.0;
  for (std::size_t mode = 0; mode < 2; ++mode) {
    CAPTURE(mode);
    const double lam = lambda[mode];
    // The shape in s: (A - lambda) v = 0, v = (k b, k (a + b) - lambda).
    std::array<double, 2> v{l.k * b, l.k * (a + b) - lam};
    const double largest = std::max(std::fabs(v[0]), std::fabs(v[1]));
    v = {v[0] / largest, v[1] / largest};
    // The 3-DOF check of the reduction: phi in the angles, with
    // rp phi_p - ri phi_i = v1, ri phi_i - rw phi_w = v2 and no momentum
    // Jp phi_p + Ji (rp/ri) phi_i + Jw (rp/rw) phi_w = 0 (orthogonal in M to
    // the rigid turning), satisfies K phi = lambda M phi for
    // K = k g1 g1^T + k g2 g2^T, g1 = (rp, -ri, 0), g2 = (0, ri, -rw).
    const double phi_i_coeff =
        l.jp * (l.ri / l.rp) + l.ji * (l.rp / l.ri) + l.jw * (l.rp / l.rw) * (l.ri / l.rw);
    const double phi_i = -(l.jp * v[0] / l.rp - l.jw * (l.rp / l.rw) * v[1] / l.rw) / phi_i_coeff;
    const std::array<double, 3> phi{(v[0] + l.ri * phi_i) / l.rp, phi_i,
                                    (l.ri * phi_i - v[1]) / l.rw};
    const double g1 = l.rp * phi[0] - l.ri * phi[1];
    const double g2 = l.ri * phi[1] - l.rw * phi[2];
    const std::array<double, 3> k_phi{l.k * g1 * l.rp, l.k * (-g1 * l.ri + g2 * l.ri),
                                      -l.k * g2 * l.rw};
    const std::array<double, 3> m_phi{l.jp * phi[0], l.ji * phi[1], l.jw * phi[2]};
    double norm = 0.0;
    double residual = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
      norm = std::max(norm, std::fabs(k_phi[i]));
      residual = std::max(residual, std::fabs(k_phi[i] - lam * m_phi[i]));
    }
    CHECK(residual / norm < 1e-12);
    // Started from the balanced state moved by eps phi (the speeds
    // unchanged), each mesh's s moves by eps v_i cos(omega t), omega = sqrt(lambda).
    const double omega = std::sqrt(lam);
    const double eps = 0.2 * f / l.k;  // the meshes stay pressed
    const double period_fast = 2.0 * pi / std::sqrt(lambda[1]);
    const double step = period_fast / 200.0;
    const double end = 3.0 * 2.0 * pi / std::sqrt(lambda[0]);
    GearTrain train =
        l.train(torque, -torque * l.rw / l.rp, w0, b1 + f / l.k, b2 + f / l.k, step, end);
    train.bodies[0].theta_rad += eps * phi[0];
    train.bodies[1].theta_rad += eps * phi[1];
    train.bodies[2].theta_rad += eps * phi[2];
    const TrainResult r = simulate_train(train);
    REQUIRE(r.series.size() > 100);
    double error = 0.0;
    for (const TrainRow& row : r.series) {
      for (std::size_t m = 0; m < 2; ++m) {
        const double steady = (m == 0 ? b1 : b2) + f / l.k;
        const double expected = steady + eps * v[m] * std::cos(omega * row.t_s);
        error = std::max(error, std::fabs(row.meshes[m].s_m - expected));
      }
    }
    // RK4's phase error at 200 steps per fastest period, (omega h)^4 / 120 per
    // radian over ~20 radians, ~2e-7 of the amplitude; the round-off of s
    // (1e-16 of |Rb theta| < 1e-2 m) below 1e-12 of eps. 1e-5: fifty times
    // the phase error's estimate.
    CHECK(error / eps < 1e-5);
  }
}

namespace {

// A two-stage train of the paper's pair: pinion 1 drives wheel 1, whose shaft
// (a torsional spring) turns pinion 2, which drives wheel 2 under a load;
// time-varying stiffness, Hertzian damping and friction, impacts from the start.
GearTrain two_stage(const StiffnessTable& table, double step) {
  const SimulationCase c = paper_case(2);
  GearTrain train;
  const double j1 = moment_of_inertia(c.gears, Gear::one);
  const double j2 = moment_of_inertia(c.gears, Gear::two);
  TrainBody p1{"pinion1", j1, c.torque1, 0.0, 50.0};
  TrainBody w1{"wheel1", j2, {}, 0.0, 10.0};
  TrainBody p2{"pinion2", j1, {}, 0.0, 10.0};
  TrainBody w2{"wheel2", j2, {}, 0.0, 2.0};
  w2.torque.constant_n_m = -0.25 * c.torque1.constant_n_m;
  train.bodies = {p1, w1, p2, w2};
  train.meshes = {TrainMesh{"stage1", 0, 1, c, borrowed(table)},
                  TrainMesh{"stage2", 2, 3, c, borrowed(table)}};
  TrainShaft shaft;
  shaft.kind = TrainShaft::Kind::torsional;
  shaft.body_a = 1;
  shaft.body_b = 2;
  shaft.stiffness_n_m_per_rad = 2e3;
  train.shafts = {shaft};
  train.integrator.step_s = step;
  train.integrator.end_time_s = 3e-3;
  train.integrator.output_every = 100;
  return train;
}

}  // namespace

TEST_CASE("a two-stage train's energy balances to the integrator's order") {
  const StiffnessTable table(paper_gear_pair(), paper_case(2).model.stiffness);
  // The input work against kinetic + stored (meshes and shaft) + the losses
  // + the parametric work, each integrated or evaluated on its own.
  const TrainResult coarse = simulate_train(two_stage(table, 4e-7));
  const TrainResult fine = simulate_train(two_stage(table, 2e-7));
  for (const TrainResult* r : {&coarse, &fine}) {
    REQUIRE(r->meshes[0].impacts >= 1);
    REQUIRE(r->meshes[1].impacts >= 1);
    REQUIRE(r->summary.damping_loss_j > 0.0);
    REQUIRE(r->summary.friction_loss_j > 0.0);
  }
  const double scale = coarse.summary.ledger_scale_j;
  CAPTURE(coarse.summary.ledger_residual_max_j);
  CAPTURE(fine.summary.ledger_residual_max_j);
  // RK4's error per unit time ~ (omega h)^4 with the mesh's omega ~ 1e5 rad/s
  // at h = 4e-7 s: ~2e-6 of the scale per period's worth of energy exchanged,
  // most of it in the ledger's oscillating terms, which cancel: 1e-7 bounds it.
  CHECK(coarse.summary.ledger_residual_max_j / scale < 1e-7);
  // Fourth order: halving h divides the residual by about 16; events cut
  // the steps, so at least 8 is asked.
  CHECK(fine.summary.ledger_residual_max_j < coarse.summary.ledger_residual_max_j / 8.0);
}

TEST_CASE("a two-stage train's per-mesh and per-body summaries agree with its totals and series") {
  const StiffnessTable table(paper_gear_pair(), paper_case(2).model.stiffness);
  GearTrain train = two_stage(table, 4e-7);
  train.integrator.output_every = 1;
  const TrainResult r = simulate_train(train);
  REQUIRE(r.meshes.size() == 2);
  REQUIRE(r.bodies.size() == 4);
  // Each mesh's losses are integrated beside the train's from what the mesh adds to the train's
  // power: their sums are the train's up to one rounding of the power per stage, ~3e4 stages of
  // 1.1e-16 each in the worst case; 1e-10 of the loss leaves room for the powers' changes of sign.
  const auto close = [](double sum, double total) {
    return std::abs(sum - total) <= 1e-10 * std::abs(total);
  };
  CHECK(r.meshes[0].damping_loss_j > 0.0);
  CHECK(r.meshes[1].damping_loss_j > 0.0);
  CHECK(close(r.meshes[0].damping_loss_j + r.meshes[1].damping_loss_j, r.summary.damping_loss_j));
  CHECK(
      close(r.meshes[0].friction_loss_j + r.meshes[1].friction_loss_j, r.summary.friction_loss_j));
  for (std::size_t k = 0; k < 2; ++k) {
    CAPTURE(k);
    // The contacts begun, counted again from the series (a row each step): a row in contact in
    // another region than the row before (the first row's contact counts, as the summary's).
    int begun = 0;
    double deepest = 0.0;
    for (std::size_t i = 0; i < r.series.size(); ++i) {
      const TrainMeshRow& m = r.series[i].meshes[k];
      if (m.region != 0 && (i == 0 || r.series[i - 1].meshes[k].region != m.region)) ++begun;
      if (m.region != 0) deepest = std::max(deepest, m.delta_m);
    }
    CHECK(begun == r.meshes[k].impacts);
    // The summary's largest penetration is booked at every step and event, the series' at every
    // step: the series' can only be less, and steps of 4e-7 s sample a contact's peak (a mesh
    // period of ~1e-4 s) to within (w h)^2 / 8 ~ 2e-4 of it.
    CHECK(deepest <= r.meshes[k].max_penetration_m);
    CHECK(deepest >= (1.0 - 1e-3) * r.meshes[k].max_penetration_m);
  }
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    CHECK(r.bodies[i].final_w_rad_per_s == r.series.back().w_rad_per_s[i]);
  }
}

namespace {

// Whether two train runs wrote the same bits: every body's angle and speed and
// every mesh's s, force and contact in every row, and each mesh's losses.
bool same_train_run(const TrainResult& a, const TrainResult& b) {
  if (a.series.size() != b.series.size() || a.meshes.size() != b.meshes.size()) return false;
  for (std::size_t i = 0; i < a.series.size(); ++i) {
    const TrainRow& x = a.series[i];
    const TrainRow& y = b.series[i];
    if (x.theta_rad != y.theta_rad || x.w_rad_per_s != y.w_rad_per_s) return false;
    for (std::size_t k = 0; k < x.meshes.size(); ++k) {
      const TrainMeshRow& m = x.meshes[k];
      const TrainMeshRow& n = y.meshes[k];
      if (m.s_m != n.s_m || m.normal_force_n != n.normal_force_n ||
          m.friction_force_n != n.friction_force_n || m.region != n.region) {
        return false;
      }
    }
  }
  for (std::size_t k = 0; k < a.meshes.size(); ++k) {
    if (a.meshes[k].damping_loss_j != b.meshes[k].damping_loss_j ||
        a.meshes[k].friction_loss_j != b.meshes[k].friction_loss_j) {
      return false;
    }
  }
  return true;
}

}  // namespace

TEST_CASE("meshes read one built table where its inputs are equal, each its own where not") {
  // The run builds the table of each mesh not given one, once for each
  // distinct pair geometry and stiffness model: the reference is the same
  // train with each mesh given the table of its own pair, built here.
  const SimulationCase c = paper_case(2);
  const StiffnessTable table(c.gears, c.model.stiffness);
  GearTrain given = two_stage(table, 4e-7);
  given.integrator.output_every = 10;
  GearTrain built = given;
  for (TrainMesh& m : built.meshes) m.table = nullptr;
  const TrainResult equal = simulate_train(built);
  CHECK(same_train_run(equal, simulate_train(given)));

  // The second stage 20 % wider: its own table (Ke per unit width scales
  // with it), not the first stage's.
  GearTrain wider = built;
  wider.meshes[1].pair.gears.face_width_m *= 1.2;
  const StiffnessTable wide(wider.meshes[1].pair.gears, c.model.stiffness);
  GearTrain wider_given = wider;
  wider_given.meshes[0].table = borrowed(table);
  wider_given.meshes[1].table = borrowed(wide);
  const TrainResult own = simulate_train(wider);
  REQUIRE(own.meshes[1].impacts >= 1);
  CHECK(same_train_run(own, simulate_train(wider_given)));
  // The power of the check above: the width changes the run (a table given
  // for another pair is refused, so the first stage's cannot be tried here).
  CHECK_FALSE(same_train_run(own, equal));
  wider_given.meshes[1].table = borrowed(table);
  CHECK_THROWS_AS(simulate_train(wider_given), InputError);
}

TEST_CASE("a train's bad input is refused naming its field") {
  const LinearTrain l;
  GearTrain t = l.train(1.0, 0.0, 0.0, 0.0, 0.0, 1e-6, 1e-4);
  SUBCASE("a mesh's pair key, addressed by the mesh's name") {
    t.meshes[1].pair.gears.teeth1 = 2;
    try {
      simulate_train(t);
      FAIL("not refused");
    } catch (const InputError& e) {
      CHECK(e.field().rfind("meshes.idler-wheel.", 0) == 0);
    }
  }
  SUBCASE("a mesh between two discs of one rigid shaft") {
    TrainShaft shaft;
    shaft.body_a = 1;
    shaft.body_b = 2;
    t.shafts = {shaft};
    t.bodies[2].theta_rad = t.bodies[1].theta_rad;
    t.bodies[2].w_rad_per_s = t.bodies[1].w_rad_per_s;
    CHECK_THROWS_WITH_AS(simulate_train(t), doctest::Contains("meshes.idler-wheel.body_b"),
                         InputError);
  }
  SUBCASE("a body without inertia") {
    t.bodies[1].inertia_kg_m2 = 0.0;
    CHECK_THROWS_WITH_AS(simulate_train(t), doctest::Contains("bodies.idler.inertia"), InputError);
  }
  SUBCASE("a body's inertia past its row's range (train_schema(), for a train built in code too)") {
    t.bodies[1].inertia_kg_m2 = 2e6;
    CHECK_THROWS_WITH_AS(simulate_train(t), doctest::Contains("bodies.idler.inertia"), InputError);
  }
  SUBCASE("a mesh on elastic bearings (a train's bearings are its bodies')") {
    Bearings& b = t.meshes[0].pair.bearings;
    b.kind = BearingKind::elastic;
    b.gear1.stiffness_x_n_per_m = 1e8;
    b.gear2.stiffness_x_n_per_m = 1e8;
    CHECK_THROWS_WITH_AS(simulate_train(t), doctest::Contains("meshes.pinion-idler.bearings.kind"),
                         InputError);
  }
  SUBCASE("two kinematic drivers on one rigid shaft") {
    t.bodies[2].w_rad_per_s = 10.0;
    TrainBody disc{"disc", 1e-3, {}, t.bodies[2].theta_rad, t.bodies[2].w_rad_per_s};
    disc.torque.kind = Torque::Kind::prescribed_speed;
    disc.torque.mean_speed_rad_per_s = 10.0;
    t.bodies[2].torque = disc.torque;
    t.bodies.push_back(disc);
    TrainShaft shaft;
    shaft.body_a = 2;
    shaft.body_b = 3;
    t.shafts = {shaft};
    CHECK_THROWS_WITH_AS(simulate_train(t), doctest::Contains("bodies.disc.torque.kind"),
                         InputError);
  }
  SUBCASE("the integrator's settings, by the [integrator] rows' ranges") {
    t.integrator.step_s = 0.0;
    CHECK_THROWS_WITH_AS(simulate_train(t), doctest::Contains("integrator.step"), InputError);
  }
  SUBCASE("more steps than kMostSteps over the end time") {
    t.integrator.end_time_s = t.integrator.step_s * (static_cast<double>(kMostSteps) + 1e3);
    CHECK_THROWS_WITH_AS(simulate_train(t), doctest::Contains("integrator.end_time"), InputError);
  }
  SUBCASE("a driven body's initial speed other than its driver's") {
    t.bodies[0].torque.kind = Torque::Kind::prescribed_speed;
    t.bodies[0].torque.mean_speed_rad_per_s = 10.0;
    t.bodies[0].w_rad_per_s = 9.0;
    CHECK_THROWS_WITH_AS(simulate_train(t), doctest::Contains("bodies.pinion.w"), InputError);
  }
  SUBCASE("a drag's parameter, by the [torque2] row's range, under the body's name") {
    t.bodies[2].torque.kind = Torque::Kind::drag;
    t.bodies[2].torque.drag_speed_scale_rad_per_s = 0.0;
    CHECK_THROWS_WITH_AS(simulate_train(t),
                         doctest::Contains("bodies.wheel.torque.drag_speed_scale"), InputError);
  }
  SUBCASE("a motor's parameter, by the [torque1] row's range, under the body's name") {
    t.bodies[0].torque.kind = Torque::Kind::induction_motor;
    t.bodies[0].torque.synchronous_speed_rad_per_s = -1.0;
    CHECK_THROWS_WITH_AS(simulate_train(t),
                         doctest::Contains("bodies.pinion.torque.synchronous_speed"), InputError);
  }
}
