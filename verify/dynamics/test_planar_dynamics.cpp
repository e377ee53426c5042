// The planar nonlinear dynamics (docs/vibration.md, "The planar dynamics")
// against the limits of VIBRATION.md section 3, each reached by a route other
// than the code under test: momentum without bearings (sums written out
// here), the energy ledger closing at RK4's order, the torsional model
// approached as 1/k_bearing, rigid bearings running the torsional code, and the
// free vibration at the first elastic frequency of `modes`'s eigenproblem.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/modes/modes.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/terms.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

using namespace gearimpact;

namespace {

constexpr double kMesh = 2.0e8;  // N/m, the constant mesh stiffness of most cases here

// The paper's case 1 (no torques, w1 = 50 rad/s, the gears apart) on elastic
// bearings of stiffness kb in both directions, without friction, at a
// constant mesh stiffness (so that k is known exactly).
SimulationCase planar_case(double kb) {
  SimulationCase c = paper_case(1);
  c.model.friction_coefficient = 0.0;
  c.model.mesh_stiffness = MeshStiffnessMode::constant;
  c.model.constant_mesh_stiffness_n_per_m = kMesh;
  c.bearings.kind = BearingKind::elastic;
  c.bearings.gear1.stiffness_x_n_per_m = kb;
  c.bearings.gear2.stiffness_x_n_per_m = kb;
  return c;
}

// Loaded by F along the drive line (T1 = F Rb1, T2 = -F Rb2), without
// Hertzian damping, started at the torsional static deflection B + F/k.
SimulationCase loaded_case(double kb, double force_n) {
  SimulationCase c = planar_case(kb);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  c.model.damping_update = DampingUpdate::off;
  c.torque1.constant_n_m = force_n * rb1;
  c.torque2.constant_n_m = -force_n * rb2;
  c.initial =
      InitialState{(c.gears.backlash_m + force_n / kMesh) / rb1, 0.0, 50.0, 50.0 * rb1 / rb2};
  return c;
}

double largest(const std::array<double, 2>& v) {
  return std::max(std::fabs(v[0]), std::fabs(v[1]));
}

}  // namespace

TEST_CASE("without bearings and torques the momenta are conserved") {
  // Free centres (k = 0): only the mesh acts, its forces equal and opposite.
  // Linear momentum is a linear invariant, which RK4 keeps to round-off. The
  // angular momentum about O1 changes by (u1 - u2) x F (the lines of action
  // keep their nominal place, docs/vibration.md); after a drive-side impact
  // without friction, starting from rest in translation, u1 - u2 and F are
  // both along n1, so it is conserved too, its quadratic terms being
  // products of parallel vectors.
  SimulationCase c = planar_case(1e9);
  // Long enough for the drive-side impact and the flight after it, before
  // the coast flanks meet.
  c.integrator.end_time_s = 2.5e-4;
  PlanarMounting m = planar_mounting(c);
  m.stiffness_x_n_per_m = {0.0, 0.0};
  m.stiffness_y_n_per_m = {0.0, 0.0};
  const PlanarState start = planar_initial_state(c);
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SimulationResult r = simulate_planar(c, table, m, start, RunControl{});
  REQUIRE(r.summary.impacts_n1 >= 1);
  REQUIRE(r.summary.impacts_n2 == 0);
  // The scale of the momenta exchanged: the pinion's initial J1 w1 and the
  // mesh impulse it passes, over Rb1.
  const double j1w1 = moment_of_inertia(c.gears, Gear::one) * start.w1_rad_per_s;
  const double impulse = j1w1 / base_radius(c.gears, Gear::one);
  const double l0 = planar_angular_momentum(c, m, start);
  double most_p = 0.0;
  double most_l = 0.0;
  double most_u = 0.0;
  for (const PlanarRow& row : r.planar_series) {
    most_p = std::max(most_p, largest(planar_linear_momentum(m, row.state)));
    most_l = std::max(most_l, std::fabs(planar_angular_momentum(c, m, row.state) - l0));
    most_u = std::max(most_u, std::fabs(row.state.x1_m));
  }
  MESSAGE("linear momentum " << most_p / impulse << ", angular " << most_l / j1w1
                             << " of their scales");
  // The centres did move (else the test shows nothing).
  CHECK(most_u > 1e-9);
  // Round-off of 2500 steps of sums of order 1: a few 1e-16 of the scale per step.
  CHECK(most_p < 1e-11 * impulse);
  CHECK(most_l < 1e-11 * j1w1);

  SUBCASE("with friction the linear momentum still is") {
    c.model.friction_coefficient = 0.1;
    const SimulationResult f = simulate_planar(c, table, m, start, RunControl{});
    double most = 0.0;
    for (const PlanarRow& row : f.planar_series) {
      most = std::max(most, largest(planar_linear_momentum(m, row.state)));
    }
    CHECK(f.summary.friction_loss_j > 0.0);
    CHECK(most < 1e-11 * impulse);
  }
}

