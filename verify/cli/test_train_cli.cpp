// End to end: `gearimpact train` on the example train. Reference: the library's run of the same
// file (read_train_file, simulate_train); the CSV's numbers, read back, are its rows' doubles,
// and its columns are named by the case file's bodies and meshes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planetary_train.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

using namespace gearimpact;
using namespace gearimpact::verify;

namespace {

const std::filesystem::path examples =
    std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples";

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The example over 2 ms (both meshes pass pairs in and out, the wheel's missing tooth not yet).
std::filesystem::path short_example(const Scratch& scratch) {
  std::string text = read(examples / "pinion_idler_wheel.toml");
  const std::size_t at = text.find("end_time = \"20 ms\"");
  REQUIRE(at != std::string::npos);
  text.replace(at, 18, "end_time = \"2 ms\"");
  const std::filesystem::path path = scratch.dir / "train.toml";
  std::ofstream(path) << text;
  return path;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  return cells;
}

}  // namespace

TEST_CASE("train's series.csv holds the library run's rows, column by named column") {
  Scratch scratch("train-cli");
  const std::filesystem::path file = short_example(scratch);
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r = run_command(cli("train " + file.string() + " --out " + out.string()));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);

  const GearTrain train = read_train_file(file);
  const TrainResult run = simulate_train(train);
  const std::vector<TrainColumn> columns = train_series_columns(train);
  std::istringstream csv(read(out / "series.csv"));
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = split(line);
  REQUIRE(header.size() == columns.size());
  // The names docs/usage.md gives, by body and mesh.
  CHECK(header[0] == "t_s");
  CHECK(header[1] == "theta_pinion_rad");
  CHECK(header[4] == "w_idler_rad_per_s");
  CHECK(header[9] == "s_pinion-idler_m");
  CHECK(header.back() == "friction_force_idler-wheel_N");
  std::size_t rows = 0;
  for (; std::getline(csv, line); ++rows) {
    REQUIRE(rows < run.series.size());
    const std::vector<std::string> cells = split(line);
    REQUIRE(cells.size() == columns.size());
    for (std::size_t c = 0; c < columns.size(); ++c) {
      // 17 significant digits read back to the same double.
      if (std::stod(cells[c]) != columns[c].value(run.series[rows])) {
        INFO("row " << rows << ", column " << header[c] << ": " << cells[c]);
        REQUIRE(false);
      }
    }
  }
  CHECK(rows == run.series.size());
  CHECK(rows > 100);

  const std::string summary = read(out / "summary.json");
  CHECK(summary == r.out);
  const std::size_t at = summary.find("\"ledger_residual_max_J\": ");
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(summary.substr(at + 25)) == run.summary.ledger_residual_max_j);
  CHECK(summary.find("{\"name\": \"idler-wheel\", \"impacts\": " +
                     std::to_string(run.meshes[1].impacts)) != std::string::npos);
  // Per mesh its losses, per body its final speed: the library run's doubles at 17 digits.
  const auto number_after = [&summary](const std::string& key, std::size_t from) {
    const std::size_t where = summary.find("\"" + key + "\": ", from);
    REQUIRE(where != std::string::npos);
    return std::stod(summary.substr(where + key.size() + 4));
  };
  const std::size_t idler_wheel = summary.find("{\"name\": \"idler-wheel\"");
  REQUIRE(idler_wheel != std::string::npos);
  CHECK(number_after("damping_loss_J", idler_wheel) == run.meshes[1].damping_loss_j);
  CHECK(number_after("friction_loss_J", idler_wheel) == run.meshes[1].friction_loss_j);
  const std::size_t wheel = summary.find("{\"name\": \"wheel\"");
  REQUIRE(wheel != std::string::npos);
  CHECK(number_after("final_w_rad_per_s", wheel) == run.bodies[2].final_w_rad_per_s);
  CHECK(run.bodies[2].final_w_rad_per_s == run.series.back().w_rad_per_s[2]);
}

