// The dynamics against invariants, closed forms and an independent integrator:
// the dynamics part of docs/model.md. Every expected value comes from an equation, a limit
// or the other integrator, never from this code's own earlier output.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "../../lib/src/dynamics/event_location.hpp"
#include "gearimpact/batch/sweep_friction.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/named_values.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/table.hpp"

using namespace gearimpact;

namespace {

double relative_difference(double a, double b) {
  const double scale = std::max(std::fabs(a), std::fabs(b));
  return scale == 0.0 ? 0.0 : std::fabs(a - b) / scale;
}

SimulationCase short_case(int number, double end_time_s, double step_s = 1e-7) {
  SimulationCase c = paper_case(number);
  c.integrator.end_time_s = end_time_s;
  c.integrator.step_s = step_s;
  return c;
}

RunControl summary_only() {
  RunControl control;
  control.keep_series = false;
  return control;
}

// Mesh stiffness for the constant-stiffness variant, of the order of Ke (N/m).
constexpr double kConstantStiffness = 2.0e8;

// The conservative variant: e = 1 (c = 0 in (33), so D = 0), f = 0, constant mesh stiffness.
SimulationResult conservative_run(double step_s, bool locate_events, double end_time_s) {
  SimulationCase c = short_case(1, end_time_s, step_s);
  c.model.friction_coefficient = 0.0;
  c.model.restitution.coefficient = 0.0;
  c.model.mesh_stiffness = MeshStiffnessMode::constant;
  c.model.constant_mesh_stiffness_n_per_m = kConstantStiffness;
  RunControl control = summary_only();
  control.locate_events = locate_events;
  return simulate(c, control);
}

}  // namespace

TEST_CASE("with f = 0 and no torques J1 w1/Rb1 + J2 w2/Rb2 is conserved to round-off") {
  // The normal force acts on both gears along the line of action with arms
  // Rb1 and Rb2 and opposite signs, (1)-(3): d/dt (J1 w1/Rb1 + J2 w2/Rb2) = 0.
  SimulationCase c = short_case(1, 3e-3);
  c.model.friction_coefficient = 0.0;
  const SimulationResult r = simulate(c);
  REQUIRE(r.summary.impacts_n1 + r.summary.impacts_n2 >= 4);
  const GearPair& g = c.gears;
  const double a1 = moment_of_inertia(g, Gear::one) / base_radius(g, Gear::one);
  const double a2 = moment_of_inertia(g, Gear::two) / base_radius(g, Gear::two);
  const double p0 = a1 * c.initial.w1_rad_per_s + a2 * c.initial.w2_rad_per_s;
  double worst = 0.0;
  for (const SeriesRow& row : r.series) {
    worst = std::max(worst,
                     std::fabs(a1 * row.w1_rad_per_s + a2 * row.w2_rad_per_s - p0) / std::fabs(p0));
  }
  // RK4 keeps linear invariants exactly in exact arithmetic; what is left is the
  // rounding of each step's update, at most a few eps per step: 4 eps x steps.
  const double bound =
      4.0 * std::numeric_limits<double>::epsilon() * static_cast<double>(r.summary.steps);
  MESSAGE("largest relative change " << worst << ", bound " << bound);
  CHECK(worst <= bound);
}

TEST_CASE("conservative variant: energy conserved to RK4 accuracy, observed order 4") {
  // Reference: the same problem at a step 64 times smaller, whose own error is
  // 64^4 ~ 1.7e7 times smaller than that of the coarsest step compared.
  const double end = 1e-3;
  const SimulationResult reference = conservative_run(end / 64000.0, true, end);
  const double w_ref = reference.summary.final_w1_rad_per_s;
  const double e0 = reference.summary.kinetic_energy_initial_j;
  double previous_error = 0.0;
  for (double h : {1e-6, 5e-7, 2.5e-7}) {
    const SimulationResult r = conservative_run(h, true, end);
    CHECK(r.summary.impacts_n1 + r.summary.impacts_n2 ==
          reference.summary.impacts_n1 + reference.summary.impacts_n2);
    const double error = std::fabs(r.summary.final_w1_rad_per_s - w_ref);
    const double energy_error =
        std::fabs(r.summary.kinetic_energy_final_j + r.summary.stored_energy_final_j - e0) / e0;
    // RK4 on an oscillator loses energy as (w h)^6/72 per step, w ~ 6e4 rad/s
    // here: at most ~2e-5 of E0 over the run even at h = 1e-6.
    CHECK(energy_error < 2e-5);
    if (previous_error > 0.0) {
      const double order = std::log2(previous_error / error);
      MESSAGE("h = " << h << ": error " << error << ", observed order " << order);
      // Step halving from h w ~ 0.06 down: the leading h^4 term dominates within
      // +-0.6 (the first halving still carries some h^5).
      CHECK(order > 3.6);
      CHECK(order < 4.6);
    }
    previous_error = error;
  }
}

