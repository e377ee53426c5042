// End to end: the named stiffness models on the command line (`stiffness
// --model`, `mesh-stiffness`, `iso6336`) and the case-file keys they read.
// References: the series sum of the printed terms, the library's own
// functions for what the program only formats, the equations of
// docs/stiffness-models.md section 4, and the rectangle rule for the time mean.
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "paper_data.hpp"
#include "relative.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

using namespace gearimpact;
using namespace gearimpact::verify;

namespace {

constexpr double degree = 3.141592653589793238462643383279502884 / 180.0;

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) rows.push_back(split_csv_line(line));
  return rows;
}

// The number after "key": in a flat JSON object.
double json_value(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\":");
  REQUIRE(at != std::string::npos);
  return std::stod(json.substr(at + key.size() + 3));
}

// Case 1 with the ROSS peer run's bores (20 mm, 60 mm) on potential-energy,
// written by the library's case-file writer.
SimulationCase case_with_bores() {
  SimulationCase c = paper_case(1);
  c.gears.bore_diameter1_m = 20e-3;
  c.gears.bore_diameter2_m = 60e-3;
  c.model.stiffness.kind = StiffnessModelKind::potential_energy;
  return c;
}

std::string written_case(const SimulationCase& c, const std::string& name) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("gearimpact-models-" + std::to_string(::getpid()) + name);
  std::ofstream(path) << write_case_file(c);
  return path.string();
}

}  // namespace

TEST_CASE("case files carry the rack and model keys and read back to the same case") {
  SimulationCase c = case_with_bores();
  c.gears.dedendum_coefficient = 1.3;
  c.gears.profile_shift1 = 0.2;
  c.gears.profile_shift2 = -0.1;
  c.gears.rack_tip_radius_coefficient = 0.3;
  c.gears.youngs_modulus2_pa = 110e9;
  c.gears.poisson_ratio2 = 0.34;
  c.model.stiffness.kind = StiffnessModelKind::ross_compatible;
  c.model.stiffness.terms.set(Term::shear, false);
  const std::string text = write_case_file(c, CaseUnits::si);
  for (const char* key :
       {"dedendum_coefficient", "profile_shift1", "profile_shift2", "rack_tip_radius_coefficient",
        "bore_diameter1", "bore_diameter2", "youngs_modulus2", "poisson_ratio2", "stiffness_model",
        "shear_term", "foundation_term"}) {
    CHECK(text.find(key) != std::string::npos);
  }
  const SimulationCase back = parse_case(text, "models.toml");
  CHECK(back.gears == c.gears);
  CHECK(back.model.stiffness == c.model.stiffness);
  // Absent keys keep the defaults: no bores, gear 1's material, derived round.
  const SimulationCase paper = parse_case(write_case_file(paper_case(1)), "paper.toml");
  CHECK_FALSE(paper.gears.bore_diameter1_m.has_value());
  CHECK_FALSE(paper.gears.youngs_modulus2_pa.has_value());
  CHECK(paper.model.stiffness.kind == StiffnessModelKind::yang_lin_1987);
  // A bad value names the key as written.
  std::string bad = text;
  bad.replace(bad.find("stiffness_model = \"ross-compatible\""),
              std::string("stiffness_model = \"ross-compatible\"").size(),
              "stiffness_model = \"ross\"");
  try {
    parse_case(bad, "bad.toml");
    FAIL("accepted");
  } catch (const CaseFileError& e) {
    CHECK(e.field() == "model.stiffness_model");
  }
}

