// Everything a simulation run needs, as plain values in SI: the gear pair, the
// external torques, the initial state, the model options where the paper is
// ambiguous (docs/model.md, sections Contact, damping, friction and Readings) and
// the integrator settings. Case files (TOML) and the paper's Table 1 both
// produce one of these; the dynamics consumes it.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/named_values.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

namespace gearimpact {

// One external torque T_i(t), N m: a mean plus a fluctuation, or a table in
// time; or, on gear 1, a kinematic driver that prescribes its motion, a motor
// with a speed controller or an induction motor; or, on gear 2, a drag that
// opposes its rotation (docs/model.md, section Rattle of a loose gear;
// docs/vibration.md, section Drive and load).
struct Torque {
  enum class Kind {
    constant,
    sinusoidal,
    harmonic,
    user,
    prescribed_speed,
    drag,
    speed_controlled,
    induction_motor,
    profile
  };
  Kind kind = Kind::constant;
  double constant_n_m = 0.0;  // Kind::constant: T
  // Kind::sinusoidal and Kind::harmonic: the mean T_m the fluctuation is added to.
  double mean_n_m = 0.0;
  double amplitude_n_m = 0.0;  // Kind::sinusoidal: T_m + A sin(W t + phase)
  double angular_frequency_rad_per_s = 0.0;
  double phase_rad = 0.0;
  // Kind::harmonic: T_m + sum_i A_i sin(w_i t + phi_i), the three of one length.
  std::vector<double> harmonic_amplitudes_n_m;
  std::vector<double> harmonic_angular_frequencies_rad_per_s;
  std::vector<double> harmonic_phases_rad;
  std::function<double(double)> user;  // Kind::user: T(t_s), through the library API only
  // Kind::prescribed_speed (gear 1 only): w1(t) = W + sum_i a_i sin(n_i W t +
  // phi_i), with W the mean speed, n_i the orders, a_i the speed amplitudes
  // and phi_i in harmonic_phases_rad; theta1(0) is initial.theta1.
  double mean_speed_rad_per_s = 0.0;
  std::vector<double> driver_orders;
  std::vector<double> driver_speed_amplitudes_rad_per_s;
  // Kind::drag (gear 2 only): T = -(T_c tanh(w / w_s) + c w), a constant
  // part whose sign switch is smoothed over the speed scale w_s, plus a
  // viscous part.
  double drag_constant_n_m = 0.0;
  double drag_viscous_n_m_s = 0.0;
  double drag_speed_scale_rad_per_s = 0.1;
  // Kind::prescribed_speed and Kind::speed_controlled: the speed W(t) that
  // replaces the constant mean_speed, linear between the points (t_i, W_i)
  // and held beyond the first and the last; a time given twice is a step
  // (refused for a kinematic driver, which would need an infinite torque).
  // Empty: W(t) = mean_speed. The orders still turn at n_i mean_speed.
  std::vector<double> speed_profile_times_s;
  std::vector<double> speed_profile_speeds_rad_per_s;
  // Kind::speed_controlled (gear 1 only): T = T_ff + K_p e + K_i Int e dt,
  // e = W_ref(t) - w of the driven body (the motor with shafts, the pinion
  // otherwise), W_ref the driver's motion above; K_p = 2 zeta_c w_c J_eq,
  // K_i = w_c^2 J_eq (gearimpact/dynamics/drive.hpp).
  double controller_bandwidth_rad_per_s = 2.0 * pi * 10.0;  // w_c = 2 pi f_c, f_c = 10 Hz
  double controller_damping_ratio = 1.0;                    // zeta_c
  // Kind::induction_motor (gear 1 only): T = 2 T_b / (s / s_b + s_b / s),
  // s = 1 - w / w_s (Kloss's form).
  double synchronous_speed_rad_per_s = 0.0;  // w_s
  double breakdown_torque_n_m = 0.0;         // T_b
  double breakdown_slip = 0.0;               // s_b
  // Kind::profile: T(t) linear between the points (t_i, T_i), held beyond
  // the first and the last; a time given twice is a step (a load step).
  std::vector<double> profile_times_s;
  std::vector<double> profile_torques_n_m;
};

// A table linear between its points (t_i, v_i), held before the first and
// after the last, a time given twice a step (at the step the left value):
// its value, slope and integral from 0 to t >= 0. The times must be
// non-decreasing and >= 0 (the schema's rows and validate_relations).
struct ProfileValue {
  double integral = 0.0;
  double value = 0.0;
  double slope = 0.0;
};
inline ProfileValue profile_at(const std::vector<double>& times, const std::vector<double>& values,
                               double t_s) {
  double integral = 0.0;
  double prev_t = 0.0;
  double prev_v = values.front();  // held from 0 to the first point
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double ti = times[i];
    const double vi = values[i];
    if (t_s <= ti) {
      const double span = ti - prev_t;
      const double slope = span > 0.0 ? (vi - prev_v) / span : 0.0;
      const double v = prev_v + slope * (t_s - prev_t);
      // The trapezoid is exact for a linear piece.
      integral += 0.5 * (prev_v + v) * (t_s - prev_t);
      return {integral, v, slope};
    }
    integral += 0.5 * (prev_v + vi) * (ti - prev_t);
    prev_t = ti;
    prev_v = vi;
  }
  integral += prev_v * (t_s - prev_t);
  return {integral, prev_v, 0.0};
}

