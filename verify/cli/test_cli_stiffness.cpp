// End to end: the `stiffness` and `energy-ratios` CSV interfaces of the
// program, their columns, precision and errors.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/sweep_files.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/helical_faults.hpp"
#include "gearimpact/stiffness/helical_ste.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "paper_data.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

using namespace gearimpact;
using namespace gearimpact::verify;

namespace {

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) rows.push_back(split_csv_line(line));
  return rows;
}

}  // namespace

TEST_CASE("stiffness: CSV columns in SI, X_start to X_end inclusive, round-trip precision") {
  const CommandResult r = run_command(cli("stiffness --points 5 --method boost-gk"));
  REQUIRE(r.exit_code == 0);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 6);
  CHECK(rows[0] == std::vector<std::string>{"x_m", "phi1_rad", "kb1", "ka1", "kb2", "ka2", "kh",
                                            "ke", "ks1", "ks2", "kf1", "kf2"});
  const GearPair pair = paper_gear_pair();
  const ContactSegment segment = contact_segment(pair);
  // 17 significant digits round-trip a double exactly.
  CHECK(std::stod(rows[1][0]) == segment.start_m);
  CHECK(std::stod(rows[5][0]) == segment.end_m);
  StiffnessModel model;
  model.rule = QuadratureRule::boost_gauss_kronrod;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double x = std::stod(rows[i][0]);
    const MeshStiffness k = mesh_stiffness(pair, x, model);
    CHECK(std::stod(rows[i][1]) == contact_angle(pair, Gear::one, x));
    CHECK(std::stod(rows[i][2]) == k.stiffness(Term::bending, Gear::one));
    CHECK(std::stod(rows[i][7]) == k.ke);
  }
}

TEST_CASE("energy-ratios: CSV of Fig. 8 over one cycle") {
  const CommandResult r = run_command(cli("energy-ratios --points 7"));
  REQUIRE(r.exit_code == 0);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 8);
  CHECK(rows[0] == std::vector<std::string>{"angle_deg", "pairs", "hertz_over_bending_one_pair",
                                            "axial_over_bending_one_pair",
                                            "hertz_over_bending_system",
                                            "axial_over_bending_system"});
  // angle_deg is phi1 of (12) in degrees at X_start.
  const GearPair pair = paper_gear_pair();
  CHECK(std::abs(std::stod(rows[1][0]) -
                 contact_angle(pair, Gear::one, contact_segment(pair).start_m) * 180.0 /
                     std::numbers::pi) < 1e-12);
}

TEST_CASE("bad arguments name the option and exit non-zero") {
  const CommandResult method = run_command(cli("stiffness --method simpson"));
  CHECK(method.exit_code != 0);
  CHECK(method.err.find("--method") != std::string::npos);
  const CommandResult points = run_command(cli("energy-ratios --points 1"));
  CHECK(points.exit_code != 0);
  CHECK(points.err.find("--points") != std::string::npos);
  CHECK(points.out.empty());
}

TEST_CASE("stiffness --case-file: a researcher's own pair, with the file's stiffness model") {
  std::ifstream in(std::string(GEARIMPACT_PAPER_DATA_DIR) + "/case1.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string toml = text.str();
  const std::size_t at = toml.find("teeth1 = 20");
  REQUIRE(at != std::string::npos);
  toml.replace(at, 11, "teeth1 = 25");
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "gearimpact_test_own_pair.toml";
  std::ofstream(file) << toml;
  const CommandResult r = run_command(cli("stiffness --points 4 --case-file " + file.string()));
  REQUIRE(r.exit_code == 0);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 5);
  GearPair pair = paper_gear_pair();
  pair.teeth1 = 25;
  const ContactSegment segment = contact_segment(pair);
  // 17 significant digits round-trip: the program's numbers are the library's.
  CHECK(std::stod(rows[1][0]) == segment.start_m);
  CHECK(std::stod(rows[4][0]) == segment.end_m);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    CHECK(std::stod(rows[i][7]) == mesh_stiffness(pair, std::stod(rows[i][0])).ke);
  }
  const CommandResult bad = run_command(cli("stiffness --case-file /nonexistent.toml"));
  CHECK(bad.exit_code != 0);
  CHECK(bad.err.find("/nonexistent.toml") != std::string::npos);
  std::filesystem::remove(file);
}

