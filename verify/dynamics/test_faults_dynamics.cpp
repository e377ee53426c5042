// The dynamics of teeth that differ (docs/faults.md): each pair reads the
// table of its own teeth, a missing tooth's pair carries nothing and stores
// nothing, a crack of depth 0 is today's run to the bit, the energy
// ledger closes with a crack and with a missing tooth, and with a linear
// contact and the viscous damper the deflection scales with the load.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

RunControl summary_only() {
  RunControl control;
  control.keep_series = false;
  return control;
}

ToothFault crack_on(Gear gear, int tooth, double q_m) {
  ToothFault f;
  f.gear = gear;
  f.tooth = tooth;
  f.state.kind = ToothKind::root_crack;
  f.state.crack.depth_m = q_m;
  f.state.crack.angle_rad = pi / 4;
  return f;
}

ToothFault missing(Gear gear, int tooth) {
  ToothFault f;
  f.gear = gear;
  f.tooth = tooth;
  f.state.kind = ToothKind::missing;
  return f;
}

// A state at rotation theta1 pressed into N1 by `delta` beyond the backlash,
// at rest.
State pressed(const SimulationCase& c, double theta1, double delta) {
  State y{};
  y[kTheta1] = theta1;
  // s = Rb1 theta1 - Rb2 theta2 = B + delta.
  y[kTheta2] = (base_radius(c.gears, Gear::one) * theta1 - c.gears.backlash_m - delta) /
               base_radius(c.gears, Gear::two);
  return y;
}

}  // namespace

TEST_CASE("a crack of depth 0 runs as the healthy pair, to the bit") {
  // FAULTS.md: zero-size faults are today's outputs. The paper's route
  // returns the healthy tooth's compliances for q = 0, so the fault's table
  // is fitted to the same values.
  for (int n = 1; n <= 3; ++n) {
    CAPTURE(n);
    SimulationCase healthy = paper_case(n);
    healthy.integrator.end_time_s = 0.01;
    SimulationCase faulted = healthy;
    faulted.faults = {crack_on(Gear::one, 0, 0.0), crack_on(Gear::two, 1, 0.0)};
    const SimulationSummary a = simulate(healthy, summary_only()).summary;
    const SimulationSummary b = simulate(faulted, summary_only()).summary;
    CHECK(a.final_w1_rad_per_s == b.final_w1_rad_per_s);
    CHECK(a.final_w2_rad_per_s == b.final_w2_rad_per_s);
    CHECK(a.damping_loss_j == b.damping_loss_j);
    CHECK(a.impacts_n1 == b.impacts_n1);
    CHECK(a.impacts_n2 == b.impacts_n2);
    CHECK(a.steps == b.steps);
  }
}

TEST_CASE("a missing tooth's pair carries nothing, the other pair everything") {
  SimulationCase c = paper_case(1);
  c.model.friction_coefficient = 0.0;
  c.faults = {missing(Gear::one, 0)};
  const StiffnessTable table(c.gears, c.model.stiffness);
  const GearSystem system(c, table, summary_only());
  const MeshLayout layout(c.gears, c.model.coast_phase);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double delta = 2e-6;
  const ContactMemory no_damping{};
  int two_pair_states = 0;
  int lone_states = 0;
  // Pinion tooth 0 is pair k = 0 on N1, at X = X_pitch + Rb1 theta1: sweep it
  // across the segment.
  for (int i = 0; i <= 200; ++i) {
    const double x0 = layout.start_m() + (layout.end_m() - layout.start_m()) * (i + 0.5) / 201.0;
    const double theta1 = (x0 - pitch_point_position(c.gears)) / rb1;
    const State y = pressed(c, theta1, delta);
    Mode m = system.classify_geometry(y);
    REQUIRE(m.region == Region::n1);
    system.classify_forces(y, no_damping, m);
    State dydt{};
    ContactTotals totals;
    system.rhs(0.0, y, m, no_damping, dydt, &totals);
    // The force and energy by hand: F = Ke delta, U = Ke delta^2 / 2 over the
    // loaded pairs other than k = 0, from the healthy table.
    double carried = 0.0;
    for (int j = 0; j < m.count; ++j) {
      const int k = m.k_first + j;
      if (k == 0) continue;
      carried += table.stiffness(layout.position_m(layout.reference_m(Region::n1, theta1), k));
    }
    const double energy = system.stored_energy(y, m).total_j();
    if (m.count == 1) {
      ++lone_states;
      // The missing tooth alone: the teeth pass through each other.
      CHECK(totals.normal_force_n == 0.0);
      CHECK(energy == 0.0);
    } else {
      ++two_pair_states;
      const double dl = system.delta(Region::n1, y);
      CHECK(relative_difference(totals.normal_force_n, carried * dl) < 1e-15);
      // The energy reads the table's term series, the force its Ke series:
      // two fits of one function, within the table's 1e-12 (test_stiffness_table).
      CHECK(relative_difference(energy, 0.5 * carried * dl * dl) < 1e-11);
    }
  }
  CHECK(two_pair_states > 0);
  CHECK(lone_states > 0);
}