// Whether torque1 follows the driver's motion below: a kinematic driver
// (prescribed-speed) or a speed controller's reference.
inline bool has_speed_reference(const Torque& t) {
  return t.kind == Torque::Kind::prescribed_speed || t.kind == Torque::Kind::speed_controlled;
}

// The motion a Kind::prescribed_speed driver gives gear 1 at time t (absolute,
// so that a continued run keeps the same driver), and the reference of a
// Kind::speed_controlled one, in closed form:
//   w1 = W + sum_i a_i sin(W_i t + phi_i),  W_i = n_i W,
// with W(t) of speed_profile in place of W when a profile is given,
//   theta1 = theta1(0) + W t + sum_i (a_i / W_i) (cos(phi_i) - cos(W_i t + phi_i)),
//   w1' = sum_i a_i W_i cos(W_i t + phi_i).
struct DriverMotion {
  double theta_rad = 0.0;
  double speed_rad_per_s = 0.0;
  double acceleration_rad_per_s2 = 0.0;
};
inline DriverMotion driver_motion(const Torque& driver, double theta0_rad, double t_s) {
  const double w = driver.mean_speed_rad_per_s;
  DriverMotion m{theta0_rad + w * t_s, w, 0.0};
  if (!driver.speed_profile_times_s.empty()) {
    // W(t) of the profile in place of W: theta1(0) + Int_0^t W dt (exact
    // for the linear pieces: quadratic in t on a ramp).
    const ProfileValue p =
        profile_at(driver.speed_profile_times_s, driver.speed_profile_speeds_rad_per_s, t_s);
    m = {theta0_rad + p.integral, p.value, p.slope};
  }
  for (std::size_t i = 0; i < driver.driver_speed_amplitudes_rad_per_s.size(); ++i) {
    const double a = driver.driver_speed_amplitudes_rad_per_s[i];
    const double wi = driver.driver_orders[i] * w;
    const double phi = driver.harmonic_phases_rad[i];
    const double arg = wi * t_s + phi;
    m.theta_rad += a / wi * (std::cos(phi) - std::cos(arg));
    m.speed_rad_per_s += a * std::sin(arg);
    m.acceleration_rad_per_s2 += a * wi * std::cos(arg);
  }
  return m;
}
inline double driver_speed_at(const Torque& driver, double t_s) {
  return driver_motion(driver, 0.0, t_s).speed_rad_per_s;
}

// theta in rad, w in rad/s. theta1 = theta2 = 0 centres the teeth in the backlash.
struct InitialState {
  double theta1_rad = 0.0;
  double theta2_rad = 0.0;
  double w1_rad_per_s = 0.0;
  double w2_rad_per_s = 0.0;
};

// The mesh stiffness of the dynamics: each loaded pair's Ke(X) of (29), or a
// constant total shared equally by the n loaded pairs (Ke = k / n), so that the
// mesh stiffness never changes: the clearance oscillator of docs/steady-state.md.
enum class MeshStiffnessMode { time_varying, constant };
inline constexpr std::array<NamedValue<MeshStiffnessMode>, 2> kMeshStiffnessModes{{
    {MeshStiffnessMode::time_varying, "time-varying", "each loaded pair's Ke(X) of (29)"},
    {MeshStiffnessMode::constant, "constant",
     "constant_mesh_stiffness shared equally by the loaded pairs (the clearance oscillator)"},
}};

