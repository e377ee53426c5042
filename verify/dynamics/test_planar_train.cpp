// A gear train whose bodies translate on elastic bearings (dynamics/train.hpp,
// TrainBody::bearing). References: the two-gear planar run (simulate with
// [bearings] kind = "elastic"), which a two-body train on the same bearings
// must equal bit for bit; the rigid train, which stiff bearings approach as
// F/k (each centre moves F/k along the line of action); the static
// equilibrium of a pinion-idler-wheel train, whose bearing forces follow by
// hand from the meshes' forces (magnitude F, a separating component F sin a
// and a tangential one F cos a opposing the driver's turning); the energy
// ledger, whose residual falls with the step at RK4's order.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "speed_cases.hpp"

using namespace gearimpact;

namespace {

std::shared_ptr<const StiffnessTable> lent(const StiffnessTable& table) {
  return {&table, [](const StiffnessTable*) {}};
}

// The paper's case 2 (impacts from the start, time-varying stiffness,
// Hertzian damping, friction) on elastic bearings of 2e8 N/m, damped.
SimulationCase elastic_paper_case() {
  SimulationCase c = paper_case(2);
  c.bearings.kind = BearingKind::elastic;
  c.bearings.gear1.stiffness_x_n_per_m = 2e8;
  c.bearings.gear1.stiffness_y_n_per_m = 3e8;
  c.bearings.gear1.damping_x_n_s_per_m = 200.0;
  c.bearings.gear2.stiffness_x_n_per_m = 4e8;
  c.bearings.gear2.damping_x_n_s_per_m = 300.0;
  c.bearings.gear2.damping_y_n_s_per_m = 100.0;
  c.model.mesh_damping_ratio = 0.02;
  c.integrator.step_s = 2e-7;
  c.integrator.end_time_s = 2e-3;
  c.integrator.output_every = 1;
  return c;
}

// The case as the library writes it as a train (two_gear_train: the bearings
// on the bodies with the planar model's masses, the pair's own rigid), with
// the table lent.
GearTrain planar_two_gear_train(const SimulationCase& c, const StiffnessTable& table) {
  GearTrain train = two_gear_train(c);
  train.meshes[0].table = lent(table);
  return train;
}

}  // namespace

