// The modes of a torsional gear train (modes/train_modes.hpp) against routes
// that do not use it: the two-stage closed form of docs/planetary.md (the
// roots of lambda^2 - (k12 A + k34 Bq) lambda + k12 k34 (A Bq - C^2), written
// out here about +z), its limit as the second stage stiffens (the single pair
// with stage 2 reflected onto shaft 2), the kinematic ratios from the teeth
// (an idler's w3 = +(Z1/Z3) w1 whatever its Z2) and the reflected inertia, and
// the two-gear model with a motor and a load behind torsional shafts
// (modes/modes.hpp, its own matrices with theta2 about -z).
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/modes/modes.hpp"
#include "gearimpact/modes/train_modes.hpp"

using namespace gearimpact;

namespace {

double relative(double a, double b) {
  return std::fabs(a - b) / std::fabs(b);
}

// A pair of z1, z2 teeth at a constant mesh stiffness k, without friction.
SimulationCase constant_pair(int z1, int z2, double k) {
  SimulationCase c;
  c.gears.teeth1 = z1;
  c.gears.teeth2 = z2;
  c.model.mesh_stiffness = MeshStiffnessMode::constant;
  c.model.constant_mesh_stiffness_n_per_m = k;
  c.model.friction_coefficient = 0.0;
  return c;
}

GearTrain empty_train() {
  GearTrain t;
  t.integrator.step_s = 1e-6;
  t.integrator.end_time_s = 1e-3;
  return t;
}

// A countershaft train, teeth 1-2 and 3-4 (the UConn rig's 32/80 and 48/64): pinion 1 drives
// wheel 2, on one shaft with pinion 3 (rigid: one body of J2 + J3; torsional: a spring), which
// drives wheel 4.
struct Countershaft {
  std::array<int, 4> z{32, 80, 48, 64};
  std::array<double, 4> j{2.1e-4, 7.3e-3, 1.3e-3, 4.4e-3};  // kg m^2
  double k12 = 3.0e8;
  double k34 = 4.0e8;

  GearTrain train(TrainShaft::Kind shaft_kind, double shaft_stiffness = 0.0) const {
    GearTrain t = empty_train();
    const char* names[4] = {"pinion1", "wheel2", "pinion3", "wheel4"};
    for (std::size_t i = 0; i < 4; ++i) {
      TrainBody b;
      b.name = names[i];
      b.inertia_kg_m2 = j[i];
      t.bodies.push_back(b);
    }
    t.meshes = {TrainMesh{"stage1", 0, 1, constant_pair(z[0], z[1], k12), nullptr},
                TrainMesh{"stage2", 2, 3, constant_pair(z[2], z[3], k34), nullptr}};
    TrainShaft s;
    s.kind = shaft_kind;
    s.body_a = 1;
    s.body_b = 2;
    s.stiffness_n_m_per_rad = shaft_stiffness;
    t.shafts = {s};
    return t;
  }
  double rb(std::size_t gear) const {
    GearPair g;
    g.teeth1 = z[gear];
    return base_radius(g, Gear::one);
  }
};

// The roots of lambda^2 - p lambda + q, the smaller by q / larger (no cancellation).
std::array<double, 2> quadratic_roots(double p, double q) {
  const double larger = 0.5 * (p + std::sqrt(p * p - 4.0 * q));
  return {q / larger, larger};
}

// The two elastic w^2 of the rigid countershaft by the closed form, about +z:
// a = (Rb1, Rb2, 0), b = (0, Rb3, Rb4), M = diag(J1, J2 + J3, J4).
std::array<double, 2> closed_form(const Countershaft& c) {
  const double j23 = c.j[1] + c.j[2];
  const double a_m_a = c.rb(0) * c.rb(0) / c.j[0] + c.rb(1) * c.rb(1) / j23;
  const double b_m_b = c.rb(2) * c.rb(2) / j23 + c.rb(3) * c.rb(3) / c.j[3];
  const double a_m_b = c.rb(1) * c.rb(2) / j23;
  return quadratic_roots(c.k12 * a_m_a + c.k34 * b_m_b,
                         c.k12 * c.k34 * (a_m_a * b_m_b - a_m_b * a_m_b));
}

}  // namespace

