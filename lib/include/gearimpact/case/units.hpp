// Quantities with units, as case files write them ("10 mm", "206.8 GPa",
// "50 kgf*mm"): a small table of the units each physical dimension allows,
// converted to SI once, where the text is read.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace gearimpact {

enum class Dimension {
  length,               // m
  angle,                // rad
  pressure,             // Pa (Young's modulus)
  density,              // kg/m^3
  torque,               // N m
  time,                 // s
  angular_velocity,     // rad/s
  angular_frequency,    // rad/s, the W of sin(W t)
  speed,                // m/s
  stiffness,            // N/m, a mesh stiffness along the line of action or a bearing's
  viscosity,            // Pa s, a lubricant's dynamic viscosity
  rotational_damping,   // N m s/rad, a viscous drag torque per angular velocity
  mass,                 // kg
  moment_of_inertia,    // kg m^2
  damping,              // N s/m, a viscous force per speed (a bearing's damper)
  torsional_stiffness,  // N m/rad, a shaft's torque per twist
  frequency,            // Hz, cycles per second: a sample rate
};

// One allowed unit: SI value = (number x 10^decimal_exponent) x factor. A
// decimal prefix is applied to the decimal text itself, so "0.05 mm" is the
// double nearest 5e-5, exactly as the literal 0.05e-3, with one rounding.
struct Unit {
  std::string_view symbol;
  int decimal_exponent;
  double factor;
};

// The units of one dimension, SI first: a view of a static table.
struct UnitList {
  const Unit* first;
  std::size_t count;
  const Unit* begin() const { return first; }
  const Unit* end() const { return first + count; }
  const Unit& front() const { return *first; }
  std::size_t size() const { return count; }
};
UnitList units_of(Dimension dimension);

// "a length", "an angle", ... for messages.
std::string_view describe(Dimension dimension);

// The allowed symbols, comma separated: "m, mm, um, cm, in".
std::string allowed_units(Dimension dimension);

// Reads "<number> <unit>" (space optional) into SI. Throws InputError naming
// `field`, the text and the allowed units when the number is not a finite
// decimal, the unit is missing, unknown or of another dimension.
double parse_quantity(std::string_view text, Dimension dimension, std::string_view field);

// The same, or a plain finite decimal number taken in the SI unit (a flag's
// "80000" or "80 kHz" for a sample rate in Hz). Errors as parse_quantity.
double parse_plain_or_quantity(std::string_view text, Dimension dimension, std::string_view field);

// Writes an SI value in `unit` (a symbol of units_of(dimension)) when the text
// reads back to exactly the same double, else in the SI unit (the first of the
// table), which always does. The number is the shortest that round-trips.
std::string format_quantity(double si_value, Dimension dimension, std::string_view unit);

// The shortest decimal text that reads back to `value` (finite), without an
// exponent when that is not much longer: "0.05", "206800000000", "1e-07".
std::string shortest_decimal(double value);

}  // namespace gearimpact
