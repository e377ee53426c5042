// The sweep and the merge at their edges, through the program: an output folder appears as a
// complete set or not at all, bounds and meaningless requests are refused before any point runs,
// a merge reads every row of every shard, and a valid run never fails in its plots. Each refusal
// exits 1 with one message naming the flag or key as written and leaves every file as it was.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "run_command.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;
using gearimpact::verify::cli;
using gearimpact::verify::CommandResult;
using gearimpact::verify::run_command;
using gearimpact::verify::Scratch;
using gearimpact::verify::signal_when_under_way;

namespace {

// A loaded pair of Table 1's case 1 with a steady state: two points a direction, one thread.
const std::string kUndamped =
    "sweep 1 --vary initial.w1 --from '2000 rad/s' --to '3000 rad/s' --points 2 --threads 1 "
    "--set model.friction_coefficient=0 --set 'torque1.mean=3 N*m'";
const std::string kSweep = kUndamped + " --set model.mesh_damping_ratio=0.05";

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Every entry under `dir` (hidden ones included) with its content, to show that a refused run
// left nothing and changed nothing.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> entries;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    entries[entry.path().string()] = entry.is_regular_file() ? read(entry.path()) : "<folder>";
  }
  return entries;
}

std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
    ++n;
  }
  return n;
}

// Runs `command` in `scratch` and checks a refusal: exit 1, one message naming each of `names`,
// no point run (no progress line), the folder as it was.
void refused(const Scratch& scratch, const std::string& command,
             const std::vector<std::string>& names) {
  CAPTURE(command);
  const auto before = snapshot(scratch.dir);
  const CommandResult r = run_command("cd " + scratch.dir.string() + " && " + command);
  CAPTURE(r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("gearimpact: error:") == 0);
  CHECK(count_of(r.err, "gearimpact: error:") == 1);
  CHECK(r.err.find("sweep: ") == std::string::npos);
  for (const std::string& name : names) CHECK(r.err.find(name) != std::string::npos);
  CHECK(snapshot(scratch.dir) == before);
}

// True when `dir` holds no hidden entry (a temporary file or folder left behind).
bool no_hidden_entries(const fs::path& dir) {
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().front() == '.') return false;
  }
  return true;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TEST_CASE("a non-empty output folder is refused before any work; --overwrite replaces it whole") {
  Scratch scratch("sweep-edges-overwrite");
  const fs::path out = scratch.dir / "out";
  fs::create_directories(out);
  // What an earlier run with a second key left: it must not stay beside new results.
  write(out / "regime-map.png", "stale");
  write(out / "sweep.csv", "stale");
  refused(scratch, cli(kSweep + " --no-plots --out " + out.string()),
          {out.string(), "--overwrite"});

  const CommandResult r =
      run_command(cli(kSweep + " --no-plots --overwrite --out " + out.string()));
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  CHECK_FALSE(fs::exists(out / "regime-map.png"));
  CHECK(read(out / "sweep.csv").rfind("line,direction,index", 0) == 0);
  CHECK(fs::exists(out / "summary.json"));
  CHECK(fs::exists(out / "poincare.csv"));
  CHECK(no_hidden_entries(scratch.dir));
  CHECK(no_hidden_entries(out));

  // An empty folder is no earlier run's: it is used as it is.
  const fs::path empty = scratch.dir / "empty";
  fs::create_directories(empty);
  const CommandResult e = run_command(cli(kSweep + " --no-plots --out " + empty.string()));
  CHECK_MESSAGE(e.exit_code == 0, e.err);
  CHECK(fs::exists(empty / "sweep.csv"));
}