TEST_CASE("a rigid countershaft's two elastic modes are the roots of the closed form") {
  const Countershaft c;
  const TrainModes m = train_modes(c.train(TrainShaft::Kind::rigid));
  REQUIRE(m.modes.size() == 3);
  CHECK(m.modes[0].rigid);
  CHECK(m.modes[0].angular_frequency == 0.0);
  const std::array<double, 2> lambda = closed_form(c);
  for (std::size_t i = 0; i < 2; ++i) {
    const TrainMode& mode = m.modes[i + 1];
    CHECK_FALSE(mode.rigid);
    const double w2 = mode.angular_frequency * mode.angular_frequency;
    // Both sides round a handful of operations on numbers of one scale; the
    // solver's error on w^2 is ~1e-15 of the largest: 1e-12 relative.
    CHECK(relative(w2, lambda[i]) < 1e-12);
    CHECK(relative(mode.frequency_hz, std::sqrt(lambda[i]) / (2.0 * pi)) < 1e-12);
    // Shares: each mesh's k (a . v)^2 over w^2, summing to 1.
    CHECK(std::fabs(mode.energy_share[0] + mode.energy_share[1] - 1.0) < 1e-12);
    CHECK(mode.energy_share[0] > 0.0);
    CHECK(mode.energy_share[1] > 0.0);
    // Mass-normalised.
    CHECK(std::fabs(mode.shape.dot(m.model.mass * mode.shape) - 1.0) < 1e-12);
  }
}

TEST_CASE("as the second stage stiffens the lower mode tends to the pair with stage 2 reflected") {
  Countershaft c;
  // k12 (Rb1^2/J1 + Rb2^2/J_2eff), J_2eff = J23 + J4 (Rb3/Rb4)^2.
  const double j2eff = c.j[1] + c.j[2] + c.j[3] * std::pow(c.rb(2) / c.rb(3), 2);
  const double limit = c.k12 * (c.rb(0) * c.rb(0) / c.j[0] + c.rb(1) * c.rb(1) / j2eff);
  std::vector<double> gaps;
  for (double k34 : {1e11, 1e12, 1e13, 1e14}) {
    c.k34 = k34;
    const TrainModes m = train_modes(c.train(TrainShaft::Kind::rigid));
    const double w2 = m.modes[1].angular_frequency * m.modes[1].angular_frequency;
    CHECK(relative(w2, closed_form(c)[0]) < 1e-10);
    CHECK(w2 < limit);  // a stiffer spring raises it towards the limit from below
    gaps.push_back(relative(w2, limit));
  }
  // The gap is O(1/k34) once k34 is well above k12 (here from ~1e11 N/m; an
  // mpmath evaluation of the closed form gives the ratios 10.12, 10.012,
  // 10.001 over these decades): tenfold per decade to 5 %. The smallest gap,
  // 4e-7, stays far above the solver's error on the lower w^2, ~1e-16 times
  // w_max^2 / w_min^2 ~ 1e6.
  for (std::size_t i = 1; i < gaps.size(); ++i) {
    CAPTURE(i);
    CHECK(gaps[i - 1] / gaps[i] > 9.5);
    CHECK(gaps[i - 1] / gaps[i] < 10.5);
  }
}

TEST_CASE("a torsional countershaft tends to the rigid one as its shaft stiffens") {
  const Countershaft c;
  const TrainModes rigid = train_modes(c.train(TrainShaft::Kind::rigid));
  double previous = 1.0;
  for (double ks : {1e6, 1e7, 1e8, 1e9}) {
    CAPTURE(ks);
    const TrainModes m = train_modes(c.train(TrainShaft::Kind::torsional, ks));
    REQUIRE(m.modes.size() == 4);
    CHECK(m.modes[0].rigid);
    CHECK(m.model.springs.size() == 3);
    CHECK(m.model.springs[2].kind == TrainSpring::Kind::shaft);
    // The lowest elastic mode approaches the rigid shaft's from below
    // (Rayleigh: a stiffer spring raises every frequency).
    const double gap = relative(m.modes[1].angular_frequency, rigid.modes[1].angular_frequency);
    CHECK(m.modes[1].angular_frequency < rigid.modes[1].angular_frequency);
    CHECK(gap < previous);
    previous = gap;
    // The highest mode's shares (two meshes and the shaft) sum to 1.
    double sum = 0.0;
    for (double s : m.modes[3].energy_share) sum += s;
    CHECK(std::fabs(sum - 1.0) < 1e-12);
  }
  CHECK(previous < 1e-3);
}

