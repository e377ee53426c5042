// Rattle of a loose gear (docs/model.md, section Rattle of a loose gear): a
// kinematic driver on gear 1 and a drag on gear 2. Expected values come from
// closed forms derived here: the loose gear's free deceleration under the
// drag, and the separation of a loose gear held on its drive flank by a
// constant drag against a driver theta1 = W t + A sin(w t).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/steady/sweep.hpp"
#include "gearimpact/stiffness/table.hpp"

using namespace gearimpact;

namespace {

// The driver's mean speed W and its one harmonic's order: the harmonic turns
// at w = n W.
constexpr double kMeanSpeed = 200.0;
constexpr double kOrder = 10.0;
constexpr double kDrag = 2.0;  // T_d, N m

// Case 1's pair without friction or damping, driven by w1 = W + a sin(w t +
// 90 deg), i.e. theta1 = W t + (a / w) sin(w t), against a constant drag
// T_d on gear 2, with a constant mesh stiffness k. It starts on the forced
// solution of the contact, so that no free vibration is excited:
// with u = Rb2 theta2 and m2 = J2 / Rb2^2, in contact on N1
//   m2 u'' = -T_d / Rb2 + k (Rb1 theta1 - u - B),
// whose forced solution is u = Rb1 (W t + A sin(w t) / (1 - r^2)) - B -
// T_d / (Rb2 k), r^2 = m2 w^2 / k, A = a / w. Its contact force
//   k delta = T_d / Rb2 - m2 Rb1 A w^2 sin(w t) / (1 - r^2)
// reaches zero when J2 (Rb1 / Rb2) A w^2 = T_d (1 - r^2): the rigid limit's
// J2 (Rb1 / Rb2) A w^2 = T_d times (1 - r^2).
SimulationCase driven_case(double k, double a) {
  SimulationCase c = driven_loose_gear(k, kMeanSpeed, kOrder, a, kDrag);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double m2 = moment_of_inertia(c.gears, Gear::two) / (rb2 * rb2);
  // Two driver periods: the force's minimum comes in the first.
  c.integrator.end_time_s = 2.0 * 2.0 * pi / (kOrder * kMeanSpeed);
  // At least 40 steps per contact period of the loose gear on the spring,
  // 2 pi / sqrt(k / m2), and within the step bound of case 1's stiffest
  // contact (2.29 us), which validation checks whatever the mesh stiffness.
  c.integrator.step_s = std::min(2.0 * pi / std::sqrt(k / m2) / 40.0, 2e-6);
  return c;
}

// The rigid limit's separating speed amplitude a = A w: J2 (Rb1/Rb2) a w = T_d.
double rigid_onset(const SimulationCase& c) {
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  return kDrag * rb2 / (moment_of_inertia(c.gears, Gear::two) * rb1 * kOrder * kMeanSpeed);
}

// The contact that starts the run ends: the loose gear leaves the drive flank.
bool separates(double k, double a) {
  RunControl control;
  control.keep_series = false;
  const SimulationResult r = simulate(driven_case(k, a), control);
  REQUIRE(!r.impacts.empty());
  return r.impacts.front().end_s.has_value();
}

// The separating amplitude by bisection, to 1e-6 of the rigid one.
double measured_onset(double k) {
  const double rigid = rigid_onset(driven_case(k, 1.0));
  double below = 0.5 * rigid;
  double above = 1.5 * rigid;
  REQUIRE(!separates(k, below));
  REQUIRE(separates(k, above));
  while (above - below > 1e-6 * rigid) {
    const double mid = 0.5 * (below + above);
    (separates(k, mid) ? above : below) = mid;
  }
  return 0.5 * (below + above);
}

// Mesh stiffnesses at which r^2 = 0.04 and 0.01: the loose gear's contact
// frequency 5 and 10 times the driver's harmonic.
double stiffness_for(double r2) {
  const SimulationCase c = driven_case(1e8, 1.0);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double m2 = moment_of_inertia(c.gears, Gear::two) / (rb2 * rb2);
  const double w = kOrder * kMeanSpeed;
  return m2 * w * w / r2;
}

}  // namespace

