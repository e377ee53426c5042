// The linearised planar model (docs/vibration.md): natural frequencies and
// mode shapes against closed forms reached by other routes (the torsional
// frequency with the effective mass written out here, the bearings alone, a
// 2-DOF characteristic equation, the stiffness matrix from s_d's gradient),
// the energy shares and M-orthogonality, and the refusals of the dynamics.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/modes/modes.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/table.hpp"

using namespace gearimpact;

namespace {

double relative(double a, double b) {
  return std::fabs(a - b) / std::fabs(b);
}

// The paper's case 1 at a constant mesh stiffness k, so that k is known
// exactly, on bearings of stiffness kb in both directions.
SimulationCase planar_case(double kb, double k = 2.0e8) {
  SimulationCase c = paper_case(1);
  c.model.mesh_stiffness = MeshStiffnessMode::constant;
  c.model.constant_mesh_stiffness_n_per_m = k;
  c.bearings.kind = BearingKind::elastic;
  c.bearings.gear1.stiffness_x_n_per_m = kb;
  c.bearings.gear2.stiffness_x_n_per_m = kb;
  return c;
}

// sqrt(k / m_e) / (2 pi), 1/m_e = Rb1^2/J1 + Rb2^2/J2, J = rho pi r^4 L / 2
// of the discs on the pitch circles, r = m z / 2, Rb = r cos a0 (the paper's
// pair has no shift: the working pressure angle is a0).
double torsional_hz(const GearPair& g, double k) {
  const double r1 = g.module_m * g.teeth1 / 2.0;
  const double r2 = g.module_m * g.teeth2 / 2.0;
  const double j1 = g.density_kg_m3 * pi * std::pow(r1, 4) * g.face_width_m / 2.0;
  const double j2 = g.density_kg_m3 * pi * std::pow(r2, 4) * g.face_width_m / 2.0;
  const double rb1 = r1 * std::cos(g.pressure_angle_rad);
  const double rb2 = r2 * std::cos(g.pressure_angle_rad);
  const double me = 1.0 / (rb1 * rb1 / j1 + rb2 * rb2 / j2);
  return std::sqrt(k / me) / (2.0 * pi);
}

// The elastic mode that stores most of its energy in the mesh.
const NaturalMode& mesh_mode(const Modes& modes) {
  const NaturalMode* best = nullptr;
  for (const NaturalMode& m : modes.modes) {
    if (m.rigid) continue;
    if (best == nullptr || m.energy_share[0] > best->energy_share[0]) best = &m;
  }
  REQUIRE(best != nullptr);
  return *best;
}

double sum(const std::array<double, kSpringParts>& shares) {
  double s = 0.0;
  for (double x : shares) s += x;
  return s;
}

}  // namespace

TEST_CASE("rigid bearings: the one elastic mode is sqrt(k / m_e) / (2 pi)") {
  SimulationCase c = planar_case(1e9);
  c.bearings.kind = BearingKind::rigid;
  const Modes modes = natural_modes(c);
  REQUIRE(modes.modes.size() == 2);
  CHECK(modes.modes[0].rigid);
  CHECK(modes.modes[0].frequency_hz == 0.0);
  CHECK_FALSE(modes.modes[1].rigid);
  // Two DOF: the eigenvalue and the written-out formula differ by rounding.
  CHECK(relative(modes.modes[1].frequency_hz, torsional_hz(c.gears, 2.0e8)) < 1e-12);
  CHECK(modes.modes[1].energy_share[0] == 1.0);
}

