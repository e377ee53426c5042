// End to end: `gearimpact ste` on the example pair with tip relief and a pitch error, its
// refusals before any work, the case-file keys of [modifications] and their refusals, and
// simulate running a case with gaps, which a sweep samples once per true period when its teeth
// differ.
#include <doctest/doctest.h>

#include <algorithm>
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

const std::filesystem::path examples =
    std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples";
const std::filesystem::path paper_data(GEARIMPACT_PAPER_DATA_DIR);

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The number after "key": in a flat JSON object.
double json_value(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\":");
  REQUIRE(at != std::string::npos);
  return std::stod(json.substr(at + key.size() + 3));
}

// A column of a CSV by its header name, as numbers.
std::vector<double> csv_column(const std::string& csv, const std::string& name) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  std::istringstream header(line);
  std::string cell;
  int index = -1;
  for (int i = 0; std::getline(header, cell, ','); ++i) {
    if (cell == name) index = i;
  }
  REQUIRE(index >= 0);
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    for (int i = 0; std::getline(row, cell, ','); ++i) {
      if (i == index) values.push_back(std::stod(cell));
    }
  }
  return values;
}

std::string pair_file(const std::string& modifications) {
  return "[gears]\nteeth1 = 20\nteeth2 = 80\nmodule = \"2 mm\"\npressure_angle = \"20 deg\"\n"
         "face_width = \"10 mm\"\nyoungs_modulus = \"206.8 GPa\"\npoisson_ratio = 0.3\n"
         "density = \"7800 kg/m^3\"\nbacklash = \"0.05 mm\"\n\n[modifications]\n" +
         modifications;
}

}  // namespace

