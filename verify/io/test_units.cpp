// The unit parser: every expected value below is the quantity's definition in
// SI (a decimal literal, 1 in = 0.0254 m, 1 kgf = 9.80665 N, 1 deg = pi/180
// rad), compared bit for bit: a decimal prefix is applied to the decimal text,
// so "0.05 mm" must be exactly the double of the literal 0.05e-3.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>

#include "gearimpact/case/units.hpp"
#include "gearimpact/error.hpp"

using namespace gearimpact;

namespace {

double q(const char* text, Dimension dimension) {
  return parse_quantity(text, dimension, "f");
}

std::string error_of(const char* text, Dimension dimension, const char* field = "gears.module") {
  try {
    parse_quantity(text, dimension, field);
  } catch (const InputError& e) {
    CHECK(e.field() == field);
    return e.what();
  }
  FAIL("no error for \"" << text << "\"");
  return {};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("decimal units are exact: the value is the double nearest the decimal") {
  CHECK(q("10 mm", Dimension::length) == 10e-3);
  CHECK(q("0.05 mm", Dimension::length) == 0.05e-3);
  CHECK(q("2 mm", Dimension::length) == 2.0e-3);
  CHECK(q("10mm", Dimension::length) == 10e-3);
  CHECK(q("  +5 um ", Dimension::length) == 5e-6);
  CHECK(q("1e-3 mm", Dimension::length) == 1e-6);
  CHECK(q("2.5 cm", Dimension::length) == 2.5e-2);
  CHECK(q("206.8 GPa", Dimension::pressure) == 206.8e9);
  CHECK(q("206800 N/mm^2", Dimension::pressure) == 206.8e9);
  CHECK(q("7800 kg/m^3", Dimension::density) == 7800.0);
  CHECK(q("7.8 g/cm^3", Dimension::density) == 7800.0);
  CHECK(q("7.8e-6 kg/mm^3", Dimension::density) == 7800.0);
  CHECK(q("50 N*mm", Dimension::torque) == 0.05);
  CHECK(q("-50 N*mm", Dimension::torque) == -0.05);
  CHECK(q("0.1 us", Dimension::time) == 1e-7);
  CHECK(q("1e-7 s", Dimension::time) == 1e-7);
  CHECK(q("1E-7 s", Dimension::time) == 1e-7);
  CHECK(q("30 ms", Dimension::time) == 0.03);
  CHECK(q("10000 rad/s", Dimension::angular_frequency) == 10000.0);
  CHECK(q("50 rad/s", Dimension::angular_velocity) == 50.0);
  CHECK(q("1 mm/s", Dimension::speed) == 1e-3);
  CHECK(q("0 mm", Dimension::length) == 0.0);
  // A mesh stiffness: N/mm = 1e3 N/m, N/um = kN/mm = 1e6 N/m, exact decimal shifts.
  CHECK(q("350 N/um", Dimension::stiffness) == 3.5e8);
  CHECK(q("350 kN/mm", Dimension::stiffness) == 3.5e8);
  CHECK(q("0.35 N/mm", Dimension::stiffness) == 350.0);
  CHECK(q("3.5e8 N/m", Dimension::stiffness) == 3.5e8);
  CHECK(q("10 cP", Dimension::viscosity) == 0.01);
  CHECK(q("0.01 Pa*s", Dimension::viscosity) == 0.01);
}

TEST_CASE("units with a factor multiply the number by their definition") {
  CHECK(q("20 deg", Dimension::angle) == 20.0 * (std::numbers::pi / 180.0));
  CHECK(q("50 kgf*mm", Dimension::torque) == 50.0 * 9.80665e-3);
  CHECK(q("1 kgf*m", Dimension::torque) == 9.80665);
  CHECK(q("1 in", Dimension::length) == 0.0254);
  CHECK(q("1 in/s", Dimension::speed) == 0.0254);
  CHECK(q("60 rpm", Dimension::angular_velocity) == 60.0 * (2.0 * std::numbers::pi / 60.0));
  CHECK(q("1 Hz", Dimension::angular_frequency) == 2.0 * std::numbers::pi);
}

TEST_CASE("errors name the field, the text as written and the allowed units") {
  const std::string lengths = "m, mm, um, cm, in";
  struct Bad {
    const char* text;
    const char* why;
  };
  for (const Bad& bad :
       {Bad{"2", "no unit"}, Bad{"mm", "no finite decimal number"},
        Bad{"", "no finite decimal number"},
        Bad{"2 furlong", "unknown unit 'furlong' for a length"},
        Bad{"2 deg", "'deg' is a unit of an angle, not of a length"},
        Bad{"2 GPa", "'GPa' is a unit of a pressure, not of a length"},
        Bad{"2 MM", "unknown unit 'MM' for a length"}, Bad{"inf mm", "no finite decimal number"},
        Bad{"nan mm", "no finite decimal number"}, Bad{"-inf mm", "no finite decimal number"},
        Bad{"1e400 mm", "outside the range of a double"},
        Bad{"1e999999999999 mm", "outside the range of a double"},
        Bad{"1e-400 mm", "outside the range of a double"},
        Bad{"1e mm", "an exponent without digits"},
        Bad{"1.2.3 mm", "unknown unit '.3 mm' for a length"}, Bad{"0x10 mm", "unknown unit"},
        Bad{". mm", "no finite decimal number"}}) {
    CAPTURE(bad.text);
    const std::string message = error_of(bad.text, Dimension::length);
    CHECK(contains(message, "gears.module = \"" + std::string(bad.text) + "\""));
    CHECK(contains(message, bad.why));
    CHECK(contains(message, "a length"));
    CHECK(contains(message, lengths));
  }
  // A value that overflows only after the unit's factor is applied.
  CHECK(contains(error_of("1e308 kgf*m", Dimension::torque, "torque1.value"),
                 "outside the range of a double"));
}

TEST_CASE("numbers in messages are the shortest text that reads back to the same double") {
  // 0.04 is stored as 0.040000000000000000832...: 17 significant digits
  // print that tail, the shortest round trip does not.
  CHECK(format_number(0.04) == "0.04");
  CHECK(format_number(0.1 + 0.2) == "0.30000000000000004");
  CHECK(format_number(1e-7) == "1e-7");
  CHECK(format_number(206.8e9) == "206800000000");
  CHECK(format_number(1e300) == "1e300");
  CHECK(format_number(0.0) == "0");
  CHECK(format_number(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(InputError("model.friction_coefficient", 0.04, "0").value() == "0.04");
  // The same text as the case files' numbers (shortest_decimal) and a round
  // trip, over a fixed xorshift sequence of doubles of every magnitude.
  std::uint64_t state = 0x2545F4914F6CDD1Dull;
  for (int i = 0; i < 5000; ++i) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    double x = 0.0;
    const std::uint64_t bits =
        (state & 0x800FFFFFFFFFFFFFull) | ((1023ull - 60 + state % 120) << 52);
    std::memcpy(&x, &bits, sizeof x);
    const std::string text = format_number(x);
    CAPTURE(text);
    CHECK(text == shortest_decimal(x));
    CHECK(std::stod(text) == x);
  }
}

TEST_CASE("format_quantity reads back to the same double, in the requested unit when it can") {
  CHECK(format_quantity(0.05e-3, Dimension::length, "mm") == "0.05 mm");
  CHECK(format_quantity(206.8e9, Dimension::pressure, "GPa") == "206.8 GPa");
  CHECK(format_quantity(1e-7, Dimension::time, "us") == "0.1 us");
  CHECK(format_quantity(20.0 * (std::numbers::pi / 180.0), Dimension::angle, "deg") == "20 deg");
  CHECK(shortest_decimal(1e-7) == "1e-7");
  CHECK(shortest_decimal(0.0004) == "0.0004");
  CHECK(shortest_decimal(-2.5) == "-2.5");
  // An invariant over many doubles of every magnitude (a fixed xorshift
  // sequence of bit patterns) and every unit: text -> double is the identity.
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  int checked = 0;
  for (int i = 0; i < 3000; ++i) {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    double x = 0.0;
    const std::uint64_t bits =
        (state & 0x800FFFFFFFFFFFFFull) | ((1023ull - 40 + state % 80) << 52);
    std::memcpy(&x, &bits, sizeof x);
    for (Dimension dimension : {Dimension::length, Dimension::angle, Dimension::pressure,
                                Dimension::density, Dimension::torque, Dimension::time,
                                Dimension::angular_velocity, Dimension::angular_frequency,
                                Dimension::speed, Dimension::stiffness, Dimension::viscosity}) {
      for (const Unit& unit : units_of(dimension)) {
        const std::string text = format_quantity(x, dimension, unit.symbol);
        CAPTURE(text);
        REQUIRE(parse_quantity(text, dimension, "x") == x);
        ++checked;
      }
    }
  }
  CHECK(checked > 30000);
}
