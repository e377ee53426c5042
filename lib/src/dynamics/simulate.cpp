#include "gearimpact/dynamics/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/dynamics/sliced_pair.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "rk4.hpp"

namespace gearimpact {

namespace {

// A series row as CSV, measured on the paper's cases (138 bytes); for the
// estimate a message gives.
constexpr double kSeriesRowBytes = 140.0;
// A sample row as CSV: 11 numbers of 17 digits and two small integers; a
// planar one, 31 numbers.
constexpr double kSampleRowBytes = 230.0;
constexpr double kPlanarSampleRowBytes = 720.0;

// "14 GB", "140 MB": the size a message gives, rounded.
std::string csv_size_text(double bytes) {
  return bytes >= 1e9 ? shortest_decimal(std::round(bytes * 1e-9)) + " GB"
                      : shortest_decimal(std::round(bytes * 1e-6)) + " MB";
}

void validate_control(const SimulationCase& c, const RunControl& control) {
  if (control.keep_series || control.on_row) {
    const double rows = series_rows(c);
    if (rows > static_cast<double>(control.most_series_rows)) {
      throw InputError(
          "integrator.end_time", shortest_decimal(c.integrator.end_time_s) + " s",
          "at most " + shortest_decimal(static_cast<double>(control.most_series_rows)) +
              " rows of time series; this run's series has about " + shortest_decimal(rows) +
              " rows (integrator.step = " + shortest_decimal(c.integrator.step_s) +
              " s, integrator.output_every = " + std::to_string(c.integrator.output_every) +
              "), about " + csv_size_text(rows * kSeriesRowBytes) +
              " as CSV: shorten the run, keep fewer rows (integrator.output_every), or lift "
              "the bound");
    }
  }
  validate_sampling(c, control);
  if (control.resume) {
    const RunState& r = *control.resume;
    const InitialState& y = r.state;
    if (!std::isfinite(r.time_s) || !std::isfinite(y.theta1_rad) || !std::isfinite(y.theta2_rad) ||
        !std::isfinite(y.w1_rad_per_s) || !std::isfinite(y.w2_rad_per_s) ||
        !std::isfinite(r.contact.damping_per_stiffness_s_m) ||
        !std::isfinite(r.contact.frozen_stiffness_n_per_m) ||
        r.contact.damping_per_stiffness_s_m < 0.0) {
      throw InputError("resume", "a state with a non-finite or negative value",
                       "the final_state of a run of " + c.name + ", finite");
    }
  }
}

// The rattle index of a driven run: its loose gear's RMS acceleration over
// that of the same run without backlash, started at the same penetration
// (s moved towards 0 by B, or s = 0 from within the backlash), so that the
// twin starts in the same contact, or at its edge.
void add_rattle_index(const SimulationCase& c, const StiffnessTable& table,
                      const RunControl& control, RattleSummary& rattle) {
  if (control.resume) return;
  const double backlash = c.gears.backlash_m;
  if (backlash == 0.0) {
    rattle.rms_acceleration2_no_backlash_rad_s2 = rattle.rms_acceleration2_rad_s2;
    rattle.rattle_index = 1.0;
    return;
  }
  // Tooth errors that use up part of the play would let the twin, without
  // it, press both flanks at once (validate_gaps): no index then.
  if (least_gap_bound_m(c.gears, c.modifications, Region::n1) +
          least_gap_bound_m(c.gears, c.modifications, Region::n2) <
      0.0) {
    return;
  }
  SimulationCase twin = c;
  twin.gears.backlash_m = 0.0;
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double s0 = rb1 * c.initial.theta1_rad - rb2 * c.initial.theta2_rad;
  const double s_twin = std::copysign(std::max(std::fabs(s0) - backlash, 0.0), s0);
  twin.initial.theta2_rad = (rb1 * c.initial.theta1_rad - s_twin) / rb2;
  RunControl quiet;
  quiet.keep_series = false;
  quiet.should_stop = control.should_stop;
  const SimulationResult r = c.integrator.kind == IntegratorKind::adaptive
                                 ? run_adaptive(twin, table, quiet)
                                 : run_fixed_step(twin, table, quiet);
  const double reference = r.summary.rattle->rms_acceleration2_rad_s2;
  rattle.rms_acceleration2_no_backlash_rad_s2 = reference;
  if (reference > 0.0) rattle.rattle_index = rattle.rms_acceleration2_rad_s2 / reference;
}

// The run of a case that check_run checked, with its table.
SimulationResult simulate_checked(const SimulationCase& c, const StiffnessTable& table,
                                  const RunControl& control) {
  if (c.bearings.kind == BearingKind::elastic) {
    // Rigid bearings never come here: they run the torsional model below.
    SimulationResult result =
        simulate_planar(c, table, planar_mounting(c), planar_initial_state(c), control);
    result.summary.foundation_extrapolations =
        foundation_extrapolations(c.gears, c.model.stiffness);
    result.summary.foundation_extrapolated = !result.summary.foundation_extrapolations.empty();
    result.summary.equivalent_mesh_damping_ratio = equivalent_mesh_damping_ratio(c, table);
    return result;
  }
  SimulationResult result = c.integrator.kind == IntegratorKind::adaptive
                                ? run_adaptive(c, table, control)
                                : run_fixed_step(c, table, control);
  result.summary.equivalent_mesh_damping_ratio = equivalent_mesh_damping_ratio(c, table);
  if (result.summary.rattle) add_rattle_index(c, table, control, *result.summary.rattle);
  const StiffnessModel& k = c.model.stiffness;
  result.summary.foundation_extrapolations = foundation_extrapolations(c.gears, k);
  result.summary.foundation_extrapolated = !result.summary.foundation_extrapolations.empty();
  return result;
}

}  // namespace

void check_table(const SimulationCase& c, const StiffnessTable& table) {
  if (table.knows_origin()) {
    if (!table.built_for(c.gears, c.model.stiffness)) {
      throw InputError("table", "a StiffnessTable built for another gear pair or stiffness model",
                       "the table of this case: StiffnessTable(c.gears, c.model.stiffness)");
    }
    return;
  }
  const ContactSegment segment = pair_contact_segment(c.gears);
  if (table.domain_start_m() > segment.start_m || table.domain_end_m() < segment.end_m) {
    throw InputError("table",
                     "a table over [" + format_number(table.domain_start_m()) + ", " +
                         format_number(table.domain_end_m()) + "] m",
                     "one that covers the contact segment [" + format_number(segment.start_m) +
                         ", " + format_number(segment.end_m) + "] m of " + c.name);
  }
}

double series_rows(const SimulationCase& c) {
  const IntegratorSettings& s = c.integrator;
  return std::floor(s.end_time_s / s.step_s / static_cast<double>(s.output_every)) + 1.0;
}

void validate_gaps(const SimulationCase& c) {
  if (is_unmodified(c.modifications)) return;
  if (c.model.mesh_stiffness == MeshStiffnessMode::constant) {
    throw InputError(std::vector<Problem>{range_problem(
        "model.mesh_stiffness", "constant",
        "\"time-varying\" with [modifications]: a constant mesh stiffness has no tooth pairs "
        "whose gaps could differ",
        "model.mesh_stiffness = \"time-varying\", or no relief and no tooth error")});
  }
  // Both lines touch where s - B > e_k on N1 and -s - B > e'_j on N2, which
  // needs e_k + e'_j < -2 B.
  const double least = least_gap_bound_m(c.gears, c.modifications, Region::n1) +
                       least_gap_bound_m(c.gears, c.modifications, Region::n2);
  if (2.0 * c.gears.backlash_m + least < 0.0) {
    throw InputError(std::vector<Problem>{range_problem(
        "gears.backlash", format_number(c.gears.backlash_m * 1e3) + " mm",
        "at least " + format_number(-0.5 * least * 1e3) +
            " mm with these [modifications]: their tooth errors (pitch, thickness, profile "
            "slope) may close the gap by up to " +
            format_number(-least * 1e3) +
            " mm on the two flanks together, so that a pair could press both the drive and the "
            "coast flank at once, which the contact on one line of action cannot describe",
        "gears.backlash = \"" + format_number(-0.5 * least * 1e3) +
            " mm\", or smaller negative tooth errors")});
  }
}

void refuse_planar_simulation(const SimulationCase& c) {
  if (c.shafts.kind == ShaftKind::elastic && c.bearings.kind != BearingKind::elastic) {
    throw InputError(std::vector<Problem>{refused_problem(
        "shafts.kind", "\"elastic\"",
        "simulated with [bearings] kind = \"elastic\" only: the motor and the load belong to "
        "the planar model",
        "\"none\" (the default) with rigid bearings",
        "add [bearings] kind = \"elastic\" to simulate the planar model with its shafts")});
  }
  if (c.tacho.pulses_per_revolution > 0 && c.bearings.kind != BearingKind::elastic) {
    throw InputError(std::vector<Problem>{refused_problem(
        "tacho.pulses_per_revolution", std::to_string(c.tacho.pulses_per_revolution),
        "a tacho with [bearings] kind = \"elastic\" only: its edges are located in the planar "
        "run, the model of signal records",
        "0 (no tacho) with rigid bearings", "add [bearings] kind = \"elastic\"")});
  }
}

double sample_count(double end_time_s, double sample_rate_hz, double t0_s) {
  const double end = t0_s + end_time_s;
  const double guess = std::floor(end_time_s * sample_rate_hz);
  // Beyond 2^53 samples the count is only an estimate for a refusal.
  if (!(guess < 9007199254740992.0)) return guess + 1.0;
  auto n = static_cast<long long>(guess);
  while (sample_time_s(t0_s, n + 1, sample_rate_hz) <= end) ++n;
  while (n > 0 && sample_time_s(t0_s, n, sample_rate_hz) > end) --n;
  return static_cast<double>(n) + 1.0;
}

void validate_sampling(const SimulationCase& c, const RunControl& control) {
  validate_sampling(
      c.integrator.end_time_s,
      c.bearings.kind == BearingKind::elastic ? kPlanarSampleRowBytes : kSampleRowBytes, control);
}

void validate_sampling(double end_time_s, double row_bytes, const RunControl& control) {
  if (!control.sample_rate_hz) return;
  const double rate = *control.sample_rate_hz;
  const std::string rate_text = format_number(rate) + " Hz";
  if (!(std::isfinite(rate) && rate > 0.0)) {
    throw InputError("sample_rate", rate_text, "a finite rate > 0 Hz");
  }
  if (!control.locate_events) {
    throw InputError("sample_rate", rate_text,
                     "only with event location (RunControl::locate_events): the dense output "
                     "of a step needs one mode");
  }
  const double most = static_cast<double>(control.most_series_rows);
  const double t0 = control.resume ? control.resume->time_s : 0.0;
  const double samples = sample_count(end_time_s, rate, t0);
  if (samples > most) {
    const double end = end_time_s;
    throw InputError("sample_rate", rate_text,
                     "a rate in (0, " + shortest_decimal((most - 1.0) / end) + "] Hz: at most " +
                         shortest_decimal(most) +
                         " samples over integrator.end_time = " + shortest_decimal(end) +
                         " s; this run would have " + shortest_decimal(samples) +
                         " samples, about " + csv_size_text(samples * row_bytes) +
                         " as CSV: lower the rate, shorten the run, or lift the bound");
  }
}

void validate(const SimulationCase& c) {
  if (c.gears.helix_angle_rad != 0.0) {
    // A helical pair: its keys as given, its refusals by name, then the
    // transverse section it runs as, with the pair table it reads (what
    // check_run does).
    validate_absent_run_keys(c);
    validate_fields(c);
    refuse_helical_run(c);
    const SimulationCase d = dynamics_case(c);
    refuse_planar_simulation(d);
    if (d.bearings.kind == BearingKind::elastic) validate_planar(d, planar_mounting(d), {});
    validate_gaps(d);
    validate_implied(c);
    return;
  }
  validate_run_keys(c);
  validate_fields(c);
  refuse_planar_simulation(c);
  if (c.bearings.kind == BearingKind::elastic) validate_planar(c, planar_mounting(c), {});
  validate_gaps(c);
  validate_implied(c);
}

namespace {

std::string six_digits(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

bool known_mean(const Torque& t) {
  return t.kind == Torque::Kind::constant || t.kind == Torque::Kind::sinusoidal ||
         t.kind == Torque::Kind::harmonic;
}

}  // namespace

std::vector<std::string> result_warnings(const SimulationCase& c, const SimulationSummary& s) {
  std::vector<std::string> warnings;
  const double bound = kMostPlausibleOverlapModules * c.gears.module_m;
  if (s.max_penetration_m > bound) {
    warnings.push_back(
        "the teeth overlapped by up to " + format_number(s.max_penetration_m * 1e3) +
        " mm on the line of action (max_penetration_m), more than " +
        format_number(kMostPlausibleOverlapModules * 100.0) + " % of the module (" +
        format_number(bound * 1e3) +
        " mm), far beyond an elastic deflection: a pair entered the contact segment already "
        "pressed in, as after a missing or broken tooth, where real teeth would have met before "
        "the segment, at the tip's corner, which this line-of-action model does not describe; "
        "from there on the run describes the model, not the gears (docs/faults.md, \"A missing "
        "tooth\")");
  }
  // A signal run (elastic bearings) is a record at an operating point: say
  // when the speed does not hold it. The paper's torsional transients change
  // their speed by design and are not checked.
  if (c.bearings.kind == BearingKind::elastic && s.speed_drift_max_rel &&
      *s.speed_drift_max_rel > c.drive.speed_tolerance) {
    warnings.push_back(speed_drift_warning(*s.speed_drift_max_rel, c.drive.speed_tolerance,
                                           c.torque1, "the pinion", "torque1"));
  }
  return warnings;
}

std::string speed_drift_warning(double drift, double tolerance, const Torque& drive,
                                const std::string& body, const std::string& torque_key) {
  const bool controlled =
      drive.kind == Torque::Kind::speed_controlled || drive.kind == Torque::Kind::prescribed_speed;
  return body + "'s mean speed over a whole revolution drifted from its reference by up to " +
         six_digits(drift * 100.0) +
         " % (speed_drift_max_rel), more than drive.speed_tolerance = " + six_digits(tolerance) +
         (controlled
              ? ": the controller's start, a profile faster than its bandwidth or a load "
                "beyond it moved it; " +
                    torque_key + ".bandwidth sets how fast it holds the reference"
              : ": nothing holds the operating point against friction and the load; " + torque_key +
                    ".kind = \"speed-controlled\" (a motor with a speed controller, "
                    "docs/vibration.md) holds it");
}

std::optional<double> equivalent_mesh_damping_ratio(const SimulationCase& c,
                                                    const StiffnessTable& table) {
  if (resolved_damping_update(c) != DampingUpdate::frozen ||
      c.model.damping_stiffness != DampingStiffness::current_pair) {
    return std::nullopt;
  }
  double force = 0.0;
  if (known_mean(c.torque2)) {
    force = std::fabs(mean_torque_n_m(c.torque2, "torque2")) / base_radius(c.gears, Gear::two);
  }
  if (force == 0.0 && known_mean(c.torque1)) {
    force = std::fabs(mean_torque_n_m(c.torque1, "torque1")) / base_radius(c.gears, Gear::one);
  }
  if (force == 0.0) return std::nullopt;
  const double speed = c.model.damping_reference_speed_m_s;
  const double g = damping_factor_per_stiffness(
      c.model.damping_form, restitution_coefficient(c.model.restitution, speed), speed);
  return g * force /
         (2.0 * std::sqrt(mean_mesh_stiffness_n_per_m(c, table) * effective_mass_kg(c.gears)));
}

std::vector<std::string> run_warnings(const SimulationCase& c) {
  std::vector<std::string> warnings;
  // A helical pair's base radii are its transverse section's.
  const GearPair pair = swept_transverse_pair(c.gears);
  const double rb1 = base_radius(pair, Gear::one);
  const double rb2 = base_radius(pair, Gear::two);
  if (known_mean(c.torque1) && known_mean(c.torque2)) {
    const double t1 = mean_torque_n_m(c.torque1, "torque1");
    const double t2 = mean_torque_n_m(c.torque2, "torque2");
    const double imbalance = t1 / rb1 + t2 / rb2;
    if (std::fabs(imbalance) > 1e-9 * std::max(std::fabs(t1 / rb1), std::fabs(t2 / rb2))) {
      const std::string key =
          c.torque2.kind == Torque::Kind::constant ? "torque2.value" : "torque2.mean";
      // Friction takes power from the train, so torques that leave an excess for
      // it can hold a speed (a rig's load set against its friction); the check
      // cannot tell, as friction's mean power is known only from a run.
      const bool friction =
          c.model.friction_law != FrictionLaw::constant || c.model.friction_coefficient > 0.0;
      const std::string consequence =
          friction ? "without friction the pair would accelerate without bound; with it a "
                     "steady speed needs the excess power T1 w1 + T2 w2 to equal friction's mean "
                     "power, which this check does not compute"
                   : "the pair accelerates without bound and has no steady state";
      warnings.push_back("unbalanced mean torques: T1/Rb1 + T2/Rb2 = " + six_digits(imbalance) +
                         " N (T1 = " + six_digits(t1) + " N*m, T2 = " + six_digits(t2) + " N*m); " +
                         consequence + "; " + key + " = \"" + format_number(-t1 * rb2 / rb1) +
                         " N*m\" balances T1" + (friction ? " without friction" : ""));
    }
  }
  if (c.gears.helix_angle_rad != 0.0 && c.bearings.kind == BearingKind::elastic) {
    warnings.push_back(
        "a helical pair in the planar model: its transverse forces act on the centres, its "
        "axial force and tilting moments are reported (axial_force1_N, ..., "
        "tilting_moment2_N_m) and act on nothing: the model has no axial or tilting freedom "
        "(docs/helical.md, \"The planar model\")");
  }
  const double v1 = rb1 * c.initial.w1_rad_per_s;
  const double v2 = rb2 * c.initial.w2_rad_per_s;
  if (std::fabs(v1 - v2) > 1e-9 * std::max(std::fabs(v1), std::fabs(v2))) {
    constexpr double rpm = 60.0 / (2.0 * pi);
    warnings.push_back("initial speeds not rolling: Rb1 w1 = " + six_digits(v1) +
                       " m/s, Rb2 w2 = " + six_digits(v2) +
                       " m/s (w1 = " + six_digits(c.initial.w1_rad_per_s * rpm) +
                       " rpm, w2 = " + six_digits(c.initial.w2_rad_per_s * rpm) +
                       " rpm); the teeth start with a relative speed of " + six_digits(v1 - v2) +
                       " m/s; initial.w2 = \"" + format_number(v1 / rb2) +
                       " rad/s\" rolls with w1");
  }
  return warnings;
}

namespace {

// check_run's checks, on the case as given and then on the case the
// dynamics run (dynamics_case); `table` is called once the case and the
// controls pass. Returns the case the dynamics run and its table.
template <typename Table>
std::pair<SimulationCase, std::shared_ptr<const StiffnessTable>> checked_table(
    const SimulationCase& c, const RunControl& control, const std::function<void()>& fields_checked,
    Table table) {
  // A helical pair's keys are checked as the user gave them; the run then
  // takes its transverse section.
  validate_absent_run_keys(c);
  validate_fields(c);
  refuse_helical_run(c);
  const SimulationCase d = dynamics_case(c);
  refuse_planar_simulation(d);
  validate_gaps(d);
  if (fields_checked) fields_checked();
  // The controls before the table, which may take a while to build.
  validate_control(d, control);
  if (d.bearings.kind == BearingKind::elastic) validate_planar(d, planar_mounting(d), control);
  std::shared_ptr<const StiffnessTable> built = table();
  check_table(d, *built);
  // The planar system's step bound is the tighter one: first, so that a step
  // refused is refused once, with the step that runs.
  if (d.bearings.kind == BearingKind::elastic) check_planar_step(d, *built, planar_mounting(d));
  validate_implied(d, *built);
  return {d, std::move(built)};
}

}  // namespace

SimulationCase dynamics_case(const SimulationCase& c) {
  if (c.gears.helix_angle_rad == 0.0) return c;
  SimulationCase d = c;
  d.gears = swept_transverse_pair(c.gears);
  return d;
}

std::shared_ptr<const StiffnessTable> run_table(const SimulationCase& c) {
  if (c.gears.helix_angle_rad == 0.0) {
    return std::make_shared<const StiffnessTable>(c.gears, c.model.stiffness);
  }
  return std::make_shared<const StiffnessTable>(helical_pair_table(c.gears, c.model.stiffness));
}

void refuse_helical_friction(const SimulationCase& c) {
  if (c.gears.helix_angle_rad == 0.0) return;
  const std::string beta = format_number(c.gears.helix_angle_rad * 180.0 / pi) + " deg";
  if (c.model.friction_law != FrictionLaw::constant) {
    throw InputError(std::vector<Problem>{
        refused_problem("model.friction_law",
                        "\"" + std::string(name_of(kFrictionLaws, c.model.friction_law)) + "\"",
                        "not with a helical pair (gears.helix_angle = " + beta +
                            "): its friction is summed over the face under the constant law only "
                            "(docs/helical.md, Friction on a helical pair)",
                        "\"constant\"", "model.friction_law = \"constant\"")});
  }
  if (c.model.friction_coefficient != 0.0 && !c.faults.empty()) {
    throw InputError(std::vector<Problem>{refused_problem(
        "model.friction_coefficient", format_number(c.model.friction_coefficient),
        "0 with [[faults]] on a helical pair (gears.helix_angle = " + beta +
            "): the face sum of friction is a healthy face's, and a fault's slices carry "
            "other loads (docs/helical.md, Friction on a helical pair)",
        "0", "model.friction_coefficient = 0, or the pair without [[faults]]")});
  }
  if (c.model.friction_coefficient != 0.0 && c.model.friction_smoothing_speed_m_s > 0.0) {
    throw InputError(std::vector<Problem>{
        refused_problem("model.friction_smoothing_speed",
                        format_number(c.model.friction_smoothing_speed_m_s) + " m/s",
                        "0 with a helical pair (gears.helix_angle = " + beta +
                            "): its friction, summed over the face, already passes the pitch point "
                            "continuously (docs/helical.md, Friction on a helical pair)",
                        "0", "model.friction_smoothing_speed = 0")});
  }
}

void refuse_helical_run(const SimulationCase& c) {
  if (c.gears.helix_angle_rad == 0.0) return;
  const std::string beta = format_number(c.gears.helix_angle_rad * 180.0 / pi) + " deg";
  if (!is_unmodified(c.modifications)) {
    throw InputError(std::vector<Problem>{refused_problem(
        "modifications",
        "reliefs or tooth errors on a helical pair (gears.helix_angle = " + beta + ")",
        "not in this run of a helical pair: a gap that varies along an inclined contact "
        "line needs the slices as separate contacts (route A of docs/helical.md), which only "
        "`gearimpact simulate` and `gearimpact train` run",
        "no relief and no tooth error with gears.helix_angle > 0",
        "run the case file with `gearimpact simulate` or `gearimpact train` (route A: each "
        "slice its own contact), or remove the relief and tooth-error keys")});
  }
  refuse_helical_friction(c);
  const HelicalGeometry g = helical_geometry(c.gears);
  const double most = static_cast<double>(MeshLayout::capacity - 1);
  if (!(g.total_contact_ratio < most)) {
    throw InputError(std::vector<Problem>{refused_problem(
        "gears.face_width", format_number(c.gears.face_width_m * 1e3) + " mm",
        "a face whose total contact ratio eps_gamma = eps_alpha + eps_beta = " +
            format_number(g.transverse_contact_ratio) + " + " + format_number(g.overlap_ratio) +
            " stays below " + format_number(most) + ": a line of action holds at most " +
            std::to_string(MeshLayout::capacity) + " tooth pairs",
        "eps_gamma < " + format_number(most),
        "a narrower face or a smaller gears.helix_angle (eps_beta = b sin(beta) / (pi m_n))")});
  }
}

CheckedRun check_run(const SimulationCase& c, const RunControl& control,
                     const std::function<void()>& fields_checked) {
  auto [d, table] = checked_table(c, control, fields_checked, [&c] { return run_table(c); });
  return CheckedRun(std::move(d), std::move(table), control);
}

CheckedRun check_run(const SimulationCase& c, std::shared_ptr<const StiffnessTable> table,
                     const RunControl& control) {
  if (!table) throw InputError("table", "none", "a StiffnessTable");
  auto [d, checked] = checked_table(c, control, {}, [&table] { return table; });
  return CheckedRun(std::move(d), std::move(checked), control);
}

SimulationResult simulate(const CheckedRun& run) {
  return simulate_checked(run.simulation_case(), run.table(), run.control());
}

void validate_run_control(const SimulationCase& c, const RunControl& control) {
  validate_control(c, control);
}

SimulationResult simulate(const SimulationCase& c, const RunControl& control) {
  // A helical pair with modifications runs its slices as a train's meshes (route A).
  if (runs_by_slices(c)) return simulate_by_slices(c, control);
  return simulate(check_run(c, control));
}

SimulationResult simulate(const SimulationCase& c, const StiffnessTable& table,
                          const RunControl& control) {
  // The caller keeps the table for the call: not owned here.
  return simulate(check_run(
      c, std::shared_ptr<const StiffnessTable>(std::shared_ptr<void>(), &table), control));
}

std::vector<ImpactRecord> struck_impacts(const SimulationResult& result) {
  std::vector<ImpactRecord> struck;
  for (const ImpactRecord& impact : result.impacts) {
    if (impact.start_s != result.start_time_s) struck.push_back(impact);
  }
  return struck;
}

ImpactSpeedHistogram impact_speed_histogram(const std::vector<ImpactRecord>& struck, int bins) {
  if (bins < 1) throw InputError("bins", std::to_string(bins), "a count >= 1");
  ImpactSpeedHistogram h;
  if (struck.empty()) return h;
  double most = 0.0;
  for (const ImpactRecord& impact : struck) most = std::max(most, impact.impact_speed_m_s);
  const double width = most / bins;
  for (int i = 0; i < bins; ++i) {
    h.lower_m_s.push_back(width * i);
    // The last edge is the largest Vi itself, not a rounded multiple of the width.
    h.upper_m_s.push_back(i + 1 == bins ? most : width * (i + 1));
  }
  h.count_n1.assign(static_cast<std::size_t>(bins), 0);
  h.count_n2.assign(static_cast<std::size_t>(bins), 0);
  for (const ImpactRecord& impact : struck) {
    // The bin whose edges hold Vi; the rounding of Vi / width can put it one
    // bin off, which the edges correct.
    int i = width > 0.0 ? static_cast<int>(impact.impact_speed_m_s / width) : 0;
    i = std::clamp(i, 0, bins - 1);
    while (i > 0 && impact.impact_speed_m_s < h.lower_m_s[static_cast<std::size_t>(i)]) --i;
    while (i + 1 < bins && impact.impact_speed_m_s >= h.upper_m_s[static_cast<std::size_t>(i)]) ++i;
    auto& counts = impact.line == Region::n1 ? h.count_n1 : h.count_n2;
    ++counts[static_cast<std::size_t>(i)];
  }
  return h;
}

}  // namespace gearimpact
