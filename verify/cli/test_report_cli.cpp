// End to end: `gearimpact report` on two user pairs (examples/), and the stiffness commands on a
// pair file ([gears] and [model] only). Reference values by closed forms written here, not by
// the library: the contact ratio of two rack-cut gears, ROSS's root half angle, the warnings'
// numbers.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "relative.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

using namespace gearimpact::verify;

namespace {

const std::filesystem::path examples =
    std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples";

constexpr double pi = 3.14159265358979323846;

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The value of `quantity` (gear "pair") in geometry.csv.
double geometry_value(const std::string& csv, const std::string& quantity) {
  std::istringstream in(csv);
  std::string line;
  const std::string key = quantity + ",pair,";
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) == 0) return std::stod(line.substr(key.size()));
  }
  FAIL("no " << quantity << " in geometry.csv");
  return 0.0;
}

double involute(double a) {
  return std::tan(a) - a;
}

// Rack-cut spur gears (ha = 1) at the centre distance without backlash: inv a_w = inv a0 + 2 tan
// a0 (x1 + x2) / (z1 + z2), a_w (r_b1 + r_b2) / cos a_w, r_a = m z / 2 + (1 + x) m, eps =
// [sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a_w sin a_w] / (pi m cos a0).
double contact_ratio(int z1, int z2, double m, double a0, double x1, double x2) {
  const double target = involute(a0) + 2.0 * std::tan(a0) * (x1 + x2) / (z1 + z2);
  double aw = a0;
  for (int i = 0; i < 60; ++i) aw -= (involute(aw) - target) / (std::tan(aw) * std::tan(aw));
  const double rb1 = 0.5 * m * z1 * std::cos(a0);
  const double rb2 = 0.5 * m * z2 * std::cos(a0);
  const double ra1 = 0.5 * m * z1 + (1.0 + x1) * m;
  const double ra2 = 0.5 * m * z2 + (1.0 + x2) * m;
  const double centre = (rb1 + rb2) / std::cos(aw);
  return (std::sqrt(ra1 * ra1 - rb1 * rb1) + std::sqrt(ra2 * ra2 - rb2 * rb2) -
          centre * std::sin(aw)) /
         (pi * m * std::cos(a0));
}

// ROSS's theta_f = [pi/2 + 2 tan a0 (ha - rho*) + 2 rho* / cos a0] / z with the full round
// rho* = c / (1 - sin a0), ha = 1, c = 0.25 (docs/stiffness-models.md section 3).
double ross_theta_f(int z) {
  const double a0 = 20.0 * pi / 180.0;
  const double rho = 0.25 / (1.0 - std::sin(a0));
  return (0.5 * pi + 2.0 * std::tan(a0) * (1.0 - rho) + 2.0 * rho / std::cos(a0)) / z;
}