TEST_CASE("without cutting steps at events the error is orders of magnitude larger") {
  const double end = 1e-3;
  const SimulationResult reference = conservative_run(end / 64000.0, true, end);
  const double h = 2.5e-7;
  const SimulationResult cut = conservative_run(h, true, end);
  const SimulationResult straddled = conservative_run(h, false, end);
  const double w_ref = reference.summary.final_w1_rad_per_s;
  const double cut_error = std::fabs(cut.summary.final_w1_rad_per_s - w_ref);
  const double straddled_error = std::fabs(straddled.summary.final_w1_rad_per_s - w_ref);
  MESSAGE("error with the cut " << cut_error << ", without " << straddled_error);
  // A step straddling a kink of the right-hand side makes an O(h^2) local
  // error instead of O(h^5): at h w ~ 0.015 that is two orders or more.
  CHECK(straddled_error > 100.0 * cut_error);
}

TEST_CASE("full model: RK4 with located events keeps order 4") {
  // Case 1 over 1 ms: impacts on both lines, pairs entering and leaving,
  // friction reversing, damping recomputed at every impact.
  const double end = 1e-3;
  const auto run = [&](double h) { return simulate(short_case(1, end, h), summary_only()); };
  const SimulationResult reference = run(end / 200000.0);
  const double loss_ref = reference.summary.damping_loss_j;
  const double e1 = std::fabs(run(2.5e-7).summary.damping_loss_j - loss_ref);
  const double e2 = std::fabs(run(1.25e-7).summary.damping_loss_j - loss_ref);
  const double order = std::log2(e1 / e2);
  MESSAGE("damping loss errors " << e1 << ", " << e2 << ": observed order " << order);
  // In the asymptotic range (h w <= 0.03 for the stiffest contact).
  CHECK(order > 3.7);
  CHECK(order < 4.3);
}

TEST_CASE("the energy ledger closes on the three cases") {
  for (int n = 1; n <= 3; ++n) {
    CAPTURE(n);
    const SimulationSummary s = simulate(paper_case(n), summary_only()).summary;
    // The energy that passes through the run.
    const double throughput =
        s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
    // The smallest ledger term in these runs, the parametric work, is ~1e-4 of
    // the throughput: 1e-7 resolves it by three orders, while RK4's error at
    // h w ~ 0.01 is of order (h w)^4 ~ 1e-8 per contact period.
    const double bound = 1e-7 * throughput;
    MESSAGE("case " << n << ": residual " << s.ledger_residual_max_j << " J of " << throughput
                    << " J, parametric work " << s.parametric_work_j << " J");
    CHECK(s.ledger_residual_max_j < bound);
    CHECK(std::fabs(s.parametric_work_j) > 10.0 * bound);
    CHECK(s.damping_loss_j > 0.0);
    CHECK(s.friction_loss_j > 0.0);
  }
}

TEST_CASE("the energy ledger closes with the viscous mesh damper, whose loss it books") {
  for (int n = 1; n <= 3; ++n) {
    CAPTURE(n);
    SimulationCase c = paper_case(n);
    c.model.mesh_damping_ratio = 0.05;
    const SimulationSummary s = simulate(c, summary_only()).summary;
    const double throughput =
        s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
    // The bound of the run without the damper: the damper adds a smooth term,
    // its loss integrated by the same RK4 as the others.
    const double bound = 1e-7 * throughput;
    MESSAGE("case " << n << ": residual " << s.ledger_residual_max_j << " J of " << throughput
                    << " J, mesh damper loss " << s.mesh_damping_loss_j << " J");
    CHECK(s.ledger_residual_max_j < bound);
    // A loss the ledger could miss without failing would be below its bound:
    // the damper's loss must stand well above it to be tested at all.
    CHECK(s.mesh_damping_loss_j > 100.0 * bound);
  }
}

