// The dynamics with the gaps of tooth modifications and errors (docs/faults.md,
// "Modifications and errors"): each pair touches by its own penetration
// delta - e_k, so that a slow loaded run follows the static transmission
// error, a relieved pair enters where the load closes its gap, the ledger
// closes, and under the Lagrangian mesh force a relieved pair enters and
// leaves without a jump of the stored energy.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

RunControl summary_only() {
  RunControl control;
  control.keep_series = false;
  return control;
}

// Both tips relieved linearly by `amount` from the start diameters of
// examples/tip_relief_20_80.toml (about 1 mm of roll length on each gear).
Modifications tip_relief(double amount_m) {
  Modifications m;
  m.gear1.tip = {amount_m, 43.2e-3, ReliefShape::linear};
  m.gear2.tip = {amount_m, 163.2e-3, ReliefShape::linear};
  return m;
}

// Case 2's pair under a constant, balanced torque T1, rolling at w1, without
// friction and Hertzian damping, with the viscous mesh damper at `zeta` to
// settle what the start leaves, pressed into N1 at theta1 = 0 by `delta0`.
SimulationCase loaded(double torque1_n_m, double w1, double zeta, double delta0_m) {
  SimulationCase c = paper_case(2);
  c.name = "loaded";
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  c.model.friction_coefficient = 0.0;
  c.model.damping_update = DampingUpdate::off;
  c.model.mesh_damping_ratio = zeta;
  c.torque1 = Torque{};
  c.torque1.constant_n_m = torque1_n_m;
  c.torque2 = Torque{};
  c.torque2.constant_n_m = -torque1_n_m * rb2 / rb1;
  c.initial.theta1_rad = 0.0;
  c.initial.theta2_rad = -(c.gears.backlash_m + delta0_m) / rb2;
  c.initial.w1_rad_per_s = w1;
  c.initial.w2_rad_per_s = w1 * rb1 / rb2;
  c.integrator.step_s = 0.5e-6;
  return c;
}

double mesh_period_s(const SimulationCase& c) {
  return 2.0 * pi / (c.gears.teeth1 * c.initial.w1_rad_per_s);
}

// s at theta1 from the series, linear between the rows about it (rows 0.5 us
// apart, where s changes by nanometres over a mesh period: the interpolation
// error is far below the tolerances).
struct Interpolated {
  double s_m;
  double normal_force_n;
};
Interpolated at_angle(const std::vector<SeriesRow>& rows, double theta1) {
  const auto after =
      std::lower_bound(rows.begin(), rows.end(), theta1,
                       [](const SeriesRow& r, double value) { return r.theta1_rad < value; });
  REQUIRE(after != rows.begin());
  REQUIRE(after != rows.end());
  const SeriesRow& b = *after;
  const SeriesRow& a = *(after - 1);
  const double u = (theta1 - a.theta1_rad) / (b.theta1_rad - a.theta1_rad);
  return {a.s_m + u * (b.s_m - a.s_m),
          a.normal_force_n + u * (b.normal_force_n - a.normal_force_n)};
}

}  // namespace

TEST_CASE("gaps that cancel run as the unmodified pair") {
  // Pinion teeth 2 um thinner, wheel teeth 2 um thicker: every gap is
  // +2 um - 2 um = 0 exactly, on both lines, yet the run takes the path of a
  // modified case (each pair's own penetration, its touching events). The
  // motion is the same; the events are located by other event functions
  // with the same zeros, so the two runs agree to the rounding of the event
  // times (1e-12 of each quantity, far below any physical difference).
  for (int n = 1; n <= 3; ++n) {
    CAPTURE(n);
    SimulationCase plain = paper_case(n);
    plain.integrator.end_time_s = 0.01;
    SimulationCase cancelling = plain;
    cancelling.modifications.gear1.thickness_m.assign(20, 2e-6);
    cancelling.modifications.gear2.thickness_m.assign(80, -2e-6);
    const SimulationSummary a = simulate(plain, summary_only()).summary;
    const SimulationSummary b = simulate(cancelling, summary_only()).summary;
    CHECK(a.impacts_n1 == b.impacts_n1);
    CHECK(a.impacts_n2 == b.impacts_n2);
    CHECK(relative_difference(a.final_w1_rad_per_s, b.final_w1_rad_per_s) < 1e-12);
    CHECK(relative_difference(a.final_w2_rad_per_s, b.final_w2_rad_per_s) < 1e-12);
    CHECK(relative_difference(a.damping_loss_j, b.damping_loss_j) < 1e-10);
    CHECK(relative_difference(a.friction_loss_j, b.friction_loss_j) < 1e-10);
  }
}