namespace {

// The planar run of c and its train (two_gear_train) the same to the bit.
void require_same_planar_run(const SimulationCase& c) {
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SimulationResult planar = simulate(c, table);
  const TrainResult train = simulate_train(planar_two_gear_train(c, table));
  REQUIRE(planar.summary.events > 10);
  REQUIRE(planar.summary.impacts_n1 + planar.summary.impacts_n2 >= 2);
  REQUIRE(train.series.size() == planar.series.size());
  REQUIRE(planar.planar_series.size() == planar.series.size());
  for (std::size_t i = 0; i < planar.series.size(); ++i) {
    const SeriesRow& a = planar.series[i];
    const PlanarRow& p = planar.planar_series[i];
    const TrainRow& b = train.series[i];
    const TrainMeshRow& m = b.meshes[0];
    const bool same =
        a.t_s == b.t_s && a.theta1_rad == b.theta_rad[0] && a.theta2_rad == b.theta_rad[1] &&
        a.w1_rad_per_s == b.w_rad_per_s[0] && a.w2_rad_per_s == b.w_rad_per_s[1] &&
        a.s_m == m.s_m && a.delta_m == m.delta_m && a.region == m.region && a.pairs == m.pairs &&
        a.normal_force_n == m.normal_force_n && a.friction_force_n == m.friction_force_n &&
        p.state.x1_m == b.centres[0].x_m && p.state.y1_m == b.centres[0].y_m &&
        p.state.x2_m == b.centres[1].x_m && p.state.y2_m == b.centres[1].y_m &&
        p.state.vx1_m_s == b.centres[0].vx_m_s && p.state.vy2_m_s == b.centres[1].vy_m_s &&
        p.bearing_fx1_n == b.centres[0].bearing_fx_n &&
        p.bearing_fy1_n == b.centres[0].bearing_fy_n &&
        p.bearing_fx2_n == b.centres[1].bearing_fx_n &&
        p.bearing_fy2_n == b.centres[1].bearing_fy_n;
    if (!same) {
      INFO("row " << i << " at t = " << a.t_s);
      REQUIRE(same);
    }
  }
  const SimulationSummary& s = planar.summary;
  const SimulationSummary& t = train.summary;
  CHECK(t.steps == s.steps);
  CHECK(t.events == s.events);
  CHECK(t.impacts_n1 == s.impacts_n1);
  CHECK(t.impacts_n2 == s.impacts_n2);
  CHECK(t.first_impact_s == s.first_impact_s);
  CHECK(t.first_impact_speed_m_s == s.first_impact_speed_m_s);
  CHECK(t.max_penetration_m == s.max_penetration_m);
  CHECK(t.final_w1_rad_per_s == s.final_w1_rad_per_s);
  CHECK(t.final_w2_rad_per_s == s.final_w2_rad_per_s);
  // The integrals of the powers, integrated as the planar run integrates them.
  CHECK(t.torque_work_j == s.torque_work_j);
  CHECK(t.damping_loss_j == s.damping_loss_j);
  CHECK(t.friction_loss_j == s.friction_loss_j);
  CHECK(t.mesh_damping_loss_j == s.mesh_damping_loss_j);
  REQUIRE(t.planar.has_value());
  CHECK(t.planar->bearing_damping_loss_j == s.planar->bearing_damping_loss_j);
  CHECK(t.planar->bearing_energy_final_j == s.planar->bearing_energy_final_j);
  CHECK(t.kinetic_energy_final_j == s.kinetic_energy_final_j);
  CHECK(t.stored_energy_final_j == s.stored_energy_final_j);
  CHECK(t.parametric_work_j == s.parametric_work_j);
  CHECK(t.energy_max_j == s.energy_max_j);
  CHECK(t.ledger_residual_max_j == s.ledger_residual_max_j);
  CHECK(t.speed_drift_max_rel == s.speed_drift_max_rel);
  REQUIRE(train.impacts.size() == 1);
  REQUIRE(train.impacts[0].size() == planar.impacts.size());
  for (std::size_t i = 0; i < planar.impacts.size(); ++i) {
    const ImpactRecord& a = planar.impacts[i];
    const ImpactRecord& b = train.impacts[0][i];
    CHECK((a.line == b.line && a.start_s == b.start_s && a.impact_speed_m_s == b.impact_speed_m_s &&
           a.end_s == b.end_s));
  }
}

}  // namespace

TEST_CASE("a two-body train on elastic bearings is the two-gear planar run, bit for bit") {
  require_same_planar_run(elastic_paper_case());
}

TEST_CASE(
    "a speed-controlled pinion on elastic bearings runs as the two-gear planar run, bit for "
    "bit") {
  // The controller's reflected inertia and load are the train's
  // (train_speed_controller), J1 + J2 (Rb1/Rb2)^2 against T2 Rb1/Rb2 as the
  // two-gear model's; its torque read at the pinion's angle and speed.
  SimulationCase c = elastic_paper_case();
  c.torque1 = Torque{};
  c.torque1.kind = Torque::Kind::speed_controlled;
  c.torque1.mean_speed_rad_per_s = c.initial.w1_rad_per_s;
  c.torque1.controller_bandwidth_rad_per_s = 2.0 * pi * 50.0;
  c.torque1.controller_damping_ratio = 1.0;
  require_same_planar_run(c);
  // The drift check over whole revolutions of the pinion (the train's first body): at
  // 500 rad/s from the start (drive.settle 0), 2.2 revolutions.
  SimulationCase drift = verify::held_at_speed(c, 500.0, 2.2);
  drift.integrator.output_every = 100;
  require_same_planar_run(drift);
  // Held to a bound it cannot meet, the train warns as the planar run does, naming its body.
  drift.drive.speed_tolerance = 1e-12;
  const StiffnessTable drift_table(c.gears, c.model.stiffness);
  const SimulationResult model = simulate(drift, drift_table);
  REQUIRE(model.summary.speed_drift_max_rel.has_value());
  const GearTrain drift_train = planar_two_gear_train(drift, drift_table);
  // Written as a train file would write it, its first body named by its key.
  GearTrain drift_train_file = drift_train;
  drift_train_file.two_gear_case = false;
  const std::vector<std::string> warned =
      train_warnings(drift_train_file, simulate_train(drift_train_file));
  REQUIRE(warned.size() == 1);
  const std::vector<std::string> model_warned = result_warnings(drift, model.summary);
  REQUIRE(model_warned.size() == 1);
  CHECK(model_warned[0].rfind("the pinion's mean speed over a whole revolution drifted", 0) == 0);
  std::string expected = "body pinion" + model_warned[0].substr(std::string("the pinion").size());
  const std::size_t key = expected.find("torque1.bandwidth");
  REQUIRE(key != std::string::npos);
  expected.replace(key, std::string("torque1.").size(), "bodies.pinion.torque.");
  CHECK(warned[0] == expected);
  // Of a two-gear file, the two-gear run's warning word for word.
  CHECK(train_warnings(drift_train, simulate_train(drift_train)) == model_warned);
  // The controller acts: the same run with the pinion's torque held at zero differs.
  SimulationCase free = c;
  free.torque1 = Torque{};
  const StiffnessTable table(c.gears, c.model.stiffness);
  CHECK(simulate(free, table).summary.final_w1_rad_per_s !=
        simulate(c, table).summary.final_w1_rad_per_s);
}