TEST_CASE("rattle: the driver's closed form, theta1 = W t + (a / w) sin(w t)") {
  const SimulationCase c = driven_case(stiffness_for(0.04), 10.0);
  const double w = kOrder * kMeanSpeed;
  for (double t : {0.0, 1e-4, 2.5e-3}) {
    const DriverMotion m = driver_motion(c.torque1, 0.0, t);
    CHECK(std::fabs(m.theta_rad - (kMeanSpeed * t + 10.0 / w * std::sin(w * t))) <= 1e-13);
    CHECK(std::fabs(m.speed_rad_per_s - (kMeanSpeed + 10.0 * std::cos(w * t))) <= 1e-12);
    CHECK(std::fabs(m.acceleration_rad_per_s2 + 10.0 * w * std::sin(w * t)) <= 1e-9);
  }
}

TEST_CASE("rattle: just below and just above the closed-form amplitude") {
  const double k = stiffness_for(0.01);
  const double onset = rigid_onset(driven_case(k, 1.0)) * (1.0 - 0.01);
  // 2 % either side of the finite-stiffness onset a_rigid (1 - r^2).
  CHECK(!separates(k, 0.98 * onset));
  CHECK(separates(k, 1.02 * onset));
}

TEST_CASE("rattle: the separation onset converges to the rigid closed form as k grows") {
  double errors[2] = {0.0, 0.0};
  int i = 0;
  for (double r2 : {0.04, 0.01}) {
    const double k = stiffness_for(r2);
    const double rigid = rigid_onset(driven_case(k, 1.0));
    const double onset = measured_onset(k);
    errors[i++] = (onset - rigid) / rigid;
    MESSAGE("k = " << k << " N/m (r^2 = " << r2 << "): onset a = " << onset
                   << " rad/s, rigid closed form " << rigid << " rad/s, relative difference "
                   << (onset - rigid) / rigid
                   << ", forced solution's a_rigid (1 - r^2) = " << rigid * (1.0 - r2));
    // The finite-stiffness closed form a_rigid (1 - r^2) to 1e-4: the
    // bisection's 1e-6 plus RK4 at 40 steps per contact period.
    CHECK(std::fabs(onset / (rigid * (1.0 - r2)) - 1.0) <= 1e-4);
  }
  // The gap to the rigid limit is -r^2: it falls 4 times as k grows 4 times.
  CHECK(errors[0] < 0.0);
  CHECK(std::fabs(errors[1]) < std::fabs(errors[0]));
  CHECK(std::fabs(errors[0] / errors[1] - 4.0) <= 0.01);
}

TEST_CASE("rattle: the ledger closes with the driver's work") {
  // Above the onset, with Hertzian damping: the loose gear hammers both
  // flanks; the driver's torque feeds what the impacts dissipate. D is
  // frozen at the reference speed: the run starts in contact at Vi = 0, where
  // each-impact's D of (32) grows without bound and stiffens the run.
  const double k = stiffness_for(0.01);
  SimulationCase c = driven_case(k, 3.0 * rigid_onset(driven_case(k, 1.0)));
  c.model.damping_update = DampingUpdate::frozen;
  c.integrator.end_time_s *= 10.0;
  RunControl control;
  control.keep_series = false;
  const SimulationResult r = simulate(c, control);
  const SimulationSummary& s = r.summary;
  MESSAGE("impacts N1 " << s.impacts_n1 << ", N2 " << s.impacts_n2 << "; driver and drag work "
                        << s.torque_work_j << " J, damping loss " << s.damping_loss_j
                        << " J, residual " << s.ledger_residual_max_j / s.ledger_scale_j);
  CHECK(s.impacts_n1 > 2);
  CHECK(s.impacts_n2 > 0);
  CHECK(s.damping_loss_j > 0.0);
  // RK4 at 150 steps per contact period over 30000 steps: 1e-9 of the
  // largest energy is ten times the residual measured (1.4e-10) and far
  // below the driver's work and the damping loss, so that a missing or
  // mis-signed driver term fails.
  CHECK(s.ledger_residual_max_j <= 1e-9 * s.ledger_scale_j);
  CHECK(std::fabs(s.torque_work_j) > 1e6 * s.ledger_residual_max_j);
  CHECK(s.damping_loss_j > 1e6 * s.ledger_residual_max_j);
}

