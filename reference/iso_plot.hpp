// The dynamic factor against ISO 6336-1's resonance ratio N = w1 / w_E1 with ISO's K_v of perfect
// gears beside it (docs/steady-state.md sections 3.5 and 4), for `sweep`, `merge` and `reproduce`;
// the axes are those of IsoScale (steady/iso_resonance.hpp).
#pragma once

#include <filesystem>
#include <string>

#include "gearimpact/steady/iso_resonance.hpp"
#include "gnuplot.hpp"

namespace gearimpact::cli {

// Writes FILE: N and ISO's K_v of perfect gears on 401 points from 0 to n_max.
void write_iso_kv_band(const std::filesystem::path& file, const IsoScale& scale, double n_max);
// The largest K_v among those points with N in [from, to] (0 for none): what the band shows of
// ISO's K_v over that range, for the figure's y range.
double highest_iso_kv(const IsoScale& scale, double n_max, double from, double to);

// The figure `name`: from `data` (CSV with a header) the dynamic factor in column df_column
// against N in n_column, up and down told apart by the word in direction_column; ISO's K_v from
// `band` (write_iso_kv_band), N = 1 marked, and N with ISO's own c_gamma_alpha on the top axis.
// With `quasi_static` the figure also draws the dynamic factor over the quasi-static peak, the
// column over IsoScale::quasi_static_force_ratio (the run's zero-speed limit), which tends to 1
// where ISO's K_v does, and its labels say which curve is which.
Figure dynamic_factor_vs_iso_n(const std::string& name, const IsoScale& scale,
                               const std::string& data, int direction_column, int n_column,
                               int df_column, const std::string& band, bool quasi_static = false);

}  // namespace gearimpact::cli