TEST_CASE("a train's sensor samples are the two-gear planar run's, bit for bit, of either kind") {
  // Samples at 51.2 kHz, one every 97.66 steps of 0.2 us: inside steps (the
  // steps' continuous extension) and cut by the run's events, on the
  // wheel's sensor at 0.3 rad.
  // The pinion starts half the backlash back, without the mesh damper: the first samples see
  // no force, and their zero acceleration's sign is the planar run's.
  SimulationCase c = elastic_paper_case();
  c.bearings.sensor_gear = 2;
  c.bearings.sensor_angle_rad = 0.3;
  c.initial.theta1_rad -= 0.5 * c.gears.backlash_m / base_radius(c.gears, Gear::one);
  c.model.mesh_damping_ratio = 0.0;
  const StiffnessTable table(c.gears, c.model.stiffness);
  const GearTrain train = planar_two_gear_train(c, table);
  std::vector<double> point;
  for (const SampleKind kind : {SampleKind::point, SampleKind::interval_average}) {
    CAPTURE(name_of(kSampleKinds, kind));
    RunControl control;
    control.sample_rate_hz = 51200.0;
    control.sample = kind;
    const SimulationResult planar = simulate(c, table, control);
    const TrainResult run = simulate_train(train, control);
    // Interval averages leave out n = 0 (sample_count).
    const auto expected = static_cast<std::size_t>(sample_count(c.integrator.end_time_s, 51200.0) -
                                                   (kind == SampleKind::point ? 0.0 : 1.0));
    REQUIRE(planar.planar_samples.size() == expected);
    REQUIRE(run.samples.size() == expected);
    if (kind == SampleKind::point) {
      REQUIRE(run.samples[0].meshes[0].region == 0);
      REQUIRE(run.samples[0].sensor_acceleration_m_per_s2 == 0.0);
    }
    for (std::size_t i = 0; i < expected; ++i) {
      const PlanarSample& a = planar.planar_samples[i];
      const TrainRow& b = run.samples[i];
      const bool same =
          a.t_s == b.t_s && a.state.theta1_rad == b.theta_rad[0] &&
          a.state.w2_rad_per_s == b.w_rad_per_s[1] && a.state.x2_m == b.centres[1].x_m &&
          a.state.vy1_m_s == b.centres[0].vy_m_s && a.bearing_fy2_n == b.centres[1].bearing_fy_n &&
          a.sensor_acceleration_m_per_s2 == b.sensor_acceleration_m_per_s2 &&
          // To the bit: a zero's sign too (before the first contact).
          std::signbit(a.sensor_acceleration_m_per_s2) ==
              std::signbit(b.sensor_acceleration_m_per_s2);
      if (!same) {
        INFO("sample " << i << " at t = " << a.t_s);
        REQUIRE(same);
      }
    }
    if (kind == SampleKind::point) {
      for (const TrainRow& row : run.samples) point.push_back(row.sensor_acceleration_m_per_s2);
    } else {
      // The two kinds differ: a mean over 19.5 us is not the value at its end.
      REQUIRE(point.size() == run.samples.size() + 1);
      CHECK(point[5] != run.samples[4].sensor_acceleration_m_per_s2);
    }
  }
}