TEST_CASE("the energy ledger closes with a crack and with a missing tooth") {
  // The bound of the ledger suite (test_dynamics): 1e-7 of the energy that
  // passes through the run resolves the parametric work by orders while
  // RK4's error at h w ~ 0.01 is ~1e-8 per contact period. A fault changes
  // the stiffness a pair reads, not how the ledger adds.
  // Pinion tooth 0 holds the reference contact at theta1 = 0, so it meets
  // its mate in every run. Case 2 with a missing tooth runs away and is
  // stopped (the next test), so it is left out here.
  for (int n = 1; n <= 3; ++n) {
    std::vector<ToothFault> faults{crack_on(Gear::one, 0, 1.0e-3)};
    if (n != 2) faults.push_back(missing(Gear::one, 0));
    for (const ToothFault& fault : faults) {
      CAPTURE(n);
      CAPTURE(to_string(fault.state.kind));
      SimulationCase healthy = paper_case(n);
      if (fault.state.kind == ToothKind::missing) {
        // While the missing tooth's pair is alone the teeth overlap, and the
        // next pair enters some 0.5 mm deep instead of a few um: a contact
        // of a hundred times the energy, whose RK4 error (h w)^4 a quarter of
        // the paper's step brings back within the bound (at the paper's
        // step the residual is 2e-5 of the throughput, at a quarter 5e-8).
        healthy.integrator.step_s /= 4.0;
      }
      SimulationCase c = healthy;
      c.faults = {fault};
      const SimulationSummary s = simulate(c, summary_only()).summary;
      const SimulationSummary h = simulate(healthy, summary_only()).summary;
      const double throughput =
          s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
      MESSAGE("case " << n << " " << to_string(fault.state.kind) << ": residual "
                      << s.ledger_residual_max_j << " J of " << throughput << " J, max penetration "
                      << s.max_penetration_m << " m, impacts " << s.impacts_n1 << "/"
                      << s.impacts_n2 << ", steps " << s.steps << ", end " << s.end_time_s);
      CHECK(s.ledger_residual_max_j < 1e-7 * throughput);
      // The faulted tooth met its mate during the run: the motion differs.
      CHECK(s.final_w2_rad_per_s != h.final_w2_rad_per_s);
    }
  }
}

TEST_CASE("teeth that pass through each other by half a pitch stop the run with a message") {
  // With every pinion tooth missing nothing holds the pinion: its torque
  // drives it ahead and s - B grows as the free motion's closed form. Half a
  // base pitch is about a tooth's thickness: beyond it the contact on the
  // line of action describes nothing, so the run must stop and say so
  // rather than go on to metres of penetration.
  SimulationCase c = paper_case(1);
  c.faults.clear();
  for (int i = 0; i < c.gears.teeth1; ++i) c.faults.push_back(missing(Gear::one, i));
  CHECK_THROWS_WITH_AS(simulate(c, summary_only()),
                       doctest::Contains("more than half a base pitch"), SimulationError);
  // The healthy pair stays far below the bound (a deflection of micrometres
  // against a half pitch of millimetres).
  const SimulationSummary healthy = simulate(paper_case(1), summary_only()).summary;
  CHECK(healthy.max_penetration_m < 1e-2 * 0.5 * base_pitch(c.gears));
}

