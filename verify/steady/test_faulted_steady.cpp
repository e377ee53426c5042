// Steady states of faulted teeth (docs/steady-state.md, "Poincare period"; docs/faults.md): the
// Poincare period is the true period of the teeth (a pinion revolution for a cracked pinion
// tooth) or its least common period with a forcing, the sweep point found there is periodic at
// that period and not at the mesh period, and a forcing incommensurate with the teeth is
// refused naming its key.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/steady/period_map.hpp"
#include "gearimpact/steady/shooting.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "steady_cases.hpp"

using namespace gearimpact;
using namespace gearimpact::steady_test;

namespace {

// Pinion tooth 3 with a root crack 0.8 mm deep at 45 degrees (a fault the paper's tooth takes).
ToothFault cracked_pinion_tooth() {
  ToothFault f;
  f.gear = Gear::one;
  f.tooth = 3;
  f.state.kind = ToothKind::root_crack;
  f.state.crack.depth_m = 0.8e-3;
  f.state.crack.angle_rad = pi / 4.0;
  return f;
}

// The loaded paper pair at w1 = 2000 rad/s (N about 0.3, below the main resonance: the teeth
// stay in contact), with the cracked tooth.
SimulationCase cracked_case() {
  SimulationCase c = loaded_paper_pair(2000.0);
  c.name = "cracked-pinion";
  c.faults = {cracked_pinion_tooth()};
  return c;
}

// The healthy mesh period of a case without forcing: 2 pi / (z1 w1_mean), w1_mean from the
// momentum J1 w1/Rb1 + J2 w2/Rb2 of the rolling pair (docs/steady-state.md section 1).
double mesh_period_s(const SimulationCase& c) {
  const GearPair& g = c.gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const double j1 = moment_of_inertia(g, Gear::one);
  const double j2 = moment_of_inertia(g, Gear::two);
  const double p = j1 * c.initial.w1_rad_per_s / rb1 + j2 * c.initial.w2_rad_per_s / rb2;
  return 2.0 * pi / (g.teeth1 * p / (j1 / rb1 + j2 * rb1 / (rb2 * rb2)));
}

}  // namespace

TEST_CASE("a cracked pinion tooth: the Poincare period is one pinion revolution") {
  const SimulationCase c = cracked_case();
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SteadyTiming timing = steady_timing(c, table, SteadySettings{});
  CHECK(timing.kind == "pinion-revolution");
  CHECK(timing.mesh_periods == c.gears.teeth1);
  // z1 mesh periods, to the rounding of the two routes' products.
  CHECK(std::fabs(timing.excitation_period_s / (c.gears.teeth1 * mesh_period_s(c)) - 1.0) < 1e-14);
  // Both steps are the same bound L rounded down to a whole number of steps per period: the
  // healthy one is at least L n / (n + 1) for its n steps per mesh period, the faulted one at
  // most L.
  SimulationCase healthy = c;
  healthy.faults.clear();
  const SteadyTiming healthy_timing = steady_timing(healthy, table, SteadySettings{});
  CHECK(healthy_timing.kind == "mesh");
  CHECK(healthy_timing.mesh_periods == 1);
  const double n = static_cast<double>(healthy_timing.steps_per_period);
  CHECK(timing.step_s <= healthy_timing.step_s * (n + 1.0) / n);
}