TEST_CASE(
    "a train's tacho is the two-gear planar run's, bit for bit, on either gear and a driver") {
  // 1e5 pulses a revolution over 2 ms from 50 rad/s (the first impacts soon stop the free
  // pinion): the pinion's edges on the steps' continuous extension, the wheel's from an offset,
  // a driven pinion's on its closed form.
  SimulationCase pinion = elastic_paper_case();
  pinion.tacho.pulses_per_revolution = 100000;
  SimulationCase wheel = pinion;
  wheel.tacho.shaft = TachoShaft::wheel;
  wheel.tacho.offset_rad = 0.3;
  SimulationCase driven = verify::driven_with_harmonic(pinion);
  const StiffnessTable table(pinion.gears, pinion.model.stiffness);
  for (const SimulationCase* c : {&pinion, &wheel, &driven}) {
    const SimulationResult planar = simulate(*c, table);
    const GearTrain train = planar_two_gear_train(*c, table);
    CHECK(train.tacho_body == (c == &wheel ? 1 : 0));
    CHECK(train.meshes[0].pair.tacho.pulses_per_revolution == 0);
    const TrainResult run = simulate_train(train);
    REQUIRE(planar.tacho_times_s.size() >= 10);
    CHECK(run.tacho_times_s == planar.tacho_times_s);
  }
  // A train on rigid bearings has none, as the two-gear torsional run; nor a body with no pulses.
  GearTrain rigid = two_gear_train(paper_case(2));
  rigid.tacho_body = 0;
  rigid.tacho.pulses_per_revolution = 2;
  CHECK_THROWS_WITH_AS(simulate_train(rigid), doctest::Contains("tacho.body"), InputError);
  GearTrain none = planar_two_gear_train(pinion, table);
  none.tacho.pulses_per_revolution = 0;
  CHECK_THROWS_WITH_AS(simulate_train(none), doctest::Contains("tacho.pulses_per_revolution"),
                       InputError);
}

TEST_CASE("a train without a sensor refuses samples, naming sample_rate") {
  RunControl control;
  control.sample_rate_hz = 51200.0;
  // The torsional pair has no centres to sense; the planar one without a [sensor] none chosen.
  GearTrain torsional = two_gear_train(paper_case(2));
  GearTrain unsensed = two_gear_train(elastic_paper_case());
  unsensed.sensor_body = -1;
  const auto refusal = [&](const GearTrain& t) {
    try {
      simulate_train(t, control);
    } catch (const InputError& e) {
      return e.problems().front().field + ": " + e.what();
    }
    return std::string("none");
  };
  for (const GearTrain& train : {torsional, unsensed}) {
    const std::string text = refusal(train);
    CHECK(text.rfind("sample_rate: ", 0) == 0);
    CHECK(text.find("[sensor] body = NAME") != std::string::npos);
  }
  GearTrain sensed = two_gear_train(elastic_paper_case());
  sensed.sensor_body = 1;
  control.sample_rate_hz = -1.0;
  CHECK(refusal(sensed).rfind("sample_rate: ", 0) == 0);
}

namespace {

// A pinion (20 teeth), an idler (30) and a wheel (60) of one module, each
// mesh of constant stiffness without friction, Hertzian damping off and a
// viscous mesh damper, the idler's centre at 70 degrees from the line
// pinion -> idler; balanced torques, each mesh started at its torsional
// static deflection; every centre on isotropic, damped bearings of k.
struct PlanarLinearTrain {
  double k_mesh = 3e8;
  double force_n = 2000.0;  // mesh 1's
  GearPair pi_pair;
  GearPair iw_pair;
  double angle1 = 0.3;
  double angle2 = 0.3 + 70.0 * pi / 180.0;