TEST_CASE("without damping and friction the ledger closes at RK4's order") {
  // Torques, bearings, impacts on the drive side: every energy is counted
  // (kinetic of x, y, theta; mesh, bearings). Each side's onset and end is
  // located, so that no step integrates the force's kink there; with a
  // constant mesh stiffness and no friction nothing else jumps, and the
  // residual falls at RK4's order: at least eightfold (order >= 3) when the
  // step halves (measured 32), and at 2e-7 s it is 1e-9 of the energies.
  SimulationCase c = planar_case(5e8);
  c.model.damping_update = DampingUpdate::off;
  c.torque1.constant_n_m = 2.0;
  c.torque2.constant_n_m = -2.0 * base_radius(c.gears, Gear::two) / base_radius(c.gears, Gear::one);
  c.integrator.end_time_s = 4e-3;
  c.integrator.step_s = 4e-7;
  c.integrator.output_every = 100;
  const SimulationResult coarse = simulate(c);
  c.integrator.step_s = 2e-7;
  c.integrator.output_every = 200;
  const SimulationResult fine = simulate(c);
  REQUIRE(fine.summary.planar);
  CHECK(fine.summary.planar->bearing_energy_final_j > 0.0);
  CHECK(fine.summary.impacts_n1 >= 1);
  CHECK(fine.summary.damping_loss_j == 0.0);
  // The mesh's largest stored energy (a constant stiffness: all of it Hertz's
  // term) is at most the energy the run holds.
  const double hertz = fine.summary.energy_max_j[index_of(Term::hertz)];
  CHECK(hertz > 0.0);
  CHECK(hertz <= fine.summary.ledger_scale_j);
  // Without shafts the motor and the load columns are the gears' own.
  const PlanarState& last = fine.planar_series.back().state;
  CHECK(last.theta_motor_rad == last.theta1_rad);
  CHECK(last.w_load_rad_per_s == last.w2_rad_per_s);
  CHECK(last.w1_rad_per_s != 0.0);
  MESSAGE("ledger residual " << coarse.summary.ledger_residual_max_j << " J, "
                             << fine.summary.ledger_residual_max_j << " J of "
                             << fine.summary.ledger_scale_j << " J");
  CHECK(fine.summary.ledger_residual_max_j < 1e-8 * fine.summary.ledger_scale_j);
  CHECK(coarse.summary.ledger_residual_max_j > 8.0 * fine.summary.ledger_residual_max_j);
  CHECK(fine.summary.events >= fine.summary.impacts_n1 + fine.summary.impacts_n2);
}