std::string printed(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("stiffness commands read a pair file; a run file missing a section is still refused") {
  const Scratch scratch("report-pair");
  const std::filesystem::path pair = examples / "pinion_17_x05.toml";
  for (const char* command : {"mesh-stiffness --samples 8 --summary", "stiffness --points 3",
                              "iso6336", "energy-ratios --points 3"}) {
    CAPTURE(command);
    const CommandResult r =
        run_command(cli(std::string(command) + " --case-file " + pair.string()));
    CHECK_MESSAGE(r.exit_code == 0, r.err);
  }
  // The pinion's theta_f names the gear, the parameter, its value and the fit's range.
  const CommandResult mesh = run_command(cli(
      "mesh-stiffness --samples 8 --summary --model ross-compatible --case-file " + pair.string()));
  REQUIRE_MESSAGE(mesh.exit_code == 0, mesh.err);
  const std::string expected = "pinion (gear 1): theta_f = " + printed("%.3g", ross_theta_f(17)) +
                               " rad, outside the fit's [0.01, 0.12] rad";
  CHECK_MESSAGE(has(mesh.err, expected), mesh.err);
  CHECK(has(mesh.out, expected));
  // check-case says it is a pair file and prints its pair, itself a pair file that reads back.
  const CommandResult checked = run_command(cli("check-case " + pair.string()));
  REQUIRE_MESSAGE(checked.exit_code == 0, checked.err);
  CHECK(has(checked.out, "a valid pair file"));
  const std::string body = checked.out.substr(checked.out.find('\n') + 1);
  CHECK(has(body, "\n[gears]\n"));
  CHECK(has(body, "\n[model]\n"));
  CHECK_FALSE(has(body, "[torque1]"));
  CHECK_FALSE(has(body, "[integrator]"));
  const std::filesystem::path echoed = scratch.dir / "echoed.toml";
  write(echoed, body);
  const CommandResult again = run_command(cli("check-case " + echoed.string()));
  CHECK_MESSAGE(again.exit_code == 0, again.err);
  CHECK(checked.out.substr(checked.out.find('\n')) == again.out.substr(again.out.find('\n')));
  // A pair file with faulted teeth keeps them in its echo, which reads back to the same case
  // (its true period: a pinion revolution of 20 mesh periods).
  const CommandResult cracked =
      run_command(cli("check-case " + (examples / "cracked_pinion.toml").string()));
  REQUIRE_MESSAGE(cracked.exit_code == 0, cracked.err);
  const std::string cracked_body = cracked.out.substr(cracked.out.find('\n') + 1);
  CHECK(has(cracked_body, "\n[[faults]]\n"));
  const std::filesystem::path cracked_echo = scratch.dir / "cracked_echo.toml";
  write(cracked_echo, cracked_body);
  const CommandResult cracked_again = run_command(cli("check-case " + cracked_echo.string()));
  CHECK_MESSAGE(cracked_again.exit_code == 0, cracked_again.err);
  CHECK(cracked.out.substr(cracked.out.find('\n')) ==
        cracked_again.out.substr(cracked_again.out.find('\n')));
  // [initial] makes it a run file, which needs its torques.
  const std::filesystem::path partial = scratch.dir / "partial.toml";
  write(partial, read(pair) + "\n[initial]\nw1 = \"100 rad/s\"\n");
  const CommandResult refused =
      run_command(cli("mesh-stiffness --samples 8 --case-file " + partial.string()));
  CHECK(refused.exit_code == 1);
  CHECK(has(refused.err, "section [torque1] is missing"));
}

TEST_CASE("report on the 23/67 run file: files, contact ratio, warnings with their numbers") {
  const Scratch scratch("report-2367");
  const std::filesystem::path out = scratch.dir / "out";
  const std::filesystem::path file = examples / "pair_23_67.toml";
  const CommandResult r =
      run_command(cli("report " + file.string() + " --samples 60 --out " + out.string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  for (const char* name :
       {"REPORT.md", "geometry.csv", "stiffness_tvms.png", "stiffness_tvms.svg",
        "stiffness_tvms.gp", "stiffness_tvms_yang-lin-1987.csv",
        "stiffness_tvms_potential-energy.csv", "stiffness_tvms_ross-compatible.csv",
        "load_sharing.csv", "load_sharing.png", "time_history.csv", "time_history_dte.png",
        "time_history_dte.svg"}) {
    CAPTURE(name);
    CHECK(std::filesystem::file_size(out / name) > 100);
  }
  // The shifts +0.2/-0.2 sum to 0: a_w = a0, eps by the closed form to round-off (a few ulps of
  // lengths of about 30 mm over a pitch).
  const double eps = contact_ratio(23, 67, 3e-3, 20.0 * pi / 180.0, 0.2, -0.2);
  CHECK(relative_difference(geometry_value(read(out / "geometry.csv"), "contact_ratio"), eps) <=
        1e-12);
  const std::string report = read(out / "REPORT.md");
  // Both rack-cut models extrapolate the pinion's foundation: ROSS's theta_f by its formula.
  CHECK_MESSAGE(has(report,
                    "ross-compatible: the fillet-foundation fit of Sainsot et al. (2004) "
                    "is used outside its range (pinion (gear 1): theta_f = " +
                        printed("%.3g", ross_theta_f(23)) + " rad"),
                report);
  // Balanced and rolling as written: no such warnings.
  CHECK_FALSE(has(report, "Unbalanced"));
  CHECK_FALSE(has(report, "not rolling"));
  CHECK(has(report, "## Time history\n\nThe case run as its file says"));

  // The same pair with w2 = 0 and T2 = -400 N*m: both warnings, with their numbers.
  std::string text = read(file);
  text.replace(text.find("-436.9565217391304 N*m"), 22, "-400 N*m");
  text.replace(text.find("343.2835820895522 rpm"), 21, "0 rpm");
  const std::filesystem::path changed = scratch.dir / "changed.toml";
  write(changed, text);
  const std::filesystem::path out2 = scratch.dir / "out2";
  const CommandResult r2 =
      run_command(cli("report " + changed.string() + " --samples 20 --out " + out2.string()));
  REQUIRE_MESSAGE(r2.exit_code == 0, r2.err);
  const std::string report2 = read(out2 / "REPORT.md");
  const double rb1 = 0.5 * 3e-3 * 23 * std::cos(20.0 * pi / 180.0);
  const double rb2 = 0.5 * 3e-3 * 67 * std::cos(20.0 * pi / 180.0);
  // The balancing torque -T1 Rb2/Rb1 as the fix, in its shortest round-trip form.
  const std::string fix = "torque2.value = \"";
  const std::size_t at = report2.find(fix);
  REQUIRE_MESSAGE(at != std::string::npos, report2);
  const double balancing = std::stod(report2.substr(at + fix.size()));
  CHECK(relative_difference(balancing, -150.0 * rb2 / rb1) < 1e-12);
  CHECK(has(report2.substr(at), " N*m\" balances T1"));
  CHECK(has(report2, "T1/Rb1 + T2/Rb2 = " + printed("%.6g", 150.0 / rb1 - 400.0 / rb2) + " N"));
  CHECK(has(report2, "Rb1 w1 = " + printed("%.6g", rb1 * 1000.0 * 2.0 * pi / 60.0) +
                         " m/s, Rb2 w2 = 0 m/s"));
  CHECK(has(r2.err, "warning: Unbalanced mean torques"));
  // check-case and simulate say the same before any run; Table 1's transients stay quiet.
  const CommandResult checked = run_command(cli("check-case " + changed.string()));
  REQUIRE_MESSAGE(checked.exit_code == 0, checked.err);
  CHECK(has(checked.err, "gearimpact: warning: unbalanced mean torques"));
  CHECK(has(checked.err, "gearimpact: warning: initial speeds not rolling"));
  CHECK(has(checked.out, "# warning: unbalanced mean torques"));
  const CommandResult run =
      run_command(cli("simulate --case-file " + changed.string() + " --t-end 0.1ms"));
  REQUIRE_MESSAGE(run.exit_code == 0, run.err);
  CHECK(has(run.err, "gearimpact: warning: unbalanced mean torques"));
  const CommandResult paper = run_command(cli("simulate --case 2 --t-end 0.1ms"));
  REQUIRE_MESSAGE(paper.exit_code == 0, paper.err);
  CHECK_FALSE(has(paper.err, "unbalanced"));
}

TEST_CASE("the unbalanced-torque warning says what friction changes") {
  // Case 2 with a load 1.5 times Table 1's: T1/Rb1 + T2/Rb2 far from 0.
  gearimpact::SimulationCase c = gearimpact::paper_case(2);
  c.torque2.constant_n_m *= 1.5;
  const auto unbalanced = [](const gearimpact::SimulationCase& k) {
    for (const std::string& w : gearimpact::run_warnings(k)) {
      if (has(w, "unbalanced mean torques")) return w;
    }
    return std::string();
  };
  c.model.friction_coefficient = 0.0;
  CHECK(has(unbalanced(c), "accelerates without bound and has no steady state"));
  // With friction an excess power can be what friction takes: a speed may hold.
  c.model.friction_coefficient = 0.04;
  CHECK(has(unbalanced(c), "friction's mean power"));
  CHECK_FALSE(has(unbalanced(c), "has no steady state"));
}

TEST_CASE("report on a 17-tooth pinion with x = +0.5 (a pair file): no time history") {
  const Scratch scratch("report-17");
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r = run_command(cli("report " + (examples / "pinion_17_x05.toml").string() +
                                          " --samples 40 --out " + out.string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  for (const char* name : {"REPORT.md", "geometry.csv", "stiffness_tvms.png", "load_sharing.png"}) {
    CAPTURE(name);
    CHECK(std::filesystem::file_size(out / name) > 100);
  }
  CHECK_FALSE(std::filesystem::exists(out / "time_history.csv"));
  // x1 + x2 = 0.5: the operating pressure angle by Newton on inv a in the test; the inverse
  // converges to round-off, so eps agrees to about 1e-12.
  const std::string geometry = read(out / "geometry.csv");
  const double eps = contact_ratio(17, 40, 2e-3, 20.0 * pi / 180.0, 0.5, 0.0);
  CHECK(relative_difference(geometry_value(geometry, "contact_ratio"), eps) <= 1e-12);
  // The centre distance a = m (z1 + z2) cos a0 / (2 cos a_w) grows with the shift: above 57 mm.
  CHECK(geometry_value(geometry, "centre_distance") > 57e-3);
  const std::string report = read(out / "REPORT.md");
  CHECK(has(report, "(a pair file)"));
  CHECK(has(report, "no time history"));
  CHECK(has(report, "pinion (gear 1): theta_f = " + printed("%.3g", ross_theta_f(17)) + " rad"));
  // A second run into the filled folder is refused without --overwrite.
  const CommandResult again =
      run_command(cli("report " + (examples / "pinion_17_x05.toml").string() +
                      " --samples 40 --out " + out.string()));
  CHECK(again.exit_code != 0);
}

TEST_CASE("iso6336 --load: the low-load factor (F_t K_A / b / 100 N/mm)^0.25 below 100 N/mm") {
  const std::string pair = " --case-file " + (examples / "pinion_17_x05.toml").string();
  const auto number_after = [](const std::string& json, const std::string& key) {
    const std::size_t at = json.find("\"" + key + "\": ");
    REQUIRE(at != std::string::npos);
    return std::stod(json.substr(at + key.size() + 4));
  };
  const CommandResult half = run_command(cli("iso6336 --load '50 N/mm'" + pair));
  REQUIRE_MESSAGE(half.exit_code == 0, half.err);
  CHECK(relative_difference(number_after(half.out, "low_load_factor"), std::pow(0.5, 0.25)) <=
        1e-15);
  // At the threshold and above c' holds as stated: the same c' as without a load.
  const CommandResult none = run_command(cli("iso6336" + pair));
  const CommandResult at = run_command(cli("iso6336 --load '100 N/mm'" + pair));
  CHECK(number_after(at.out, "low_load_factor") == 1.0);
  CHECK(number_after(at.out, "c_prime_n_mm_um") == number_after(none.out, "c_prime_n_mm_um"));
  CHECK(none.out.find("low_load_factor") == std::string::npos);
  // A torque: F_t / b = T1 / (r1 b), r1 = m z1 / 2 = 17 mm, b = 20 mm: 20 N*m is 58.8 N/mm.
  const CommandResult torque = run_command(cli("iso6336 --load '20 N*m'" + pair));
  REQUIRE_MESSAGE(torque.exit_code == 0, torque.err);
  const double line_load_n_mm = 20.0 / (17e-3 * 20e-3) * 1e-3;
  CHECK(relative_difference(number_after(torque.out, "specific_load_n_mm"), line_load_n_mm) <=
        1e-15);
  CHECK(relative_difference(number_after(torque.out, "low_load_factor"),
                            std::pow(line_load_n_mm / 100.0, 0.25)) <= 1e-15);
  const CommandResult bad = run_command(cli("iso6336 --load '50 kg'" + pair));
  CHECK(bad.exit_code == 1);
  CHECK(has(bad.err, "--load"));
  CHECK(has(bad.err, "N/mm"));
}

TEST_CASE(
    "report on Table 1's case 1: a zero mean torque has no line load, the report is written") {
  // Case 1 is a free impact (T1 = T2 = 0): ISO's low-load factor has no load to take, so the
  // report leaves that line out instead of refusing the case.
  const Scratch scratch("report-case1");
  const std::filesystem::path out = scratch.dir / "out";
  const std::filesystem::path file =
      std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / "case1.toml";
  const CommandResult r =
      run_command(cli("report " + file.string() + " --samples 40 --out " + out.string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const std::string report = read(out / "REPORT.md");
  CHECK(has(report, "## Time history"));
  CHECK_FALSE(has(report, "low-load factor (F_t K_A / b / 100 N/mm)^0.25 below 100 N/mm is"));
  CHECK(std::filesystem::exists(out / "time_history.csv"));
}

TEST_CASE("report on a pair file with a missing tooth says its sections are the healthy pair's") {
  // The report's stiffness sections are of healthy teeth; a faulted case must
  // not pass for a healthy one.
  Scratch scratch("report-faulted");
  const std::filesystem::path pair = scratch.dir / "faulted.toml";
  std::ofstream(pair) << "[gears]\nteeth1 = 20\nteeth2 = 80\nmodule = \"2 mm\"\n"
                         "pressure_angle = \"20 deg\"\nface_width = \"10 mm\"\n"
                         "youngs_modulus = \"206.8 GPa\"\npoisson_ratio = 0.3\n"
                         "density = \"7800 kg/m^3\"\nbacklash = \"0.05 mm\"\n\n[[faults]]\n"
                         "gear = \"pinion\"\ntooth = 0\nkind = \"missing\"\n";
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r = run_command(cli("report " + pair.string() + " --out " + out.string()));
  REQUIRE(r.exit_code == 0);
  std::ifstream in(out / "REPORT.md");
  const std::string md((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(md.find("1 faulted teeth") != std::string::npos);
  CHECK(md.find("healthy pair's") != std::string::npos);
  // A pair file has no time history to run with the faults.
  CHECK(md.find("time history runs") == std::string::npos);
  // Its own section draws the faulted stiffness over the pinion revolution (its true period):
  // 400 samples (the default --samples) in each of 20 mesh periods. Where the missing tooth would
  // carry alone the mesh stiffness is 0 and the healthy one is not; outside the missing tooth's
  // contact the two columns are one curve.
  CHECK(md.find("## Mesh stiffness with the faults") != std::string::npos);
  CHECK(md.find("pinion-revolution, 20 mesh periods") != std::string::npos);
  for (const char* file : {"mesh_stiffness.png", "mesh_stiffness.svg", "mesh_stiffness.gp"}) {
    CAPTURE(file);
    CHECK(std::filesystem::exists(out / file));
  }
  std::ifstream csv(out / "mesh_stiffness.csv");
  std::string line;
  std::getline(csv, line);
  REQUIRE(line.rfind("fraction,theta1_rad,pairs,ke_n_m,healthy_ke_n_m,", 0) == 0);
  int rows = 0;
  int zero_rows = 0;
  int equal_rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    std::istringstream fields(line);
    std::string field;
    std::vector<double> v;
    // The first five columns; a row with one pair in contact leaves the second pair's empty.
    while (v.size() < 5 && std::getline(fields, field, ',')) v.push_back(std::stod(field));
    REQUIRE(v.size() == 5);
    CHECK(v[4] > 0.0);
    zero_rows += v[3] == 0.0;
    equal_rows += v[3] == v[4];
  }
  CHECK(rows == 20 * 400);
  CHECK(zero_rows > 0);
  // Pinion tooth 0 is in contact eps_alpha = 1.69 of the 20 mesh periods: the rest agree.
  CHECK(equal_rows > rows * 18 / 20);
  CHECK(equal_rows < rows);
}

namespace {

// The rows of a CSV with a header, as numbers.
std::vector<std::vector<double>> csv_numbers(const std::string& csv, std::string& header) {
  std::istringstream in(csv);
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::vector<double> row;
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("report of a tip-relieved pair: load sharing beside the unmodified, by hand at the tip") {
  // The paper's pair (a pair file) with a linear pinion tip relief of C_a = 2 um from the roll
  // distance s_r = X_end - 0.3 (X_end - X_start - t0), inside the exit's two-pair zone, at
  // T1 = 100 N m. At the pinion's tip X_end two pairs are in contact: A there, with the gap C_a
  // (the relief's full amount at the tip), and B a base pitch back, unrelieved. The two-pair
  // compliance split with the gap: k_A (delta - e) + k_B delta = F, so
  //   delta = (F + k_A C_a) / (k_A + k_B),  share_A = k_A (delta - C_a) / F
  // (delta > C_a here), below the unrelieved share k_A / (k_A + k_B). k from the quadrature of
  // mesh_stiffness, not the report's table; at X_start neither pair is relieved, so there the
  // shares agree.
  const gearimpact::GearPair g = gearimpact::paper_gear_pair();
  const gearimpact::ContactSegment seg = gearimpact::contact_segment(g);
  const double t0 = gearimpact::base_pitch(g);
  const double rb1 = gearimpact::base_radius(g, gearimpact::Gear::one);
  const double c_a = 2e-6;
  const double s_r = seg.end_m - 0.3 * (seg.end_m - seg.start_m - t0);
  char start[64];
  std::snprintf(start, sizeof start, "%.17g mm", 2e3 * std::sqrt(rb1 * rb1 + s_r * s_r));
  Scratch scratch("report-relief");
  const std::string gears =
      "[gears]\nteeth1 = 20\nteeth2 = 80\nmodule = \"2 mm\"\npressure_angle = \"20 deg\"\n"
      "face_width = \"10 mm\"\nyoungs_modulus = \"206.8 GPa\"\npoisson_ratio = 0.3\n"
      "density = \"7800 kg/m^3\"\nbacklash = \"0.05 mm\"\n";
  const std::filesystem::path relieved = scratch.dir / "relieved.toml";
  const std::filesystem::path plain = scratch.dir / "plain.toml";
  write(relieved, gears + "\n[modifications]\ntip_relief1 = \"2 um\"\ntip_relief_start1 = \"" +
                      start + "\"\n");
  write(plain, gears);
  const CommandResult r =
      run_command(cli("report " + relieved.string() + " --torque '100 N*m' --samples 40 --out " +
                      (scratch.dir / "relieved").string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const CommandResult p = run_command(
      cli("report " + plain.string() + " --samples 40 --out " + (scratch.dir / "plain").string()));
  REQUIRE_MESSAGE(p.exit_code == 0, p.err);

  std::string header;
  const std::vector<std::vector<double>> rows =
      csv_numbers(read(scratch.dir / "relieved" / "load_sharing.csv"), header);
  REQUIRE(header == "x1_mm,path_fraction,pairs,share,share_modified");
  REQUIRE(rows.size() == 40);
  // The unmodified columns are the plain pair's report, to the byte.
  std::string plain_header;
  const std::vector<std::vector<double>> plain_rows =
      csv_numbers(read(scratch.dir / "plain" / "load_sharing.csv"), plain_header);
  CHECK(plain_header == "x1_mm,path_fraction,pairs,share");
  REQUIRE(plain_rows.size() == rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j < 4; ++j) CHECK(rows[i][j] == plain_rows[i][j]);
  }

  const double force = 100.0 / rb1;
  const std::vector<double>& tip = rows.back();
  CHECK(std::fabs(tip[0] * 1e-3 - seg.end_m) <= 1e-15);
  REQUIRE(tip[2] == 2.0);
  const double k_a = gearimpact::mesh_stiffness(g, seg.end_m).ke;
  const double k_b = gearimpact::mesh_stiffness(g, seg.end_m - t0).ke;
  const double delta = (force + k_a * c_a) / (k_a + k_b);
  REQUIRE(delta > c_a);
  const double by_hand = k_a * (delta - c_a) / force;
  MESSAGE("share at the tip: unrelieved " << tip[3] << ", relieved " << tip[4] << " (by hand "
                                          << by_hand << ")");
  // The table fits Ke to 1e-12 and the share is a difference of O(1) terms: 1e-10.
  CHECK(std::fabs(tip[4] - by_hand) <= 1e-10);
  CHECK(std::fabs(tip[3] - k_a / (k_a + k_b)) <= 1e-10);
  CHECK(tip[4] < tip[3] - 0.05);  // the relief unloads the tip
  // At the entry no pair is relieved: the same split.
  const std::vector<double>& entry = rows.front();
  CHECK(std::fabs(entry[4] - entry[3]) <= 1e-10);

  // REPORT.md names the relief and has the STE section; the plain pair's has neither.
  const std::string md = read(scratch.dir / "relieved" / "REPORT.md");
  CHECK(md.find("pinion tip relief 2 um at the tip, linear") != std::string::npos);
  CHECK(md.find("## Static transmission error") != std::string::npos);
  CHECK(md.find("T1 = 100 N m") != std::string::npos);
  for (const char* file : {"ste.csv", "ste_unmodified.csv", "ste.png", "ste_load_sharing.png"}) {
    CAPTURE(file);
    CHECK(std::filesystem::exists(scratch.dir / "relieved" / file));
  }
  const std::string plain_md = read(scratch.dir / "plain" / "REPORT.md");
  CHECK(plain_md.find("## Static transmission error") == std::string::npos);
  CHECK_FALSE(std::filesystem::exists(scratch.dir / "plain" / "ste.csv"));
  // --torque has nothing to load on a pair without modifications or faults.
  const CommandResult t =
      run_command(cli("report " + plain.string() + " --torque '100 N*m' --out " +
                      (scratch.dir / "refused").string()));
  CHECK(t.exit_code == 1);
  CHECK(t.err.find("--torque") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(scratch.dir / "refused"));
}