TEST_CASE("rattle: a loose gear in free flight decelerates under its drag") {
  // No harmonic: w1 = W. The loose gear starts centred in the backlash at
  // the pinion's speed, so it flies freely until its lag closes the backlash.
  SimulationCase c = driven_case(stiffness_for(0.01), 0.0);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double j2 = moment_of_inertia(c.gears, Gear::two);
  const double w20 = kMeanSpeed * rb1 / rb2;
  c.initial.theta2_rad = 0.0;
  c.initial.w1_rad_per_s = kMeanSpeed;
  c.initial.w2_rad_per_s = w20;
  c.torque2.drag_constant_n_m = 0.5;
  c.torque2.drag_viscous_n_m_s = 1e-3;
  c.integrator.end_time_s = 2e-3;
  const SimulationResult r = simulate(c);
  // J2 w2' = -(T_c + c w2): w2 = (w20 + T_c / c) exp(-c t / J2) - T_c / c.
  const double tc = 0.5;
  const double cv = 1e-3;
  int checked = 0;
  for (const SeriesRow& row : r.series) {
    if (row.region != static_cast<int>(Region::free)) break;
    const double expected = (w20 + tc / cv) * std::exp(-cv * row.t_s / j2) - tc / cv;
    // tanh(w2 / 0.1 rad/s) is 1 to double precision at w2 > 4 rad/s; RK4's
    // error on an exponential at these steps is below 1e-12 of w2.
    CHECK(std::fabs(row.w2_rad_per_s - expected) <= 1e-10 * w20);
    CHECK(row.w1_rad_per_s == kMeanSpeed);
    ++checked;
  }
  CHECK(checked > 10);
}

