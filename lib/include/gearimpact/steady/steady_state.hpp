// The steady state of the loaded, running pair, found by running it (docs/steady-state.md sections
// 1 and 4): the gear model is run one excitation period at a time, the state (s, s') is sampled at
// the end of each period, and the run is steady when those Poincare samples repeat with a period
// of 1 to max_period excitation periods (periodicity.hpp); aperiodic or not converged within the
// limit otherwise, never an assumed value.
//
// What a point carries to the next (continuation): the whole RunState, i.e. the angles, the speeds
// and the contact memory (the Hertzian D of the last impact). Under DampingUpdate::each_impact a
// no-impact point therefore keeps the D of the last impact of an earlier point; frozen or off
// remove that history, so a sweep whose branches must not depend on it should use one of them.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/steady/periodicity.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// Relative to the loaded flank (N1 when T1's mean is >= 0, else N2): NI the loaded flank never
// separates, SS impacts on the loaded flank only, DS impacts on the other flank too (rattle),
// NC no contact at all over the steady window (an unloaded pair drifting in the backlash).
enum class Regime { no_impact, single_sided, double_sided, no_contact };
std::string to_string(Regime regime);  // "NI", "SS", "DS", "NC"

struct SteadySettings {
  // The RK4 step is the contact period 2 pi sqrt(m_e / k_max) over this, rounded down so that an
  // excitation period is a whole number of steps: the samples fall on the grid.
  double steps_per_contact_period = 128.0;
  // Samples repeat when they agree within this fraction of B in s and of B w_n in s'
  // (w_n = sqrt(k_mean / m_e)), periodicity.hpp.
  double tolerance = 1e-6;
  int max_period = 8;
  std::size_t window = 16;
  std::size_t trend_window = 64;
  // The most excitation periods one point may run before it is reported not converged.
  int max_periods = 3000;
};

// The most tooth patterns (true periods of faulted teeth) one Poincare period may hold when a
// torque's forcing is commensurate with them only over several (steady_timing).
inline constexpr long long kMostToothPatternsPerPoincarePeriod = 100;

// The sampling (Poincare) period and the step of a case (docs/steady-state.md, "Poincare
// period"). Without faults: the forcing period 2 pi / w when the torques fluctuate (their
// angular frequencies must be whole multiples of the lowest), else the mesh period
// 2 pi / (z1 w1_mean), w1_mean the mean pinion speed of the rolling pair with the case's
// momentum J1 w1/Rb1 + J2 w2/Rb2; under a prescribed-speed driver the common period of its
// orders and the mesh. With faults (SimulationCase::faults) the teeth repeat only after their
// true period P, N mesh periods (a pinion or wheel revolution, or the hunting period,
// true_period_mesh_periods), and the Poincare period is the least common period of P and the
// driver's or the forcing's period: for a forcing of period T, q P = p T with whole p and the
// least q <= kMostToothPatternsPerPoincarePeriod (to 1e-9 relative), P taken at the mean speed
// including the forcing's share of the momentum; otherwise the forcing is incommensurate and
// refused.
struct SteadyTiming {
  double excitation_period_s = 0.0;
  double step_s = 0.0;
  long long steps_per_period = 0;
  // What the period is the common period of, joined by "+": "mesh" (every tooth alike),
  // "pinion-revolution", "wheel-revolution" or "hunting" (faulted teeth), "forcing" (a torque's
  // fluctuation), "driver" (a prescribed speed's orders, or its revolution).
  std::string kind;
  // The mesh periods in it; 0 when it is not tied to the mesh (a healthy pair's forcing period).
  long long mesh_periods = 0;
};

// The angular frequencies of the torques' fluctuations (the harmonics with amplitude != 0 and
// frequency != 0, in the order of torque1 then torque2); empty for torques that do not
// fluctuate.
std::vector<double> forcing_frequencies(const SimulationCase& c);

// Throws InputError naming the key unless the case can have a steady state: torques constant,
// sinusoidal or harmonic (a user function's mean and period are not known); mean torques balanced
// (T1/Rb1 + T2/Rb2 = 0, both along the line of action as in docs/model.md's equations of motion);
// no friction: friction loss f N |Vs| is drawn from the mean rotation, which balanced torques do
// not feed, so with f > 0 the pair slows down without end. A case with faults is sampled at
// its true period (SteadyTiming).
void require_steady_case(const SimulationCase& c);

// A pair with less backlash than this many modules (none at all, B = 0) measures
// its relative positions on this length instead: the size of a precision
// gear's profile error (about 2 um at m = 2 mm), below which two states of a
// real pair are not told apart.
inline constexpr double kLeastStateScalePerModule = 1e-3;

// The scales (L, L w_n) of s and s' in the periodicity test and the shooting,
// L = max(B, kLeastStateScalePerModule module), w_n = sqrt(k_mean / m_e):
// positive for every pair, the backlash itself for every pair with some.
// Throws as natural_frequency_rad_per_s.
Eigen::Vector2d state_scale(const SimulationCase& c, const StiffnessTable& table);