TEST_CASE("with damping the ledger books the bearings' loss") {
  SimulationCase c = planar_case(5e8);
  c.bearings.gear1.damping_x_n_s_per_m = 2e3;
  c.bearings.gear2.damping_x_n_s_per_m = 2e3;
  c.integrator.end_time_s = 4e-3;
  c.integrator.output_every = 1000;
  const SimulationResult r = simulate(c);
  REQUIRE(r.summary.planar);
  CHECK(r.summary.planar->bearing_damping_loss_j > 0.0);
  CHECK(r.summary.damping_loss_j > 0.0);
  // The losses are of the scale of the energies, the residual far below.
  CHECK(r.summary.planar->bearing_damping_loss_j > 1e-3 * r.summary.ledger_scale_j);
  CHECK(r.summary.ledger_residual_max_j < 1e-8 * r.summary.ledger_scale_j);
}

TEST_CASE("rigid bearings run the torsional model bit for bit") {
  // kind = "rigid" with bearing values set (which rigid bearings do not read)
  // against the case without [bearings].
  SimulationCase plain = paper_case(1);
  plain.integrator.end_time_s = 5e-3;
  SimulationCase rigid = plain;
  rigid.bearings.kind = BearingKind::rigid;
  rigid.bearings.gear1.stiffness_x_n_per_m = 1e9;
  rigid.bearings.gear2.damping_x_n_s_per_m = 1e3;
  const SimulationResult a = simulate(plain);
  const SimulationResult b = simulate(rigid);
  REQUIRE(a.series.size() == b.series.size());
  CHECK(b.planar_series.empty());
  CHECK_FALSE(b.summary.planar);
  bool same = true;
  for (std::size_t i = 0; i < a.series.size(); ++i) {
    same = same && a.series[i].theta1_rad == b.series[i].theta1_rad &&
           a.series[i].theta2_rad == b.series[i].theta2_rad &&
           a.series[i].w1_rad_per_s == b.series[i].w1_rad_per_s &&
           a.series[i].w2_rad_per_s == b.series[i].w2_rad_per_s &&
           a.series[i].normal_force_n == b.series[i].normal_force_n;
  }
  CHECK(same);
  CHECK(a.summary.ledger_residual_max_j == b.summary.ledger_residual_max_j);
}

TEST_CASE("stiff bearings approach the torsional model as 1/k_bearing") {
  // Loaded, in contact throughout, no friction and no damping: both models
  // are smooth, so the integration error (RK4 at 1e-8 s, w h <= 0.1 on the
  // stiffest bearing) is far below the difference. The planar model starts
  // off its own equilibrium by the bearings' compliance, so its theta2
  // oscillates about the torsional one with an amplitude ~ F/k_b; the
  // largest difference over the run falls tenfold per tenfold stiffer
  // bearing. Its mesh mode is slower by O(k_mesh/k_b), a phase drift of
  // w_m T k_mesh/k_b (w_m T ~ 12, k_mesh/k_b <= 1e-3 here): 1/k within 5 %.
  constexpr double force = 400.0;  // N
  SimulationCase torsional = loaded_case(1e9, force);
  torsional.bearings.kind = BearingKind::rigid;
  torsional.integrator.end_time_s = 5e-4;
  torsional.integrator.step_s = 1e-8;
  torsional.integrator.output_every = 10;
  const SimulationResult t = simulate(torsional);
  std::vector<double> differences;
  for (const double kb : {2e11, 2e12, 2e13}) {
    SimulationCase planar = loaded_case(kb, force);
    planar.integrator = torsional.integrator;
    const SimulationResult p = simulate(planar);
    REQUIRE(p.summary.impacts_n1 == 1);  // the contact it starts in, never left
    REQUIRE(p.series.size() == t.series.size());
    double most = 0.0;
    for (std::size_t i = 0; i < t.series.size(); ++i) {
      most = std::max(most, std::fabs(p.series[i].theta2_rad - t.series[i].theta2_rad));
    }
    differences.push_back(most);
  }
  MESSAGE("largest theta2 differences " << differences[0] << ", " << differences[1] << ", "
                                        << differences[2] << " rad");
  CHECK(differences[2] > 0.0);
  CHECK(std::fabs(differences[0] / differences[1] - 10.0) < 0.5);
  CHECK(std::fabs(differences[1] / differences[2] - 10.0) < 0.5);
}

