// The dynamic factor against ISO 6336-1's resonance ratio N = w1 / w_E1 with ISO's K_v of perfect
// gears beside it (STEADY-STATE.md sections 3.5 and 4), for `sweep`, `merge` and `reproduce`.
//
// The axis N uses the model's own mean mesh stiffness as c_gamma_alpha b, so that the model's main
// resonance sits near N = 1 (at (d_m1 / d_1)^2 for solid discs, verify/steady/
// test_iso_main_resonance.cpp); N with ISO's own c_gamma_alpha (stiffness/iso6336.hpp) is the
// second axis, a fixed multiple of the first.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gnuplot.hpp"

namespace gearimpact::cli {

struct IsoScale {
  // w_E1 of ISO's (6) with m_red of (30) on the pinion's mean diameter (d_a1 + d_f1) / 2, and
  // c_gamma_alpha b = the model's mean mesh stiffness, or ISO's c_gamma_alpha.
  double resonance_speed_rad_s = 0.0;
  double resonance_speed_iso_stiffness_rad_s = 0.0;
  double contact_ratio = 0.0;  // eps_alpha, for ISO's K_v
  // F_t / b = |T1 mean| / (r1 b): ISO's line load at the reference circle (K_A = 1).
  double line_load_n_m = 0.0;
};

// The scale of c's pair, or nothing when ISO's K_v has no meaning for it (no mean load).
std::optional<IsoScale> iso_scale(const SimulationCase& c, const StiffnessTable& table);

// Writes FILE: N and ISO's K_v of perfect gears on 401 points from 0 to n_max.
void write_iso_kv_band(const std::filesystem::path& file, const IsoScale& scale, double n_max);

// The figure `name`: from `data` (CSV with a header) the dynamic factor in column df_column
// against N in n_column, up and down told apart by the word in direction_column; ISO's K_v from
// `band` (write_iso_kv_band), N = 1 marked, and N with ISO's own c_gamma_alpha on the top axis.
Figure dynamic_factor_vs_iso_n(const std::string& name, const IsoScale& scale,
                               const std::string& data, int direction_column, int n_column,
                               int df_column, const std::string& band);

}  // namespace gearimpact::cli