TEST_CASE(
    "the rigid mode turns each body at its ratio of teeth; the inertia reflected to shaft 1") {
  SUBCASE("a countershaft: w2 = -(Z1/Z2) w1, w4 = Z1 Z3 / (Z2 Z4) w1 about +z") {
    const Countershaft c;
    const TrainModes m = train_modes(c.train(TrainShaft::Kind::rigid));
    const Eigen::VectorXd v = body_shape(m.model, m.modes[0]);
    // Forward senses about +z: pinion 1 +, wheel 2 and pinion 3 - (one external
    // mesh away), wheel 4 + (two).
    const std::array<double, 4> sense{1.0, -1.0, -1.0, 1.0};
    const double z1 = c.z[0], z2 = c.z[1], z3 = c.z[2], z4 = c.z[3];
    // One module: Rb ratios are teeth ratios up to rounding of the radii.
    CHECK(relative(sense[1] * v(1) / (sense[0] * v(0)), -z1 / z2) < 1e-14);
    CHECK(relative(sense[2] * v(2) / (sense[0] * v(0)), -z1 / z2) < 1e-14);
    CHECK(relative(sense[3] * v(3) / (sense[0] * v(0)), z1 * z3 / (z2 * z4)) < 1e-14);
    // v^T M v = 1 with v1 the pinion's: J_eq = 1 / v1^2.
    const double j_eq = c.j[0] + (c.j[1] + c.j[2]) * std::pow(z1 / z2, 2) +
                        c.j[3] * std::pow(z1 * z3 / (z2 * z4), 2);
    CHECK(relative(1.0 / (v(0) * v(0)), j_eq) < 1e-14);
  }
  SUBCASE("an idler: w3 = +(Z1/Z3) w1 whatever its Z2") {
    for (int z2 : {18, 30, 71}) {
      CAPTURE(z2);
      GearTrain t = empty_train();
      for (const char* name : {"pinion", "idler", "wheel"}) {
        TrainBody b;
        b.name = name;
        b.inertia_kg_m2 = 1e-3;
        t.bodies.push_back(b);
      }
      t.meshes = {TrainMesh{"a", 0, 1, constant_pair(20, z2, 2e8), nullptr},
                  TrainMesh{"b", 1, 2, constant_pair(z2, 60, 3e8), nullptr}};
      const TrainModes m = train_modes(t);
      REQUIRE(m.modes.size() == 3);
      REQUIRE(m.modes[0].rigid);
      CHECK_FALSE(m.modes[1].rigid);
      const Eigen::VectorXd v = body_shape(m.model, m.modes[0]);
      // About +z the idler turns the other way (-1), the wheel as the pinion (+1):
      // w3 / w1 in +z is v3 / v1 in the forward senses.
      CHECK(relative(v(2) / v(0), 20.0 / 60.0) < 1e-14);
      CHECK(relative(-v(1) / v(0), -20.0 / z2) < 1e-14);
      // The rigid mode stores nothing.
      CHECK((m.model.stiffness * m.modes[0].shape).norm() <
            1e-9 * m.model.stiffness.norm() * m.modes[0].shape.norm());
    }
  }
}

