// Outputs at the edges, through the program: a folder name never reaches a
// shell, a device or FIFO is never replaced by an output, a failed write to
// standard output is an error, and every refusal (the option parser's too)
// exits 1 with one prefix. Devices are made with mknod in a temporary folder,
// never the machine's own /dev/null or /dev/full.
#include <doctest/doctest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/io/modes_files.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/paper/table1.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;
using gearimpact::verify::cli;
using gearimpact::verify::CommandResult;
using gearimpact::verify::run_command;
using gearimpact::verify::Scratch;
using gearimpact::verify::signal_when_under_way;

namespace {

// A character device like /dev/null (1, 3) or /dev/full (1, 7) in `dir`;
// false where this user may not make one.
bool make_device(const fs::path& path, unsigned minor) {
  return ::mknod(path.c_str(), S_IFCHR | 0666, makedev(1, minor)) == 0;
}

bool is_character_device(const fs::path& path) {
  struct stat status {};
  return ::stat(path.c_str(), &status) == 0 && S_ISCHR(status.st_mode);
}

// Single quotes for the shell that run_command uses to start the program.
std::string single_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char ch : text) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return quoted + "'";
}

// A 1 MiB tmpfs mounted at `dir` for a full-disk test, unmounted at the end;
// not mounted where this user may not mount (then the test says so and skips).
struct SmallDisk {
  fs::path dir;
  bool mounted = false;
  explicit SmallDisk(fs::path at) : dir(std::move(at)) {
    fs::create_directories(dir);
    mounted = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=1m") == 0;
  }
  ~SmallDisk() {
    if (mounted) ::umount(dir.c_str());
  }
  SmallDisk(const SmallDisk&) = delete;
  SmallDisk& operator=(const SmallDisk&) = delete;
};

}  // namespace

TEST_CASE("an output folder's name never reaches a shell") {
  Scratch scratch("edges");
  const fs::path marker = scratch.dir / "PWNED";
  // $(...), a double quote and $HOME: each would change the command line of
  // a shell that saw the name.
  const fs::path out = scratch.dir / ("x$(touch " + marker.string() + ")\"$HOME");
  // The name holds slashes; an output folder's own folder must exist.
  fs::create_directories(out.parent_path());
  const CommandResult r = run_command(
      cli("sweep 1 --vary initial.w1 --from 2000 --to 3000 --points 2 --direction up --threads 1 "
          "--set model.friction_coefficient=0 --set 'torque1.mean=3 N*m' "
          "--set model.mesh_damping_ratio=0.05 --out " +
          single_quoted(out.string())));
  CHECK(r.exit_code == 0);
  CHECK_FALSE(fs::exists(marker));
  CHECK(fs::exists(out / "sweep.csv"));
  // gnuplot ran in that folder and drew there (where it is installed, as on CI).
  CHECK(fs::exists(out / "amplitude.png"));
}

TEST_CASE("an output never replaces a device or a FIFO") {
  Scratch scratch("edges");
  const fs::path null_device = scratch.dir / "null";
  if (!make_device(null_device, 3)) {
    MESSAGE("skipped: this user cannot make a device node");
    return;
  }
  const CommandResult r =
      run_command(cli("simulate --case 1 --t-end 1ms --out " + null_device.string()));
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("gearimpact: error:") == 0);
  CHECK(r.err.find(null_device.string()) != std::string::npos);
  CHECK(r.err.find("character device") != std::string::npos);
  CHECK(is_character_device(null_device));

  const fs::path fifo = scratch.dir / "fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const CommandResult f = run_command(cli("simulate --case 1 --t-end 1ms --out " + fifo.string()));
  CHECK(f.exit_code == 1);
  CHECK(f.err.find("FIFO") != std::string::npos);
  struct stat status {};
  REQUIRE(::stat(fifo.c_str(), &status) == 0);
  CHECK(S_ISFIFO(status.st_mode));
  // Nothing else was left in the folder: no temporary file beside the targets.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(scratch.dir)) ++entries;
  CHECK(entries == 2);
}

TEST_CASE("a failed write to standard output is an error") {
  Scratch scratch("edges");
  const fs::path full_device = scratch.dir / "full";
  if (!make_device(full_device, 7)) {
    MESSAGE("skipped: this user cannot make a device node");
    return;
  }
  for (const char* command : {"schema", "simulate --case 1 --t-end 1ms", "stiffness --points 50"}) {
    CAPTURE(command);
    const CommandResult r = run_command(cli(command) + " > " + full_device.string());
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("gearimpact: error: cannot write standard output") != std::string::npos);
  }
}

TEST_CASE("the option parser's refusals exit 1 with the program's prefix") {
  for (const char* command :
       {"simulate --bogus", "simulate --case", "sweep 1 --vary initial.w1", "no-such-command"}) {
    CAPTURE(command);
    const CommandResult r = run_command(cli(command));
    CHECK(r.exit_code == 1);
    CHECK(r.err.find("gearimpact: error:") == 0);
  }
  // Help is not a refusal.
  CHECK(run_command(cli("--help")).exit_code == 0);
  CHECK(run_command(cli("simulate --help")).exit_code == 0);
}

