// The two readings of the mesh force (docs/model.md, section Energies): the
// Newtonian F = Ke delta of the paper and the Lagrangian one derived from
// V = 1/2 Ke(theta1) delta^2. Expected values come from the energy, an
// integral of the recorded series with the table's derivative, and the
// constant-stiffness limit where the two are one, never from earlier output.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/table.hpp"

using namespace gearimpact;

namespace {

// Kinetic plus stored energy of a row, computed here from the state: the
// loaded pairs of (42) at theta1 and 1/2 Ke(X) delta^2 each, Ke from the
// table the run used.
struct EnergyProbe {
  const SimulationCase& c;
  const StiffnessTable& table;
  double j1 = moment_of_inertia(c.gears, Gear::one);
  double j2 = moment_of_inertia(c.gears, Gear::two);

  double kinetic(const SeriesRow& row) const {
    return 0.5 * j1 * row.w1_rad_per_s * row.w1_rad_per_s +
           0.5 * j2 * row.w2_rad_per_s * row.w2_rad_per_s;
  }
  // The loaded pairs of the row's region.
  LoadedPairs pairs(const SeriesRow& row) const {
    if (row.region == static_cast<int>(Region::free)) return {};
    return loaded_pairs(c.gears, static_cast<Region>(row.region), row.theta1_rad,
                        c.model.coast_phase);
  }
  double stored(const SeriesRow& row) const {
    const LoadedPairs p = pairs(row);
    double u = 0.0;
    for (std::size_t j = 0; j < p.count; ++j) {
      u += 0.5 * table.stiffness_and_derivative(p.position_m[j]).stiffness_n_per_m * row.delta_m *
           row.delta_m;
    }
    return u;
  }
  // d/dt of the stored energy at fixed delta: sum 1/2 dKe/dX dX/dt delta^2,
  // dX/dt = +-Rb1 w1 on N1 / N2.
  double stiffness_power(const SeriesRow& row) const {
    const LoadedPairs p = pairs(row);
    const double x_rate = (row.region == static_cast<int>(Region::n1) ? 1.0 : -1.0) *
                          base_radius(c.gears, Gear::one) * row.w1_rad_per_s;
    double power = 0.0;
    for (std::size_t j = 0; j < p.count; ++j) {
      power += 0.5 * table.stiffness_and_derivative(p.position_m[j]).derivative_n_per_m2 *
               row.delta_m * row.delta_m * x_rate;
    }
    return power;
  }
};

// Case 1's pair without damping, friction or torques: rolling at w1 with the
// relative mode started from a deflection delta0 on N1, so that it rattles
// through the backlash on both lines, while pairs enter and leave under load.
SimulationCase conservative_case(double w1, double step_s, double end_time_s) {
  SimulationCase c = paper_case(1);
  c.model.friction_coefficient = 0.0;
  c.model.damping_update = DampingUpdate::off;
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  constexpr double delta0_m = 5e-6;
  c.initial.theta1_rad = (c.gears.backlash_m + delta0_m) / rb1;
  c.initial.theta2_rad = 0.0;
  c.initial.w1_rad_per_s = w1;
  c.initial.w2_rad_per_s = w1 * rb1 / rb2;
  c.integrator.step_s = step_s;
  c.integrator.end_time_s = end_time_s;
  return c;
}

double mesh_period_s(const SimulationCase& c, double w1) {
  return 2.0 * pi / (c.gears.teeth1 * w1);
}

}  // namespace

