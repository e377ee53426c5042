// Table 1 of the paper: its three cases on the gear pair of section 7, under
// each reading docs/model.md leaves open (section Readings).
#pragma once

#include <array>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/named_values.hpp"

namespace gearimpact {

// Units of Table 1's torques. docs/model.md: kgf-mm by default (only they reproduce
// Fig. 7), N-mm as the table labels them.
enum class TorqueUnit { kgf_mm, n_mm };
inline constexpr std::array<NamedValue<TorqueUnit>, 2> kTorqueUnits{{
    {TorqueUnit::kgf_mm, "kgf-mm", "docs/model.md's reading, the only one that reproduces Fig. 7"},
    {TorqueUnit::n_mm, "n-mm", "as Table 1 labels its torques"},
}};

// The paper's cases 1, 2, 3 (Table 1) on paper_gear_pair(). Case 3's forcing
// frequency: 10000 rad/s by default (the OCR's literal "10000"), 1000 the
// alternative. Throws InputError for another case number.
SimulationCase paper_case(int number, TorqueUnit unit = TorqueUnit::kgf_mm,
                          double case3_angular_frequency_rad_per_s = 10000.0);

// One choice for each reading docs/model.md leaves open; the defaults are docs/model.md's.
struct PaperReading {
  TorqueUnit torque_unit = TorqueUnit::kgf_mm;
  double case3_angular_frequency_rad_per_s = 10000.0;
  DampingForm damping_form = DampingForm::herbert_mcwhannell;
  DampingStiffness damping_stiffness = DampingStiffness::current_pair;
  RestitutionLaw restitution;
  CoastPhase coast_phase = CoastPhase::half_base_pitch;
  AxialMomentSign moment_sign = AxialMomentSign::physical;
};

// Table 1's case under a reading.
SimulationCase paper_case(int number, const PaperReading& reading);

// Newton metres per unit of Table 1.
double torque_unit_n_m(TorqueUnit unit);

// How the paper's pair is loaded for a steady state (docs/steady-state.md section 1).
struct PairLoad {
  double static_force_n = 1000.0;  // F on the line of action: T1 = F Rb1, T2 = -F Rb2
  DampingUpdate damping_update = DampingUpdate::off;
  double damping_reference_speed_m_s = 1.0;  // V_ref of DampingUpdate::frozen
  // The teeth start on the drive flank at the static deflection F / k of this
  // stiffness, so that a run starts in contact.
  double deflection_stiffness_n_per_m = 1.0e9;
};

// The paper's pair (case 1's) with its time-varying mesh stiffness, loaded by
// `load` with balanced torques, rolling at w1 (w2 = w1 Rb1 / Rb2), without
// friction (a steady state needs none) and with the viscous mesh damper at
// zeta = 0.05: the loaded pair of the steady-state reproduction, suites and
// benchmark.
SimulationCase loaded_paper_pair(double w1_rad_per_s, const PairLoad& load);

// Case 1's pair as a loose gear on a spring: without friction or Hertzian
// damping, on the constant mesh stiffness k, the pinion driven at
// w1 = W + a sin(q W t + 90 deg) (a prescribed speed) against a constant drag
// T_d on the wheel, and started on the forced solution of the contact: the
// wheel pressed by the drag's static deflection T_d / (Rb2 k) beyond the
// backlash and moving at Rb1 (W + a / (1 - r)) / Rb2, r = m2 (q W)^2 / k with
// m2 = J2 / Rb2^2, so that whatever separates is the forcing's doing, not a
// start transient (docs/model.md, "Rattle of a loose gear"). The integrator's step and end
// time are the caller's.
SimulationCase driven_loose_gear(double k_n_per_m, double mean_speed_rad_per_s, double order,
                                 double amplitude_rad_per_s, double drag_n_m);

}  // namespace gearimpact