namespace {

// The angular frequency at which a small free vibration of the loaded case c
// (bearings kb, mesh force F) oscillates, and the first elastic one of
// `modes`. At the static equilibrium (written out: each bearing carries the
// mesh force F n1, the mesh deflects by F/k, each shaft twists by its torque
// over k_t), the motion started with a velocity along the first elastic mode
// shape stays in that mode: with a constant mesh stiffness, drive-side
// contact throughout and no friction the planar equations are linear there.
std::pair<double, double> free_vibration(const SimulationCase& c, double kb, double force) {
  const Modes modes = natural_modes(linear_model(linear_parameters(c, kMesh)));
  const NaturalMode& first = modes.modes[modes.model.rigid_modes];
  const double a = operating_pressure_angle(c.gears);
  const double rb1 = base_radius(c.gears, Gear::one);
  PlanarState s;
  s.x1_m = -force * std::sin(a) / kb;
  s.y1_m = -force * std::cos(a) / kb;
  s.x2_m = -s.x1_m;
  s.y2_m = -s.y1_m;
  // s_d = B + F/k with (u1 - u2) . n1 = -2F/kb.
  s.theta1_rad = (c.gears.backlash_m + force / kMesh + 2.0 * force / kb) / rb1;
  const bool shafts = c.shafts.kind == ShaftKind::elastic;
  if (shafts) {
    s.theta_motor_rad =
        s.theta1_rad + c.torque1.constant_n_m / c.shafts.motor_stiffness_n_m_per_rad;
    s.theta_load_rad = s.theta2_rad + c.torque2.constant_n_m / c.shafts.load_stiffness_n_m_per_rad;
  }
  // Velocities along the shape (x1, y1, theta1, x2, y2, theta2[, motor, load]),
  // 1e-4 in SI at most.
  const Eigen::VectorXd v = 1e-4 / first.shape.cwiseAbs().maxCoeff() * first.shape;
  s.vx1_m_s = v(0);
  s.vy1_m_s = v(1);
  s.w1_rad_per_s = v(2);
  s.vx2_m_s = v(3);
  s.vy2_m_s = v(4);
  s.w2_rad_per_s = v(5);
  if (shafts) {
    s.w_motor_rad_per_s = v(6);
    s.w_load_rad_per_s = v(7);
  }
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SimulationResult r = simulate_planar(c, table, planar_mounting(c), s, RunControl{});
  // The modal coordinate's velocity v^T M q', which oscillates as cos(w t):
  // its zero crossings are half periods apart.
  const Eigen::VectorXd mv = modes.model.mass * first.shape;
  std::vector<double> crossings;
  double previous = 0.0;
  for (std::size_t i = 0; i < r.planar_series.size(); ++i) {
    const PlanarState& q = r.planar_series[i].state;
    double eta = mv(0) * q.vx1_m_s + mv(1) * q.vy1_m_s + mv(2) * q.w1_rad_per_s +
                 mv(3) * q.vx2_m_s + mv(4) * q.vy2_m_s + mv(5) * q.w2_rad_per_s;
    if (shafts) eta += mv(6) * q.w_motor_rad_per_s + mv(7) * q.w_load_rad_per_s;
    if (i > 0 && previous * eta < 0.0) {
      // Linear interpolation between rows.
      const double t0 = r.planar_series[i - 1].t_s;
      const double t1 = r.planar_series[i].t_s;
      crossings.push_back(t0 + (t1 - t0) * previous / (previous - eta));
    }
    previous = eta;
  }
  REQUIRE(crossings.size() >= 4);
  const double half_period =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  MESSAGE("first elastic mode " << first.frequency_hz << " Hz, measured " << 0.5 / half_period
                                << " Hz over " << crossings.size() << " crossings");
  return {pi / half_period, first.angular_frequency};
}

}  // namespace