TEST_CASE("mesh-stiffness on a helical pair: both routes over a mesh period; simulate runs it") {
  const std::filesystem::path file =
      std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples" / "helical_h501.toml";
  const CommandResult r =
      run_command(cli("mesh-stiffness --case-file " + file.string() + " --samples 20"));
  REQUIRE(r.exit_code == 0);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 21);
  CHECK(rows[0] == std::vector<std::string>{"fraction", "theta1_rad", "k_slices_n_m", "k_face_n_m",
                                            "contact_line_length_m",
                                            "contact_line_length_slices_m"});
  // The example's pair, built here: the program prints the library's slice
  // model to the bit (17 significant digits).
  GearPair pair;
  pair.teeth1 = 20;
  pair.teeth2 = 30;
  pair.module_m = 3.5e-3;
  pair.pressure_angle_rad = 20.0 * std::numbers::pi / 180.0;
  pair.helix_angle_rad = 15.0 * std::numbers::pi / 180.0;
  pair.face_width_m = 23e-3;
  pair.youngs_modulus_pa = 206e9;
  pair.poisson_ratio = 0.3;
  pair.profile_shift1 = 0.1809;
  pair.profile_shift2 = 0.0891;
  const FaceStiffness face(pair, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(pair, face);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double theta = std::stod(rows[i][1]);
    CHECK(std::stod(rows[i][2]) == mesh.stiffness_slices(Region::n1, theta, 32));
    CHECK(std::stod(rows[i][3]) == mesh.stiffness_face(Region::n1, theta));
  }
  const CommandResult summary =
      run_command(cli("mesh-stiffness --summary --case-file " + file.string()));
  REQUIRE(summary.exit_code == 0);
  CHECK(summary.out.find("\"iso_c_gamma_alpha_b_n_m\"") != std::string::npos);
  // simulate runs it in the torsional model (the run file beside the pair
  // file), and refuses by key what it cannot take: here a smoothed friction
  // sign (the face sum of a helical pair's friction is continuous already);
  // --figure is refused, naming the flag.
  const CommandResult runs = run_command(
      cli("simulate --case-file " + (file.parent_path() / "helical_h501_run.toml").string() +
          " --set 'integrator.end_time=1 ms'"));
  CHECK(runs.exit_code == 0);
  CHECK(runs.out.find("\"ledger_residual_max_J\"") != std::string::npos);
  // check-case derives the transverse section the run uses: r1 = z1 m_n / (2 cos beta), and
  // the overlap ratio b sin(beta) / (pi m_n) (equal to b tan(beta_b) / p_bt); both printed
  // with 17 digits, so 1e-14 is the rounding of the two routes.
  const CommandResult checked =
      run_command(cli("check-case " + (file.parent_path() / "helical_h501_run.toml").string()));
  REQUIRE(checked.exit_code == 0);
  const auto printed = [&](const std::string& label) {
    const std::size_t at = checked.out.find(label);
    REQUIRE(at != std::string::npos);
    return std::stod(checked.out.substr(at + label.size()));
  };
  const double beta = pair.helix_angle_rad;
  const double r1 = 20 * 3.5e-3 / (2.0 * std::cos(beta));
  CHECK(std::abs(printed("pitch radii r1, r2 = ") - r1) <= 1e-14 * r1);
  const double eps_beta = 23e-3 * std::sin(beta) / (std::numbers::pi * 3.5e-3);
  CHECK(std::abs(printed("eps_beta = ") - eps_beta) <= 1e-14 * eps_beta);
  CHECK(checked.out.find("root crack") == std::string::npos);
  const CommandResult run =
      run_command(cli("simulate --case 1 --set 'gears.helix_angle=15 deg' --set "
                      "'model.friction_smoothing_speed=1e-3 m/s'"));
  CHECK(run.exit_code != 0);
  CHECK(run.err.find("model.friction_smoothing_speed") != std::string::npos);
  // On elastic bearings (the planar example) the series adds the axial forces and tilting
  // moments, the summary their largest values, and the run warns that they act on nothing.
  const Scratch scratch("helical-planar");
  const std::filesystem::path series = scratch.dir / "planar.csv";
  const CommandResult planar = run_command(
      cli("simulate --case-file " + (file.parent_path() / "helical_h501_planar.toml").string() +
          " --set 'integrator.end_time=0.2 ms' --out " + series.string()));
  REQUIRE(planar.exit_code == 0);
  CHECK(planar.out.find("\"axial_force_max_N\"") != std::string::npos);
  CHECK(planar.err.find("axial or tilting freedom") != std::string::npos);
  std::ifstream planar_csv(series);
  std::string header;
  std::getline(planar_csv, header);
  CHECK(header.find("coast_penetration_m,axial_force1_N,axial_force2_N,tilting_moment1_N_m,"
                    "tilting_moment2_N_m") != std::string::npos);
  // The steady sweeps take it on elastic bearings (a sweep of it takes seconds: test_helical
  // checks the planar steady state); what a steady state refuses they refuse before any work,
  // by the key: here friction (refused for every pair), and nothing written.
  const std::filesystem::path swept_dir = scratch.dir / "sweep";
  const CommandResult swept =
      run_command(cli("sweep " + (file.parent_path() / "helical_h501_planar.toml").string() +
                      " --vary initial.w1 --from '900 rpm' --to '1000 rpm' --points 2 --set "
                      "model.friction_coefficient=0.04 --out " +
                      swept_dir.string()));
  CHECK(swept.exit_code != 0);
  CHECK(swept.err.find("error: model.friction_coefficient = 0.04") != std::string::npos);
  CHECK(!std::filesystem::exists(swept_dir));
  const CommandResult figure =
      run_command(cli("mesh-stiffness --case-file " + file.string() + " --figure does-not-matter"));
  CHECK(figure.exit_code != 0);
  CHECK(figure.err.find("--figure") != std::string::npos);
}

