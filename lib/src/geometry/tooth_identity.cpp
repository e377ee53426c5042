#include "gearimpact/geometry/tooth_identity.hpp"

#include <numeric>

namespace gearimpact {

namespace {

// n mod z in 0 ... z-1 for negative n too.
int tooth_number(long long n, int z) {
  const long long r = n % z;
  return static_cast<int>(r < 0 ? r + z : r);
}

}  // namespace

TeethInContact teeth_of_pair(const GearPair& pair, Region line, int k) {
  const int z1 = teeth(pair, Gear::one);
  const int z2 = teeth(pair, Gear::two);
  if (line == Region::n2) {
    return {tooth_number(k, z1), tooth_number(static_cast<long long>(k) + 1, z2)};
  }
  const long long n = -static_cast<long long>(k);
  return {tooth_number(n, z1), tooth_number(n, z2)};
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