TEST_CASE("lagrangian: kinetic + stored energy conserved over 1000 mesh cycles, order 4") {
  // w1 = 2000 rad/s: a mesh period of 157 us; 1000 of them at h = 1 us and
  // 0.5 us, every pair entry and exit an impulse on the pinion.
  constexpr double w1 = 2000.0;
  const double end = 1000.0 * mesh_period_s(paper_case(1), w1);
  double errors[2] = {0.0, 0.0};
  int index = 0;
  for (double h : {1e-6, 0.5e-6}) {
    SimulationCase c = conservative_case(w1, h, end);
    c.model.mesh_force = MeshForce::lagrangian;
    const StiffnessTable table(c.gears, c.model.stiffness);
    RunControl control;
    control.keep_series = true;
    const SimulationResult r = simulate(c, table, control);
    REQUIRE(r.summary.impacts_n1 > 100);
    REQUIRE(r.summary.impacts_n2 > 100);
    const EnergyProbe probe{c, table};
    const double e0 = probe.kinetic(r.series.front()) + probe.stored(r.series.front());
    double worst = 0.0;
    for (const SeriesRow& row : r.series) {
      worst = std::max(worst, std::fabs(probe.kinetic(row) + probe.stored(row) - e0) / e0);
    }
    errors[index++] = worst;
    // The ledger closes with no parametric term: the forces did that work.
    CHECK(r.summary.parametric_work_j == 0.0);
    CHECK(r.summary.parametric_jump_work_j == 0.0);
    const double residual = r.summary.ledger_residual_max_j / r.summary.ledger_scale_j;
    MESSAGE("h = " << h << ": largest |E - E0| / E0 = " << worst << ", ledger residual " << residual
                   << ", " << r.summary.impacts_n1 + r.summary.impacts_n2 << " impacts, "
                   << r.summary.steps << " steps");
    // With nothing booked but kinetic and stored energy, the residual is
    // the energy error itself.
    CHECK(residual <= 1.01 * worst + 1e-14);
  }
  const double ratio = errors[0] / errors[1];
  MESSAGE("error ratio under step halving " << ratio);
  // RK4 with every kink of the right-hand side stepped onto: global error
  // O(h^4), a ratio of 16 for the halving; the band allows the h^5 term at
  // omega h ~ 0.09 of the stiffest contact.
  CHECK(ratio > 12.0);
  CHECK(ratio < 40.0);
}