TEST_CASE("the mesh damper's loss equals c times the integral of s'^2 over the run") {
  // The run of the summary's example: no Hertzian damping, the damper alone
  // dissipates at the contacts. The reference integrates c s'^2, s' = Rb1 w1
  // - Rb2 w2, over the series of every step by the trapezoidal rule: an
  // independent quadrature of the kept states, where the ledger integrates
  // the power inside each RK4 step. The trapezoidal rule's error is
  // h^2 / 12 of the integral of (c s'^2)'' per unit time: with s' oscillating
  // at the contact's omega ~ 5e4 rad/s and h = 1e-7 s, (2 omega h)^2 / 12 ~
  // 1e-5 relative at most (observed far less); RK4's own error is (h
  // omega)^4 ~ 1e-9. Halving the rows (every other one) must grow the
  // trapezoid's difference about fourfold, its order.
  SimulationCase c = short_case(2, 5e-3);
  c.model.damping_update = DampingUpdate::off;
  c.model.mesh_damping_ratio = 0.05;
  const SimulationResult r = simulate(c);
  REQUIRE(r.summary.mesh_damper);
  const double damper =
      case_mesh_damping_n_s_per_m(c, StiffnessTable(c.gears, c.model.stiffness), nullptr);
  REQUIRE(damper > 0.0);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  const auto trapezoid = [&](std::size_t stride) {
    const auto power = [&](const SeriesRow& row) {
      const double rate = rb1 * row.w1_rad_per_s - rb2 * row.w2_rad_per_s;
      return damper * rate * rate;
    };
    double sum = 0.0;
    std::size_t last = 0;
    for (std::size_t i = stride; i < r.series.size(); i += stride) {
      sum += 0.5 * (r.series[i].t_s - r.series[last].t_s) *
             (power(r.series[i]) + power(r.series[last]));
      last = i;
    }
    if (last + 1 < r.series.size()) {
      const SeriesRow& end = r.series.back();
      sum += 0.5 * (end.t_s - r.series[last].t_s) * (power(end) + power(r.series[last]));
    }
    return sum;
  };
  const double loss = r.summary.mesh_damping_loss_j;
  const double fine = trapezoid(1);
  const double coarse = trapezoid(2);
  MESSAGE("mesh damper loss " << loss << " J, c = " << damper
                              << " N s/m; trapezoid's relative difference "
                              << relative_difference(loss, fine) << " (every other row "
                              << relative_difference(loss, coarse) << ")");
  CHECK(relative_difference(loss, fine) < 1e-5);
  const double ratio = std::fabs(coarse - loss) / std::fabs(fine - loss);
  CHECK(ratio > 3.0);
  CHECK(ratio < 5.0);
  // The ledger closes with it, and would not without it.
  const SimulationSummary& s = r.summary;
  const double throughput =
      s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
  const double closure = s.kinetic_energy_final_j + s.stored_energy_final_j -
                         s.kinetic_energy_initial_j - s.stored_energy_initial_j - s.torque_work_j +
                         s.damping_loss_j + s.friction_loss_j + s.mesh_damping_loss_j -
                         s.parametric_work_j;
  CHECK(s.damping_loss_j == 0.0);
  CHECK(std::fabs(closure) < 1e-7 * throughput);
  CHECK(s.mesh_damping_loss_j > 100.0 * 1e-7 * throughput);
}

TEST_CASE("the damping update policies set D from Vi, from the reference speed, or not at all") {
  SimulationCase c = short_case(2, 5e-3);
  c.model.friction_coefficient = 0.0;
  RunControl control = summary_only();
  c.model.damping_update = DampingUpdate::frozen;
  c.model.damping_reference_speed_m_s = 0.5;
  const SimulationResult frozen = simulate(c, control);
  REQUIRE(frozen.impacts.size() >= 2);
  // (33) at V_ref for every impact, whatever its own Vi.
  const double e_ref = 1.0 - 0.022 * std::pow(0.5 / 1e-3, 0.375);
  for (const ImpactRecord& impact : frozen.impacts) {
    CHECK(std::fabs(impact.restitution - e_ref) <= 1e-15);
  }
  CHECK(frozen.impacts[0].impact_speed_m_s != frozen.impacts[1].impact_speed_m_s);
  c.model.damping_update = DampingUpdate::off;
  const SimulationSummary off = simulate(c, control).summary;
  // No Hertzian damping: the only loss left is friction, which is off too.
  CHECK(off.damping_loss_j == 0.0);
  CHECK(frozen.summary.damping_loss_j > 0.0);
}

