#include "gearimpact/geometry/iso1328.hpp"

#include <cmath>
#include <random>

namespace gearimpact {

namespace {

// sqrt(2)^(A - 5) as a power of 2, times sqrt(2) for odd A - 5: exact or one
// correctly rounded square root, where std::pow may differ in its last bit
// between libraries.
double class_step(int tolerance_class) {
  const int e = tolerance_class - 5;
  if (e % 2 == 0) return std::ldexp(1.0, e / 2);
  return std::sqrt(2.0) * std::ldexp(1.0, (e - 1) / 2);
}

}  // namespace

double iso1328_rounded_um(double value_um) {
  if (value_um > 10.0) return std::round(value_um);
  if (value_um >= 5.0) return std::round(2.0 * value_um) / 2.0;
  return std::round(10.0 * value_um) / 10.0;
}

Iso1328Tolerances iso1328_tolerances(const GearPair& pair, Gear gear, int tolerance_class) {
  // The formulae take d and m_n in mm and give um.
  const double m = pair.module_m * 1e3;
  const double d = m * teeth(pair, gear);
  const double step = class_step(tolerance_class);
  const double single_pitch_um = (0.001 * d + 0.4 * m + 5.0) * step;
  const double profile_slope_um = (0.4 * m + 0.001 * d + 4.0) * step;
  // Divided, not multiplied by 1e-6 (itself rounded): 10 um is 1e-5 m exactly as written.
  return {iso1328_rounded_um(single_pitch_um) / 1e6, iso1328_rounded_um(profile_slope_um) / 1e6};
}

double symmetric_uniform(std::uint64_t bits, double half_width) {
  const double u = static_cast<double>(bits >> 11) * 0x1.0p-53;
  return (2.0 * u - 1.0) * half_width;
}

DrawnToothErrors draw_tooth_errors(const GearPair& pair, Gear gear, int tolerance_class,
                                   std::uint32_t seed) {
  const Iso1328Tolerances t = iso1328_tolerances(pair, gear, tolerance_class);
  const auto z = static_cast<std::size_t>(teeth(pair, gear));
  std::mt19937_64 engine(2 * static_cast<std::uint64_t>(seed) + (gear == Gear::one ? 0 : 1));
  // A rotation moves a tooth's flank along the line of action by r_b / r of
  // its arc on the reference circle.
  const double to_line = std::cos(pair.pressure_angle_rad);
  DrawnToothErrors drawn;
  drawn.pitch_m.resize(z);
  drawn.profile_slope_m.resize(z);
  for (double& f : drawn.pitch_m) f = symmetric_uniform(engine(), 0.5 * t.single_pitch_m) * to_line;
  for (double& f : drawn.profile_slope_m) f = symmetric_uniform(engine(), t.profile_slope_m);
  return drawn;
}

}  // namespace gearimpact