TEST_CASE("base-circle shapes: the rigid mode rolls, the mesh mode keeps the momentum balance") {
  SimulationCase c = planar_case(1e9);
  c.bearings.kind = BearingKind::rigid;
  const Modes modes = natural_modes(c);
  REQUIRE(modes.modes.size() == 2);
  // Rolling without deflection: Rb1 theta1 = Rb2 theta2, both scaled to 1.
  const Eigen::VectorXd rolling = base_circle_shape(modes.model, modes.modes[0]);
  CHECK(std::fabs(rolling(0) - 1.0) < 1e-12);
  CHECK(std::fabs(rolling(1) - 1.0) < 1e-12);
  // The elastic mode is M-orthogonal to rolling: J1 v1 / Rb1 + J2 v2 / Rb2 = 0, so
  // Rb1 v1 / (Rb2 v2) = -m_e2 / m_e1 with m_ei = J_i / Rb_i^2 (discs on the pitch circles).
  const GearPair& g = c.gears;
  const double r1 = g.module_m * g.teeth1 / 2.0;
  const double r2 = g.module_m * g.teeth2 / 2.0;
  const double rb1 = r1 * std::cos(g.pressure_angle_rad);
  const double rb2 = r2 * std::cos(g.pressure_angle_rad);
  const double me1 = g.density_kg_m3 * pi * std::pow(r1, 4) * g.face_width_m / 2.0 / (rb1 * rb1);
  const double me2 = g.density_kg_m3 * pi * std::pow(r2, 4) * g.face_width_m / 2.0 / (rb2 * rb2);
  const Eigen::VectorXd mesh = base_circle_shape(modes.model, modes.modes[1]);
  CHECK(relative(mesh(0) / mesh(1), -me2 / me1) < 1e-12);
  // The pinion's effective mass is the smaller: it moves more, and carries the 1.
  CHECK(mesh(0) == 1.0);
}

TEST_CASE("very stiff bearings approach the torsional mode, the difference falling as 1/kb") {
  const double k = 2.0e8;
  const double ft = torsional_hz(paper_gear_pair(), k);
  const Modes stiff = natural_modes(planar_case(1e14));
  REQUIRE(stiff.modes.size() == 6);
  CHECK(stiff.model.rigid_modes == 1);
  const auto difference = [&](double kb) {
    return (ft - mesh_mode(natural_modes(planar_case(kb, k))).frequency_hz) / ft;
  };
  const double d12 = difference(1e12);
  const double d13 = difference(1e13);
  const double d14 = (ft - mesh_mode(stiff).frequency_hz) / ft;
  // Quasi-statically the mesh acts in series with both bearings along n1, each of compliance
  // sin^2 a / k_x + cos^2 a / k_y = 1 / kb: k_eff = 1 / (1 / k + 2 / kb), so
  // df / f = k / kb to first order. The second order (k / kb and the bearing masses' inertia)
  // is 3e-3 of it at kb = 1e12 (measured: d12 / d13 = 10.026), a tenth of that per decade.
  CHECK(std::fabs(d14 / (k / 1e14) - 1.0) < 1e-3);
  CHECK(std::fabs(d13 / (k / 1e13) - 1.0) < 3e-3);
  CHECK(std::fabs(d12 / d13 - 10.0) < 0.05);
  CHECK(std::fabs(d13 / d14 - 10.0) < 0.01);
  // At the schema's stiffest bearing the rounding (eps kb / m against w^2) still leaves the
  // frequency right to 1e-8 of itself: the first-order difference holds to that.
  CHECK(std::fabs(difference(1e16) - k / 1e16) < 1e-8);
}

TEST_CASE("zero mesh stiffness: each gear on its bearing, sqrt(k_b / m) per direction") {
  LinearParameters p;
  p.base_radius1_m = 0.02;
  p.base_radius2_m = 0.05;
  p.working_pressure_angle_rad = 20.0 * pi / 180.0;
  p.inertia1_kg_m2 = 1e-4;
  p.inertia2_kg_m2 = 3e-3;
  p.mesh_stiffness_n_per_m = 0.0;
  p.bearings = BearingKind::elastic;
  p.mass_kg = {0.5, 2.5};
  p.bearing_stiffness_x_n_per_m = {1e8, 3e8};
  p.bearing_stiffness_y_n_per_m = {2e8, 5e8};
  const Modes modes = natural_modes(linear_model(p));
  REQUIRE(modes.modes.size() == 6);
  CHECK(modes.modes[0].rigid);
  CHECK(modes.modes[1].rigid);
  std::vector<double> expected{std::sqrt(1e8 / 0.5), std::sqrt(2e8 / 0.5), std::sqrt(3e8 / 2.5),
                               std::sqrt(5e8 / 2.5)};
  std::sort(expected.begin(), expected.end());
  for (std::size_t i = 0; i < 4; ++i) {
    // A diagonal pencil: the solver's rounding, a few ulps.
    CHECK(relative(modes.modes[i + 2].angular_frequency, expected[i]) < 1e-12);
    // Each stores its energy in one bearing.
    const std::array<double, kSpringParts>& share = modes.modes[i + 2].energy_share;
    CHECK(std::max(share[1], share[2]) == doctest::Approx(1.0).epsilon(1e-12));
  }
}