TEST_CASE("a faulted sweep point repeats at the true period and not at the mesh period") {
  const SimulationCase base = cracked_case();
  const int z1 = base.gears.teeth1;
  const StiffnessTable table(base.gears, base.model.stiffness);
  // A step that puts every mesh period on the RK4 grid (steps per revolution a multiple of z1),
  // so that the states one mesh period apart are read off the same run the sweep makes.
  SteadySettings settings;
  SteadyTiming timing;
  for (double steps = 128.0; steps < 256.0; steps += 0.25) {
    settings.steps_per_contact_period = steps;
    timing = steady_timing(base, table, settings);
    if (timing.steps_per_period % z1 == 0) break;
  }
  REQUIRE(timing.steps_per_period % z1 == 0);

  SteadySweepSpec spec;
  spec.base = base;
  spec.vary = "initial.w1";
  spec.from_si = 2000.0;
  spec.to_si = 2100.0;
  spec.points = 2;
  spec.directions = {SweepDirection::up};
  spec.settings = settings;
  spec.threads = 1;
  const SteadySweep sweep = run_steady_sweep(spec);
  CHECK(sweep.spec.poincare_period_kind == "pinion-revolution");
  CHECK(sweep.spec.poincare_mesh_periods[0] == z1);
  CHECK(sweep.spec.poincare_period_s[0] == timing.excitation_period_s);
  // The higher speed turns a revolution sooner.
  CHECK(sweep.spec.poincare_period_s[1] < sweep.spec.poincare_period_s[0]);
  REQUIRE(sweep.rows.size() == 2u);
  const SteadyPoint& point = sweep.rows[0].point;
  MESSAGE(point.explanation << " after " << point.periods_run << " periods");
  REQUIRE(point.verdict == PeriodicityVerdict::periodic);
  CHECK(point.period == 1);
  CHECK(point.regime == Regime::no_impact);
  CHECK(point.timing.excitation_period_s == timing.excitation_period_s);

  // Two more revolutions from where the point ended, as find_steady_state runs them, read at
  // every mesh period: 2 z1 + 1 samples.
  const double rb1 = base_radius(base.gears, Gear::one);
  const double rb2 = base_radius(base.gears, Gear::two);
  const Eigen::Vector2d scale = state_scale(base, table);
  SimulationCase run = base;
  run.integrator.kind = IntegratorKind::rk4;
  run.integrator.step_s = timing.step_s;
  run.integrator.end_time_s = timing.excitation_period_s;
  run.integrator.output_every = 1;
  const long long steps_per_mesh = timing.steps_per_period / z1;
  std::vector<Eigen::Vector2d> samples;
  const auto relative = [&](const InitialState& y) {
    return Eigen::Vector2d(rb1 * y.theta1_rad - rb2 * y.theta2_rad,
                           rb1 * y.w1_rad_per_s - rb2 * y.w2_rad_per_s);
  };
  RunState state = point.final_state;
  samples.push_back(relative(state.state));
  for (int revolution = 0; revolution < 2; ++revolution) {
    long long step = 0;
    RunControl control;
    control.keep_series = false;
    control.resume = state;
    // Rows come at every step (no impacts in this regime: checked below), the first being the
    // start; a row ends step `step`.
    control.on_row = [&](const SeriesRow& row) {
      if (row.t_s <= state.time_s) return;
      ++step;
      if (step % steps_per_mesh == 0 && step < timing.steps_per_period) {
        samples.push_back(
            Eigen::Vector2d(row.s_m, rb1 * row.w1_rad_per_s - rb2 * row.w2_rad_per_s));
      }
    };
    const SimulationResult r = simulate(run, table, control);
    CHECK(r.summary.impacts_n1 + r.summary.impacts_n2 == 0);
    CHECK(step == timing.steps_per_period);
    state = r.final_state;
    samples.push_back(relative(state.state));
  }
  REQUIRE(samples.size() == static_cast<std::size_t>(2 * z1 + 1));
  const auto distance = [&](std::size_t a, std::size_t b) {
    const Eigen::Vector2d d = samples[a] - samples[b];
    return std::max(std::fabs(d[0]) / scale[0], std::fabs(d[1]) / scale[1]);
  };
  // At the true period every sample repeats. The point was accepted when its last 16 samples
  // agreed within the tolerance 1e-6 (scaled as periodicity.hpp), and what is left of the
  // transient only shrinks; 1e-6 also bounds the samples a revolution apart here.
  double true_period = 0.0;
  for (int k = 0; k <= z1; ++k) true_period = std::max(true_period, distance(k, k + z1));
  MESSAGE("samples one revolution apart differ by at most " << true_period << " of the scale");
  CHECK(true_period <= settings.tolerance);
  // At the mesh period, and at every period up to the classifier's largest (max_period = 8
  // mesh periods), some sample does not repeat, by more than a hundred times the tolerance
  // (measured: 1.2e-3 to 1.6e-3 of B): the cracked tooth's softer mesh moves the deflection
  // while it meshes.
  for (int p = 1; p <= settings.max_period; ++p) {
    double most = 0.0;
    for (std::size_t k = 0; k + static_cast<std::size_t>(p) < samples.size(); ++k) {
      most = std::max(most, distance(k, k + static_cast<std::size_t>(p)));
    }
    MESSAGE("samples " << p << " mesh periods apart differ by up to " << most);
    CHECK(most > 1e2 * settings.tolerance);
  }
}

