// The steady-state sweep as a library call and its files: shards of a sweep merge to the rows of
// one run; summary.json read back by a JSON reader holds the spec and the counts of the rows; the
// merge refuses shards of different sweeps; run_steady_sweep refuses a bad grid or shard before
// any work. The reference for the merge is the unsharded run itself (the rows are a function of
// the key alone, so any split must give them back bit for bit).
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/sweep_files.hpp"

using namespace gearimpact;

namespace {

std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      ("gearimpact-sweep-files-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The sharded tests' case (verify/slurm/sharded-sweep.toml): 2 backlash lines x 2 directions of
// 3 speeds, a fraction of a second.
SteadySweepSpec small_sweep() {
  SteadySweepSpec spec;
  spec.base = read_case_file(std::string(GEARIMPACT_PAPER_DATA_DIR) +
                             "/../verify/slurm/sharded-sweep.toml");
  spec.vary = "initial.w1";
  spec.from_si = 3000.0;
  spec.to_si = 5000.0;
  spec.points = 3;
  spec.vary2 = "gears.backlash";
  spec.from2_si = 4e-5;
  spec.to2_si = 6e-5;
  spec.points2 = 2;
  spec.threads = 2;
  return spec;
}

}  // namespace

TEST_CASE("three shards merge to the rows of one run, and summary.json holds spec and counts") {
  const SteadySweepSpec spec = small_sweep();
  const SteadySweep whole = run_steady_sweep(spec);
  REQUIRE(whole.rows.size() == 2u * 2u * 3u);
  REQUIRE(shard_point_count(spec) == whole.rows.size());
  for (std::size_t i = 1; i < whole.rows.size(); ++i) {
    CHECK(sweep_key_less(whole.rows[i - 1], whole.rows[i]));
  }

  std::vector<std::filesystem::path> shards;
  std::size_t shard_points = 0;
  for (int k = 0; k < 3; ++k) {
    SteadySweepSpec part = spec;
    part.shard = {k, 3};
    shard_points += shard_point_count(part);
    shards.push_back(scratch("shard" + std::to_string(k)));
    write_sweep_folder(shards.back(), run_steady_sweep(part));
  }
  CHECK(shard_points == whole.rows.size());
  const SteadySweep merged = merge_sweep_folders(shards);
  CHECK(sweep_csv(merged.rows) == sweep_csv(whole.rows));
  CHECK(poincare_csv(merged.rows) == poincare_csv(whole.rows));
  CHECK_FALSE(merged.shard.has_value());

  // The summary by a JSON reader: the spec as given, the counts of the rows.
  const nlohmann::json summary = nlohmann::json::parse(read(shards[0] / "summary.json"));
  const nlohmann::json& s = summary.at("spec");
  CHECK(s.at("case") == "sharded-sweep");
  CHECK(s.at("vary") == "initial.w1");
  CHECK(s.at("from_si").get<double>() == spec.from_si);
  CHECK(s.at("to_si").get<double>() == spec.to_si);
  CHECK(s.at("points") == 3);
  CHECK(s.at("from2_si").get<double>() == spec.from2_si);
  CHECK(s.at("to2_si").get<double>() == spec.to2_si);
  CHECK(s.at("lines") == 2);
  CHECK(s.at("directions") == "up,down");
  CHECK(s.at("damping_update") == "frozen");  // the case file's, by its schema name
  CHECK(s.at("tolerance").get<double>() == SteadySettings{}.tolerance);
  CHECK(s.contains("iso_resonance_speed_rad_s"));  // a sweep of w1
  CHECK(summary.at("shard") == "0/3");
  const nlohmann::json merged_summary = nlohmann::json::parse(sweep_summary_json(merged));
  CHECK(merged_summary.at("spec") == s);
  CHECK_FALSE(merged_summary.contains("shard"));
  CHECK(merged_summary.at("points_written") == whole.rows.size());
  std::size_t converged = 0;
  for (const SweepPointResult& r : whole.rows) converged += r.point.converged ? 1 : 0;
  CHECK(merged_summary.at("points_converged") == converged);
  std::size_t by_regime = 0;
  for (const auto& [name, n] : merged_summary.at("regimes").items()) {
    CAPTURE(name);
    by_regime += n.get<std::size_t>();
  }
  CHECK(by_regime == converged);
  for (const std::filesystem::path& dir : shards) std::filesystem::remove_all(dir);
}

TEST_CASE("the merge refuses shards of two different sweeps, naming the folder") {
  SteadySweepSpec spec = small_sweep();
  spec.vary2.clear();
  spec.points = 1;
  spec.to_si = spec.from_si;
  spec.directions = {SweepDirection::up};
  const std::filesystem::path a = scratch("a");
  const std::filesystem::path b = scratch("b");
  write_sweep_folder(a, run_steady_sweep(spec));
  spec.settings.tolerance = 2e-6;
  write_sweep_folder(b, run_steady_sweep(spec));
  try {
    merge_sweep_folders({a, b});
    FAIL("shards of different sweeps merged");
  } catch (const InputError& e) {
    CHECK(e.value() == b.string());
  }
  // A folder without a summary.json is named too.
  const std::filesystem::path empty = scratch("empty");
  std::filesystem::create_directories(empty);
  try {
    merge_sweep_folders({empty});
    FAIL("a folder without summary.json merged");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find((empty / "summary.json").string()) != std::string::npos);
  }
  for (const auto& dir : {a, b, empty}) std::filesystem::remove_all(dir);
}

TEST_CASE("run_steady_sweep refuses a bad grid or shard before any work, naming the argument") {
  const auto refused = [](const SteadySweepSpec& spec, const char* argument) {
    try {
      run_steady_sweep(spec);
      FAIL("accepted");
    } catch (const InputError& e) {
      CHECK(e.field() == argument);
    }
  };
  SteadySweepSpec spec = small_sweep();
  spec.points = 0;
  refused(spec, "points");
  spec = small_sweep();
  spec.shard = {3, 3};
  refused(spec, "shard");
  spec = small_sweep();
  spec.points2 = 0;
  refused(spec, "points2");
  spec = small_sweep();
  spec.directions.clear();
  refused(spec, "directions");
}