TEST_CASE("stiffness --model potential-energy: every term, Ke their series sum, a warning") {
  const std::string file = written_case(case_with_bores(), "pe.toml");
  const CommandResult r = run_command(cli("stiffness --case-file " + file + " --points 9"));
  REQUIRE(r.exit_code == 0);
  // The paper's pinion has theta_f = 0.1506 rad, outside the fit's 0.12.
  CHECK(r.err.find("warning") != std::string::npos);
  CHECK(r.err.find("extrapolation") != std::string::npos);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 10);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    double compliance = 0.0;
    for (std::size_t j = 2; j < rows[i].size(); ++j) {
      if (j != 7) compliance += 1.0 / std::stod(rows[i][j]);
    }
    // (29) over eleven printed values, each rounded to 17 digits.
    CHECK(relative_difference(1.0 / compliance, std::stod(rows[i][7])) < 1e-14);
  }
  // The same positions through --x-values give the same row.
  const CommandResult one = run_command(
      cli("stiffness --case-file " + file + " --model potential-energy --x-values " + rows[4][0]));
  REQUIRE(one.exit_code == 0);
  CHECK(csv_rows(one.out)[1] == rows[4]);
  // --model overrides the case file's: the paper's model has no ks, kf.
  const CommandResult paper =
      run_command(cli("stiffness --case-file " + file + " --model yang-lin-1987 --points 2"));
  REQUIRE(paper.exit_code == 0);
  CHECK(csv_rows(paper.out)[1][8] == "inf");
  CHECK(paper.err.empty());
  std::filesystem::remove(file);
}

TEST_CASE("mesh-stiffness: one period, and its summary's min, max and exact mean") {
  const std::string file = written_case(case_with_bores(), "tvms.toml");
  const CommandResult csv =
      run_command(cli("mesh-stiffness --case-file " + file + " --samples 4000"));
  REQUIRE(csv.exit_code == 0);
  const auto rows = csv_rows(csv.out);
  REQUIRE(rows.size() == 4001);
  // The healthy columns first, then the same pairs all healthy (here the same) and each pair's
  // teeth and Ke.
  REQUIRE(rows[0].size() >= 5u);
  CHECK(std::vector<std::string>(rows[0].begin(), rows[0].begin() + 5) ==
        std::vector<std::string>{"fraction", "theta1_rad", "pairs", "ke_n_m", "healthy_ke_n_m"});
  CHECK(rows[0][5] == "pair1_pinion_tooth");
  double sum = 0.0;
  double low = 1e300;
  double high = 0.0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double k = std::stod(rows[i][3]);
    sum += k;
    low = std::min(low, k);
    high = std::max(high, k);
  }
  const CommandResult json = run_command(cli("mesh-stiffness --case-file " + file + " --summary"));
  REQUIRE(json.exit_code == 0);
  const double mean = json_value(json.out, "mean_n_m");
  // The rectangle rule over 4000 samples of a function with two jumps of
  // about 40 % a period: its error is below a jump over the sample count.
  CHECK(relative_difference(sum / 4000.0, mean) < 1e-3);
  CHECK(json_value(json.out, "min_n_m") <= low);
  CHECK(json_value(json.out, "max_n_m") >= high);
  CHECK(json_value(json.out, "contact_ratio") == contact_ratio(case_with_bores().gears));
  CHECK(json.out.find("\"extrapolated\": true") != std::string::npos);
  CHECK(json.err.find("warning") != std::string::npos);
  std::filesystem::remove(file);
}