TEST_CASE("a small free vibration has the first elastic frequency of modes") {
  constexpr double kb = 1e9;
  constexpr double force = 400.0;
  SimulationCase c = loaded_case(kb, force);
  c.integrator.step_s = 5e-8;
  c.integrator.end_time_s = 4e-3;
  // The interpolation's error at each crossing is (w h)^2 / 8 of a step at
  // most; over the crossings' span it is far below 1e-5.
  const auto [measured, expected] = free_vibration(c, kb, force);
  CHECK(std::fabs(measured - expected) < 1e-5 * expected);

  SUBCASE("with a motor and a load on shafts (8 DOF)") {
    c.shafts.kind = ShaftKind::elastic;
    c.shafts.motor_inertia_kg_m2 = 2e-4;
    c.shafts.motor_stiffness_n_m_per_rad = 2e3;
    c.shafts.load_inertia_kg_m2 = 8e-4;
    c.shafts.load_stiffness_n_m_per_rad = 5e3;
    // A slower first mode (the shafts'): a longer run for as many crossings,
    // every tenth step kept (w h ~ 2e-3 between rows).
    c.integrator.end_time_s = 1e-2;
    c.integrator.output_every = 10;
    const auto [shaft_measured, shaft_expected] = free_vibration(c, kb, force);
    CHECK(shaft_expected < 0.5 * expected);
    CHECK(std::fabs(shaft_measured - shaft_expected) < 1e-5 * shaft_expected);
  }
}

TEST_CASE("a fault acts on the planar model as on the torsional one") {
  // A missing pinion tooth early in the run, the time-varying stiffness
  // of the paper's model, loaded: on bearings of 2e13 N/m the planar run
  // follows the faulted torsional run, far closer than the healthy torsional
  // run does (measured 5e-9 against 3e-6 rad): the planar mesh reads the
  // teeth's tables, a missing tooth's pair carrying nothing.
  constexpr double force = 400.0;
  SimulationCase faulted = loaded_case(2e13, force);
  faulted.model.mesh_stiffness = MeshStiffnessMode::time_varying;
  ToothFault missing;
  missing.gear = Gear::one;
  missing.tooth = 1;
  missing.state.kind = ToothKind::missing;
  faulted.faults.push_back(missing);
  faulted.integrator.end_time_s = 4e-3;
  faulted.integrator.step_s = 1e-8;
  faulted.integrator.output_every = 100;
  SimulationCase torsional = faulted;
  torsional.bearings.kind = BearingKind::rigid;
  SimulationCase healthy = torsional;
  healthy.faults.clear();
  const SimulationResult p = simulate(faulted);
  const SimulationResult t = simulate(torsional);
  const SimulationResult h = simulate(healthy);
  REQUIRE(p.series.size() == t.series.size());
  REQUIRE(h.series.size() == t.series.size());
  double planar_to_faulted = 0.0;
  double healthy_to_faulted = 0.0;
  for (std::size_t i = 0; i < t.series.size(); ++i) {
    planar_to_faulted =
        std::max(planar_to_faulted, std::fabs(p.series[i].theta2_rad - t.series[i].theta2_rad));
    healthy_to_faulted =
        std::max(healthy_to_faulted, std::fabs(h.series[i].theta2_rad - t.series[i].theta2_rad));
  }
  MESSAGE("largest theta2 difference: planar to faulted "
          << planar_to_faulted << " rad, healthy to faulted " << healthy_to_faulted << " rad");
  CHECK(healthy_to_faulted > 0.0);
  CHECK(planar_to_faulted < 1e-2 * healthy_to_faulted);
}

