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
#include <utility>
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

TEST_CASE("run_steady_sweep refuses unbounded or meaningless work before any point, naming it") {
  const auto refused = [](const SteadySweepSpec& spec, const char* argument) {
    CAPTURE(argument);
    try {
      run_steady_sweep(spec, [](const SweepPointResult&) { FAIL("a point ran"); });
      FAIL("accepted");
    } catch (const InputError& e) {
      CHECK(e.field() == argument);
    }
  };
  SteadySweepSpec spec = small_sweep();
  spec.max_points = 11;  // the spec's 3 points x 2 lines x 2 directions = 12
  refused(spec, "max_points");
  spec = small_sweep();
  spec.points = 1000000000;  // refused before a grid of gigabytes is made
  refused(spec, "max_points");
  spec = small_sweep();
  std::swap(spec.from_si, spec.to_si);
  refused(spec, "from");
  spec = small_sweep();
  spec.vary2 = spec.vary;
  refused(spec, "vary2");
  spec = small_sweep();
  spec.vary = "integrator.step";
  spec.from_si = 1e-7;
  spec.to_si = 2e-7;
  refused(spec, "vary");
  for (const double steps : {kLeastStepsPerContactPeriod - 1, kMostStepsPerContactPeriod + 1}) {
    spec = small_sweep();
    spec.settings.steps_per_contact_period = steps;
    refused(spec, "steps_per_contact_period");
  }
  spec = small_sweep();
  spec.settings.max_periods = 0;
  refused(spec, "max_periods");
  spec = small_sweep();
  spec.settings.tolerance = 2 * kMostTolerance;
  refused(spec, "tolerance");
}

TEST_CASE("the merge's reader names the file and line of the first bad row") {
  SteadySweepRecord spec;
  spec.from_si = 0.0;
  spec.to_si = 1.0;
  spec.points = 2;
  spec.lines = 1;
  spec.directions = {SweepDirection::up};
  const std::string header =
      "line,direction,index,value_si,regime,period,converged,dte_mean_m,dte_amplitude_m,"
      "dte_rms_m,s_min_m,s_max_m,dynamic_factor,impacts_drive_per_period,"
      "impacts_coast_per_period\n";
  const std::string good = "0,up,0,0,SS,1,true,1e-06,2e-06,3e-06,-1e-05,1e-05,1.5,1,0\n";
  CHECK(parse_sweep_csv(header + good, "s/sweep.csv", spec).size() == 1u);
  const auto message = [&](const std::string& text) {
    try {
      parse_sweep_csv(text, "s/sweep.csv", spec);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK(message(header + good + "0,up,1,1,SS,1,true,nan,2e-06,3e-06,-1e-05,1e-05,1.5,1,0\n")
            .find("s/sweep.csv:3: nan") != std::string::npos);
  CHECK(message(header + good + "0,down,1,1,SS,1,true,1,1,1,1,1,1,1,0\n")
            .find("s/sweep.csv:3: direction down") != std::string::npos);
  CHECK(message(header + "0,up,0,1.5,SS,1,true,1,1,1,1,1,1,1,0\n").find("s/sweep.csv:2") !=
        std::string::npos);
  CHECK(message(header + good.substr(0, good.size() - 3)).find("cut short") != std::string::npos);
  CHECK(message(header + "0,up,4294967296,0,SS,1,true,1,1,1,1,1,1,1,0\n").find("4294967296") !=
        std::string::npos);
}