TEST_CASE("newtonian: the parametric work is the integral of 1/2 dKe/dtheta1 delta^2 plus jumps") {
  constexpr double w1 = 2000.0;
  constexpr double h = 0.1e-6;
  SimulationCase c = conservative_case(w1, h, 40.0 * mesh_period_s(paper_case(1), w1));
  const StiffnessTable table(c.gears, c.model.stiffness);
  RunControl control;
  control.keep_series = true;
  const SimulationResult r = simulate(c, table, control);
  const EnergyProbe probe{c, table};
  const double rb1 = base_radius(c.gears, Gear::one);
  const double xs = table.domain_start_m();
  const double xe = table.domain_end_m();
  // Ke and dKe/dX of pairs at `x` (Ke continued along its tangent a hair
  // beyond the segment, as the right-hand side does), with delta and w1.
  const auto stored = [&](const std::vector<double>& x, double delta) {
    double u = 0.0;
    for (double xj : x) {
      u += 0.5 * table.stiffness_and_derivative(std::clamp(xj, xs, xe)).stiffness_n_per_m * delta *
           delta;
    }
    return u;
  };
  const auto power = [&](const std::vector<double>& x, double delta, double x_rate) {
    double p = 0.0;
    for (double xj : x) {
      p += 0.5 * table.stiffness_and_derivative(std::clamp(xj, xs, xe)).derivative_n_per_m2 *
           delta * delta * x_rate;
    }
    return p;
  };
  // Route 2, from the series alone: the trapezoid rule over the rows; where
  // the loaded pairs differ between two rows, the interval is split where a
  // pair crosses X_start or X_end (theta1 linear in between), the state
  // interpolated linearly there, and the jump of 1/2 Ke delta^2 between the
  // old and the new pairs taken at that point.
  double continuous = 0.0;
  double jumps = 0.0;
  double scale = 0.0;
  int changes = 0;
  for (std::size_t i = 1; i < r.series.size(); ++i) {
    const SeriesRow& a = r.series[i - 1];
    const SeriesRow& b = r.series[i];
    const double dt = b.t_s - a.t_s;
    const double pa = probe.stiffness_power(a);
    const double pb = probe.stiffness_power(b);
    scale += 0.5 * (std::fabs(pa) + std::fabs(pb)) * dt;
    const LoadedPairs la = probe.pairs(a);
    const LoadedPairs lb = probe.pairs(b);
    const double line = b.region == static_cast<int>(Region::n1) ? 1.0 : -1.0;
    const double dx = line * rb1 * (b.theta1_rad - a.theta1_rad);
    const bool changed =
        a.region == b.region && b.region != static_cast<int>(Region::free) &&
        (la.count != lb.count || std::fabs(la.position_m[0] + dx - lb.position_m[0]) > 1e-9);
    if (!changed) {
      continuous += 0.5 * (pa + pb) * dt;
      continue;
    }
    ++changes;
    // The fraction of the interval where a pair of a leaves or one of b enters.
    double phi = 0.5;
    for (std::size_t j = 0; j < la.count; ++j) {
      for (double bound : {xs, xe}) {
        const double f = (bound - la.position_m[j]) / dx;
        if (f > 0.0 && f < 1.0) phi = f;
      }
    }
    for (std::size_t j = 0; j < lb.count; ++j) {
      for (double bound : {xs, xe}) {
        const double f = (bound - (lb.position_m[j] - dx)) / dx;
        if (f > 0.0 && f < 1.0) phi = f;
      }
    }
    std::vector<double> old_x;
    std::vector<double> new_x;
    for (std::size_t j = 0; j < la.count; ++j) old_x.push_back(la.position_m[j] + phi * dx);
    for (std::size_t j = 0; j < lb.count; ++j) new_x.push_back(lb.position_m[j] - (1 - phi) * dx);
    const double delta = a.delta_m + phi * (b.delta_m - a.delta_m);
    const double x_rate = line * rb1 * (a.w1_rad_per_s + phi * (b.w1_rad_per_s - a.w1_rad_per_s));
    jumps += stored(new_x, delta) - stored(old_x, delta);
    continuous += 0.5 * phi * dt * (pa + power(old_x, delta, x_rate)) +
                  0.5 * (1.0 - phi) * dt * (power(new_x, delta, x_rate) + pb);
  }
  const double booked_continuous = r.summary.parametric_work_j - r.summary.parametric_jump_work_j;
  MESSAGE("continuous part: ledger " << booked_continuous << " J, series " << continuous
                                     << " J (of |integrand| " << scale << " J); jumps: ledger "
                                     << r.summary.parametric_jump_work_j << " J, series " << jumps
                                     << " J, " << changes << " pair changes under load");
  REQUIRE(changes >= 5);
  REQUIRE(std::fabs(r.summary.parametric_jump_work_j) > 0.0);
  // The trapezoid rule's error is O((omega h)^2) of the integrand, omega h ~
  // 0.01 at h = 0.1 us, and O(omega h) of one interval where a contact
  // begins or ends (delta ~ 0 there, so little): 1e-3 of the integral of
  // |integrand| holds both; the jumps, interpolated to the crossing, likewise.
  CHECK(std::fabs(continuous - booked_continuous) <= 1e-3 * scale);
  CHECK(std::fabs(jumps - r.summary.parametric_jump_work_j) <=
        1e-3 * std::fabs(r.summary.parametric_jump_work_j));
}