TEST_CASE("ste writes its files, and the summary's figures are those of ste.csv") {
  Scratch scratch("ste-cli");
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r =
      run_command(cli("ste " + (examples / "tip_relief_20_80.toml").string() +
                      " --torque \"100 N*m\" --points 50 --out " + out.string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  for (const char* file :
       {"ste.csv", "ste_unmodified.csv", "ste_pairs.csv", "ste_unmodified_pairs.csv",
        "summary.json", "ste.png", "ste_load_sharing.png", "ste.gp", "ste_load_sharing.gp"}) {
    CHECK_MESSAGE(std::filesystem::is_regular_file(out / file), file);
  }
  const std::string csv = read(out / "ste.csv");
  const std::vector<double> ste = csv_column(csv, "ste_m");
  // One pinion tooth has a pitch error: the true period is z1 = 20 mesh periods.
  CHECK(ste.size() == 20u * 50u);
  CHECK(csv_column(read(out / "ste_unmodified.csv"), "ste_m").size() == ste.size());
  const std::string summary = read(out / "summary.json");
  CHECK(summary == r.out);
  const auto [least, most] = std::minmax_element(ste.begin(), ste.end());
  // 17 significant digits in both files: the same doubles.
  CHECK(relative_difference(json_value(summary, "ste_peak_to_peak_m"), *most - *least) < 1e-15);
  double sum = 0.0;
  for (double v : ste) sum += v;
  CHECK(relative_difference(json_value(summary, "ste_mean_m"),
                            sum / static_cast<double>(ste.size())) < 1e-13);
  CHECK(json_value(summary, "mesh_periods") == 20.0);
  // The pitch error of 5 um: the kinematic error runs from 0 to 5 um.
  CHECK(relative_difference(json_value(summary, "kte_peak_to_peak_m"), 5e-6) < 1e-12);
  CHECK(json_value(summary, "unmodified_kte_peak_to_peak_m") == 0.0);
  // Relief and error only add to the deflection.
  CHECK(json_value(summary, "ste_peak_to_peak_m") >
        json_value(summary, "unmodified_ste_peak_to_peak_m"));
}

TEST_CASE("ste_pairs.csv holds each pair from entry to exit; its shares are ste.csv's") {
  Scratch scratch("ste-pairs");
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r =
      run_command(cli("ste " + (examples / "tip_relief_20_80.toml").string() +
                      " --torque \"100 N*m\" --points 50 --out " + out.string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  // ste.csv: each point's shares, slot by slot.
  const std::string csv = read(out / "ste.csv");
  const std::vector<double> theta = csv_column(csv, "theta1_deg");
  const std::vector<double> pairs = csv_column(csv, "pairs");
  // ste_pairs.csv: blocks of rows, one block per pair, separated by empty lines.
  std::istringstream in(read(out / "ste_pairs.csv"));
  std::string line;
  std::getline(in, line);
  CHECK(line == "pair,pinion_tooth,wheel_tooth,theta1_deg,share,gap_m,stiffness_n_per_m");
  std::vector<double> share_sum(theta.size(), 0.0);
  std::vector<int> rows_at(theta.size(), 0);
  int blocks = 1;
  bool previous_empty = false;
  double previous_theta = -1.0;
  std::string pair;
  while (std::getline(in, line)) {
    if (line.empty()) {
      if (!previous_empty) ++blocks;
      previous_empty = true;
      previous_theta = -1.0;
      continue;
    }
    previous_empty = false;
    std::istringstream row(line);
    std::vector<std::string> cells;
    std::string cell;
    while (std::getline(row, cell, ',')) cells.push_back(cell);
    REQUIRE(cells.size() == 7u);
    // Within a block one pair, at rising angles.
    if (previous_theta < 0.0) pair = cells[0];
    CHECK(cells[0] == pair);
    const double t = std::stod(cells[3]);
    CHECK(t > previous_theta);
    previous_theta = t;
    // The point of ste.csv at this angle (the same 17-digit text, so the same double).
    const auto at = std::find(theta.begin(), theta.end(), t);
    REQUIRE(at != theta.end());
    const std::size_t i = static_cast<std::size_t>(at - theta.begin());
    share_sum[i] += std::stod(cells[4]);
    ++rows_at[i];
  }
  // 20 mesh periods, each pair in contact over about eps_alpha of them: about 20 pairs.
  CHECK(blocks >= 20);
  CHECK(blocks <= 22);
  for (std::size_t i = 0; i < theta.size(); ++i) {
    CAPTURE(theta[i]);
    // Every pair in the segment appears once, and the shares of a point add up to the whole
    // force (the static balance: sum F_k = F).
    CHECK(rows_at[i] == static_cast<int>(pairs[i]));
    CHECK(std::abs(share_sum[i] - 1.0) < 1e-12);
  }
}

TEST_CASE("ste draws one curve where the modifications leave every gap at 0") {
  Scratch scratch("ste-plain");
  const std::filesystem::path file = scratch.dir / "pair.toml";
  write(file, pair_file("tip_relief1 = \"0 mm\"\n"));
  const std::filesystem::path out = scratch.dir / "out";
  const CommandResult r =
      run_command(cli("ste " + file.string() + " --torque \"100 N*m\" --out " + out.string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  for (const char* script : {"ste.gp", "ste_load_sharing.gp"}) {
    CAPTURE(script);
    const std::string text = read(out / script);
    CHECK(text.find("no modifications") != std::string::npos);
    CHECK(text.find("unmodified") == std::string::npos);
  }
  CHECK(read(out / "ste.csv") == read(out / "ste_unmodified.csv"));
}

TEST_CASE("ste refuses bad flags before any work, naming the flag and its range") {
  Scratch scratch("ste-refusals");
  const std::string input = (examples / "tip_relief_20_80.toml").string();
  const std::filesystem::path out = scratch.dir / "out";
  struct Case {
    std::string arguments;
    std::string names;
    std::string allowed;
  };
  for (const Case& c : std::vector<Case>{
           {"--torque \"0 N*m\"", "--torque", "> 0"},
           {"--torque \"-3 N*m\"", "--torque", "> 0"},
           {"--torque 5", "--torque", "N*m"},
           {"--torque \"1 N*m\" --points 1", "--points", "2 to 100000"},
           {"--torque \"1 N*m\" --points 100001", "--points", "2 to 100000"},
       }) {
    const CommandResult r =
        run_command(cli("ste " + input + " " + c.arguments + " --out " + out.string()));
    CHECK_MESSAGE(r.exit_code == 1, c.arguments);
    CHECK_MESSAGE(r.err.find(c.names) != std::string::npos, r.err);
    CHECK_MESSAGE(r.err.find(c.allowed) != std::string::npos, r.err);
    CHECK(r.err.rfind("gearimpact: error: ", 0) == 0);
    CHECK(!std::filesystem::exists(out));
  }
  const CommandResult missing = run_command(cli("ste " + input + " --out " + out.string()));
  CHECK(missing.exit_code == 1);
  CHECK(missing.err.find("--torque") != std::string::npos);
}

TEST_CASE("ste of faulted teeth: each pair on its own table, beside the healthy pair") {
  Scratch scratch("ste-faulted");
  const std::filesystem::path out = scratch.dir / "out";
  // Pinion tooth 3 cracked, tooth 12 missing.
  const CommandResult r =
      run_command(cli("ste " + (examples / "cracked_pinion.toml").string() +
                      " --torque \"20 N*m\" --points 50 --out " + out.string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const std::string summary = read(out / "summary.json");
  CHECK(json_value(summary, "mesh_periods") == 20.0);
  // Where the missing tooth's pair is alone in the segment no pair carries the load: ste_m is
  // empty in those rows, the summary counts them and stderr says so.
  const double uncarried = json_value(summary, "uncarried_points");
  CHECK(uncarried > 0.0);
  CHECK(json_value(summary, "unmodified_uncarried_points") == 0.0);
  CHECK_MESSAGE(r.err.find("missing tooth") != std::string::npos, r.err);
  std::istringstream rows(read(out / "ste.csv"));
  std::string line;
  std::getline(rows, line);
  int empty = 0;
  int total = 0;
  while (std::getline(rows, line)) {
    ++total;
    std::istringstream row(line);
    std::string cell;
    for (int i = 0; i <= 2; ++i) std::getline(row, cell, ',');
    if (cell.empty()) {
      ++empty;
      CHECK(line.find(",12/12") != std::string::npos);
    }
  }
  CHECK(total == 20 * 50);
  CHECK(empty == static_cast<int>(uncarried));
  // The faulted pair's STE beside the healthy one, and its peak above it (a single pair
  // carries the load near its ends where the missing tooth's neighbour would share it).
  CHECK(json_value(summary, "ste_max_m") > json_value(summary, "unmodified_ste_max_m"));
  const std::string gp = read(out / "ste.gp");
  CHECK(gp.find("STE healthy, unmodified") != std::string::npos);
  CHECK(gp.find("STE faulted") != std::string::npos);
}

TEST_CASE("ste refuses what it cannot answer: teeth pressed through each other") {
  Scratch scratch("ste-cannot");
  const std::filesystem::path out = scratch.dir / "out";
  // 1e9 N*m on a 10 mm face: a deflection of metres, past half a base pitch
  // (2 mm pi cos 20 deg / 2 = 2.95 mm), where the teeth have passed through
  // each other.
  const std::string input = (examples / "tip_relief_20_80.toml").string();
  const CommandResult t =
      run_command(cli("ste " + input + " --torque \"1e9 N*m\" --out " + out.string()));
  CHECK(t.exit_code == 1);
  CHECK_MESSAGE(t.err.find("--torque") != std::string::npos, t.err);
  CHECK_MESSAGE(t.err.find("half a base pitch") != std::string::npos, t.err);
  CHECK(!std::filesystem::exists(out));
}

TEST_CASE("[modifications] keys: units read, and refusals name file, line, key and range") {
  Scratch scratch("ste-keys");
  const std::filesystem::path file = scratch.dir / "pair.toml";
  struct Case {
    std::string modifications;
    std::string names;
    std::string allowed;
  };
  for (const Case& c : std::vector<Case>{
           // Outside the active profile of the pinion (tip 44 mm).
           {"tip_relief1 = \"10 um\"\ntip_relief_start1 = \"45 mm\"\n",
            "pair.toml:14: modifications.tip_relief_start1", "44 mm): the active profile"},
           // A relief without its start diameter.
           {"tip_relief2 = \"10 um\"\n", "modifications.tip_relief_start2", "a diameter in ["},
           {"root_relief1 = \"2 mm\"\n", "pair.toml:13: modifications.root_relief1", "1 mm"},
           {"pitch_deviations1 = [\"1 um\", \"2 um\"]\n", "modifications.pitch_deviations1",
            "teeth1 = 20"},
           {"thickness_deviations2 = [\"3 mm\"]\n", "modifications.thickness_deviations2[0]",
            "within 1 mm"},
           {"tip_relief_shape1 = \"cubic\"\n", "modifications.tip_relief_shape1", "\"parabolic\""},
       }) {
    write(file, pair_file(c.modifications));
    const CommandResult r = run_command(cli("check-case " + file.string()));
    CHECK_MESSAGE(r.exit_code == 1, c.modifications);
    CHECK_MESSAGE(r.err.find(c.names) != std::string::npos, r.err);
    CHECK_MESSAGE(r.err.find(c.allowed) != std::string::npos, r.err);
  }
  // A valid file reads back with its values in SI.
  write(file, pair_file("tip_relief1 = \"10 um\"\ntip_relief_start1 = \"43.2 mm\"\n"
                        "tip_relief_shape1 = \"parabolic\"\n"));
  const CommandResult ok = run_command(cli("check-case " + file.string()));
  REQUIRE_MESSAGE(ok.exit_code == 0, ok.err);
  CHECK(ok.out.find("tip_relief1 = \"1e-5 m\"") != std::string::npos);
  CHECK(ok.out.find("tip_relief_shape1 = \"parabolic\"") != std::string::npos);
}

TEST_CASE("simulate runs a case with gaps; sweep samples teeth that differ once per true period") {
  Scratch scratch("ste-simulate");
  const std::filesystem::path file = scratch.dir / "run.toml";
  const std::string base = read(paper_data / "case1.toml");
  write(
      file, base + "\n[modifications]\npitch_deviations2 = [" + [] {
        std::string list;
        for (int i = 0; i < 80; ++i)
          list += std::string(i ? ", " : "") + (i == 3 ? "\"2 um\"" : "\"0 um\"");
        return list;
      }() + "]\n");
  const CommandResult r = run_command(cli("simulate --case-file " + file.string() +
                                          " --set 'integrator.end_time=1 ms' --out " +
                                          (scratch.dir / "series.csv").string()));
  CHECK_MESSAGE(r.exit_code == 0, r.err);
  // Wheel tooth 3 repeats after 80 mesh periods, a wheel revolution: the sweep samples there.
  const CommandResult sweep =
      run_command(cli("sweep " + file.string() +
                      " --vary initial.w1 --from '3000 rad/s' --to '6000 rad/s' --points 2 "
                      "--set model.friction_coefficient=0 --threads 1 --no-plots --out " +
                      (scratch.dir / "sweep").string()));
  REQUIRE_MESSAGE(sweep.exit_code == 0, sweep.err);
  const std::string summary = read(scratch.dir / "sweep" / "summary.json");
  CHECK_MESSAGE(summary.find("\"wheel-revolution\"") != std::string::npos, summary);
}

TEST_CASE("a sweep's quasi-static peak is the relieved pair's own, as ste states it") {
  // Case 2's pair at T1 = 20 N m (balanced by T2 = -80 N m) with both tips relieved by 1 um: the
  // single pair's STE before a pair enters, about 1.8 um, passes the entering pair's gap, so the
  // entry still jumps, by less than the unrelieved pair's K_after / K_before.
  Scratch scratch("ste-sweep-peak");
  const std::filesystem::path file = scratch.dir / "run.toml";
  std::string text = read(paper_data / "case2.toml");
  const auto replace = [&text](const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    text.replace(at, from.size(), to);
  };
  replace("value = \"50 kgf*mm\"", "value = \"20 N*m\"");
  replace("value = \"-50 kgf*mm\"", "value = \"-80 N*m\"");
  write(file, text +
                  "\n[modifications]\ntip_relief1 = \"1 um\"\ntip_relief_start1 = \"43.2 mm\"\n"
                  "tip_relief2 = \"1 um\"\ntip_relief_start2 = \"163.2 mm\"\n");
  const CommandResult ste =
      run_command(cli("ste " + file.string() + " --torque '20 N*m' --no-plots --out " +
                      (scratch.dir / "ste").string()));
  REQUIRE_MESSAGE(ste.exit_code == 0, ste.err);
  const double relieved = json_value(ste.out, "quasi_static_force_ratio");
  const double unrelieved = json_value(ste.out, "unmodified_quasi_static_force_ratio");
  CHECK(relieved > 1.0);
  CHECK(relieved < unrelieved);
  const CommandResult sweep =
      run_command(cli("sweep " + file.string() +
                      " --vary initial.w1 --from '3000 rad/s' --to '6000 rad/s' --points 2 "
                      "--direction up --set model.friction_coefficient=0 --set "
                      "model.mesh_damping_ratio=0.05 --damping-update off --threads 1 --no-plots "
                      "--out " +
                      (scratch.dir / "sweep").string()));
  REQUIRE_MESSAGE(sweep.exit_code == 0, sweep.err);
  const std::string summary = read(scratch.dir / "sweep" / "summary.json");
  // One function of the same pair, load and table, both printed to 17 digits: the same number.
  CHECK(json_value(summary, "quasi_static_force_ratio") == relieved);
}