TEST_CASE("a slow loaded run with relief follows the static transmission error") {
  // Quasi-static limit. At w1 = 5 rad/s the mesh frequency z1 w1 = 100 rad/s
  // is ~760 times below the contact's natural frequency (~7.6e4 rad/s), so
  // inertia changes the deflection by ~(1/760)^2 of its variation; the mesh
  // damper (zeta = 0.1, c ~ 800 N s/m) adds c ds/dt ~ 0.2 N against F ~ 2700 N
  // (ds/dt ~ dSTE/dX Rb1 w1 ~ 3e-4 m/s): ~1e-4 of F. The run starts at the
  // static deflection and rolling, and the little it leaves decays as
  // exp(-zeta w_n t), below 1e-9 after 3 ms, before the first angle compared.
  // Tolerance 1e-3 (of the STE, of F for the forces, absolute on the
  // shares): ten times the damper's part. If the dynamics loaded every pair
  // by the line's deflection, the force in a two-pair zone would be off by
  // the entering pair's k (delta - 0) instead of k (delta - e): tens of %.
  constexpr double torque = 50.0;
  const SimulationCase base = loaded(torque, 5.0, 0.1, 0.0);
  const StiffnessTable table(base.gears, base.model.stiffness);
  const Modifications m = tip_relief(10e-6);
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 40;
  const StaticTransmissionError ste =
      static_transmission_error(base.gears, m, torque, table, options);
  REQUIRE(ste.mesh_periods == 1);
  SimulationCase c = loaded(torque, 5.0, 0.1, ste.points[0].ste_m);
  c.modifications = m;
  c.integrator.end_time_s = 1.05 * mesh_period_s(c);
  const SimulationResult r = simulate(c, table);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double force = torque / rb1;
  int compared = 0;
  int two_pair_with_open_gap = 0;
  for (const StePoint& p : ste.points) {
    // After the start's transient (3 ms: 0.015 rad).
    if (p.theta1_rad < 0.015) continue;
    CAPTURE(p.theta1_rad);
    const Interpolated run = at_angle(r.series, p.theta1_rad);
    const double delta = run.s_m - c.gears.backlash_m;
    CHECK(std::fabs(delta - p.ste_m) < 1e-3 * p.ste_m);
    CHECK(relative_difference(run.normal_force_n, force) < 1e-3);
    for (std::size_t j = 0; j < p.pairs; ++j) {
      const double share = p.stiffness_n_per_m[j] * std::max(0.0, delta - p.gap_m[j]) / force;
      CHECK(std::fabs(share - p.share[j]) < 1e-3);
    }
    if (p.pairs == 2 && std::min(p.share[0], p.share[1]) == 0.0) ++two_pair_with_open_gap;
    ++compared;
  }
  CHECK(compared >= 30);
  // The comparison covers angles where a pair inside the segment does not yet
  // (or no longer) touch: the relief's late entry and early exit.
  CHECK(two_pair_with_open_gap >= 2);
}