TEST_CASE("with a constant mesh stiffness both forms are bit-identical") {
  SimulationCase c = paper_case(1);
  c.integrator.end_time_s = 3e-3;
  c.model.mesh_stiffness = MeshStiffnessMode::constant;
  c.model.constant_mesh_stiffness_n_per_m = 2e8;
  const SimulationResult newtonian = simulate(c);
  c.model.mesh_force = MeshForce::lagrangian;
  const SimulationResult lagrangian = simulate(c);
  REQUIRE(newtonian.series.size() == lagrangian.series.size());
  REQUIRE(newtonian.summary.impacts_n1 + newtonian.summary.impacts_n2 > 2);
  for (std::size_t i = 0; i < newtonian.series.size(); ++i) {
    const SeriesRow& a = newtonian.series[i];
    const SeriesRow& b = lagrangian.series[i];
    const bool same =
        a.t_s == b.t_s && a.theta1_rad == b.theta1_rad && a.theta2_rad == b.theta2_rad &&
        a.w1_rad_per_s == b.w1_rad_per_s && a.w2_rad_per_s == b.w2_rad_per_s &&
        a.delta_m == b.delta_m && a.normal_force_n == b.normal_force_n &&
        a.friction_force_n == b.friction_force_n && a.region == b.region && a.pairs == b.pairs;
    if (!same) FAIL("row " << i << " differs");
  }
  CHECK(newtonian.summary.damping_loss_j == lagrangian.summary.damping_loss_j);
  CHECK(newtonian.summary.friction_loss_j == lagrangian.summary.friction_loss_j);
  CHECK(newtonian.summary.impacts_n1 == lagrangian.summary.impacts_n1);
  CHECK(newtonian.summary.impacts_n2 == lagrangian.summary.impacts_n2);
}

TEST_CASE("the difference between the forms falls as the speed rises") {
  // Case 2's pair under a balanced load (T2 = -T1 Rb2/Rb1, T1 = 50 kgf mm),
  // rolling at w1 from the static deflection, the start's transient damped by
  // a viscous mesh damper (zeta = 0.05, D of (32) off), over 10 mesh cycles at
  // each speed. The stored energy's jumps and the extra torque's work per mesh
  // cycle do not depend on the speed and the pinion's kinetic energy grows as
  // w1^2: Oh, Grosh and Barber (2005) find the two forms apart at low speed.
  std::vector<double> differences;
  for (double w1 : {25.0, 50.0, 100.0, 200.0}) {
    SimulationCase c = paper_case(2);
    const StiffnessTable table(c.gears, c.model.stiffness);
    const double rb1 = base_radius(c.gears, Gear::one);
    const double rb2 = base_radius(c.gears, Gear::two);
    c.torque2.constant_n_m = -c.torque1.constant_n_m * rb2 / rb1;
    c.model.damping_update = DampingUpdate::off;
    c.model.mesh_damping_ratio = 0.05;
    const double static_deflection =
        c.torque1.constant_n_m / rb1 / mean_mesh_stiffness_n_per_m(c, table);
    c.initial.theta1_rad = (c.gears.backlash_m + static_deflection) / rb1;
    c.initial.w1_rad_per_s = w1;
    c.initial.w2_rad_per_s = rb1 * w1 / rb2;
    c.integrator.end_time_s = 10.0 * mesh_period_s(c, w1);
    const SimulationResult newtonian = simulate(c, table);
    c.model.mesh_force = MeshForce::lagrangian;
    const SimulationResult lagrangian = simulate(c, table);
    REQUIRE(newtonian.series.size() == lagrangian.series.size());
    double most = 0.0;
    for (std::size_t i = 0; i < newtonian.series.size(); ++i) {
      most = std::max(
          most, std::fabs(newtonian.series[i].w1_rad_per_s - lagrangian.series[i].w1_rad_per_s));
    }
    differences.push_back(most / w1);
    MESSAGE("w1 = " << w1 << " rad/s: largest |w1_L - w1_N| / w1 = " << most / w1 << ", final w1 N "
                    << newtonian.summary.final_w1_rad_per_s << " L "
                    << lagrangian.summary.final_w1_rad_per_s << ", parametric work (N) "
                    << newtonian.summary.parametric_work_j << " J, impacts "
                    << newtonian.summary.impacts_n1 + newtonian.summary.impacts_n2);
  }
  for (std::size_t i = 1; i < differences.size(); ++i) CHECK(differences[i] < differences[i - 1]);
}