TEST_CASE("an output that is the run's input, or in a missing folder, is refused before the run") {
  Scratch scratch("edges");
  const fs::path case_file = scratch.dir / "case.toml";
  fs::copy_file(fs::path(GEARIMPACT_PAPER_DATA_DIR) / "case1.toml", case_file);
  const auto size_before = fs::file_size(case_file);
  const CommandResult same = run_command(
      cli("simulate --case-file " + case_file.string() + " --out " + case_file.string()));
  CHECK(same.exit_code == 1);
  CHECK(same.err.find("it is the input") != std::string::npos);
  CHECK(fs::file_size(case_file) == size_before);

  const fs::path missing = scratch.dir / "no-such-folder" / "series.csv";
  const CommandResult folder =
      run_command(cli("simulate --case 1 --t-end 50ms --out " + missing.string()));
  CHECK(folder.exit_code == 1);
  CHECK(folder.err.find("does not exist") != std::string::npos);

  const CommandResult empty = run_command(cli("simulate --case-file ''"));
  CHECK(empty.exit_code == 1);
  CHECK(empty.err.find("--case-file") != std::string::npos);
}

TEST_CASE("a long series streams to its file instead of growing in memory") {
#if defined(__SANITIZE_ADDRESS__)
  MESSAGE("skipped under AddressSanitizer, which cannot run under an address-space limit");
#else
  Scratch scratch("edges");
  const fs::path series = scratch.dir / "series.csv";
  // 60 ms of case 1 at the 0.1 us step is 600,000 rows, 80 MB of CSV. Held in
  // memory (rows and text) it needs about 200 MB; streamed, the program stays
  // well under the 100 MB of address space it is given here.
  const CommandResult r = run_command(
      "ulimit -v 100000 && " + cli("simulate --case 1 --t-end 60ms --out " + series.string()));
  CHECK(r.exit_code == 0);
  CHECK(fs::file_size(series) > 70'000'000);
  // The streamed file holds the bytes the library's series_csv writes from a
  // series kept in memory: a 1 ms run of each, compared whole.
  const fs::path short_series = scratch.dir / "short.csv";
  REQUIRE(
      run_command(cli("simulate --case 1 --t-end 1ms --out " + short_series.string())).exit_code ==
      0);
  gearimpact::SimulationCase c = gearimpact::paper_case(1);
  c.integrator.end_time_s = 1e-3;
  const std::string kept = gearimpact::series_csv(gearimpact::simulate(c).series);
  std::ifstream in(short_series, std::ios::binary);
  const std::string streamed((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  CHECK(streamed.size() == kept.size());
  CHECK(streamed == kept);
#endif
}

TEST_CASE("a series run ended by SIGINT, SIGTERM or SIGKILL leaves nothing beside its output") {
  Scratch scratch("edges-signal");
  const fs::path series = scratch.dir / "series.csv";
  for (const char* signal_name : {"INT", "TERM", "KILL"}) {
    CAPTURE(signal_name);
    // Some seconds of streaming (2 million rows); the signal comes 0.5 s after the handlers.
    run_command(signal_when_under_way(
        cli("simulate --case 1 --t-end 200ms --out " + series.string()) + " >/dev/null 2>&1",
        signal_name, 0.5));
    // The streamed rows went to an anonymous file, which ends with the process.
    CHECK(fs::is_empty(scratch.dir));
  }
}

TEST_CASE("a series longer than the row budget is refused before the run, with the estimate") {
  Scratch scratch("edges-rows");
  const fs::path series = scratch.dir / "series.csv";
  // 10 s at the 0.1 us step: 1e8 + 1 rows, twice the default budget of 5e7.
  const CommandResult r = run_command(cli("simulate --case 1 --t-end 10 --out " + series.string()));
  CHECK(r.exit_code == 1);
  for (const char* part : {"--t-end = 10 ", "at most 50000000 rows", "about 100000001 rows",
                           "about 14 GB", "--every", "--max-rows"}) {
    CAPTURE(part);
    CHECK(r.err.find(part) != std::string::npos);
  }
  CHECK(fs::is_empty(scratch.dir));
  // --every thins the series below the bound; --max-rows sets the bound.
  const CommandResult thin = run_command(
      cli("simulate --case 1 --t-end 1ms --every 10 --max-rows 1001 --out " + series.string()));
  CHECK_MESSAGE(thin.exit_code == 0, thin.err);
  const CommandResult tight = run_command(
      cli("simulate --case 1 --t-end 1ms --every 10 --max-rows 1000 --out " + series.string()));
  CHECK(tight.exit_code == 1);
  CHECK(tight.err.find("about 1001 rows") != std::string::npos);
  const CommandResult bad = run_command(cli("simulate --case 1 --max-rows 0"));
  CHECK(bad.exit_code == 1);
  CHECK(bad.err.find("--max-rows = 0") != std::string::npos);
}

TEST_CASE("a full disk fails the run naming the output, and leaves nothing on the disk") {
  Scratch scratch("edges-disk");
  const SmallDisk disk(scratch.dir / "disk");
  if (!disk.mounted) {
    MESSAGE("skipped: this user may not mount a tmpfs to fill");
    return;
  }
  // 10 ms of case 1 is 14 MB of series against 1 MiB of disk.
  const fs::path series = disk.dir / "series.csv";
  const CommandResult r =
      run_command(cli("simulate --case 1 --t-end 10ms --out " + series.string()));
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("gearimpact: error: cannot write " + series.string()) != std::string::npos);
  CHECK(r.err.find("No space left on device") != std::string::npos);
  CHECK(fs::is_empty(disk.dir));
  // Standard output on the full disk: 20,000 stiffness rows are 2.5 MB.
  const CommandResult out =
      run_command(cli("stiffness --points 20000") + " > " + (disk.dir / "k.csv").string());
  CHECK(out.exit_code == 1);
  CHECK(out.err.find("standard output") != std::string::npos);
  fs::remove(disk.dir / "k.csv");
  // A sweep's folder on a disk filled to the last page: the run fails naming
  // it, and nothing of it stays beside the filler.
  {
    std::ofstream filler(disk.dir / "filler", std::ios::binary);
    const std::string page(4096, 'x');
    while (filler.write(page.data(), static_cast<std::streamsize>(page.size()))) {
    }
  }
  const fs::path folder = disk.dir / "sweep";
  const CommandResult sweep =
      run_command(cli("sweep 1 --vary initial.w1 --from 2000 --to 3000 --points 3 --set "
                      "model.friction_coefficient=0 --set 'torque1.mean=3 N*m' --set "
                      "model.mesh_damping_ratio=0.05 --no-plots --out " +
                      folder.string()));
  CHECK(sweep.exit_code == 1);
  CHECK(sweep.err.find("No space left on device") != std::string::npos);
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(disk.dir)) {
    names.push_back(entry.path().filename().string());
  }
  CHECK(names == std::vector<std::string>{"filler"});
}

