// The `simulate` and `sweep-friction` subcommands of the reference program:
// their outputs carry the columns and keys issue 5 names, in full precision.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "run_command.hpp"

using gearimpact::verify::cli;
using gearimpact::verify::CommandResult;
using gearimpact::verify::run_command;

TEST_CASE("simulate writes the time series and prints the JSON summary") {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / "gearimpact_test_simulate.csv";
  std::filesystem::remove(out);
  const CommandResult r =
      run_command(cli("simulate --case 2 --t-end 0.002 --every 100 --out " + out.string()));
  REQUIRE(r.exit_code == 0);
  for (const char* key :
       {"\"impacts_n1\"", "\"impacts_n2\"", "\"last_n2_impact_s\"", "\"damping_loss_J\"",
        "\"friction_loss_J\"", "\"hertz_energy_max_J\"", "\"bending_energy_max_J\"",
        "\"axial_energy_max_J\"", "\"ledger_residual_J\"", "\"steps\""}) {
    CAPTURE(key);
    CHECK(r.out.find(key) != std::string::npos);
  }
  CHECK(r.out.find("nan") == std::string::npos);
  std::ifstream in(out);
  REQUIRE(in.good());
  std::string header;
  std::getline(in, header);
  CHECK(header ==
        "t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,s_m,delta_m,region,pairs,normal_force_N,"
        "friction_force_N");
  int rows = 0;
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    ++rows;
    last = line;
  }
  // 0.002 s / 1e-7 s = 20000 steps, every 100th kept, plus t = 0.
  CHECK(rows == 201);
  CHECK(last.rfind("0.002,", 0) == 0);
  // Full precision, not printf's default 6 digits: w1 after impacts is not a
  // short decimal, so its %.17g form carries 17 digits (16 with a trailing zero dropped).
  std::string field = last;
  for (int i = 0; i < 3; ++i) field = field.substr(field.find(',') + 1);
  field = field.substr(0, field.find(','));
  const auto digits =
      std::count_if(field.begin(), field.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
  CHECK(digits >= 15);
  std::filesystem::remove(out);
}

TEST_CASE("simulate refuses a step that does not resolve contact, naming the limit") {
  const CommandResult r = run_command(cli("simulate --case 1 --dt 1e-5"));
  CHECK(r.exit_code != 0);
  CHECK(r.err.find("step") != std::string::npos);
  CHECK(r.err.find("20 steps per period") != std::string::npos);
}

TEST_CASE("sweep-friction prints f and the three ratios") {
  const CommandResult r =
      run_command(cli("sweep-friction --from 0.02 --to 0.04 --step 0.02 --t-end 0.001"));
  REQUIRE(r.exit_code == 0);
  std::istringstream lines(r.out);
  std::string line;
  std::getline(lines, line);
  CHECK(line == "f,ratio_case1,ratio_case2,ratio_case3");
  int rows = 0;
  while (std::getline(lines, line)) {
    ++rows;
    CHECK(std::count(line.begin(), line.end(), ',') == 3);
  }
  CHECK(rows == 2);
}

TEST_CASE("simulate --case-file runs a case file: the paper's files give the --case results") {
  // paper_data/caseN.toml is Table 1 written by hand in the file's units;
  // paper_case(N) is the same table in code. The runs must agree to the bit.
  for (int n = 1; n <= 3; ++n) {
    CAPTURE(n);
    const std::string file =
        std::string(GEARIMPACT_PAPER_DATA_DIR) + "/case" + std::to_string(n) + ".toml";
    const CommandResult from_file =
        run_command(cli("simulate --case-file " + file + " --t-end 0.002"));
    const CommandResult from_table =
        run_command(cli("simulate --case " + std::to_string(n) + " --t-end 0.002"));
    REQUIRE(from_file.exit_code == 0);
    CHECK(from_file.out == from_table.out);
  }
  const CommandResult both = run_command(cli("simulate --case 1 --case-file x.toml"));
  CHECK(both.exit_code != 0);
  const CommandResult neither = run_command(cli("simulate"));
  CHECK(neither.exit_code != 0);
  CHECK(neither.err.find("--case-file") != std::string::npos);
}

TEST_CASE("a case file whose step cannot resolve the contact is refused at its line") {
  std::ifstream in(std::string(GEARIMPACT_PAPER_DATA_DIR) + "/case1.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string toml = text.str();
  const std::size_t at = toml.find("step = ");
  REQUIRE(at != std::string::npos);
  toml.replace(at, toml.find('\n', at) - at, "step = \"5 us\"");
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "gearimpact_test_big_step.toml";
  std::ofstream(file) << toml;
  const CommandResult r = run_command(cli("simulate --case-file " + file.string()));
  CHECK(r.exit_code == 1);
  CHECK(r.err.find(file.string() + ":") != std::string::npos);
  CHECK(r.err.find("integrator.step = \"5 us\"") != std::string::npos);
  // The largest resolving step of the paper's pair is 1/20 of the period of
  // its stiffest contact, about 2.3 us: the message states it.
  CHECK(r.err.find("(0, 2.28") != std::string::npos);
  std::filesystem::remove(file);
}

TEST_CASE("the same case gives a bit-identical CSV on repeated runs") {
  const std::filesystem::path a = std::filesystem::temp_directory_path() / "gearimpact_det_a.csv";
  const std::filesystem::path b = std::filesystem::temp_directory_path() / "gearimpact_det_b.csv";
  REQUIRE(run_command(cli("simulate --case 3 --t-end 0.003 --out " + a.string())).exit_code == 0);
  REQUIRE(run_command(cli("simulate --case 3 --t-end 0.003 --out " + b.string())).exit_code == 0);
  const auto read = [](const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  const std::string first = read(a);
  CHECK(first.size() > 1000);
  CHECK(first == read(b));
  std::filesystem::remove(a);
  std::filesystem::remove(b);
}
