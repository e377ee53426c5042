// A helical pair with faults in the static commands (docs/helical.md,
// Faults): the mesh stiffness over the true period and the loaded STE read the
// tables a run reads (MeshTables of the swept transverse section: route B's
// face integral with each band of the face in its own state), so that the
// three agree by construction.
#pragma once

#include <cstddef>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/helical_ste.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

namespace gearimpact {

// The tables a run of the helical pair with these faults reads: MeshTables of
// swept_transverse_pair(pair) over helical_pair_table(pair, model). Checks the
// faults first (check_tooth_faults); InputError naming gears.helix_angle for a
// spur pair.
MeshTables helical_mesh_tables(const GearPair& pair, const StiffnessModel& model,
                               const std::vector<ToothFault>& faults);

// The mesh stiffness of a helical pair with faults over the true period of its
// teeth (N mesh periods, true_period_mesh_periods), on the drive line N1, as
// true_period_mesh_stiffness gives a spur pair's; each pair k's Ke the table
// of its teeth (helical_mesh_tables) at its mid-face contact X_k = X_pitch +
// Rb1 theta1 + k p_bt, every pair whose X_k lies on the table's widened
// segment counted. theta1 = 0 where pair 0 (pinion tooth 0 against wheel
// tooth 0) has its mid-face contact at the pitch point, the run's origin
// (simulation_theta1_offset_rad 0). The extremes are over the samples; the
// means are the tables' integrals over the segment (GSL QAG on each piece to
// 1e-12) over N p_bt. At most kMostTruePeriodSamples samples (InputError
// naming "samples" beyond).
TruePeriodMeshStiffness helical_true_period_mesh_stiffness(const GearPair& pair,
                                                           const StiffnessModel& model,
                                                           const std::vector<ToothFault>& faults,
                                                           std::size_t samples_per_mesh_period);

// The loaded STE of a helical pair without modifications from `tables`
// (helical_mesh_tables of the pair, with or without faults): at each pinion
// angle delta = F_bt / sum_k Ke_k(X_k), the route B of the healthy pair's
// helical_static_transmission_error with each pair's Ke its teeth's table.
// The load across the face w(y_j) = sum_k kappa_kj delta, kappa_kj the
// per-width stiffness of slice j of pair k at X_kj in its state
// (helical_slice_stiffness over the pair's face_bands). options.mesh_periods 0:
// the true period of the tables' teeth. Throws as
// validate_helical_static_transmission_error, and InputError naming
// [[faults]] when missing teeth leave no pair in contact at an angle.
HelicalStaticTransmissionError helical_static_transmission_error(
    const GearPair& pair, double torque1_n_m, const StiffnessModel& model, const MeshTables& tables,
    StaticTransmissionErrorOptions options = {});

}  // namespace gearimpact