namespace {

// An output's columns as docs/usage.md lists them: a Markdown table of name and unit.
template <typename Row>
std::string documented(const gearimpact::Columns<Row>& columns) {
  std::string out = "| column | unit |\n|---|---|\n";
  for (const gearimpact::Column<Row>& c : columns) {
    out += "| `" + c.name + "` | " + (c.unit.empty() ? "-" : c.unit) + " |\n";
  }
  return out;
}

// The table docs/usage.md holds between "<!-- columns NAME -->" and "<!-- end columns -->".
std::string doc_table(const std::string& doc, const std::string& name) {
  const std::string open = "<!-- columns " + name + " -->\n";
  const std::size_t at = doc.find(open);
  if (at == std::string::npos) return "(no block " + name + ")";
  const std::size_t from = at + open.size();
  const std::size_t to = doc.find("<!-- end columns -->", from);
  if (to == std::string::npos) return "(block " + name + " not closed)";
  return doc.substr(from, to - from);
}

}  // namespace

TEST_CASE("docs/usage.md lists exactly the columns of each output's table") {
  std::ifstream in(fs::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "docs" / "usage.md");
  REQUIRE(in);
  const std::string doc{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  // A train of one body BODY and one mesh MESH: the names of its columns as the docs write them.
  gearimpact::GearTrain train;
  train.bodies.resize(1);
  train.bodies[0].name = "BODY";
  train.meshes.resize(1);
  train.meshes[0].name = "MESH";
  // A train of bodies A and B, one mesh MESH and a torsional shaft between them: its modes'
  // columns as the docs write them.
  gearimpact::GearTrain two_bodies;
  two_bodies.bodies.resize(2);
  two_bodies.bodies[0].name = "A";
  two_bodies.bodies[1].name = "B";
  two_bodies.meshes.resize(1);
  two_bodies.meshes[0].name = "MESH";
  gearimpact::TrainShaft shaft;
  shaft.kind = gearimpact::TrainShaft::Kind::torsional;
  shaft.body_a = 0;
  shaft.body_b = 1;
  two_bodies.shafts = {shaft};
  const std::vector<std::pair<std::string, std::string>> tables{
      {"series", documented(gearimpact::series_columns())},
      {"samples", documented(gearimpact::sample_columns())},
      {"planar-series", documented(gearimpact::planar_series_columns())},
      {"planar-series-helical", documented(gearimpact::planar_series_columns(true))},
      {"planar-samples", documented(gearimpact::planar_sample_columns())},
      {"train-series", documented(gearimpact::train_series_columns(train))},
      {"rattle-impacts", documented(gearimpact::rattle_impact_columns())},
      {"planetary-modes", documented(gearimpact::stage_modes_columns())},
      {"train-modes", documented(gearimpact::train_modes_columns(two_bodies))}};
  for (const auto& [name, expected] : tables) {
    INFO("docs/usage.md's block \"<!-- columns " << name << " -->\" should read:\n" << expected);
    CHECK(doc_table(doc, name) == expected);
  }
  // The CSV headers are the tables' names.
  CHECK(gearimpact::series_csv_header() ==
        "t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,s_m,delta_m,region,pairs,normal_force_N,"
        "friction_force_N\n");
}