TEST_CASE(
    "ste and report on a helical pair: the library's slice STE, its files; lead keys on spur") {
  const Scratch scratch("helical-ste");
  const std::filesystem::path example =
      std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples" / "helical_h501.toml";
  std::ifstream in(example);
  std::stringstream text;
  text << in.rdbuf();
  std::string toml = text.str();
  const std::string model = "[model]";
  toml.replace(toml.find(model), model.size(),
               "[modifications]\ncrowning1 = \"4 um\"\nmisalignment_y = \"0.01 deg\"\n\n[model]");
  const std::filesystem::path file = scratch.dir / "crowned.toml";
  std::ofstream(file) << toml;
  const CommandResult r = run_command(cli("ste " + file.string() +
                                          " --torque '150 N*m' --points 7 "
                                          "--no-plots --out " +
                                          (scratch.dir / "ste").string()));
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("\"route\": \"slices\"") != std::string::npos);
  std::ifstream csv_file(scratch.dir / "ste" / "ste.csv");
  std::stringstream csv;
  csv << csv_file.rdbuf();
  const auto rows = csv_rows(csv.str());
  REQUIRE(rows.size() == 8);
  CHECK(rows[0][2] == "ste_m");
  // The example's pair and modifications, built here: the program prints the library's STE.
  GearPair pair;
  pair.teeth1 = 20;
  pair.teeth2 = 30;
  pair.module_m = 3.5e-3;
  pair.pressure_angle_rad = 20.0 * std::numbers::pi / 180.0;
  pair.helix_angle_rad = 15.0 * std::numbers::pi / 180.0;
  pair.face_width_m = 23e-3;
  pair.youngs_modulus_pa = 206e9;
  pair.poisson_ratio = 0.3;
  pair.profile_shift1 = 0.1809;
  pair.profile_shift2 = 0.0891;
  pair.backlash_m = 0.05e-3;
  Modifications m;
  m.gear1.lead.crowning_m = 4e-6;
  m.misalignment.gamma_y_rad = 0.01 * std::numbers::pi / 180.0;
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 7;
  const HelicalStaticTransmissionError ste =
      helical_static_transmission_error(pair, m, 150.0, StiffnessModel{}, options);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    CHECK(std::stod(rows[i][2]) == ste.points[i - 1].ste_m);
    CHECK(std::stod(rows[i][8]) == ste.points[i - 1].face_load_factor);
  }
  // report: the helical geometry table, the contact lines, the stiffness and the STE files.
  const std::filesystem::path report = scratch.dir / "report";
  const CommandResult rep = run_command(
      cli("report " + file.string() + " --samples 8 --torque '150 N*m' --out " + report.string()));
  REQUIRE(rep.exit_code == 0);
  for (const char* name : {"REPORT.md", "geometry.csv", "contact_lines.png",
                           "helical_mesh_stiffness.png", "ste_face_load.csv", "ste_summary.json"}) {
    CHECK(std::filesystem::exists(report / name));
  }
  std::ifstream geometry_file(report / "geometry.csv");
  std::stringstream geometry;
  geometry << geometry_file.rdbuf();
  const std::string eps_beta =
      "overlap_ratio eps_beta,pair," + format_number(helical_geometry(pair).overlap_ratio) + ",1";
  CHECK(geometry.str().find(eps_beta) != std::string::npos);
  // A lead key on a spur pair is refused by name before any work.
  std::string spur = toml;
  const std::string helix = "helix_angle = \"15 deg\"";
  spur.replace(spur.find(helix), helix.size(), "helix_angle = \"0 deg\"");
  const std::filesystem::path spur_file = scratch.dir / "spur.toml";
  std::ofstream(spur_file) << spur;
  const CommandResult refused =
      run_command(cli("ste " + spur_file.string() + " --torque '150 N*m' --out " +
                      (scratch.dir / "refused").string()));
  CHECK(refused.exit_code != 0);
  CHECK(refused.err.find("modifications.crowning1") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(scratch.dir / "refused"));
}

