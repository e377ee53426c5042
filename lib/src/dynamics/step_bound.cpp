#include "gearimpact/dynamics/step_bound.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <utility>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

namespace {

// Four significant digits: the numbers a message explains a bound with.
std::string digits(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

// The smallest and largest sum of Ke over the loaded pairs (42), sampled at 17
// positions along one base pitch, Ke(X) of one pair given by `ke`.
std::pair<double, double> total_stiffness_extremes(const SimulationCase& c,
                                                   const std::function<double(double)>& ke) {
  const GearPair& g = c.gears;
  const MeshLayout layout(g, c.model.coast_phase);
  const double t0 = layout.base_pitch_m();
  constexpr int samples = 16;
  double softest = std::numeric_limits<double>::infinity();
  double stiffest = 0.0;
  for (int i = 0; i <= samples; ++i) {
    const double u = layout.start_m() + t0 * i / samples;
    const LoadedRange range = layout.loaded(u);
    double total = 0.0;
    for (int k = range.k_first; k < range.k_first + range.count; ++k) {
      total += ke(layout.position_m(u, k));
    }
    softest = std::min(softest, total);
    stiffest = std::max(stiffest, total);
  }
  return {softest, stiffest};
}

// 1/steps of the period of the stiffest contact.
double largest_step(const SimulationCase& c, double stiffest,
                    double steps = kStepsPerContactPeriod) {
  const double period = 2.0 * pi / std::sqrt(stiffest * inverse_effective_mass_per_kg(c.gears));
  return period / steps;
}

// The peak |T(t)| of a torque and the key that sets most of it, w_s the
// gear's initial speed; a torque given as a function has no known peak (0, no key).
std::pair<double, std::string> torque_peak(const Torque& t, const std::string& section,
                                           double w_s) {
  switch (t.kind) {
    case Torque::Kind::constant:
      return {std::fabs(t.constant_n_m), section + ".value"};
    case Torque::Kind::sinusoidal: {
      const double mean = std::fabs(t.mean_n_m);
      const double amplitude = std::fabs(t.amplitude_n_m);
      return {mean + amplitude, section + (amplitude >= mean ? ".amplitude" : ".mean")};
    }
    case Torque::Kind::harmonic: {
      const double mean = std::fabs(t.mean_n_m);
      double amplitudes = 0.0;
      for (double a : t.harmonic_amplitudes_n_m) amplitudes += std::fabs(a);
      return {mean + amplitudes, section + (amplitudes >= mean ? ".amplitudes" : ".mean")};
    }
    case Torque::Kind::drag:
      // Its viscous part at the speed it starts from; the constant part is
      // at most drag_constant.
      return {std::fabs(t.drag_constant_n_m) + std::fabs(t.drag_viscous_n_m_s * w_s),
              section + (std::fabs(t.drag_constant_n_m) >= std::fabs(t.drag_viscous_n_m_s * w_s)
                             ? ".drag_constant"
                             : ".drag_viscous")};
    case Torque::Kind::profile: {
      double peak = 0.0;
      for (double v : t.profile_torques_n_m) peak = std::max(peak, std::fabs(v));
      return {peak, section + ".profile_torques"};
    }
    case Torque::Kind::induction_motor:
      // Kloss's law never exceeds its breakdown torque.
      return {std::fabs(t.breakdown_torque_n_m), section + ".breakdown_torque"};
    case Torque::Kind::user:
    case Torque::Kind::prescribed_speed:
    case Torque::Kind::speed_controlled:
      // A driver's or a controller's torque is whatever the mesh and the load
      // need: it has no peak of its own.
      break;
  }
  return {0.0, std::string()};
}

// The static deflection the torques imply: each torque's peak tooth load
// |T|/Rb over the smallest total mesh stiffness.
void validate_static_deflection(const SimulationCase& c, double softest) {
  const GearPair& g = c.gears;
  const double most = kMostStaticDeflectionPerModule * g.module_m;
  const std::array<std::pair<const Torque*, Gear>, 2> torques{
      {{&c.torque1, Gear::one}, {&c.torque2, Gear::two}}};
  for (std::size_t i = 0; i < torques.size(); ++i) {
    const auto [torque, gear] = torques[i];
    const std::string section = "torque" + std::to_string(i + 1);
    const double w = i == 0 ? c.initial.w1_rad_per_s : c.initial.w2_rad_per_s;
    const auto [peak, key] = torque_peak(*torque, section, w);
    const double rb = base_radius(g, gear);
    const double load = peak / rb;
    if (load <= most * softest) continue;
    const double deflection = load / softest;
    const std::string n = std::to_string(i + 1);
    throw InputError(
        key, digits(peak) + " N*m",
        "a peak |T" + n + "| <= " + digits(most * softest * rb) + " N*m: its tooth load |T" + n +
            "|/Rb" + n + " = " + digits(load) + " N over the smallest mesh stiffness " +
            digits(softest) + " N/m is a static deflection of " +
            (std::isfinite(deflection) ? digits(deflection) + " m" : "more than any double") +
            ", above " + digits(kMostStaticDeflectionPerModule) + " module = " + digits(most) +
            " m, where the linear-elastic tooth model no longer holds; lower the torque, or "
            "stiffen the pair (gears.youngs_modulus = " +
            digits(g.youngs_modulus_pa) + " Pa, gears.face_width = " + digits(g.face_width_m) +
            " m)");
  }
}

// Each gear's initial speed against the step: at least kStepsPerMeshPeriod
// steps per mesh period 2 pi / (z |w|).
void validate_speeds(const SimulationCase& c) {
  const double step = c.integrator.step_s;
  const std::array<std::pair<int, double>, 2> gears{
      {{c.gears.teeth1, c.initial.w1_rad_per_s}, {c.gears.teeth2, c.initial.w2_rad_per_s}}};
  for (std::size_t i = 0; i < gears.size(); ++i) {
    const auto [teeth, w] = gears[i];
    // The speed at which largest_mesh_step_s(teeth, w) is the step.
    const double fastest = 2.0 * pi / (kStepsPerMeshPeriod * teeth * step);
    if (i == 0 && has_speed_reference(c.torque1)) {
      // The driver's (or the reference's) fastest speed, W + sum_i |a_i|,
      // W the largest of a speed profile's.
      const Torque& d = c.torque1;
      double peak = std::fabs(d.mean_speed_rad_per_s);
      for (double v : d.speed_profile_speeds_rad_per_s) peak = std::max(peak, std::fabs(v));
      for (double a : d.driver_speed_amplitudes_rad_per_s) peak += std::fabs(a);
      if (peak <= fastest) continue;
      throw InputError("torque1.mean_speed", digits(d.mean_speed_rad_per_s) + " rad/s",
                       "a driver whose fastest speed mean_speed + sum_i |speed_amplitudes[i]| = " +
                           digits(peak) + " rad/s is at most " + digits(fastest) +
                           " rad/s: at least " + digits(kStepsPerMeshPeriod) +
                           " steps of integrator.step = " + digits(step) +
                           " s per mesh period 2 pi / (z1 |w1|), z1 = " + std::to_string(teeth) +
                           "; a faster driver needs a smaller integrator.step");
    }
    if (std::fabs(w) <= fastest) continue;
    const std::string n = std::to_string(i + 1);
    throw InputError(
        "initial.w" + n, digits(w) + " rad/s",
        "|w" + n + "| <= " + digits(fastest) + " rad/s: at least " + digits(kStepsPerMeshPeriod) +
            " steps of integrator.step = " + digits(step) + " s per mesh period 2 pi / (z" + n +
            " |w" + n + "|), z" + n + " = " + std::to_string(teeth) +
            ", so that the changes of the loaded pairs are resolved; a faster gear "
            "needs a smaller integrator.step");
  }
}

// Each torque's forcing frequencies against the step, as the speeds: at least
// kStepsPerMeshPeriod steps per period 2 pi / W of a sinusoid or a harmonic.
void validate_forcing(const SimulationCase& c) {
  const double step = c.integrator.step_s;
  const double fastest = 2.0 * pi / (kStepsPerMeshPeriod * step);
  const std::array<std::pair<const char*, const Torque*>, 2> torques{
      {{"torque1", &c.torque1}, {"torque2", &c.torque2}}};
  for (const auto& [name, torque] : torques) {
    const auto check = [&](const std::string& key, double w) {
      if (std::fabs(w) <= fastest) return;
      throw InputError(key, digits(w) + " rad/s",
                       "at most " + digits(fastest) + " rad/s: at least " +
                           digits(kStepsPerMeshPeriod) +
                           " steps of integrator.step = " + digits(step) +
                           " s per forcing period 2 pi / W, so that the torque is resolved; "
                           "a faster forcing needs a smaller integrator.step");
    };
    if (has_speed_reference(*torque)) {
      // The driver's harmonics turn at n_i W.
      for (std::size_t i = 0; i < torque->driver_orders.size(); ++i) {
        check(std::string(name) + ".orders[" + std::to_string(i) + "]",
              torque->driver_orders[i] * torque->mean_speed_rad_per_s);
      }
    } else if (torque->kind == Torque::Kind::sinusoidal) {
      check(std::string(name) + ".angular_frequency", torque->angular_frequency_rad_per_s);
    } else if (torque->kind == Torque::Kind::harmonic) {
      const std::vector<double>& w = torque->harmonic_angular_frequencies_rad_per_s;
      for (std::size_t i = 0; i < w.size(); ++i) {
        check(std::string(name) + ".angular_frequencies[" + std::to_string(i) + "]", w[i]);
      }
    }
  }
}

// The drag's smoothed constant part and its viscous part relax w2 with the
// time constant tau = J2 / (drag_constant / drag_speed_scale + drag_viscous)
// near w2 = 0: at least kStepsPerContactPeriod steps per 2 pi tau, as for a
// contact period, so that explicit steps resolve it.
void validate_drag(const SimulationCase& c) {
  const Torque& d = c.torque2;
  if (d.kind != Torque::Kind::drag) return;
  const double rate = d.drag_constant_n_m / d.drag_speed_scale_rad_per_s + d.drag_viscous_n_m_s;
  if (!(rate > 0.0)) return;
  const double tau = moment_of_inertia(c.gears, Gear::two) / rate;
  const double step = c.integrator.step_s;
  if (step <= 2.0 * pi * tau / kStepsPerContactPeriod) return;
  throw InputError(
      "torque2.drag_speed_scale", digits(d.drag_speed_scale_rad_per_s) + " rad/s",
      "a scale at which the drag's relaxation time J2 / (drag_constant / drag_speed_scale + "
      "drag_viscous) = " +
          digits(tau) + " s spans at least " + digits(kStepsPerContactPeriod) +
          " steps of integrator.step = " + digits(step) +
          " s per 2 pi of it; raise drag_speed_scale (or lower drag_viscous, or the step)");
}

// The rate at which the rolling sweeps the sliding speed through zero at the
// pitch point, |dVs/dt| = Rb1 |w1| (|w1| + |w2|): the contact moves along the
// line at Rb1 w1, and Vs = w1 X1 - w2 (lp - X1) changes by w1 + w2 per metre
// of it. At the gears' initial speeds (the driver's fastest, W + sum |a_i|).
double sliding_sweep_rate_m_s2(const SimulationCase& c) {
  double w1 = std::fabs(c.initial.w1_rad_per_s);
  if (c.torque1.kind == Torque::Kind::prescribed_speed) {
    w1 = std::fabs(c.torque1.mean_speed_rad_per_s);
    for (double a : c.torque1.driver_speed_amplitudes_rad_per_s) w1 += std::fabs(a);
  }
  const double w2 = std::fabs(c.initial.w2_rad_per_s);
  return base_radius(c.gears, Gear::one) * w1 * (w1 + w2);
}

// The smoothed sign tanh(Vs / v_s) turns the friction over a band of sliding
// speeds 2 v_s wide (from -0.76 to +0.76 of f N); the rolling sweeps Vs
// through it in 2 v_s / |dVs/dt|. A fixed step must cut that time into at
// least kStepsPerContactPeriod steps (the sliding speed changes by at most
// v_s / 10 per step), or the steps jump across the band as across the exact
// switch, without its event: the smoothing then resolves nothing. The
// adaptive integrator's error control shortens its steps there by itself.
void validate_friction_smoothing(const SimulationCase& c) {
  const ModelOptions& m = c.model;
  const double vs = m.friction_smoothing_speed_m_s;
  if (!(vs > 0.0) || c.integrator.kind == IntegratorKind::adaptive) return;
  if (m.friction_law == FrictionLaw::constant && m.friction_coefficient == 0.0) return;
  const double step = c.integrator.step_s;
  const double rate = sliding_sweep_rate_m_s2(c);
  const double least = 0.5 * kStepsPerContactPeriod * step * rate;
  if (vs >= least) return;
  throw InputError(
      "model.friction_smoothing_speed", digits(vs) + " m/s",
      ">= " + digits(least) + " m/s (or 0, the exact switch): the band 2 v_s over which " +
          "tanh(Vs / v_s) turns the friction spans at least " + digits(kStepsPerContactPeriod) +
          " steps of integrator.step = " + digits(step) +
          " s, in which the rolling changes the sliding speed at the pitch point by Rb1 |w1| "
          "(|w1| + |w2|) = " +
          digits(rate) + " m/s^2 at the initial speeds; raise it, or a smaller integrator.step");
}

// A damping frozen at a reference impact speed is known before the run: under
// the torques' tooth load, its rate per fixed step h D F / m_e must stay inside
// RK4's stability interval, or the first loaded contact diverges.
void validate_frozen_damping(const SimulationCase& c) {
  const ModelOptions& m = c.model;
  if (c.integrator.kind == IntegratorKind::adaptive ||
      resolved_damping_update(c) != DampingUpdate::frozen) {
    return;
  }
  const double speed = m.damping_reference_speed_m_s;
  const double d = damping_factor_per_stiffness(
      m.damping_form, restitution_coefficient(m.restitution, speed), speed);
  const double load = peak_tooth_load_n(c);
  const double rate = damping_rate_per_step(c, d, load);
  const double limit = real_stability_limit(c.integrator.kind);
  if (!(rate > limit)) return;
  const std::string method = name_of(kIntegratorKinds, c.integrator.kind);
  throw InputError("model.damping_reference_speed", digits(speed) + " m/s",
                   "a speed whose frozen damping the fixed-step " + method +
                       " can carry: at it (32)-(33) give D = " + digits(d) +
                       " s/m, and under the tooth load " + digits(load) +
                       " N its rate per step h D F / m_e = " + digits(rate) + " exceeds " +
                       digits(limit) + ", where " + method + " diverges",
                   "raise model.damping_reference_speed, or integrator.kind = \"adaptive\", or a "
                   "smaller integrator.step");
}

void validate_implied(const SimulationCase& c, const std::pair<double, double>& extremes) {
  // The torques and the step of a gear pair alone are defaults no one gave.
  validate_run_keys(c);
  const double softest = c.model.mesh_stiffness == MeshStiffnessMode::constant
                             ? c.model.constant_mesh_stiffness_n_per_m
                             : extremes.first;
  // Independent checks, every refusal reported at once.
  Problems problems;
  problems.collect([&] { validate_static_deflection(c, softest); });
  // Dormand-Prince at a fixed step needs half RK4's steps per period.
  problems.collect([&] {
    validate_step(c, largest_step(c, extremes.second, steps_per_contact_period(c.integrator.kind)));
  });
  problems.collect([&] { validate_speeds(c); });
  problems.collect([&] { validate_forcing(c); });
  problems.collect([&] { validate_drag(c); });
  problems.collect([&] { validate_friction_smoothing(c); });
  problems.collect([&] { validate_frozen_damping(c); });
  problems.throw_if_any();
}

}  // namespace

void validate_step(const SimulationCase& c, double largest) {
  const IntegratorSettings& s = c.integrator;
  if (s.step_s <= largest) return;
  const double steps = steps_per_contact_period(s.kind);
  const double period = largest * steps;
  const std::string why =
      "at least " + digits(steps) +
      " steps per period of the stiffest contact, 2 pi sqrt(m_e / K) with K its mesh stiffness "
      "(gears.youngs_modulus, gears.face_width) and m_e = " +
      digits(effective_mass_kg(c.gears)) +
      " kg the effective mass of the gears' discs (gears.density, gears.module, gears.face_width)";
  if (!(largest > 0.0) || !std::isnormal(largest)) {
    throw InputError("integrator.step", digits(s.step_s) + " s",
                     "no step: " + why + "; that period is " +
                         (period > 0.0 ? digits(period) + " s" : "0 s to double precision") +
                         ", too short to resolve; check those keys' values and units");
  }
  throw InputError(
      "integrator.step", digits(s.step_s) + " s",
      "<= " + format_number(largest) + " s: " + why + "; that period is " + digits(period) + " s");
}

double peak_tooth_load_n(const SimulationCase& c) {
  const double load1 = torque_peak(c.torque1, "torque1", c.initial.w1_rad_per_s).first /
                       base_radius(c.gears, Gear::one);
  const double load2 = torque_peak(c.torque2, "torque2", c.initial.w2_rad_per_s).first /
                       base_radius(c.gears, Gear::two);
  return std::max(load1, load2);
}

double damping_rate_per_step(const SimulationCase& c, double damping_per_stiffness_s_m,
                             double load_n) {
  const GearPair& g = c.gears;
  const double rb2 = base_radius(g, Gear::two);
  const double mass = c.torque1.kind == Torque::Kind::prescribed_speed
                          ? moment_of_inertia(g, Gear::two) / (rb2 * rb2)
                          : effective_mass_kg(g);
  return c.integrator.step_s * damping_per_stiffness_s_m * load_n / mass;
}

double largest_resolving_step_s(const SimulationCase& c) {
  return largest_step(c, total_stiffness_extremes(c, [&](double x) {
                           return mesh_stiffness(c.gears, x, c.model.stiffness).ke;
                         }).second);
}

double largest_mesh_step_s(int teeth, double w_rad_per_s) {
  return 2.0 * pi / (kStepsPerMeshPeriod * teeth * std::fabs(w_rad_per_s));
}

namespace {

// The bounds of a case whose stiffest summed mesh stiffness is `stiffest`.
StepBounds step_bounds(const SimulationCase& c, double stiffest) {
  StepBounds b;
  b.contact_period_s = largest_step(c, stiffest, 1.0);
  b.rk4_step_s = largest_step(c, stiffest, steps_per_contact_period(IntegratorKind::rk4));
  b.dopri5_step_s = largest_step(c, stiffest, steps_per_contact_period(IntegratorKind::dopri5));
  b.mesh_step_s = largest_mesh_step_s(c.gears.teeth1, c.initial.w1_rad_per_s);
  b.mesh_period_s = b.mesh_step_s * kStepsPerMeshPeriod;
  if (!std::isfinite(b.mesh_period_s)) b.mesh_period_s = 0.0;
  return b;
}

}  // namespace

StepBounds step_bounds(const SimulationCase& c) {
  if (c.gears.helix_angle_rad != 0.0) {
    // A helical pair's bounds are those of the transverse section it runs
    // as, with the pair table it reads.
    const SimulationCase d = dynamics_case(c);
    const StiffnessTable table = helical_pair_table(c.gears, c.model.stiffness);
    return step_bounds(
        d, total_stiffness_extremes(d, [&](double x) { return table.stiffness(x); }).second);
  }
  return step_bounds(c, total_stiffness_extremes(c, [&](double x) {
                          return mesh_stiffness(c.gears, x, c.model.stiffness).ke;
                        }).second);
}

double largest_resolving_step_s(const SimulationCase& c, const StiffnessTable& table) {
  return largest_step(
      c, total_stiffness_extremes(c, [&](double x) { return table.stiffness(x); }).second);
}

void validate_implied(const SimulationCase& c) {
  if (c.gears.helix_angle_rad != 0.0) {
    // A helical pair: what its run refuses, by name, then what the fields
    // imply on the transverse section it runs as, with the table it reads.
    // Its modifications are the run's to refuse: a train runs them by slices
    // (route A), which `simulate` does not (it refuses them itself).
    validate_absent_run_keys(c);
    SimulationCase plain = c;
    plain.modifications = Modifications{};
    refuse_helical_run(plain);
    validate_implied(dynamics_case(plain), helical_pair_table(c.gears, c.model.stiffness));
    return;
  }
  validate_implied(c, total_stiffness_extremes(c, [&](double x) {
                     return mesh_stiffness(c.gears, x, c.model.stiffness).ke;
                   }));
}

void validate_implied(const SimulationCase& c, const StiffnessTable& table) {
  validate_implied(c, total_stiffness_extremes(c, [&](double x) { return table.stiffness(x); }));
}

}  // namespace gearimpact