TEST_CASE("the stiffness matrix is k g g^T of s_d's gradient plus the bearings") {
  LinearParameters p;
  p.base_radius1_m = 0.03;
  p.base_radius2_m = 0.07;
  p.working_pressure_angle_rad = 0.4;
  p.inertia1_kg_m2 = 2e-4;
  p.inertia2_kg_m2 = 5e-3;
  p.mesh_stiffness_n_per_m = 3e8;
  p.bearings = BearingKind::elastic;
  p.mass_kg = {0.7, 3.0};
  p.bearing_stiffness_x_n_per_m = {1e9, 2e9};
  p.bearing_stiffness_y_n_per_m = {3e9, 4e9};
  const LinearModel m = linear_model(p);
  // s_d = Rb1 theta1 - Rb2 theta2 + (u1 - u2) . (sin a, cos a), q = (x1, y1, theta1, x2, y2,
  // theta2).
  Eigen::VectorXd g(6);
  g << std::sin(0.4), std::cos(0.4), 0.03, -std::sin(0.4), -std::cos(0.4), -0.07;
  Eigen::MatrixXd k = 3e8 * g * g.transpose();
  k(0, 0) += 1e9;
  k(1, 1) += 3e9;
  k(3, 3) += 2e9;
  k(4, 4) += 4e9;
  CHECK((m.stiffness - k).norm() <= 1e-15 * k.norm());
  Eigen::VectorXd mass(6);
  mass << 0.7, 0.7, 2e-4, 3.0, 3.0, 5e-3;
  CHECK(m.mass == Eigen::MatrixXd(mass.asDiagonal()));
}

TEST_CASE("one translation coupled to the torsion: the 2-DOF characteristic equation") {
  // Gear 1 on a bearing across the centre line (y, k_y) meshing with a fixed wheel:
  // s = cos(a) y + Rb theta. det(K - lambda M) = 0 is
  // m J lambda^2 - (m k Rb^2 + J (k_y + k cos^2 a)) lambda + k_y k Rb^2 = 0.
  const double mass = 0.8, inertia = 3e-4, rb = 0.025, ky = 4e8, k = 2.5e8, a = 0.35;
  LinearModel model;
  model.dofs = {Dof::y1, Dof::theta1};
  model.mass = Eigen::MatrixXd::Zero(2, 2);
  model.mass(0, 0) = mass;
  model.mass(1, 1) = inertia;
  Eigen::VectorXd bearing(2), mesh(2);
  bearing << 1.0, 0.0;
  mesh << std::cos(a), rb;
  model.springs = {{SpringPart::bearing1, ky, bearing}, {SpringPart::mesh, k, mesh}};
  model.stiffness = ky * bearing * bearing.transpose() + k * mesh * mesh.transpose();
  model.rigid_modes = 0;
  const Modes modes = natural_modes(model);
  REQUIRE(modes.modes.size() == 2);
  const double b = mass * k * rb * rb + inertia * (ky + k * std::cos(a) * std::cos(a));
  const double root = std::sqrt(b * b - 4.0 * mass * inertia * ky * k * rb * rb);
  const double low = (b - root) / (2.0 * mass * inertia);
  const double high = (b + root) / (2.0 * mass * inertia);
  // The low root loses digits to cancellation in b - root: 1e-10 is its error with room.
  CHECK(relative(modes.modes[0].angular_frequency, std::sqrt(low)) < 1e-10);
  CHECK(relative(modes.modes[1].angular_frequency, std::sqrt(high)) < 1e-10);
  // The shape from the first row of (K - lambda M) v = 0: v = (1, r),
  // r = -(k_y + k cos^2 a - lambda m) / (k cos a Rb); its mesh share
  // k (cos a + Rb r)^2 / (k (cos a + Rb r)^2 + k_y).
  for (const double lambda : {low, high}) {
    const std::size_t i = lambda == low ? 0 : 1;
    const double r = -(ky + k * std::cos(a) * std::cos(a) - lambda * mass) / (k * std::cos(a) * rb);
    const double e_mesh = k * std::pow(std::cos(a) + rb * r, 2);
    CHECK(std::fabs(modes.modes[i].energy_share[0] - e_mesh / (e_mesh + ky)) < 1e-9);
    CHECK(std::fabs(modes.modes[i].shape(1) / modes.modes[i].shape(0) - r) < 1e-9 * std::fabs(r));
  }
}

