// What the program does that other code calls in-process: the Python package binds these
// (python/src/module.cpp), so that its results are the program's without running it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/modes/modes.hpp"
#include "gearimpact/stiffness/fillet_foundation.hpp"
#include "gearimpact/stiffness/helical_ste.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "gnuplot.hpp"

namespace gearimpact::cli {

// The most contact positions the stiffness commands sample (--points, --samples, and the Python
// package's points and samples): more only cost time, the curves are smooth long before.
inline constexpr int kMostSamples = 1000000;

// `gearimpact mesh-stiffness`: the CSV over the true period of the teeth with `faults` (one
// mesh period without), `samples` per mesh period, and (--summary) its JSON
// (true_period_mesh_stiffness). Throws InputError naming "samples" unless
// 2 <= samples <= kMostSamples (and the true period's samples stay within
// kMostTruePeriodSamples), and as check_tooth_faults.
struct MeshStiffnessTexts {
  std::string csv;
  std::string summary_json;
  bool extrapolated = false;
  std::vector<FoundationExtrapolation> extrapolations;  // which gears, inputs and ranges
  TruePeriodMeshStiffness tvms;
};
MeshStiffnessTexts mesh_stiffness_texts(const GearPair& pair, const StiffnessModel& model,
                                        int samples, const std::vector<ToothFault>& faults = {});

// `gearimpact ste`: the static transmission error of the case's pair with its modifications
// (ste.csv), of the same pair healthy and unmodified over the same angles (ste_unmodified.csv) and
// the summary.json of both, at pinion torque T1 > 0 and `points_per_mesh_period` angles per mesh
// period. Throws InputError naming "torque" or "points" before the stiffness table is built.
struct SteTexts {
  StaticTransmissionError modified;
  StaticTransmissionError unmodified;
  std::string csv;
  std::string unmodified_csv;
  std::string pairs_csv;
  std::string unmodified_pairs_csv;
  std::string summary_json;
  // quasi_static_peak_force_ratio of the case's pair and of the healthy unmodified one.
  double quasi_static_force_ratio = 1.0;
  double unmodified_quasi_static_force_ratio = 1.0;
  // False when the modifications leave every gap at 0: the two curves are one.
  bool modified_differs = true;
};
SteTexts ste_texts(const SimulationCase& c, double torque1_n_m, int points_per_mesh_period);
// A helical pair's `ste` (docs/helical.md, "Loaded STE and the load across the face"): the
// checks before any work (no [[faults]], the torque, the points, the slices, the
// modifications), then the slice model's STE of the pair with its modifications and
// unmodified, written into `dir` as ste.csv, ste_unmodified.csv, ste_face_load.csv,
// `summary_name` and, with `plots`, ste.png and ste_face_load.png.
struct HelicalSteFiles {
  HelicalStaticTransmissionError modified;
  HelicalStaticTransmissionError unmodified;
  std::string summary_json;
};
void check_helical_ste(const SimulationCase& c, double torque1_n_m, int points_per_mesh_period);
// The STE of both pairs and the summary's JSON, refusing a deflection past half a transverse
// base pitch naming "torque"; write_helical_ste_files writes them.
HelicalSteFiles helical_ste_of(const SimulationCase& c, double torque1_n_m,
                               int points_per_mesh_period);
HelicalSteFiles write_helical_ste_files(const SimulationCase& c, double torque1_n_m,
                                        int points_per_mesh_period,
                                        const std::filesystem::path& dir, bool plots,
                                        const std::string& summary_name);
// `report` on a helical pair file `case_file`, read as `c`: its geometry, contact lines, mesh
// stiffness over a mesh period beside ISO 6336-1 and, with [modifications], the STE and the
// load across the face.
void write_helical_report(const SimulationCase& c, const std::string& case_file,
                          const std::string& out, bool overwrite, int samples,
                          const std::string& torque);
// The gears whose teeth differ by the case's faults, known before any table is built (the
// faulted part of the STE's true period).
DistinctTeeth faulted_teeth(const SimulationCase& c);
// The figures of `ste` (ste.png and ste_load_sharing.png) from the files of `texts` in the folder
// they are drawn in: the case's STE and each pair's load share, beside the healthy unmodified
// pair's where they differ.
Figure ste_figure(const SimulationCase& c, const SteTexts& texts);
Figure ste_sharing_figure(const SimulationCase& c, const SteTexts& texts);

// `gearimpact modes`: the natural modes of the case's linearised model at its mean mesh
// stiffness (modes.csv), the crossings of the mesh harmonics 1..harmonics with them up to the
// pinion speed max_pinion_speed_rad_per_s (campbell.csv; absent: 1.1 times the speed at which
// the first harmonic meets the highest natural frequency) and summary.json. Throws InputError
// naming "harmonics" or "max_speed" before the stiffness tables are built.
struct ModesTexts {
  Modes modes;
  std::vector<CampbellCrossing> crossings;
  double max_pinion_speed_rad_per_s = 0.0;
  std::string csv;
  std::string campbell_csv;
  std::string shapes_csv;
  std::string summary_json;
};
inline constexpr int kMostHarmonics = 100;
ModesTexts modes_texts(const SimulationCase& c, int harmonics,
                       std::optional<double> max_pinion_speed_rad_per_s = std::nullopt);

// `gearimpact iso6336`: the JSON of ISO 6336-1 method B for the pair at this helix angle, with
// the low-load correction at a specific load F_t K_A / b (N/m) when one is given.
std::string iso6336_text(const GearPair& pair, double helix_angle_deg,
                         std::optional<double> specific_load_n_per_m = std::nullopt);

// `iso6336 --load TEXT`: a load per face width F_t K_A / b ("50 N/mm") or the pinion's torque
// ("150 N*m", F_t = |T1| / r1 at the reference circle, K_A = 1), as F_t K_A / b in N/m. Throws
// InputError naming --load, with the units of both, for anything else or a load <= 0.
double specific_load_of(const std::string& text, const GearPair& pair);

// `gearimpact sweep CASE OPTIONS...` on the case `c`: the rows and the spec, nothing written and
// no progress printed (--out and --no-plots are read and not used). Throws InputError naming the
// option for a bad one.
SteadySweep sweep_with_options(const SimulationCase& c, const std::vector<std::string>& options);

// `gearimpact reproduce --out OUT [--paper-data PAPER_DATA] [--fe]` (empty: the program's default
// folder): every figure and REPORT.md into `out`, progress on stderr; with_fe adds the
// finite-element check (minutes). Returns REPORT.md's path.
std::filesystem::path reproduce(const std::filesystem::path& out, const std::string& paper_data,
                                bool with_fe = false);

}  // namespace gearimpact::cli