TEST_CASE("an output folder in a missing or read-only folder, or a file, is refused before work") {
  Scratch scratch("sweep-edges-out-path");
  refused(scratch, cli(kSweep + " --no-plots --out " + (scratch.dir / "missing" / "out").string()),
          {(scratch.dir / "missing").string(), "does not exist"});
  write(scratch.dir / "a-file", "mine");
  refused(scratch, cli(kSweep + " --no-plots --out " + (scratch.dir / "a-file").string()),
          {(scratch.dir / "a-file").string(), "not a folder"});
  if (::geteuid() == 0) {
    MESSAGE("read-only folder skipped: root may write any folder");
    return;
  }
  const fs::path locked = scratch.dir / "locked";
  fs::create_directories(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  refused(scratch, cli(kSweep + " --no-plots --out " + (locked / "out").string()),
          {locked.string(), "cannot be written"});
  fs::permissions(locked, fs::perms::owner_all);
}

TEST_CASE("bounds and meaningless sweeps are refused before any point runs, naming the flag") {
  Scratch scratch("sweep-edges-bounds");
  const std::string out = " --no-plots --out " + (scratch.dir / "out").string();
  const std::string base =
      "sweep 1 --vary initial.w1 --from '2000 rad/s' --to '3000 rad/s' --threads 1 "
      "--set model.friction_coefficient=0 --set 'torque1.mean=3 N*m'";
  const std::string second = " --vary2 gears.backlash --from2 4e-5 --to2 6e-5";
  struct Bad {
    std::string arguments;
    std::vector<std::string> names;
  };
  const std::vector<Bad> bad{
      // The estimate and the flag that lifts the bound.
      {base + " --points 100000000", {"--points", "200000000 points", "--max-points"}},
      {base + " --points 1000" + second + " --points2 1000",
       {"--points", "2000000 points", "1000 lines", "--max-points"}},
      {base + " --points 3 --max-points 5", {"--points", "6 points", "at most 5"}},
      // A bound that is no bound: NaN compared false and let every size through.
      // (refused by the parser, which takes numbers in decimal only).
      {base + " --points 3 --max-points nan", {"--max-points: \"nan\"", "decimal number"}},
      {base + " --points 3 --max-points 0", {"--max-points = 0", "[1, 9e18]"}},
      {base + " --points 3 --points2 2000000000 --vary2 initial.theta1 --from2 0 --to2 1",
       {"--points", "2000000000 lines", "--max-points"}},
      // Finite ends whose distance is not: the grid's step would be NaN.
      {"sweep 1 --vary initial.w1 --from '-1e308 rad/s' --to '1e308 rad/s' --points 3 "
       "--set model.friction_coefficient=0 --set 'torque1.mean=3 N*m'",
       {"--to = 1e308", "a finite number"}},
      // A friction law has friction whatever friction_coefficient says.
      {base + " --points 2 --set model.friction_law=benedict-kelley "
              "--set 'model.lubricant_viscosity=100 cP' --set 'model.surface_roughness=0.4 um'",
       {"model.friction_law", "constant"}},
      // A backlash beyond the tooth space, at an end of the sweep.
      {"sweep 1 --vary gears.backlash --from 0 --to 1e308 --points 3 "
       "--set model.friction_coefficient=0 --set 'torque1.mean=3 N*m'",
       {"gears.backlash", "an end of the sweep", "pi m / 4"}},
      {base + " --points 2 --steps-per-contact-period 1e7",
       {"--steps-per-contact-period", "[20, 10000]"}},
      {base + " --points 2 --steps-per-contact-period 5", {"--steps-per-contact-period"}},
      {base + " --points 2 --max-periods 0", {"--max-periods", "1000000"}},
      {base + " --points 2 --tolerance 0", {"--tolerance", "0.1"}},
      {base + " --points 2 --tolerance 1", {"--tolerance"}},
      {base + " --points 2 --threads 100000", {"--threads", "1024"}},
      {"sweep 1 --vary initial.w1 --from '3000 rad/s' --to '2000 rad/s' --points 2 "
       "--set model.friction_coefficient=0",
       {"--from", "3000"}},
      {base + " --points 2 --vary2 initial.w1 --from2 '2000 rad/s' --to2 '3000 rad/s' --points2 2",
       {"--vary2", "initial.w1"}},
      // Keys no point reads: the steady state sets the integrator itself; the reference speed
      // is read only by frozen damping.
      {"sweep 1 --vary integrator.step --from 1e-7 --to 2e-7 --points 2",
       {"--vary", "integrator.step"}},
      {"sweep 1 --vary model.damping_reference_speed --from 1 --to 2 --points 2 "
       "--set model.friction_coefficient=0 --damping-update each-impact",
       {"--vary", "model.damping_reference_speed", "frozen"}},
      // "auto" on the sweeps' rigid bearings resolves to each-impact: the same.
      {"sweep 1 --vary model.damping_reference_speed --from 1 --to 2 --points 2 "
       "--set model.friction_coefficient=0 --damping-update auto",
       {"--vary", "model.damping_reference_speed", "resolves to \"each-impact\""}},
      // An integer key on a grid of fractions: refused before the first point, not after it.
      {"sweep 1 --vary gears.teeth1 --from 20 --to 25 --points 3 "
       "--set model.friction_coefficient=0",
       {"--points", "gears.teeth1", "22.5"}},
      {base + " --points 2 --shard ''", {"--shard"}},
      {"SLURM_ARRAY_TASK_ID=x SLURM_ARRAY_TASK_COUNT=2 " + std::string(GEARIMPACT_CLI) + " " +
           base + " --points 2",
       {"SLURM_ARRAY_TASK_ID", "\"x\""}},
  };
  for (const Bad& b : bad) {
    const std::string command =
        b.arguments.rfind("SLURM", 0) == 0 ? b.arguments + out : cli(b.arguments + out);
    refused(scratch, command, b.names);
  }
  // The same bound on threads in the other commands that take them.
  refused(scratch, cli("sweep-friction --threads 100000"), {"--threads", "1024"});
  // The last value of a grid is checked as the first: a step that cannot exist there is
  // refused before the first point runs, naming the end.
  refused(
      scratch,
      cli("sweep 1 --vary initial.w1 --from '2000 rad/s' --to '1e308 rad/s' --points 2 --threads 1 "
          "--set model.friction_coefficient=0 --set 'torque1.mean=3 N*m'" +
          out),
      {"initial.w1 = 1e", "an end of the sweep"});
}

TEST_CASE("a valid run never fails in its plots: an empty or one-value figure is skipped") {
  Scratch scratch("sweep-edges-plots");
  // The regime map draws the up sweeps: none here.
  const fs::path down = scratch.dir / "down";
  const CommandResult r = run_command(
      cli(kSweep +
          " --direction down --vary2 gears.backlash --from2 4e-5 --to2 6e-5 --points2 2 "
          "--out " +
          down.string()));
  CHECK_MESSAGE(r.exit_code == 0, r.err);
  CHECK(r.err.find("note: no regime-map plot") != std::string::npos);
  CHECK(fs::exists(down / "sweep.csv"));
  CHECK_FALSE(fs::exists(down / "regime-map.png"));
  CHECK_FALSE(fs::exists(down / "regime-map.gp"));

  // A shard with no line of its own (4 shards of a sweep of one line up): an empty, valid set.
  const fs::path idle = scratch.dir / "idle";
  const CommandResult s =
      run_command(cli(kSweep + " --direction up --shard 3/4 --out " + idle.string()));
  CHECK_MESSAGE(s.exit_code == 0, s.err);
  CHECK(s.err.find("note: no amplitude plot: nothing") != std::string::npos);
  CHECK(lines_of(read(idle / "sweep.csv")).size() == 1u);
  CHECK_FALSE(fs::exists(idle / "amplitude.png"));

  // One value: nothing to draw a line through.
  const fs::path single = scratch.dir / "single";
  const CommandResult o = run_command(
      cli("sweep 1 --vary initial.w1 --from 2000 --to 2000 --points 1 --direction up --threads 1 "
          "--set model.friction_coefficient=0 --set 'torque1.mean=3 N*m' "
          "--set model.mesh_damping_ratio=0.05 --out " +
          single.string()));
  CHECK_MESSAGE(o.exit_code == 0, o.err);
  CHECK(o.err.find("note: no amplitude plot: a single value") != std::string::npos);
  CHECK(fs::exists(single / "sweep.csv"));
  CHECK(no_hidden_entries(scratch.dir));
}

TEST_CASE("two sweeps into one folder: one complete set results, never a mix") {
  Scratch scratch("sweep-edges-race");
  // Two sweeps that differ in their last value, so that each file tells which run wrote it.
  const auto sweep_to = [&](const char* to, const fs::path& out, const char* extra) {
    return cli(std::string("sweep 1 --vary initial.w1 --from 2000 --to ") + to +
               " --points 3 --threads 1 --set model.friction_coefficient=0 "
               "--set 'torque1.mean=3 N*m' --set model.mesh_damping_ratio=0.05 --no-plots " +
               extra + " --out " + out.string());
  };
  for (const char* extra : {"", "--overwrite"}) {
    for (int trial = 0; trial < 3; ++trial) {
      CAPTURE(extra);
      CAPTURE(trial);
      const fs::path out = scratch.dir / ("out" + std::string(extra) + std::to_string(trial));
      const fs::path a_rc = scratch.dir / "a.rc";
      const fs::path b_rc = scratch.dir / "b.rc";
      std::string both = "(";
      both += sweep_to("3000", out, extra);
      both += " 2>/dev/null; echo $? > ";
      both += a_rc.string();
      both += ") & (";
      both += sweep_to("3500", out, extra);
      both += " 2>/dev/null; echo $? > ";
      both += b_rc.string();
      both += ") & wait";
      run_command(both);
      const int a = std::stoi(read(a_rc));
      const int b = std::stoi(read(b_rc));
      // Without --overwrite the second to finish is refused; with it, both may succeed, the
      // later one replacing the earlier whole.
      if (std::string(extra).empty()) {
        CHECK(a + b == 1);
      } else {
        CHECK(a * b == 0);
      }
      const std::vector<std::string> rows = lines_of(read(out / "sweep.csv"));
      REQUIRE(rows.size() == 1u + 2u * 3u);
      const bool to_3500 = rows[3].find(",3500,") != std::string::npos;
      CHECK((to_3500 || rows[3].find(",3000,") != std::string::npos));
      const std::string summary = read(out / "summary.json");
      CHECK(summary.find(to_3500 ? "\"to_si\": 3500" : "\"to_si\": 3000") != std::string::npos);
      const std::string poincare = read(out / "poincare.csv");
      CHECK(poincare.find(to_3500 ? ",3500," : ",3000,") != std::string::npos);
      CHECK(poincare.find(to_3500 ? ",3000," : ",3500,") == std::string::npos);
      CHECK(no_hidden_entries(scratch.dir));
      fs::remove(a_rc);
      fs::remove(b_rc);
    }
  }
}

TEST_CASE("merge reads every row of every shard and names the shard, file and line of a bad one") {
  Scratch scratch("sweep-edges-merge");
  const fs::path s0 = scratch.dir / "shard-0";
  const fs::path s1 = scratch.dir / "shard-1";
  for (const auto& [shard, dir] : {std::pair{"0/2", s0}, std::pair{"1/2", s1}}) {
    const CommandResult r =
        run_command(cli(kSweep + " --no-plots --shard " + shard + " --out " + dir.string()));
    REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  }
  const fs::path merged = scratch.dir / "merged";
  const auto merge = [&](const fs::path& other) {
    return cli("merge --no-plots " + s0.string() + " " + other.string() + " --out " +
               merged.string());
  };
  // The good pair merges.
  const CommandResult good = run_command(merge(s1));
  REQUIRE_MESSAGE(good.exit_code == 0, good.err);
  CHECK(lines_of(read(merged / "sweep.csv")).size() == 1u + 2u * 2u);
  fs::remove_all(merged);

  // Its output may not be a shard, nor hold one.
  refused(scratch,
          cli("merge --no-plots " + s0.string() + " " + s1.string() + " --out " + s0.string()),
          {s0.string(), "input"});
  refused(scratch,
          cli("merge --no-plots " + s0.string() + " " + s1.string() + " --overwrite --out " +
              scratch.dir.string()),
          {scratch.dir.string(), "input"});

  // Corrupted copies of shard 1: each refused naming the copy's file and the line of the row.
  const std::string sweep_text = read(s1 / "sweep.csv");
  const std::string poincare_text = read(s1 / "poincare.csv");
  const std::vector<std::string> sweep_rows = lines_of(sweep_text);
  REQUIRE(sweep_rows.size() == 3u);
  const auto replace_line = [&](std::size_t n, const std::string& line) {
    std::vector<std::string> rows = sweep_rows;
    rows[n] = line;
    std::string text;
    for (const std::string& row : rows) text += row + "\n";
    return text;
  };
  const auto field_replaced = [&](std::size_t n, std::size_t field, const std::string& value) {
    std::vector<std::string> fields;
    std::stringstream row(sweep_rows[n]);
    for (std::string f; std::getline(row, f, ',');) fields.push_back(f);
    fields[field] = value;
    std::string line;
    for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? "," : "") + fields[i];
    return replace_line(n, line);
  };
  std::string crlf;
  for (char ch : sweep_text) crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
  struct Corruption {
    const char* name;
    const char* file;
    std::string text;
    std::string place;  // the line named
    std::string detail;
  };
  const std::vector<Corruption> corruptions{
      {"nan", "sweep.csv", field_replaced(2, 8, "nan"), ":3", "nan"},
      {"inf", "sweep.csv", field_replaced(1, 3, "inf"), ":2", "finite"},
      {"extra-column", "sweep.csv", replace_line(1, sweep_rows[1] + ",1"), ":2", "22 fields"},
      {"crlf", "sweep.csv", crlf, ":1", "CRLF"},
      {"huge-index", "sweep.csv", field_replaced(2, 2, "99999999999"), ":3", "99999999999"},
      {"index-out-of-grid", "sweep.csv", field_replaced(2, 2, "2"), ":3", "[0, 2)"},
      {"line-out-of-grid", "sweep.csv", field_replaced(1, 0, "1"), ":2", "[0, 1)"},
      // Inside the grid's ends but at no index of it (the grid is 2000, 3000).
      {"value-off-grid", "sweep.csv", field_replaced(1, 3, "2500"), ":2", "grid at index"},
      // The last field (mesh_frequency_hz) cut to its first three characters, or to nothing.
      {"last-field-cut", "sweep.csv",
       replace_line(1, sweep_rows[1].substr(0, sweep_rows[1].rfind(',') + 4)), ":2", "cut short"},
      {"last-field-empty", "sweep.csv",
       replace_line(1, sweep_rows[1].substr(0, sweep_rows[1].rfind(',') + 1)), ":2", "cut short"},
      {"cut-mid-number", "poincare.csv", poincare_text.substr(0, poincare_text.size() - 4),
       ":" + std::to_string(lines_of(poincare_text).size()), "cut short"},
  };
  for (const Corruption& c : corruptions) {
    CAPTURE(c.name);
    const fs::path bad = scratch.dir / (std::string("bad-") + c.name);
    fs::copy(s1, bad);
    write(bad / c.file, c.text);
    const std::string file = (bad / c.file).string();
    refused(scratch, merge(bad), {file + c.place, c.detail});
    CHECK_FALSE(fs::exists(merged));
    fs::remove_all(bad);
  }

  // A shard of another case (another damping ratio, another reference speed of frozen damping):
  // its spec's case key differs, though every swept setting agrees.
  struct Mismatch {
    std::string own;    // the keys of the shard 0
    std::string other;  // the keys of the foreign shard 1
  };
  for (const Mismatch& m :
       {Mismatch{kSweep, kUndamped + " --set model.mesh_damping_ratio=0.06"},
        Mismatch{
            kSweep + " --damping-update frozen",
            kSweep + " --damping-update frozen --set 'model.damping_reference_speed=2 m/s'"}}) {
    CAPTURE(m.other);
    const fs::path own = scratch.dir / "own";
    const fs::path foreign = scratch.dir / "foreign";
    REQUIRE(run_command(cli(m.own + " --no-plots --shard 0/2 --out " + own.string())).exit_code ==
            0);
    REQUIRE(
        run_command(cli(m.other + " --no-plots --shard 1/2 --out " + foreign.string())).exit_code ==
        0);
    refused(scratch,
            cli("merge --no-plots " + own.string() + " " + foreign.string() + " --out " +
                merged.string()),
            {foreign.string(), "case_key_fnv1a64"});
    CHECK_FALSE(fs::exists(merged));
    fs::remove_all(own);
    fs::remove_all(foreign);
  }
}

