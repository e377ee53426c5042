// End to end: `gearimpact fe-check` through gmsh and CalculiX. The pipeline
// against a cantilever's closed-form deflection, then one coarse 2-D tooth:
// its meshes converge, and its compliance against the potential-energy model
// with the fillet foundation. Skipped, saying so, where gmsh or ccx is absent
// (scripts/setup.sh installs both).
#include <doctest/doctest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "relative.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

using namespace gearimpact::verify;

namespace {

bool on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (::access((folder + "/" + name).c_str(), X_OK) == 0) return true;
  }
  return false;
}

bool programs_present() {
  if (on_path("gmsh") && on_path("ccx")) return true;
  MESSAGE(
      "skipped: gmsh or ccx (CalculiX) is not on PATH; scripts/setup.sh installs the Debian "
      "packages gmsh and calculix-ccx");
  return false;
}

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

double json_value(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\":");
  REQUIRE(at != std::string::npos);
  return std::stod(json.substr(at + key.size() + 3));
}

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) fields.push_back(cell);
    rows.push_back(fields);
  }
  return rows;
}

// The paper's pair (20/80, m 2 mm, b 10 mm) with bores 20 / 60 mm.
const std::filesystem::path kPaperPairWithBores =
    std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples" / "paper_pair_bores.toml";

// One coarse run of the wheel's tooth at three positions (SAP, middle, EAP) on three meshes
// (tooth elements 1, 0.5, 0.25 mm), shared by the cases below. The wheel: its theta_f lies inside
// the foundation fit's range (the pinion's does not), where the model claims its accuracy.
struct ToothRun {
  CommandResult result;
  std::string csv;
  std::string summary;
};
const ToothRun& tooth_run() {
  static const ToothRun run = [] {
    Scratch scratch("fe-tooth");
    const std::filesystem::path& case_file = kPaperPairWithBores;
    ToothRun r;
    r.result =
        run_command(cli("fe-check " + case_file.string() + " --gear 2 --positions 3 " +
                        "--element-size 0.5 --no-plots --out " + (scratch.dir / "out").string()));
    r.csv = read(scratch.dir / "out" / "fe_check.csv");
    r.summary = read(scratch.dir / "out" / "summary.json");
    return r;
  }();
  return run;
}

}  // namespace