TEST_CASE("RK4 and the adaptive Dormand-Prince integrator agree on the three cases") {
  for (int n = 1; n <= 3; ++n) {
    CAPTURE(n);
    SimulationCase c = paper_case(n);
    const SimulationSummary rk4 = simulate(c, summary_only()).summary;
    c.integrator.kind = IntegratorKind::adaptive;
    const SimulationSummary adaptive = simulate(c, summary_only()).summary;
    CHECK(rk4.impacts_n1 == adaptive.impacts_n1);
    CHECK(rk4.impacts_n2 == adaptive.impacts_n2);
    // Both integrators carry errors near 1e-9 (h w ~ 0.01 for RK4, rtol 1e-10
    // for dopri5); a missed or extra impact changes the losses by percents.
    const double bound = 1e-6;
    const double d_damping = relative_difference(rk4.damping_loss_j, adaptive.damping_loss_j);
    const double d_friction = relative_difference(rk4.friction_loss_j, adaptive.friction_loss_j);
    const double d_w1 = relative_difference(rk4.final_w1_rad_per_s, adaptive.final_w1_rad_per_s);
    const double d_w2 = relative_difference(rk4.final_w2_rad_per_s, adaptive.final_w2_rad_per_s);
    MESSAGE("case " << n << ": relative differences damping " << d_damping << ", friction "
                    << d_friction << ", w1 " << d_w1 << ", w2 " << d_w2);
    CHECK(d_damping < bound);
    CHECK(d_friction < bound);
    CHECK(d_w1 < bound);
    CHECK(d_w2 < bound);
  }
}

namespace {

// The damped contact alone, x'' = -(K x + D x x')/m, (30),(34) along the line
// of action. With v = x' and q = D/K: v dv/(1 + q v) = -(K/m) x dx, whose
// integral is (u - ln(1 + u))/q^2 = -(K/m) x^2/2 + const with u = q v. At onset
// and at separation x = 0, so u - ln(1 + u) takes the same value at both: the
// rebound u is the negative root, and the restitution -u_end/u_start depends on
// u_start = q Vi alone (not on m or K).
double closed_form_restitution(double u_impact) {
  const double level = u_impact - std::log1p(u_impact);
  double lo = -1.0 + 1e-15;  // u - ln(1 + u) -> inf as u -> -1
  double hi = 0.0;           // and is 0 at u = 0
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid - std::log1p(mid) > level) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return -0.5 * (lo + hi) / u_impact;
}

// (32), written out here from docs/model.md, independent of the library's version.
double d_over_k(DampingForm form, double e, double vi) {
  switch (form) {
    case DampingForm::herbert_mcwhannell:
      return 6.0 * (1.0 - e) / (((2.0 * e - 1.0) * (2.0 * e - 1.0) + 3.0) * vi);
    case DampingForm::hunt_crossley:
      return 3.0 * (1.0 - e) / (2.0 * vi);
    case DampingForm::lee_wang:
      return 3.0 * (1.0 - e) / (4.0 * vi);
  }
  return 0.0;
}

}  // namespace

TEST_CASE("one impact of the damped contact against its closed-form rebound") {
  for (DampingForm form :
       {DampingForm::herbert_mcwhannell, DampingForm::hunt_crossley, DampingForm::lee_wang}) {
    SimulationCase c = short_case(1, 1.2e-4);
    c.model.friction_coefficient = 0.0;
    c.model.damping_form = form;
    c.model.mesh_stiffness = MeshStiffnessMode::constant;
    c.model.constant_mesh_stiffness_n_per_m = kConstantStiffness;
    RunControl control = summary_only();
    const SimulationResult r = simulate(c, control);
    REQUIRE(!r.impacts.empty());
    const ImpactRecord& impact = r.impacts.front();
    REQUIRE(impact.end_speed_m_s.has_value());
    // Case 1 approaches at Rb1 w1(0) (gear 2 at rest, no torques).
    const double vi = base_radius(c.gears, Gear::one) * c.initial.w1_rad_per_s;
    CHECK(relative_difference(impact.impact_speed_m_s, vi) < 1e-12);
    // (33) with Vi in mm/s, p = 3/8, c = 0.022.
    const double target = 1.0 - 0.022 * std::pow(vi / 1e-3, 0.375);
    CHECK(relative_difference(impact.restitution, target) < 1e-14);
    const double realized = *impact.end_speed_m_s / impact.impact_speed_m_s;
    const double closed = closed_form_restitution(d_over_k(form, target, vi) * vi);
    MESSAGE("form " << static_cast<int>(form) << ": e(Vi) = " << target << ", realized " << realized
                    << ", closed form " << closed << ", approximation error " << closed - target);
    // RK4 at h w ~ 0.006 over one contact: relative error ~ (h w)^4 ~ 1e-9.
    CHECK(std::fabs(realized - closed) < 1e-8);
  }
  // Herbert and McWhannell's form is the one made for e far from 1 (e ~ 0.71
  // here): its realized restitution is nearer to e(Vi) than Hunt and Crossley's.
  const double vi = 0.9396926207859084;
  const double e = 1.0 - 0.022 * std::pow(vi / 1e-3, 0.375);
  const double hm = closed_form_restitution(d_over_k(DampingForm::herbert_mcwhannell, e, vi) * vi);
  const double hc = closed_form_restitution(d_over_k(DampingForm::hunt_crossley, e, vi) * vi);
  CHECK(std::fabs(hm - e) < std::fabs(hc - e));
}