TEST_CASE("a pinion and a wheel with a motor and a load on shafts: the two-gear model's modes") {
  // The same system by modes/modes.hpp (its own matrices, theta2 about -z).
  SimulationCase c = constant_pair(20, 80, 2.5e8);
  LinearParameters p;
  p.base_radius1_m = base_radius(c.gears, Gear::one);
  p.base_radius2_m = base_radius(c.gears, Gear::two);
  p.working_pressure_angle_rad = c.gears.pressure_angle_rad;
  p.inertia1_kg_m2 = moment_of_inertia(c.gears, Gear::one);
  p.inertia2_kg_m2 = moment_of_inertia(c.gears, Gear::two);
  p.mesh_stiffness_n_per_m = 2.5e8;
  p.shafts = ShaftKind::elastic;
  p.motor_inertia_kg_m2 = 5e-3;
  p.motor_stiffness_n_m_per_rad = 4e3;
  p.load_inertia_kg_m2 = 2e-2;
  p.load_stiffness_n_m_per_rad = 9e4;
  const Modes reference = natural_modes(linear_model(p));

  GearTrain t = empty_train();
  const auto body = [](const char* name, double j) {
    TrainBody b;
    b.name = name;
    b.inertia_kg_m2 = j;
    return b;
  };
  t.bodies = {body("motor", p.motor_inertia_kg_m2), body("pinion", p.inertia1_kg_m2),
              body("wheel", p.inertia2_kg_m2), body("load", p.load_inertia_kg_m2)};
  t.meshes = {TrainMesh{"mesh", 1, 2, c, nullptr}};
  TrainShaft motor{TrainShaft::Kind::torsional, 0, 1, p.motor_stiffness_n_m_per_rad};
  TrainShaft load{TrainShaft::Kind::torsional, 2, 3, p.load_stiffness_n_m_per_rad};
  t.shafts = {motor, load};
  const TrainModes m = train_modes(t);
  // The constant pair's mean stiffness is its k.
  CHECK(m.model.mesh_stiffness_n_per_m[0] == 2.5e8);
  REQUIRE(m.modes.size() == reference.modes.size());
  for (std::size_t i = 0; i < m.modes.size(); ++i) {
    CAPTURE(i);
    CHECK(m.modes[i].rigid == reference.modes[i].rigid);
    if (m.modes[i].rigid) continue;
    // Two solvers on matrices of one scale: 1e-10 relative.
    CHECK(relative(m.modes[i].frequency_hz, reference.modes[i].frequency_hz) < 1e-10);
    // Shares: mesh, motor shaft, load shaft against the reference's parts.
    CHECK(std::fabs(m.modes[i].energy_share[0] -
                    reference.modes[i].energy_share[static_cast<std::size_t>(SpringPart::mesh)]) <
          1e-8);
    CHECK(std::fabs(
              m.modes[i].energy_share[1] -
              reference.modes[i].energy_share[static_cast<std::size_t>(SpringPart::motor_shaft)]) <
          1e-8);
    CHECK(std::fabs(
              m.modes[i].energy_share[2] -
              reference.modes[i].energy_share[static_cast<std::size_t>(SpringPart::load_shaft)]) <
          1e-8);
  }
}

TEST_CASE("a mesh of stiffness 0 leaves two rigid modes; bad stiffnesses are refused") {
  const Countershaft c;
  const GearTrain t = c.train(TrainShaft::Kind::rigid);
  const TrainModes m = train_modes(train_linear_model(t, {0.0, 4e8}));
  REQUIRE(m.modes.size() == 3);
  CHECK(m.modes[0].rigid);
  CHECK(m.modes[1].rigid);
  CHECK_FALSE(m.modes[2].rigid);
  // The pinion alone, then the countershaft with wheel 4: each group turns alone.
  const bool pinion_alone = m.modes[0].shape(1) == 0.0 && m.modes[0].shape(2) == 0.0;
  const bool pinion_still = m.modes[1].shape(0) == 0.0;
  CHECK(pinion_alone);
  CHECK(pinion_still);
  // The elastic mode is stage 2's alone: sqrt(k34 (Rb3^2/J23 + Rb4^2/J4)).
  const double j23 = c.j[1] + c.j[2];
  const double w = std::sqrt(4e8 * (c.rb(2) * c.rb(2) / j23 + c.rb(3) * c.rb(3) / c.j[3]));
  CHECK(relative(m.modes[2].angular_frequency, w) < 1e-12);
  CHECK_THROWS_AS(train_linear_model(t, {-1.0, 4e8}), InputError);
  CHECK_THROWS_AS(train_linear_model(t, {1e8}), InputError);
  try {
    train_linear_model(t, {std::nan(""), 4e8});
    FAIL("a NaN stiffness was taken");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("meshes.stage1.mesh_stiffness") != std::string::npos);
  }
}