TEST_CASE(
    "a jump the pinion's kinetic energy cannot pay stops the run, naming time, pair, energies") {
  // Case 2's pair under its load at the static deflection, the pinion
  // creeping at 1e-4 rad/s (1.9 um/s on the line of action) with a pair
  // 1 nm before X_start: the pair enters under load within a millisecond,
  // and 1/2 Ke delta^2 of it is far more than J1 w1^2 / 2 ~ 1e-13 J.
  SimulationCase c = paper_case(2);
  const StiffnessTable table(c.gears, c.model.stiffness);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  c.torque2.constant_n_m = -c.torque1.constant_n_m * rb2 / rb1;
  c.model.damping_update = DampingUpdate::off;
  c.model.mesh_damping_ratio = 0.05;
  // Without friction: at a creeping w1 the sliding speed reverses too often.
  c.model.friction_coefficient = 0.0;
  c.model.mesh_force = MeshForce::lagrangian;
  const MeshLayout layout(c.gears, c.model.coast_phase);
  const double x0 = layout.reference_m(Region::n1, 0.0);
  const double k = std::floor((layout.start_m() - x0) / layout.base_pitch_m());
  c.initial.theta1_rad = (layout.start_m() - 1e-9 - x0 - k * layout.base_pitch_m()) / rb1;
  const double static_deflection =
      c.torque1.constant_n_m / rb1 / mean_mesh_stiffness_n_per_m(c, table);
  c.initial.theta2_rad =
      (rb1 * c.initial.theta1_rad - c.gears.backlash_m - static_deflection) / rb2;
  c.initial.w1_rad_per_s = 1e-4;
  c.initial.w2_rad_per_s = rb1 * 1e-4 / rb2;
  c.integrator.end_time_s = 2e-3;
  std::string message;
  try {
    simulate(c, table);
  } catch (const SimulationError& e) {
    message = e.what();
  }
  MESSAGE(message);
  CHECK(message.find("mesh_force = \"lagrangian\"") != std::string::npos);
  CHECK(message.find("t = ") != std::string::npos);
  CHECK(message.find("pair k = " + std::to_string(static_cast<int>(k)) + " of N1 enters") !=
        std::string::npos);
  CHECK(message.find("stored energy jumps by") != std::string::npos);
  CHECK(message.find("kinetic energy") != std::string::npos);
  // The Newtonian reading runs through the same entry, booking the jump.
  c.model.mesh_force = MeshForce::newtonian;
  CHECK(simulate(c, table).summary.parametric_jump_work_j > 0.0);
}

TEST_CASE("lagrangian: RK4 and the adaptive integrator agree on case 2") {
  // The impulses are applied at the located events of either integrator: the
  // two runs share no step, so their agreement checks where the jumps land.
  SimulationCase c = paper_case(2);
  c.integrator.end_time_s = 10e-3;
  c.model.mesh_force = MeshForce::lagrangian;
  RunControl control;
  control.keep_series = false;
  const SimulationSummary rk4 = simulate(c, control).summary;
  c.integrator.kind = IntegratorKind::adaptive;
  const SimulationSummary adaptive = simulate(c, control).summary;
  CHECK(rk4.impacts_n1 == adaptive.impacts_n1);
  CHECK(rk4.impacts_n2 == adaptive.impacts_n2);
  const auto relative = [](double a, double b) {
    return std::fabs(a - b) / std::max(std::fabs(a), std::fabs(b));
  };
  MESSAGE("damping loss " << rk4.damping_loss_j << " / " << adaptive.damping_loss_j
                          << " J, final w1 " << rk4.final_w1_rad_per_s << " / "
                          << adaptive.final_w1_rad_per_s << " rad/s");
  // The bound of the dynamics suite's comparison of the two integrators on
  // the Newtonian cases: both carry errors near 1e-9, and a jump paid at the
  // wrong place would move w1 by the jump's share of J1 w1^2 / 2, percents.
  CHECK(relative(rk4.damping_loss_j, adaptive.damping_loss_j) < 1e-6);
  CHECK(relative(rk4.final_w1_rad_per_s, adaptive.final_w1_rad_per_s) < 1e-6);
  CHECK(rk4.parametric_work_j == 0.0);
  CHECK(adaptive.parametric_work_j == 0.0);
}