TEST_CASE("mesh-stiffness of faulted teeth: the summary over the true period against the CSV") {
  // The paper's pair with pinion tooth 3 cracked and pinion tooth 12 missing: a pinion
  // revolution of 20 mesh periods, --samples per mesh period.
  Scratch scratch("mesh-stiffness-faulted");
  const std::filesystem::path file = scratch.dir / "cracked.toml";
  std::ofstream(file) << "name = \"cracked\"\n[gears]\nteeth1 = 20\nteeth2 = 80\n"
                         "module = \"2 mm\"\npressure_angle = \"20 deg\"\n"
                         "face_width = \"10 mm\"\nyoungs_modulus = \"206.8 GPa\"\n"
                         "poisson_ratio = 0.3\ndensity = \"7800 kg/m^3\"\n"
                         "backlash = \"0.05 mm\"\n\n[[faults]]\ngear = \"pinion\"\ntooth = 3\n"
                         "kind = \"root-crack\"\ndepth = \"0.8 mm\"\nangle = \"45 deg\"\n\n"
                         "[[faults]]\ngear = \"pinion\"\ntooth = 12\nkind = \"missing\"\n";
  const int per_mesh = 500;
  const CommandResult csv = run_command(cli("mesh-stiffness --case-file " + file.string() +
                                            " --samples " + std::to_string(per_mesh)));
  REQUIRE(csv.exit_code == 0);
  const auto rows = csv_rows(csv.out);
  const std::size_t count = 20u * per_mesh;
  REQUIRE(rows.size() == count + 1);
  CHECK(rows[0][5] == "pair1_pinion_tooth");
  CHECK(rows[0][6] == "pair1_wheel_tooth");
  double sum = 0.0;
  double low = 1e300;
  double high = 0.0;
  double variation = 0.0;
  double smooth_step = 0.0;  // the largest change between neighbours with the same pairs
  int missing_rows = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double k = std::stod(rows[i][3]);
    CHECK(std::stod(rows[i][0]) == static_cast<double>(i - 1) / count);
    sum += k;
    low = std::min(low, k);
    high = std::max(high, k);
    // Wrapping round: the period's last row against its first.
    const auto& next = rows[i + 1 < rows.size() ? i + 1 : 1];
    const double change = std::fabs(std::stod(next[3]) - k);
    variation += change;
    if (next[2] == rows[i][2] && next[5] == rows[i][5]) smooth_step = std::max(smooth_step, change);
    for (std::size_t j = 5; j + 2 < rows[i].size(); j += 3) {
      if (rows[i][j] == "12") {
        ++missing_rows;
        CHECK(std::stod(rows[i][j + 2]) == 0.0);
      }
    }
  }
  CHECK(missing_rows > 0);
  const CommandResult json =
      run_command(cli("mesh-stiffness --case-file " + file.string() + " --summary"));
  REQUIRE(json.exit_code == 0);
  CHECK(json.out.find("\"period\": \"pinion-revolution\"") != std::string::npos);
  CHECK(json_value(json.out, "mesh_periods") == 20.0);
  const double mean = json_value(json.out, "mean_n_m");
  // The rectangle rule on a periodic function of bounded variation V errs by at most V / count
  // (each sample stands for 1 / count of the period, over which the function moves by its
  // variation there); V is read from the samples.
  MESSAGE("rectangle mean " << sum / count << " against " << mean << ", bound "
                            << variation / count);
  CHECK(std::fabs(sum / count - mean) <= variation / count);
  // The extremes bound every sample, and some sample lies within one smooth step of each (the
  // extreme sits on a smooth piece or at its one-sided end).
  const double min = json_value(json.out, "min_n_m");
  const double max = json_value(json.out, "max_n_m");
  CHECK(min <= low);
  CHECK(max >= high);
  CHECK(low - min <= smooth_step);
  CHECK(max - high <= smooth_step);
  // Where the missing tooth's pair is the only one, the mesh has no stiffness.
  CHECK(min == 0.0);
  CHECK(json_value(json.out, "mean_n_m") < json_value(json.out, "healthy_mean_n_m"));

  // --figure: the CSV and summary beside the figure, which marks the faulted teeth.
  const std::filesystem::path out = scratch.dir / "figure";
  const CommandResult figure = run_command(cli("mesh-stiffness --case-file " + file.string() +
                                               " --samples 50 --figure " + out.string()));
  REQUIRE(figure.exit_code == 0);
  CHECK(std::filesystem::exists(out / "mesh_stiffness.png"));
  CHECK(std::filesystem::exists(out / "mesh_stiffness.csv"));
  std::ifstream script(out / "mesh_stiffness.gp");
  const std::string gp((std::istreambuf_iterator<char>(script)), std::istreambuf_iterator<char>());
  CHECK(gp.find("pinion 3 root-crack") != std::string::npos);
  CHECK(gp.find("pinion 12 missing") != std::string::npos);

  // More samples than the true period's bound (1e7 over 20 mesh periods): refused under the flag
  // before any work, with the bound per mesh period.
  const CommandResult many = run_command(
      cli("mesh-stiffness --case-file " + file.string() + " --samples 1000000 --summary"));
  CHECK(many.exit_code != 0);
  CHECK(many.err.find("--samples") != std::string::npos);
  CHECK(many.err.find("at most 500000 per mesh period") != std::string::npos);
}

