// The files of `gearimpact modes` (docs/vibration.md): the natural modes of
// the linearised model, where the mesh harmonics cross them, and a summary.
#pragma once

#include <cstddef>
#include <iterator>
#include <string>
#include <vector>

#include "gearimpact/io/columns.hpp"
#include "gearimpact/modes/modes.hpp"
#include "gearimpact/modes/planetary.hpp"
#include "gearimpact/modes/train_modes.hpp"

namespace gearimpact {

// One row per mode, ascending frequency:
// mode,rigid,frequency_hz,angular_frequency_rad_per_s,share_mesh,share_bearing1,
// share_bearing2,share_motor_shaft,share_load_shaft, then the mass-normalised
// shape's components of the model's DOFs: x1_per_sqrt_kg, y1_per_sqrt_kg,
// theta1_rad_per_sqrt_kg_m, ... (x, y only on elastic bearings; theta_motor,
// theta_load only on elastic shafts). mode counts from 1; rigid is true or false.
std::string modes_csv(const Modes& modes);

// A row of modes.csv and mode_shapes.csv: the mode, its number (from 1) and its shape on the base
// circles (base_circle_shape).
struct ModeRow {
  int number = 0;
  NaturalMode mode;
  Eigen::VectorXd base_circle;
};
std::vector<ModeRow> mode_rows(const Modes& modes);
// The columns of modes.csv, mode_shapes.csv and campbell.csv, each described once (the CSV
// writers and the Python package's arrays follow them), for the DOFs of `model`.
Columns<ModeRow> modes_columns(const LinearModel& model);
Columns<ModeRow> mode_shapes_columns(const LinearModel& model);
Columns<CampbellCrossing> campbell_columns();

// One row per mode, as modes.csv numbers them: mode,rigid,frequency_hz, then
// base_circle_shape's components, named x1, y1, rb1_theta1, x2, y2,
// rb2_theta2, rb1_theta_motor, rb2_theta_load (those the model has):
// dimensionless, the largest magnitude of each mode 1. What modes_shapes.png draws.
std::string mode_shapes_csv(const Modes& modes);

// One row per crossing: harmonic,mode,frequency_hz,pinion_speed_rad_per_s,
// pinion_speed_rpm (mode as modes.csv numbers it).
std::string campbell_csv(const std::vector<CampbellCrossing>& crossings);

// What the modes were computed from, and the torsional reference
// sqrt(k / m_e) / (2 pi) with 1/m_e = Rb1^2/J1 + Rb2^2/J2.
struct ModesSummary {
  std::string case_name;
  int teeth1 = 0;
  int harmonics = 0;
  double max_pinion_speed_rad_per_s = 0.0;
};
std::string modes_summary_json(const ModesSummary& summary, const Modes& modes,
                               const std::vector<CampbellCrossing>& crossings);

// ---- A planetary stage's modes (docs/planetary.md) ----

// The kinds of spring a planetary stage's strain energy is shared among, in
// the order of modes.csv's share columns (the per-planet kinds summed over
// the planets).
inline constexpr StageSpring kStageSpringKinds[] = {
    StageSpring::sun_mesh,    StageSpring::ring_mesh,    StageSpring::planet_bearing,
    StageSpring::sun_support, StageSpring::ring_support, StageSpring::carrier_support};
inline constexpr std::size_t kStageSpringKindCount = std::size(kStageSpringKinds);

// A row of a planetary modes.csv: one mode, numbered from 1.
struct StageModeRow {
  int number = 0;
  double frequency_hz = 0.0;
  int multiplicity = 1;
  bool rigid = false;
  StageModeType type = StageModeType::mixed;
  double share[kStageSpringKindCount] = {};  // by kind, summing to 1 (0 for a rigid mode)
};
std::vector<StageModeRow> stage_mode_rows(const PlanetaryModes& modes);
// mode, frequency_hz, multiplicity, rigid, type, share_sun_mesh, share_ring_mesh,
// share_planet_bearing, share_sun_support, share_ring_support, share_carrier_support.
Columns<StageModeRow> stage_modes_columns();
// The case's name, the planets and their angles, the dofs, the rigid modes and each
// distinct frequency with its multiplicity and type.
std::string stage_modes_summary_json(const std::string& case_name, const PlanetaryModes& modes);

// ---- A torsional train's modes (docs/planetary.md, "Modes of a torsional train") ----

// A row of a train's modes.csv: one mode, numbered from 1, and its shape per body.
struct TrainModeRow {
  int number = 0;
  TrainMode mode;
  Eigen::VectorXd body_shape;  // body_shape(model, mode)
};
std::vector<TrainModeRow> train_mode_rows(const TrainModes& modes);
// mode, rigid, frequency_hz, angular_frequency_rad_per_s; share_MESH per mesh (by its name);
// share_shaft_A_B per torsional shaft (by its two bodies' names); theta_BODY_rad_per_sqrt_kg_m
// per body, the mass-normalised shape in each body's forward sense.
Columns<TrainModeRow> train_modes_columns(const GearTrain& train);
// The case's name, the bodies and their degrees of freedom, each mesh's stiffness, the rigid
// modes and the elastic frequencies.
std::string train_modes_summary_json(const std::string& case_name, const GearTrain& train,
                                     const TrainModes& modes);

}  // namespace gearimpact