TEST_CASE("a relieved pair starts carrying load where the load closes its gap") {
  // Wheel tip relief only, linear: on N1 a pair enters the segment at the
  // wheel's tip, X_start, where its gap is C; it touches once the deflection
  // delta reaches e(X) = C (s - s_r) / (s_a - s_r), s = lp - X the wheel's
  // roll distance. Before that the pair one base pitch ahead carries F
  // alone, delta = F / Ke(X + t0). The closed form of the entry X* solves
  // F / Ke(X* + t0) = e(X*) (a fixed point: Ke varies by ~1e-3 over the
  // shift). The run's delta differs from F / Ke by the mesh damper's force,
  // ~1e-4 of F (previous test), which moves X* by 1e-4 delta (s_a - s_r) / C:
  // tolerance 1e-3 delta (s_a - s_r) / C.
  constexpr double torque = 50.0;
  constexpr double amount = 10e-6;
  SimulationCase c = loaded(torque, 5.0, 0.1, 0.0);
  c.modifications.gear2.tip = {amount, 163.2e-3, ReliefShape::linear};
  const StiffnessTable table(c.gears, c.model.stiffness);
  const StaticTransmissionError ste =
      static_transmission_error(c.gears, c.modifications, torque, table, {40, 0});
  c.initial.theta2_rad =
      -(c.gears.backlash_m + ste.points[0].ste_m) / base_radius(c.gears, Gear::two);
  c.integrator.end_time_s = 1.05 * mesh_period_s(c);
  const SimulationResult r = simulate(c, table);
  const GearSystem system(c, table, summary_only());
  const MeshLayout layout(c.gears, c.model.coast_phase);
  // The closed form.
  const double lp = line_of_action_length(c.gears);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double s_a = std::sqrt(std::pow(tip_radius(c.gears, Gear::two), 2) - rb2 * rb2);
  const double s_r = std::sqrt(std::pow(0.5 * 163.2e-3, 2) - rb2 * rb2);
  const double force = torque / base_radius(c.gears, Gear::one);
  const double t0 = layout.base_pitch_m();
  double x_star = layout.start_m();
  double delta_star = 0.0;
  for (int i = 0; i < 50; ++i) {
    delta_star = force / table.stiffness(x_star + t0);
    x_star = lp - s_r - (s_a - s_r) * delta_star / amount;
  }
  REQUIRE(x_star > layout.start_m());
  // The run's entry: the first row at which the newest pair of a two-pair
  // mode touches, after rows in which it did not.
  double previous_x = 0.0;
  bool waiting = false;
  std::vector<double> entries;
  for (const SeriesRow& row : r.series) {
    const State y{row.theta1_rad, row.theta2_rad, row.w1_rad_per_s, row.w2_rad_per_s};
    const Mode mode = system.classify_geometry(y);
    if (mode.region != Region::n1 || mode.count != 2) {
      waiting = false;
      continue;
    }
    const double x = system.pair_position(mode, y, 0);
    if (!mode.touching[0]) {
      waiting = true;
    } else if (waiting) {
      entries.push_back(0.5 * (x + previous_x));
      waiting = false;
    }
    previous_x = x;
  }
  REQUIRE(entries.size() == 1);
  const double tolerance = 1e-3 * delta_star * (s_a - s_r) / amount;
  MESSAGE("entry at X = " << entries[0] << " m, closed form " << x_star << " m, start "
                          << layout.start_m() << " m, tolerance " << tolerance << " m");
  CHECK(std::fabs(entries[0] - x_star) < tolerance);
}

