// End to end: `gearimpact train` on the example train. Reference: the library's run of the same
// file (read_train_file, simulate_train); the CSV's numbers, read back, are its rows' doubles,
// and its columns are named by the case file's bodies and meshes.
#include <doctest/doctest.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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
