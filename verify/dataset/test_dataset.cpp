// Data sets (docs/datasets.md): the spec's plan and labels, the design's strata, refusals before
// any work, SHA-256 against FIPS 180-4's examples, and the program end to end: a set run whole,
// in two or five shards and merged, and killed then resumed gives the same bytes in every record;
// the anti-alias decimator's record against anti_alias_resample of the undecimated record.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "gearimpact/constants.hpp"
#include "gearimpact/dataset/run.hpp"
#include "gearimpact/dataset/spec.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/mat_image.hpp"
#include "gearimpact/io/npz_image.hpp"
#include "gearimpact/io/sha256.hpp"
#include "gearimpact/signals/decimate.hpp"
#include "run_command.hpp"
#include "scratch.hpp"
// After the library's headers: signal.h defines si_value, a parameter's name there.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace gearimpact;
using gearimpact::verify::cli;
using gearimpact::verify::run_command;
using gearimpact::verify::Scratch;

namespace {

const fs::path kHere = GEARIMPACT_DATASET_TEST_DIR;

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string six_text() {
  return read(kHere / "six.toml");
}

dataset::DatasetSpec spec_of(const std::string& text) {
  return dataset::parse_spec(text, kHere, "six.toml");
}

// The refusal's text of a spec (empty when accepted).
std::string refusal(const std::string& text, const dataset::Bounds& bounds = {}) {
  try {
    dataset::make_plan(spec_of(text), bounds);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("sha256_hex: FIPS 180-4's examples") {
  CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(sha256_hex(std::string(1000000, 'a')) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("the plan of six records: conditions, labels and splits from the spec's values") {
  const dataset::Plan plan = dataset::make_plan(spec_of(six_text()));
  REQUIRE(plan.records.size() == 6);
  REQUIRE(plan.conditions.size() == 6);
  CHECK(plan.samples_per_record == 1000);  // 50 ms at 20 kHz
  // The grid, last factor fastest; 1 rpm = 2 pi / 60 rad/s, 1 mm = 1e-3 m.
  const double speeds[] = {2400.0 * 2.0 * pi / 60.0, 1800.0 * 2.0 * pi / 60.0};
  const double depths[] = {0.2e-3, 0.6e-3, 1e-3};
  for (std::size_t c = 0; c < 6; ++c) {
    const dataset::Condition& k = plan.conditions[c];
    const double w = speeds[c / 3];
    const double q = depths[c % 3];
    CHECK(std::abs(k.values[0] / w - 1.0) < 1e-15);  // a unit's factor: rounding
    CHECK(k.values[1] == q);
    // The labels are the case's keys: the controller's reference and the crack depth.
    CHECK(k.simulation_case.torque1.mean_speed_rad_per_s == k.values[0]);
    CHECK(k.simulation_case.faults.at(0).state.crack.depth_m == k.values[1]);
    // The pair starts rolling at the reference.
    CHECK(k.simulation_case.initial.w1_rad_per_s == k.values[0]);
    CHECK(k.split == (c < 3 ? "train" : "test"));
  }
  // Seeds depend on (set seed, condition, replicate) only, and differ.
  std::set<std::uint64_t> seeds;
  for (const dataset::Record& r : plan.records) {
    CHECK(r.seed == dataset::record_seed(7, r.condition, r.replicate));
    seeds.insert(r.seed);
  }
  CHECK(seeds.size() == 6);
}

TEST_CASE("a Latin hypercube puts each factor's values once in each stratum") {
  const std::string text = replaced(
      replaced(replaced(six_text(), "levels = [\"2400 rpm\", \"1800 rpm\"]",
                        "range = [\"1500 rpm\", \"2500 rpm\"]"),
               "levels = [\"0.2 mm\", \"0.6 mm\", \"1 mm\"]", "range = [\"0.1 mm\", \"1.2 mm\"]"),
      "[[split.heldout]]\nkey = \"torque1.mean_speed\"\nlevels = [\"1800 rpm\"]",
      "[design]\nkind = \"latin-hypercube\"\npoints = 7");
  const dataset::Plan plan = dataset::make_plan(spec_of(text));
  REQUIRE(plan.conditions.size() == 7);
  const double low[] = {1500.0 * 2.0 * pi / 60.0, 0.1e-3};
  const double high[] = {2500.0 * 2.0 * pi / 60.0, 1.2e-3};
  for (std::size_t i = 0; i < 2; ++i) {
    std::set<int> strata;
    for (const dataset::Condition& c : plan.conditions) {
      const double u = (c.values[i] - low[i]) / (high[i] - low[i]);
      strata.insert(static_cast<int>(std::floor(u * 7.0)));
    }
    CHECK(strata == std::set<int>{0, 1, 2, 3, 4, 5, 6});
  }
}

TEST_CASE("a bad spec is refused before any work, naming the key as written and its range") {
  SUBCASE("a key that does not exist") {
    const std::string e =
        refusal(replaced(six_text(), "\"faults[0].depth\"", "\"faults[0].dept\""));
    CHECK(e.find("factors[1].key = faults[0].dept") != std::string::npos);
    CHECK(e.find("depth") != std::string::npos);
    const std::string e2 =
        refusal(replaced(six_text(), "\"torque1.mean_speed\"", "\"torque1.mean_sped\""));
    CHECK(e2.find("did you mean torque1.mean_speed") != std::string::npos);
  }
  SUBCASE("a level outside its range, named with the condition") {
    const std::string e = refusal(replaced(six_text(), "\"1 mm\"]", "\"9 mm\"]"));
    CHECK(e.find("faults[0].depth = 9 mm") != std::string::npos);
    CHECK(e.find("q <") != std::string::npos);  // the admissible depth
    const std::string e2 = refusal(replaced(six_text(), "\"30 dB\"", "\"300 dB\""));
    CHECK(e2.find("recorder.noise_snr = 300 dB") != std::string::npos);
    CHECK(e2.find("[-100, 200]") != std::string::npos);
  }
  SUBCASE("a fault the base case does not have") {
    const std::string e =
        refusal(replaced(six_text(), "\"faults[0].depth\"", "\"faults[1].depth\""));
    CHECK(e.find("faults[1].depth") != std::string::npos);
    CHECK(e.find("1 [[faults]] table") != std::string::npos);
  }
  SUBCASE("a bound, with the estimate") {
    dataset::Bounds bounds;
    bounds.max_records = 5;
    const std::string e = refusal(six_text(), bounds);
    CHECK(e.find("records = 6") != std::string::npos);
    CHECK(e.find("max_records lifts the bound") != std::string::npos);
    bounds = {};
    bounds.max_bytes = 1e5;
    const std::string e2 = refusal(six_text(), bounds);
    CHECK(e2.find("bytes = ") != std::string::npos);
    CHECK(e2.find("max_bytes lifts the bound") != std::string::npos);
  }
}

namespace {

// The records' bytes of a folder, by name.
std::map<std::string, std::string> records_in(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".h5") files[entry.path().filename()] = read(entry.path());
  }
  return files;
}

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

}  // namespace

TEST_CASE(
    "the program: whole, two shards (one on two threads) merged, five shards merged, and killed "
    "then resumed give the same bytes") {
  Scratch scratch("dataset");
  const fs::path spec = kHere / "six.toml";
  const fs::path whole = scratch.dir / "whole";
  const auto run = [&](const std::string& args) {
    const auto r = run_command(cli("dataset " + quoted(spec) + " " + args + " --quiet"));
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
  };
  // The program names its flag, before any work.
  const auto bounded =
      run_command(cli("dataset " + quoted(spec) + " --out " + quoted(whole) + " --max-records 5"));
  CHECK(bounded.exit_code == 1);
  CHECK(bounded.err.find("records = 6: the set's estimate is above the bound 5") !=
        std::string::npos);
  CHECK(bounded.err.find("--max-records lifts the bound") != std::string::npos);
  CHECK(!fs::exists(whole));
  run("--out " + quoted(whole));
  const std::map<std::string, std::string> reference = records_in(whole);
  REQUIRE(reference.size() == 6);

  const fs::path sharded = scratch.dir / "sharded";
  run("--out " + quoted(sharded) + " --shard 0/2");
  CHECK(records_in(sharded).size() == 3);
  // A merge before every shard ran names the missing records.
  const auto early =
      run_command(cli("dataset merge " + quoted(sharded) + " --out " + quoted(scratch.dir / "x")));
  CHECK(early.exit_code == 1);
  CHECK(early.err.find("3 missing") != std::string::npos);
  CHECK(!fs::exists(scratch.dir / "x"));
  // Two threads in this shard: the files do not depend on them.
  run("--out " + quoted(sharded) + " --shard 1/2 --threads 2");
  const fs::path merged = scratch.dir / "merged";
  const auto m = run_command(cli("dataset merge " + quoted(sharded) + " --out " + quoted(merged)));
  INFO(m.err);
  REQUIRE(m.exit_code == 0);
  CHECK(records_in(merged) == reference);
  // Five shards (one of them empty: six records, ids 0 and 5 in shard 0), into their own
  // folders, merged from the five.
  std::string five;
  for (int k = 0; k < 5; ++k) {
    const fs::path part = scratch.dir / ("five-" + std::to_string(k));
    run("--out " + quoted(part) + " --shard " + std::to_string(k) + "/5");
    CHECK(records_in(part).size() == (k == 0 ? 2u : 1u));
    five += " " + quoted(part);
  }
  const fs::path merged5 = scratch.dir / "merged5";
  const auto m5 = run_command(cli("dataset merge" + five + " --out " + quoted(merged5)));
  INFO(m5.err);
  REQUIRE(m5.exit_code == 0);
  CHECK(records_in(merged5) == reference);
  CHECK(read(merged5 / "labels.csv") == read(merged / "labels.csv"));
  // A record in two folders is refused, naming it.
  const auto doubled = run_command(cli("dataset merge " + quoted(sharded) + " " + quoted(whole) +
                                       " --out " + quoted(scratch.dir / "y")));
  CHECK(doubled.exit_code == 1);
  CHECK(doubled.err.find("record 0") != std::string::npos);
  CHECK(doubled.err.find("one shard folder per record") != std::string::npos);
  CHECK(!fs::exists(scratch.dir / "y"));

  // Killed: SIGKILL once the first record is complete, then the same command again.
  const fs::path resumed = scratch.dir / "resumed";
  fs::create_directories(resumed);
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    ::execl(GEARIMPACT_CLI, GEARIMPACT_CLI, "dataset", spec.c_str(), "--out", resumed.c_str(),
            "--quiet", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  for (int i = 0; i < 2000 && !fs::exists(resumed / "r0000000.json"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  // And what a kill between the two writes of a record, or a damaged file, would leave: a file
  // without its sidecar, and a file cut short under its sidecar.
  run("--out " + quoted(resumed) + " --shard 0/1");
  fs::remove(resumed / "r0000004.json");
  const std::string cut = read(resumed / "r0000005.h5").substr(0, 1000);
  std::ofstream(resumed / "r0000005.h5", std::ios::binary | std::ios::trunc) << cut;
  const auto again = run_command(cli("dataset " + quoted(spec) + " --out " + quoted(resumed)));
  REQUIRE(again.exit_code == 0);
  // Four records were complete, two were made again.
  CHECK(again.err.find("6/6 records (4 found complete)") != std::string::npos);
  CHECK(records_in(resumed) == reference);

  // A set larger than its disk is refused before anything is written: 120000 records of 10 s,
  // 1.75 TB by the estimate.
  const fs::path big = scratch.dir / "big";
  std::ofstream(scratch.dir / "big.toml") << replaced(
      replaced(replaced(six_text(), "../../examples/", (kHere / "../../examples/").string()),
               "replicates = 1", "replicates = 20000"),
      "duration = \"50 ms\"", "duration = \"10 s\"");
  const auto full = run_command(cli("dataset " + quoted(scratch.dir / "big.toml") + " --out " +
                                    quoted(big) + " --max-bytes 1e15 --max-samples 1e15"));
  CHECK(full.exit_code == 1);
  CHECK(full.err.find("--out = ") != std::string::npos);
  CHECK(full.err.find("bytes free, below 1.2 times the shard's estimate") != std::string::npos);
  CHECK(fs::is_empty(big));

  // A folder of another spec's set is refused.
  std::ofstream(scratch.dir / "six.toml")
      << replaced(six_text(), "../../examples/", (kHere / "../../examples/").string())
      << "\n# another spec\n";
  const auto other = run_command(
      cli("dataset " + quoted(scratch.dir / "six.toml") + " --out " + quoted(whole) + " --quiet"));
  CHECK(other.exit_code == 1);
  CHECK(other.err.find("spec sha256") != std::string::npos);
}

namespace {

// da/dN = C (Y dsigma sqrt(pi a))^m (dsigma in MPa) integrated by classical RK4 from a0 over n
// cycles in `steps` steps: an independent method for the closed form.
double integrated_depth(double a0, double n, double c, double m, double y, double dsigma_mpa,
                        int steps) {
  const auto rate = [&](double a) { return c * std::pow(y * dsigma_mpa * std::sqrt(pi * a), m); };
  double a = a0;
  const double h = n / steps;
  for (int i = 0; i < steps; ++i) {
    const double k1 = rate(a);
    const double k2 = rate(a + 0.5 * h * k1);
    const double k3 = rate(a + 0.5 * h * k2);
    const double k4 = rate(a + h * k3);
    a += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return a;
}

std::string trajectory_spec(const std::string& m, const std::string& spacing) {
  return replaced(
      replaced(
          six_text(),
          "[[factors]]\nkey = \"faults[0].depth\"\nlevels = [\"0.2 mm\", \"0.6 mm\", \"1 mm\"]\n",
          ""),
      "[[split.heldout]]",
      "[trajectory]\nkey = \"faults[0].depth\"\ninitial = \"0.1 mm\"\nfinal = \"1.2 mm\"\n"
      "paris_c = 1e-11\nparis_m = " +
          m +
          "\ngeometry_factor = 1.12\n"
          "stress_range = \"200 MPa\"\nsnapshots = 5\nspacing = \"" +
          spacing +
          "\"\n\n"
          "[[split.heldout]]");
}

}  // namespace

TEST_CASE("a Paris-law trajectory: snapshot depths against the growth law integrated numerically") {
  for (const std::string m : {"4", "2", "3.3"}) {
    for (const std::string spacing : {"cycles", "depth"}) {
      CAPTURE(m);
      CAPTURE(spacing);
      const dataset::Plan plan = dataset::make_plan(spec_of(trajectory_spec(m, spacing)));
      REQUIRE(plan.conditions.size() == 10);  // 2 speeds x 5 snapshots
      REQUIRE(plan.spec.factors.back().key == "faults[0].depth");
      for (const dataset::Condition& c : plan.conditions) {
        const double a = c.values.back();
        CHECK(c.simulation_case.faults.at(0).state.crack.depth_m == a);
        // RK4 with 20000 steps: its error (h^4) is far below the 1e-9 bar on these smooth
        // growths (a rises by 12 times at most).
        const double reference =
            integrated_depth(1e-4, c.cycles, 1e-11, std::stod(m), 1.12, 200.0, 20000);
        CHECK(std::abs(a / reference - 1.0) < 1e-9);
        CHECK(c.cycles_to_failure == plan.conditions.front().cycles_to_failure);
        // The whole trajectory shares its design condition's split.
        CHECK(c.split == plan.conditions[c.trajectory * 5].split);
      }
      CHECK(plan.conditions[4].values.back() == 1.2e-3);  // the last snapshot: the final depth
      CHECK(plan.conditions[0].values.back() == 1e-4);
      const double to_failure = plan.conditions.front().cycles_to_failure;
      CHECK(std::abs(integrated_depth(1e-4, to_failure, 1e-11, std::stod(m), 1.12, 200.0, 20000) /
                         1.2e-3 -
                     1.0) < 1e-9);
      if (spacing == "cycles") {
        CHECK(std::abs(plan.conditions[2].cycles / (0.5 * to_failure) - 1.0) < 1e-15);
      } else {
        CHECK(std::abs(plan.conditions[2].values.back() / 0.65e-3 - 1.0) < 1e-15);
      }
    }
  }
}

TEST_CASE("a random design: seeded, in range; a held-out range takes its conditions") {
  const std::string text =
      replaced(replaced(replaced(six_text(), "levels = [\"2400 rpm\", \"1800 rpm\"]",
                                 "range = [\"1500 rpm\", \"2500 rpm\"]"),
                        "levels = [\"1800 rpm\"]", "range = [\"1500 rpm\", \"2000 rpm\"]"),
               "[[split.heldout]]",
               "[design]\nkind = \"random\"\npoints = 20\nseed = 11\n\n[[split.heldout]]");
  const dataset::Plan a = dataset::make_plan(spec_of(text));
  const dataset::Plan b = dataset::make_plan(spec_of(text));
  const dataset::Plan c = dataset::make_plan(spec_of(replaced(text, "seed = 11", "seed = 12")));
  REQUIRE(a.conditions.size() == 20);
  const double low = 1500.0 * 2.0 * pi / 60.0;
  const double split = 2000.0 * 2.0 * pi / 60.0;
  const double high = 2500.0 * 2.0 * pi / 60.0;
  int held = 0;
  bool differs = false;
  for (std::size_t k = 0; k < 20; ++k) {
    const double w = a.conditions[k].values[0];
    CHECK(w >= low);
    CHECK(w <= high);
    CHECK(a.conditions[k].values == b.conditions[k].values);
    differs = differs || a.conditions[k].values != c.conditions[k].values;
    CHECK(a.conditions[k].split == (w <= split ? "test" : "train"));
    held += a.conditions[k].split == "test";
  }
  CHECK(differs);
  CHECK(held > 0);
  CHECK(held < 20);
}

namespace {

// six.toml without noise (which the decimated record adds at its own rate), at `rate`, with
// `recorder` as its [recorder] section.
std::string without_noise(const std::string& rate, const std::string& recorder) {
  // Shorter than six.toml's records (20 ms after 10 ms), to keep the sanitized pass cheap.
  return replaced(
      replaced(replaced(replaced(six_text(), "[recorder]\nnoise_snr = \"30 dB\"\n", recorder),
                        "sample_rate = \"20 kHz\"", "sample_rate = \"" + rate + "\""),
               "duration = \"50 ms\"", "duration = \"20 ms\""),
      "settle = \"20 ms\"", "settle = \"10 ms\"");
}

}  // namespace

TEST_CASE(
    "the anti-alias decimator: a record decimated from 4 x its rate is anti_alias_resample of the "
    "undecimated record, bit for bit; the same bytes whole and in five shards") {
  const dataset::Plan fine = dataset::make_plan(spec_of(without_noise("80 kHz", "")));
  const dataset::Plan decimated =
      dataset::make_plan(spec_of(without_noise("20 kHz", "[recorder]\noversample = 4\n")));
  REQUIRE(decimated.records.size() == 6);
  const std::size_t n = decimated.samples_per_record;
  REQUIRE(fine.samples_per_record == 4 * n);
  // The filter anti_alias_resample designs for 80 kHz to 20 kHz (decimate.hpp): order
  // ceil((100 - 8) / (2.285 dw)), dw = 2 pi 2 kHz / 80 kHz, raised to even: 258.
  const dataset::Oversampling over =
      dataset::oversampling(20e3, decimated.conditions[0].recorder, 200, static_cast<long long>(n));
  REQUIRE(over.filter.has_value());
  CHECK(over.filter->order == 258);
  CHECK(over.lead == 33);  // ceil(129 / 4)
  // Two records: the first condition's, and the last (another speed and depth).
  for (const std::size_t id : {std::size_t{0}, std::size_t{5}}) {
    CAPTURE(id);
    // The same seed: the same start angle.
    REQUIRE(fine.records[id].seed == decimated.records[id].seed);
    const dataset::RecordData a = dataset::make_record(fine, fine.records[id]);
    const dataset::RecordData d = dataset::make_record(decimated, decimated.records[id]);
    REQUIRE(d.sensor.size() == n);
    signals::UniformRecord undecimated;
    undecimated.rate_hz = 80e3;
    undecimated.values = a.sensor;
    const signals::UniformRecord expected = signals::anti_alias_resample(undecimated, 20e3);
    // Its outputs start and end half the span inside the record: 33 samples at 20 kHz.
    REQUIRE(expected.values.size() == n - 2 * 33 + 1);
    CHECK(expected.start_s == 33 * 4 / 80e3);
    std::size_t same = 0;
    for (std::size_t j = 0; j < expected.values.size(); ++j) {
      same += d.sensor[j + 33] == expected.values[j] ? 1 : 0;
    }
    CHECK(same == expected.values.size());
    // The truth: the fine record's every fourth sample.
    for (std::size_t k = 0; k < d.truth.size(); ++k) {
      std::size_t equal = 0;
      for (std::size_t j = 0; j < n; ++j) equal += d.truth[k][j] == a.truth[k][4 * j] ? 1 : 0;
      CHECK(equal == n);
    }
    std::size_t flags = 0;
    for (std::size_t j = 0; j < n; ++j) flags += d.contact[j] == a.contact[4 * j] ? 1 : 0;
    CHECK(flags == n);
    // The file names its filter.
    const std::string file = dataset::record_file(decimated, decimated.records[id], d);
    for (const char* name :
         {"simulation_rate_hz", "decimator_passband_edge_hz", "decimator_stopband_edge_hz",
          "decimator_taps", "decimator_kaiser_beta", "alias_free_band_hz"}) {
      CHECK(file.find(name) != std::string::npos);
    }
  }

  // Whole, and in five shards (two of them on two threads) into one folder.
  Scratch scratch("dataset-decimated");
  const fs::path whole = scratch.dir / "whole";
  const fs::path sharded = scratch.dir / "sharded";
  fs::create_directories(whole);
  fs::create_directories(sharded);
  CHECK(dataset::run_shard(decimated, whole.string(), {0, 1}).done == 6);
  for (int k = 0; k < 5; ++k) {
    dataset::run_shard(decimated, sharded.string(), {k, 5}, k < 2 ? 2 : 1);
  }
  const auto reference = records_in(whole);
  CHECK(reference.size() == 6);
  CHECK(records_in(sharded) == reference);
}

TEST_CASE("a bad oversampling is refused before any work, naming the key and its range") {
  CHECK(refusal(replaced(six_text(), "[recorder]\n", "[recorder]\noversample = 0\n"))
            .find("recorder.oversample") != std::string::npos);
  CHECK(refusal(replaced(six_text(), "[recorder]\n", "[recorder]\noversample = 2.5\n"))
            .find("an integer in [1, 64]") != std::string::npos);
  // At oversample 2 the filter's order is 130 (decimate.hpp's formula): its half span, 65 fine
  // samples, is 33 recorded samples, which with one more take 1.7 ms of settling; 1 ms is short.
  const std::string e =
      refusal(replaced(replaced(six_text(), "[recorder]\n", "[recorder]\noversample = 2\n"),
                       "settle = \"20 ms\"", "settle = \"1 ms\""));
  CHECK(e.find("dataset.settle") != std::string::npos);
  CHECK(e.find("at least 0.0017 s with recorder.oversample = 2") != std::string::npos);
}

TEST_CASE(
    "NPZ and MAT records: CRC-32's check value; a .npy header; MATLAB names; an unknown format "
    "refused") {
  // The CRC catalogue's check value of CRC-32/ISO-HDLC, the CRC ZIP stores.
  CHECK(crc32("123456789") == 0xCBF43926u);
  CHECK(crc32("") == 0u);
  // NEP 1: magic, version 1.0, the header's length; data at a multiple of 64 bytes (numpy.save
  // writes these 144 bytes for [1.0, -2.5]).
  const std::string npy = npy_file(std::vector<double>{1.0, -2.5});
  REQUIRE(npy.size() == 128 + 16);
  CHECK(npy.substr(0, 8) == std::string("\x93NUMPY\x01\x00", 8));
  CHECK(static_cast<unsigned char>(npy[8]) + 256 * static_cast<unsigned char>(npy[9]) == 118);
  CHECK(npy.substr(10, 118).find("{'descr': '<f8', 'fortran_order': False, 'shape': (2,), }") == 0);
  CHECK(npy[127] == '\n');
  // 1.0 little-endian: 00 .. 00 f0 3f.
  CHECK(npy.substr(128, 8) == std::string("\0\0\0\0\0\0\xf0\x3f", 8));
  // MATLAB names of the HDF5 layout's paths and labels (docs/datasets.md).
  CHECK(matlab_name("/") == "root");
  CHECK(matlab_name("/signals/sensor") == "signals_sensor");
  CHECK(matlab_name("faults[0].depth_m") == "faults_0__depth_m");
  CHECK(matlab_name("3x") == "x3x");
  CHECK(matlab_name(std::string(80, 'a')).size() == 63);
  // "mat" is a format where the build has libmatio, and refused naming the library otherwise.
  const std::string m =
      refusal(replaced(six_text(), "[dataset]\n", "[dataset]\nformat = \"mat\"\n"));
  CHECK(m.empty() == mat_files_available());
  if (!mat_files_available()) CHECK(m.find("libmatio") != std::string::npos);
  const std::string e =
      refusal(replaced(six_text(), "[dataset]\n", "[dataset]\nformat = \"csv\"\n"));
  CHECK(e.find("dataset.format") != std::string::npos);
  CHECK(e.find("\"npz\"") != std::string::npos);
}