TEST_CASE("the energy ledger closes with relief and with tooth errors") {
  // The bound of the ledger suite (test_faults_dynamics): 1e-7 of the energy
  // that passes through the run. The gaps add the work of the gap moving
  // with the pinion, -N de_k/dX dX/dt, which the ledger books as parametric
  // work; a term left out would show as a residual of that size (the
  // relief's slope 1e-2 times the load's work over the relieved length).
  for (const MeshForce form : {MeshForce::newtonian, MeshForce::lagrangian}) {
    for (int n = 1; n <= 3; ++n) {
      CAPTURE(n);
      CAPTURE(form == MeshForce::lagrangian);
      SimulationCase c = paper_case(n);
      c.integrator.end_time_s = 0.01;
      c.model.mesh_force = form;
      c.modifications = tip_relief(0.2e-6);
      c.modifications.gear2.root = {0.1e-6, 158.5e-3, ReliefShape::parabolic};
      c.modifications.gear1.pitch_m.assign(20, 0.0);
      c.modifications.gear1.pitch_m[0] = 0.05e-6;
      c.modifications.gear2.profile_slope_m.assign(80, 0.0);
      c.modifications.gear2.profile_slope_m[1] = 0.1e-6;
      const SimulationSummary s = simulate(c, summary_only()).summary;
      const double throughput =
          s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
      MESSAGE("case " << n << ": residual " << s.ledger_residual_max_j << " J of " << throughput
                      << " J, parametric " << s.parametric_work_j << " J, impacts " << s.impacts_n1
                      << "/" << s.impacts_n2);
      CHECK(s.ledger_residual_max_j < 1e-7 * throughput);
      SimulationCase plain = c;
      plain.modifications = {};
      CHECK(simulate(plain, summary_only()).summary.final_w2_rad_per_s != s.final_w2_rad_per_s);
    }
  }
}

TEST_CASE("Lagrangian: with enough tip relief a pair enters and leaves without a jump") {
  // V = sum 1/2 Ke delta_k^2 jumps where a pair enters or leaves under load.
  // Tip relief on both gears larger than the deflection leaves the entering
  // pair (at the wheel's tip) and the leaving one (at the pinion's tip) with
  // a negative penetration: it carries nothing and stores nothing there, so
  // the stored energy does not jump; the pair takes its load where its
  // penetration passes 0, continuously. The unmodified pair pays a jump at
  // every entry and exit, ~ F^2 / (2 k) each.
  constexpr double torque = 20.0;
  const SimulationCase base = loaded(torque, 200.0, 0.1, 0.0);
  const StiffnessTable table(base.gears, base.model.stiffness);
  const auto run = [&](const Modifications& m) {
    const StaticTransmissionError ste =
        static_transmission_error(base.gears, m, torque, table, {40, 0});
    SimulationCase c = loaded(torque, 200.0, 0.1, ste.points[0].ste_m);
    c.modifications = m;
    c.model.mesh_force = MeshForce::lagrangian;
    c.integrator.end_time_s = 3.0 * mesh_period_s(c);
    return simulate(c, table, summary_only()).summary;
  };
  const SimulationSummary plain = run({});
  const SimulationSummary relieved = run(tip_relief(10e-6));
  REQUIRE(plain.stored_energy_jumps_j);
  REQUIRE(relieved.stored_energy_jumps_j);
  // The unmodified pair's jumps by hand: a pair enters at X_start with the
  // deflection the pair ahead held alone, delta = F / Ke(X_start + t0), and
  // adds 1/2 Ke(X_start) delta^2; one leaves at X_end with the deflection of
  // the two, F / (Ke(X_end) + Ke(X_end - t0)), and takes 1/2 Ke(X_end) delta^2
  // with it. Three of each in three mesh periods. The motion at w1 = 200 rad/s
  // (mesh frequency 4000 rad/s, ~1/19 of the contact's) moves the deflection
  // by a few % from the static one: tolerance 10 %.
  const double force = torque / base_radius(base.gears, Gear::one);
  const MeshLayout layout(base.gears, base.model.coast_phase);
  const double xs = layout.start_m();
  const double xe = layout.end_m();
  const double t0 = layout.base_pitch_m();
  const double entering = force / table.stiffness(xs + t0);
  const double leaving = force / (table.stiffness(xe) + table.stiffness(xe - t0));
  const double by_hand =
      3.0 * 0.5 *
      (table.stiffness(xs) * entering * entering + table.stiffness(xe) * leaving * leaving);
  MESSAGE("jumps: unmodified " << *plain.stored_energy_jumps_j << " J (by hand " << by_hand
                               << " J), relieved " << *relieved.stored_energy_jumps_j << " J");
  CHECK(relative_difference(*plain.stored_energy_jumps_j, by_hand) < 0.1);
  // What is left are the events where a pair's penetration passes 0, located
  // to a few ulps of the event time: 1/2 Ke (d(delta_k)/dt dt)^2 each
  // (~1e-16 J measured).
  CHECK(*relieved.stored_energy_jumps_j < 1e-12 * *plain.stored_energy_jumps_j);
  CHECK(relieved.ledger_residual_max_j < 1e-7 * relieved.ledger_scale_j);
}

