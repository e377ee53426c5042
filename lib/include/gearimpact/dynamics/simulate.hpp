// A simulation run of the gear impact dynamics (docs/model.md, sections Contact,
// damping, friction; Equations of motion; Energies): the system is in
// system.hpp, the event-cut RK4 and the adaptive integrator in rk4.cpp and
// adaptive.cpp, the energy ledger in ledger.hpp. This is what a caller needs:
// the run's inputs beyond the case (RunControl), its outputs (the time series,
// the impacts, the summary, the final state) and simulate().
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/planar_state.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/named_values.hpp"
#include "gearimpact/stiffness/fillet_foundation.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/terms.hpp"

namespace gearimpact {

// A run that cannot continue: a non-finite state, or event location that stalls.
class SimulationError : public Error {
 public:
  using Error::Error;
};

// One row of the time series. normal_force_n and friction_force_n are summed
// over the loaded pairs; friction_force_n carries the sign of Ff in (35)-(38).
struct SeriesRow {
  double t_s;
  double theta1_rad;
  double theta2_rad;
  double w1_rad_per_s;
  double w2_rad_per_s;
  double s_m;
  double delta_m;
  int region;
  int pairs;
  double normal_force_n;
  double friction_force_n;
};

// One sample of a run at t = t0 + n / fs exactly (RunControl::sample_rate_hz;
// sample_time_s), from the integrator's dense output inside the accepted step
// that holds it (RK4: its continuous extension of order 3; the adaptive
// Dormand-Prince: its own of order 4); a sample at a step's end is that
// step's state. Steps end at events, so a sample belongs to one mode's step:
// at an event time it is the left limit, in the mode before the event.
struct SampleRow {
  double t_s;
  double theta1_rad;
  double theta2_rad;
  double w1_rad_per_s;
  double w2_rad_per_s;
  // w1', w2' (RunControl::sample): interval averages [w(t_n) - w(t_{n-1})] /
  // (t_n - t_{n-1}) of the dense output, or under SampleKind::point the
  // equations of motion at the sampled state in its step's mode (the
  // derivative of the interpolant would be an order less accurate).
  double acceleration1_rad_per_s2;
  double acceleration2_rad_per_s2;
  double s_m;
  // s - B: the deflection measured from the contact of the drive flank N1
  // (the sweep's dte_contact with T1 loading N1): positive in an N1 contact,
  // -2B at the onset of an N2 contact.
  double dte_m;
  // Normal forces summed over the loaded pairs of each line (0 off it).
  double normal_force_n1_n;
  double normal_force_n2_n;
  int region;
  int pairs;
};

// The time of sample n of a run that starts at t0: the one formula of the
// sampled rows, so that a caller computes the same doubles.
inline double sample_time_s(double t0_s, long long n, double sample_rate_hz) {
  return t0_s + static_cast<double>(n) / sample_rate_hz;
}

// One impact: a contact that begins at `start_s` with approach speed Vi on
// `line`; it ends (if it ends within the run) with separation speed `end_speed_m_s`.
// A run that starts in contact counts that contact as an impact at t = 0.
struct ImpactRecord {
  Region line;
  double start_s;
  double impact_speed_m_s;  // Vi, d(delta)/dt at onset
  double restitution;       // e(Vi) of (33)
  std::optional<double> end_s;
  std::optional<double> end_speed_m_s;  // -d(delta)/dt when the contact ends
};

// How a loose gear moves against its driver over a run: no impact after the
// start, impacts on one flank only, or on both (rattle).
enum class RattleRegime { no_impact, single_sided, double_sided };
inline constexpr std::array<NamedValue<RattleRegime>, 3> kRattleRegimes{{
    {RattleRegime::no_impact, "no-impact", "no impact after the start"},
    {RattleRegime::single_sided, "single-sided", "impacts on one flank only"},
    {RattleRegime::double_sided, "double-sided", "impacts on both flanks: rattle"},
}};

// The rattle outputs of a run under a kinematic driver ([torque1] kind =
// "prescribed-speed"), docs/model.md section Rattle of a loose gear. A contact
// the run starts in is no impact here.
struct RattleSummary {
  double impacts_per_s_n1 = 0.0;  // drive flank
  double impacts_per_s_n2 = 0.0;  // back flank
  // Vi of the impacts along the line of action (0 without impacts).
  double impact_speed_mean_m_s = 0.0;
  double impact_speed_max_m_s = 0.0;
  // The Hertzian damping loss per second of the run: what the impacts
  // dissipate (the viscous mesh damper's loss is not counted).
  double impact_power_w = 0.0;
  // sqrt(Int w2'^2 dt / duration), each step's w2' its mean change of w2.
  double rms_acceleration2_rad_s2 = 0.0;
  // The same of the run with backlash 0 (started at the same penetration),
  // and the ratio: the rattle index. Absent for a continued run, and where
  // negative tooth errors (modifications) use up part of the backlash, which
  // the twin does not have; with backlash 0 already the index is 1.
  std::optional<double> rms_acceleration2_no_backlash_rad_s2;
  std::optional<double> rattle_index;
  RattleRegime regime = RattleRegime::no_impact;
};

// What the planar ledger adds to SimulationSummary's energies (which then
// hold the mesh's stored energy, the kinetic energy of every body, the
// torque work and the mesh's losses): the bearings' and the shafts' strain
// energy and damping loss. A torsional run has none.
struct PlanarEnergies {
  double bearing_energy_initial_j = 0.0;
  double bearing_energy_final_j = 0.0;
  double bearing_damping_loss_j = 0.0;
  double shaft_energy_initial_j = 0.0;
  double shaft_energy_final_j = 0.0;
  double shaft_damping_loss_j = 0.0;
};

// The largest magnitudes, over the ends of a planar run's accepted steps, of
// a helical pair's axial force (the same on both gears) and tilting moments
// (PlanarRow's axial_force1_n, ...): reported, not in the planar model.
struct HelicalThrustMaxima {
  double axial_force_max_n = 0.0;
  double tilting_moment1_max_n_m = 0.0;
  double tilting_moment2_max_n_m = 0.0;
};

// One slice of a helical pair's face in a two-gear run by route A (sliced_pair.hpp): its name
// in the train's run (mesh_slice1, ...), the contacts begun on each line (a contact at the start
// counts), its largest penetration and its losses (the Hertzian damping's and the viscous mesh
// damper's).
struct SliceSummary {
  std::string name;
  int impacts_n1 = 0;
  int impacts_n2 = 0;
  double max_penetration_m = 0.0;
  double damping_loss_j = 0.0;
  double mesh_damping_loss_j = 0.0;
};

struct SimulationSummary {
  std::string case_name;
  std::string integrator;
  // The reading of the Hertzian D the run took (model.damping_update with
  // "auto" resolved by the bearings: resolved_damping_update).
  DampingUpdate damping_update = DampingUpdate::each_impact;
  // The drift check (SpeedDriftMonitor, gearimpact/dynamics/drive.hpp): the
  // largest |mean pinion speed / reference mean - 1| over the run's whole
  // revolutions; none before one. A planar run above drive.speed_tolerance warns.
  std::optional<double> speed_drift_max_rel;
  // A frozen D as a damping ratio of the mesh's relative mode
  // (equivalent_mesh_damping_ratio below); none under the other readings.
  std::optional<double> equivalent_mesh_damping_ratio;
  // model.friction_coefficient, f of the constant law: the coefficient of every
  // pair under friction_law = "constant" only.
  double friction_coefficient = 0.0;
  FrictionLaw friction_law = FrictionLaw::constant;
  // Under the other laws, the line's coefficient sum(f N) / sum(N) over its
  // loaded pairs at the end of each accepted step: its mean over the loaded
  // time (each value weighted by its step's length) and its largest value.
  // Absent under the constant law, or without loaded time.
  std::optional<double> friction_coefficient_mean;
  std::optional<double> friction_coefficient_max;
  double end_time_s = 0.0;
  double step_s = 0.0;
  int impacts_n1 = 0;
  int impacts_n2 = 0;
  std::optional<double> first_impact_s;
  std::optional<double> first_impact_speed_m_s;
  std::optional<double> last_n1_impact_s;
  std::optional<double> last_n2_impact_s;
  double max_penetration_m = 0.0;
  // Energies, J. Losses and works are integrals from 0 to end_time_s.
  double kinetic_energy_initial_j = 0.0;
  double kinetic_energy_final_j = 0.0;
  double stored_energy_initial_j = 0.0;
  double stored_energy_final_j = 0.0;
  double torque_work_j = 0.0;
  double damping_loss_j = 0.0;
  double friction_loss_j = 0.0;
  double mesh_damping_loss_j = 0.0;  // Int c s'^2 dt of the viscous mesh damper
  // Whether the run has that damper (model.mesh_damping_ratio > 0): then the
  // summary's JSON books its loss as mesh_damper_loss_J, which other runs'
  // summaries leave out so that they keep their bytes.
  bool mesh_damper = false;
  // Work of the time-varying stiffness: the integral of 0.5 delta^2 dKe/dX dX/dt
  // plus the jumps of stored energy when a pair enters or leaves under load.
  // Both 0 with mesh_force = "lagrangian", whose forces do that work on the
  // pinion instead (its kinetic energy pays it).
  double parametric_work_j = 0.0;
  double parametric_jump_work_j = 0.0;
  // Under mesh_force = "lagrangian" only: the sum of |dU| over the jumps of the
  // stored energy where a pair enters or leaves, which the pinion's kinetic
  // energy (or a kinematic driver's work) paid. With enough tip relief a pair
  // enters and leaves unloaded and this is 0.
  std::optional<double> stored_energy_jumps_j;
  // The largest stored energy of each term of (29) over the run (kTerms order;
  // 0 for a term the stiffness model does not have).
  std::array<double, kTermCount> energy_max_j{};
  StiffnessModelKind stiffness_model = StiffnessModelKind::yang_lin_1987;
  // Whether the model's fillet-foundation term uses the fit of Sainsot et al.
  // (2004) outside its range (false for a model without that term).
  bool foundation_extrapolated = false;
  // Which gears, with the fit's inputs (empty unless foundation_extrapolated).
  std::vector<FoundationExtrapolation> foundation_extrapolations;
  // (kinetic + stored)(t) - (kinetic + stored)(0) - torque work + losses -
  // parametric work: zero for the exact solution. Final value and largest |value|.
  double ledger_residual_j = 0.0;
  double ledger_residual_max_j = 0.0;
  // The largest kinetic + stored energy of the run, the scale of the residual.
  double ledger_scale_j = 0.0;
  double final_w1_rad_per_s = 0.0;
  double final_w2_rad_per_s = 0.0;
  long long steps = 0;   // accepted steps, including those cut at events
  long long events = 0;  // mode changes located
  long long rhs_evaluations = 0;
  std::optional<RattleSummary> rattle;   // only under a kinematic driver
  std::optional<PlanarEnergies> planar;  // only with [bearings] kind = "elastic"
  // Only for a helical pair on elastic bearings.
  std::optional<HelicalThrustMaxima> helical_thrust;
  // Only for a helical pair run by route A (simulate_by_slices): each slice's summary.
  std::vector<SliceSummary> slices;
};

// What a contact remembers from its onset, (32),(33): with no impact, D keeps
// the last impact's value.
struct ContactMemory {
  double damping_per_stiffness_s_m = 0.0;  // D / K of (32)
  double frozen_stiffness_n_per_m = 0.0;   // K for the pitch-pair and Hertz readings
};

// Where a run ended, to continue from: the time, the state, and the damping of
// the contact it may be in. A planar run's ([bearings] kind = "elastic") adds
// its whole state (`state` then holds its gears' angles and speeds) and the
// coast line's contact memory (`contact` is the drive line's): each line of
// action remembers its own.
struct RunState {
  double time_s = 0.0;
  InitialState state;
  ContactMemory contact;
  std::optional<PlanarState> planar;
  ContactMemory coast_contact;
};

struct SimulationResult {
  std::vector<SeriesRow> series;
  std::vector<SampleRow> samples;  // with RunControl::sample_rate_hz and keep_samples
  std::vector<ImpactRecord> impacts;
  SimulationSummary summary;
  RunState final_state;
  // With [bearings] kind = "elastic" (planar.hpp): the planar rows (with
  // RunControl::keep_series) beside `series`, and the final planar state.
  std::vector<PlanarRow> planar_series;
  // Its samples (PlanarSample) with RunControl::sample_rate_hz and keep_samples.
  std::vector<PlanarSample> planar_samples;
  std::optional<PlanarState> planar_final_state;
  // With [tacho] pulses_per_revolution > 0 (planar runs): the true edge
  // times, jitter-free (signals::tacho_jitter gives the emitted ones).
  std::vector<double> tacho_times_s;
  double start_time_s = 0.0;  // 0, or the time a continued run resumed at
};

// The impacts a run struck: its impact records but a contact it started in
// (the ones the rattle summary counts), in time order.
std::vector<ImpactRecord> struck_impacts(const SimulationResult& result);

// The distribution of the struck impacts' Vi: `bins` bins of equal width from
// 0 to the largest Vi, bin i holding lower_m_s[i] <= Vi < upper_m_s[i] and the
// last bin its upper edge too. No bins without impacts.
struct ImpactSpeedHistogram {
  std::vector<double> lower_m_s;
  std::vector<double> upper_m_s;
  std::vector<long long> count_n1;
  std::vector<long long> count_n2;
};
inline constexpr int kImpactSpeedBins = 20;
ImpactSpeedHistogram impact_speed_histogram(const std::vector<ImpactRecord>& struck,
                                            int bins = kImpactSpeedBins);

// Thrown when RunControl::should_stop asks a run to stop.
class SimulationStopped : public SimulationError {
 public:
  using SimulationError::SimulationError;
};

// What a sample's accelerations are (docs/signals.md, "The sensor's sample").
// interval-average: the exact mean of the acceleration over the interval that
// ends at the sample, a_n = [v(t_n) - v(t_{n-1})] / (t_n - t_{n-1}), v the
// velocity from the integrator's dense output at both ends. Its transfer is
// H(f) = sinc(f T) e^{-i pi f T} (T = 1 / fs): the droop of sinc(f T) = sin(pi
// f T) / (pi f T) and a delay of T / 2; H vanishes at every multiple of fs, so
// the steps of the acceleration (pair entries, friction reversals) fold back
// at second order in 1 / fs instead of first. Sample n = 0 has no interval: an
// interval-average run's samples are n = 1, 2, ...
// point: the acceleration at t_n from the equations of motion (the values before
// the interval average existed; a point value of an acceleration that steps).
// Only the accelerations differ: angles, velocities, forces and deflections are
// point values of the state at t_n in both.
enum class SampleKind { interval_average, point };
inline constexpr std::array<NamedValue<SampleKind>, 2> kSampleKinds{{
    {SampleKind::interval_average, "interval-average",
     "the mean acceleration over the interval ending at each sample (velocity difference / T)"},
    {SampleKind::point, "point", "the acceleration at each sample's instant"},
}};

struct TrainRow;  // dynamics/train.hpp

// Controls that are not part of the physical case.
struct RunControl {
  bool keep_series = true;
  // false: no event location, the mode (region, pairs, friction sign) is
  // re-evaluated at every RK4 stage. Exists only to show what the cut buys.
  bool locate_events = true;
  // An observer of the output grid: called with every row the series would
  // keep (every output_every-th step), whether or not keep_series.
  std::function<void(const SeriesRow&)> on_row;
  // The same for the planar rows of a case with [bearings] kind = "elastic".
  std::function<void(const PlanarRow&)> on_planar_row;
  // The same for a gear train's rows (simulate_train), whether or not keep_series.
  std::function<void(const TrainRow&)> on_train_row;
  // The most rows the series (kept or observed) may have, checked before the
  // run against series_rows(); refused with the estimate, naming
  // integrator.end_time. It bounds the samples too (sample_count()), naming
  // sample_rate.
  long long most_series_rows = kMostSeriesRows;
  // Samples at t = t0 + n / sample_rate_hz (Hz, finite and > 0), n = 0, 1, ...
  // up to the run's end (SampleRow): kept in SimulationResult::samples when
  // keep_samples, and passed to on_sample. They are interpolated inside the
  // accepted steps and leave the integration as it is. Needs locate_events.
  std::optional<double> sample_rate_hz;
  // The samples' accelerations: interval averages (from n = 1 on) or point values.
  SampleKind sample = SampleKind::interval_average;
  bool keep_samples = true;
  std::function<void(const SampleRow&)> on_sample;
  // The same for the samples of a case with [bearings] kind = "elastic".
  std::function<void(const PlanarSample&)> on_planar_sample;
  // The same for a gear train's samples (simulate_train: its sensor's).
  std::function<void(const TrainRow&)> on_train_sample;
  // When set, asked every kStepsBetweenStopChecks steps; true ends the run
  // with SimulationStopped. Lets a caller cancel a long run (an interactive
  // session's Ctrl-C, a time limit); it may also throw its own exception.
  std::function<bool()> should_stop;
  // Continue a run: start at resume->time_s from its state and contact
  // memory (a contact in progress is not a new impact), and run for the
  // case's end_time_s. The case's initial state is not used then.
  std::optional<RunState> resume;
};

// Often enough to stop within about a millisecond of the paper's cases, rarely
// enough that the check costs nothing next to the steps.
inline constexpr long long kStepsBetweenStopChecks = 16384;

// The rows of a run's time series: the start and every output_every-th step
// of end_time / step. The adaptive integrator's steps vary; its first step
// stands in for them, so its count is an estimate.
double series_rows(const SimulationCase& c);

// The checks of a case with gaps between the flanks ([modifications]: a relief
// amount or a tooth error not 0) that the dynamics needs beyond the fields:
// InputError naming model.mesh_stiffness under a constant mesh stiffness
// (which has no teeth to modify), and gears.backlash when negative gaps
// (thicker teeth, pitch or profile deviations) could press the drive and the
// coast flanks at once (2 B + the least gap on N1 + that on N2 < 0, a bound
// over every pair). simulate(), validate() and the run pool call it.
void validate_gaps(const SimulationCase& c);
// A table given with a case must be the table of its pair and model; one
// built from a function must at least cover the contact segment. Throws
// InputError naming "table".
void check_table(const SimulationCase& c, const StiffnessTable& table);
// What simulate() refuses of the planar keys: elastic shafts on rigid
// bearings (the motor and the load belong to the planar model), naming
// shafts.kind, and a tacho on rigid bearings.
void refuse_planar_simulation(const SimulationCase& c);
// The sample grid of a run of end_time_s (integrator.end_time) at
// sample_rate_hz: the n >= 0 with sample_time_s(t0, n, rate) <= t0 +
// end_time_s, for t0 = 0 (about floor(end_time_s rate) + 1; a continued run's
// start moves the end's rounding). Interval averages (SampleKind) leave out
// n = 0: one sample fewer.
double sample_count(double end_time_s, double sample_rate_hz, double t0_s = 0.0);

// Throws InputError naming sample_rate unless RunControl::sample_rate_hz is
// absent, or finite and > 0 with event location and at most most_series_rows
// samples (sample_count) over a run of end_time_s; row_bytes, a sample's row
// as CSV, sizes the refusal's estimate. simulate(), simulate_planar() and
// simulate_train() call it before any work.
void validate_sampling(double end_time_s, double row_bytes, const RunControl& control);
// The same for a run of c, whose rows are SampleRow's or PlanarSample's.
void validate_sampling(const SimulationCase& c, const RunControl& control);

// Throws InputError naming the first field outside its range (validate_fields),
// then the planar keys (refuse_planar_simulation, and with elastic bearings the mounting's
// fields: validate_planar of planar.hpp), then the gaps of its modifications (validate_gaps),
// then what the fields imply together (validate_implied of step_bound.hpp).
void validate(const SimulationCase& c);

// What a user should hear before running a valid case, each a sentence with its numbers and the
// value that cures it: mean torques that do not balance (T1/Rb1 + T2/Rb2 != 0: the pair
// accelerates without bound) and initial speeds that do not roll (Rb1 w1 != Rb2 w2: the teeth
// start with a relative speed). A driver's and a drag's means are not known before the run, so a
// driven case is checked for its speeds only. Bounds as require_balanced_mean_torques: 1e-9.
std::vector<std::string> run_warnings(const SimulationCase& c);

// A frozen D (32) as a damping ratio: the Hertzian damper (34) linearised about the static
// deflection delta_s = F_s / k_mean, G = D delta delta' ~ (D delta_s) delta' per loaded pair.
// With D = Ke g, g = damping_factor_per_stiffness(form, e(V_ref), V_ref) and K each loaded pair's
// current Ke (damping_stiffness = "current-pair"), the pairs' dampers sum to the viscous
// c = g k_mean delta_s = g F_s, whose ratio to the relative mode's critical damping is
//   zeta = g F_s / (2 sqrt(k_mean m_e)).
// F_s is the static mesh force of the load: |mean torque2| / Rb2, else |mean torque1| / Rb1.
// None unless the resolved reading is frozen, K is the current pair's and a mean torque is known.
std::optional<double> equivalent_mesh_damping_ratio(const SimulationCase& c,
                                                    const StiffnessTable& table);

// What a user should hear about a finished run: teeth that overlapped on the line of action by
// more than kMostPlausibleOverlapModules of the module, far beyond any elastic deflection. That
// happens where a pair enters the contact segment already pressed in (after a missing or broken
// tooth the gears turn freely until the next pair reaches the segment), where real teeth would
// have met before it, at the tip's corner, which a line-of-action model does not describe.
inline constexpr double kMostPlausibleOverlapModules = 0.05;
std::vector<std::string> result_warnings(const SimulationCase& c, const SimulationSummary& s);
// The warning of a signal run whose body (`body`: "the pinion", "body NAME") drifted from its
// speed reference by `drift` (speed_drift_max_rel) over `tolerance` (drive.speed_tolerance),
// its torque `drive` keyed `torque_key` ("torque1", "bodies.NAME.torque"): what moved it and
// the key that holds it.
std::string speed_drift_warning(double drift, double tolerance, const Torque& drive,
                                const std::string& body, const std::string& torque_key);

class CheckedRun;

// The case as the dynamics run it: a helical pair (gears.helix_angle > 0)
// replaced by its transverse section with its contact lines' sweep
// (swept_transverse_pair: lengths, radii, masses and the backlash B along the
// transverse line of action), each tooth pair reading the face-integrated
// table of run_table; a spur case unchanged.
SimulationCase dynamics_case(const SimulationCase& c);
// The table each tooth pair of a run of c reads: StiffnessTable(c.gears,
// c.model.stiffness), or for a helical pair helical_pair_table (stiffness/helical.hpp).
std::shared_ptr<const StiffnessTable> run_table(const SimulationCase& c);
// What a run refuses of a helical pair (none for a spur one), naming the key:
// modifications (which route A runs, sliced_pair.hpp), the friction that
// refuse_helical_friction refuses (docs/helical.md, Dynamics), and
// gears.face_width where eps_gamma reaches MeshLayout::capacity - 1.
void refuse_helical_run(const SimulationCase& c);
// Its refusals of a helical pair's friction (none for a spur pair), which a
// train's helical mesh meets too: model.friction_law other than "constant",
// a friction coefficient with [[faults]] or with model.friction_smoothing_speed.
void refuse_helical_friction(const SimulationCase& c);

// Checks a run once (what simulate() checks, in its order): the case's keys and fields
// (validate_absent_run_keys, validate_fields), a helical pair's refusals (refuse_helical_run),
// then on the case the dynamics run (dynamics_case, which the CheckedRun holds) the planar keys
// (refuse_planar_simulation), the gaps of its modifications (validate_gaps); then the run's
// controls (the series and sample bounds, a resumed state) and the planar mounting
// (validate_planar); then its stiffness table (built here, or the one given, which check_table
// checks against the case), the planar step bound (check_planar_step) and what the fields imply
// with that table (validate_implied). Throws InputError naming the key, before any run.
// `fields_checked`, when given, is called once the case's keys, fields and gaps pass, before the
// controls and the table (which may take a while): the program says its warnings there
// (run_warnings).
CheckedRun check_run(const SimulationCase& c, const RunControl& control = {},
                     const std::function<void()>& fields_checked = {});
CheckedRun check_run(const SimulationCase& c, std::shared_ptr<const StiffnessTable> table,
                     const RunControl& control = {});

// A run that check_run checked: the case, its table and the controls it was checked with. Only
// check_run makes one, and simulate(const CheckedRun&) runs it without checking it again.
class CheckedRun {
 public:
  const SimulationCase& simulation_case() const { return case_; }
  const StiffnessTable& table() const { return *table_; }
  const RunControl& control() const { return control_; }

