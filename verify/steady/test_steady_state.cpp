// The steady-state driver against closed forms of the clearance oscillator (docs/steady-state.md
// sections 2 and 3), derived here from the equations of motion, and against itself at half the
// step (the accuracy of the step it chooses).
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/period_map.hpp"
#include "gearimpact/steady/shooting.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "steady_cases.hpp"

using namespace gearimpact;
using namespace gearimpact::steady_test;

TEST_CASE("linear limit: amplitude and phase of the steady response against the closed form") {
  // F_m = 2, F_a = 0.5, zeta = 0.05: A = F_a / sqrt((1 - Omega^2)^2 + (2 zeta Omega)^2) < F_m at
  // every Omega below, so the drive flank never separates and the response is linear.
  for (double omega : {0.5, 0.8, 1.3, 2.0}) {
    CAPTURE(omega);
    const ClearanceCase cc = clearance_case(2.0, 0.5, 0.05, omega);
    const StiffnessTable table(cc.c.gears, cc.c.model.stiffness);
    const SteadyPoint p = find_steady_state(cc.c, table, SteadySettings{});
    REQUIRE(p.converged);
    CHECK(p.period == 1);
    CHECK(p.regime == Regime::no_impact);
    // m_e s'' + c s' + k (s - B) = F_static + m_e Rb1 dT1 / J1 sin(w t) in contact on N1, so
    // s = B + F_static / k + a sin(w t - phi) with
    //   a = (m_e Rb1 dT1 / (J1 k)) / sqrt((1 - Omega^2)^2 + (2 zeta Omega)^2),
    //   phi = atan2(2 zeta Omega, 1 - Omega^2).
    const double zeta = 0.05;
    const double a = cc.force_amplitude_n / cc.stiffness_n_per_m /
                     std::sqrt(std::pow(1.0 - omega * omega, 2) + std::pow(2.0 * zeta * omega, 2));
    const double phi = std::atan2(2.0 * zeta * omega, 1.0 - omega * omega);
    const double s_static = cc.c.gears.backlash_m + cc.static_force_n / cc.stiffness_n_per_m;
    // At t = 0 of the forcing (a Poincare sample): s - s_static = -a sin(phi), s' = a w cos(phi).
    const PoincareSample& sample = p.poincare.back();
    const double measured_a = std::hypot(sample.s_m - s_static, sample.s_rate_m_s / cc.w_rad_per_s);
    const double measured_phi =
        std::atan2(-(sample.s_m - s_static), sample.s_rate_m_s / cc.w_rad_per_s);
    MESSAGE("Omega " << omega << ": a = " << a << " m, relative error of the sampled amplitude "
                     << (measured_a - a) / a << ", of half the peak-to-peak "
                     << (*p.dte_amplitude_m - a) / a << "; phase error " << measured_phi - phi
                     << " rad; periods run " << p.periods_run);
    // RK4 at 128 steps a contact period (w h ~ 0.05): its error on a damped oscillator is of
    // order (w h)^4 / 120 ~ 5e-8 per period, amplified at most by the resonance's Q = 10, below
    // 1e-6; the sampled orbit repeats within 1e-6 B, a further 1e-6 B / a < 1e-6 here.
    CHECK(std::fabs(measured_a - a) <= 1e-6 * a);
    CHECK(std::fabs(*p.dte_amplitude_m - a) <= 1e-6 * a);
    CHECK(std::fabs(measured_phi - phi) <= 1e-6);
    CHECK(std::fabs(*p.dte_mean_m - s_static) <= 1e-6 * a);
    // The RMS of a sine about its mean: a / sqrt 2, by the rectangle rule on a whole period,
    // exact for a trigonometric polynomial of degree below the number of steps.
    CHECK(std::fabs(*p.dte_rms_m - a / std::sqrt(2.0)) <= 1e-6 * a);
  }
}

TEST_CASE("the chosen step: amplitudes within 1e-6 B of a run at half the step") {
  // With impacts (contact lost, r = F_a / F_m = 0.6 at Omega = 0.9: rattle), where
  // the events of contact matter, and in the time-varying paper pair.
  const ClearanceCase cc = clearance_case(1.0, 0.6, 0.05, 0.9);
  const StiffnessTable table(cc.c.gears, cc.c.model.stiffness);
  SteadySettings settings;
  const SteadyPoint coarse = find_steady_state(cc.c, table, settings);
  settings.steps_per_contact_period *= 2.0;
  const SteadyPoint fine = find_steady_state(cc.c, table, settings);
  REQUIRE(coarse.converged);
  REQUIRE(fine.converged);
  CHECK(coarse.regime != Regime::no_impact);
  CHECK(fine.timing.step_s < 0.51 * coarse.timing.step_s);
  const double b = cc.c.gears.backlash_m;
  MESSAGE("amplitude " << *coarse.dte_amplitude_m / b << " B, at half the step "
                       << *fine.dte_amplitude_m / b << " B, difference "
                       << std::fabs(*coarse.dte_amplitude_m - *fine.dte_amplitude_m) / b << " B");
  CHECK(std::fabs(*coarse.dte_amplitude_m - *fine.dte_amplitude_m) <= 1e-6 * b);
  CHECK(std::fabs(*coarse.dte_mean_m - *fine.dte_mean_m) <= 1e-6 * b);

  SimulationCase paper = loaded_paper_pair(3000.0);
  const StiffnessTable paper_table(paper.gears, paper.model.stiffness);
  SteadySettings paper_settings;
  const SteadyPoint p1 = find_steady_state(paper, paper_table, paper_settings);
  paper_settings.steps_per_contact_period *= 2.0;
  const SteadyPoint p2 = find_steady_state(paper, paper_table, paper_settings);
  REQUIRE(p1.converged);
  REQUIRE(p2.converged);
  const double pb = paper.gears.backlash_m;
  MESSAGE("paper pair at w1 = 3000 rad/s: "
          << to_string(p1.regime) << ", amplitude " << *p1.dte_amplitude_m / pb << " B, difference "
          << std::fabs(*p1.dte_amplitude_m - *p2.dte_amplitude_m) / pb << " B");
  CHECK(std::fabs(*p1.dte_amplitude_m - *p2.dte_amplitude_m) <= 1e-6 * pb);
}