TEST_CASE("a sweep ended by a signal leaves no output; a rerun is not hindered by what it left") {
  Scratch scratch("sweep-edges-signal");
  for (const char* signal_name : {"INT", "TERM", "KILL"}) {
    CAPTURE(signal_name);
    const fs::path out = scratch.dir / "out";
    // Long enough to be under way when the signal comes (some seconds).
    run_command(signal_when_under_way(
        cli("sweep 1 --vary initial.w1 --from '2000 rad/s' --to '3000 rad/s' --points 1000 "
            "--direction up "
            "--threads 1 "
            "--set model.friction_coefficient=0 --set 'torque1.mean=3 N*m' "
            "--set model.mesh_damping_ratio=0.05 --no-plots --out " +
            out.string()) +
            " 2>/dev/null",
        signal_name, 0.5));
    CHECK_FALSE(fs::exists(out));
    // SIGKILL cannot be caught: its hidden temporary folder stays until the
    // next run into the same folder removes it.
    if (std::string(signal_name) != "KILL") CHECK(fs::is_empty(scratch.dir));
    const CommandResult r = run_command(cli(kSweep + " --no-plots --out " + out.string()));
    CHECK_MESSAGE(r.exit_code == 0, r.err);
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(scratch.dir)) {
      names.push_back(entry.path().filename().string());
    }
    CHECK(names == std::vector<std::string>{"out"});
    fs::remove_all(out);
  }
}

TEST_CASE("a sweep whose reader goes away (SIGPIPE) leaves no temporary folder") {
  Scratch scratch("sweep-edges-pipe");
  const fs::path out = scratch.dir / "out";
  // `head -1` reads the first progress line and exits; the next write to the
  // closed pipe raises SIGPIPE.
  run_command(cli(kSweep + " --no-plots --out " + out.string()) + " 2>&1 | head -1 >/dev/null");
  for (const auto& entry : fs::directory_iterator(scratch.dir)) {
    CHECK(entry.path().filename() == "out");
  }
}