TEST_CASE("the torsional run by the fixed-step Dormand-Prince: one undamped contact, order 5") {
  // The conservative variant (e = 1, f = 0, the constant stiffness k shared by
  // the loaded pairs: one linear spring while in contact). Case 1's pinion
  // strikes the wheel at rest at Vi = Rb1 w1(0), and delta then swings
  // through half a period of w = sqrt(k / m_e), m_e = 1 / (Rb1^2/J1 +
  // Rb2^2/J2): the contact lasts pi / w and the teeth part at Vi again.
  SimulationCase c = short_case(1, 1.2e-4);
  c.model.friction_coefficient = 0.0;
  c.model.restitution.coefficient = 0.0;
  c.model.mesh_stiffness = MeshStiffnessMode::constant;
  c.model.constant_mesh_stiffness_n_per_m = kConstantStiffness;
  const double w = std::sqrt(kConstantStiffness / effective_mass_kg(c.gears));
  const double vi = base_radius(c.gears, Gear::one) * c.initial.w1_rad_per_s;
  // The larger of the relative errors of the contact's duration and of its end speed.
  const auto error = [&](IntegratorKind kind, double h) {
    c.integrator.kind = kind;
    c.integrator.step_s = h;
    const SimulationResult r = simulate(c, summary_only());
    REQUIRE(!r.impacts.empty());
    const ImpactRecord& impact = r.impacts.front();
    REQUIRE(impact.end_s.has_value());
    CHECK(r.summary.integrator == name_of(kIntegratorKinds, kind));
    CHECK(relative_difference(impact.impact_speed_m_s, vi) < 1e-12);
    return std::max(std::fabs(w * (*impact.end_s - impact.start_s) - pi) / pi,
                    std::fabs(*impact.end_speed_m_s / vi - 1.0));
  };
  // h w = 0.06 and 0.03: in the asymptotic range of both methods, with the
  // errors (about 7e-10 and 2e-11 for Dormand-Prince) far above the round-off
  // (a few 1e-16 of the duration's events and speeds).
  const double h = 1e-6;
  REQUIRE(w * h < 0.07);
  const double dopri5 = error(IntegratorKind::dopri5, h);
  const double dopri5_half = error(IntegratorKind::dopri5, 0.5 * h);
  const double rk4 = error(IntegratorKind::rk4, h);
  const double order = std::log2(dopri5 / dopri5_half);
  MESSAGE("w h = " << w * h << ": Dormand-Prince errors " << dopri5 << ", " << dopri5_half
                   << " (observed order " << order << "), RK4's " << rk4);
  // Order 5 (the step and the event located on its order-4 continuous
  // extension both err by O(h^5)), within +-0.6 as the RK4 test above allows
  // for its order 4; and an order more than RK4 at the same step, whose error
  // is then larger by a factor of the order of 1/(w h) ~ 16 (160 here): at
  // least 4 times.
  CHECK(order > 4.4);
  CHECK(order < 5.6);
  CHECK(dopri5 < 0.25 * rk4);
}

TEST_CASE("friction: |Ff| = f N on a single loaded pair, and it dissipates") {
  SimulationCase c = short_case(2, 0.02);
  c.integrator.output_every = 10;
  const SimulationResult r = simulate(c);
  int single = 0;
  for (const SeriesRow& row : r.series) {
    if (row.pairs != 1 || row.normal_force_n <= 0.0) continue;
    ++single;
    // (35)-(38): Ff = +-f N, the rounding of one product.
    CHECK(std::fabs(std::fabs(row.friction_force_n) - 0.04 * row.normal_force_n) <=
          4.0 * std::numeric_limits<double>::epsilon() * row.normal_force_n);
  }
  CHECK(single > 100);
  CHECK(r.summary.friction_loss_j > 0.0);
}