TEST_CASE("rattle: refusals name the key and its range") {
  const std::string base =
      "[gears]\nteeth1 = 20\nteeth2 = 40\nmodule = \"2 mm\"\npressure_angle = \"20 deg\"\n"
      "face_width = \"10 mm\"\nyoungs_modulus = \"206 GPa\"\npoisson_ratio = 0.3\n"
      "density = \"7800 kg/m^3\"\nbacklash = \"0.05 mm\"\n";
  const std::string driver =
      "[torque1]\nkind = \"prescribed-speed\"\nmean_speed = \"1000 rpm\"\norders = [2]\n"
      "speed_amplitudes = [\"5 rad/s\"]\nphases = [\"0 deg\"]\n";
  const std::string drag =
      "[torque2]\nkind = \"drag\"\ndrag_constant = \"0.1 N*m\"\ndrag_viscous = \"1e-4 "
      "N*m*s/rad\"\n";
  const std::string initial =
      "[initial]\nw1 = \"1000 rpm\"\n[integrator]\nstep = \"1 us\"\nend_time = \"1 ms\"\n";
  const auto message = [](const std::string& text) {
    try {
      parse_case(text, "rattle.toml");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const SimulationCase c = parse_case(base + driver + drag + initial, "rattle.toml");
  CHECK(c.torque1.kind == Torque::Kind::prescribed_speed);
  CHECK(std::fabs(c.torque1.mean_speed_rad_per_s - 1000.0 * pi / 30.0) <= 1e-12);
  CHECK(c.torque2.drag_viscous_n_m_s == 1e-4);
  std::string slower = initial;
  slower.replace(slower.find("1000 rpm"), 8, "900 rpm");
  const std::string mismatch = message(base + driver + drag + slower);
  CHECK(mismatch.find("initial.w1") != std::string::npos);
  CHECK(mismatch.find("104.7197") != std::string::npos);
  std::string two_orders = driver;
  two_orders.replace(two_orders.find("[2]"), 3, "[2, 4]");
  CHECK(message(base + two_orders + drag + initial).find("torque1.orders") != std::string::npos);
  std::string negative = drag;
  negative.replace(negative.find("0.1 N*m"), 7, "-0.1 N*m");
  CHECK(message(base + driver + negative + initial).find("torque2.drag_constant") !=
        std::string::npos);
  std::string order0 = driver;
  order0.replace(order0.find("[2]"), 3, "[0]");
  CHECK(message(base + order0 + drag + initial).find("torque1.orders") != std::string::npos);
  // A driver on gear 2 and a drag on gear 1 are no choice of theirs.
  std::string driver2 = driver;
  driver2.replace(driver2.find("torque1"), 7, "torque2");
  std::string drag1 = drag;
  drag1.replace(drag1.find("torque2"), 7, "torque1");
  const std::string swapped = message(base + drag1 + driver2 + initial);
  CHECK(swapped.find("kind") != std::string::npos);
  CHECK(swapped != "accepted");
}

TEST_CASE("rattle outputs: a run that never separates is no impact, index 1") {
  // Half the onset: the loose gear stays on its forced solution, with
  // theta2'' = -(Rb1 / Rb2) a w sin(w t) / (1 - r^2), whose RMS over whole
  // periods is (Rb1 / Rb2) a w / ((1 - r^2) sqrt 2). The twin without
  // backlash starts at the same penetration and moves the same way.
  const double k = stiffness_for(0.01);
  const double a = 0.5 * rigid_onset(driven_case(k, 1.0));
  const SimulationCase c = driven_case(k, a);
  RunControl control;
  control.keep_series = false;
  const SimulationResult r = simulate(c, control);
  REQUIRE(r.summary.rattle.has_value());
  const RattleSummary& rattle = *r.summary.rattle;
  CHECK(rattle.regime == RattleRegime::no_impact);
  CHECK(rattle.impacts_per_s_n1 == 0.0);
  CHECK(rattle.impacts_per_s_n2 == 0.0);
  CHECK(rattle.impact_speed_max_m_s == 0.0);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double w = kOrder * kMeanSpeed;
  const double expected = rb1 / rb2 * a * w / ((1.0 - 0.01) * std::sqrt(2.0));
  // Each step's mean w2' stands for w2' over it: the RMS of step means of a
  // sinusoid is low by (w h)^2 / 24 = 7e-7 at w h = 4e-3.
  CHECK(std::fabs(rattle.rms_acceleration2_rad_s2 / expected - 1.0) <= 1e-5);
  REQUIRE(rattle.rattle_index.has_value());
  // The same motion twice, apart from the rounding of B in s - B.
  CHECK(std::fabs(*rattle.rattle_index - 1.0) <= 1e-6);
  const std::string json = summary_json(r.summary);
  CHECK(json.find("\"rattle_regime\": \"no-impact\"") != std::string::npos);
  CHECK(json.find("\"rattle_index\": ") != std::string::npos);
}

TEST_CASE("rattle outputs: a strongly rattling run strikes both flanks") {
  const double k = stiffness_for(0.01);
  SimulationCase c = driven_case(k, 3.0 * rigid_onset(driven_case(k, 1.0)));
  c.model.damping_update = DampingUpdate::frozen;
  c.integrator.end_time_s *= 10.0;
  RunControl control;
  control.keep_series = false;
  const SimulationResult r = simulate(c, control);
  REQUIRE(r.summary.rattle.has_value());
  const RattleSummary& rattle = *r.summary.rattle;
  const SimulationSummary& s = r.summary;
  const double duration = c.integrator.end_time_s;
  MESSAGE("impacts/s N1 " << rattle.impacts_per_s_n1 << ", N2 " << rattle.impacts_per_s_n2
                          << "; Vi mean " << rattle.impact_speed_mean_m_s << " max "
                          << rattle.impact_speed_max_m_s << " m/s; power " << rattle.impact_power_w
                          << " W; rattle index " << rattle.rattle_index.value_or(-1.0));
  CHECK(rattle.regime == RattleRegime::double_sided);
  // The contact the run starts in is not counted.
  CHECK(std::fabs(rattle.impacts_per_s_n1 * duration - (s.impacts_n1 - 1)) <= 1e-9);
  CHECK(std::fabs(rattle.impacts_per_s_n2 * duration - s.impacts_n2) <= 1e-9);
  CHECK(rattle.impacts_per_s_n2 > 0.0);
  // Mean and max of the impacts' own Vi, from the impact records.
  double most = 0.0;
  double sum = 0.0;
  int n = 0;
  for (const ImpactRecord& impact : r.impacts) {
    if (impact.start_s == 0.0) continue;
    most = std::max(most, impact.impact_speed_m_s);
    sum += impact.impact_speed_m_s;
    ++n;
  }
  CHECK(rattle.impact_speed_max_m_s == most);
  CHECK(std::fabs(rattle.impact_speed_mean_m_s - sum / n) <= 1e-15 * most);
  CHECK(rattle.impact_speed_mean_m_s < rattle.impact_speed_max_m_s);
  CHECK(std::fabs(rattle.impact_power_w * duration / s.damping_loss_j - 1.0) <= 1e-12);
  // Impacts add acceleration peaks the backlash-free twin does not have.
  REQUIRE(rattle.rattle_index.has_value());
  CHECK(*rattle.rattle_index > 1.5);
}

TEST_CASE("rattle outputs: only a driven run's summary has them") {
  SimulationCase c = paper_case(1);
  c.integrator.end_time_s = 1e-4;
  RunControl control;
  control.keep_series = false;
  const SimulationResult r = simulate(c, control);
  CHECK(!r.summary.rattle.has_value());
  CHECK(summary_json(r.summary).find("rattle") == std::string::npos);
}

TEST_CASE("rattle: a continued driven run goes on as one run, restarted at t = 0 or not") {
  const double k = stiffness_for(0.01);
  SimulationCase c = driven_case(k, 3.0 * rigid_onset(driven_case(k, 1.0)));
  c.model.damping_update = DampingUpdate::frozen;
  const double period = 2.0 * pi / (kOrder * kMeanSpeed);
  // Whole steps per period, so that the two halves' grids are the whole run's.
  c.integrator.step_s = period / 1600.0;
  c.integrator.end_time_s = 2.0 * period;
  RunControl control;
  control.keep_series = false;
  const SimulationResult whole = simulate(c, control);
  SimulationCase half = c;
  half.integrator.end_time_s = period;
  const SimulationResult first = simulate(half, control);
  RunControl go_on = control;
  go_on.resume = first.final_state;
  const SimulationResult second = simulate(half, go_on);
  // The driver's phase at t = 0 is its phase after a whole period.
  go_on.resume->time_s = 0.0;
  const SimulationResult restarted = simulate(half, go_on);
  const InitialState& a = whole.final_state.state;
  for (const SimulationResult* r : {&second, &restarted}) {
    const InitialState& b = r->final_state.state;
    // The same steps but for the rounding of t (t0 + k h against k h) and of
    // theta1 (its closed form at 2 periods against 1 period plus 1 period):
    // 1e-9 rad on 2 rad of theta1, 1e-9 relative on the speeds.
    CHECK(std::fabs(b.theta1_rad - a.theta1_rad) <= 1e-9);
    CHECK(std::fabs(b.theta2_rad - a.theta2_rad) <= 1e-9);
    CHECK(std::fabs(b.w1_rad_per_s - a.w1_rad_per_s) <= 1e-9 * kMeanSpeed);
    CHECK(std::fabs(b.w2_rad_per_s - a.w2_rad_per_s) <= 1e-9 * kMeanSpeed);
  }
}

TEST_CASE("rattle sweep: the regime map over the drag brackets the closed-form onset") {
  // Fixed amplitude a; the loose gear stays in contact when
  // T_d (1 - r^2) > J2 (Rb1 / Rb2) a w (the forced solution's onset, read for
  // the drag), and leaves its drive flank below. Hertzian damping (frozen D)
  // takes each point to its steady state.
  const double k = stiffness_for(0.01);
  const double a = 0.5;
  SimulationCase c = driven_case(k, a);
  c.model.damping_update = DampingUpdate::frozen;
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double w = kOrder * kMeanSpeed;
  const double onset = moment_of_inertia(c.gears, Gear::two) * rb1 / rb2 * a * w / (1.0 - 0.01);
  // Seven drags from 0.42 to 1.62 times the onset, a grid step of 0.2 times
  // it: none within 2 % of it.
  const double grid_step = 0.2 * onset;
  std::vector<double> grid;
  for (int i = 0; i < 7; ++i) grid.push_back(onset * 0.42 + grid_step * i);
  SteadySettings settings;
  settings.max_periods = 400;
  const TableFor table_for = [](const SimulationCase& x) {
    return std::make_shared<const StiffnessTable>(x.gears, x.model.stiffness);
  };
  // Downwards, from the held loose gear: each point starts from the last
  // one's steady state. Upwards, the rattling orbit of the low drags goes on
  // past the onset (a rattling orbit coexists with the held one there), so
  // the map of an up sweep shows the hysteresis, not the onset.
  for (SweepDirection direction : {SweepDirection::down, SweepDirection::up}) {
    const std::vector<SweepPointResult> points =
        sweep_line(c, table_for, "torque2.drag_constant", grid, direction, 0, settings, nullptr);
    REQUIRE(points.size() == grid.size());
    double lowest_held = grid.back() + grid_step;
    double highest_struck = 0.0;
    for (const SweepPointResult& p : points) {
      MESSAGE(to_string(direction)
              << ": T_d / onset = " << p.value_si / onset << ": " << to_string(p.point.regime)
              << ", period " << period_label(p.point) << ", " << p.point.periods_run << " periods"
              << (p.failure.empty() ? "" : ", " + p.failure));
      REQUIRE(p.failure.empty());
      REQUIRE(p.point.converged);
      // Below the onset the loose gear cannot stay held, in either direction.
      if (p.value_si < onset) CHECK(p.point.regime != Regime::no_impact);
      if (p.point.regime == Regime::no_impact) {
        lowest_held = std::min(lowest_held, p.value_si);
      } else {
        highest_struck = std::max(highest_struck, p.value_si);
      }
    }
    if (direction == SweepDirection::down) {
      // One boundary, half way between the highest drag that rattles and the
      // lowest that holds, within one grid step of the onset. (The point 2 %
      // above the onset rattles: the step of the drag from the point before
      // starts a transient that knocks the loose gear off its flank, and the
      // rattling orbit coexists there.)
      CHECK(highest_struck < lowest_held);
      const double boundary = 0.5 * (highest_struck + lowest_held);
      MESSAGE("map boundary " << boundary / onset << " x the onset");
      CHECK(std::fabs(boundary - onset) <= grid_step);
    }
  }
}

TEST_CASE("rattle sweep: a driven case with w2 at rest is not warned of a momentum speed") {
  // The driver holds w1 whatever w2 starts at, so no point runs at the momentum's mean speed;
  // the same speeds under torques (no driver) are warned of.
  SimulationCase c = driven_case(stiffness_for(0.01), 0.5);
  c.model.damping_update = DampingUpdate::frozen;
  c.model.mesh_damping_ratio = 0.05;
  c.initial.w2_rad_per_s = 0.0;
  SteadySweepSpec spec;
  spec.base = c;
  spec.vary = "torque2.drag_constant";
  for (const std::string& w : sweep_warnings(spec))
    CHECK_MESSAGE(w.find("momentum") == std::string::npos, w);
  spec.base.torque1 = Torque{};
  spec.base.torque2 = Torque{};
  const std::vector<std::string> warned = sweep_warnings(spec);
  CHECK(std::any_of(warned.begin(), warned.end(),
                    [](const std::string& w) { return w.find("momentum") != std::string::npos; }));
}

TEST_CASE("rattle: the step must resolve the driver and the drag") {
  const double k = stiffness_for(0.01);
  const auto refused_key = [](const SimulationCase& c) {
    try {
      simulate(c);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("accepted");
  };
  // The drag's relaxation time J2 / (T_c / w_s): 2 N m over 1e-6 rad/s is
  // far below 20 steps of 2 us per 2 pi of it.
  SimulationCase sharp = driven_case(k, 0.1);
  sharp.torque2.drag_speed_scale_rad_per_s = 1e-6;
  CHECK(refused_key(sharp) == "torque2.drag_speed_scale");
  // An order whose harmonic turns faster than 20 steps a period: 2 pi /
  // (20 x 2 us) = 1.6e5 rad/s, here 1000 W = 2e5 rad/s.
  SimulationCase fast = driven_case(k, 0.1);
  fast.torque1.driver_orders = {1000.0};
  CHECK(refused_key(fast) == "torque1.orders[0]");
}

TEST_CASE("rattle outputs: the impacts' table and histogram hold the summary's impacts") {
  const double k = stiffness_for(0.01);
  SimulationCase c = driven_case(k, 3.0 * rigid_onset(driven_case(k, 1.0)));
  c.model.damping_update = DampingUpdate::frozen;
  c.integrator.end_time_s *= 10.0;
  RunControl control;
  control.keep_series = false;
  const SimulationResult r = simulate(c, control);
  REQUIRE(r.summary.rattle.has_value());
  const RattleSummary& rattle = *r.summary.rattle;
  const double duration = c.integrator.end_time_s;
  const std::vector<ImpactRecord> struck = struck_impacts(r);
  // The run starts in contact on N1, which is not struck.
  CHECK(struck.size() + 1 == r.impacts.size());
  const double counted = (rattle.impacts_per_s_n1 + rattle.impacts_per_s_n2) * duration;
  CHECK(std::fabs(static_cast<double>(struck.size()) - counted) <= 1e-9 * counted);
  // One row per impact after the header, each naming its flank.
  const std::string csv = rattle_impacts_csv(struck);
  CHECK(csv.rfind("t_s,flank,impact_speed_m_s\n", 0) == 0);
  CHECK(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')) == struck.size() + 1);
  std::size_t n2_rows = 0;
  for (std::size_t at = csv.find(",N2,"); at != std::string::npos; at = csv.find(",N2,", at + 1))
    ++n2_rows;
  // Counts from rates: n / duration * duration is n to rounding.
  CHECK(std::fabs(static_cast<double>(n2_rows) - rattle.impacts_per_s_n2 * duration) <= 1e-9);
  // The bins cover [0, max Vi] edge to edge, and their counts add up to the impacts.
  const ImpactSpeedHistogram h = impact_speed_histogram(struck);
  REQUIRE(h.lower_m_s.size() == static_cast<std::size_t>(kImpactSpeedBins));
  CHECK(h.lower_m_s.front() == 0.0);
  CHECK(h.upper_m_s.back() == rattle.impact_speed_max_m_s);
  long long n1 = 0;
  long long n2 = 0;
  for (std::size_t i = 0; i < h.lower_m_s.size(); ++i) {
    if (i > 0) CHECK(h.lower_m_s[i] == h.upper_m_s[i - 1]);
    n1 += h.count_n1[i];
    n2 += h.count_n2[i];
  }
  CHECK(std::fabs(static_cast<double>(n1) - rattle.impacts_per_s_n1 * duration) <= 1e-9);
  CHECK(std::fabs(static_cast<double>(n2) - rattle.impacts_per_s_n2 * duration) <= 1e-9);
  CHECK(n2 > 0);
  // The fastest impact is in the last bin, which holds its upper edge.
  CHECK(h.count_n1.back() + h.count_n2.back() >= 1);
  const std::string table = impact_speed_histogram_csv(h);
  CHECK(table.rfind("lower_m_s,upper_m_s,count_n1,count_n2,count\n", 0) == 0);
  // No impacts, no bins.
  CHECK(impact_speed_histogram({}).lower_m_s.empty());
}

TEST_CASE("rattle sweep: the driver's speed amplitude is a swept key, across the onset") {
  // The forced solution's onset a_rigid (1 - r^2) (the closed form above);
  // two amplitudes 10 % either side of it, swept upwards.
  const double k = stiffness_for(0.01);
  const double onset = rigid_onset(driven_case(k, 1.0)) * (1.0 - 0.01);
  // The base starts on the lower amplitude's forced solution (no free
  // vibration), the point above from the held state it carries.
  SimulationCase c = driven_case(k, 0.9 * onset);
  c.model.damping_update = DampingUpdate::frozen;
  const std::string key = "torque1.speed_amplitudes[0]";
  const Field& field = sweep_field(key, "--vary");
  CHECK(field.name() == key);
  CHECK(field.kind == FieldKind::quantity);
  SimulationCase moved = c;
  apply_sweep_value(moved, c, key, 0.7);
  CHECK(moved.torque1.driver_speed_amplitudes_rad_per_s == std::vector<double>{0.7});
  // The driver's w1(0) = W + a sin(90 deg) moves with the amplitude.
  CHECK(std::fabs(moved.initial.w1_rad_per_s - (kMeanSpeed + 0.7)) <= 1e-12);
  const TableFor table_for = [](const SimulationCase& x) {
    return std::make_shared<const StiffnessTable>(x.gears, x.model.stiffness);
  };
  SteadySettings settings;
  settings.max_periods = 400;
  const std::vector<SweepPointResult> points = sweep_line(
      c, table_for, key, {0.9 * onset, 1.1 * onset}, SweepDirection::up, 0, settings, nullptr);
  REQUIRE(points.size() == 2);
  for (const SweepPointResult& p : points) {
    MESSAGE("a / onset = " << p.value_si / onset << ": " << to_string(p.point.regime) << ", "
                           << p.point.periods_run << " periods"
                           << (p.failure.empty() ? "" : ", " + p.failure));
    REQUIRE(p.failure.empty());
  }
  CHECK(points[0].point.regime == Regime::no_impact);
  CHECK(points[1].point.regime != Regime::no_impact);
}

TEST_CASE("rattle sweep: an element key past the list is refused with the index range") {
  const SimulationCase c = driven_case(stiffness_for(0.01), 0.5);
  const auto refusal = [&](const std::string& key) {
    try {
      SimulationCase moved = c;
      apply_sweep_value(moved, c, key, 0.7);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // The case's list has one element.
  const std::string past = refusal("torque1.speed_amplitudes[1]");
  CHECK(past.find("torque1.speed_amplitudes[1]") != std::string::npos);
  CHECK(past.find("[0, 0]") != std::string::npos);
  // Beyond what any list of the row may hold.
  const std::string far = refusal("torque1.speed_amplitudes[999]");
  CHECK(far.find("torque1.speed_amplitudes[999]") != std::string::npos);
  CHECK(far.find("an index in [0, ") != std::string::npos);
  // An element's range is its list's.
  const std::string negative = [&] {
    try {
      SimulationCase moved = c;
      apply_sweep_value(moved, c, "torque1.speed_amplitudes[0]", -1.0);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  }();
  CHECK(negative.find("torque1.speed_amplitudes[0]") != std::string::npos);
  // A scalar key takes no index.
  CHECK(refusal("torque2.drag_constant[0]").find("--vary") == std::string::npos);
  CHECK(refusal("torque2.drag_constant[0]") != "accepted");
}