TEST_CASE("train runs the two-stage rig on bearings as the library does, its centres' columns") {
  // The example as a user runs it, over its own 10 ms.
  Scratch scratch("train-cli-bearings");
  const std::filesystem::path file = examples / "two_stage_rig_bearings.toml";
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r = run_command(cli("train " + file.string() + " --out " + out.string()));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const GearTrain train = read_train_file(file);
  const TrainResult run = simulate_train(train);
  const std::vector<TrainColumn> columns = train_series_columns(train);
  std::istringstream csv(read(out / "series.csv"));
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = split(line);
  REQUIRE(header.size() == columns.size());
  // After the meshes' columns: each body with bearings (input, wheel1, output), then the sensor.
  const auto column = [&header](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  CHECK(column("x_input_m") < header.size());
  CHECK(column("bearing_fy_wheel1_N") < header.size());
  CHECK(column("x_pinion2_m") == header.size());
  CHECK(header.back() == "sensor_acceleration_m_per_s2");
  std::size_t rows = 0;
  for (; std::getline(csv, line); ++rows) {
    REQUIRE(rows < run.series.size());
    const std::vector<std::string> cells = split(line);
    REQUIRE(cells.size() == columns.size());
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (std::stod(cells[c]) != columns[c].value(run.series[rows])) {
        INFO("row " << rows << ", column " << header[c] << ": " << cells[c]);
        REQUIRE(false);
      }
    }
  }
  CHECK(rows == run.series.size());
  // The rig works its bearings: its centres move and their dampers take energy.
  REQUIRE(run.summary.planar.has_value());
  CHECK(run.summary.planar->bearing_damping_loss_j > 0.0);
  const std::string summary = read(out / "summary.json");
  CHECK(summary.find("\"bearing_damping_loss_J\": ") != std::string::npos);
}

TEST_CASE("train --set writes the file's series as if the file said so") {
  Scratch scratch("train-cli-set");
  const std::filesystem::path file = short_example(scratch);
  const CommandResult edited =
      run_command(cli("train " + file.string() + " --out " + (scratch.dir / "a").string()));
  const CommandResult set =
      run_command(cli("train " + (examples / "pinion_idler_wheel.toml").string() +
                      " --set 'integrator.end_time=2 ms' --out " + (scratch.dir / "b").string()));
  REQUIRE(edited.exit_code == 0);
  REQUIRE(set.exit_code == 0);
  CHECK(read(scratch.dir / "a" / "series.csv") == read(scratch.dir / "b" / "series.csv"));
}

TEST_CASE("train refuses a bad key by its name before writing anything") {
  Scratch scratch("train-cli-refused");
  std::string text = read(examples / "pinion_idler_wheel.toml");
  const std::size_t at = text.find("body_b = \"wheel\"");
  REQUIRE(at != std::string::npos);
  text.replace(at, 16, "body_b = \"whel\"");
  const std::filesystem::path file = scratch.dir / "train.toml";
  std::ofstream(file) << text;
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r = run_command(cli("train " + file.string() + " --out " + out.string()));
  CHECK(r.exit_code != 0);
  CHECK(r.err.find("meshes.idler-wheel.body_b") != std::string::npos);
  CHECK(!std::filesystem::exists(out));
}

TEST_CASE(
    "train --sample-rate writes the sensor's samples, and refuses them by flag before any work") {
  Scratch scratch("train-cli-samples");
  const std::string rig =
      (examples / "rig_17_38.toml").string() + " --set 'integrator.end_time=2 ms'";
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r =
      run_command(cli("train " + rig + " --sample-rate '51.2 kHz' --out " + out.string()));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  // The series' columns, one row a sample from n = 1 (interval averages) to 2 ms: 102 rows.
  const std::string samples = read(out / "samples.csv");
  CHECK(samples.substr(0, samples.find('\n')) ==
        read(out / "series.csv").substr(0, samples.find('\n')));
  CHECK(std::count(samples.begin(), samples.end(), '\n') == 1 + 102);
  // Refused naming the flag, nothing written: a train without a [sensor], --sample alone, a
  // stage file.
  const std::vector<std::tuple<std::string, std::string>> refused = {
      {(examples / "pinion_idler_wheel.toml").string() + " --sample-rate 1000", "--sample-rate"},
      {rig + " --sample point", "--sample"},
      {(examples / "planetary_stage.toml").string() + " --sample-rate 1000", "--sample-rate"},
  };
  for (const auto& [args, flag] : refused) {
    const std::filesystem::path none = scratch.dir / "none";
    const CommandResult bad = run_command(cli("train " + args + " --out " + none.string()));
    INFO(args << ": " << bad.err);
    CHECK(bad.exit_code != 0);
    CHECK(bad.err.find("error: " + flag + " = ") != std::string::npos);
    CHECK(!std::filesystem::exists(none));
  }
}

