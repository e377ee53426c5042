// Tooth errors drawn from a flank tolerance class of ISO 1328-1:2013
// (docs/faults.md, "Errors drawn from a tolerance class"): the tolerances
// against hand values of the standard's formulae (5) and (7), the engine
// against the output the C++ standard fixes and against an independent
// implementation of MT19937-64, every draw inside its tolerance, the
// statistics of many draws, the refusals, and the drawn errors reaching the
// gaps and the static transmission error as lists would.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/iso1328.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"
#include "relative.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

using namespace gearimpact;
using gearimpact::verify::cli;
using gearimpact::verify::CommandResult;
using gearimpact::verify::relative_difference;
using gearimpact::verify::run_command;
using gearimpact::verify::Scratch;

namespace {

// The message of the InputError `check` throws, or "" if it throws none.
template <typename Check>
std::string refusal(Check check) {
  try {
    check();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The documented transform of one raw output, written out here from its
// definition: the 53 high bits as k 2^-53, then (2u - 1) h.
double transform(std::uint64_t bits, double half_width) {
  const double u = std::ldexp(static_cast<double>(bits >> 11), -53);
  return (2.0 * u - 1.0) * half_width;
}

}  // namespace

TEST_CASE("the tolerances of the paper's pair are the hand values of formulae (5) and (7)") {
  // z1 = 20, z2 = 80, m = 2 mm: d1 = 40 mm, d2 = 160 mm. Class 5:
  // f_pT1 = 0.04 + 0.8 + 5 = 5.84 -> 6.0 um (5 to 10 um: to 0.5 um),
  // f_HaT1 = 0.8 + 0.04 + 4 = 4.84 -> 4.8 um (below 5 um: to 0.1 um). The
  // other classes scale them by sqrt(2)^(A-5) before rounding: class 6
  // 5.84 sqrt(2) = 8.259 -> 8.5 and 4.84 sqrt(2) = 6.845 -> 7.0, the wheel's
  // 5.96 sqrt(2) = 8.429 -> 8.5 and 4.96 sqrt(2) = 7.014 -> 7.0; class 9
  // times 4: 23.36 -> 23, 19.36 -> 19 and 23.84 -> 24, 19.84 -> 20 (above
  // 10 um: to 1 um); class 1 over 4: 1.46 -> 1.5, 1.21 -> 1.2; class 11 times
  // 8: 46.72 -> 47, 38.72 -> 39 and 47.68 -> 48, 39.68 -> 40.
  struct Hand {
    int tolerance_class;
    Gear gear;
    double single_pitch_um;
    double profile_slope_um;
  };
  const Hand hand[] = {
      {5, Gear::one, 6.0, 4.8},    {5, Gear::two, 6.0, 5.0},   {6, Gear::one, 8.5, 7.0},
      {6, Gear::two, 8.5, 7.0},    {9, Gear::one, 23.0, 19.0}, {9, Gear::two, 24.0, 20.0},
      {1, Gear::one, 1.5, 1.2},    {1, Gear::two, 1.5, 1.2},   {11, Gear::one, 47.0, 39.0},
      {11, Gear::two, 48.0, 40.0},
  };
  const GearPair g = paper_gear_pair();
  for (const Hand& h : hand) {
    CAPTURE(h.tolerance_class);
    CAPTURE(static_cast<int>(h.gear));
    const Iso1328Tolerances t = iso1328_tolerances(g, h.gear, h.tolerance_class);
    // A rounded value in um times 1e-6: one rounding of a double, 1e-16.
    CHECK(relative_difference(t.single_pitch_m, h.single_pitch_um * 1e-6) < 1e-15);
    CHECK(relative_difference(t.profile_slope_m, h.profile_slope_um * 1e-6) < 1e-15);
  }
}

TEST_CASE("tolerances are rounded to 1 um above 10 um, 0.5 um from 5 um, 0.1 um below") {
  CHECK(iso1328_rounded_um(10.4) == 10.0);
  CHECK(iso1328_rounded_um(10.6) == 11.0);
  CHECK(iso1328_rounded_um(7.26) == 7.5);
  CHECK(iso1328_rounded_um(7.24) == 7.0);
  CHECK(iso1328_rounded_um(5.2) == 5.0);
  CHECK(iso1328_rounded_um(4.96) == 5.0);
  CHECK(relative_difference(iso1328_rounded_um(4.94), 4.9) < 1e-15);
  CHECK(relative_difference(iso1328_rounded_um(1.21), 1.2) < 1e-15);
}

TEST_CASE("the engine is the standard's mt19937_64, whose draws an independent MT19937-64 gives") {
  // The C++ standard requires the 10000th output of a default-constructed
  // mt19937_64 to be 9981545732273789042 ([rand.predef]).
  std::mt19937_64 standard;
  standard.discard(9999);
  CHECK(standard() == 9981545732273789042ULL);
  // The outputs for seed 2 * 42 + (gear - 1), from a Python transcription of
  // Matsumoto and Nishimura's mt19937-64.c (init_genrand64, genrand64_int64),
  // which gives the value above too: gear 1's first position and first
  // profile slope (output 21 of a 20-tooth pinion), gear 2's first position
  // and first profile slope (output 81 of an 80-tooth wheel).
  const GearPair g = paper_gear_pair();
  const double to_line = std::cos(g.pressure_angle_rad);
  const DrawnToothErrors one = draw_tooth_errors(g, Gear::one, 6, 42);
  const DrawnToothErrors two = draw_tooth_errors(g, Gear::two, 6, 42);
  // Class 6: f_pT = 8.5 um on both gears, f_HaT = 7 um.
  CHECK(one.pitch_m[0] == transform(11873449873677792259ULL, 0.5 * 8.5e-6) * to_line);
  CHECK(one.profile_slope_m[0] == transform(561170283893026072ULL, 7e-6));
  CHECK(two.pitch_m[0] == transform(16623058694301960360ULL, 0.5 * 8.5e-6) * to_line);
  CHECK(two.profile_slope_m[0] == transform(13421261918569257971ULL, 7e-6));
  CHECK(two.profile_slope_m[79] == transform(10781386693650357268ULL, 7e-6));
}

TEST_CASE("the transform spans [-h, h): all zero bits give -h, all ones the largest below h") {
  CHECK(symmetric_uniform(0, 3e-6) == -3e-6);
  CHECK(symmetric_uniform(~0ULL, 3e-6) == (1.0 - 0x1.0p-52) * 3e-6);
  CHECK(symmetric_uniform(1ULL << 63, 3e-6) == 0.0);
}

TEST_CASE("the same seed draws the same teeth bit for bit, another seed other teeth") {
  const GearPair g = paper_gear_pair();
  const DrawnToothErrors a = draw_tooth_errors(g, Gear::two, 7, 2024);
  const DrawnToothErrors b = draw_tooth_errors(g, Gear::two, 7, 2024);
  CHECK(a.pitch_m == b.pitch_m);
  CHECK(a.profile_slope_m == b.profile_slope_m);
  const DrawnToothErrors c = draw_tooth_errors(g, Gear::two, 7, 2025);
  CHECK(a.pitch_m != c.pitch_m);
  CHECK(a.profile_slope_m != c.profile_slope_m);
  // The two gears of one seed have streams of their own.
  const DrawnToothErrors pinion = draw_tooth_errors(g, Gear::one, 7, 2024);
  CHECK(pinion.pitch_m[0] != a.pitch_m[0]);
}

TEST_CASE("every draw lies inside its tolerance, single pitch and cumulative pitch too") {
  const GearPair g = paper_gear_pair();
  const double to_line = std::cos(g.pressure_angle_rad);
  for (const int tolerance_class : {1, 6, 11}) {
    for (const Gear gear : {Gear::one, Gear::two}) {
      const Iso1328Tolerances t = iso1328_tolerances(g, gear, tolerance_class);
      for (std::uint32_t seed = 0; seed < 50; ++seed) {
        const DrawnToothErrors d = draw_tooth_errors(g, gear, tolerance_class, seed);
        const std::size_t z = d.pitch_m.size();
        REQUIRE(z == static_cast<std::size_t>(teeth(g, gear)));
        REQUIRE(d.profile_slope_m.size() == z);
        double least = d.pitch_m[0];
        double most = d.pitch_m[0];
        for (std::size_t i = 0; i < z; ++i) {
          CHECK(std::fabs(d.pitch_m[i]) <= 0.5 * t.single_pitch_m * to_line);
          CHECK(std::fabs(d.profile_slope_m[i]) <= t.profile_slope_m);
          // The single pitch deviation of tooth i, the closing one included.
          const double single = d.pitch_m[i] - d.pitch_m[(i + z - 1) % z];
          CHECK(std::fabs(single) < t.single_pitch_m * to_line);
          least = std::min(least, d.pitch_m[i]);
          most = std::max(most, d.pitch_m[i]);
        }
        CHECK(most - least < t.single_pitch_m * to_line);
      }
    }
  }
}

TEST_CASE("many draws have the mean and variance of the uniform distribution") {
  // 1250 seeds of an 80-tooth wheel: N = 100000 values of each error. For
  // X uniform on [-h, h): mean 0 with standard error h / sqrt(3 N) = 0.0018 h;
  // mean of X^2 = h^2 / 3 with standard error h^2 sqrt(4 / (45 N)) =
  // 0.00094 h^2. Five standard errors bound both; the draws are fixed by
  // their seeds, so the check cannot fail by chance on another run.
  const GearPair g = paper_gear_pair();
  const Iso1328Tolerances t = iso1328_tolerances(g, Gear::two, 6);
  const double h_pitch = 0.5 * t.single_pitch_m * std::cos(g.pressure_angle_rad);
  const double h_slope = t.profile_slope_m;
  double sum_pitch = 0.0;
  double sum_pitch2 = 0.0;
  double sum_slope = 0.0;
  double sum_slope2 = 0.0;
  double n = 0.0;
  for (std::uint32_t seed = 0; seed < 1250; ++seed) {
    const DrawnToothErrors d = draw_tooth_errors(g, Gear::two, 6, seed);
    for (std::size_t i = 0; i < d.pitch_m.size(); ++i) {
      const double p = d.pitch_m[i] / h_pitch;
      const double s = d.profile_slope_m[i] / h_slope;
      sum_pitch += p;
      sum_pitch2 += p * p;
      sum_slope += s;
      sum_slope2 += s * s;
      n += 1.0;
    }
  }
  REQUIRE(n == 100000.0);
  const double mean_bound = 5.0 / std::sqrt(3.0 * n);
  const double square_bound = 5.0 * std::sqrt(4.0 / (45.0 * n));
  CHECK(std::fabs(sum_pitch / n) < mean_bound);
  CHECK(std::fabs(sum_slope / n) < mean_bound);
  CHECK(std::fabs(sum_pitch2 / n - 1.0 / 3.0) < square_bound);
  CHECK(std::fabs(sum_slope2 / n - 1.0 / 3.0) < square_bound);
}

TEST_CASE(
    "a class and a list of the same errors, a gear outside ISO's scope, a lone seed: refused") {
  const GearPair g = paper_gear_pair();
  Modifications m;
  m.gear1.iso1328_class = 6;
  m.gear1.pitch_m.assign(20, 1e-6);
  std::string text = refusal([&] { validate_modifications(g, m); });
  CHECK(contains(text, "modifications.iso1328_class1 = 6"));
  CHECK(contains(text, "pitch_deviations1"));
  // One error for the one bad input.
  CHECK(!contains(text, "problems"));
  // The thickness is not drawn: its list stands beside a class.
  m.gear1.pitch_m.clear();
  m.gear1.thickness_m.assign(20, 1e-6);
  CHECK_NOTHROW(validate_modifications(g, m));

  GearPair fine = g;
  fine.module_m = 0.4e-3;
  Modifications w;
  w.gear2.iso1328_class = 3;
  text = refusal([&] { validate_modifications(fine, w); });
  CHECK(contains(text, "modifications.iso1328_class2 = 3"));
  CHECK(contains(text, "0.5 mm <= m <= 70 mm"));

  Modifications seed_only;
  seed_only.error_seed = 7;
  text = refusal([&] { validate_modifications(g, seed_only); });
  CHECK(contains(text, "modifications.error_seed = 7"));
}

TEST_CASE("a class outside 0 to 11 and a seed beyond 32 bits are refused with the key and range") {
  SimulationCase c;
  std::string text = refusal([&] { set_field(c, "modifications.iso1328_class1", "12"); });
  CHECK(contains(text, "modifications.iso1328_class1"));
  CHECK(contains(text, "[0, 11]"));
  text = refusal([&] { set_field(c, "modifications.iso1328_class2", "2.5"); });
  CHECK(contains(text, "modifications.iso1328_class2"));
  text = refusal([&] { set_field(c, "modifications.error_seed", "4294967296"); });
  CHECK(contains(text, "modifications.error_seed"));
  CHECK_NOTHROW(set_field(c, "modifications.error_seed", "4294967295"));
  CHECK(c.modifications.error_seed == 4294967295U);
}

TEST_CASE("drawn errors reach the gaps and the static transmission error as their lists would") {
  const GearPair g = paper_gear_pair();
  Modifications drawn;
  drawn.gear1.iso1328_class = 7;
  drawn.gear2.iso1328_class = 5;
  drawn.error_seed = 11;
  REQUIRE_NOTHROW(validate_modifications(g, drawn));
  CHECK(!is_unmodified(drawn));
  const DistinctTeeth distinct = distinct_teeth(drawn);
  CHECK(distinct.pinion);
  CHECK(distinct.wheel);
  // The same errors given as lists.
  Modifications listed;
  listed.gear1.pitch_m = draw_tooth_errors(g, Gear::one, 7, 11).pitch_m;
  listed.gear1.profile_slope_m = draw_tooth_errors(g, Gear::one, 7, 11).profile_slope_m;
  listed.gear2.pitch_m = draw_tooth_errors(g, Gear::two, 5, 11).pitch_m;
  listed.gear2.profile_slope_m = draw_tooth_errors(g, Gear::two, 5, 11).profile_slope_m;
  const ToothGaps a(g, drawn);
  const ToothGaps b(g, listed);
  const ContactSegment seg = contact_segment(g);
  for (const Region line : {Region::n1, Region::n2}) {
    CHECK(least_gap_bound_m(g, drawn, line) == least_gap_bound_m(g, listed, line));
    for (int k = -80; k <= 0; ++k) {
      const double x = seg.start_m + (seg.end_m - seg.start_m) * (k + 80) / 80.0;
      CHECK(a.gap_m(line, k, x) == b.gap_m(line, k, x));
    }
  }
  // A constant pair stiffness: the STE of the drawn teeth over the hunting
  // period equals that of the lists, point for point.
  const PairStiffnessFunction k = [](int, double) { return 2e8; };
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 4;
  const StaticTransmissionError ste_drawn = static_transmission_error(g, drawn, 100.0, k, options);
  const StaticTransmissionError ste_listed =
      static_transmission_error(g, listed, 100.0, k, options);
  CHECK(ste_drawn.mesh_periods == 80);
  REQUIRE(ste_drawn.points.size() == ste_listed.points.size());
  for (std::size_t i = 0; i < ste_drawn.points.size(); ++i) {
    CHECK(ste_drawn.points[i].ste_m == ste_listed.points[i].ste_m);
  }
  CHECK(ste_drawn.ste_peak_to_peak_m > 0.0);
}

TEST_CASE("check-case echoes the class and the seed, which read back, and prints the drawn teeth") {
  SimulationCase c = paper_case(2);
  c.modifications.gear1.iso1328_class = 6;
  c.modifications.error_seed = 42;
  const std::string text = write_case_file(c, CaseUnits::si);
  CHECK(contains(text, "iso1328_class1 = 6\n"));
  CHECK(contains(text, "error_seed = 42\n"));
  // Gear 2 has no class: its row stays out, as every modification at its default.
  CHECK(!contains(text, "iso1328_class2"));
  const SimulationCase back = parse_case(text, "echo.toml");
  CHECK(back.modifications == c.modifications);

  Scratch scratch("iso1328-check-case");
  const std::filesystem::path file = scratch.dir / "class6.toml";
  std::ofstream(file) << text;
  const CommandResult run = run_command(cli("check-case " + file.string()));
  REQUIRE(run.exit_code == 0);
  CHECK(contains(run.out, "iso1328_class1 = 6\n"));
  CHECK(contains(run.out, "gear 1, ISO 1328-1:2013 class 6: f_pT = 8.5e-6 m, f_HalphaT = 7e-6 m"));
  const DrawnToothErrors d = draw_tooth_errors(c.gears, Gear::one, 6, 42);
  CHECK(contains(run.out, "pitch_deviations1 = [" + shortest_decimal(d.pitch_m[0]) + ", " +
                              shortest_decimal(d.pitch_m[1]) + ", "));
  CHECK(contains(run.out, ", " + shortest_decimal(d.profile_slope_m[19]) + "]\n"));
}

TEST_CASE("a run with drawn errors is the run with the same errors as lists, bit for bit") {
  SimulationCase drawn = paper_case(2);
  drawn.integrator.end_time_s = 0.002;
  drawn.modifications.gear1.iso1328_class = 6;
  drawn.modifications.gear2.iso1328_class = 8;
  drawn.modifications.error_seed = 5;
  SimulationCase listed = drawn;
  listed.modifications = with_drawn_errors(drawn.gears, drawn.modifications);
  listed.modifications.gear1.iso1328_class = 0;
  listed.modifications.gear2.iso1328_class = 0;
  listed.modifications.error_seed = 0;
  REQUIRE(!listed.modifications.gear2.pitch_m.empty());
  RunControl control;
  control.keep_series = false;
  const SimulationSummary a = simulate(drawn, control).summary;
  const SimulationSummary b = simulate(listed, control).summary;
  CHECK(a.final_w1_rad_per_s == b.final_w1_rad_per_s);
  CHECK(a.final_w2_rad_per_s == b.final_w2_rad_per_s);
  CHECK(a.impacts_n1 == b.impacts_n1);
  CHECK(a.events == b.events);
  CHECK(a.ledger_residual_max_j == b.ledger_residual_max_j);
  SimulationCase plain = drawn;
  plain.modifications = {};
  CHECK(simulate(plain, control).summary.final_w2_rad_per_s != a.final_w2_rad_per_s);
}