TEST_CASE("no steady state: unbalanced mean torques, friction, a user torque are refused") {
  ClearanceCase cc = clearance_case(2.0, 0.5, 0.05, 0.8);
  const StiffnessTable table(cc.c.gears, cc.c.model.stiffness);
  const auto message = [&](const SimulationCase& c) {
    try {
      find_steady_state(c, table, SteadySettings{});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SimulationCase c = cc.c;
  c.torque2.constant_n_m *= 1.01;
  const std::string imbalance = message(c);
  CHECK(imbalance.find("mean torques") != std::string::npos);
  CHECK(imbalance.find("T1/Rb1 + T2/Rb2") != std::string::npos);
  c = cc.c;
  c.model.friction_coefficient = 0.04;
  CHECK(message(c).find("friction") != std::string::npos);
  c = cc.c;
  c.torque2.kind = Torque::Kind::user;
  c.torque2.user = [](double) { return 0.0; };
  CHECK(message(c).find("torque2") != std::string::npos);
}

TEST_CASE("an unbalanced, rubbing steady case: both refusals at once, each with its fix") {
  ClearanceCase cc = clearance_case(2.0, 0.5, 0.05, 0.8);
  SimulationCase c = cc.c;
  c.torque2.constant_n_m = -150.0;
  c.model.friction_coefficient = 0.04;
  std::vector<Problem> problems;
  try {
    require_steady_case(c);
    FAIL("no error");
  } catch (const InputError& e) {
    problems = e.problems();
  }
  REQUIRE(problems.size() == 2);
  CHECK(problems[0].field == "torque2.value");
  CHECK(problems[1].field == "model.friction_coefficient");
  CHECK(problems[1].fix.find("--set model.friction_coefficient=0") != std::string::npos);
  // The balancing torque as the fix prints it: T2 = -T1 Rb2 / Rb1, read back from the text.
  const std::string& fix = problems[0].fix;
  CAPTURE(fix);
  const std::string prefix = "torque2.value = \"";
  REQUIRE(fix.rfind(prefix, 0) == 0);
  CHECK(fix.find("--set 'torque2.value=") != std::string::npos);
  const double balancing = std::stod(fix.substr(prefix.size()));
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  // torque1 is sinusoidal about its mean; the message prints the shortest round trip.
  CHECK(balancing == -c.torque1.mean_n_m * rb2 / rb1);
  // It cures the imbalance, and a torque 1e-6 off it does not (the check allows 1e-9).
  c.model.friction_coefficient = 0.0;
  c.torque2.constant_n_m = balancing;
  CHECK_NOTHROW(require_steady_case(c));
  c.torque2.constant_n_m = balancing * (1.0 + 1e-6);
  CHECK_THROWS_AS(require_steady_case(c), InputError);
}

TEST_CASE("the steady state of the loaded pair is the fixed point of its period map") {
  // The paper's pair loaded with 1000 N and rolling at w1 = 9512.767 rad/s (about 1.5 times the
  // resonance speed w_n / z1) with its time-varying stiffness, zeta = 0.05, no Hertzian damping:
  // the teeth never separate, the motion in s is linear with stable multipliers, so the steady
  // state is the one period-1 orbit, found by running from the stiffest mesh's static
  // deflection, and independently by Newton on the period map.
  SimulationCase c = loaded_paper_pair(9512.767);
  c.model.damping_update = DampingUpdate::off;
  constexpr double static_force_n = 1000.0;
  const double rb1 = base_radius(c.gears, Gear::one);
  c.initial.theta1_rad = (c.gears.backlash_m + static_force_n / 1e9) / rb1;
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SteadySettings settings;
  const SteadyPoint point = find_steady_state(c, table, settings);
  MESSAGE(point.explanation << " after " << point.periods_run << " periods");
  REQUIRE(point.verdict == PeriodicityVerdict::periodic);
  CHECK(point.period == 1);
  CHECK(point.regime == Regime::no_impact);
  // The same orbit by an independent route: Newton on the period map of (s, s') from the
  // static deflection. The sampled state equals its fixed point to the periodicity tolerance
  // (1e-6 of B and of B w_n) times the contraction factor rho / (1 - rho) of periodicity.hpp,
  // under 10 for the multipliers here (modulus below 0.9 a period).
  const GearPeriodMap map(c, table, settings);
  ShootingSettings shooting;
  shooting.scale = map.scale();
  const Eigen::Vector2d guess(c.gears.backlash_m + static_force_n / 8e8, 0.0);
  const PeriodicOrbit orbit = find_periodic_orbit(map, guess, shooting);
  REQUIRE(point.poincare.size() == 1);
  const double ds = std::fabs(point.poincare[0].s_m - orbit.fixed_point[0]) / map.scale()[0];
  const double dv = std::fabs(point.poincare[0].s_rate_m_s - orbit.fixed_point[1]) / map.scale()[1];
  MESSAGE("steady sample against the shot fixed point: " << ds << " B, " << dv << " B w_n");
  CHECK(ds <= 1e-5);
  CHECK(dv <= 1e-5);
  CHECK(std::abs(orbit.floquet_multipliers[0]) < 0.9);
}