TEST_CASE("the FE pipeline gives a cantilever's Timoshenko deflection") {
  if (!programs_present()) return;
  Scratch scratch("fe-cantilever");
  const CommandResult r =
      run_command(cli("fe-check --cantilever --out " + (scratch.dir / "out").string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const double length = json_value(r.out, "length_m");
  const double depth = json_value(r.out, "depth_m");
  const double width = json_value(r.out, "width_m");
  const double e = json_value(r.out, "youngs_modulus_pa");
  const double x = json_value(r.out, "measured_x_m");
  CHECK(json_value(r.out, "poisson_ratio") == 0.0);
  // Timoshenko beam, unit tip load: v(x) = x^2 (3L - x) / (6 E I) + x / (k G A) with k = 5/6 (the
  // stiffness models' 1.2 = 1 / k) and G = E / 2 at nu = 0. With nu = 0 the clamp restrains no
  // Poisson contraction, so plane stress has no end effect beyond the shear's warping, and the
  // measured point lies one depth from the load, past its local field.
  const double i = width * depth * depth * depth / 12.0;
  const double area = width * depth;
  const double expected =
      x * x * (3.0 * length - x) / (6.0 * e * i) + x / (5.0 / 6.0 * 0.5 * e * area);
  // 0.2 %: the shear term is 0.6 % of the deflection, so a pipeline that lost it, or the
  // thickness, the units or a constraint, fails; the mesh's own error is about 1e-5.
  CHECK(relative_difference(json_value(r.out, "deflection_m_per_n"), expected) < 2e-3);
}

// The edge-cracked strip in pure bending (Brown and Srawley 1966, ASTM STP 410, as quoted in
// Tada, Paris and Irwin, The Stress Analysis of Cracks Handbook): K = sigma sqrt(pi a) F(a / W),
// sigma = 6 M / (B W^2), F = 1.122 - 1.40 s + 7.33 s^2 - 13.08 s^3 + 14.0 s^4 (0.2 % for
// s <= 0.6). With G = K^2 / E (plane stress) = M^2 / (2 B) dC/da, the crack adds to the
// rotation across it Delta theta / M = 72 pi / (E B W^2) Int_0^s t F(t)^2 dt.
double edge_crack_rotation_per_moment(double e, double b, double w, double depth) {
  const auto f = [](double t) {
    return 1.122 - 1.40 * t + 7.33 * t * t - 13.08 * t * t * t + 14.0 * t * t * t * t;
  };
  // Simpson's rule on a polynomial of degree 9: 2000 intervals are exact to rounding.
  const int n = 2000;
  const double s = depth / w;
  const double h = s / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double t = i * h;
    const double weight = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += weight * t * f(t) * f(t);
  }
  return 72.0 * 3.14159265358979323846 / (e * b * w * w) * sum * h / 3.0;
}

// A slit from the tension edge of the same cantilever, 40 mm from the clamp: the deflection it
// adds at the measured point (x = 90 mm) is the crack's rotation under M = 60 mm x 1 N carried
// 50 mm on. Tada's own closed form for F (0.923 + 0.199 (1 - sin)^4 ...) lies 1.6 % and 3.5 %
// below this polynomial's integral at a / W = 0.2 and 0.4; the FE meets the polynomial.
TEST_CASE("a slit in the cantilever adds the edge-cracked strip's rotation (fracture mechanics)") {
  if (!programs_present()) return;
  Scratch scratch("fe-edge-crack");
  const CommandResult healthy =
      run_command(cli("fe-check --cantilever --out " + (scratch.dir / "healthy").string()));
  REQUIRE_MESSAGE(healthy.exit_code == 0, healthy.err);
  for (const double crack : {0.002, 0.004}) {
    const std::string name = crack < 0.003 ? "crack2" : "crack4";
    const CommandResult r =
        run_command(cli("fe-check --cantilever --edge-crack " + std::to_string(crack) + " --out " +
                        (scratch.dir / name).string()));
    REQUIRE_MESSAGE(r.exit_code == 0, r.err);
    CHECK(json_value(r.out, "edge_crack_m") == doctest::Approx(crack).epsilon(1e-12));
    const double length = json_value(r.out, "length_m");
    const double x_crack = json_value(r.out, "crack_x_m");
    const double x = json_value(r.out, "measured_x_m");
    const double added =
        json_value(r.out, "deflection_m_per_n") - json_value(healthy.out, "deflection_m_per_n");
    const double expected = edge_crack_rotation_per_moment(json_value(r.out, "youngs_modulus_pa"),
                                                           json_value(r.out, "width_m"),
                                                           json_value(r.out, "depth_m"), crack) *
                            (length - x_crack) * (x - x_crack);
    MESSAGE("a = " << crack << " m: the slit adds " << added << " m/N, the strip's rotation "
                   << expected << " m/N");
    // 1 %: the polynomial's 0.2 % on F (0.4 % on F^2), the slit tip's discretisation (measured
    // 0.2 % at these meshes and at meshes of half the size) and the shear at the crack, left
    // out of the pure-bending K; a slit not opened adds nothing, one opened by its length
    // only in part adds less.
    CHECK(relative_difference(added, expected) < 0.01);
  }
}

TEST_CASE("a coarse tooth's FE compliance converges within 1 % between the two finest meshes") {
  if (!programs_present()) return;
  const ToothRun& run = tooth_run();
  REQUIRE_MESSAGE(run.result.exit_code == 0, run.result.err);
  CHECK(run.summary.find("\"converged\": true") != std::string::npos);
  const auto rows = csv_rows(run.csv);
  REQUIRE(rows.size() == 4);
  // Columns: s, r, y_t, tau, the three meshes, ...
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double mesh2 = std::stod(rows[k][5]);
    const double mesh3 = std::stod(rows[k][6]);
    CHECK(relative_difference(mesh2, mesh3) < 0.01);
  }
}

// The paper's wheel with a 1 mm root crack at 45 deg (a slit from the potential-energy model's
// crack start), at three positions on two coarse meshes (tooth elements 1 and 0.5 mm; the
// third mesh would treble the time).
const ToothRun& cracked_run() {
  static const ToothRun run = [] {
    Scratch scratch("fe-crack");
    ToothRun r;
    r.result =
        run_command(cli("fe-check " + kPaperPairWithBores.string() + " --gear 2 --positions 3 " +
                        "--element-size 0.5 --refinements 2 --crack-depths 1e-3 --no-plots --out " +
                        (scratch.dir / "out").string()));
    r.csv = read(scratch.dir / "out" / "fe_crack.csv");
    r.summary = read(scratch.dir / "out" / "summary.json");
    return r;
  }();
  return run;
}

// The band: papers that validate the potential-energy model with the fillet foundation against
// finite elements report agreement within about 5 to 10 % (docs/verification.md says which
// figures were and were not checked); 10 % is taken. Measured on this wheel: 3.8 to 7.3 % (the
// finest default mesh), the FE stiffer. The pinions, whose foundation fit is extrapolated, lie
// outside the band (10 to 15 %): reported in docs/verification.md, not asserted here.
TEST_CASE("the wheel tooth's FE compliance agrees with the potential-energy model within 10 %") {
  if (!programs_present()) return;
  const ToothRun& run = tooth_run();
  REQUIRE_MESSAGE(run.result.exit_code == 0, run.result.err);
  CHECK(run.summary.find("\"foundation_extrapolated\": false") != std::string::npos);
  const auto rows = csv_rows(run.csv);
  REQUIRE(rows.size() == 4);
  std::size_t fe_vs_pe = 0;
  for (std::size_t c = 0; c < rows[0].size(); ++c) {
    if (rows[0][c] == "fe_vs_pe") fe_vs_pe = c;
  }
  REQUIRE(fe_vs_pe > 0);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double difference = std::stod(rows[k][fe_vs_pe]);
    MESSAGE("s = " << rows[k][0] << " m: FE vs potential energy " << 100.0 * difference << " %");
    CHECK(std::fabs(difference) < 0.10);
  }
}

