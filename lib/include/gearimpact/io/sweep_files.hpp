// The files of a steady-state sweep (batch/steady_sweep.hpp) and the merge of its shards:
//   sweep.csv     line,direction,index,value_si,regime,period,converged,dte_mean_m,
//                 dte_amplitude_m,dte_rms_m,s_min_m,s_max_m,dte_contact_mean_m,
//                 dte_contact_min_m,dte_contact_max_m,dynamic_factor,impacts_drive_per_period,
//                 impacts_coast_per_period,w1_mean_rad_s,w2_mean_rad_s,pinion_rpm,
//                 mesh_frequency_hz (one row a point; steady_state.hpp says what each is)
//   poincare.csv  line,direction,index,value_si,s_m,ds_m_s (one row a Poincare sample)
//   summary.json  "spec" (what every shard shares), "shard" (of a run), "points_written",
//                 "points_converged", "regimes" (converged points by regime), "jumps" and
//                 "contact_loss" (steady/sweep.hpp: sweep_jumps, contact_changes, of the rows
//                 written), "warnings" (of the run, kept by a merge)
// Numbers at 17 significant digits, so that a merge reads back the very doubles it writes; an
// absent figure (a point not converged) is an empty field. Rows in key order (sweep_key_less).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "gearimpact/batch/steady_sweep.hpp"

namespace gearimpact {

std::string sweep_csv(const std::vector<SweepPointResult>& rows);
std::string poincare_csv(const std::vector<SweepPointResult>& rows);
std::string sweep_summary_json(const SteadySweep& sweep);

// Writes the three files into `dir` (made if missing), each atomically. A command writes them
// into an AtomicFolder (io/atomic_file.hpp), so that the folder appears as a set.
void write_sweep_folder(const std::filesystem::path& dir, const SteadySweep& sweep);

// The rows of the text of a sweep.csv (named `file` in messages) as the points they were
// written from (period_label and the optional figures read back to the same text), checked as
// merge_sweep_folders checks them against the shard's `spec`; throws InputError naming file:line
// of the first bad row.
std::vector<SweepPointResult> parse_sweep_csv(const std::string& text, const std::string& file,
                                              const SteadySweepRecord& spec);

// The shards' folders as one sweep: their rows by key, their common spec. Throws InputError
// (field "merge") naming the folder or file when one is unreadable or not a sweep's, when the
// specs differ (the key that differs; the spec holds a hash of every input of the base case),
// naming the file and line of the first bad row (a header not the writer's, a line ending in CR
// or cut short, a field count, a number not finite or not read whole, a line, direction, index
// or value outside the spec's grids), when a key comes twice (a folder given twice, or overlapping
// shards), and naming the first missing key (line, direction, index) when a shard is missing.
// Points read back carry the written figures only (not the run's failure text, timing or final
// state).
SteadySweep merge_sweep_folders(const std::vector<std::filesystem::path>& dirs);

}  // namespace gearimpact