  PlanarLinearTrain() {
    pi_pair.teeth1 = 20;
    pi_pair.teeth2 = 30;
    iw_pair.teeth1 = 30;
    iw_pair.teeth2 = 60;
  }
  SimulationCase pair(const GearPair& g) const {
    SimulationCase c;
    c.gears = g;
    c.model.mesh_stiffness = MeshStiffnessMode::constant;
    c.model.constant_mesh_stiffness_n_per_m = k_mesh;
    c.model.friction_coefficient = 0.0;
    c.model.damping_update = DampingUpdate::off;
    c.model.mesh_damping_ratio = 0.3;
    return c;
  }
  // Mesh 2's force: the idler's moments balance, F1 Rb_i = F2 Rb_i' (the
  // idler's base radius as each pair has it).
  double force2() const {
    return force_n * base_radius(pi_pair, Gear::two) / base_radius(iw_pair, Gear::one);
  }
  GearTrain train(double k_bearing, double step, double end) const {
    GearTrain t;
    const double s1 = pi_pair.backlash_m + force_n / k_mesh;
    const double s2 = iw_pair.backlash_m + force2() / k_mesh;
    TrainBody p{"pinion", moment_of_inertia(pi_pair, Gear::one), {}, 0.0, 0.0};
    TrainBody i{"idler",
                moment_of_inertia(pi_pair, Gear::two),
                {},
                -s1 / base_radius(pi_pair, Gear::two),
                0.0};
    TrainBody w{"wheel", moment_of_inertia(iw_pair, Gear::two), {}, 0.0, 0.0};
    w.theta_rad =
        (base_radius(iw_pair, Gear::one) * i.theta_rad - s2) / base_radius(iw_pair, Gear::two);
    p.torque.constant_n_m = force_n * base_radius(pi_pair, Gear::one);
    w.torque.constant_n_m = -force2() * base_radius(iw_pair, Gear::two);
    if (k_bearing > 0.0) {
      const std::array<double, 3> mass = {disc_mass(pi_pair, Gear::one),
                                          disc_mass(pi_pair, Gear::two),
                                          disc_mass(iw_pair, Gear::two)};
      TrainBody* bodies[3] = {&p, &i, &w};
      for (std::size_t j = 0; j < 3; ++j) {
        GearBearing b;
        b.stiffness_x_n_per_m = k_bearing;
        b.damping_x_n_s_per_m = 0.6 * std::sqrt(k_bearing * mass[j]);
        b.mass_kg = mass[j];
        bodies[j]->bearing = b;
      }
    }
    t.bodies = {p, i, w};
    TrainMesh m1{"pinion-idler", 0, 1, pair(pi_pair), nullptr};
    TrainMesh m2{"idler-wheel", 1, 2, pair(iw_pair), nullptr};
    m1.centre_angle_rad = angle1;
    m2.centre_angle_rad = angle2;
    t.meshes = {m1, m2};
    t.integrator.step_s = step;
    t.integrator.end_time_s = end;
    t.integrator.output_every = 1000000;
    return t;
  }
};

// s of each mesh's turning alone, Rb_a theta_a - Rb_b theta_b, at a row.
std::array<double, 2> turning_s(const PlanarLinearTrain& l, const TrainRow& row) {
  return {base_radius(l.pi_pair, Gear::one) * row.theta_rad[0] -
              base_radius(l.pi_pair, Gear::two) * row.theta_rad[1],
          base_radius(l.iw_pair, Gear::one) * row.theta_rad[1] -
              base_radius(l.iw_pair, Gear::two) * row.theta_rad[2]};
}

}  // namespace

TEST_CASE(
    "a two-gear case on elastic bearings is written as a train with its bearings on its bodies") {
  SimulationCase c = elastic_paper_case();
  c.bearings.gear2.mass_kg = 3.5;
  c.bearings.sensor_gear = 2;
  c.bearings.sensor_angle_rad = 0.3;
  const GearTrain train = two_gear_train(c);
  CHECK(train.meshes[0].pair.bearings.kind == BearingKind::rigid);
  REQUIRE(train.bodies[0].bearing.has_value());
  REQUIRE(train.bodies[1].bearing.has_value());
  const GearBearing& b1 = *train.bodies[0].bearing;
  const GearBearing& b2 = *train.bodies[1].bearing;
  // No mass given: the disc's, as the planar model takes it; a mass given: that one.
  CHECK(b1.mass_kg == disc_mass(c.gears, Gear::one));
  CHECK(b2.mass_kg == 3.5);
  CHECK(b1.stiffness_x_n_per_m == 2e8);
  CHECK(b1.stiffness_y_n_per_m == 3e8);
  CHECK(b2.damping_y_n_s_per_m == 100.0);
  CHECK(train.sensor_body == 1);
  CHECK(train.sensor_angle_rad == 0.3);
  // The given mass moves the run as the planar model's: the same to the bit.
  const StiffnessTable table(c.gears, c.model.stiffness);
  GearTrain lent_train = train;
  lent_train.meshes[0].table = lent(table);
  const SimulationResult planar = simulate(c, table);
  const TrainResult run = simulate_train(lent_train);
  CHECK(run.summary.final_w2_rad_per_s == planar.summary.final_w2_rad_per_s);
  REQUIRE(run.summary.planar.has_value());
  CHECK(run.summary.planar->bearing_energy_final_j ==
        planar.summary.planar->bearing_energy_final_j);
  // On rigid bearings the bodies turn about fixed axes.
  const GearTrain rigid = two_gear_train(paper_case(2));
  CHECK_FALSE(rigid.bodies[0].bearing.has_value());
  CHECK_FALSE(rigid.bodies[1].bearing.has_value());
  CHECK(rigid.sensor_body == -1);
}