TEST_CASE("train writes a two-gear file's tacho.csv as simulate --tacho-out writes it") {
  Scratch scratch("train-cli-tacho");
  const std::string rig = (examples / "rig_17_38.toml").string() +
                          " --set 'integrator.end_time=20 ms' --set tacho.pulses_per_revolution=8"
                          " --set 'tacho.jitter=1 us'";
  const std::filesystem::path out = scratch.dir / "out";
  const std::filesystem::path tacho = scratch.dir / "tacho.csv";
  const CommandResult train = run_command(cli("train " + rig + " --out " + out.string()));
  const CommandResult simulate =
      run_command(cli("simulate --case-file " + rig + " --tacho-out " + tacho.string()));
  INFO(train.err << simulate.err);
  REQUIRE(train.exit_code == 0);
  REQUIRE(simulate.exit_code == 0);
  const std::string written = read(out / "tacho.csv");
  CHECK(std::count(written.begin(), written.end(), '\n') > 5);
  CHECK(written == read(tacho));
}

// ---- A planetary stage's file ([stage]) through `gearimpact train` ----

namespace {

// examples/planetary_stage.toml written out by hand as the library's PlanetaryStage: the
// reference the program's run is compared with, bit for bit.
PlanetaryStage example_stage_by_hand() {
  PlanetaryStage s;
  s.teeth = {21, 30, 81};
  s.planets = 3;
  s.held = HeldMember::ring;
  s.mesh.gears.module_m = 2.0e-3;
  s.mesh.gears.pressure_angle_rad = 20.0 * pi / 180.0;
  s.mesh.gears.face_width_m = 20.0e-3;
  s.mesh.gears.youngs_modulus_pa = 206.8e9;
  s.mesh.gears.poisson_ratio = 0.3;
  s.mesh.gears.density_kg_m3 = 7800.0;
  s.mesh.gears.backlash_m = 0.05e-3;
  s.mesh.model.friction_coefficient = 0.0;
  s.mesh.model.mesh_damping_ratio = 0.1;
  s.sun_inertia_kg_m2 = 4.8e-5;
  s.planet_inertia_kg_m2 = 2.0e-4;
  s.ring_inertia_kg_m2 = 4.2e-2;
  s.carrier_inertia_kg_m2 = 2e-3;
  s.planet_mass_kg = 0.3;
  s.input_speed_rad_per_s = 100.0;
  s.carrier_torque.kind = Torque::Kind::constant;
  s.carrier_torque.constant_n_m = -40.0;
  s.sun_torque.kind = Torque::Kind::prescribed_speed;
  s.sun_torque.mean_speed_rad_per_s = 100.0;
  s.integrator.step_s = 1e-6;
  s.integrator.end_time_s = 5e-3;
  return s;
}

std::vector<std::vector<double>> csv_numbers(const std::string& text, std::string& header) {
  std::istringstream csv(text);
  std::getline(csv, header);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(csv, line)) {
    std::vector<double> row;
    for (const std::string& cell : split(line)) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace

TEST_CASE("train runs a stage file: the library's stage run bit for bit, Willis within the play") {
  Scratch scratch("train-cli-stage");
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r = run_command(
      cli("train " + (examples / "planetary_stage.toml").string() + " --out " + out.string()));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);

  const PlanetaryStage stage = example_stage_by_hand();
  const GearTrain train = planetary_train(stage);
  const TrainResult run = simulate_train(train);
  const std::vector<TrainColumn> columns = train_series_columns(train);
  std::string header;
  const std::vector<std::vector<double>> series = csv_numbers(read(out / "series.csv"), header);
  CHECK(header.rfind("t_s,theta_sun_rad,w_sun_rad_per_s,theta_ring_rad", 0) == 0);
  REQUIRE(series.size() == run.series.size());
  for (std::size_t i = 0; i < series.size(); ++i) {
    REQUIRE(series[i].size() == columns.size());
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (series[i][c] != columns[c].value(run.series[i])) {
        INFO("row " << i << ", column " << c);
        REQUIRE(false);
      }
    }
  }
  // The ring sensor's column: planetary_ring_sensor of the same run.
  const std::vector<double> y = planetary_ring_sensor(stage, run);
  const std::vector<std::vector<double>> ring = csv_numbers(read(out / "ring_sensor.csv"), header);
  CHECK(header == "t_s,ring_sensor_y_N");
  REQUIRE(ring.size() == y.size());
  bool nonzero = false;
  for (std::size_t i = 0; i < y.size(); ++i) {
    REQUIRE(ring[i][0] == run.series[i].t_s);
    REQUIRE(ring[i][1] == y[i]);
    nonzero = nonzero || y[i] != 0.0;
  }
  CHECK(nonzero);
  const std::string summary = read(out / "summary.json");
  CHECK(summary == r.out);
  const auto number_after = [&summary](const std::string& key) {
    const std::size_t where = summary.find("\"" + key + "\": ");
    REQUIRE(where != std::string::npos);
    return std::stod(summary.substr(where + key.size() + 4));
  };
  CHECK(summary.find("{\"name\": \"ring_planet2\", \"impacts\": " +
                     std::to_string(run.meshes[4].impacts)) != std::string::npos);
  // The mean speeds from the angles the series holds (first row to last).
  const double time = run.series.back().t_s - run.series.front().t_s;
  const auto mean = [&](int body) {
    const auto b = static_cast<std::size_t>(body);
    return (run.series.back().theta_rad[b] - run.series.front().theta_rad[b]) / time;
  };
  CHECK(number_after("mean_w_sun_rad_per_s") == mean(kSunBody));
  CHECK(number_after("mean_w_carrier_rad_per_s") == mean(kCarrierBody));
  const double residual = number_after("willis_residual");
  CHECK(residual == planetary_willis(stage, run).residual);
  // The bound: with r_b = m Z cos(a) / 2, T (Z_s (w_s - w_c) + Z_r (w_r - w_c)) =
  // 2 (Delta s_sp + Delta s_rp) / (m cos a) for planet 1's two meshes, and each s starts at 0
  // (centred in the play) and stays within [-(B + p), B + p], B the half play (gears.backlash) and
  // p the largest penetration of any mesh. So the residual is at most
  // 4 (B + p) / (m cos a T (Z_s |w_s - w_c| + Z_r |w_r - w_c|)): about 6.6e-3 here, as the
  // meshes take up the play from centred to the drive flanks under the load.
  double p = 0.0;
  for (const TrainMeshSummary& m : run.meshes) p = std::max(p, m.max_penetration_m);
  const double ws = mean(kSunBody), wr = mean(kRingBody), wc = mean(kCarrierBody);
  const double scale = time * (21.0 * std::fabs(ws - wc) + 81.0 * std::fabs(wr - wc));
  const double bound = 4.0 * (0.05e-3 + p) / (2.0e-3 * std::cos(20.0 * pi / 180.0) * scale);
  CAPTURE(bound);
  CHECK(residual > 0.0);
  CHECK(residual <= bound);
  // The Willis carrier speed, w_s Z_s / (Z_s + Z_r), at the run's end (the play taken up).
  CHECK(std::fabs(run.bodies[kCarrierBody].final_w_rad_per_s / (100.0 * 21.0 / 102.0) - 1.0) <
        1e-5);
}

