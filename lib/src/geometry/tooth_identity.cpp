#include "gearimpact/geometry/tooth_identity.hpp"

#include <numeric>

namespace gearimpact {

TeethInContact teeth_of_pair(const GearPair& pair, Region line, int k) {
  return teeth_of_pair(teeth(pair, Gear::one), teeth(pair, Gear::two), line, k);
}

long long true_period_mesh_periods(const GearPair& pair, DistinctTeeth distinct) {
  const long long z1 = teeth(pair, Gear::one);
  const long long z2 = teeth(pair, Gear::two);
  if (distinct.pinion && distinct.wheel) return std::lcm(z1, z2);
  if (distinct.pinion) return z1;
  if (distinct.wheel) return z2;
  return 1;
}

}  // namespace gearimpact