TEST_CASE("a pinion-idler-wheel train on bearings holds its static equilibrium by hand") {
  const PlanarLinearTrain l;
  // Settled: the slowest mode (the meshes' torsional one, ~2.4e4 rad/s,
  // damped at about 0.3 of critical by the mesh dampers and the bearings')
  // decays by about e^-20 over 3e-3 s.
  const TrainResult r = simulate_train(l.train(5e8, 1e-7, 3e-3));
  REQUIRE(r.series.size() >= 2);
  const TrainRow& end = r.series.back();
  REQUIRE(end.centres.size() == 3);
  const double a = operating_pressure_angle(l.pi_pair);
  REQUIRE(a == operating_pressure_angle(l.iw_pair));
  const double f1 = l.force_n;
  const double f2 = l.force2();
  // The line of centres and its counter-clockwise normal of each mesh.
  const std::array<double, 2> e1{std::cos(l.angle1), std::sin(l.angle1)};
  const std::array<double, 2> n1{-e1[1], e1[0]};
  const std::array<double, 2> e2{std::cos(l.angle2), std::sin(l.angle2)};
  const std::array<double, 2> n2{-e2[1], e2[0]};
  // The pinion turns counter-clockwise and drives: the idler pushes it away
  // (-F1 sin a along e1) and against its turning (-F1 cos a along n1); its
  // bearing holds it with the opposite. The idler turns clockwise and
  // drives the wheel: the wheel pushes it away (-F2 sin a along e2) and
  // against its clockwise turning (+F2 cos a along n2); the pinion pushes it
  // with the reaction of the pinion's force. The wheel takes the reaction of
  // the idler's.
  const std::array<double, 2> on_pinion{-f1 * (std::sin(a) * e1[0] + std::cos(a) * n1[0]),
                                        -f1 * (std::sin(a) * e1[1] + std::cos(a) * n1[1])};
  const std::array<double, 2> on_idler_from_wheel{
      f2 * (-std::sin(a) * e2[0] + std::cos(a) * n2[0]),
      f2 * (-std::sin(a) * e2[1] + std::cos(a) * n2[1])};
  const std::array<std::array<double, 2>, 3> bearing{
      std::array<double, 2>{-on_pinion[0], -on_pinion[1]},
      std::array<double, 2>{on_pinion[0] - on_idler_from_wheel[0],
                            on_pinion[1] - on_idler_from_wheel[1]},
      std::array<double, 2>{on_idler_from_wheel[0], on_idler_from_wheel[1]}};
  for (std::size_t j = 0; j < 3; ++j) {
    CAPTURE(j);
    const double fx = end.centres[j].bearing_fx_n;
    const double fy = end.centres[j].bearing_fy_n;
    CAPTURE(fx);
    CAPTURE(fy);
    // From the start's departure (~F: the centres start unloaded), settled
    // to 6e-8 of F when measured; 1e-6 of F is the bound asked, well above
    // the forces' round-off (1e-16 of k u ~ F).
    CHECK(std::abs(fx - bearing[j][0]) < 1e-6 * f1);
    CHECK(std::abs(fy - bearing[j][1]) < 1e-6 * f1);
  }
  // Each mesh still carries its force on its drive line.
  CHECK(std::abs(end.meshes[0].normal_force_n - f1) < 1e-6 * f1);
  CHECK(std::abs(end.meshes[1].normal_force_n - f2) < 1e-6 * f1);
  CHECK(end.meshes[0].region == 1);
  CHECK(end.meshes[1].region == 1);
}

