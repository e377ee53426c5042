// What a designer needs before a run: the points of single tooth contact (where a relief starts),
// where a root crack starts and how deep it may reach, the step bounds of a run, printed by
// `check-case` and `report`; a plain number for a speed warned of, and a sample rate with its
// unit. References: the base-circle geometry of rack-cut gears in closed form written here
// (d = 2 sqrt(Rb^2 + roll^2), the rolls from the tip circles and a base pitch), Rb sin theta_b of
// (13), the contact period and the mesh period from their definitions, and the validators' own
// refusals at each bound.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "gearimpact/case/units.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"
#include "relative.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

using namespace gearimpact;
using namespace gearimpact::verify;

namespace {

constexpr double kPi = 3.14159265358979323846;

const std::filesystem::path kExamples =
    std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples";

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The value of `quantity` for `gear` ("pinion", "wheel", "pair") in geometry.csv.
double csv_value(const std::string& csv, const std::string& quantity, const std::string& gear) {
  std::istringstream in(csv);
  std::string line;
  const std::string key = quantity + "," + gear + ",";
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) return std::stod(line.substr(key.size()));
  }
  FAIL("no " << quantity << " of the " << gear << " in geometry.csv");
  return 0.0;
}

double involute(double a) {
  return std::tan(a) - a;
}

// The diameters of single tooth contact of rack-cut spur gears (ha = 1) at the centre distance
// without backlash, as a textbook gives them: inv a_w = inv a0 + 2 tan a0 (x1 + x2) / (z1 + z2),
// a_w = (Rb1 + Rb2) / cos a_w, r_a = m z / 2 + (1 + x) m, p_b = pi m cos a0. On the pinion the
// active profile starts at the roll a_w sin a_w - sqrt(ra2^2 - Rb2^2) and ends at
// sqrt(ra1^2 - Rb1^2). A tooth carries alone from where the pair ahead leaves (at the tip, a base
// pitch on: LPSTC at the tip's roll - p_b) to where the pair behind enters (HPSTC at the start's
// roll + p_b), d = 2 sqrt(Rb^2 + roll^2); the wheel alike with the gears swapped.
struct SingleContact {
  double lpstc1, hpstc1, lpstc2, hpstc2;
};
SingleContact textbook_single_contact(int z1, int z2, double m, double a0, double x1, double x2) {
  const double target = involute(a0) + 2.0 * std::tan(a0) * (x1 + x2) / (z1 + z2);
  double aw = a0;
  for (int i = 0; i < 60; ++i) aw -= (involute(aw) - target) / (std::tan(aw) * std::tan(aw));
  const double rb1 = 0.5 * m * z1 * std::cos(a0);
  const double rb2 = 0.5 * m * z2 * std::cos(a0);
  const double ra1 = 0.5 * m * z1 + (1.0 + x1) * m;
  const double ra2 = 0.5 * m * z2 + (1.0 + x2) * m;
  const double centre = (rb1 + rb2) / std::cos(aw);
  const double pb = kPi * m * std::cos(a0);
  const double tip_roll1 = std::sqrt(ra1 * ra1 - rb1 * rb1);
  const double tip_roll2 = std::sqrt(ra2 * ra2 - rb2 * rb2);
  const double lp = centre * std::sin(aw);
  const auto d = [](double rb, double roll) { return 2.0 * std::sqrt(rb * rb + roll * roll); };
  return {d(rb1, tip_roll1 - pb), d(rb1, lp - tip_roll2 + pb), d(rb2, tip_roll2 - pb),
          d(rb2, lp - tip_roll1 + pb)};
}

}  // namespace

