#include "gearimpact/geometry/tooth_identity.hpp"

#include <cmath>
#include <numeric>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

TeethInContact teeth_of_pair(const GearPair& pair, Region line, int k) {
  return teeth_of_pair(teeth(pair, Gear::one), teeth(pair, Gear::two), line, k);
}

ToothPassage tooth_passage(const GearPair& pair, Gear gear, int tooth) {
  const int z = teeth(pair, gear);
  if (tooth < 0 || tooth >= z) {
    throw InputError("tooth", std::to_string(tooth),
                     "a tooth number in [0, " + std::to_string(z - 1) + "] of gear " +
                         std::to_string(static_cast<int>(gear)));
  }
  const double rb = base_radius(pair, gear);
  const ContactSegment segment = contact_segment(pair);
  const double entry = (segment.start_m - pitch_point_position(pair)) / rb +
                       2.0 * pi * static_cast<double>(tooth) / static_cast<double>(z);
  return {entry - 2.0 * pi * std::floor(entry / (2.0 * pi)),
          (segment.end_m - segment.start_m) / rb};
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