TEST_CASE("stiff bearings approach the rigid train as F/k") {
  const PlanarLinearTrain l;
  // The rigid train stays at its static deflection (constant stiffness,
  // balanced torques): each mesh's turning s = B + F/k_mesh.
  const TrainResult rigid = simulate_train(l.train(0.0, 1e-7, 1e-3));
  const std::array<double, 2> rigid_s = turning_s(l, rigid.series.back());
  std::array<double, 2> excess_at_1e11{};
  for (const double kb : {1e11, 1e12}) {
    CAPTURE(kb);
    // A step within the planar train's bound (check_planar_train_step).
    const TrainResult r = simulate_train(l.train(kb, kb > 5e11 ? 4e-8 : 1e-7, 2e-3));
    const std::array<double, 2> s = turning_s(l, r.series.back());
    // Each centre yields by its meshes' force over k: the pinion's and the
    // wheel's by F/k along their mesh's drive normal, the idler's along the
    // resultant of both meshes' forces on it. The turning makes up each
    // mesh's centres' approach along its normal, so that s_d keeps
    // B + F/k_mesh: the rigid train's turning s plus that approach.
    const double a = operating_pressure_angle(l.pi_pair);
    const std::array<double, 2> line1{
        std::sin(a) * std::cos(l.angle1) - std::cos(a) * std::sin(l.angle1),
        std::sin(a) * std::sin(l.angle1) + std::cos(a) * std::cos(l.angle1)};
    // Mesh 2's drive normal, the idler turning clockwise: the mirror of the
    // counter-clockwise one about the line of centres.
    const std::array<double, 2> line2{
        std::sin(a) * std::cos(l.angle2) + std::cos(a) * std::sin(l.angle2),
        std::sin(a) * std::sin(l.angle2) - std::cos(a) * std::cos(l.angle2)};
    // A mesh's force on its body a's centre is -F n, on b's +F n (the
    // gradient of 1/2 k (s_d - B)^2, s_d holding +(u_a - u_b) . n); a
    // centre's bearing holds it at u = (the meshes' force on it) / k.
    const double f1 = l.force_n;
    const double f2 = l.force2();
    const std::array<double, 2> u_p{-f1 * line1[0] / kb, -f1 * line1[1] / kb};
    const std::array<double, 2> u_i{(f1 * line1[0] - f2 * line2[0]) / kb,
                                    (f1 * line1[1] - f2 * line2[1]) / kb};
    const std::array<double, 2> u_w{f2 * line2[0] / kb, f2 * line2[1] / kb};
    // s_d = turning + (u_a - u_b) . n keeps B + F/k_mesh: the turning's excess
    // is -(u_a - u_b) . n.
    const double expected1 = -((u_p[0] - u_i[0]) * line1[0] + (u_p[1] - u_i[1]) * line1[1]);
    const double expected2 = -((u_i[0] - u_w[0]) * line2[0] + (u_i[1] - u_w[1]) * line2[1]);
    const double excess1 = s[0] - rigid_s[0];
    const double excess2 = s[1] - rigid_s[1];
    CAPTURE(excess1);
    CAPTURE(expected1);
    CAPTURE(excess2);
    CAPTURE(expected2);
    // Settled over 2e-3 s (the slowest mode, ~2.4e4 rad/s at about 0.3 of
    // critical: about e^-14) from the start's departure (~F/k); 1e-3 of it.
    CHECK(std::abs(excess1 - expected1) < 1e-3 * expected1);
    CHECK(std::abs(excess2 - expected2) < 1e-3 * std::abs(expected2));
    if (kb < 5e11) {
      excess_at_1e11 = {excess1, excess2};
    } else {
      // The rate: ten times stiffer bearings, a tenth of the excess.
      CHECK(excess_at_1e11[0] / excess1 == doctest::Approx(10.0).epsilon(2e-3));
      CHECK(excess_at_1e11[1] / excess2 == doctest::Approx(10.0).epsilon(2e-3));
    }
  }
}