 private:
  CheckedRun(SimulationCase c, std::shared_ptr<const StiffnessTable> table, RunControl control)
      : case_(std::move(c)), table_(std::move(table)), control_(std::move(control)) {}
  friend CheckedRun check_run(const SimulationCase& c, const RunControl& control,
                              const std::function<void()>& fields_checked);
  friend CheckedRun check_run(const SimulationCase& c, std::shared_ptr<const StiffnessTable> table,
                              const RunControl& control);

  SimulationCase case_;
  std::shared_ptr<const StiffnessTable> table_;
  RunControl control_;
};

// The checks of a run's controls against its case (what check_run checks of them): the series
// bound (naming integrator.end_time), the samples (validate_sampling) and a resumed state.
void validate_run_control(const SimulationCase& c, const RunControl& control);

// The run of a checked case, with the controls it was checked with.
SimulationResult simulate(const CheckedRun& run);
// check_run, then that run: every check once, in that order. A helical pair with
// modifications runs by route A instead (simulate_by_slices, dynamics/sliced_pair.hpp).
SimulationResult simulate(const SimulationCase& c, const RunControl& control = {});
// Same, with a stiffness table already built for c.gears and c.model.stiffness
// (checked when the table knows what it was built for: StiffnessTable::built_for).
SimulationResult simulate(const SimulationCase& c, const StiffnessTable& table,
                          const RunControl& control = {});

}  // namespace gearimpact