TEST_CASE("bad input is refused with the field and its range") {
  const auto message_of = [](const SimulationCase& c) {
    try {
      validate(c);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SimulationCase c = paper_case(1);
  c.integrator.step_s = 1e-5;
  const std::string step = message_of(c);
  CHECK(step.find("step") != std::string::npos);
  CHECK(step.find(format_number(largest_resolving_step_s(c))) != std::string::npos);

  c = paper_case(1);
  c.model.friction_coefficient = -0.1;
  CHECK(message_of(c).find("friction") != std::string::npos);
  c = paper_case(1);
  c.integrator.end_time_s = 0.0;
  CHECK(message_of(c).find("end_time") != std::string::npos);
  c = paper_case(1);
  c.integrator.output_every = 0;
  CHECK(message_of(c).find("output_every") != std::string::npos);
  c = paper_case(1);
  c.initial.w1_rad_per_s = std::numeric_limits<double>::quiet_NaN();
  CHECK(message_of(c).find("w1") != std::string::npos);
  c = paper_case(1);
  c.model.restitution.exponent = 0.0;
  CHECK(message_of(c).find("restitution_exponent") != std::string::npos);
  c = paper_case(1);
  c.torque1.kind = Torque::Kind::user;
  CHECK(message_of(c).find("torque1.user") != std::string::npos);
  c = paper_case(1);
  c.gears.backlash_m = -1.0;
  CHECK(message_of(c).find("backlash") != std::string::npos);
}

TEST_CASE("check_run checks a run once: simulate, check_run and the table paths refuse alike") {
  // The key each public path names: simulate (which is check_run and the run), check_run, and
  // both with a table built for the case. Each bad input stands for one stage of the checks.
  const auto field_of = [](const auto& work) {
    try {
      work();
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  struct Bad {
    std::string key;
    void (*make)(SimulationCase&, RunControl&);
  };
  const std::vector<Bad> bad{
      // a row's range (validate_fields)
      {"model.friction_coefficient",
       [](SimulationCase& c, RunControl&) { c.model.friction_coefficient = -0.1; }},
      // the planar keys (refuse_planar_simulation): a tacho's edges are the planar run's only
      {"tacho.pulses_per_revolution",
       [](SimulationCase& c, RunControl&) { c.tacho.pulses_per_revolution = 4; }},
      // the gaps (validate_gaps): teeth a millimetre thicker on every flank press the drive and
      // the coast flanks at once within the paper's backlash
      {"gears.backlash",
       [](SimulationCase& c, RunControl&) {
         c.modifications.gear1.thickness_m.assign(static_cast<std::size_t>(c.gears.teeth1), -1e-3);
       }},
      // the controls: a series longer than the bound
      {"integrator.end_time",
       [](SimulationCase&, RunControl& control) {
         control.keep_series = true;
         control.most_series_rows = 10;
       }},
      // what the fields imply with the table (validate_implied): a step past the contact's
      {"integrator.step", [](SimulationCase& c, RunControl&) { c.integrator.step_s = 1e-5; }},
  };
  const SimulationCase base = short_case(1, 1e-4);
  const auto table = std::make_shared<const StiffnessTable>(base.gears, base.model.stiffness);
  for (const Bad& b : bad) {
    CAPTURE(b.key);
    SimulationCase c = base;
    RunControl control = summary_only();
    b.make(c, control);
    CHECK(field_of([&] { simulate(c, control); }) == b.key);
    CHECK(field_of([&] { check_run(c, control); }) == b.key);
    CHECK(field_of([&] { simulate(c, *table, control); }) == b.key);
    CHECK(field_of([&] { check_run(c, table, control); }) == b.key);
  }
  // A table of another pair is refused, naming it; the table given is the one the run uses.
  SimulationCase other = base;
  other.gears.teeth1 += 1;
  CHECK(field_of([&] { check_run(other, table); }) == "table");
  const CheckedRun checked = check_run(base, table, summary_only());
  CHECK(&checked.table() == table.get());

  // The program's warnings hook runs once, after the case's keys, fields and gaps pass and
  // before the checks that need the table: never for a case refused before it.
  int calls = 0;
  const auto count = [&calls] { ++calls; };
  check_run(base, summary_only(), count);
  CHECK(calls == 1);
  calls = 0;
  SimulationCase refused = base;
  refused.model.friction_coefficient = -0.1;
  CHECK_THROWS_AS(check_run(refused, summary_only(), count), InputError);
  CHECK(calls == 0);
  refused = base;
  refused.integrator.step_s = 1e-5;
  CHECK_THROWS_AS(check_run(refused, summary_only(), count), InputError);
  CHECK(calls == 1);
}

TEST_CASE("a diverging run stops with the time and step, never a NaN") {
  SimulationCase c = short_case(1, 1e-3);
  c.torque1.kind = Torque::Kind::user;
  c.torque1.user = [](double t) {
    return t < 2e-4 ? 0.0 : std::numeric_limits<double>::quiet_NaN();
  };
  for (IntegratorKind kind : {IntegratorKind::rk4, IntegratorKind::adaptive}) {
    c.integrator.kind = kind;
    try {
      simulate(c);
      FAIL("no error");
    } catch (const SimulationError& e) {
      const std::string what = e.what();
      CHECK(what.find("t = ") != std::string::npos);
      CHECK(what.find("step") != std::string::npos);
    }
  }
}

TEST_CASE("sweep_friction does not depend on the number of threads") {
  std::vector<SimulationCase> cases{short_case(1, 2e-3), short_case(2, 2e-3)};
  const std::vector<SweepRow> one = sweep_friction(cases, 0.01, 0.03, 0.01, 1);
  const std::vector<SweepRow> two = sweep_friction(cases, 0.01, 0.03, 0.01, 2);
  REQUIRE(one.size() == 3);
  REQUIRE(two.size() == 3);
  for (std::size_t i = 0; i < one.size(); ++i) {
    CHECK(one[i].friction_coefficient == two[i].friction_coefficient);
    for (std::size_t j = 0; j < cases.size(); ++j) CHECK(one[i].ratio[j] == two[i].ratio[j]);
  }
  CHECK(one.back().friction_coefficient == doctest::Approx(0.03).epsilon(1e-12));
}

TEST_CASE("a user torque function through the API: the same sine gives the same run") {
  // Case 3's T1 = A sin(W t) written as a user function must reproduce the
  // built-in sinusoid: the same doubles at the same times, so the same run.
  const SimulationCase builtin = short_case(3, 2e-3);
  SimulationCase user = builtin;
  const Torque sine = builtin.torque1;
  user.torque1 = Torque{};
  user.torque1.kind = Torque::Kind::user;
  user.torque1.user = [sine](double t) {
    return sine.amplitude_n_m * std::sin(sine.angular_frequency_rad_per_s * t + sine.phase_rad);
  };
  RunControl control;
  control.keep_series = false;
  const SimulationSummary a = simulate(builtin, control).summary;
  const SimulationSummary b = simulate(user, control).summary;
  CHECK(a.impacts_n1 + a.impacts_n2 > 0);
  CHECK(a.impacts_n1 == b.impacts_n1);
  CHECK(a.impacts_n2 == b.impacts_n2);
  CHECK(a.damping_loss_j == b.damping_loss_j);
  CHECK(a.torque_work_j == b.torque_work_j);
  CHECK(a.final_w1_rad_per_s == b.final_w1_rad_per_s);
}

TEST_CASE("torques: a mean plus harmonics, T = T_m + sum A_i sin(w_i t + phi_i)") {
  Torque h;
  h.kind = Torque::Kind::harmonic;
  h.mean_n_m = 2.0;
  h.harmonic_amplitudes_n_m = {0.5, -0.25};
  h.harmonic_angular_frequencies_rad_per_s = {1000.0, 3000.0};
  h.harmonic_phases_rad = {0.1, 0.2};
  const double t = 1.234e-3;
  const double expected =
      2.0 + 0.5 * std::sin(1000.0 * t + 0.1) - 0.25 * std::sin(3000.0 * t + 0.2);
  // The same sum in another order: a few roundings of terms of size 2.
  CHECK(std::fabs(torque_at(h, t) - expected) <=
        4.0 * std::numeric_limits<double>::epsilon() * 2.0);
  CHECK(mean_torque_n_m(h, "torque1") == 2.0);
  // One harmonic with its mean is the sinusoid with its mean, the same run.
  SimulationCase sine = short_case(3, 1e-3);
  sine.torque1.mean_n_m = 0.3;
  SimulationCase harmonic = sine;
  harmonic.torque1.kind = Torque::Kind::harmonic;
  harmonic.torque1.harmonic_amplitudes_n_m = {sine.torque1.amplitude_n_m};
  harmonic.torque1.harmonic_angular_frequencies_rad_per_s = {
      sine.torque1.angular_frequency_rad_per_s};
  harmonic.torque1.harmonic_phases_rad = {sine.torque1.phase_rad};
  const SimulationSummary a = simulate(sine, summary_only()).summary;
  const SimulationSummary b = simulate(harmonic, summary_only()).summary;
  CHECK(a.torque_work_j == b.torque_work_j);
  CHECK(a.final_w1_rad_per_s == b.final_w1_rad_per_s);
  // Harmonics of unequal length are refused naming the list that differs from the amplitudes.
  harmonic.torque1.harmonic_phases_rad.clear();
  try {
    validate(harmonic);
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("torque1.phases") != std::string::npos);
  }
  Torque user;
  user.kind = Torque::Kind::user;
  CHECK_THROWS_AS(mean_torque_n_m(user, "torque2"), InputError);
}

TEST_CASE("a run a thousand teeth on is the same run: pairs enter and leave at the same instants") {
  // Turning both gears by whole teeth (theta1 + n 2 pi / z1, theta2 + n 2 pi / z2) moves every
  // pair by n base pitches, so the motion in s is the same (42). Far from theta1 = 0 the mesh
  // positions are metres long (ref + k t0 with |ref| ~ 6 m for n = 1000), where the event
  // functions and the classification of the loaded pairs must round alike: when they did not,
  // a pair entered up to a step late now and then, and s differed by 4e-9 m (1e-4 B) within
  // 40 mesh periods. The paper's pair loaded with 1000 N, rolling at 7927 rad/s (NI, two pair
  // changes a mesh period), no friction, no Hertzian damping, zeta = 0.05.
  SimulationCase c = paper_case(1);
  c.model.friction_coefficient = 0.0;
  c.model.damping_update = DampingUpdate::off;
  c.model.mesh_damping_ratio = 0.05;
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  c.torque1 = Torque{};
  c.torque1.constant_n_m = 1000.0 * rb1;
  c.torque2 = Torque{};
  c.torque2.constant_n_m = -1000.0 * rb2;
  const double w1 = 7927.3;
  c.initial = InitialState{(c.gears.backlash_m + 1000.0 / 1e9) / rb1, 0.0, w1, w1 * rb1 / rb2};
  c.integrator.step_s = 2.0 * pi / (c.gears.teeth1 * w1) / 111.0;
  c.integrator.end_time_s = 40.0 * 2.0 * pi / (c.gears.teeth1 * w1);
  const SimulationResult near = simulate(c);
  SimulationCase far = c;
  const int teeth_on = 1000;
  far.initial.theta1_rad += teeth_on * 2.0 * pi / c.gears.teeth1;
  far.initial.theta2_rad += teeth_on * 2.0 * pi / c.gears.teeth2;
  const SimulationResult shifted = simulate(far);
  REQUIRE(near.series.size() == shifted.series.size());
  CHECK(near.summary.events == shifted.summary.events);
  double largest = 0.0;
  for (std::size_t i = 0; i < near.series.size(); ++i) {
    largest = std::max(largest, std::fabs(near.series[i].s_m - shifted.series[i].s_m));
    CHECK(near.series[i].pairs == shifted.series[i].pairs);
  }
  MESSAGE("largest difference in s: " << largest << " m; events " << near.summary.events << ", "
                                      << shifted.summary.events);
  // The shift itself rounds theta1 (~314 rad, spacing 5.7e-14 rad) and theta2: s starts apart by
  // ~1e-15 m, and each step rounds the larger angles about as much; a damped, stable motion
  // keeps that below 1e-13 m (5e-8 of the static deflection of 2e-6 m).
  CHECK(largest <= 1e-13);
}

// The run's event location (lib/src/dynamics/event_location.hpp, not a public
// header: the systems reach it through step_methods.hpp).
TEST_CASE("event location ends the step just past the first of several values that cross in it") {
  // Values falling linearly through zero at 0.7 and 0.3 of the step [0, 1]
  // (0.3 - t and 0.7 - t are exact near their roots, Sterbenz): the step
  // must end past 0.3, where the earlier one is negative, by no more than the
  // location's tolerance (4 eps of the step) and its bump past an exact zero
  // (4 eps again), whichever value comes first in the list.
  for (const bool early_first : {true, false}) {
    const double root[2] = {early_first ? 0.3 : 0.7, early_first ? 0.7 : 0.3};
    const double g_a[2] = {root[0], root[1]};
    const double g_b[2] = {root[0] - 1.0, root[1] - 1.0};
    const auto value = [&](double t, int i) { return root[i] - t; };
    const double t = gearimpact::earliest_event(0.0, 1.0, g_a, g_b, 2, value);
    CHECK(0.3 - t < 0.0);
    CHECK(t - 0.3 <= 8.0 * std::numeric_limits<double>::epsilon());
  }
  // A value that stays positive to the step's end is no event: the step is whole.
  const double g_a[2] = {0.5, 0.2};
  const double g_b[2] = {0.1, 0.3};
  CHECK(gearimpact::earliest_event(0.0, 1.0, g_a, g_b, 2, [](double, int) { return 1.0; }) == 1.0);
}
