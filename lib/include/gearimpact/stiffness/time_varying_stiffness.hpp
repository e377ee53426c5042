// Time-varying mesh stiffness (TVMS) over one mesh period of a rack-generated
// pair, with the exact kinematics of the line of action (docs/stiffness-models.md,
// section 1): at the fraction f in [0, 1) of the period the pairs in contact
// sit at s = s_SAP + (f + k) p_b in [s_SAP, s_EAP] and act in parallel.
#pragma once

#include <cstddef>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

// Positions (m from T1) of the pairs in contact at fraction f of the period,
// ascending; a pair exactly at s_SAP or s_EAP counts as in contact.
std::vector<double> contact_positions(const RackGearPairGeometry& pair, double fraction);

// The mesh stiffness at fraction f: the sum of the pair stiffnesses there.
double mesh_stiffness_at(const RackGearPairGeometry& pair, const StiffnessModel& model,
                         double fraction);

struct MeshStiffnessSample {
  double fraction;
  double theta1_rad;  // pinion rotation from the position with a pair at s_SAP: f 2 pi / z1
  int pairs;
  double stiffness_n_per_m;
};

struct TimeVaryingMeshStiffness {
  std::vector<MeshStiffnessSample> samples;  // at f = i / count, i = 0 .. count - 1
  // Extremes over the period: the number of pairs changes where a pair leaves
  // at s_EAP (f_e = frac((s_EAP - s_SAP) / p_b)) and where one enters at
  // s_SAP (f = 0); between, the stiffness is smooth. On each such piece the
  // extremes include its one-sided end values, so min and max are the
  // infimum and supremum of the stiffness over the period.
  double min_n_per_m;
  double min_at_fraction;
  double max_n_per_m;
  double max_at_fraction;
  // The exact time mean at constant speed: the integral over f in [0, 1),
  // by adaptive quadrature on each smooth piece (GSL QAG).
  double mean_n_per_m;
  // The gears whose fillet-foundation fit the model uses outside its range (empty: none, or no
  // foundation term): the stiffness above is partly an extrapolation (fillet_foundation.hpp).
  std::vector<FoundationExtrapolation> foundation_extrapolations;
};

// Throws InputError for fewer than 2 samples, QuadratureError when an
// integral misses its tolerance.
TimeVaryingMeshStiffness time_varying_mesh_stiffness(const RackGearPairGeometry& pair,
                                                     const StiffnessModel& model,
                                                     std::size_t sample_count = 200);

// The same over a GearPair for any named model: Ke of mesh_stiffness.hpp at
// X1 = s, the pairs placed on the pair's contact segment (for the unshifted
// or shifted geometry of gear_pair.hpp) a base pitch apart.
TimeVaryingMeshStiffness time_varying_mesh_stiffness(const GearPair& pair,
                                                     const StiffnessModel& model,
                                                     std::size_t sample_count = 200);

// Load sharing along the path of contact: one pair at X1 (m from C1) on the pair's contact
// segment carries k(X1) / sum_j k(X1 + j t0) of the mesh force, the sum over the pairs then in
// contact a base pitch t0 apart, since the loaded pairs deflect alike (docs/model.md).
struct LoadShareSample {
  double x1_m;
  int pairs;     // pairs in contact with this one
  double share;  // in (0, 1]
};
// `points` (>= 2) positions from X_start to X_end inclusive (contact_positions of gear_pair.hpp).
// Throws InputError for fewer than 2 points.
std::vector<LoadShareSample> load_sharing(const GearPair& pair, const StiffnessModel& model,
                                          int points);

// The same mean by another route: every pair crosses the path of contact once
// per period, so the mean is (1 / p_b) Int k_pair(s) ds over [s_SAP, s_EAP]
// (Boost's adaptive Gauss-Kronrod).
double path_mean_mesh_stiffness(const RackGearPairGeometry& pair, const StiffnessModel& model);

}  // namespace gearimpact