TEST_CASE("the ledger's largest energy of each term is that of the steps' states") {
  // A pair carrying F stores F^2 c / 2 in a term of compliance c, F = delta /
  // c_total: written out here from each step's row (the
  // loaded pairs at theta1, the table's compliances there), against the
  // summary's maxima. The run passes from two pairs to one and back, where
  // the terms share the load differently; the ledger skips the terms at a step
  // that cannot raise a maximum, and must not miss one that does.
  SimulationCase c = loaded_case(1e9, 400.0);
  c.model.mesh_stiffness = MeshStiffnessMode::time_varying;
  c.integrator.end_time_s = 4e-3;
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SimulationResult r = simulate(c, table);
  std::array<double, kTermCount> most{};
  std::array<bool, 2> pair_counts{};  // one pair, two pairs seen
  // From the first step's end: the initial state is no step's.
  for (std::size_t row = 1; row < r.planar_series.size(); ++row) {
    const PlanarRow& p = r.planar_series[row];
    std::array<double, kTermCount> u{};
    for (const auto line : {Region::n1, Region::n2}) {
      const double delta = line == Region::n1 ? p.drive_penetration_m : p.coast_penetration_m;
      if (delta <= 0.0) continue;
      const LoadedPairs pairs =
          loaded_pairs(c.gears, line, p.state.theta1_rad, c.model.coast_phase);
      if (line == Region::n1) pair_counts[std::min<std::size_t>(pairs.count, 2) - 1] = true;
      for (std::size_t k = 0; k < pairs.count; ++k) {
        const Compliances at = table.compliance(pairs.position_m[k]);
        const double force = delta / at.total_m_per_n();
        for (std::size_t i = 0; i < kTermCount; ++i) {
          u[i] += 0.5 * force * force * at.m_per_n[i];
        }
      }
    }
    for (std::size_t i = 0; i < kTermCount; ++i) most[i] = std::max(most[i], u[i]);
  }
  CHECK(pair_counts[0]);
  CHECK(pair_counts[1]);
  // The paper's model has no shear or foundation term: those store nothing.
  CHECK(most[index_of(Term::hertz)] > 0.0);
  CHECK(most[index_of(Term::bending)] > 0.0);
  for (std::size_t i = 0; i < kTermCount; ++i) {
    INFO(std::string(kTerms[i].id));
    const double reported = r.summary.energy_max_j[i];
    // The same products summed in another order: a few rounding errors.
    CHECK(std::fabs(reported - most[i]) <= 1e-12 * most[i]);
  }
}

TEST_CASE("what the planar model does not take is refused by its key") {
  const auto field_of = [](const SimulationCase& c) {
    try {
      simulate(c);
    } catch (const InputError& e) {
      return std::string(e.field());
    }
    return std::string("none");
  };
  SimulationCase c = planar_case(1e9);
  c.integrator.end_time_s = 1e-5;
  SimulationCase driven = c;
  driven.torque1.kind = Torque::Kind::prescribed_speed;
  driven.torque1.mean_speed_rad_per_s = 50.0;
  CHECK(field_of(driven) == "torque1.kind");
  SimulationCase adaptive = c;
  adaptive.integrator.kind = IntegratorKind::adaptive;
  CHECK(field_of(adaptive) == "integrator.kind");
  SimulationCase coarse = c;
  coarse.integrator.step_s = 1e-5;
  coarse.integrator.end_time_s = 1e-3;
  CHECK(field_of(coarse) == "integrator.step");
  SimulationCase shafts_only = paper_case(1);
  shafts_only.shafts.kind = ShaftKind::elastic;
  shafts_only.shafts.motor_inertia_kg_m2 = 1e-3;
  shafts_only.shafts.motor_stiffness_n_m_per_rad = 1e4;
  shafts_only.shafts.load_inertia_kg_m2 = 1e-3;
  shafts_only.shafts.load_stiffness_n_m_per_rad = 1e4;
  CHECK(field_of(shafts_only) == "shafts.kind");
  const StiffnessTable table(c.gears, c.model.stiffness);
  PlanarMounting m = planar_mounting(c);
  m.stiffness_y_n_per_m[1] = -1.0;
  CHECK_THROWS_WITH_AS(simulate_planar(c, table, m, planar_initial_state(c)),
                       doctest::Contains("stiffness_y2"), InputError);
}