TEST_CASE("train refuses a stage file's bad key and range by name before writing anything") {
  Scratch scratch("train-cli-stage-refused");
  const std::string text = read(examples / "planetary_stage.toml");
  for (const auto& [from, to, named] :
       {std::tuple<std::string, std::string, std::string>{"planets = 3", "planet = 3",
                                                          "stage.planet"},
        {"planets = 3", "planets = 7", "stage.planets"},
        {"ring_teeth = 81", "ring_teeth = 80", "stage.ring_teeth"},
        {"kind = \"prescribed-speed\"", "kind = \"prescribed\"", "stage.sun_torque.kind"},
        // Unequal spacing: one angle per planet, none shared, each a multiple of 360 / 102 deg
        // (the assembly condition; 116.4706 is 33 steps cut to 7 digits).
        {"planets = 3", "planets = 3\nplanet_angles = [\"0 deg\", \"120 deg\"]",
         "stage.planet_angles = 2 angles"},
        {"planets = 3", "planets = 3\nplanet_angles = [\"0 deg\", \"120 deg\", \"120 deg\"]",
         "stage.planet_angles[2] = \"120 deg\""},
        {"planets = 3", "planets = 3\nplanet_angles = [\"0 deg\", \"116.4706 deg\", \"240 deg\"]",
         "stage.planet_angles[1] = \"116.4706 deg\""},
        {"[stage]\n", "[[faults]]\nkind = \"missing\"\ngear = \"pinion\"\ntooth = 0\n[stage]\n",
         "faults[0].gear"},
        // A stage's [[faults]] name their member, which must be the stage's, and a tooth of it;
        // a ring tooth can only be missing.
        {"[stage]\n", "[[faults]]\nkind = \"missing\"\nmember = \"planet4\"\ntooth = 0\n[stage]\n",
         "faults[0].member"},
        {"[stage]\n", "[[faults]]\nkind = \"missing\"\nmember = \"sun\"\ntooth = 21\n[stage]\n",
         "faults[0].tooth"},
        {"[stage]\n", "[[faults]]\nkind = \"spall\"\nmember = \"ring\"\ntooth = 3\n[stage]\n",
         "faults[0].kind"},
        {"[stage]\n",
         "[[faults]]\nkind = \"missing\"\nmember = \"ring\"\ntooth = 3\n[[faults]]\n"
         "kind = \"root-crack\"\nmember = \"planet2\"\ntooth = 3\nangle = \"45 deg\"\n"
         "depth = \"9 mm\"\n[stage]\n",
         "faults[1].depth"}}) {
    std::string edited = text;
    const std::size_t at = edited.find(from);
    REQUIRE(at != std::string::npos);
    edited.replace(at, from.size(), to);
    const std::filesystem::path file = scratch.dir / "stage.toml";
    std::ofstream(file) << edited;
    const std::filesystem::path out = scratch.dir / "out";
    const CommandResult r = run_command(cli("train " + file.string() + " --out " + out.string()));
    INFO(to, "\n", r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.find(named) != std::string::npos);
    CHECK(!std::filesystem::exists(out));
  }
}