TEST_CASE("sweep of the helical example: the program's steady summary is the library's") {
  // `gearimpact sweep` on examples/helical_h501_run.toml, three speeds up, against
  // run_steady_sweep on the same file read by the library: the program is glue, so every
  // figure of sweep.csv (printed to round-trip) is the library's to the bit.
  const Scratch scratch("helical-sweep");
  const std::filesystem::path example = std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." /
                                        "examples" / "helical_h501_run.toml";
  const std::filesystem::path out = scratch.dir / "sweep";
  const CommandResult r =
      run_command(cli("sweep " + example.string() +
                      " --vary initial.w1 --from '100 rad/s' --to '300 rad/s' "
                      "--points 3 --direction up --threads 1 --no-plots --out " +
                      out.string()));
  REQUIRE(r.exit_code == 0);
  std::ifstream csv_file(out / "sweep.csv");
  std::stringstream csv;
  csv << csv_file.rdbuf();
  const auto rows = csv_rows(csv.str());
  REQUIRE(rows.size() == 4);
  const auto column = [&](const std::string& name) {
    for (std::size_t j = 0; j < rows[0].size(); ++j) {
      if (rows[0][j] == name) return j;
    }
    FAIL("no column " << name);
    return std::size_t{0};
  };
  SteadySweepSpec spec;
  spec.base = read_case_file(example);
  spec.vary = "initial.w1";
  spec.from_si = 100.0;
  spec.to_si = 300.0;
  spec.points = 3;
  spec.directions = {SweepDirection::up};
  spec.threads = 1;
  const SteadySweep sweep = run_steady_sweep(spec);
  REQUIRE(sweep.rows.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    CAPTURE(i);
    const std::vector<std::string>& row = rows[i + 1];
    const SteadyPoint& p = sweep.rows[i].point;
    REQUIRE(p.converged);
    CHECK(row[column("converged")] == "true");
    CHECK(std::stod(row[column("value_si")]) == sweep.rows[i].value_si);
    CHECK(std::stoi(row[column("period")]) == p.period);
    CHECK(std::stod(row[column("dte_mean_m")]) == *p.dte_mean_m);
    CHECK(std::stod(row[column("dte_amplitude_m")]) == *p.dte_amplitude_m);
    CHECK(std::stod(row[column("s_min_m")]) == *p.s_min_m);
    CHECK(std::stod(row[column("s_max_m")]) == *p.s_max_m);
    CHECK(std::stod(row[column("dynamic_factor")]) == *p.dynamic_factor);
    CHECK(std::stod(row[column("w1_mean_rad_s")]) == *p.w1_mean_rad_s);
    CHECK(std::stod(row[column("impacts_drive_per_period")]) == *p.impacts_drive_per_period);
    // The mesh frequency is the transverse pair's z1 w1 / (2 pi), z1 = 20.
    CHECK(std::abs(std::stod(row[column("mesh_frequency_hz")]) -
                   20.0 * *p.w1_mean_rad_s / (2.0 * std::numbers::pi)) <=
          1e-12 * 20.0 * *p.w1_mean_rad_s);
  }
}

