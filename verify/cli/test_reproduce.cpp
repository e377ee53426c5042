// End to end: `gearimpact reproduce` writes every figure of the paper with its
// data and plot, and a REPORT.md in which no statement fails unexplained and
// the default reading is the one the evidence supports.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.hpp"

using namespace gearimpact::verify;

TEST_CASE("reproduce: every figure, its data, and REPORT.md with no unexplained failure") {
  const std::filesystem::path out = std::filesystem::temp_directory_path() /
                                    ("gearimpact-reproduce-" + std::to_string(::getpid()));
  std::filesystem::remove_all(out);
  const CommandResult r = run_command(cli("reproduce --out " + out.string()));
  CAPTURE(r.err);
  REQUIRE(r.exit_code == 0);
  const std::vector<std::string> figures{"fig4a_case1_relative_displacement",
                                         "fig4b_case1_angular_displacements",
                                         "fig4c_case1_angular_velocities",
                                         "fig5a_case2_relative_displacement",
                                         "fig5b_case2_angular_velocities",
                                         "fig6a_case3_relative_displacement",
                                         "fig6b_case3_angular_velocities",
                                         "fig7_friction_sweep",
                                         "fig8_energy_ratios",
                                         "fig8_energy_ratios_flipped_moment",
                                         "steady_state_dynamic_factor",
                                         "steady_state_regimes",
                                         "rattle_map"};
  for (const std::string& figure : figures) {
    for (const char* extension : {".png", ".svg", ".gp"}) {
      const std::filesystem::path file = out / (figure + extension);
      CAPTURE(file);
      CHECK(std::filesystem::exists(file));
      CHECK(std::filesystem::file_size(file) > 100);
    }
  }
  for (const char* data :
       {"case1_time_series.csv", "case2_time_series.csv", "case3_time_series.csv",
        "case1_summary.json", "case2_summary.json", "case3_summary.json", "fig7_friction_sweep.csv",
        "fig8_energy_ratios.csv", "fig8_energy_ratios_flipped_moment.csv", "steady_state.csv",
        "steady_state_iso_kv_band.csv", "rattle_map.csv", "rattle_boundary.csv"}) {
    CAPTURE(data);
    CHECK(std::filesystem::exists(out / data));
  }
  std::ifstream in(out / "REPORT.md");
  std::stringstream text;
  text << in.rdbuf();
  const std::string report = text.str();
  CHECK(report.find("unexplained failures: 0") != std::string::npos);
  CHECK(report.find("| FAIL |") == std::string::npos);
  CHECK(report.find("Verdict: the default stands.") != std::string::npos);
  // The steady-state section with its table, and its sweep: 41 speeds up and 41 down.
  CHECK(report.find("## Steady state of the loaded pair") != std::string::npos);
  CHECK(report.find("| dynamic factor at N = 1 |") != std::string::npos);
  CHECK(report.find("## Rattle of a loose gear (an extension)") != std::string::npos);
  std::ifstream steady(out / "steady_state.csv");
  std::stringstream steady_text;
  steady_text << steady.rdbuf();
  const std::string csv = steady_text.str();
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 2 * 41);
  // No temporary files (hidden siblings) are left behind by the atomic writes.
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    CHECK(entry.path().filename().string().front() != '.');
  }
  std::filesystem::remove_all(out);
}
