// The planar planetary stage (dynamics/planetary_train.hpp with `supports`;
// the carrier-frame meshes and pinned planets of dynamics/train_planar.cpp).
// References: the rotational stage's run (the stiff-support limit, bounded
// by the compliance the supports add in series with each mesh); the static
// balance of identical, equally spaced planets (each sun mesh carries
// T_s / (N Rb_s)), which a floating sun keeps by symmetry; the ledger's
// residual at RK4's order.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planetary_train.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"

using namespace gearimpact;

namespace {

// A steel stage of module 2 mm, 20 deg, 20 mm wide (as test_planetary_train's).
PlanetaryStage stage_of(int sun, int planet, int ring, int planets) {
  PlanetaryStage s;
  s.teeth = {sun, planet, ring};
  s.mesh.gears.module_m = 2.0e-3;
  s.mesh.gears.face_width_m = 20.0e-3;
  s.mesh.gears.backlash_m = 0.05e-3;
  s.mesh.model.friction_coefficient = 0.0;
  s.mesh.model.mesh_damping_ratio = 0.1;
  s.planets = planets;
  const auto disc = [&](int z) {
    const double r = 0.5 * s.mesh.gears.module_m * z;
    return s.mesh.gears.density_kg_m3 * pi * r * r * r * r * s.mesh.gears.face_width_m / 2.0;
  };
  s.sun_inertia_kg_m2 = disc(sun);
  s.planet_inertia_kg_m2 = disc(planet);
  s.ring_inertia_kg_m2 = 4.0 * disc(ring);
  s.carrier_inertia_kg_m2 = 2.0e-3;
  s.planet_mass_kg = 0.3;
  s.integrator.kind = IntegratorKind::rk4;
  s.integrator.step_s = 1.0e-6;
  s.integrator.end_time_s = 0.002;
  return s;
}

StageSupports supports_of(double k, double bearing) {
  StageSupports p;
  p.sun_mass_kg = 0.8;
  p.ring_mass_kg = 2.5;
  p.carrier_mass_kg = 3.0;
  p.sun_support_n_per_m = k;
  p.ring_support_n_per_m = k;
  p.carrier_support_n_per_m = k;
  p.planet_bearing_n_per_m = bearing;
  return p;
}

Torque constant_torque(double t) {
  Torque q;
  q.kind = Torque::Kind::constant;
  q.constant_n_m = t;
  return q;
}

Torque driver(double w) {
  Torque q;
  q.kind = Torque::Kind::prescribed_speed;
  q.mean_speed_rad_per_s = w;
  return q;
}

// The stage driven at 100 rad/s on the sun, 20 N m on the carrier, on supports of 1e8 N/m and
// planet bearings of 5e8 N/m, 4 ms at 0.5 us.
PlanetaryStage driven_planar_stage(int sun, int planet, int ring, int planets) {
  PlanetaryStage s = stage_of(sun, planet, ring, planets);
  s.input_speed_rad_per_s = 100.0;
  s.sun_torque = driver(100.0);
  s.carrier_torque = constant_torque(-20.0);
  s.supports = supports_of(1.0e8, 5.0e8);
  s.integrator.end_time_s = 0.004;
  s.integrator.step_s = 0.5e-6;
  return s;
}

double sun_base_radius(const PlanetaryStage& s) {
  return 0.5 * s.mesh.gears.module_m * s.teeth.sun * std::cos(s.mesh.gears.pressure_angle_rad);
}

}  // namespace