TEST_CASE("what the dynamics refuses with gaps, naming the key") {
  SimulationCase c = paper_case(1);
  c.integrator.end_time_s = 1e-4;
  c.modifications = tip_relief(5e-6);
  SUBCASE("a constant mesh stiffness has no pairs to relieve") {
    c.model.mesh_stiffness = MeshStiffnessMode::constant;
    c.model.constant_mesh_stiffness_n_per_m = 3e8;
    try {
      simulate(c, summary_only());
      FAIL("not refused");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find("model.mesh_stiffness") != std::string::npos);
    }
  }
  SUBCASE("thicker teeth that could press both flanks at once") {
    // Every pinion tooth 30 um thicker, every wheel tooth 0: the gap on both
    // lines is -30 um, together -60 um against the play 2 B = 100 um: run.
    // At -30 um each wheel tooth too, -120 um: refused, B at least 60 um.
    c.modifications.gear1.thickness_m.assign(20, -30e-6);
    CHECK_NOTHROW(simulate(c, summary_only()));
    c.modifications.gear2.thickness_m.assign(80, -30e-6);
    try {
      simulate(c, summary_only());
      FAIL("not refused");
    } catch (const InputError& e) {
      const std::string text = e.what();
      CHECK(text.find("gears.backlash") != std::string::npos);
      CHECK(text.find("at least 0.06") != std::string::npos);
    }
  }
  SUBCASE("steady states: reliefs run, and so do teeth that differ (once per true period)") {
    CHECK_NOTHROW(require_steady_case([&] {
      SimulationCase balanced = c;
      balanced.model.friction_coefficient = 0.0;
      return balanced;
    }()));
    c.model.friction_coefficient = 0.0;
    c.modifications.gear2.pitch_m.assign(80, 0.0);
    c.modifications.gear2.pitch_m[3] = 1e-6;
    CHECK_NOTHROW(require_steady_case(c));
    // The same case runs as a transient.
    CHECK_NOTHROW(simulate(c, summary_only()));
  }
}

TEST_CASE("RK4 and the adaptive integrator agree with gaps") {
  // Two integrators that share no step, with the same event functions: case
  // 2 with relief on both tips and one pinion tooth out of position. The
  // bound of the integrator suite's cross-check: impact counts exactly, w1
  // and the damping loss to 1e-6 (RK4's error at the paper's step, ~1e-8,
  // and the adaptive tolerance 1e-10, well inside it).
  SimulationCase c = paper_case(2);
  c.integrator.end_time_s = 0.01;
  c.modifications = tip_relief(0.2e-6);
  c.modifications.gear1.pitch_m.assign(20, 0.0);
  c.modifications.gear1.pitch_m[0] = 0.05e-6;
  const SimulationSummary rk4 = simulate(c, summary_only()).summary;
  c.integrator.kind = IntegratorKind::adaptive;
  const SimulationSummary adaptive = simulate(c, summary_only()).summary;
  CHECK(rk4.impacts_n1 == adaptive.impacts_n1);
  CHECK(rk4.impacts_n2 == adaptive.impacts_n2);
  CHECK(relative_difference(rk4.final_w1_rad_per_s, adaptive.final_w1_rad_per_s) < 1e-6);
  CHECK(relative_difference(rk4.damping_loss_j, adaptive.damping_loss_j) < 1e-6);
}