TEST_CASE("train runs a stage file's faulted teeth: the library's run of the stage's faults") {
  // examples/planetary_stage_cracked_sun.toml over 1 ms (the cracked tooth is at planet 1's
  // sun mesh at t = 0), against the stage written out by hand
  // with its crack as a StageFault, bit for bit; the healthy stage's run differs.
  Scratch scratch("train-cli-stage-faults");
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r =
      run_command(cli("train " + (examples / "planetary_stage_cracked_sun.toml").string() +
                      " --set 'integrator.end_time=1 ms' --out " + out.string()));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  PlanetaryStage stage = example_stage_by_hand();
  const double ws = 2.0 * pi * (21 + 81) / (21 * 30e-3);
  stage.input_speed_rad_per_s = 1017.2776211624092;
  CHECK(std::fabs(stage.input_speed_rad_per_s / ws - 1.0) < 1e-15);
  stage.sun_torque.mean_speed_rad_per_s = 1017.2776211624092;
  stage.carrier_torque.constant_n_m = -400.0;
  stage.mesh.model.damping_update = DampingUpdate::frozen;
  stage.integrator.output_every = 4;
  stage.integrator.end_time_s = 1e-3;
  StageFault crack;
  crack.member = FaultMember::sun;
  crack.tooth = 0;
  crack.state.kind = ToothKind::root_crack;
  crack.state.crack.depth_m = 1e-3;
  crack.state.crack.angle_rad = 45.0 * pi / 180.0;
  const PlanetaryStage healthy = stage;
  stage.faults = {crack};
  const auto csv_of = [](const PlanetaryStage& s) {
    const GearTrain train = planetary_train(s);
    const TrainResult run = simulate_train(train);
    const std::vector<TrainColumn> columns = train_series_columns(train);
    std::vector<std::vector<double>> rows;
    for (const TrainRow& row : run.series) {
      rows.emplace_back();
      for (const TrainColumn& c : columns) rows.back().push_back(c.value(row));
    }
    return rows;
  };
  std::string header;
  const std::vector<std::vector<double>> series = csv_numbers(read(out / "series.csv"), header);
  CHECK(series == csv_of(stage));
  CHECK(series != csv_of(healthy));
}