// The slit's compliance converges although its tip is singular: the compliance is an energy, and
// the singular field's energy is finite. Measured on this coarse run: at most 0.35 % between its
// two meshes (0.28 % between the default's two finest).
TEST_CASE("a cracked tooth's FE compliance converges and exceeds the healthy tooth's") {
  if (!programs_present()) return;
  const ToothRun& run = cracked_run();
  REQUIRE_MESSAGE(run.result.exit_code == 0, run.result.err);
  CHECK(run.summary.find("\"crack_converged\": true") != std::string::npos);
  const auto rows = csv_rows(run.csv);
  REQUIRE(rows.size() == 4);
  std::size_t column[4] = {0, 0, 0, 0};
  const char* names[4] = {"last_mesh_change", "fe_change", "pe_change", "fe_vs_pe"};
  for (std::size_t c = 0; c < rows[0].size(); ++c) {
    for (std::size_t n = 0; n < 4; ++n) {
      if (rows[0][c] == names[n]) column[n] = c;
    }
  }
  for (const std::size_t c : column) REQUIRE(c > 0);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double fe_change = std::stod(rows[k][column[1]]);
    const double pe_change = std::stod(rows[k][column[2]]);
    MESSAGE("s = " << rows[k][4] << " m: the crack adds " << 100.0 * fe_change << " % by FE, "
                   << 100.0 * pe_change << " % by the potential-energy model; FE "
                   << "vs the model " << 100.0 * std::stod(rows[k][column[3]]) << " %");
    CHECK(std::stod(rows[k][column[0]]) < 0.01);
    // The slit weakens the tooth at every position: a slit left closed (its faces tied) would
    // add nothing.
    CHECK(fe_change > 0.01);
    // Where the crack's reading stands against the FE, reported (docs/verification.md): the
    // model's increase is a third to a half of the FE's at 1 mm; asserted only that both rise.
    CHECK(pe_change > 0.0);
  }
}

// Refused before any mesh or folder, each naming the flag (no outside program runs).
TEST_CASE(
    "fe-check refuses a crack past the centre line, a spall or chip off the layers or the path, "
    "and mixed modes") {
  Scratch scratch("fe-refusals");
  const std::string out = " --out " + (scratch.dir / "out").string();
  const std::string wheel = "fe-check " + kPaperPairWithBores.string() + " --gear 2";
  const std::filesystem::path rig =
      std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples" / "rig_17_38.toml";
  // q sin nu = 2.83 mm against the wheel's h_c = 2.23 mm.
  CommandResult r = run_command(cli(wheel + " --crack-depths 4e-3" + out));
  CHECK(r.exit_code != 0);
  CHECK(r.err.find("q sin nu < h_c") != std::string::npos);
  // 5 mm of a 15 mm face falls between the quarters' layer planes.
  r = run_command(cli("fe-check " + rig.string() + " --spall-width 5e-3" + out));
  CHECK(r.exit_code != 0);
  CHECK(r.err.find("--spall-width") != std::string::npos);
  r = run_command(cli(wheel + " --spall-width 5e-3 --crack-depths 1e-3" + out));
  CHECK(r.err.find("--spall-width") != std::string::npos);
  r = run_command(cli(wheel + " --edge-crack 1e-3" + out));
  CHECK(r.err.find("--edge-crack") != std::string::npos);
  r = run_command(cli("fe-check --cantilever --crack-depths 1e-3" + out));
  CHECK(r.err.find("--crack-depths") != std::string::npos);
  // A width given twice; a position off the active path (the rig's ends at 1.85 and 15.98 mm,
  // less 0.5 mm); positions without a solid run; a chip without its radius, or mixed with a
  // spall; a chip's radius off the pinion's active profile.
  r = run_command(cli("fe-check " + rig.string() + " --spall-width 7.5e-3,7.5e-3" + out));
  CHECK(r.err.find("--spall-width") != std::string::npos);
  r = run_command(cli("fe-check " + rig.string() + " --spall-width 7.5e-3 --solid-at 2e-3" + out));
  CHECK(r.exit_code != 0);
  CHECK(r.err.find("--solid-at = 0.002") != std::string::npos);
  r = run_command(cli("fe-check " + rig.string() + " --solid-at 8e-3" + out));
  CHECK(r.err.find("--solid-at") != std::string::npos);
  r = run_command(cli("fe-check " + rig.string() + " --chip-width 7.5e-3" + out));
  CHECK(r.err.find("--chip-radius") != std::string::npos);
  r = run_command(cli("fe-check " + rig.string() +
                      " --chip-width 7.5e-3 --chip-radius 27e-3 --spall-width "
                      "7.5e-3" +
                      out));
  CHECK(r.err.find("--chip-width") != std::string::npos);
  r = run_command(
      cli("fe-check " + rig.string() + " --chip-width 7.5e-3 --chip-radius 29.5e-3" + out));
  CHECK(r.exit_code != 0);
  CHECK(r.err.find("--chip-radius = 0.0295") != std::string::npos);
  CHECK(!std::filesystem::exists(scratch.dir / "out"));
}
