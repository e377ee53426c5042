// Elastic energies of loaded tooth pairs: (5),(16),(17),(28), and the ratios of
// the paper's Fig. 8.
#pragma once

#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

// (5),(16),(17),(28): U = F^2 / (2 K) for each term of a pair carrying F.
struct ElasticEnergy {
  double hertz_j = 0.0;
  double bending_j = 0.0;  // both teeth
  double axial_j = 0.0;    // both teeth
  double total_j() const { return hertz_j + bending_j + axial_j; }
};
ElasticEnergy pair_energy(const MeshStiffness& k, double force_n);

// A total force shared by pairs in parallel with equal deflection: pair j
// carries W Ke_j / sum Ke. Returns the summed energies.
ElasticEnergy shared_load_energy(const std::vector<MeshStiffness>& pairs, double total_force_n);

// One row of Fig. 8 for a gear-1 tooth in contact at X1.
struct EnergyRatios {
  double x1_m;
  double phi1_deg;  // (12), the figure's "angular position"
  int pairs;        // loaded pairs on the line at that instant
  double hertz_over_bending_one_pair;
  double axial_over_bending_one_pair;
  double hertz_over_bending_system;
  double axial_over_bending_system;
};

// `points` evenly spaced contact positions of one tooth from X_start to X_end
// inclusive; the other loaded pairs sit a base pitch away (42).
std::vector<EnergyRatios> energy_ratio_cycle(const GearPair& pair, int points,
                                             const StiffnessModel& model = {});

// The smallest and largest value of one ratio over a cycle, and the phi1 of
// the largest. `ratio` names a member, e.g. &EnergyRatios::axial_over_bending_system.
struct RatioExtremes {
  double min;
  double max;
  double phi1_at_max_deg;
};
RatioExtremes extremes(const std::vector<EnergyRatios>& rows, double EnergyRatios::*ratio);

// The phi1 interval of a cycle where a single pair is loaded: the first row
// with one pair after two, and the last row with one pair before two.
struct AngleZone {
  double start_deg;
  double end_deg;
};
AngleZone one_pair_zone(const std::vector<EnergyRatios>& rows);

}  // namespace gearimpact