// The coordinates a steady state is sampled in (the Poincare sample of find_steady_state) and the
// period map's state (period_map.hpp): (s, s') of the gears' turning, s = Rb1 theta1 -
// Rb2 theta2; for a case on elastic bearings whose state holds its planar state, then the
// centres x1, y1, x2, y2 and with shafts the twists Rb1 (theta_m - theta1), Rb2 (theta_l -
// theta2), as lengths, then their speeds in the same order: 10 coordinates, 14 with shafts. A
// periodic motion repeats every one of them; the rigid rotation (the mean angle, which grows,
// and its speed) is left out.
Eigen::VectorXd poincare_state(const SimulationCase& c, const RunState& state);
// Their scales in the same order: (L, L w_n) of state_scale for (s, s'), then L for each planar
// displacement and L w_n for each planar speed.
Eigen::VectorXd poincare_scale(const SimulationCase& c, const StiffnessTable& table);

// The case a steady state, a sweep point or a period map runs: a helical pair's transverse
// section (dynamics_case of dynamics/simulate.hpp), on rigid or elastic bearings, after what
// its run refuses by name (refuse_helical_run: friction, faults, modifications); a spur case
// unchanged. Every function here taking a helical case runs this case, with the table the
// caller gives, which for a helical pair must be its pair table (run_table), as in simulate.
SimulationCase steady_dynamics_case(const SimulationCase& c);

// Throws InputError as require_steady_case, and when the torques' frequencies have no common
// period, a faulted case's forcing is incommensurate with its teeth (naming the forcing's key
// and initial.w1), or (without fluctuation) the mean speed is 0.
SteadyTiming steady_timing(const SimulationCase& c, const StiffnessTable& table,
                           const SteadySettings& settings);

struct PoincareSample {
  double s_m = 0.0;
  double s_rate_m_s = 0.0;
};

struct SteadyPoint {
  PeriodicityVerdict verdict = PeriodicityVerdict::not_converged;
  int period = 0;          // in excitation periods when periodic, else 0
  bool converged = false;  // periodic or aperiodic; the figures below are empty otherwise
  Regime regime = Regime::no_contact;
  int periods_run = 0;
  SteadyTiming timing;
  // Over the steady window (the last `period` periods, or the last `window` periods when
  // aperiodic), from the output grid with the extremes of s between grid points taken from the
  // cubic Hermite interpolant of s and s': mean of s, half its peak-to-peak, RMS about the mean.
  std::optional<double> dte_mean_m;
  std::optional<double> dte_amplitude_m;
  std::optional<double> dte_rms_m;
  std::optional<double> s_min_m;
  std::optional<double> s_max_m;
  // The same window's deflection into the loaded flank, measured from the contact: s - B when
  // the drive flank N1 is loaded, -s - B when the coast flank N2 is (B half the total play, so
  // that contact is at s = +-B): positive in contact, negative when the flanks have separated.
  std::optional<double> dte_contact_mean_m;
  std::optional<double> dte_contact_min_m;
  std::optional<double> dte_contact_max_m;
  // The speeds that ran: the means of w1 and w2 over the window's rows, the pinion's in rpm, and
  // the mesh frequency z1 |w1| / (2 pi) in Hz.
  std::optional<double> w1_mean_rad_s;
  std::optional<double> w2_mean_rad_s;
  std::optional<double> pinion_rpm;
  std::optional<double> mesh_frequency_hz;
  // The largest mesh force (normal forces summed) over the static load |T1_mean| / Rb1; empty
  // without load.
  std::optional<double> dynamic_factor;
  std::optional<double> impacts_drive_per_period;  // N1
  std::optional<double> impacts_coast_per_period;  // N2
  // The last `period` samples when periodic, the last `window` ones otherwise.
  std::vector<PoincareSample> poincare;
  // Where the point ended, at time 0 of the excitation: the start of the next point.
  RunState final_state;
  std::string explanation;
};

// The period as the sweep's files write it: "1" to "8" when periodic, "aperiodic", or empty when
// not converged.
std::string period_label(const SteadyPoint& point);

// Runs c (from `start` when given, else from c.initial at t = 0) period by period until its
// Poincare samples settle. Throws InputError as steady_timing, SimulationError from the run.
// A case on elastic bearings runs the planar model (dynamics/planar.hpp): each period continues
// its planar state (RunState::planar; a start without one puts the centres at rest on their
// bearings, as planar_initial_state), and its Poincare samples add to (s, s') of the gears'
// turning the centres x1, y1, x2, y2 (and with shafts the twists Rb1 (theta_m - theta1),
// Rb2 (theta_l - theta2)) on the scale L of state_scale, then their speeds on L w_n, so that a
// point is periodic when every coordinate repeats. Its s (the figures above) is the drive line's
// s_d, which adds the centres' relative motion along the line; the step also resolves the planar
// system's shortest period (planar_largest_step_s). final_state then holds the planar state.
// With rigid bearings the samples are (s, s') alone.
SteadyPoint find_steady_state(const SimulationCase& c, const StiffnessTable& table,
                              const SteadySettings& settings,
                              const std::optional<RunState>& start = std::nullopt);

}  // namespace gearimpact
