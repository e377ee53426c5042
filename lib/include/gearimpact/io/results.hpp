// The program's tables and summaries as text, one writer each, shared by the
// commands and the reproduction: CSV at 17 significant digits (every double
// reads back exactly), JSON with absent values as null.
#pragma once

#include <string>
#include <vector>

#include "gearimpact/batch/sweep_friction.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

// t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,s_m,delta_m,region,pairs,normal_force_N,friction_force_N
std::string series_csv(const std::vector<SeriesRow>& rows);
// The summary as a JSON object.
std::string summary_json(const SimulationSummary& summary);
// Fig. 7: f,ratio_case1,ratio_case2,... (friction loss / damping loss).
std::string friction_sweep_csv(const std::vector<SweepRow>& rows);
// Fig. 8: angle_deg,pairs,hertz_over_bending_one_pair,...
std::string energy_ratios_csv(const std::vector<EnergyRatios>& rows);
// x_m,phi1_rad, the stiffness of every per-tooth term of gear 1 then gear 2
// (kb1,ka1,kb2,ka2), of every per-pair term (kh), and ke, N/m, at each X1.
std::string stiffness_csv(const GearPair& pair, const StiffnessModel& model,
                          const std::vector<double>& x1_m);

}  // namespace gearimpact