TEST_CASE("stiff supports and planet bearings: the planar stage runs the rotational stage's run") {
  // 25/23/71, N = 3, ring held, the sun driven at 100 rad/s, 200 N m on the
  // carrier, constant mesh stiffness 5e8 N/m (so that the contact's
  // stiffness does not move with the tiny shifts of the pairs' positions)
  // and no backlash, so that the meshes take up the load from t = 0 without
  // impacts, whose timing a rattling run would amplify. Each support and
  // bearing of 1e12 N/m adds to a mesh line at most the compliances of the
  // springs its two centres sit on, projected on the line (|cos| <= 1): the
  // sun's support, the planet's bearing (radial and tangential) and the
  // carrier's support, 4e-12 m/N against the mesh's 2e-9 m/N: the line's
  // stiffness, and so its force at the same deflection history, moves by at
  // most 2e-3 relative. The supports and bearings are damped here (0.3 of
  // critical on their own masses, set on the built train): undamped, the
  // load's step at t = 0 would leave the stiff bearings ringing (MHz, about
  // 1e-3 of the carrier's speed), which the rotational stage has no
  // coordinate for; a damper in parallel only stiffens the series. Measured:
  // 2.9e-4 of the largest force.
  PlanetaryStage s = stage_of(25, 23, 71, 3);
  s.mesh.gears.backlash_m = 0.0;
  // The contact damping D of (32) frozen at its reference speed in both (as
  // the planar train reads "auto"): each-impact would set it from the
  // meshes' first approach, here at rest, and not alike in the two models.
  s.mesh.model.damping_update = DampingUpdate::frozen;
  s.mesh.model.mesh_stiffness = MeshStiffnessMode::constant;
  s.mesh.model.constant_mesh_stiffness_n_per_m = 5.0e8;
  s.input_speed_rad_per_s = 100.0;
  s.sun_torque = driver(100.0);
  s.carrier_torque = constant_torque(-200.0);
  s.integrator.step_s = 0.04e-6;
  s.integrator.end_time_s = 1.0e-3;
  const TrainResult rotational = simulate_train(planetary_train(s));
  s.supports = supports_of(1.0e12, 1.0e12);
  GearTrain stiff = planetary_train(s);
  for (TrainBody& b : stiff.bodies) {
    if (!b.bearing) continue;
    b.bearing->damping_x_n_s_per_m = 0.6 * std::sqrt(1.0e12 * *b.bearing->mass_kg);
  }
  const TrainResult planar = simulate_train(stiff);
  REQUIRE(planar.series.size() == rotational.series.size());
  REQUIRE(planar.series.front().centres.size() == 6);
  double largest_force = 0.0;
  double worst_force = 0.0;
  double largest_translation = 0.0;
  for (std::size_t r = 0; r < planar.series.size(); ++r) {
    const TrainRow& p = planar.series[r];
    const TrainRow& q = rotational.series[r];
    for (std::size_t k = 0; k < p.meshes.size(); ++k) {
      largest_force = std::max(largest_force, q.meshes[k].normal_force_n);
      worst_force =
          std::max(worst_force, std::fabs(p.meshes[k].normal_force_n - q.meshes[k].normal_force_n));
    }
    for (const TrainCentreRow& c : p.centres) {
      largest_translation = std::max({largest_translation, std::fabs(c.x_m), std::fabs(c.y_m)});
    }
  }
  CAPTURE(largest_force);
  CAPTURE(worst_force);
  CAPTURE(largest_translation);
  CHECK(largest_force > 100.0);  // the meshes carried the load
  CHECK(worst_force < 2e-3 * largest_force);
  // The centres did move (by about F / k, 1e-9 m), and no more than the
  // largest force over the stiffness.
  CHECK(largest_translation > 0.0);
  CHECK(largest_translation < 2.0 * largest_force / 1.0e12);
}