// How the mesh force follows from the time-varying stiffness (docs/model.md,
// section Energies). The Newtonian reading is the paper's F = Ke delta, under
// which the varying stiffness does work on the system (the ledger's parametric
// work); the Lagrangian one derives the forces from V = 1/2 Ke(theta1) delta^2,
// so the pinion also feels -1/2 dKe/dtheta1 delta^2 and every jump of V at a
// pair's entry or exit is paid by the pinion's kinetic energy.
enum class MeshForce { newtonian, lagrangian };
inline constexpr std::array<NamedValue<MeshForce>, 2> kMeshForces{{
    {MeshForce::newtonian, "newtonian",
     "F = Ke delta on each pair (the paper's); the varying stiffness does parametric work"},
    {MeshForce::lagrangian, "lagrangian",
     "from V = 1/2 Ke(theta1) delta^2: the pinion also feels -1/2 dKe/dtheta1 delta^2, and a "
     "jump of V at a pair's entry or exit is an impulse on the pinion's speed"},
}};

// When the Hertzian damping factor D of (32) is set (docs/steady-state.md section 1).
enum class DampingUpdate {
  // each_impact with rigid bearings (the paper's torsional model, on which
  // the reproduction rests), frozen with elastic ones (signal runs, whose
  // level must not depend on the start): resolved_damping_update below.
  automatic,
  // At every impact from e(Vi), carried with the state while no impact comes
  // (the paper's; a continued run or a sweep carries the last impact's D).
  each_impact,
  // From e(V_ref) at the stated reference impact speed, the same at every
  // impact: D depends on the case alone, not on the history.
  frozen,
  // D = 0: no Hertzian damping (the mesh damper can stand in for it).
  off,
};
inline constexpr std::array<NamedValue<DampingUpdate>, 4> kDampingUpdates{{
    {DampingUpdate::automatic, "auto",
     "each-impact with rigid bearings (the paper's), frozen with elastic bearings (signal runs: "
     "D does not depend on the start)"},
    {DampingUpdate::each_impact, "each-impact",
     "D from e(Vi) at every impact, carried with the state (the paper's)"},
    {DampingUpdate::frozen, "frozen",
     "D from e(damping_reference_speed), the same at every impact"},
    {DampingUpdate::off, "off", "D = 0"},
}};

struct ModelOptions {
  double friction_coefficient = 0.04;  // f of (35) under FrictionLaw::constant
  FrictionLaw friction_law = FrictionLaw::constant;
  BenedictKelleyLaw benedict_kelley;  // the lubricated contact of FrictionLaw::benedict_kelley
  FrictionTable friction_table;       // f against the slide-to-roll ratio of FrictionLaw::table
  // v_s of Ff = f N tanh(Vs / v_s), which replaces sign(Vs) of (35) when > 0;
  // 0 keeps the exact switch, located as an event.
  double friction_smoothing_speed_m_s = 0.0;
  DampingForm damping_form = DampingForm::herbert_mcwhannell;
  DampingStiffness damping_stiffness = DampingStiffness::current_pair;
  RestitutionLaw restitution;
  CoastPhase coast_phase = CoastPhase::half_base_pitch;
  StiffnessModel stiffness;  // quadrature method and the sign of the Fa h moment
  MeshStiffnessMode mesh_stiffness = MeshStiffnessMode::time_varying;
  double constant_mesh_stiffness_n_per_m = 0.0;  // k of MeshStiffnessMode::constant, > 0
  MeshForce mesh_force = MeshForce::newtonian;
  // zeta of the linear viscous mesh damper c = 2 zeta sqrt(k_mean m_e) on s'
  // (mesh.hpp); 0 leaves it out.
  double mesh_damping_ratio = 0.0;
  DampingUpdate damping_update = DampingUpdate::automatic;
  double damping_reference_speed_m_s = 1.0;  // V_ref of DampingUpdate::frozen, > 0
};

// How the gears' centres are held (docs/vibration.md). Rigid bearings fix the
// centres: the paper's torsional model, the one the dynamics integrate.
// Elastic bearings let each centre move in the plane on a spring and a damper
// per direction: the planar model, which simulate() integrates
// (dynamics/planar.hpp) and of which `gearimpact modes` reads the linearised
// form; the run pool, the steady sweeps and the period map (shooting, Floquet
// multipliers, continuation) run it too.
enum class BearingKind { rigid, elastic };
inline constexpr std::array<NamedValue<BearingKind>, 2> kBearingKinds{{
    {BearingKind::rigid, "rigid",
     "the centres are fixed: the torsional model of the paper (2 DOF)"},
    {BearingKind::elastic, "elastic",
     "each centre moves in the plane on its bearing's springs and dampers (x, y, theta per "
     "gear: 6 DOF); run by `gearimpact simulate`, `sweep`, `sweep-friction` and `modes`"},
}};