TEST_CASE("iso6336: method B for the paper's pair and for a helical variant") {
  const CommandResult r = run_command(cli("iso6336"));
  REQUIRE(r.exit_code == 0);
  // docs/stiffness-models.md: c' b = 1.34e8 N/m for the paper's pair, to its digits.
  CHECK(std::fabs(json_value(r.out, "c_prime_b_n_m") - 1.34e8) <= 0.005e8);
  CHECK(json_value(r.out, "zn1") == 20.0);
  // c_gamma_alpha = c' (0.75 eps_alpha + 0.25), to rounding.
  CHECK(relative_difference(json_value(r.out, "c_gamma_alpha_n_mm_um"),
                            json_value(r.out, "c_prime_n_mm_um") *
                                (0.75 * json_value(r.out, "eps_alpha") + 0.25)) < 1e-14);
  const CommandResult helical = run_command(cli("iso6336 --helix-angle 15"));
  REQUIRE(helical.exit_code == 0);
  // zn = z / (cos^2 beta_b cos beta), tan beta_b = tan beta cos alpha_t.
  const double beta = 15.0 * degree;
  const double alpha_t = std::atan(std::tan(20.0 * degree) / std::cos(beta));
  const double beta_b = std::atan(std::tan(beta) * std::cos(alpha_t));
  CHECK(relative_difference(json_value(helical.out, "zn1"),
                            20.0 / (std::cos(beta_b) * std::cos(beta_b) * std::cos(beta))) < 1e-14);
}

TEST_CASE("bad flag values are refused naming the flag") {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"stiffness --model ross", "--model"},
      {"stiffness --x-values 0.5", "--x-values"},
      {"stiffness --x-values 0.002,abc", "--x-values"},
      {"stiffness --x-values 0.002 --points 3", "--x-values"},
      {"mesh-stiffness --samples 1", "--samples"},
      {"mesh-stiffness --model nope", "--model"},
      {"iso6336 --helix-angle 50", "--helix-angle"},
      {"stiffness --model potential-energy", "bore_diameter1"},
  };
  for (const auto& [arguments, flag] : cases) {
    CAPTURE(arguments);
    const CommandResult r = run_command(cli(arguments));
    CHECK(r.exit_code != 0);
    CHECK(r.err.find(flag) != std::string::npos);
    CHECK(r.out.empty());
  }
}

TEST_CASE("simulate warns in its JSON and on stderr when the foundation fit is extrapolated") {
  // The paper's pinion: theta_f = 0.1506 rad, outside the fit's [0.01, 0.12]
  // (docs/stiffness-models.md, section 3, Which stiffness model), with the bores of ROSS's run.
  const std::string model =
      " --set model.stiffness_model=potential-energy --set \"gears.bore_diameter1=20 mm\""
      " --set \"gears.bore_diameter2=60 mm\"";
  const verify::CommandResult pe =
      verify::run_command(verify::cli("simulate --case 1 --t-end 2e-4" + model));
  REQUIRE(pe.exit_code == 0);
  CHECK(pe.out.find("\"foundation_extrapolated\": true") != std::string::npos);
  CHECK(pe.out.find("\"foundation_energy_max_J\"") != std::string::npos);
  CHECK(pe.err.find("warning") != std::string::npos);
  // The paper's model has no foundation term: its summary says nothing of it.
  const verify::CommandResult paper =
      verify::run_command(verify::cli("simulate --case 1 --t-end 2e-4"));
  REQUIRE(paper.exit_code == 0);
  CHECK(paper.out.find("foundation") == std::string::npos);
}