TEST_CASE("a forcing at the pinion's shaft speed: the Poincare period is one revolution") {
  // A torque ripple on the pinion at its mean speed, once per revolution: commensurate with the
  // cracked pinion. The mean speed includes the ripple's share of the momentum,
  // A cos(phi) / (w Rb1) (P' = T1/Rb1 + T2/Rb2), so the initial speeds are set below it.
  SimulationCase c = cracked_case();
  const GearPair& g = c.gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const double j1 = moment_of_inertia(g, Gear::one);
  const double j2 = moment_of_inertia(g, Gear::two);
  const double w = 2000.0;
  const double amplitude = 0.05 * c.torque1.constant_n_m;
  c.torque1.kind = Torque::Kind::sinusoidal;
  c.torque1.mean_n_m = c.torque1.constant_n_m;
  c.torque1.amplitude_n_m = amplitude;
  c.torque1.angular_frequency_rad_per_s = w;
  c.torque1.phase_rad = 0.0;
  // Rolling at w1 with momentum p0 = (J1/Rb1 + J2 Rb1/Rb2^2) w1: its mean is p0 + A / (w Rb1).
  const double inertia = j1 / rb1 + j2 * rb1 / (rb2 * rb2);
  const double w1 = w - amplitude / (w * rb1) / inertia;
  c.initial.w1_rad_per_s = w1;
  c.initial.w2_rad_per_s = w1 * rb1 / rb2;
  const StiffnessTable table(g, c.model.stiffness);
  const SteadyTiming timing = steady_timing(c, table, SteadySettings{});
  CHECK(timing.kind == "pinion-revolution+forcing");
  CHECK(timing.mesh_periods == g.teeth1);
  CHECK(std::fabs(timing.excitation_period_s * w / (2.0 * pi) - 1.0) < 1e-14);

  // Twice the ripple's frequency at 2.5 times the revolution's: q P = p T with q = 2, p = 5,
  // two revolutions.
  SimulationCase twice = c;
  twice.torque1.angular_frequency_rad_per_s = 2.5 * w;
  const double w1_twice = w - amplitude / (2.5 * w * rb1) / inertia;
  twice.initial.w1_rad_per_s = w1_twice;
  twice.initial.w2_rad_per_s = w1_twice * rb1 / rb2;
  const SteadyTiming two = steady_timing(twice, table, SteadySettings{});
  CHECK(two.kind == "pinion-revolution+forcing");
  CHECK(two.mesh_periods == 2 * g.teeth1);
  CHECK(std::fabs(two.excitation_period_s * 2.5 * w / (2.0 * pi) / 5.0 - 1.0) < 1e-14);

  // A ripple at sqrt(2) times the shaft speed has no common period with the teeth within
  // kMostToothPatternsPerPoincarePeriod revolutions: refused, naming its key and the speed.
  SimulationCase off = c;
  off.torque1.angular_frequency_rad_per_s = std::sqrt(2.0) * w;
  try {
    steady_timing(off, table, SteadySettings{});
    FAIL("an incommensurate forcing was accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "torque1.angular_frequency, initial.w1");
    CHECK(std::string(e.what()).find("commensurate") != std::string::npos);
  }
}

TEST_CASE("the period map of a faulted case spans the true period") {
  // Shooting on the map of (s, s'): the map starts every period at the case's centre of mass,
  // which a true period (z1 base pitches for the cracked pinion) brings back to the same teeth.
  SimulationCase c = cracked_case();
  c.model.damping_update = DampingUpdate::off;
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SteadySettings settings;
  const GearPeriodMap map(c, table, settings);
  CHECK(std::fabs(map.period_s() / (c.gears.teeth1 * mesh_period_s(c)) - 1.0) < 1e-14);
  // Its fixed point is the steady state found by running: the sampled state equals it to the
  // periodicity tolerance (1e-6 of B and of B w_n) times the contraction factor
  // rho / (1 - rho) of periodicity.hpp, under 10 for multipliers of modulus below 0.9 a period.
  const SteadyPoint point = find_steady_state(c, table, settings);
  REQUIRE(point.verdict == PeriodicityVerdict::periodic);
  REQUIRE(point.period == 1);
  ShootingSettings shooting;
  shooting.scale = map.scale();
  const Eigen::Vector2d guess(c.gears.backlash_m + 1000.0 / 8e8, 0.0);
  const PeriodicOrbit orbit = find_periodic_orbit(map, guess, shooting);
  const double ds = std::fabs(point.poincare[0].s_m - orbit.fixed_point[0]) / map.scale()[0];
  const double dv = std::fabs(point.poincare[0].s_rate_m_s - orbit.fixed_point[1]) / map.scale()[1];
  MESSAGE("steady sample against the shot fixed point: " << ds << " B, " << dv << " B w_n; "
                                                         << "multiplier "
                                                         << std::abs(orbit.floquet_multipliers[0]));
  CHECK(ds <= 1e-5);
  CHECK(dv <= 1e-5);
  CHECK(std::abs(orbit.floquet_multipliers[0]) < 0.9);
}

TEST_CASE("a prescribed-speed driver: the common period of its orders and the faulted teeth") {
  // In pinion revolutions the teeth repeat after N / z1 = a / b and a driver of orders with
  // greatest common divisor g after 1 / g: the least common period is a / gcd(b, g) revolutions,
  // that is 2 pi a / (W gcd(b, g)).
  SimulationCase c = loaded_paper_pair(2000.0);
  const double w = 2000.0;
  c.torque1 = Torque{};
  c.torque1.kind = Torque::Kind::prescribed_speed;
  c.torque1.mean_speed_rad_per_s = w;
  c.torque1.driver_orders = {2.0, 4.0};
  c.torque1.driver_speed_amplitudes_rad_per_s = {1.0, 0.5};
  c.torque1.harmonic_phases_rad = {0.0, 0.0};
  c.torque2 = Torque{};
  c.torque2.kind = Torque::Kind::drag;
  c.torque2.drag_constant_n_m = 1.0;
  const StiffnessTable table(c.gears, c.model.stiffness);
  const int z1 = c.gears.teeth1;  // 20
  const int z2 = c.gears.teeth2;  // 80
  struct Expected {
    std::vector<ToothFault> faults;
    const char* kind;
    double revolutions;
    long long mesh_periods;
  };
  ToothFault wheel_tooth = cracked_pinion_tooth();
  wheel_tooth.gear = Gear::two;
  // Healthy: gcd(z1, 2, 4) = 2, half a revolution. A cracked pinion tooth: a / b = 1 / 1, one
  // revolution. A cracked wheel tooth: z2 / z1 = 4 / 1, four revolutions (the wheel's one).
  for (const Expected& e :
       {Expected{{}, "mesh+driver", 0.5, z1 / 2},
        Expected{{cracked_pinion_tooth()}, "pinion-revolution+driver", 1.0, z1},
        Expected{{wheel_tooth}, "wheel-revolution+driver", 4.0, z2},
        Expected{{cracked_pinion_tooth(), wheel_tooth}, "hunting+driver", 4.0, z2}}) {
    CAPTURE(e.kind);
    c.faults = e.faults;
    const SteadyTiming timing = steady_timing(c, table, SteadySettings{});
    CHECK(timing.kind == e.kind);
    CHECK(timing.mesh_periods == e.mesh_periods);
    CHECK(std::fabs(timing.excitation_period_s / (2.0 * pi * e.revolutions / w) - 1.0) < 1e-14);
  }
}

TEST_CASE("a pitch error on one pinion tooth: a pinion revolution, and the point is periodic") {
  // A tooth error that differs from tooth to tooth repeats after the true period as a fault
  // does: pinion tooth 3 lags 2 um, the others none.
  SimulationCase c = loaded_paper_pair(2000.0);
  c.name = "pitch-error";
  c.modifications.gear1.pitch_m.assign(static_cast<std::size_t>(c.gears.teeth1), 0.0);
  c.modifications.gear1.pitch_m[3] = 2e-6;
  const StiffnessTable table(c.gears, c.model.stiffness);
  const SteadyTiming timing = steady_timing(c, table, SteadySettings{});
  CHECK(timing.kind == "pinion-revolution");
  CHECK(timing.mesh_periods == c.gears.teeth1);
  CHECK(std::fabs(timing.excitation_period_s / (c.gears.teeth1 * mesh_period_s(c)) - 1.0) < 1e-14);
  // One value on every tooth repeats every mesh period.
  SimulationCase even = c;
  even.modifications.gear1.pitch_m.assign(static_cast<std::size_t>(c.gears.teeth1), 2e-6);
  CHECK(steady_timing(even, table, SteadySettings{}).kind == "mesh");

  SteadySweepSpec spec;
  spec.base = c;
  spec.vary = "initial.w1";
  spec.from_si = 2000.0;
  spec.to_si = 2000.0;
  spec.points = 1;
  spec.directions = {SweepDirection::up};
  spec.threads = 1;
  const SteadySweep sweep = run_steady_sweep(spec);
  CHECK(sweep.spec.poincare_period_kind == "pinion-revolution");
  REQUIRE(sweep.rows.size() == 1u);
  const SteadyPoint& point = sweep.rows[0].point;
  MESSAGE(point.explanation << " after " << point.periods_run << " periods");
  CHECK(point.verdict == PeriodicityVerdict::periodic);
  CHECK(point.period == 1);
}
