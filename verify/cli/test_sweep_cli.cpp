// The `sweep` and `merge` commands end to end: sharded runs merge to the same bytes as one run,
// a missing shard is named by its key, bad input is refused naming the key.
#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "run_command.hpp"

using gearimpact::verify::cli;
using gearimpact::verify::run_command;

namespace {

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("gearimpact-sweep-" + std::to_string(::getpid()) + "-" + name);
  std::filesystem::remove_all(dir);
  return dir;
}

}  // namespace

TEST_CASE("sweep: 1 shard and 4 shards merge to the same bytes; a missing shard is named") {
  // The paper's pair loaded with 160 N on the line of action (balanced), rolling, with the
  // viscous mesh damper and D frozen, so that steady states exist; two lines (two backlashes)
  // in both directions: four units of work, one per shard of four.
  const std::filesystem::path one = scratch("one");
  const std::string base =
      "sweep 1 --vary initial.w1 --from '3000 rad/s' --to '6000 rad/s' --points 4 "
      "--vary2 gears.backlash --from2 '0.04 mm' --to2 '0.05 mm' --points2 2 "
      "--set 'torque1.mean=3 N*m' --set 'torque2.mean=-12 N*m' "
      "--set model.friction_coefficient=0 --set model.mesh_damping_ratio=0.05 "
      "--set 'initial.w2=125 rad/s' --damping-update frozen "
      "--set 'model.damping_reference_speed=0.1 m/s' --no-plots";
  const auto whole = run_command(cli(base + " --shard 0/1 --out " + one.string()));
  REQUIRE_MESSAGE(whole.exit_code == 0, whole.err);
  CHECK(whole.err.find("sweep: 16/16") != std::string::npos);
  const std::filesystem::path merged_one = scratch("merged-one");
  const auto m1 = run_command(cli("merge " + one.string() + " --out " + merged_one.string()));
  REQUIRE_MESSAGE(m1.exit_code == 0, m1.err);

  std::string shard_dirs;
  for (int k = 0; k < 4; ++k) {
    const std::filesystem::path dir = scratch("shard" + std::to_string(k));
    const auto r =
        run_command(cli(base + " --shard " + std::to_string(k) + "/4 --out " + dir.string()));
    REQUIRE_MESSAGE(r.exit_code == 0, r.err);
    shard_dirs.append(" ").append(dir.string());
  }
  const std::filesystem::path merged_four = scratch("merged-four");
  std::string merge_four = "merge";
  merge_four.append(shard_dirs).append(" --out ").append(merged_four.string());
  const auto m4 = run_command(cli(merge_four));
  REQUIRE_MESSAGE(m4.exit_code == 0, m4.err);
  for (const char* file : {"sweep.csv", "poincare.csv", "summary.json"}) {
    CAPTURE(file);
    const std::string a = read(merged_one / file);
    CHECK(!a.empty());
    CHECK(a == read(merged_four / file));
  }
  // 2 lines x 2 directions x 4 points and the header.
  const std::string csv = read(merged_one / "sweep.csv");
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 17);

  // Without shard 3 (line 1, down) the merge names the first missing key.
  const std::string without_last = shard_dirs.substr(0, shard_dirs.rfind(' '));
  std::string merge_three = "merge";
  merge_three.append(without_last).append(" --out ").append(scratch("x").string());
  const auto missing = run_command(cli(merge_three));
  CHECK(missing.exit_code != 0);
  CHECK(missing.err.find("line 1, direction down, index 0") != std::string::npos);
  // A folder given twice: its rows would be doubled, so the merge refuses them.
  const std::string twice =
      "merge " + one.string() + " " + one.string() + " --out " + scratch("y").string();
  const auto doubled = run_command(cli(twice));
  CHECK(doubled.exit_code != 0);
  CHECK(doubled.err.find("line 0, direction up, index 0") != std::string::npos);
}

TEST_CASE("sweep: bad input is refused naming the key") {
  const std::filesystem::path out = scratch("bad");
  // Table 1's case 2: T1 = 50 kgf mm, T2 = -50 kgf mm, so T1/Rb1 + T2/Rb2 != 0.
  const auto imbalance =
      run_command(cli("sweep 2 --vary initial.w1 --from '3000 rad/s' --to '6000 rad/s' --points 3 "
                      "--set model.friction_coefficient=0 --no-plots --out " +
                      out.string()));
  CHECK(imbalance.exit_code != 0);
  CHECK(imbalance.err.find("mean torques") != std::string::npos);
  const auto key = run_command(cli(
      "sweep 1 --vary gears.nonsense --from 1 --to 2 --points 3 --no-plots --out " + out.string()));
  CHECK(key.exit_code != 0);
  CHECK(key.err.find("gears.nonsense") != std::string::npos);
  const auto points =
      run_command(cli("sweep 1 --vary initial.w1 --from '3000 rad/s' --to '6000 rad/s' --points 0 "
                      "--no-plots --out " +
                      out.string()));
  CHECK(points.exit_code != 0);
  CHECK(points.err.find("--points") != std::string::npos);
  const auto unit =
      run_command(cli("sweep 1 --vary initial.w1 --from '3000 mm' --to '6000 rad/s' --points 3 "
                      "--no-plots --out " +
                      out.string()));
  CHECK(unit.exit_code != 0);
  CHECK(unit.err.find("--from") != std::string::npos);
}
