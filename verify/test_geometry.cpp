#include <doctest/doctest.h>

#include <cmath>

#include "gearimpact/gear_pair.hpp"

using namespace gearimpact;

TEST_CASE("placeholder: X at the pitch point is Rb1 tan a0") {
  const GearPair pair = paper_gear_pair();
  CHECK(pitch_point_position(pair) == base_radius(pair, Gear::one) * std::tan(pair.pressure_angle_rad));
}
