// Sweeps of the steady state: the switch from no impact to single-sided impacts against the
// closed-form onset of contact loss (docs/steady-state.md section 3.2, derived here), and the
// hysteresis of a softening clearance oscillator swept up and down.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/sweep.hpp"
#include "steady_cases.hpp"

using namespace gearimpact;
using namespace gearimpact::steady_test;

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
