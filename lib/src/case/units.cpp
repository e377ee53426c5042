#include "gearimpact/case/units.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

constexpr double kDegree = pi / 180.0;
constexpr double kInch = 0.0254;
// 1 kgf = 9.80665 N (standard gravity); the same constant as torque_unit_n_m.
constexpr double kKilogramForce = 9.80665;

// The first unit of each table is the SI one (exponent 0, factor 1).
constexpr std::array kLength{Unit{"m", 0, 1.0}, Unit{"mm", -3, 1.0}, Unit{"um", -6, 1.0},
                             Unit{"cm", -2, 1.0}, Unit{"in", 0, kInch}};
constexpr std::array kAngle{Unit{"rad", 0, 1.0}, Unit{"deg", 0, kDegree}};
constexpr std::array kPressure{Unit{"Pa", 0, 1.0}, Unit{"kPa", 3, 1.0}, Unit{"MPa", 6, 1.0},
                               Unit{"GPa", 9, 1.0}, Unit{"N/mm^2", 6, 1.0}};
constexpr std::array kDensity{Unit{"kg/m^3", 0, 1.0}, Unit{"g/cm^3", 3, 1.0},
                              Unit{"kg/mm^3", 9, 1.0}};
constexpr std::array kTorque{Unit{"N*m", 0, 1.0}, Unit{"N*mm", -3, 1.0},
                             Unit{"kgf*mm", 0, kKilogramForce * 1e-3},
                             Unit{"kgf*m", 0, kKilogramForce}};
constexpr std::array kTime{Unit{"s", 0, 1.0}, Unit{"ms", -3, 1.0}, Unit{"us", -6, 1.0},
                           Unit{"ns", -9, 1.0}};
constexpr std::array kAngularVelocity{Unit{"rad/s", 0, 1.0}, Unit{"rpm", 0, 2.0 * pi / 60.0}};
// Hz counts cycles: W = 2 pi f.
constexpr std::array kAngularFrequency{Unit{"rad/s", 0, 1.0}, Unit{"Hz", 0, 2.0 * pi}};
constexpr std::array kFrequency{Unit{"Hz", 0, 1.0}, Unit{"kHz", 3, 1.0}, Unit{"MHz", 6, 1.0}};
constexpr std::array kSpeed{Unit{"m/s", 0, 1.0}, Unit{"mm/s", -3, 1.0}, Unit{"in/s", 0, kInch}};
// A mesh stiffness, force per length along the line of action: N/um = kN/mm = 1e6 N/m.
constexpr std::array kStiffness{Unit{"N/m", 0, 1.0}, Unit{"N/mm", 3, 1.0}, Unit{"N/um", 6, 1.0},
                                Unit{"kN/mm", 6, 1.0}};
// A dynamic viscosity: 1 cP = 1 mPa*s = 1e-3 Pa*s.
constexpr std::array kViscosity{Unit{"Pa*s", 0, 1.0}, Unit{"mPa*s", -3, 1.0}, Unit{"cP", -3, 1.0}};

// A viscous torque per angular velocity.
constexpr std::array kRotationalDamping{Unit{"N*m*s/rad", 0, 1.0}, Unit{"N*mm*s/rad", -3, 1.0}};
constexpr std::array kMass{Unit{"kg", 0, 1.0}, Unit{"g", -3, 1.0}};
constexpr std::array kMomentOfInertia{Unit{"kg*m^2", 0, 1.0}, Unit{"kg*mm^2", -6, 1.0},
                                      Unit{"kg*cm^2", -4, 1.0}};
// A bearing's viscous damper: N*s/mm = 1e3 N*s/m.
constexpr std::array kDamping{Unit{"N*s/m", 0, 1.0}, Unit{"N*s/mm", 3, 1.0}};
constexpr std::array kTorsionalStiffness{Unit{"N*m/rad", 0, 1.0}, Unit{"N*mm/rad", -3, 1.0},
                                         Unit{"kN*m/rad", 3, 1.0}};

constexpr std::array kDimensions{Dimension::length,
                                 Dimension::angle,
                                 Dimension::pressure,
                                 Dimension::density,
                                 Dimension::torque,
                                 Dimension::time,
                                 Dimension::angular_velocity,
                                 Dimension::angular_frequency,
                                 Dimension::speed,
                                 Dimension::stiffness,
                                 Dimension::viscosity,
                                 Dimension::rotational_damping,
                                 Dimension::mass,
                                 Dimension::moment_of_inertia,
                                 Dimension::damping,
                                 Dimension::torsional_stiffness,
                                 Dimension::frequency};

// Exponents beyond this put any mantissa outside the doubles (with up to a few
// hundred digits); it keeps the exponent arithmetic far from int overflow.
constexpr long kLargestExponent = 100000;