// Per gear and direction (x along the centre line O1 -> O2, y across it), in SI.
struct GearBearing {
  double stiffness_x_n_per_m = 0.0;
  // Absent: stiffness_x (isotropic).
  std::optional<double> stiffness_y_n_per_m;
  double damping_x_n_s_per_m = 0.0;
  // Absent: damping_x.
  std::optional<double> damping_y_n_s_per_m;
  // Absent: the disc of moment_of_inertia, rho pi r^2 L (geometry/gear_pair.hpp).
  std::optional<double> mass_kg;
};

struct Bearings {
  BearingKind kind = BearingKind::rigid;
  GearBearing gear1;
  GearBearing gear2;
  // The accelerometer of a planar run's samples (PlanarSample): on the
  // bearing of gear 1 or 2, measuring along the direction at sensor_angle_rad
  // from x towards y. Read with kind = "elastic" only.
  int sensor_gear = 1;
  double sensor_angle_rad = pi / 2.0;  // across the centre line
};

// The y stiffness and damping of a bearing: its own, else the x one's.
inline double stiffness_y(const GearBearing& b) {
  return b.stiffness_y_n_per_m.value_or(b.stiffness_x_n_per_m);
}
inline double damping_y(const GearBearing& b) {
  return b.damping_y_n_s_per_m.value_or(b.damping_x_n_s_per_m);
}

// Whether the torques act on the gears themselves or on a motor and a load
// behind torsional shafts (docs/vibration.md).
enum class ShaftKind { none, elastic };
inline constexpr std::array<NamedValue<ShaftKind>, 2> kShaftKinds{{
    {ShaftKind::none, "none", "the torques act on the gears"},
    {ShaftKind::elastic, "elastic",
     "a motor inertia on the pinion's shaft and a load inertia on the wheel's, each through a "
     "torsional spring and damper (2 more DOF), with elastic bearings; run by `gearimpact "
     "simulate`, `sweep`, `sweep-friction` and `modes`"},
}};

struct Shafts {
  ShaftKind kind = ShaftKind::none;
  double motor_inertia_kg_m2 = 0.0;          // J_m, on the pinion's side
  double motor_stiffness_n_m_per_rad = 0.0;  // k_t of the pinion's shaft
  double motor_damping_n_m_s_per_rad = 0.0;  // c_t of the pinion's shaft
  double load_inertia_kg_m2 = 0.0;           // J_L, on the wheel's side
  double load_stiffness_n_m_per_rad = 0.0;   // k_t of the wheel's shaft
  double load_damping_n_m_s_per_rad = 0.0;   // c_t of the wheel's shaft
};

enum class IntegratorKind { rk4, adaptive, dopri5 };
inline constexpr std::array<NamedValue<IntegratorKind>, 3> kIntegratorKinds{{
    {IntegratorKind::rk4, "rk4", "fixed-step RK4 with event location"},
    {IntegratorKind::adaptive, "adaptive", "Dormand-Prince 5(4) with the same event location"},
    {IntegratorKind::dopri5, "dopri5",
     "Dormand-Prince 5(4) at the fixed integrator.step with the same event location, order 5, "
     "for long signals; the torsional and the planar model alike"},
}};

// Fewer steps per contact period than this do not resolve the contact.
inline constexpr double kStepsPerContactPeriod = 20.0;
// Dormand-Prince 5(4) at a fixed step resolves a period in half RK4's steps:
// at 10 steps a period of a harmonic oscillator its frequency errs by 2.6e-5
// and its amplitude by 9.8e-5 a period, RK4's at 20 by 7.8e-5 and 1.3e-4
// (verify/dynamics/test_planar_dynamics.cpp computes both).
inline constexpr double kDopri5StepsPerContactPeriod = 10.0;
// The steps per contact period a fixed-step method needs (the adaptive
// method's first and largest step: RK4's count).
inline constexpr double steps_per_contact_period(IntegratorKind kind) {
  return kind == IntegratorKind::dopri5 ? kDopri5StepsPerContactPeriod : kStepsPerContactPeriod;
}
// Fewer steps per mesh period 2 pi / (z |w|) than this do not resolve the
// changes of the loaded pairs (two or more a mesh period): the same count as
// for the contact, whose stiffness they change.
inline constexpr double kStepsPerMeshPeriod = kStepsPerContactPeriod;
// The largest static deflection the torques may imply (the largest tooth load
// over the smallest mesh stiffness), as a fraction of the module: the
// linear-elastic tooth model of (4)-(29) is a small-deflection model of a
// tooth about 1.57 module thick at the pitch line; a tenth of a module is
// several times the deflection of a fully loaded steel pair (a few um at
// m = 2 mm) and far past yield.
inline constexpr double kMostStaticDeflectionPerModule = 0.1;
// A run of more steps than this is a mistake (days of computing), not a case.
inline constexpr long long kMostSteps = 2'000'000'000LL;
// The most rows of a time series a run keeps or writes unless its caller
// lifts the bound (RunControl::most_series_rows): 5e7 rows are 7 GB of CSV or
// 4.4 GB of memory, 5 s of the paper's cases at the 0.1 us step.
inline constexpr long long kMostSeriesRows = 50'000'000LL;