TEST_CASE("shares in [0, 1] summing to 1, M-orthogonal shapes, K v = w^2 M v") {
  SimulationCase c = planar_case(5e8);
  c.bearings.gear1.stiffness_y_n_per_m = 8e8;
  c.bearings.gear2.mass_kg = 1.5;
  c.shafts.kind = ShaftKind::elastic;
  c.shafts.motor_inertia_kg_m2 = 2e-3;
  c.shafts.motor_stiffness_n_m_per_rad = 5e4;
  c.shafts.load_inertia_kg_m2 = 8e-3;
  c.shafts.load_stiffness_n_m_per_rad = 9e4;
  const Modes modes = natural_modes(c);
  REQUIRE(modes.modes.size() == 8);
  const LinearModel& m = modes.model;
  CHECK(m.parameters.mass_kg[1] == 1.5);
  // The disc's mass, rho pi r^2 L, when mass1 is absent.
  const double r1 = c.gears.module_m * c.gears.teeth1 / 2.0;
  CHECK(relative(m.parameters.mass_kg[0],
                 c.gears.density_kg_m3 * pi * r1 * r1 * c.gears.face_width_m) < 1e-15);
  Eigen::MatrixXd v(8, 8);
  for (std::size_t i = 0; i < 8; ++i) {
    const NaturalMode& mode = modes.modes[i];
    v.col(static_cast<Eigen::Index>(i)) = mode.shape;
    CHECK(mode.rigid == (i == 0));
    if (mode.rigid) continue;
    for (double s : mode.energy_share) {
      CHECK(s >= 0.0);
      CHECK(s <= 1.0);
    }
    CHECK(std::fabs(sum(mode.energy_share) - 1.0) < 1e-12);
    // The residual of the eigenpair, against the largest term: the solver's backward error.
    const Eigen::VectorXd residual = m.stiffness * mode.shape - mode.angular_frequency *
                                                                    mode.angular_frequency *
                                                                    m.mass * mode.shape;
    CHECK(residual.norm() <= 1e-12 * m.stiffness.norm() * mode.shape.norm());
    if (i > 1) CHECK(mode.frequency_hz >= modes.modes[i - 1].frequency_hz);
  }
  // V^T M V = I: the mass normalisation and the orthogonality, to the solver's rounding.
  const Eigen::MatrixXd gram = v.transpose() * m.mass * v;
  CHECK((gram - Eigen::MatrixXd::Identity(8, 8)).cwiseAbs().maxCoeff() < 1e-10);
  // The rigid mode turns the whole train: theta_motor = theta1, theta_load = theta2,
  // Rb1 theta1 = Rb2 theta2, centres still.
  const Eigen::VectorXd& rigid = modes.modes[0].shape;
  CHECK(std::fabs(rigid(6) - rigid(2)) < 1e-6 * std::fabs(rigid(2)));
  CHECK(std::fabs(m.parameters.base_radius1_m * rigid(2) - m.parameters.base_radius2_m * rigid(5)) <
        1e-6 * m.parameters.base_radius1_m * std::fabs(rigid(2)));
}

TEST_CASE("the mesh stiffness is the table's mean over a mesh period") {
  SimulationCase c = paper_case(1);
  c.bearings.kind = BearingKind::elastic;
  c.bearings.gear1.stiffness_x_n_per_m = 1e9;
  c.bearings.gear2.stiffness_x_n_per_m = 1e9;
  const Modes modes = natural_modes(c);
  const StiffnessTable table(c.gears, c.model.stiffness);
  CHECK(modes.model.parameters.mesh_stiffness_n_per_m == mean_mesh_stiffness_n_per_m(c, table));
}

TEST_CASE("Campbell crossings: k Z1 w1 = w of each elastic mode, up to the largest speed") {
  const Modes modes = natural_modes(planar_case(1e9));
  const std::vector<CampbellCrossing> all = campbell_crossings(modes, 20, 3, 1e9);
  CHECK(all.size() == 3 * 5);
  for (const CampbellCrossing& x : all) {
    const NaturalMode& m = modes.modes[x.mode];
    CHECK_FALSE(m.rigid);
    CHECK(relative(x.harmonic * 20.0 * x.pinion_speed_rad_per_s, m.angular_frequency) < 1e-15);
  }
  // Only the crossings below the speed.
  const double speed = all[2].pinion_speed_rad_per_s;
  for (const CampbellCrossing& x : campbell_crossings(modes, 20, 3, speed)) {
    CHECK(x.pinion_speed_rad_per_s <= speed);
  }
  CHECK_THROWS_AS(campbell_crossings(modes, 20, 0, speed), InputError);
  CHECK_THROWS_AS(campbell_crossings(modes, 20, 3, -1.0), InputError);
}

