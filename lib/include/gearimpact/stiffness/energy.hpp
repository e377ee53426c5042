// Elastic energies of loaded tooth pairs: (5),(16),(17),(28), and the ratios of
// the paper's Fig. 8.
#pragma once

#include <array>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/terms.hpp"

namespace gearimpact {

// Elastic energy of a pair by term, J.
struct ElasticEnergy {
  std::array<double, kTermCount> j{};
  double of(Term term) const { return j[index_of(term)]; }
  double total_j() const {
    double sum = 0.0;
    for (double u : j) sum += u;
    return sum;
  }
};

// (5),(16),(17),(28): U = F^2 / (2 K) = F^2 c / 2 for each term of a pair
// carrying F, c the term's compliance as it enters (29) (a term switched off
// is 0 and stores nothing). The one place the stored energy is computed: the
// energy split of Fig. 8 and the simulation's ledger both call it.
ElasticEnergy pair_energy(const Compliances& compliance, double force_n);

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
// inclusive; the other loaded pairs sit a base pitch away (42). A term that is
// off has no energy: its ratio is 0. Throws InputError naming
// model.bending_term when the bending term, every ratio's denominator, is off.
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
