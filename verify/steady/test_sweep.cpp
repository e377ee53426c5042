// Sweeps of the steady state: the switch from no impact to single-sided impacts against the
// closed-form onset of contact loss (docs/steady-state.md section 3.2, derived here), and the
// hysteresis of a softening clearance oscillator swept up and down.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/sweep.hpp"
#include "relative.hpp"
#include "steady_cases.hpp"

using namespace gearimpact;
using namespace gearimpact::steady_test;
using gearimpact::verify::relative_difference;

namespace {

std::vector<SweepPointResult> sweep_frequency(const ClearanceCase& cc, double omega_from,
                                              double omega_to, int points,
                                              SweepDirection direction) {
  const double w_n = cc.w_rad_per_s;  // clearance_case(..., omega = 1) puts w at w_n
  const std::vector<double> grid =
      sweep_grid(omega_from * w_n, omega_to * w_n, points, "from", "to", "points");
  auto table = std::make_shared<const StiffnessTable>(cc.c.gears, cc.c.model.stiffness);
  return sweep_line(cc.c, [&](const SimulationCase&) { return table; }, "torque1.angular_frequency",
                    grid, direction, 0, SteadySettings{}, {});
}

}  // namespace

TEST_CASE("a sweep switches from NI to SS within one grid step of the closed-form onset") {
  const double zeta = 0.05;
  const double mean_force = 1.0;
  for (double r : {0.5, 0.8}) {
    CAPTURE(r);
    // A = F_m with A = F_a / sqrt((1 - Omega^2)^2 + (2 zeta Omega)^2), r = F_a / F_m:
    // (1 - u)^2 + 4 zeta^2 u = r^2 in u = Omega^2, u^2 - 2 B0 u + 1 - r^2 = 0 with
    // B0 = 1 - 2 zeta^2; the lower root is the onset on the way up.
    const double b0 = 1.0 - 2.0 * zeta * zeta;
    const double onset = std::sqrt(b0 - std::sqrt(b0 * b0 - 1.0 + r * r));
    const ClearanceCase cc = clearance_case(mean_force, r * mean_force, zeta, 1.0);
    // The onset falls between grid points, 0.35 of a step above one.
    const double from = onset - 0.193;
    const double to = onset + 0.107;
    const int points = 16;
    const double grid_step = (to - from) / (points - 1);
    const std::vector<SweepPointResult> up =
        sweep_frequency(cc, from, to, points, SweepDirection::up);
    int first_impacting = -1;
    for (const SweepPointResult& p : up) {
      REQUIRE(p.point.converged);
      if (p.point.regime != Regime::no_impact && first_impacting < 0) first_impacting = p.index;
    }
    REQUIRE(first_impacting > 0);
    const double w_n = cc.w_rad_per_s;
    const double switch_at = up[static_cast<std::size_t>(first_impacting)].value_si / w_n;
    const double last_ni = up[static_cast<std::size_t>(first_impacting - 1)].value_si / w_n;
    MESSAGE("r = " << r << ": onset Omega " << onset << ", last NI " << last_ni << ", first "
                   << to_string(up[static_cast<std::size_t>(first_impacting)].point.regime) << " "
                   << switch_at << ", grid step " << grid_step);
    CHECK(up[static_cast<std::size_t>(first_impacting)].point.regime == Regime::single_sided);
    // The switch brackets the onset: the last NI point below it, the first SS point at most one
    // grid step above (1e-12 for the rounding of the grid values).
    CHECK(last_ni <= onset + 1e-12);
    CHECK(switch_at >= onset - 1e-12);
    CHECK(switch_at - onset <= grid_step * (1.0 + 1e-9));
  }
}