TEST_CASE(
    "LPSTC and HPSTC against the textbook's base-circle geometry, in the library and report") {
  // The shifted 17/40 pair of examples/ (x1 = 0.5): the operating pressure angle by Newton on
  // inv a in the test and in the library; both converge to round-off, so the diameters agree
  // to about 1e-13 (the contact ratio of this pair agrees to 1e-12, test_report_cli).
  const SimulationCase c = read_pair_or_run_file(kExamples / "pinion_17_x05.toml").simulation_case;
  const SingleContact expected =
      textbook_single_contact(17, 40, 2e-3, 20.0 * kPi / 180.0, 0.5, 0.0);
  const ActiveProfile p1 = active_profile(c.gears, Gear::one);
  const ActiveProfile p2 = active_profile(c.gears, Gear::two);
  CHECK(relative_difference(p1.lowest_single_contact_diameter_m, expected.lpstc1) <= 1e-12);
  CHECK(relative_difference(p1.highest_single_contact_diameter_m, expected.hpstc1) <= 1e-12);
  CHECK(relative_difference(p2.lowest_single_contact_diameter_m, expected.lpstc2) <= 1e-12);
  CHECK(relative_difference(p2.highest_single_contact_diameter_m, expected.hpstc2) <= 1e-12);
  // Inside the active profile, in order: SAP < LPSTC < HPSTC < tip (contact ratio in (1, 2)).
  CHECK(p1.start_diameter_m < p1.lowest_single_contact_diameter_m);
  CHECK(p1.lowest_single_contact_diameter_m < p1.highest_single_contact_diameter_m);
  CHECK(p1.highest_single_contact_diameter_m < p1.tip_diameter_m);

  const Scratch scratch("designer-bounds-report");
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r = run_command(cli("report " + (kExamples / "pinion_17_x05.toml").string() +
                                          " --samples 40 --out " + out.string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const std::string csv = read(out / "geometry.csv");
  CHECK(relative_difference(csv_value(csv, "lpstc_diameter", "pinion"), expected.lpstc1) <= 1e-12);
  CHECK(relative_difference(csv_value(csv, "hpstc_diameter", "pinion"), expected.hpstc1) <= 1e-12);
  CHECK(relative_difference(csv_value(csv, "lpstc_diameter", "wheel"), expected.lpstc2) <= 1e-12);
  CHECK(relative_difference(csv_value(csv, "hpstc_diameter", "wheel"), expected.hpstc2) <= 1e-12);
  // The step bound of the pair, as step_bounds gives it (shortest decimals: exact).
  const StepBounds b = step_bounds(c);
  CHECK(csv_value(csv, "largest_step_rk4", "pair") == b.rk4_step_s);
  CHECK(csv_value(csv, "largest_step_dopri5", "pair") == b.dopri5_step_s);
  const std::string report = read(out / "REPORT.md");
  CHECK(has(report, "Step bound of a run"));
  CHECK(has(report, "HPSTC"));
}

TEST_CASE(
    "the crack's reach: h_c = Rb sin theta_b on the paper's tooth, and the validator's bound") {
  const SimulationCase c = paper_case(1);
  RootCrack crack;
  crack.angle_rad = 30.0 * kPi / 180.0;
  const CrackReach reach = crack_reach(c.gears, c.model.stiffness, Gear::one, crack);
  // (13): theta_b = pi / (2 z) + inv a0 for the unshifted paper pair; the crack starts at the
  // base circle.
  const double rb = base_radius(c.gears, Gear::one);
  const double theta_b = kPi / (2.0 * c.gears.teeth1) + involute(c.gears.pressure_angle_rad);
  CHECK(reach.start_radius_m == rb);
  CHECK(relative_difference(reach.start_half_thickness_m, rb * std::sin(theta_b)) <= 1e-15);
  CHECK(relative_difference(reach.largest_depth_m, rb * std::sin(theta_b) / 0.5) <= 1e-15);
  // The validator refuses a depth just past the reach and takes one just short of it.
  std::vector<ToothFault> faults(1);
  faults[0].state.kind = ToothKind::root_crack;
  faults[0].state.crack = crack;
  faults[0].state.crack.depth_m = reach.largest_depth_m * (1.0 + 1e-9);
  CHECK_THROWS_AS(check_tooth_faults(c.gears, c.model.stiffness, faults), InputError);
  faults[0].state.crack.depth_m = reach.largest_depth_m * (1.0 - 1e-9);
  CHECK_NOTHROW(check_tooth_faults(c.gears, c.model.stiffness, faults));
  // The other models start the crack on the fillet: the validator's bound there too.
  SimulationCase pe = c;
  pe.model.stiffness.kind = StiffnessModelKind::potential_energy;
  pe.gears.bore_diameter1_m = 0.02;
  pe.gears.bore_diameter2_m = 0.02;
  const CrackReach fillet = crack_reach(pe.gears, pe.model.stiffness, Gear::two, crack);
  CHECK(fillet.start_half_thickness_m > 0.0);
  faults[0].gear = Gear::two;
  faults[0].state.crack.depth_m = fillet.largest_depth_m * (1.0 + 1e-9);
  CHECK_THROWS_AS(check_tooth_faults(pe.gears, pe.model.stiffness, faults), InputError);
  faults[0].state.crack.depth_m = fillet.largest_depth_m * (1.0 - 1e-9);
  CHECK_NOTHROW(check_tooth_faults(pe.gears, pe.model.stiffness, faults));
}

TEST_CASE("step bounds: the contact period's 1/20 and 1/10, the mesh period's 1/20, as enforced") {
  SimulationCase c = paper_case(2);
  const StepBounds b = step_bounds(c);
  CHECK(b.rk4_step_s == largest_resolving_step_s(c));
  CHECK(relative_difference(b.rk4_step_s, b.contact_period_s / 20.0) <= 1e-15);
  CHECK(relative_difference(b.dopri5_step_s, b.contact_period_s / 10.0) <= 1e-15);
  CHECK(relative_difference(b.mesh_period_s,
                            2.0 * kPi / (c.gears.teeth1 * std::fabs(c.initial.w1_rad_per_s))) <=
        1e-15);
  CHECK(relative_difference(b.mesh_step_s, b.mesh_period_s / 20.0) <= 1e-15);
  // The validator: a step a little above the rk4 bound is refused, at it accepted.
  c.integrator.step_s = b.rk4_step_s * (1.0 + 1e-9);
  try {
    validate(c);
    FAIL("a step above the bound passed");
  } catch (const InputError& e) {
    CHECK(e.field() == "integrator.step");
  }
  c.integrator.step_s = b.rk4_step_s;
  CHECK_NOTHROW(validate(c));
}

TEST_CASE("check-case prints the bounds a run is held to") {
  const std::string file =
      (std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / "case2.toml").string();
  const CommandResult r = run_command(cli("check-case " + file));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const StepBounds b = step_bounds(read_case_file(file));
  CHECK_MESSAGE(
      has(r.out, "integrator.step <= " + shortest_decimal(b.rk4_step_s) + " s with kind = \"rk4\""),
      r.out);
  CHECK(has(r.out, "<= " + shortest_decimal(b.dopri5_step_s) + " s with \"dopri5\""));
  CHECK(has(r.out, "mesh period 2 pi / (z1 |w1|) = " + shortest_decimal(b.mesh_period_s)));
  CHECK(has(r.out, "tip_relief_start1 in [d_SAP, d_a)"));
  CHECK(has(r.out, "HPSTC d = "));
  CHECK(has(r.out, "h_c = "));
  // A pair file: the contact's bounds, no speed.
  const CommandResult pair =
      run_command(cli("check-case " + (kExamples / "pinion_17_x05.toml").string()));
  REQUIRE_MESSAGE(pair.exit_code == 0, pair.err);
  CHECK(has(pair.out, "with kind = \"rk4\""));
  CHECK_FALSE(has(pair.out, "mesh period 2 pi"));
}

TEST_CASE("a plain number for a speed warns, with a unit it does not; a sample rate in kHz") {
  const Scratch scratch("designer-bounds-units");
  const std::string run = "simulate --case 1 --t-end '0.02 ms' --out ";
  const CommandResult plain =
      run_command(cli(run + (scratch.dir / "a.csv").string() + " --set initial.w1=150"));
  CHECK(has(plain.err, "initial.w1 = 150 is read as 150 rad/s (1432.39 rpm)"));
  CHECK(has(plain.err, "write \"150 rad/s\" or \"150 rpm\""));
  const CommandResult unit =
      run_command(cli(run + (scratch.dir / "b.csv").string() + " --set 'initial.w1=150 rad/s'"));
  CHECK_FALSE(has(unit.err, "is read as"));
  CHECK(plain.exit_code == unit.exit_code);
  // The sweep's ends: a plain speed warns before any work.
  const CommandResult sweep = run_command(
      cli("sweep 2 --vary initial.w1 --from 2000 --to 2100 --points 2 --max-points 0.5 --out " +
          (scratch.dir / "sweep").string()));
  CHECK(has(sweep.err, "--from (initial.w1) = 2000 is read as 2000 rad/s (19098.6 rpm)"));
  // A sample rate with its unit is the same rate as the plain number in Hz: the same samples.
  const std::filesystem::path khz = scratch.dir / "khz.csv";
  const std::filesystem::path hz = scratch.dir / "hz.csv";
  const CommandResult with_unit = run_command(
      cli("simulate --case 1 --t-end '0.2 ms' --sample-rate '80 kHz' --out " + khz.string()));
  REQUIRE_MESSAGE(with_unit.exit_code == 0, with_unit.err);
  const CommandResult plain_hz = run_command(
      cli("simulate --case 1 --t-end '0.2 ms' --sample-rate 80000 --out " + hz.string()));
  REQUIRE_MESSAGE(plain_hz.exit_code == 0, plain_hz.err);
  CHECK(read(khz) == read(hz));
  CHECK(read(khz).size() > 100);
  const CommandResult bad =
      run_command(cli("simulate --case 1 --t-end '0.2 ms' --sample-rate '80 rpm' --out " +
                      (scratch.dir / "bad.csv").string()));
  CHECK(bad.exit_code == 1);
  CHECK(has(bad.err, "--sample-rate"));
  CHECK(has(bad.err, "kHz"));
}
