// What the program does that other code calls in-process: the Python package binds these
// (python/src/module.cpp), so that its results are the program's without running it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/model.hpp"

namespace gearimpact::cli {

// Whether the model's foundation fit is used outside its range for this pair (its inputs are the
// gears' own, the same at every position); false for a model without the foundation term.
bool foundation_extrapolated(const GearPair& pair, const StiffnessModel& model);

// The most contact positions the stiffness commands sample (--points, --samples, and the Python
// package's points and samples): more only cost time, the curves are smooth long before.
inline constexpr int kMostSamples = 1000000;

// `gearimpact mesh-stiffness`: the CSV of one mesh period and (--summary) its JSON. Throws
// InputError naming "samples" unless 2 <= samples <= kMostSamples.
struct MeshStiffnessTexts {
  std::string csv;
  std::string summary_json;
  bool extrapolated = false;
};
MeshStiffnessTexts mesh_stiffness_texts(const GearPair& pair, const StiffnessModel& model,
                                        int samples);

// `gearimpact iso6336`: the JSON of ISO 6336-1 method B for the pair at this helix angle.
std::string iso6336_text(const GearPair& pair, double helix_angle_deg);

// `gearimpact sweep CASE OPTIONS...` on the case `c`: the rows and the spec, nothing written and
// no progress printed (--out and --no-plots are read and not used). Throws InputError naming the
// option for a bad one.
SteadySweep sweep_with_options(const SimulationCase& c, const std::vector<std::string>& options);

// `gearimpact reproduce --out OUT [--paper-data PAPER_DATA]` (empty: the program's default
// folder): every figure and REPORT.md into `out`, progress on stderr. Returns REPORT.md's path.
std::filesystem::path reproduce(const std::filesystem::path& out, const std::string& paper_data);

}  // namespace gearimpact::cli
