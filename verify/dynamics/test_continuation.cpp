// A run continued from where another ended, the row observer, the stop
// request and the check of a stiffness table against its case: the
// interfaces that sweeps and callers build on.
#include <doctest/doctest.h>

#include <cmath>
#include <iterator>
#include <string>
#include <vector>

#include "gearimpact/dynamics/planar_state.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/table.hpp"

using namespace gearimpact;

namespace {

// A step and a split time that are powers of two: every grid time t0 + k h of
// the continued run is then the same double as k' h of the whole run (sums
// of powers of two far inside 53 bits), so the two runs take the same steps
// and must agree bit for bit in the mechanical state.
constexpr double kStep = 0x1p-24;  // 5.96e-8 s, below the paper's 1e-7 s
constexpr double kSplit = 0x1p-7;  // 7.8125 ms
constexpr double kWhole = 0x1p-6;  // 15.625 ms

SimulationCase case_lasting(int number, double duration_s) {
  SimulationCase c = paper_case(number);
  c.integrator.step_s = kStep;
  c.integrator.end_time_s = duration_s;
  return c;
}

double relative_difference(double a, double b) {
  const double scale = std::max(std::fabs(a), std::fabs(b));
  return scale == 0.0 ? 0.0 : std::fabs(a - b) / scale;
}

}  // namespace

TEST_CASE("a run continued from the final state of its first half is the whole run") {
  for (int number : {1, 2, 3}) {
    CAPTURE(number);
    RunControl summary;
    summary.keep_series = false;
    const SimulationResult whole = simulate(case_lasting(number, kWhole), summary);
    const SimulationResult first = simulate(case_lasting(number, kSplit), summary);
    RunControl resume = summary;
    resume.resume = first.final_state;
    const SimulationResult second = simulate(case_lasting(number, kWhole - kSplit), resume);

    CHECK(first.final_state.time_s == kSplit);
    CHECK(second.final_state.time_s == kWhole);
    CHECK(second.summary.end_time_s == kWhole);
    // The same steps from the same state: the mechanical state to the bit.
    CHECK(second.final_state.state.theta1_rad == whole.final_state.state.theta1_rad);
    CHECK(second.final_state.state.theta2_rad == whole.final_state.state.theta2_rad);
    CHECK(second.final_state.state.w1_rad_per_s == whole.final_state.state.w1_rad_per_s);
    CHECK(second.final_state.state.w2_rad_per_s == whole.final_state.state.w2_rad_per_s);
    CHECK(second.final_state.contact.damping_per_stiffness_s_m ==
          whole.final_state.contact.damping_per_stiffness_s_m);
    // A contact in progress at the split is not a new impact.
    CHECK(first.summary.impacts_n1 + second.summary.impacts_n1 == whole.summary.impacts_n1);
    CHECK(first.summary.impacts_n2 + second.summary.impacts_n2 == whole.summary.impacts_n2);
    // The losses are integrals restarted at the split: the halves add up to
    // the whole but for the rounding of one addition and of the integrals'
    // different accumulation (a few ulps of the sum, 1e-12 leaves room).
    CHECK(relative_difference(first.summary.damping_loss_j + second.summary.damping_loss_j,
                              whole.summary.damping_loss_j) < 1e-12);
    CHECK(relative_difference(first.summary.friction_loss_j + second.summary.friction_loss_j,
                              whole.summary.friction_loss_j) < 1e-12);
    // Each half closes its own ledger, at the bound of the whole runs
    // (test_dynamics.cpp: 1e-7 of the throughput).
    CHECK(std::fabs(second.summary.ledger_residual_max_j) <=
          1e-7 * (second.summary.ledger_scale_j + std::fabs(second.summary.torque_work_j) +
                  second.summary.damping_loss_j + second.summary.friction_loss_j));
  }
}

