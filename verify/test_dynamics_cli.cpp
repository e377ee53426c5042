// The `simulate` and `sweep-friction` subcommands of the reference program:
// their outputs carry the columns and keys issue 5 names, in full precision.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct Output {
  int status;
  std::string text;
};

// Runs the program with `arguments`, stdout (and stderr, when asked) captured.
Output run_cli(const std::string& arguments, bool with_stderr = false) {
  const std::string command =
      std::string(GEARIMPACT_CLI) + " " + arguments + (with_stderr ? " 2>&1" : "");
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string text;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) {
    text += buffer.data();
  }
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

}  // namespace

TEST_CASE("simulate writes the time series and prints the JSON summary") {
  const std::filesystem::path out =
      std::filesystem::temp_directory_path() / "gearimpact_test_simulate.csv";
  std::filesystem::remove(out);
  const Output r = run_cli("simulate --case 2 --t-end 0.002 --every 100 --out " + out.string());
  REQUIRE(r.status == 0);
  for (const char* key :
       {"\"impacts_n1\"", "\"impacts_n2\"", "\"last_n2_impact_s\"", "\"damping_loss_J\"",
        "\"friction_loss_J\"", "\"hertz_energy_max_J\"", "\"bending_energy_max_J\"",
        "\"axial_energy_max_J\"", "\"ledger_residual_J\"", "\"steps\""}) {
    CAPTURE(key);
    CHECK(r.text.find(key) != std::string::npos);
  }
  CHECK(r.text.find("nan") == std::string::npos);
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
  const Output r = run_cli("simulate --case 1 --dt 1e-5", true);
  CHECK(r.status != 0);
  CHECK(r.text.find("step") != std::string::npos);
  CHECK(r.text.find("20 steps per period") != std::string::npos);
}

TEST_CASE("sweep-friction prints f and the three ratios") {
  const Output r = run_cli("sweep-friction --from 0.02 --to 0.04 --step 0.02 --t-end 0.001");
  REQUIRE(r.status == 0);
  std::istringstream lines(r.text);
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