TEST_CASE("the energy ledger closes with a spall; with a chip, up to the step of Ke at r_k") {
  // The bound of the crack's ledger test above. A spall's or a partial
  // chip's contact line jumps where the contact meets the fault's edge, and
  // with it Ke. That step is no event of the run, so the stored energy
  // 1/2 dKe delta^2 it adds or takes is left out of the parametric work.
  // Entering and leaving a spall cancel but for the change of delta: its
  // ledger closes to the bound. A chip's step comes once per pass, always
  // the same way: its residual may grow by up to 1/2 |dKe| delta_max^2 each
  // time the chipped tooth meshes (on either line, once a revolution each).
  for (int n = 1; n <= 3; ++n) {
    const SimulationCase healthy = paper_case(n);
    const GearPair& g = healthy.gears;
    const ContactSegment segment = contact_segment(g);
    const double rb1 = base_radius(g, Gear::one);
    const auto x_at = [&](double f) {
      return segment.start_m + f * (segment.end_m - segment.start_m);
    };
    ToothFault spall;
    spall.gear = Gear::one;
    spall.tooth = 0;
    spall.state.kind = ToothKind::spall;
    spall.state.spall.start_radius_m = std::hypot(rb1, x_at(0.3));
    spall.state.spall.end_radius_m = std::hypot(rb1, x_at(0.6));
    spall.state.spall.width_m = 0.5 * g.face_width_m;
    spall.state.spall.depth_m = 0.3e-3;
    ToothFault chip;
    chip.gear = Gear::one;
    chip.tooth = 0;
    chip.state.kind = ToothKind::tip_chip;
    chip.state.chip.radius_m = std::hypot(rb1, x_at(0.75));
    chip.state.chip.width_m = 0.5 * g.face_width_m;
    for (const ToothFault& fault : {spall, chip}) {
      CAPTURE(n);
      CAPTURE(to_string(fault.state.kind));
      SimulationCase c = healthy;
      c.faults = {fault};
      const SimulationResult r = simulate(c, summary_only());
      const SimulationSummary& s = r.summary;
      const SimulationSummary h = simulate(healthy, summary_only()).summary;
      const double throughput =
          s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
      double steps = 0.0;
      if (fault.state.kind == ToothKind::tip_chip) {
        // Ke just below and just above r_k (1e-9 of the segment either side).
        const double x = x_at(0.75);
        const double e = 1e-9 * (segment.end_m - segment.start_m);
        const double dke =
            mesh_stiffness(g, x - e, c.model.stiffness, ToothState{}, ToothState{}).ke -
            mesh_stiffness(g, x + e, c.model.stiffness, fault.state, ToothState{}).ke;
        const double revolutions =
            std::fabs(r.final_state.state.theta1_rad - c.initial.theta1_rad) / (2.0 * pi);
        steps = 2.0 * (std::floor(revolutions) + 1.0) * 0.5 * std::fabs(dke) * s.max_penetration_m *
                s.max_penetration_m;
      }
      MESSAGE("case " << n << " " << to_string(fault.state.kind) << ": residual "
                      << s.ledger_residual_max_j << " J of " << throughput
                      << " J; uncounted steps of Ke at most " << steps << " J");
      CHECK(s.ledger_residual_max_j < 1e-7 * throughput + steps);
      CHECK(s.final_w2_rad_per_s != h.final_w2_rad_per_s);
    }
  }
}

TEST_CASE("a run whose teeth overlap far beyond an elastic deflection is warned about") {
  // The paper's pair rolling at 50 rad/s under Table 1's 50 kgf*mm on the pinion, balanced by
  // the wheel (examples/spall_20_80.toml's load), with pinion tooth 1 missing: where the pair
  // ahead leaves alone, the gears fly until the next pair reaches the segment, which it enters
  // already pressed in by tenths of a millimetre (docs/faults.md, "A missing tooth"); the
  // healthy pair stays at micrometres.
  SimulationCase healthy = paper_case(2);
  healthy.torque2.constant_n_m = -healthy.torque1.constant_n_m * 4.0;
  healthy.initial.w2_rad_per_s = healthy.initial.w1_rad_per_s / 4.0;
  healthy.integrator.end_time_s = 0.01;
  SimulationCase broken = healthy;
  broken.faults = {missing(Gear::one, 1)};
  const SimulationSummary a = simulate(healthy, summary_only()).summary;
  const SimulationSummary b = simulate(broken, summary_only()).summary;
  const double bound = kMostPlausibleOverlapModules * healthy.gears.module_m;
  CHECK(a.max_penetration_m < 0.1 * bound);
  CHECK(result_warnings(healthy, a).empty());
  REQUIRE(b.max_penetration_m > bound);
  const std::vector<std::string> warnings = result_warnings(broken, b);
  REQUIRE(warnings.size() == 1u);
  CHECK(warnings[0].find("max_penetration_m") != std::string::npos);
  CHECK(warnings[0].find("missing or broken tooth") != std::string::npos);
}