struct IntegratorSettings {
  IntegratorKind kind = IntegratorKind::rk4;
  double step_s = 1.0e-7;  // the fixed step (the adaptive one's first step)
  double end_time_s = 0.03;
  double adaptive_relative_tolerance = 1e-10;
  int output_every = 1;  // keep every n-th row of the time series
};

// The bound on a run's speed drift (docs/vibration.md, section Drive and
// load): the mean pinion speed over each whole revolution that begins after
// the start has settled, against the reference's mean over it.
struct Drive {
  double speed_tolerance = 1e-3;
  // The start's transient (a controller's integral taking up the friction,
  // the first contacts) is not drift: revolutions that begin before this
  // time are not checked. 0.1 s: a 10 Hz loop's error has fallen by e^-6.3.
  double settle_s = 0.1;
};

// A tacho on one shaft (docs/vibration.md, "Tacho"): an edge where the
// shaft's angle crosses offset + 2 pi k / pulses_per_revolution upward (k
// whole, the levels above its angle at the start), located as an event on
// the run's true angle. Planar runs only; 0 pulses: no tacho.
enum class TachoShaft { pinion, wheel, motor };
inline constexpr std::array<NamedValue<TachoShaft>, 3> kTachoShafts{{
    {TachoShaft::pinion, "pinion", "the pinion's angle theta1"},
    {TachoShaft::wheel, "wheel", "the wheel's angle theta2"},
    {TachoShaft::motor, "motor", "the motor's angle ([shafts]; the pinion's without shafts)"},
}};
struct Tacho {
  int pulses_per_revolution = 0;
  TachoShaft shaft = TachoShaft::pinion;
  double offset_rad = 0.0;
  // The standard deviation of a Gaussian jitter of each edge's time, seeded:
  // the emitted times (the true ones are kept jitter-free).
  double jitter_s = 0.0;
  std::uint32_t seed = 0;
};

struct SimulationCase {
  std::string name;
  GearPair gears;
  Torque torque1;
  Torque torque2;
  InitialState initial;
  ModelOptions model;
  IntegratorSettings integrator;
  // Tip and root relief and tooth errors, as gaps between the flanks
  // (modifications.hpp): the static transmission error and the dynamics read
  // them (each pair touches by its own penetration, delta - e_k).
  Modifications modifications;
  // Teeth that differ from the others ([[faults]], docs/faults.md); empty:
  // every tooth healthy.
  std::vector<ToothFault> faults;
  // The mounting of the pair (docs/vibration.md); the defaults are the
  // paper's torsional model.
  Bearings bearings;
  Shafts shafts;
  // The keys a run needs that the case leaves out ("torque1.kind", "integrator.end_time", ...):
  // a gear pair alone (a pair file, or gearimpact.case() given the pair's keys only) has no
  // torques and no end time, which the stiffness, the STE, ISO 6336, the modes and the report do
  // not read. Its torques and integrator hold their defaults, unused: every run refuses the case
  // naming these keys (validate_run_keys of case/schema.hpp), and write_case_file writes the pair
  // alone. Empty: nothing a run needs is missing.
  std::vector<std::string> run_keys_absent;
  Drive drive;
  Tacho tacho;
};

// The reading of D that a run takes: model.damping_update, with "auto"
// resolved by the bearings (each-impact rigid, frozen elastic).
inline DampingUpdate resolved_damping_update(const SimulationCase& c) {
  if (c.model.damping_update != DampingUpdate::automatic) return c.model.damping_update;
  return c.bearings.kind == BearingKind::elastic ? DampingUpdate::frozen
                                                 : DampingUpdate::each_impact;
}

}  // namespace gearimpact