TEST_CASE(
    "planar sweep of the helical example: the program's files are the library's, byte for byte") {
  // `gearimpact sweep` on examples/helical_h501_planar.toml (bearings of 1 GN/m), two speeds,
  // against run_steady_sweep on the same file read by the library and its own writers
  // (sweep_csv, poincare_csv): the program is glue, so both files must be the same bytes. The
  // bearings' damping is raised (--set, the same values in the spec) so that the planar
  // transient dies within a few mesh periods and the two points take well under a second.
  const Scratch scratch("helical-planar-sweep");
  const std::filesystem::path example = std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." /
                                        "examples" / "helical_h501_planar.toml";
  const std::filesystem::path out = scratch.dir / "sweep";
  const CommandResult r = run_command(
      cli("sweep " + example.string() +
          " --vary initial.w1 --from '150 rad/s' --to '160 rad/s' --points 2 --direction up "
          "--threads 1 --no-plots --set 'bearings.damping_x1=2e4 N*s/m' --set "
          "'bearings.damping_x2=2e4 N*s/m' --set model.mesh_damping_ratio=0.1 --out " +
          out.string()));
  REQUIRE(r.exit_code == 0);
  const auto text = [](const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream all;
    all << in.rdbuf();
    return all.str();
  };
  SteadySweepSpec spec;
  spec.base = read_case_file(example);
  spec.base.bearings.gear1.damping_x_n_s_per_m = 2e4;
  spec.base.bearings.gear2.damping_x_n_s_per_m = 2e4;
  spec.base.model.mesh_damping_ratio = 0.1;
  spec.vary = "initial.w1";
  spec.from_si = 150.0;
  spec.to_si = 160.0;
  spec.points = 2;
  spec.directions = {SweepDirection::up};
  spec.threads = 1;
  const SteadySweep sweep = run_steady_sweep(spec);
  REQUIRE(sweep.rows.size() == 2);
  for (const SweepPointResult& row : sweep.rows) CHECK(row.point.converged);
  CHECK(text(out / "sweep.csv") == sweep_csv(sweep.rows));
  CHECK(text(out / "poincare.csv") == poincare_csv(sweep.rows));
}

TEST_CASE("mesh-stiffness, ste and report of a faulted helical pair: the library's tables") {
  // H501 with a spall on pinion tooth 0 over [5, 15) mm of the face: the
  // program prints the library's true-period stiffness to the bit (17
  // significant digits); ste and report write their files; faults with
  // modifications are refused by name before any work.
  const std::filesystem::path pair_file =
      std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples" / "helical_h501.toml";
  const Scratch scratch("helical-faults");
  const std::filesystem::path file = scratch.dir / "spalled.toml";
  {
    std::ifstream in(pair_file);
    std::ofstream out(file);
    out << in.rdbuf()
        << "\n[[faults]]\ngear = \"pinion\"\ntooth = 0\nkind = \"spall\"\n"
           "start_radius = \"37 mm\"\nend_radius = \"38.5 mm\"\nwidth = \"10 mm\"\n"
           "depth = \"0.2 mm\"\nface_start = \"5 mm\"\n";
  }
  const CommandResult r =
      run_command(cli("mesh-stiffness --case-file " + file.string() + " --samples 5"));
  REQUIRE(r.exit_code == 0);
  const auto rows = csv_rows(r.out);
  REQUIRE(rows.size() == 1 + 20 * 5);
  CHECK(rows[0][3] == "ke_n_m");
  CHECK(rows[0][4] == "healthy_ke_n_m");
  const SimulationCase c = read_pair_or_run_file(file).simulation_case;
  const TruePeriodMeshStiffness tvms =
      helical_true_period_mesh_stiffness(c.gears, c.model.stiffness, c.faults, 5);
  bool same = true;
  bool differs = false;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    same = same && std::stod(rows[i][3]) == tvms.samples[i - 1].ke_n_per_m &&
           std::stod(rows[i][4]) == tvms.samples[i - 1].healthy_ke_n_per_m;
    differs = differs || rows[i][3] != rows[i][4];
  }
  CHECK(same);
  CHECK(differs);
  const CommandResult ste =
      run_command(cli("ste " + file.string() + " --torque '200 N*m' --points 10 --no-plots --out " +
                      (scratch.dir / "ste").string()));
  CHECK(ste.exit_code == 0);
  CHECK(std::filesystem::exists(scratch.dir / "ste" / "ste_face_load.csv"));
  const std::filesystem::path crowned = scratch.dir / "spalled_crowned.toml";
  {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    std::string toml = text.str();
    const std::string model = "[model]";
    toml.replace(toml.find(model), model.size(),
                 "[modifications]\ncrowning1 = \"4 um\"\n\n[model]");
    std::ofstream(crowned) << toml;
  }
  const CommandResult modified =
      run_command(cli("ste " + crowned.string() + " --torque '200 N*m' --out " +
                      (scratch.dir / "refused").string()));
  CHECK(modified.exit_code != 0);
  CHECK(modified.err.find("[[faults]]") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(scratch.dir / "refused"));
  const CommandResult report = run_command(
      cli("report " + file.string() + " --samples 10 --out " + (scratch.dir / "report").string()));
  CHECK(report.exit_code == 0);
  CHECK(std::filesystem::exists(scratch.dir / "report" / "mesh_stiffness.csv"));
  CHECK(std::filesystem::exists(scratch.dir / "report" / "ste.csv"));
}