TEST_CASE("a planar run continued from the final state of its first half is the whole run") {
  // Case 1 on elastic bearings (the planar model, both lines of action with their own contact
  // memories), on the powers-of-two grid above over a shorter run: 2 ms, split at 1 ms.
  constexpr double split = 0x1p-10;
  constexpr double whole_s = 0x1p-9;
  const auto planar = [](double duration_s) {
    SimulationCase c = case_lasting(1, duration_s);
    c.bearings.kind = BearingKind::elastic;
    c.bearings.gear1.stiffness_x_n_per_m = 1e8;
    c.bearings.gear2.stiffness_x_n_per_m = 1e8;
    c.bearings.gear1.damping_x_n_s_per_m = 100.0;
    c.bearings.gear2.damping_x_n_s_per_m = 100.0;
    return c;
  };
  RunControl summary;
  summary.keep_series = false;
  const SimulationResult whole = simulate(planar(whole_s), summary);
  const SimulationResult first = simulate(planar(split), summary);
  REQUIRE(first.final_state.planar);
  RunControl resume = summary;
  resume.resume = first.final_state;
  const SimulationResult second = simulate(planar(whole_s - split), resume);
  CHECK(second.start_time_s == split);
  CHECK(second.final_state.time_s == whole_s);
  REQUIRE(second.planar_final_state);
  REQUIRE(whole.planar_final_state);
  const PlanarState& a = *second.planar_final_state;
  const PlanarState& b = *whole.planar_final_state;
  // The same steps from the same state: every coordinate to the bit.
  const double got[] = {a.x1_m,    a.y1_m,    a.theta1_rad,   a.x2_m,    a.y2_m,    a.theta2_rad,
                        a.vx1_m_s, a.vy1_m_s, a.w1_rad_per_s, a.vx2_m_s, a.vy2_m_s, a.w2_rad_per_s};
  const double want[] = {b.x1_m,         b.y1_m,       b.theta1_rad, b.x2_m,
                         b.y2_m,         b.theta2_rad, b.vx1_m_s,    b.vy1_m_s,
                         b.w1_rad_per_s, b.vx2_m_s,    b.vy2_m_s,    b.w2_rad_per_s};
  for (std::size_t i = 0; i < std::size(got); ++i) {
    CAPTURE(i);
    CHECK(got[i] == want[i]);
  }
  CHECK(second.final_state.contact.damping_per_stiffness_s_m ==
        whole.final_state.contact.damping_per_stiffness_s_m);
  CHECK(second.final_state.coast_contact.damping_per_stiffness_s_m ==
        whole.final_state.coast_contact.damping_per_stiffness_s_m);
  // A contact in progress at the split is not a new impact.
  CHECK(first.summary.impacts_n1 + second.summary.impacts_n1 == whole.summary.impacts_n1);
  CHECK(first.summary.impacts_n2 + second.summary.impacts_n2 == whole.summary.impacts_n2);
  // A torsional state cannot continue a planar run: refused naming resume.
  RunControl torsional = summary;
  torsional.resume = first.final_state;
  torsional.resume->planar.reset();
  try {
    (void)simulate(planar(whole_s - split), torsional);
    FAIL("a planar run continued from a state without its planar state");
  } catch (const InputError& e) {
    CHECK(e.field() == "resume");
  }
}

TEST_CASE("the row observer sees exactly the rows the series keeps, with or without it") {
  SimulationCase c = paper_case(1);
  c.integrator.end_time_s = 2e-3;
  c.integrator.output_every = 50;
  const SimulationResult kept = simulate(c);
  std::vector<SeriesRow> seen;
  RunControl observe;
  observe.keep_series = false;
  observe.on_row = [&seen](const SeriesRow& row) { seen.push_back(row); };
  const SimulationResult observed = simulate(c, observe);
  CHECK(observed.series.empty());
  REQUIRE(seen.size() == kept.series.size());
  for (std::size_t i = 0; i < seen.size(); ++i) {
    CHECK(seen[i].t_s == kept.series[i].t_s);
    CHECK(seen[i].s_m == kept.series[i].s_m);
    CHECK(seen[i].normal_force_n == kept.series[i].normal_force_n);
  }
}

TEST_CASE("a stop request ends the run with SimulationStopped") {
  SimulationCase c = paper_case(1);
  int asked = 0;
  RunControl control;
  control.keep_series = false;
  control.should_stop = [&asked] { return ++asked == 3; };
  CHECK_THROWS_AS(simulate(c, control), SimulationStopped);
  CHECK(asked == 3);
}

TEST_CASE("a stiffness table is checked against the case it is used for") {
  const SimulationCase c = paper_case(1);
  SimulationCase other = c;
  other.gears.face_width_m = 12e-3;
  const StiffnessTable wrong(other.gears, other.model.stiffness);
  CHECK(wrong.built_for(other.gears, other.model.stiffness));
  CHECK_FALSE(wrong.built_for(c.gears, c.model.stiffness));
  CHECK_THROWS_AS(simulate(c, wrong), InputError);
  StiffnessModel flipped = c.model.stiffness;
  flipped.moment_sign = AxialMomentSign::flipped;
  CHECK_THROWS_AS(simulate(c, StiffnessTable(c.gears, flipped)), InputError);

  // A table fitted from a function of our own: the same function as the pair
  // constructor's gives the same table, and so the same run, bit for bit.
  SimulationCase short_run = c;
  short_run.integrator.end_time_s = 2e-3;
  const ContactSegment segment = contact_segment(c.gears);
  const StiffnessTable from_function(segment.start_m, segment.end_m, [&](double x) {
    return mesh_stiffness(c.gears, x, c.model.stiffness).included;
  });
  CHECK_FALSE(from_function.knows_origin());
  const SimulationResult a = simulate(short_run, from_function);
  const SimulationResult b = simulate(short_run);
  CHECK(a.summary.final_w1_rad_per_s == b.summary.final_w1_rad_per_s);
  CHECK(a.summary.damping_loss_j == b.summary.damping_loss_j);
  // One that does not cover the contact segment is refused.
  const StiffnessTable too_short(
      segment.start_m, 0.5 * (segment.start_m + segment.end_m),
      [&](double x) { return mesh_stiffness(c.gears, x, c.model.stiffness).included; });
  CHECK_THROWS_AS(simulate(short_run, too_short), InputError);
}