TEST_CASE("with a linear contact and the viscous damper the deflection scales with the load") {
  // The loaded pair of the steady-state sweeps (paper/table1: the viscous mesh damper at
  // zeta = 0.05, no Hertzian damping, no friction, balanced torques, started at the static
  // deflection F / 1e9 m on N1) on the pair and model of reproduce's faults section (bores
  // 20/60 mm, potential energy), with pinion tooth 0 cracked (q/h_c = 0.77) at w1 = 1410 rad/s,
  // where the crack separates the teeth (reproduce, docs/faults.md). In contact
  // m_e delta'' + c delta' + Ke(X) delta = F, in the backlash m_e delta'' + c delta' = F: both
  // are linear in (delta, F), and contact is lost where delta = 0, so at the load lambda F the
  // deflection is lambda delta, with the same impacts, until the backlash crossing delta = -2B
  // (a length that does not scale; not reached here). What is not scaled is the mesh phase
  // X = X_p + Rb1 theta1: theta1 carries a share of s, and the start sits at theta1 = (B + F /
  // 1e9) / Rb1, so X shifts by less than (lambda - 1) max(delta), some 1e-7 m or 2e-5 of a base
  // pitch, and the steps of Ke at the pairs' entries and exits move by as little. The difference
  // is then proportional to lambda - 1 (observed 1.1e-4 (lambda - 1) of the deflection, lambda =
  // 0.5 to 5); the bound 5e-4 |lambda - 1| is four times that, and far below what a change of
  // the contact history needs (delta reaching 0 at one load and not at the other would differ
  // by a share of order 1). So a lower load alone brings no separation: that needs a length that
  // does not scale (a tooth error, a relief, the backlash) or a force that is not linear in the
  // deflection (the Hertzian damping D delta delta').
  const double w1 = 1410.0;
  const double base_force_n = 10.0;
  RunControl control = summary_only();
  control.sample_rate_hz = 1e6;
  const auto run = [&](double force_n) {
    PairLoad load;
    load.static_force_n = force_n;
    SimulationCase c = loaded_paper_pair(w1, load);
    c.gears.bore_diameter1_m = 20e-3;
    c.gears.bore_diameter2_m = 60e-3;
    c.model.stiffness.kind = StiffnessModelKind::potential_energy;
    c.faults = {crack_on(Gear::one, 0, 1.5e-3)};
    // Two and a half pinion revolutions: the cracked tooth meets its mate three times.
    c.integrator.end_time_s = 5.0 * pi / w1;
    return simulate(c, control);
  };
  const SimulationResult base = run(base_force_n);
  REQUIRE(base.samples.size() > 10000u);
  double base_max = 0.0;
  for (const SampleRow& row : base.samples) base_max = std::max(base_max, std::fabs(row.dte_m));
  for (double lambda : {0.5, 2.0, 5.0}) {
    CAPTURE(lambda);
    const SimulationResult scaled = run(lambda * base_force_n);
    REQUIRE(scaled.samples.size() == base.samples.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < base.samples.size(); ++i) {
      REQUIRE(scaled.samples[i].t_s == base.samples[i].t_s);
      worst = std::max(worst, std::fabs(scaled.samples[i].dte_m - lambda * base.samples[i].dte_m));
    }
    MESSAGE("lambda " << lambda << ": largest |delta_lambda - lambda delta| / (lambda max delta) = "
                      << worst / (lambda * base_max) << ", impacts " << scaled.summary.impacts_n1
                      << "/" << scaled.summary.impacts_n2);
    CHECK(worst < 5e-4 * std::fabs(lambda - 1.0) * lambda * base_max);
    // The same contact history at every load: the same impacts on the drive flank, none on the
    // coast flank.
    CHECK(scaled.summary.impacts_n1 == base.summary.impacts_n1);
    CHECK(scaled.summary.impacts_n2 == 0);
  }
  // The crack separates the teeth (beyond the contact the run starts in).
  CHECK(base.summary.impacts_n1 > 1);
}