TEST_CASE(
    "a floating sun keeps equal static load sharing among identical, equally spaced planets") {
  // Ring held, sun torque T_s, the carrier loaded by -T_s (1 + Z_r / Z_s):
  // the damped stage settles to its static balance, where by the planets'
  // symmetry every sun mesh carries T_s / (N Rb_s), and every ring mesh the
  // same, whatever the supports (the central members' net forces cancel).
  // The sun floats (support 0), the others on 1e8 N/m, the planets on 1e8 N/m
  // bearings; N = 3 (25/23/71, constant stiffness) and N = 4 (24/24/72).
  struct Case {
    int zs, zp, zr, n;
  };
  for (const Case& c : {Case{25, 23, 71, 3}, Case{24, 24, 72, 4}}) {
    CAPTURE(c.n);
    PlanetaryStage s = stage_of(c.zs, c.zp, c.zr, c.n);
    s.mesh.model.mesh_stiffness = MeshStiffnessMode::constant;
    s.mesh.model.constant_mesh_stiffness_n_per_m = 5.0e8;
    s.mesh.model.mesh_damping_ratio = 0.2;
    s.supports = supports_of(1.0e8, 1.0e8);
    s.supports->sun_support_n_per_m = 0.0;
    const double ts = 20.0;
    s.sun_torque = constant_torque(ts);
    s.carrier_torque = constant_torque(-ts * (1.0 + double(c.zr) / c.zs));
    s.integrator.step_s = 0.5e-6;
    s.integrator.end_time_s = 0.012;
    // The bearings damped (0.3 of critical on their own masses, set on the
    // built train; the floating sun has none) so that the stage settles.
    GearTrain train = planetary_train(s);
    for (TrainBody& b : train.bodies) {
      if (!b.bearing || b.bearing->stiffness_x_n_per_m == 0.0) continue;
      b.bearing->damping_x_n_s_per_m =
          0.6 * std::sqrt(b.bearing->stiffness_x_n_per_m * *b.bearing->mass_kg);
    }
    const TrainResult r = simulate_train(train);
    const double share = ts / (c.n * sun_base_radius(s));
    const TrainRow& last = r.series.back();
    for (int i = 0; i < 2 * c.n; ++i) {
      CAPTURE(i);
      CAPTURE(last.meshes[static_cast<std::size_t>(i)].normal_force_n);
      // Settled: the slowest mode damped through the meshes; measured below
      // 1e-9 after 12 ms, the bound leaves room for what is left of it.
      CHECK(std::fabs(last.meshes[static_cast<std::size_t>(i)].normal_force_n / share - 1.0) <
            1e-6);
    }
    // The sun's centre stays where symmetry puts it.
    CHECK(std::hypot(last.centres[kSunBody].x_m, last.centres[kSunBody].y_m) < 1e-12);
  }
}

TEST_CASE("the planar stage closes its ledger at RK4's order") {
  // Driven and loaded, with friction on the sun meshes, supports of 1e8 N/m
  // and bearings of 5e8 N/m: the ledger (torque work = kinetic + stored
  // energy of the meshes, supports and bearings + losses) closes at RK4's
  // order: a quarter of the step divides its residual by far more than 64.
  PlanetaryStage d = driven_planar_stage(25, 23, 71, 3);
  d.mesh.model.friction_coefficient = 0.06;
  const TrainResult coarse = simulate_train(planetary_train(d));
  d.integrator.step_s = 0.125e-6;
  const TrainResult fine = simulate_train(planetary_train(d));
  CAPTURE(coarse.summary.ledger_residual_max_j);
  CAPTURE(fine.summary.ledger_residual_max_j);
  CAPTURE(coarse.summary.ledger_scale_j);
  REQUIRE(coarse.summary.planar.has_value());
  CHECK(coarse.summary.planar->bearing_energy_final_j > 0.0);
  CHECK(coarse.summary.friction_loss_j > 0.0);
  CHECK(coarse.summary.ledger_residual_max_j / coarse.summary.ledger_scale_j < 1e-5);
  CHECK(fine.summary.ledger_residual_max_j < coarse.summary.ledger_residual_max_j / 64.0);
}

