// Time-varying mesh stiffness (TVMS) over one mesh period of a rack-generated
// pair, with the exact kinematics of the line of action (docs/stiffness-models.md,
// section 1): at the fraction f in [0, 1) of the period the pairs in contact
// sit at s = s_SAP + (f + k) p_b in [s_SAP, s_EAP] and act in parallel.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

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

// The mesh stiffness over the true period of a pair whose teeth may differ (docs/faults.md,
// docs/usage.md "mesh-stiffness"): N mesh periods (true_period_mesh_periods: 1 when every tooth
// is alike, z1 or z2 when one gear's teeth differ, lcm(z1, z2) when both do), at rest on the
// drive line N1, each pair's Ke from mesh_stiffness with its teeth's states (a missing tooth's
// pair 0), directly rather than from a fitted table.
//
// One origin for every pair: theta1 = 0 where pinion tooth 0 meets wheel tooth 0 at the start
// of the contact segment X_start (that pair enters). Without faults this is the one mesh
// period of time_varying_mesh_stiffness above (a pair at s_SAP), to the bit. The simulation
// measures theta1 from pair 0/0 at the pitch point instead: its angle is this theta1 plus
// simulation_theta1_offset_rad = (X_start - X_pitch) / Rb1.
struct TruePeriodSample {
  double fraction;                      // of the true period, i / (N n)
  double theta1_rad;                    // fraction N 2 pi / z1
  std::vector<TeethInContact> teeth;    // of each pair in contact, the one entering last first
  std::vector<double> pair_ke_n_per_m;  // each pair's Ke, 0 for a missing tooth
  double ke_n_per_m;                    // their sum
  double healthy_ke_n_per_m;            // the same pairs all healthy
};

struct TruePeriodMeshStiffness {
  long long mesh_periods = 1;  // N
  // "mesh" (every tooth alike), "pinion-revolution", "wheel-revolution" or "hunting".
  std::string period_kind;
  double simulation_theta1_offset_rad = 0.0;
  // n per mesh period over the N mesh periods, at fraction i / (N n) of the true period.
  std::vector<TruePeriodSample> samples;
  // Over the true period, as TimeVaryingMeshStiffness over one mesh period (the extremes of
  // each smooth piece of each mesh period, the mean by GSL QAG on each piece), with the
  // fraction of the true period where the extremes fall; the mean of the same pairs all healthy.
  double min_n_per_m = 0.0;
  double min_at_fraction = 0.0;
  double max_n_per_m = 0.0;
  double max_at_fraction = 0.0;
  double mean_n_per_m = 0.0;
  double healthy_mean_n_per_m = 0.0;
  std::vector<FoundationExtrapolation> foundation_extrapolations;
};

// `samples_per_mesh_period` (n >= 2) samples in each of the N mesh periods; at most
// kMostTruePeriodSamples in all (InputError naming "samples" beyond). Checks the faults
// (check_tooth_faults) first; QuadratureError when an integral misses its tolerance.
inline constexpr std::size_t kMostTruePeriodSamples = 10000000;
TruePeriodMeshStiffness true_period_mesh_stiffness(const GearPair& pair,
                                                   const StiffnessModel& model,
                                                   const std::vector<ToothFault>& faults,
                                                   std::size_t samples_per_mesh_period);

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