TEST_CASE("train writes a stage's mesh_teeth.csv: planetary_mesh_teeth of the library's run") {
  Scratch scratch("train-cli-stage-teeth");
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r =
      run_command(cli("train " + (examples / "planetary_stage.toml").string() +
                      " --set 'integrator.end_time=0.5 ms' --out " + out.string()));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  PlanetaryStage stage = example_stage_by_hand();
  stage.integrator.end_time_s = 0.5e-3;
  const TrainResult run = simulate_train(planetary_train(stage));
  std::string header;
  // The teeth at each mesh: planetary_mesh_teeth of each row of the same run.
  const std::vector<std::vector<double>> teeth = csv_numbers(read(out / "mesh_teeth.csv"), header);
  CHECK(header.rfind("t_s,sun_tooth_at_sun_planet1,planet1_tooth_at_sun_planet1,"
                     "planet1_tooth_at_ring_planet1,ring_tooth_at_ring_planet1,",
                     0) == 0);
  REQUIRE(teeth.size() == run.series.size());
  for (std::size_t i = 0; i < teeth.size(); ++i) {
    const std::vector<StageMeshTeeth> at = planetary_mesh_teeth(stage, run.series[i]);
    REQUIRE(teeth[i].size() == 1 + 4 * at.size());
    REQUIRE(teeth[i][0] == run.series[i].t_s);
    for (std::size_t n = 0; n < at.size(); ++n) {
      REQUIRE(teeth[i][1 + 4 * n] == at[n].sun);
      REQUIRE(teeth[i][2 + 4 * n] == at[n].planet_at_sun);
      REQUIRE(teeth[i][3 + 4 * n] == at[n].planet_at_ring);
      REQUIRE(teeth[i][4 + 4 * n] == at[n].ring);
    }
  }
}

TEST_CASE("train --set stage.planet_angles takes a list as the file writes it, bit for bit") {
  // The example stage (21/30/81: assembly steps of 360 / 102 deg) with its planets at 0, 33 and
  // 69 steps, written in the file and set from the command line: the same run to the bit, and
  // not the equally spaced one.
  Scratch scratch("train-cli-stage-angles");
  const std::string angles = "[\"0 deg\", \"116.47058823529412 deg\", \"243.52941176470588 deg\"]";
  std::string text = read(examples / "planetary_stage.toml");
  const std::size_t at = text.find("planets = 3");
  REQUIRE(at != std::string::npos);
  text.replace(at, 11, "planets = 3\nplanet_angles = " + angles);
  const std::filesystem::path file = scratch.dir / "stage.toml";
  std::ofstream(file) << text;
  const std::string short_run = " --set 'integrator.end_time=0.2 ms'";
  const std::string example = (examples / "planetary_stage.toml").string();
  const CommandResult written = run_command(
      cli("train " + file.string() + short_run + " --out " + (scratch.dir / "a").string()));
  const CommandResult set =
      run_command(cli("train " + example + short_run + " --set 'stage.planet_angles=" + angles +
                      "' --out " + (scratch.dir / "b").string()));
  const CommandResult equal =
      run_command(cli("train " + example + short_run + " --out " + (scratch.dir / "c").string()));
  INFO(set.err);
  REQUIRE(written.exit_code == 0);
  REQUIRE(set.exit_code == 0);
  REQUIRE(equal.exit_code == 0);
  for (const char* name : {"series.csv", "ring_sensor.csv", "mesh_teeth.csv", "summary.json"}) {
    CAPTURE(name);
    CHECK(read(scratch.dir / "a" / name) == read(scratch.dir / "b" / name));
  }
  CHECK(read(scratch.dir / "b" / "series.csv") != read(scratch.dir / "c" / "series.csv"));

  // Refused by the element's name before any work: a plain number is an angle in rad (120 rad is
  // out of [0, 2 pi)); an angle off the assembly condition, by the file reader's check.
  for (const auto& [value, named] :
       {std::pair<std::string, std::string>{"[0, 120, 240]", "stage.planet_angles[1]"},
        {"[\"0 deg\", \"116.4706 deg\", \"240 deg\"]", "stage.planet_angles[1]"},
        {"0 deg, 120 deg, 240 deg, 300 deg, 330 deg, 350 deg", "stage.planet_angles"}}) {
    const std::filesystem::path out = scratch.dir / "refused";
    const CommandResult r = run_command(cli(
        "train " + example + " --set 'stage.planet_angles=" + value + "' --out " + out.string()));
    INFO(value, "\n", r.err);
    CHECK(r.exit_code != 0);
    CHECK(r.err.find(named) != std::string::npos);
    CHECK(!std::filesystem::exists(out));
  }
}