TEST_CASE(
    "a stage's support and bearing dampers act on their own members; a centred sun's takes "
    "nothing") {
  // 24/24/72, N = 4: Z_s / N = 6 and Z_r / N = 18, so the four sun meshes are in phase, and so
  // are the four ring meshes; with the planets equally spaced their forces on each central member
  // cancel at every instant, and the sun, the ring and the carrier stay centred: the sun's damper
  // takes no energy but rounding's (the planets' directions are cosines of multiples of pi / 2,
  // 6e-17 from 0, and the phases 24 n / 4 whole to 1e-15; measured, 2.4e-23 of the planets'
  // dampers' loss; 1e-12 bounds it eleven decades short of a damper that acts). Each planet is
  // pushed by its two meshes, so a planet bearing's damper does take energy; and with the planets
  // unequally spaced (0, 93.75, 180 and 266.25 deg, multiples of 360 / 96 deg, the assembly
  // condition) the sun is pushed off its centre and its damper takes energy (measured, 3.0e-2 of
  // the planets'; the bound 1e-3 is for a damper that acts). The ledger books each and closes.
  PlanetaryStage s = driven_planar_stage(24, 24, 72, 4);
  s.mesh.gears.backlash_m = 0.0;  // loaded from t = 0, no impacts
  // About a tenth of critical on the sun (2 sqrt(k m) = 1.8e4 N s/m) and on a planet (2.4e4).
  const double c = 2000.0;
  const auto run = [](const PlanetaryStage& t) {
    const TrainResult r = simulate_train(planetary_train(t));
    REQUIRE(r.summary.planar.has_value());
    CHECK(r.summary.ledger_residual_max_j / r.summary.ledger_scale_j < 1e-5);
    return r;
  };
  PlanetaryStage sun = s;
  sun.supports->sun_support_damping_n_s_per_m = c;
  PlanetaryStage planets = s;
  planets.supports->planet_bearing_damping_n_s_per_m = c;
  PlanetaryStage unequal = sun;
  unequal.planet_angles_rad = {0.0, 93.75 * pi / 180.0, pi, 266.25 * pi / 180.0};
  const TrainResult by_sun = run(sun);
  const TrainResult by_planets = run(planets);
  const TrainResult by_unequal = run(unequal);
  const double sun_loss = by_sun.summary.planar->bearing_damping_loss_j;
  const double planet_loss = by_planets.summary.planar->bearing_damping_loss_j;
  const double unequal_loss = by_unequal.summary.planar->bearing_damping_loss_j;
  CAPTURE(sun_loss);
  CAPTURE(planet_loss);
  CAPTURE(unequal_loss);
  CHECK(planet_loss > 0.0);
  CHECK(sun_loss <= 1e-12 * planet_loss);
  CHECK(unequal_loss > 1e-3 * planet_loss);
  // The keys put the dampers where a train built by hand has them: the same run, bit for bit.
  GearTrain by_hand = planetary_train(s);
  for (std::size_t b = kFirstPlanetBody; b < by_hand.bodies.size(); ++b) {
    by_hand.bodies[b].bearing->damping_x_n_s_per_m = c;
  }
  const TrainResult hand = simulate_train(by_hand);
  REQUIRE(hand.series.size() == by_planets.series.size());
  bool same = true;
  for (std::size_t r = 0; r < hand.series.size(); ++r) {
    for (std::size_t k = 0; k < hand.series[r].meshes.size(); ++k) {
      same = same && hand.series[r].meshes[k].normal_force_n ==
                         by_planets.series[r].meshes[k].normal_force_n;
    }
    for (std::size_t k = 0; k < hand.series[r].centres.size(); ++k) {
      same = same && hand.series[r].centres[k].x_m == by_planets.series[r].centres[k].x_m &&
             hand.series[r].centres[k].y_m == by_planets.series[r].centres[k].y_m;
    }
  }
  CHECK(same);
  CHECK(hand.summary.planar->bearing_damping_loss_j == planet_loss);
}