const Unit* find_unit(Dimension dimension, std::string_view symbol) {
  for (const Unit& unit : units_of(dimension)) {
    if (unit.symbol == symbol) return &unit;
  }
  return nullptr;
}

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
bool is_space(char c) {
  return c == ' ' || c == '\t';
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

// A decimal number split into its mantissa text and its exponent.
struct Decimal {
  std::string_view mantissa;  // sign, digits, at most one point
  long exponent = 0;
};

// d1.d2...dn x 10^e written plainly when short, else as d1.d2...dn e E.
std::string plain_decimal(bool negative, std::string digits, long exponent) {
  while (digits.size() > 1 && digits.back() == '0') digits.pop_back();
  const long n = static_cast<long>(digits.size());
  std::string body;
  if (digits == "0") {
    body = "0";
  } else if (exponent >= 0 && exponent < n - 1) {
    body = digits.substr(0, static_cast<std::size_t>(exponent + 1)) + "." +
           digits.substr(static_cast<std::size_t>(exponent + 1));
  } else if (exponent >= n - 1 && exponent < 16) {
    body = digits + std::string(static_cast<std::size_t>(exponent - (n - 1)), '0');
  } else if (exponent < 0 && exponent >= -4) {
    body = "0." + std::string(static_cast<std::size_t>(-exponent - 1), '0') + digits;
  } else {
    body.push_back(digits.front());
    if (n > 1) {
      body.push_back('.');
      body.append(digits.begin() + 1, digits.end());
    }
    body.append(1, 'e').append(std::to_string(exponent));
  }
  return (negative ? "-" : "") + body;
}

// The shortest round-trip digits of `value` and their decimal exponent.
struct ShortestDigits {
  bool negative;
  std::string digits;
  long exponent;
};

ShortestDigits shortest_digits(double value) {
  std::array<char, 64> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                       std::chars_format::scientific);
  const std::string_view text(buffer.data(), static_cast<std::size_t>(end - buffer.data()));
  ShortestDigits result{false, {}, 0};
  std::size_t i = 0;
  if (text[i] == '-') {
    result.negative = true;
    ++i;
  }
  for (; i < text.size() && text[i] != 'e'; ++i) {
    if (text[i] != '.') result.digits += text[i];
  }
  std::string_view exponent = text.substr(i + 1);
  if (!exponent.empty() && exponent.front() == '+') exponent.remove_prefix(1);
  std::from_chars(exponent.data(), exponent.data() + exponent.size(), result.exponent);
  return result;
}

}  // namespace

UnitList units_of(Dimension dimension) {
  switch (dimension) {
    case Dimension::length:
      return {kLength.data(), kLength.size()};
    case Dimension::angle:
      return {kAngle.data(), kAngle.size()};
    case Dimension::pressure:
      return {kPressure.data(), kPressure.size()};
    case Dimension::density:
      return {kDensity.data(), kDensity.size()};
    case Dimension::torque:
      return {kTorque.data(), kTorque.size()};
    case Dimension::time:
      return {kTime.data(), kTime.size()};
    case Dimension::angular_velocity:
      return {kAngularVelocity.data(), kAngularVelocity.size()};
    case Dimension::angular_frequency:
      return {kAngularFrequency.data(), kAngularFrequency.size()};
    case Dimension::speed:
      return {kSpeed.data(), kSpeed.size()};
    case Dimension::stiffness:
      return {kStiffness.data(), kStiffness.size()};
    case Dimension::viscosity:
      return {kViscosity.data(), kViscosity.size()};
    case Dimension::rotational_damping:
      return {kRotationalDamping.data(), kRotationalDamping.size()};
    case Dimension::mass:
      return {kMass.data(), kMass.size()};
    case Dimension::moment_of_inertia:
      return {kMomentOfInertia.data(), kMomentOfInertia.size()};
    case Dimension::damping:
      return {kDamping.data(), kDamping.size()};
    case Dimension::torsional_stiffness:
      return {kTorsionalStiffness.data(), kTorsionalStiffness.size()};
    case Dimension::frequency:
      return {kFrequency.data(), kFrequency.size()};
  }
  return {};
}

std::string_view describe(Dimension dimension) {
  switch (dimension) {
    case Dimension::length:
      return "a length";
    case Dimension::angle:
      return "an angle";
    case Dimension::pressure:
      return "a pressure";
    case Dimension::density:
      return "a density";
    case Dimension::torque:
      return "a torque";
    case Dimension::time:
      return "a time";
    case Dimension::angular_velocity:
      return "an angular velocity";
    case Dimension::angular_frequency:
      return "an angular frequency";
    case Dimension::speed:
      return "a speed";
    case Dimension::stiffness:
      return "a stiffness";
    case Dimension::viscosity:
      return "a dynamic viscosity";
    case Dimension::rotational_damping:
      return "a rotational damping";
    case Dimension::mass:
      return "a mass";
    case Dimension::moment_of_inertia:
      return "a moment of inertia";
    case Dimension::damping:
      return "a damping";
    case Dimension::torsional_stiffness:
      return "a torsional stiffness";
    case Dimension::frequency:
      return "a frequency";
  }
  return "a quantity";
}