TEST_CASE("up and down sweeps of a softening case jump at different frequencies") {
  // F_m = 1, r = 0.5, zeta = 0.05: losing contact softens the mesh, the resonance bends to
  // lower frequencies and two stable branches coexist over a band (Comparin and Singh 1989).
  const ClearanceCase cc = clearance_case(1.0, 0.5, 0.05, 1.0);
  const int points = 41;
  const std::vector<SweepPointResult> up =
      sweep_frequency(cc, 0.7, 1.3, points, SweepDirection::up);
  const std::vector<SweepPointResult> down =
      sweep_frequency(cc, 0.7, 1.3, points, SweepDirection::down);
  // The largest change of the amplitude between neighbouring points of each sweep, in the
  // order the sweep visits them: the jump.
  const auto jump = [](const std::vector<SweepPointResult>& s) {
    std::size_t at = 1;
    double largest = 0.0;
    for (std::size_t i = 1; i < s.size(); ++i) {
      REQUIRE(s[i].point.converged);
      REQUIRE(s[i - 1].point.converged);
      const double change =
          std::fabs(*s[i].point.dte_amplitude_m - *s[i - 1].point.dte_amplitude_m);
      if (change > largest) {
        largest = change;
        at = i;
      }
    }
    return std::pair<std::size_t, double>{at, largest};
  };
  const auto [up_at, up_size] = jump(up);
  const auto [down_at, down_size] = jump(down);
  const double w_n = cc.w_rad_per_s;
  const double b = cc.c.gears.backlash_m;
  const double up_from = up[up_at - 1].value_si / w_n;
  const double up_to = up[up_at].value_si / w_n;
  const double down_from = down[down_at - 1].value_si / w_n;
  const double down_to = down[down_at].value_si / w_n;
  MESSAGE("up: jump of " << up_size / b << " B between Omega " << up_from << " and " << up_to
                         << "; down: jump of " << down_size / b << " B between Omega " << down_from
                         << " and " << down_to);
  // A jump is a change far above the smooth change between grid points (the amplitude is of
  // order B here, a grid step moves it by a few per cent of B away from the jump).
  CHECK(up_size > 0.2 * b);
  CHECK(down_size > 0.2 * b);
  // Hysteresis: the two jumps lie in disjoint grid intervals (at most a shared end).
  const bool disjoint = std::max(down_from, down_to) <= std::min(up_from, up_to) ||
                        std::max(up_from, up_to) <= std::min(down_from, down_to);
  CHECK(disjoint);
}

TEST_CASE("bad sweep input is refused with the key") {
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(message([] { sweep_grid(1.0, 2.0, 0, "--from", "--to", "--points"); }).find("--points") !=
        std::string::npos);
  CHECK(message([] { sweep_field("torque1.nonsense", "--vary"); }).find("torque1.nonsense") !=
        std::string::npos);
  // A choice is not a value along a line.
  CHECK(message([] { sweep_field("model.damping_update", "--vary"); }).find("--vary") !=
        std::string::npos);
}

TEST_CASE("a sweep sets any numeric schema key, a constant torque's mean its value") {
  SimulationCase c = paper_case(1);
  set_sweep_value(c, "gears.face_width", 0.011);
  CHECK(c.gears.face_width_m == 0.011);
  set_sweep_value(c, "torque1.mean", 2.5);
  CHECK(c.torque1.kind == Torque::Kind::constant);
  CHECK(c.torque1.constant_n_m == 2.5);
  set_field(c, "torque1.kind", "sinusoidal");
  set_sweep_value(c, "torque1.mean", 1.5);
  CHECK(c.torque1.mean_n_m == 1.5);
  // The balance companion moves the other mean: T1/Rb1 + T2/Rb2 = 0.
  const SimulationCase base = c;
  apply_sweep_value(c, base, "torque1.mean", 3.0);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  // Two roundings in -T1 Rb2/Rb1 and one in each quotient: a few ulps of T/Rb.
  CHECK(std::fabs(c.torque1.mean_n_m / rb1 + c.torque2.constant_n_m / rb2) <=
        1e-15 * std::fabs(c.torque1.mean_n_m / rb1));
  // The schema's range holds: a negative backlash is refused naming the key.
  CHECK_THROWS_AS(set_sweep_value(c, "gears.backlash", -1e-6), InputError);
}