namespace {

// The stage of stage_of (25/23/71, N = 3) on supports of 1e8 N/m and planet
// bearings of 5e8 N/m damped at `bearing_damping`, every member turning at
// omega with no torque and none held, the carrier at omega by a driver when
// `driven` (else free): the stage spins as one rigid body, each mesh's s at the
// middle of its play, so that only the turning axes load the centres.
GearTrain spinning_stage(double omega, bool driven, double bearing_damping) {
  PlanetaryStage s = stage_of(25, 23, 71, 3);
  s.input_speed_rad_per_s = 100.0;
  s.sun_torque = driver(100.0);
  s.supports = supports_of(1.0e8, 5.0e8);
  s.supports->planet_bearing_damping_n_s_per_m = bearing_damping;
  s.integrator.step_s = 0.5e-6;
  s.integrator.end_time_s = 0.003;
  GearTrain t = planetary_train(s);
  for (TrainBody& b : t.bodies) {
    b.held = false;
    b.torque = constant_torque(0.0);
    b.w_rad_per_s = omega;
  }
  if (driven) t.bodies[kCarrierBody].torque = driver(omega);
  return t;
}

}  // namespace

TEST_CASE("a planet turning with its carrier settles on its bearing at m R W^2 / (k - m W^2)") {
  // In the carrier's axes, turning at W, a planet of mass m on its pin at R
  // whose bearing (k radial) holds it still there is pressed outward by m W^2
  // (R + d): k d = m W^2 (R + d). Dampers of half the critical damping on
  // the planet's mass (2 * 0.5 * sqrt(k m)) settle it within 1 ms (the
  // transient falls as exp(-0.5 sqrt(k/m) t), e^-61 by 3 ms); the meshes'
  // play (5e-5 m) is never reached (d sin(alpha) < 1e-6 m). 1e-9 relative:
  // RK4 holds a steady state to rounding, and the bound is 5e4 times below
  // the shift's m W^2 / k = 5.4e-5 part (the centripetal m W^2 d) and 1e5
  // times below leaving the turning axes out altogether (d = 0).
  const double omega = 300.0;
  const double k = 5.0e8;
  const double m = 0.3;
  const GearTrain t = spinning_stage(omega, true, std::sqrt(k * m));
  const TrainResult r = simulate_train(t);
  REQUIRE(!r.series.empty());
  const TrainRow& last = r.series.back();
  for (std::size_t p = kFirstPlanetBody; p < t.bodies.size(); ++p) {
    CAPTURE(p);
    const TrainBody::Pin& pin = *t.bodies[p].pin;
    const double expected = m * omega * omega * pin.radius_m / (k - m * omega * omega);
    const TrainCentreRow& c = last.centres[p];
    const double radial = c.x_m * std::cos(pin.angle_rad) + c.y_m * std::sin(pin.angle_rad);
    const double tangential = c.y_m * std::cos(pin.angle_rad) - c.x_m * std::sin(pin.angle_rad);
    CAPTURE(expected);
    CAPTURE(radial);
    CHECK(std::fabs(radial - expected) <= 1e-9 * expected);
    // At a steady speed the tangential (Euler and Coriolis) terms vanish.
    CHECK(std::fabs(tangential) <= 1e-9 * expected);
    // The bearing holds it with the centrifugal force, k d inward.
    const double fr =
        c.bearing_fx_n * std::cos(pin.angle_rad) + c.bearing_fy_n * std::sin(pin.angle_rad);
    CHECK(std::fabs(fr + k * expected) <= 1e-9 * k * expected);
  }
  // The central members feel nothing (the planets' pulls on the carrier
  // cancel), and no mesh touched.
  for (const std::size_t central : {kSunBody, kRingBody, kCarrierBody}) {
    CHECK(std::fabs(last.centres[central].x_m) < 1e-15);
    CHECK(std::fabs(last.centres[central].y_m) < 1e-15);
  }
  for (const TrainMeshSummary& mesh : r.meshes) CHECK(mesh.impacts == 0);
}

