// Tooth errors drawn from a flank tolerance class of ISO 1328-1:2013
// (docs/faults.md, "Errors drawn from a tolerance class").
//
// The tolerances are the standard's formulae for the single pitch tolerance
// f_pT (5) and the profile slope tolerance f_HalphaT (7) of class A, each the
// class-5 value times sqrt(2)^(A - 5) and rounded as the standard rounds
// them. The draw takes the raw output of std::mt19937_64, whose sequence the
// C++ standard fixes, through the transform below (never a std::
// distribution, whose results differ between standard libraries), so that a
// seed gives the same numbers bit for bit on every compiler; only the
// positions' cos(alpha) onto the line of action comes from std::cos, as the
// rest of the geometry does.
#pragma once

#include <cstdint>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

// f_pT and f_HalphaT of one gear, m, as the standard rounds them.
struct Iso1328Tolerances {
  double single_pitch_m;   // f_pT, measured along the reference circle
  double profile_slope_m;  // f_HalphaT, measured along the line of action
};

// A tolerance in micrometres rounded as ISO 1328-1:2013 rounds its values:
// above 10 um to a whole micrometre, from 5 to 10 um to 0.5 um, below 5 um to
// 0.1 um.
double iso1328_rounded_um(double value_um);

// The tolerances of `gear` of `pair` in flank tolerance class `tolerance_class`
// (1 to 11, the schema's range), from its reference diameter d = m z and
// normal module m: f_pT = (0.001 d + 0.4 m + 5) sqrt(2)^(A-5) and
// f_HalphaT = (0.4 m + 0.001 d + 4) sqrt(2)^(A-5), d and m in mm, um.
Iso1328Tolerances iso1328_tolerances(const GearPair& pair, Gear gear, int tolerance_class);

// A number in [-half_width, half_width) from one 64-bit output of the engine:
// its 53 high bits as u = k 2^-53 in [0, 1), then (2u - 1) half_width. 2u - 1
// is exact, so the result is one correctly rounded product on any IEEE
// machine.
double symmetric_uniform(std::uint64_t bits, double half_width);

// The errors of one gear's teeth drawn from its tolerances, one value per
// tooth, tooth 0 first, in m along the line of action. The engine is
// std::mt19937_64 seeded with 2 seed + (gear - 1), so that each gear has its
// own stream; it gives the z positions first, then the z profile slopes:
// - position (pitch) deviations uniform in [-f_pT/2, f_pT/2) on the
//   reference circle, times cos(alpha) to the line of action: every single
//   pitch deviation (the difference of neighbouring positions, the closing
//   one from the last tooth to tooth 0 among them) lies within +-f_pT, and
//   the total cumulative pitch deviation within f_pT, below F_pT;
// - profile slope deviations uniform in [-f_HalphaT, f_HalphaT) over the
//   active profile; over the standard's evaluation range, a part of it, the
//   slope of the same straight line is smaller still.
struct DrawnToothErrors {
  std::vector<double> pitch_m;
  std::vector<double> profile_slope_m;
};
DrawnToothErrors draw_tooth_errors(const GearPair& pair, Gear gear, int tolerance_class,
                                   std::uint32_t seed);

}  // namespace gearimpact