TEST_CASE("a planar case is valid; elastic shafts on rigid bearings are refused, naming the key") {
  // simulate, the sweeps and the period map run it (verify/dynamics/test_planar_dynamics.cpp,
  // verify/steady/test_sweep.cpp, verify/steady/test_gear_floquet.cpp).
  const SimulationCase planar = planar_case(1e9);
  CHECK_NOTHROW(validate(planar));
  // A planar mounting outside its rows is refused by validate, naming the field.
  SimulationCase massless = planar;
  massless.bearings.gear1.mass_kg = 0.0;
  CHECK_THROWS_AS(validate(massless), InputError);
  SimulationCase shafts = paper_case(1);
  shafts.bearings = planar.bearings;
  shafts.shafts.kind = ShaftKind::elastic;
  shafts.shafts.motor_inertia_kg_m2 = 1e-3;
  shafts.shafts.motor_stiffness_n_m_per_rad = 1e4;
  shafts.shafts.load_inertia_kg_m2 = 1e-3;
  shafts.shafts.load_stiffness_n_m_per_rad = 1e4;
  CHECK_NOTHROW(validate(shafts));
  // Elastic shafts on rigid bearings are not a model (refuse_planar_simulation).
  SimulationCase rigid_shafts = shafts;
  rigid_shafts.bearings.kind = BearingKind::rigid;
  try {
    validate(rigid_shafts);
    FAIL("validate passed elastic shafts on rigid bearings");
  } catch (const InputError& e) {
    CHECK(e.field() == "shafts.kind");
  }
}

TEST_CASE("bearing keys: read from a case file, each refused by its row") {
  const std::string pair =
      "[gears]\nteeth1 = 20\nteeth2 = 40\nmodule = \"3 mm\"\npressure_angle = \"20 deg\"\n"
      "face_width = \"10 mm\"\nyoungs_modulus = \"206 GPa\"\npoisson_ratio = 0.3\n"
      "density = \"7800 kg/m^3\"\nbacklash = \"0.05 mm\"\n";
  const SimulationCase c = parse_pair_or_run(pair +
                                                 "[bearings]\nkind = \"elastic\"\n"
                                                 "stiffness_x1 = \"500 N/um\"\n"
                                                 "stiffness_x2 = \"600 N/um\"\n"
                                                 "damping_y2 = \"200 N*s/m\"\nmass2 = \"2 kg\"\n",
                                             "pair.toml")
                               .simulation_case;
  CHECK(c.bearings.kind == BearingKind::elastic);
  CHECK(c.bearings.gear1.stiffness_x_n_per_m == 5e8);
  CHECK(stiffness_y(c.bearings.gear1) == 5e8);
  CHECK(damping_y(c.bearings.gear2) == 200.0);
  CHECK(c.bearings.gear2.mass_kg == 2.0);
  CHECK_FALSE(c.bearings.gear1.mass_kg.has_value());
  const auto refusal = [&](const std::string& bearings) {
    try {
      parse_pair_or_run(pair + bearings, "pair.toml");
    } catch (const CaseFileError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string zero = refusal(
      "[bearings]\nkind = \"elastic\"\nstiffness_x1 = \"0 N/m\"\nstiffness_x2 = \"1 N/m\"\n");
  CHECK(zero.find("bearings.stiffness_x1") != std::string::npos);
  CHECK(zero.find("[0.001, 1e16] N/m") != std::string::npos);
  const std::string missing = refusal("[bearings]\nkind = \"elastic\"\nstiffness_x1 = \"1 N/m\"\n");
  CHECK(missing.find("bearings.stiffness_x2") != std::string::npos);
  // A key of the planar model without kind = "elastic" is not read, so it is refused.
  const std::string unread = refusal("[bearings]\nstiffness_x1 = \"1 N/m\"\n");
  CHECK(unread.find("bearings.stiffness_x1") != std::string::npos);
  CHECK(unread.find("not used by kind = \"rigid\"") != std::string::npos);
}
