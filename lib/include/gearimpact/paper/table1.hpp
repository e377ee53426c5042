// Table 1 of the paper: its three cases on the gear pair of section 7, under
// each reading MODEL.md leaves open (section Readings).
#pragma once

#include "gearimpact/case/simulation_case.hpp"

namespace gearimpact {

// Units of Table 1's torques. MODEL.md: kgf-mm by default (only they reproduce
// Fig. 7), N-mm as the table labels them.
enum class TorqueUnit { kgf_mm, n_mm };

// The paper's cases 1, 2, 3 (Table 1) on paper_gear_pair(). Case 3's forcing
// frequency: 10000 rad/s by default (the OCR's literal "10000"), 1000 the
// alternative. Throws InputError for another case number.
SimulationCase paper_case(int number, TorqueUnit unit = TorqueUnit::kgf_mm,
                          double case3_angular_frequency_rad_s = 10000.0);

// One choice for each reading MODEL.md leaves open; the defaults are MODEL.md's.
struct PaperReading {
  TorqueUnit torque_unit = TorqueUnit::kgf_mm;
  double case3_angular_frequency_rad_s = 10000.0;
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

}  // namespace gearimpact