TEST_CASE("the planar model's sweep on stiff bearings is the torsional sweep, jumps included") {
  // The softening case above on a coarser grid, once on rigid bearings (the torsional model, 2
  // DOF) and once on elastic bearings of k_b = 1e11 N/m per direction (the planar model, 6 DOF
  // with both lines of action): the torsional model is the planar one's limit k_b -> infinity.
  const ClearanceCase cc = clearance_case(1.0, 0.5, 0.05, 1.0);
  SimulationCase planar = cc.c;
  const double kb = 1e11;
  planar.bearings.kind = BearingKind::elastic;
  planar.bearings.gear1.stiffness_x_n_per_m = kb;
  planar.bearings.gear2.stiffness_x_n_per_m = kb;
  // Each bearing mode damped at 5 %, c = 0.1 sqrt(k_b m) with the gear's mass (the disc's):
  // the centres' ringing settles, so that the Poincare samples, which hold the centres' motion
  // too, repeat.
  const PlanarMounting mounting = planar_mounting(planar);
  planar.bearings.gear1.damping_x_n_s_per_m = 0.1 * std::sqrt(kb * mounting.mass_kg[0]);
  planar.bearings.gear2.damping_x_n_s_per_m = 0.1 * std::sqrt(kb * mounting.mass_kg[1]);
  const double w_n = cc.w_rad_per_s;
  const std::vector<double> grid = sweep_grid(0.76 * w_n, 1.24 * w_n, 7, "from", "to", "points");
  const auto run = [&](const SimulationCase& c, SweepDirection d) {
    auto table = std::make_shared<const StiffnessTable>(c.gears, c.model.stiffness);
    return sweep_line(c, [&](const SimulationCase&) { return table; }, "torque1.angular_frequency",
                      grid, d, 0, SteadySettings{}, {});
  };
  // The bearings add their compliance to the mesh's along the line of action: quasi-statically
  // (the excitation far below the bearing modes, sqrt(k_b / m) ~ 1e6 rad/s against w_n ~ 3e4
  // rad/s) the mesh stiffness k becomes k / (1 + eps), eps = k (1/k_b1 + 1/k_b2) = 4e-3, and
  // w_n moves by eps / 2. A linear oscillator's amplitude moves with w_n by at most 1/(2 zeta)
  // of that, relative (the largest |d ln A / d ln w_n| of A = 1 / sqrt((1 - W^2)^2 + (2 zeta
  // W)^2)): eps / (4 zeta) = 2e-2. The contact's nonlinearity steepens the branches near the
  // jumps: twice that bound, 4e-2. The integrators' own errors are far below it: the torsional
  // RK4 runs 20+ steps per contact period (phase error about 1e-4 a period), the planar one many
  // more (its step resolves the bearings). Stiffer bearings tighten the bound in proportion, at
  // the cost of a step shorter by sqrt(k_b): 1e11 N/m keeps the test within a second.
  const double eps = 2.0 * cc.stiffness_n_per_m / kb;
  const double zeta = 0.05;
  const double tolerance = 2.0 * eps / (4.0 * zeta);
  double largest = 0.0;
  double largest_mean = 0.0;
  for (SweepDirection d : {SweepDirection::up, SweepDirection::down}) {
    const std::vector<SweepPointResult> torsional = run(cc.c, d);
    const std::vector<SweepPointResult> elastic = run(planar, d);
    REQUIRE(torsional.size() == elastic.size());
    for (std::size_t i = 0; i < torsional.size(); ++i) {
      const SteadyPoint& t = torsional[i].point;
      const SteadyPoint& p = elastic[i].point;
      CAPTURE(to_string(d));
      CAPTURE(torsional[i].value_si / w_n);
      REQUIRE(t.converged);
      REQUIRE(p.converged);
      CHECK(p.period == t.period);
      CHECK(p.regime == t.regime);
      const double a = relative_difference(*p.dte_amplitude_m, *t.dte_amplitude_m);
      const double r = relative_difference(*p.dte_rms_m, *t.dte_rms_m);
      const double m = relative_difference(*p.dte_mean_m, *t.dte_mean_m);
      CHECK(a <= tolerance);
      CHECK(r <= tolerance);
      // The mean of s: B and the static deflection F_m / k, which s_d holds in both models (the
      // bearings' share of the compliance moves the centres, and s_d adds their motion).
      CHECK(m <= tolerance);
      largest = std::max({largest, a, r});
      largest_mean = std::max(largest_mean, m);
    }
    // The jump: the largest change of the amplitude between neighbouring points, in the same
    // grid interval on both models.
    const auto jump_at = [](const std::vector<SweepPointResult>& s) {
      std::size_t at = 1;
      double most = 0.0;
      for (std::size_t i = 1; i < s.size(); ++i) {
        const double change =
            std::fabs(*s[i].point.dte_amplitude_m - *s[i - 1].point.dte_amplitude_m);
        if (change > most) {
          most = change;
          at = i;
        }
      }
      return at;
    };
    CHECK(jump_at(elastic) == jump_at(torsional));
  }
  MESSAGE("planar against torsional: amplitude and RMS within "
          << largest << ", mean within " << largest_mean << " (bound " << tolerance << ")");
}