std::string allowed_units(Dimension dimension) {
  std::string list;
  for (const Unit& unit : units_of(dimension)) {
    if (!list.empty()) list += ", ";
    list += unit.symbol;
  }
  return list;
}

double parse_quantity(std::string_view text, Dimension dimension, std::string_view field) {
  const std::string written = "\"" + std::string(text) + "\"";
  const auto fail = [&](const std::string& why) {
    throw InputError({refused_problem(std::string(field), written, why,
                                      "expected " + std::string(describe(dimension)) +
                                          ": a finite decimal number followed by one of the "
                                          "units " +
                                          allowed_units(dimension))});
  };
  // The unit, not the number, is wrong: the message lists the units.
  const auto fail_unit = [&](const std::string& why) {
    throw InputError({refused_problem(
        std::string(field), written, why,
        "units of " + std::string(describe(dimension)) + ": " + allowed_units(dimension))});
  };
  const std::string_view body = trim(text);

  // The number: [sign] digits [. digits] [e|E [sign] digits].
  std::size_t i = 0;
  if (i < body.size() && (body[i] == '+' || body[i] == '-')) ++i;
  const std::size_t mantissa_begin = !body.empty() && body[0] == '+' ? 1 : 0;
  std::size_t digits = 0;
  bool point = false;
  for (; i < body.size(); ++i) {
    if (is_digit(body[i])) {
      ++digits;
    } else if (body[i] == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (digits == 0) fail("no finite decimal number");
  Decimal number{body.substr(mantissa_begin, i - mantissa_begin), 0};
  if (i < body.size() && (body[i] == 'e' || body[i] == 'E')) {
    std::size_t j = i + 1;
    bool negative = false;
    if (j < body.size() && (body[j] == '+' || body[j] == '-')) negative = body[j++] == '-';
    const std::size_t exponent_begin = j;
    while (j < body.size() && is_digit(body[j])) ++j;
    if (j == exponent_begin) fail("an exponent without digits");
    long magnitude = 0;
    const auto result = std::from_chars(body.data() + exponent_begin, body.data() + j, magnitude);
    if (result.ec != std::errc{} || magnitude > kLargestExponent) {
      fail("a number outside the range of a double");
    }
    number.exponent = negative ? -magnitude : magnitude;
    i = j;
  }

  const std::string_view symbol = trim(body.substr(i));
  if (symbol.empty()) fail("no unit");
  const Unit* unit = find_unit(dimension, symbol);
  if (unit == nullptr) {
    for (Dimension other : kDimensions) {
      if (other != dimension && find_unit(other, symbol) != nullptr) {
        fail_unit("'" + std::string(symbol) + "' is a unit of " + std::string(describe(other)) +
                  ", not of " + std::string(describe(dimension)));
      }
    }
    fail_unit("unknown unit '" + std::string(symbol) + "' for " + std::string(describe(dimension)));
  }

  const std::string shifted =
      std::string(number.mantissa) + "e" + std::to_string(number.exponent + unit->decimal_exponent);
  double value = 0.0;
  const auto result = std::from_chars(shifted.data(), shifted.data() + shifted.size(), value);
  if (result.ec != std::errc{} || result.ptr != shifted.data() + shifted.size() ||
      !std::isfinite(value * unit->factor)) {
    fail("a number outside the range of a double");
  }
  return value * unit->factor;
}

double parse_plain_or_quantity(std::string_view text, Dimension dimension, std::string_view field) {
  std::string_view body = trim(text);
  if (!body.empty() && body.front() == '+') body.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(body.data(), body.data() + body.size(), value);
  // from_chars reads "inf" and "nan": a plain number is a finite decimal.
  if (!body.empty() && error == std::errc{} && end == body.data() + body.size() &&
      std::isfinite(value) && body.find_first_of("iInN") == std::string_view::npos) {
    return value;
  }
  return parse_quantity(text, dimension, field);
}

std::string shortest_decimal(double value) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  const ShortestDigits d = shortest_digits(value);
  return plain_decimal(d.negative, d.digits, d.exponent);
}

std::string format_quantity(double si_value, Dimension dimension, std::string_view unit_symbol) {
  const UnitList table = units_of(dimension);
  const Unit* unit = find_unit(dimension, unit_symbol);
  if (unit != nullptr && std::isfinite(si_value)) {
    std::string number;
    if (unit->factor == 1.0) {
      // Shift the decimal exponent of the shortest digits: reading back
      // shifts it again, so the text denotes exactly the same decimal.
      const ShortestDigits d = shortest_digits(si_value);
      number = plain_decimal(d.negative, d.digits, d.exponent - unit->decimal_exponent);
    } else {
      number = shortest_decimal(si_value / unit->factor);
    }
    std::string text = number + " " + std::string(unit->symbol);
    if (parse_quantity(text, dimension, "format_quantity") == si_value) return text;
  }
  return shortest_decimal(si_value) + " " + std::string(table.front().symbol);
}

}  // namespace gearimpact