TEST_CASE("a free stage spinning on its planets' damped bearings keeps its energy") {
  // The carrier free at 300 rad/s: the planets, let go at their pins, swing
  // outward and settle, the carrier giving up the kinetic energy that their
  // bearings' dampers take and their springs store (5.0e-3 J at the end).
  // Each of these is booked on its own (kinetic energy with the axes'
  // turning, the bearings' energy, their dampers' loss), so a term of the
  // turning axes left out or of the wrong sign leaves a residual that does
  // not fall with the step. Measured: without the carrier's -sum u x F,
  // 2.3e-7 J at this step and at half of it (4.5e-5 of the bearings'
  // energy); with the Coriolis term's sign turned, 6.4e-2 J (13 times the
  // bearings' energy); with the terms as they are, 3.8e-11 J (2.6e-11 J at
  // half the step), the rounding of the carrier's 1318 J (3e-14 of it).
  // 1e-6 of the bearings' energy lies between.
  const TrainResult r = simulate_train(spinning_stage(300.0, false, 0.3 * std::sqrt(5.0e8 * 0.3)));
  REQUIRE(r.summary.planar.has_value());
  CAPTURE(r.summary.ledger_residual_max_j);
  CAPTURE(r.summary.ledger_scale_j);
  CAPTURE(r.summary.planar->bearing_energy_final_j);
  CHECK(r.summary.planar->bearing_energy_final_j > 1e-3);
  CHECK(r.summary.ledger_residual_max_j < 1e-6 * r.summary.planar->bearing_energy_final_j);
}

TEST_CASE("the planar stage's bad input is refused by its key") {
  PlanetaryStage s = stage_of(25, 23, 71, 3);
  s.supports = supports_of(1.0e8, 1.0e8);
  const auto refused = [](const PlanetaryStage& t, const char* key) {
    try {
      planetary_train(t);
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find(key) != std::string::npos);
      return true;
    }
    return false;
  };
  PlanetaryStage t = s;
  t.planet_mass_kg.reset();
  CHECK(refused(t, "planet_mass"));
  t = s;
  t.supports->planet_bearing_n_per_m = 0.0;
  CHECK(refused(t, "planet_bearing"));
  t = s;
  t.supports->ring_support_n_per_m = -1.0;
  CHECK(refused(t, "ring_support"));
  t = s;
  t.supports->carrier_mass_kg = 0.0;
  CHECK(refused(t, "carrier_mass"));
  t = s;
  t.supports->planet_bearing_damping_n_s_per_m = -1.0;
  CHECK(refused(t, "planet_bearing_damping"));
  t = s;
  t.supports->sun_support_damping_n_s_per_m = std::nan("");
  CHECK(refused(t, "sun_support_damping"));
  // The ranges are the stage file's rows' (train_schema()), for a stage built
  // in code too: past a row's upper bound is refused with the row's reason.
  t = s;
  t.supports->sun_support_damping_n_s_per_m = 2.0e6;
  CHECK(refused(t, "squeeze-film"));
  t.supports->sun_support_damping_n_s_per_m = 1.0e6;
  CHECK_FALSE(refused(t, "sun_support_damping"));
  t = s;
  t.sun_inertia_kg_m2 = 2.0e6;
  CHECK(refused(t, "sun_inertia"));
  t = s;
  t.input_speed_rad_per_s = 2.0e5;
  CHECK(refused(t, "input_speed"));
  // On bearings a train turns in one carrier's axes: the third planet moved
  // to a carrier of its own, its meshes are refused by their carrier key.
  GearTrain two = planetary_train(s);
  two.bodies.push_back(two.bodies[kCarrierBody]);
  two.bodies.back().name = "carrier2";
  const int second = static_cast<int>(two.bodies.size()) - 1;
  const int planet = kFirstPlanetBody + 2;
  two.bodies[planet].pin->carrier = second;
  for (TrainMesh& m : two.meshes) {
    if (m.body_b == planet) m.carrier = second;
  }
  std::string message;
  try {
    simulate_train(two);
  } catch (const InputError& e) {
    message = e.what();
  }
  CAPTURE(message);
  CHECK(message.find(".carrier") != std::string::npos);
  CHECK(message.find("one carrier's axes") != std::string::npos);
}
