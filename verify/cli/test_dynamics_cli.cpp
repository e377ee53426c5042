// The `simulate` and `sweep-friction` subcommands of the reference program:
// their outputs carry the columns and keys docs/case-files.md names, in full precision.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

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
  CHECK(r.err.find("<= 2.28") != std::string::npos);
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

namespace {

std::string paper_case_file_with(const std::string& key_line) {
  std::ifstream in(std::string(GEARIMPACT_PAPER_DATA_DIR) + "/case1.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string toml = text.str();
  const std::string key = key_line.substr(0, key_line.find(' '));
  const std::size_t at = toml.find("\n" + key + " = ");
  REQUIRE(at != std::string::npos);
  toml.replace(at + 1, toml.find('\n', at + 1) - at - 1, key_line);
  return toml;
}

int line_count(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace

TEST_CASE("every out-of-range option value is refused, naming the option and its range") {
  struct Bad {
    const char* arguments;
    const char* named;    // the option as typed
    const char* allowed;  // part of the allowed range
  };
  for (const Bad& bad : {
           Bad{"simulate --case 1 --t-end 0", "--t-end = 0", "a time > 0 s"},
           Bad{"simulate --case 1 --t-end -2ms", "--t-end = -2ms", "a time > 0 s"},
           Bad{"simulate --case 1 --t-end 2furlong", "--t-end",
               "unknown unit 'furlong' for a time"},
           Bad{"simulate --case 1 --dt -1", "--dt = -1", "a time > 0 s"},
           Bad{"simulate --case 1 --dt 1e-5", "--dt = 1e-5", "20 steps per period"},
           Bad{"simulate --case 1 --t-end 1000", "--t-end", "at most 2e9 steps"},
           Bad{"simulate --case 1 --friction -0.1", "--friction = -0.1", "[0, 1]"},
           Bad{"simulate --case 1 --rtol 7", "--rtol = 7", "[1e-14, 1e-3]"},
           Bad{"simulate --case 1 --rtol 5e-3", "--rtol = 5e-3", "[1e-14, 1e-3]"},
           Bad{"simulate --case 1 --restitution-exponent 2", "--restitution-exponent = 2",
               "(0, 1]"},
           Bad{"simulate --case 3 --case3-frequency nan", "--case3-frequency = nan", ">= 0 rad/s"},
           Bad{"simulate --case 1 --every 0", "--every = 0", "an integer in [1, 2147483647]"},
           Bad{"simulate --case 1 --every 2.5", "--every = 2.5", "an integer in [1, 2147483647]"},
           Bad{"simulate --case 1 --integrator euler", "--integrator = euler", "\"adaptive\""},
           Bad{"simulate --case 1 --speed-unit 0", "--speed-unit = 0", "a speed > 0 m/s"},
           Bad{"simulate --case 1 --damping-stiffness pear", "--damping-stiffness = pear",
               "\"current-pair\""},
           Bad{"simulate --case 1 --set integrator.end_time=0", "--set integrator.end_time = 0",
               "a time > 0 s"},
           Bad{"simulate --case 1 --set no.key=1", "--set = no.key=1", "gearimpact schema"},
           Bad{"simulate --case 1 --set gears.modul=3mm", "--set = gears.modul=3mm",
               "did you mean --set gears.module=3mm?"},
           Bad{"simulate --case 1 --set integrator.end_time", "--set = integrator.end_time",
               "section.key=value"},
           Bad{"simulate --case 1 --t-end 1ms --set integrator.end_time=2ms",
               "--set integrator.end_time = 2ms", "already set by --t-end"},
           Bad{"simulate --case-file " GEARIMPACT_PAPER_DATA_DIR "/case1.toml --torque-unit n-mm",
               "--torque-unit = n-mm", "only with --case"},
           Bad{"sweep-friction --from -0.01", "--from = -0.01", "[0, 1]"},
           Bad{"sweep-friction --to nan", "--to = nan", "[0, 1]"},
           Bad{"sweep-friction --from 0.05 --to 0.01", "--to", ">= from"},
           Bad{"sweep-friction --step 0", "--step", "> 0"},
           Bad{"sweep-friction --step 1e-9", "--step", "(to - from) / 1e5"},
           Bad{"sweep-friction --threads -1", "--threads = -1", "an integer in [0, 1024]"},
           Bad{"sweep-friction --threads 2000", "--threads = 2000", "an integer in [0, 1024]"},
           Bad{"sweep-friction --t-end 0", "--t-end = 0", "a time > 0 s"},
       }) {
    CAPTURE(bad.arguments);
    const CommandResult r = run_command(cli(bad.arguments));
    CHECK(r.exit_code == 1);
    CHECK(r.out.empty());
    CHECK(r.err.find(std::string("gearimpact: error: ") + bad.named) != std::string::npos);
    // A unit is refused for what it is, not for where it lies.
    const bool unit = std::string(bad.allowed).rfind("unknown unit", 0) == 0;
    CHECK(r.err.find(unit ? ": unknown unit '" : " is outside the allowed range") !=
          std::string::npos);
    CHECK(r.err.find(bad.allowed) != std::string::npos);
  }
}

TEST_CASE("a case file's run refused for a key an option set names the option, as with --case") {
  // The run is checked once (check_run), every refusal named by the option that set its key: the
  // planar keys' refusals too (here the tacho, which rigid bearings refuse), which named the
  // case-file key with a case file before.
  for (const std::string& source :
       {std::string("--case 1"),
        std::string("--case-file " GEARIMPACT_PAPER_DATA_DIR "/case1.toml")}) {
    CAPTURE(source);
    const CommandResult r =
        run_command(cli("simulate " + source + " --set tacho.pulses_per_revolution=1"));
    CHECK(r.exit_code == 1);
    CHECK(r.out.empty());
    CHECK(r.err.find("gearimpact: error: --set tacho.pulses_per_revolution = 1: a tacho with "
                     "[bearings] kind = \"elastic\" only") != std::string::npos);
  }
}

TEST_CASE("option values with units, --set and the old spellings give the same run") {
  const CommandResult plain = run_command(cli("simulate --case 2 --t-end 0.002 --dt 1e-7"));
  REQUIRE(plain.exit_code == 0);
  for (const char* same : {"--t-end 2ms --dt \"0.1 us\"", "--set integrator.end_time=2ms",
                           "--t-end 0.002 --set integrator.step=100ns"}) {
    CAPTURE(same);
    const CommandResult r = run_command(cli(std::string("simulate --case 2 ") + same));
    REQUIRE(r.exit_code == 0);
    CHECK(r.out == plain.out);
    CHECK(r.err.empty());
  }
  // Old command-line spellings of case-file names: the same run, one line of
  // notice each on stderr naming the case-file spelling.
  const std::string now =
      "simulate --case 2 --t-end 0.002 --damping-stiffness pitch-pair-at-impact "
      "--coast-phase half-base-pitch --speed-unit \"1 in/s\"";
  const std::string old =
      "simulate --case 2 --t-end 0.002 --damping-stiffness pitch-pair --coast-phase half-pitch "
      "--speed-unit in/s";
  const CommandResult new_names = run_command(cli(now));
  const CommandResult old_names = run_command(cli(old));
  REQUIRE(new_names.exit_code == 0);
  REQUIRE(old_names.exit_code == 0);
  CHECK(old_names.out == new_names.out);
  CHECK(new_names.out != plain.out);
  CHECK(line_count(old_names.err) == 3);
  for (const char* notice : {"\"pitch-pair-at-impact\"", "\"half-base-pitch\"", "\"1 in/s\""}) {
    CHECK(old_names.err.find(notice) != std::string::npos);
  }
  // A flag given with a case file overrides the file: a different run.
  const std::string file = std::string(GEARIMPACT_PAPER_DATA_DIR) + "/case2.toml";
  const CommandResult file_run = run_command(cli(
      "simulate --case-file " + file + " " + now.substr(std::string("simulate --case 2").size())));
  REQUIRE(file_run.exit_code == 0);
  CHECK(file_run.out == new_names.out);
}

TEST_CASE("check-case and simulate --case-file refuse the same file with the same message") {
  // The two ranges the validators used to disagree on: check-case accepted
  // these and simulate refused them, without the file's line.
  for (const char* line : {"restitution_exponent = 2.0", "relative_tolerance = 5e-3"}) {
    CAPTURE(line);
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / "gearimpact_test_one_range.toml";
    std::ofstream(file) << paper_case_file_with(line);
    const CommandResult check = run_command(cli("check-case " + file.string()));
    const CommandResult run = run_command(cli("simulate --case-file " + file.string()));
    CHECK(check.exit_code == 1);
    CHECK(run.exit_code == 1);
    CHECK(check.err == run.err);
    CHECK(check.err.find(file.string() + ":") != std::string::npos);
    const std::string key = std::string(line).substr(0, std::string(line).find(' '));
    CHECK(check.err.find("." + key + " = ") != std::string::npos);
    std::filesystem::remove(file);
  }
}

TEST_CASE("simulate of a driven case writes its impacts and their histogram beside --out") {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "gearimpact_test_rattle_files";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::filesystem::path case_file = dir / "rattle.toml";
  std::ofstream(case_file)
      << "[gears]\nteeth1 = 20\nteeth2 = 40\nmodule = \"2 mm\"\npressure_angle = \"20 deg\"\n"
         "face_width = \"10 mm\"\nyoungs_modulus = \"206 GPa\"\npoisson_ratio = 0.3\n"
         "density = \"7800 kg/m^3\"\nbacklash = \"0.05 mm\"\n[torque1]\nkind = "
         "\"prescribed-speed\"\nmean_speed = \"1000 rpm\"\norders = [2]\nspeed_amplitudes = "
         "[\"20 rad/s\"]\nphases = [\"0 deg\"]\n[torque2]\nkind = \"drag\"\ndrag_constant = "
         "\"0.05 N*m\"\ndrag_viscous = \"0 N*m*s/rad\"\n[initial]\nw1 = \"1000 rpm\"\nw2 = \"500 "
         "rpm\"\n[integrator]\nstep = "
         "\"1 us\"\nend_time = \"20 ms\"\n";
  const std::string base = "simulate --case-file " + case_file.string() + " --out ";
  const CommandResult r = run_command(cli(base + (dir / "series.csv").string()));
  REQUIRE(r.exit_code == 0);
  const auto number = [&](const std::string& key) {
    const std::size_t at = r.out.find("\"" + key + "\": ");
    REQUIRE(at != std::string::npos);
    return std::stod(r.out.substr(at + key.size() + 4));
  };
  const double impacts =
      (number("rattle_impacts_per_s_n1") + number("rattle_impacts_per_s_n2")) * 0.02;
  const auto lines = [](const std::filesystem::path& path) {
    std::ifstream in(path);
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);) rows.push_back(line);
    return rows;
  };
  const std::vector<std::string> rows = lines(dir / "rattle_impacts.csv");
  REQUIRE(!rows.empty());
  CHECK(rows.front() == "t_s,flank,impact_speed_m_s");
  // The summary's rates times the duration: whole impacts, to rounding.
  CHECK(impacts > 2.0);
  CHECK(std::fabs(static_cast<double>(rows.size() - 1) - impacts) <= 1e-9 * impacts);
  const std::vector<std::string> bins = lines(dir / "rattle_impacts_histogram.csv");
  REQUIRE(!bins.empty());
  CHECK(bins.front() == "lower_m_s,upper_m_s,count_n1,count_n2,count");
  long long counted = 0;
  for (std::size_t i = 1; i < bins.size(); ++i) {
    counted += std::stoll(bins[i].substr(bins[i].rfind(',') + 1));
  }
  CHECK(counted == static_cast<long long>(rows.size() - 1));
  // The series may not take a name the impacts take.
  const CommandResult clash = run_command(cli(base + (dir / "rattle_impacts.csv").string()));
  CHECK(clash.exit_code != 0);
  CHECK(clash.err.find("--out") != std::string::npos);
  CHECK(clash.err.find("rattle_impacts_histogram.csv") != std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("the spalled example passes check-case without a warning") {
  const std::filesystem::path example =
      std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples" / "spall_20_80.toml";
  const CommandResult check = run_command(cli("check-case " + example.string()));
  CHECK(check.exit_code == 0);
  CHECK(check.out.find("valid") != std::string::npos);
  CHECK(check.out.find("kind = \"spall\"") != std::string::npos);
  // Balanced torques and rolling speeds: nothing to warn about.
  CHECK(check.err.empty());
}

TEST_CASE("check-case on a planar example says what runs it: the period map included") {
  const std::filesystem::path example =
      std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "examples" / "rig_17_38.toml";
  const CommandResult check = run_command(cli("check-case " + example.string()));
  CHECK(check.exit_code == 0);
  const std::size_t note = check.out.find("# note: elastic bearings");
  REQUIRE(note != std::string::npos);
  const std::string line = check.out.substr(note, check.out.find('\n', note) - note);
  CHECK(line.find("period map (shooting, Floquet multipliers, continuation)") != std::string::npos);
  CHECK(line.find("refuses") == std::string::npos);
}

TEST_CASE("the mesh damper's loss is its own term of the summary, and the ledger closes with it") {
  // The run of the summary's example: no Hertzian damping (damping_loss_J 0),
  // the viscous mesh damper dissipates instead. Its loss is
  // mesh_damper_loss_J; the printed terms close the ledger to its residual.
  const auto closure = [](const nlohmann::json& j, bool planar) {
    double sum =
        j.at("kinetic_energy_final_J").get<double>() + j.at("stored_energy_final_J").get<double>() -
        j.at("kinetic_energy_initial_J").get<double>() -
        j.at("stored_energy_initial_J").get<double>() - j.at("torque_work_J").get<double>() +
        j.at("damping_loss_J").get<double>() + j.at("friction_loss_J").get<double>() +
        j.at("mesh_damper_loss_J").get<double>() - j.at("parametric_work_J").get<double>();
    if (planar) {
      sum += j.at("bearing_energy_final_J").get<double>() -
             j.at("bearing_energy_initial_J").get<double>() +
             j.at("bearing_damping_loss_J").get<double>() +
             j.at("shaft_energy_final_J").get<double>() -
             j.at("shaft_energy_initial_J").get<double>() +
             j.at("shaft_damping_loss_J").get<double>();
    }
    return sum;
  };
  const std::string damped =
      " --t-end '5 ms' --set model.damping_update=off --set model.mesh_damping_ratio=0.05";
  for (const bool planar : {false, true}) {
    CAPTURE(planar);
    const std::string bearings =
        planar ? " --set bearings.kind=elastic --set 'bearings.stiffness_x1=5e8 N/m' --set "
                 "'bearings.stiffness_x2=5e8 N/m'"
               : "";
    const CommandResult r = run_command(cli("simulate --case 2" + damped + bearings));
    REQUIRE(r.exit_code == 0);
    const nlohmann::json j = nlohmann::json::parse(r.out);
    const double loss = j.at("mesh_damper_loss_J").get<double>();
    const double scale = j.at("ledger_scale_J").get<double>();
    const double residual = j.at("ledger_residual_J").get<double>();
    MESSAGE(std::string(planar ? "planar" : "torsional")
            << ": mesh damper loss " << loss << " J, damping loss "
            << j.at("damping_loss_J").get<double>() << " J, closure " << closure(j, planar)
            << " J, residual " << residual << " J of " << scale << " J");
    CHECK(j.at("damping_loss_J").get<double>() == 0.0);
    // The terms as printed (17 digits) sum to the run's own residual but for
    // the rounding of a few sums of terms of the scale's size.
    CHECK(std::fabs(closure(j, planar) - residual) < 1e-12 * scale);
    // The ledger's bound (test_dynamics), and a loss standing far above it.
    CHECK(std::fabs(residual) < 1e-7 * scale);
    CHECK(loss > 100.0 * 1e-7 * scale);
  }
  // Without a damper the key is left out (the other summaries keep their bytes).
  const CommandResult plain = run_command(cli("simulate --case 2 --t-end '1 ms'"));
  REQUIRE(plain.exit_code == 0);
  CHECK(plain.out.find("mesh_damper_loss_J") == std::string::npos);
}

TEST_CASE(
    "a friction smoothing speed the step cannot resolve, or one that removes friction, is "
    "refused") {
  // Case 2 at the default step 1e-7 s: Rb1 |w1| (|w1| + |w2|) at w1 = 50,
  // w2 = 0 rad/s, Rb1 = 20 mm cos 20 deg, is 46.98 m/s^2, so v_s must be
  // at least 10 h of it, 4.698e-05 m/s.
  const CommandResult coarse =
      run_command(cli("simulate --case 2 --set 'model.friction_smoothing_speed=1e-5 m/s'"));
  CHECK(coarse.exit_code == 1);
  CHECK(coarse.err.find("model.friction_smoothing_speed") != std::string::npos);
  CHECK(coarse.err.find(">= 4.698e-05 m/s") != std::string::npos);
  CHECK(coarse.out.empty());
  const CommandResult huge =
      run_command(cli("simulate --case 2 --set 'model.friction_smoothing_speed=1e300 m/s'"));
  CHECK(huge.exit_code == 1);
  CHECK(huge.err.find("model.friction_smoothing_speed") != std::string::npos);
  CHECK(huge.err.find("0.1 m/s") != std::string::npos);
  CHECK(huge.out.empty());
  // A smaller step resolves the same v_s; a resolvable v_s runs at the default step.
  CHECK(run_command(cli("simulate --case 2 --t-end '0.2 ms' --dt 1e-8 --set "
                        "'model.friction_smoothing_speed=1e-5 m/s'"))
            .exit_code == 0);
  CHECK(run_command(cli("simulate --case 2 --t-end '0.2 ms' --set "
                        "'model.friction_smoothing_speed=1e-4 m/s'"))
            .exit_code == 0);
}