namespace {

// The paper's pair, pinion -> idler (the same pair as gear 1 and 2) ->
// wheel: impacts, time-varying stiffness, Hertzian damping, friction, on
// damped bearings, the second line of centres at 120 degrees.
GearTrain impacting_train(const StiffnessTable& table, double step) {
  const SimulationCase c = paper_case(2);
  const double j1 = moment_of_inertia(c.gears, Gear::one);
  const double j2 = moment_of_inertia(c.gears, Gear::two);
  GearTrain t;
  const double ratio = base_radius(c.gears, Gear::one) / base_radius(c.gears, Gear::two);
  TrainBody p{"pinion", j1, c.torque1, 0.0, 50.0};
  TrainBody i{"idler", j2, {}, 0.0, 50.0 * ratio};
  TrainBody w{"wheel", j2, c.torque2, 0.0, 0.98 * 50.0 * ratio};
  GearBearing b;
  b.stiffness_x_n_per_m = 3e8;
  b.damping_x_n_s_per_m = 150.0;
  b.mass_kg = disc_mass(c.gears, Gear::one);
  p.bearing = b;
  b.mass_kg = disc_mass(c.gears, Gear::two);
  b.stiffness_y_n_per_m = 5e8;
  i.bearing = b;
  w.bearing = b;
  t.bodies = {p, i, w};
  TrainMesh m1{"first", 0, 1, c, lent(table)};
  TrainMesh m2{"second", 1, 2, c, lent(table)};
  m2.pair.gears.teeth1 = c.gears.teeth2;
  m2.pair.gears.teeth2 = c.gears.teeth2;
  m2.table = nullptr;
  m2.centre_angle_rad = 2.0 * pi / 3.0;
  t.meshes = {m1, m2};
  t.integrator.step_s = step;
  t.integrator.end_time_s = 1.5e-3;
  t.integrator.output_every = 100;
  t.sensor_body = 1;
  return t;
}

}  // namespace

TEST_CASE("a train on bearings closes its ledger at RK4's order, bearings included") {
  const StiffnessTable table(paper_gear_pair(), paper_case(2).model.stiffness);
  const TrainResult coarse = simulate_train(impacting_train(table, 2e-7));
  const TrainResult fine = simulate_train(impacting_train(table, 1e-7));
  for (const TrainResult* r : {&coarse, &fine}) {
    REQUIRE(r->meshes[0].impacts >= 1);
    REQUIRE(r->meshes[1].impacts >= 1);
    REQUIRE(r->summary.planar->bearing_damping_loss_j > 0.0);
    REQUIRE(r->summary.damping_loss_j > 0.0);
  }
  const double scale = coarse.summary.ledger_scale_j;
  CAPTURE(coarse.summary.ledger_residual_max_j);
  CAPTURE(fine.summary.ledger_residual_max_j);
  CAPTURE(scale);
  // As the torsional two-stage train's: RK4's (omega h)^4 per period of
  // exchange, most of it cancelling; 1e-7 of the scale bounds it.
  CHECK(coarse.summary.ledger_residual_max_j / scale < 1e-7);
  // Fourth order: halving h divides it by about 16; events cut steps: 8.
  CHECK(fine.summary.ledger_residual_max_j < coarse.summary.ledger_residual_max_j / 8.0);
}

TEST_CASE("a train on bearings refuses what it does not run, naming the field") {
  const StiffnessTable table(paper_gear_pair(), paper_case(2).model.stiffness);
  const auto field_of = [](const GearTrain& t) {
    try {
      simulate_train(t);
    } catch (const InputError& e) {
      return e.problems().front().field;
    }
    return std::string("none");
  };
  GearTrain t = impacting_train(table, 2e-7);
  t.bodies[1].bearing->mass_kg.reset();
  CHECK(field_of(t) == "bodies.idler.bearings.mass");
  t = impacting_train(table, 2e-7);
  t.bodies[2].bearing->damping_y_n_s_per_m = -1.0;
  CHECK(field_of(t) == "bodies.wheel.bearings.damping_y");
  t = impacting_train(table, 2e-7);
  t.meshes[1].pair.model.mesh_force = MeshForce::lagrangian;
  CHECK(field_of(t) == "meshes.second.model.mesh_force");
  // A mesh in a carrier's frame whose body_b sits on no pin of that carrier (the idler-wheel
  // mesh held by the pinion as a carrier): a planetary stage's planet needs its pin.
  t = impacting_train(table, 2e-7);
  t.meshes[1].carrier = 0;
  CHECK(field_of(t) == "meshes.second.carrier");
  t = impacting_train(table, 2e-7);
  t.integrator.kind = IntegratorKind::adaptive;
  CHECK(field_of(t) == "integrator.kind");
  t = impacting_train(table, 2e-7);
  t.sensor_body = 5;
  CHECK(field_of(t) == "sensor_body");
  t = impacting_train(table, 2e-7);
  for (TrainBody& b : t.bodies) b.bearing.reset();
  CHECK(field_of(t) == "sensor_body");
  t = impacting_train(table, 2e-7);
  t.bodies[0].bearing->stiffness_x_n_per_m = 1e13;
  CHECK(field_of(t) == "integrator.step");
}
