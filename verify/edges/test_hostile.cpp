// Hostile input through the program, as an attacker or a careless user writes it: a column's
// name built to run a command in gnuplot, a tooth number past int32, a FIFO, a line of NULs or a
// header of megabytes where a CSV belongs, a sample rate whose grid does not fit in memory. Each
// refusal exits 1 with one "gearimpact: error:" message that names the key or flag, prints no
// nan, leaves no output folder or temporary folder; each accepted input still draws its figures
// and runs nothing. Devices and FIFOs are made in a temporary folder, never the machine's own.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "run_command.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;
using gearimpact::verify::cli;
using gearimpact::verify::CommandResult;
using gearimpact::verify::run_command;
using gearimpact::verify::Scratch;

namespace {

const fs::path kExamples = fs::path(GEARIMPACT_PAPER_DATA_DIR).parent_path() / "examples";

// Single quotes for the shell that run_command uses to start the program.
std::string single_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char ch : text) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return quoted + "'";
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The names in `dir` (a refusal leaves nothing: no output, no hidden temporary folder).
std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename());
  return names;
}

// One refusal: exit 1, one "gearimpact: error:" message naming `key`, no nan, nothing on
// standard output.
void check_refusal(const CommandResult& r, const std::string& key) {
  INFO(r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.err.rfind("gearimpact: error: ", 0) == 0);
  CHECK(r.err.find(key) != std::string::npos);
  CHECK(r.err.find("nan") == std::string::npos);
  CHECK(r.out.empty());
}

// A record of ten revolutions of a shaft at 5 rev/s, 200 rows a revolution, and a signal of a
// 20-tooth gear's mesh order; the angle and the signal columns carry the given names.
void write_record(const fs::path& path, const std::string& angle, const std::string& signal,
                  const std::string& before_header = "") {
  std::ofstream out(path, std::ios::binary);
  out << before_header << "t_s," << angle << "," << signal << "\n";
  for (int i = 0; i <= 2000; ++i) {
    const double theta = 2.0 * std::numbers::pi * i / 200.0;
    char line[128];
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", i * 1e-3, theta,
                  1.0 + std::cos(20.0 * theta));
    out << line;
  }
}

}  // namespace

TEST_CASE("a column's name reaches gnuplot's scripts as inert text") {
  Scratch scratch("hostile-gnuplot");
  const fs::path dir = scratch.dir;
  // Each payload makes a file in the folder if gnuplot ever runs it: a backquote, system() in
  // double quotes, a quote that would close a single-quoted string, a macro, a carriage return
  // (a line break inside the script) before a command, a backslash that would continue a line.
  const std::string signal = "x`touch BACKQUOTE`'\"system(\"touch SYSTEM\")@m\\";
  const std::string angle = "a'.system('touch QUOTE').'\rsystem(\"touch NEWLINE\")";
  const fs::path csv = dir / "record.csv";
  write_record(csv, angle, signal);
  const fs::path out = dir / "out";
  const CommandResult r =
      run_command("cd " + single_quoted(dir.string()) + " && " +
                  cli("signals record.csv --column " + single_quoted(signal) + " --angle-column " +
                      single_quoted(angle) + " --teeth 20 --samples-per-revolution 160 --out out"));
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::set<std::string> left{"out", "record.csv"};
  CHECK(entries(dir) == left);
  // gnuplot runs in the output folder: a payload that ran would have left its file there.
  for (const char* made : {"BACKQUOTE", "SYSTEM", "QUOTE", "NEWLINE"}) {
    CAPTURE(made);
    CHECK_FALSE(fs::exists(out / made));
  }
  // The figures are drawn, each with the name in its title as text.
  for (const char* figure : {"waveform", "spectrum", "order_spectrum", "tsa"}) {
    CAPTURE(figure);
    CHECK(fs::file_size(out / (std::string(figure) + ".png")) > 0);
    CHECK(fs::file_size(out / (std::string(figure) + ".svg")) > 0);
  }
  CHECK(read(out / "waveform.gp").find("set title 'Waveform of x`touch BACKQUOTE`''") !=
        std::string::npos);
  // The scripts stay inert when a reader redraws them.
  const std::set<std::string> outputs = entries(out);
  for (const char* script : {"waveform.gp", "spectrum.gp", "order_spectrum.gp", "tsa.gp"}) {
    CAPTURE(script);
    const CommandResult again =
        run_command("cd " + single_quoted(out.string()) + " && gnuplot " + script);
    CHECK(again.exit_code == 0);
  }
  CHECK(entries(out) == outputs);
  CHECK(entries(dir) == left);
}

TEST_CASE("a fault's tooth beyond int32 is refused under its key, not wrapped") {
  Scratch scratch("hostile-tooth");
  const std::string text = read(kExamples / "cracked_pinion.toml");
  const std::string first = "tooth = 3\n";
  REQUIRE(text.find(first) != std::string::npos);
  // 2^31 once read as -2^31 (ste crashed); 2^32 as 0; -1 and the gear's 20 teeth are out too.
  for (const char* tooth : {"2147483648", "4294967296", "9223372036854775807", "-1", "20"}) {
    CAPTURE(tooth);
    std::string changed = text;
    changed.replace(changed.find(first), first.size(), "tooth = " + std::string(tooth) + "\n");
    const fs::path file = scratch.dir / "pair.toml";
    std::ofstream(file) << changed;
    const fs::path out = scratch.dir / "out";
    for (const std::string& command :
         {"check-case " + file.string(),
          "ste " + file.string() + " --torque '100 N*m' --out " + out.string(),
          "mesh-stiffness --case-file " + file.string() + " --samples 50 --figure " + out.string(),
          "stiffness --case-file " + file.string() + " --points 5"}) {
      CAPTURE(command);
      const CommandResult r = run_command(cli(command));
      check_refusal(r, "faults[0].tooth = " + std::string(tooth));
      CHECK(r.err.find(std::string(tooth) == "20" ? "0 ... 19" : "[0, 99999]") !=
            std::string::npos);
    }
    CHECK(entries(scratch.dir) == std::set<std::string>{"pair.toml"});
  }
}

TEST_CASE("signals reads a regular file only, within bounds, and quotes little of it") {
  Scratch scratch("hostile-signals");
  const fs::path dir = scratch.dir;
  const fs::path out = dir / "out";
  const auto signals = [&](const std::string& input, const std::string& more = "") {
    // `timeout` turns a hang (a FIFO without a writer once blocked for ever) into a failure.
    return run_command("timeout 60 " + cli("signals " + single_quoted(input) + " --column x " +
                                           more + " --no-plots --out " + out.string()));
  };

  // A FIFO with no writer: refused from its type, before an open for reading could block.
  const fs::path fifo = dir / "fifo.csv";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  check_refusal(signals(fifo.string()), "not a regular file");
  // A folder.
  check_refusal(signals(dir.string()), "not a regular file");
  // A device of NULs (/dev/zero's numbers), where this user may make one.
  const fs::path zero = dir / "zero";
  if (::mknod(zero.c_str(), S_IFCHR | 0666, makedev(1, 5)) == 0) {
    check_refusal(signals(zero.string()), "not a regular file");
    fs::remove(zero);
  }
  fs::remove(fifo);

  // A 16 MiB line of NULs after the header and two rows: refused at that line, the message
  // quoting a short prefix only.
  {
    const fs::path nul = dir / "nul.csv";
    {
      std::ofstream file(nul, std::ios::binary);
      file << "t_s,x\n0,1\n1,2\n" << std::string(std::size_t{16} << 20, '\0');
    }
    const CommandResult r = signals(nul.string());
    check_refusal(r, "nul.csv:4");
    CHECK(r.err.find("NUL") != std::string::npos);
    CHECK(r.err.size() < 600);
    fs::remove(nul);
  }
  // A 10 MB header line: refused as too long, not echoed.
  {
    const fs::path wide = dir / "wide.csv";
    std::ofstream(wide, std::ios::binary) << "t_s," << std::string(10000000, 'a') << "\n0,1\n";
    const CommandResult r = signals(wide.string());
    check_refusal(r, "wide.csv:1");
    CHECK(r.err.find("longer than 65536 bytes") != std::string::npos);
    CHECK(r.err.size() < 600);
    fs::remove(wide);
  }
  // A row with a field more than the header, two columns of one name.
  {
    const fs::path extra = dir / "extra.csv";
    write_record(extra, "theta_rad", "x");
    std::ofstream(extra, std::ios::app) << "2.001,1,1,7\n";
    check_refusal(signals(extra.string()), "extra.csv:2003");
    const fs::path twice = dir / "twice.csv";
    write_record(twice, "x", "x");
    const CommandResult r = signals(twice.string());
    check_refusal(r, "--column = x");
    CHECK(r.err.find("two columns") != std::string::npos);
    fs::remove(extra);
    fs::remove(twice);
  }
  // A sample rate inside the old bound whose grid (1e9 samples a second) does not fit: refused
  // with the estimate, before any grid is made.
  {
    const fs::path record = dir / "record.csv";
    write_record(record, "theta_rad", "x");
    const CommandResult r = signals(record.string(), "--sample-rate 1e9");
    check_refusal(r, "--sample-rate");
    CHECK(r.err.find("2e+09 samples") != std::string::npos);
    fs::remove(record);
  }
  // A gap of 40 % of the record (rows 401 to 1199 of 2001 left out), once bridged silently.
  {
    const fs::path gapped = dir / "gapped.csv";
    write_record(gapped, "theta_rad", "x");
    std::istringstream all(read(gapped));
    std::string kept;
    std::string line;
    for (int number = 0; std::getline(all, line); ++number) {
      if (number <= 401 || number >= 1201) kept += line + "\n";
    }
    std::ofstream(gapped, std::ios::binary) << kept;
    const CommandResult r = signals(gapped.string());
    check_refusal(r, "--time-column = t_s");
    CHECK(r.err.find("a gap of 0.8 s (40 % of the record)") != std::string::npos);
    fs::remove(gapped);
  }
  CHECK(entries(dir).empty());

  // Valid: a UTF-8 byte order mark before the header (a spreadsheet's export) is no part of
  // "t_s", and the spectrum is the one without it.
  const fs::path plain = dir / "plain.csv";
  const fs::path marked = dir / "marked.csv";
  write_record(plain, "theta_rad", "x");
  write_record(marked, "theta_rad", "x", "\xEF\xBB\xBF");
  const CommandResult a = signals(plain.string());
  REQUIRE(a.exit_code == 0);
  const std::string spectrum = read(out / "spectrum.csv");
  fs::remove_all(out);
  const CommandResult b = signals(marked.string());
  INFO(b.err);
  REQUIRE(b.exit_code == 0);
  CHECK(read(out / "spectrum.csv") == spectrum);
}

TEST_CASE("ste's angles are bounded by what they cost, before any work") {
  Scratch scratch("hostile-ste");
  const fs::path out = scratch.dir / "out";
  // The relieved pair's true period is 20 mesh periods: 100000 points a mesh period are 2e6
  // angles, over the 1e6 the bound allows (8e6 angles of another pair once took 9.3 GB of memory
  // and wrote 4.2 GB of CSV); the message gives the estimate, at 1.2 kB and 490 bytes an angle.
  const CommandResult r =
      run_command(cli("ste " + (kExamples / "tip_relief_20_80.toml").string() +
                      " --torque '100 N*m' --points 100000 --out " + out.string()));
  check_refusal(r, "--points = 100000");
  CHECK(r.err.find("at most 50000 per mesh period") != std::string::npos);
  CHECK(r.err.find("these 2000000 would take about 2.4 GB and write about 980 MB") !=
        std::string::npos);
  CHECK(entries(scratch.dir).empty());
}

TEST_CASE("SIGTERM while gnuplot draws stops gnuplot too and leaves no folder") {
  Scratch scratch("hostile-sigterm");
  // A stand-in for gnuplot, first on PATH: it writes its pid where the test reads it, then
  // draws for ever (sleep, in its own process as exec keeps the pid).
  const fs::path bin = scratch.dir / "bin";
  const fs::path work = scratch.dir / "work";
  const fs::path mark = scratch.dir / "gnuplot.pid";
  fs::create_directories(bin);
  fs::create_directories(work);
  std::ofstream(bin / "gnuplot") << "#!/bin/sh\necho $$ > '" << mark.string() << ".part' && mv '"
                                 << mark.string() << ".part' '" << mark.string()
                                 << "'\nexec sleep 60\n";
  fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  write_record(work / "record.csv", "theta_rad", "x");
  const std::string path = bin.string() + ":" + (std::getenv("PATH") ? std::getenv("PATH") : "");

  const pid_t program = ::fork();
  REQUIRE(program >= 0);
  if (program == 0) {
    if (::chdir(work.c_str()) != 0) ::_exit(127);
    const int log = ::open("../log.txt", O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(log, STDOUT_FILENO);
    ::dup2(log, STDERR_FILENO);
    ::setenv("PATH", path.c_str(), 1);
    ::execl(GEARIMPACT_CLI, GEARIMPACT_CLI, "signals", "record.csv", "--column", "x", "--out",
            "out", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // gnuplot has started once its pid is written (the program has then written its CSV files
  // into its hidden folder).
  for (int i = 0; i < 3000 && !fs::exists(mark); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  REQUIRE(fs::exists(mark));
  pid_t gnuplot = 0;
  std::ifstream(mark) >> gnuplot;
  REQUIRE(gnuplot > 0);
  REQUIRE(::kill(program, SIGTERM) == 0);
  int status = 0;
  REQUIRE(::waitpid(program, &status, 0) == program);
  CHECK(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGTERM);
  // The program stopped its child before it ended: the pid names no process any more.
  const bool alive = ::kill(gnuplot, 0) == 0;
  CHECK_FALSE(alive);
  if (alive) ::kill(gnuplot, SIGKILL);  // this test's own stray, so that none outlives it
  // Nothing is left beside the record: no output, no hidden temporary folder.
  CHECK(entries(work) == std::set<std::string>{"record.csv"});
}

TEST_CASE("counts in hexadecimal, empty values and flags that would do nothing are refused") {
  Scratch scratch("hostile-flags");
  const std::string out = (scratch.dir / "out").string();
  const std::string pair = (kExamples / "tip_relief_20_80.toml").string();
  const std::string rig = (kExamples / "rig_17_38.toml").string();
  const fs::path record = scratch.dir / "record.csv";
  write_record(record, "theta_rad", "x");
  struct Refused {
    std::string arguments;
    std::string names;  // what the message must hold: the flag, and why
  };
  const std::vector<Refused> refused{
      // CLI11 read 0x10 as 16; strtod reads it too.
      {"stiffness --points 0x10", "--points: \"0x10\" is not a whole number in decimal digits"},
      {"mesh-stiffness --samples 0x10", "--samples: \"0x10\""},
      {"ste " + pair + " --torque '100 N*m' --points 0x10 --out " + out, "--points: \"0x10\""},
      {"signals " + record.string() + " --column x --sample-rate 0x10 --out " + out,
       "--sample-rate = \"0x10\""},
      {"signals " + record.string() + " --column x --sample-rate inf --out " + out,
       "--sample-rate = \"inf\""},
      {"simulate --case 1 --t-end 1ms --dt 0x1p-20", "--dt"},
      // An empty value was the option left out: the default, or no file written.
      {"modes " + rig + " --max-speed '' --out " + out, "--max-speed: an empty value"},
      {"signals " + record.string() + " --column x --sample-rate '' --out " + out,
       "--sample-rate: an empty value"},
      {"simulate --case 1 --t-end 1ms --out ''", "--out: an empty value"},
      {"mesh-stiffness --samples 10 --figure ''", "--figure: an empty value"},
      // Flags that do nothing where they stand.
      {"simulate --case 1 --t-end 1ms --rtol 1e-8", "--rtol = 1e-8: not used by"},
      {"simulate --case 1 --t-end 1ms --case3-frequency 1000", "--case3-frequency = 1000"},
      {"sweep 1 --vary initial.w1 --from 1000 --to 2000 --points 2 --from2 1 --out " + out,
       "--from2 requires --vary2"},
      {"sweep 1 --vary initial.w1 --from 1000 --to 2000 --points 2 --points2 3 --out " + out,
       "--points2 requires --vary2"},
      {"mesh-stiffness --samples 10 --overwrite", "--overwrite requires --figure"},
      // Once blamed on --teeth with the range "3 to 0", and truncated to 3 then blamed on --t-end.
      {"signals " + record.string() +
           " --column x --angle-column theta_rad --teeth 20 --sidebands 100000 --out " + out,
       "--sidebands = 100000 is outside the allowed range: 0 to 9 for 20 teeth"},
      {"simulate --case 1 --t-end 1ms --max-rows 3.5", "--max-rows = 3.5"},
      // A misspelt command is named, with the commands there are.
      {"frobnicate", "no command \"frobnicate\"; the commands: stiffness"},
  };
  for (const Refused& r : refused) {
    CAPTURE(r.arguments);
    check_refusal(run_command(cli(r.arguments)), r.names);
    CHECK(entries(scratch.dir) == std::set<std::string>{"record.csv"});
  }
  // Positive controls: the same flags where they do something.
  for (const std::string& valid :
       {std::string("stiffness --points 16"),
        std::string("simulate --case 1 --t-end 0.1ms --integrator adaptive --rtol 1e-8"),
        std::string("simulate --case 3 --t-end 0.1ms --case3-frequency 1000")}) {
    CAPTURE(valid);
    const CommandResult r = run_command(cli(valid));
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("nan") == std::string::npos);
  }
}

TEST_CASE("values past any gear, bearing or shaft are refused under their own key") {
  // Each was once blamed on another key (gears.backlash, addendum_coefficient with "-inf m",
  // integrator.step, "did not converge") or failed mid-run with "X1 = nan".
  const std::string rig = (kExamples / "rig_17_38.toml").string();
  // The shafts elastic with the rig's values, but for `key`, which the test sets.
  const auto shafts = [](const std::string& key) {
    std::string text = " --set shafts.kind=elastic";
    for (const char* set : {"motor_inertia=2e-3 kg*m^2", "motor_stiffness=5e4 N*m/rad",
                            "load_inertia=8e-3 kg*m^2", "load_stiffness=9e4 N*m/rad"}) {
      if (std::string(set).rfind(key, 0) != 0) text += " --set 'shafts." + std::string(set) + "'";
    }
    return text;
  };
  struct Refused {
    std::string set;
    std::string key;
    std::string range;
  };
  const std::vector<Refused> refused{
      {"'gears.module=1e-30 m'", "gears.module = 1e-30 m", "[1e-6, 1] m"},
      {"'gears.module=1e300 m'", "gears.module = 1e300 m", "[1e-6, 1] m"},
      {"'bearings.damping_x1=1e300 N*s/m'", "bearings.damping_x1", "[0, 1000000] N*s/m"},
      {"'bearings.mass1=1e-300 kg'", "bearings.mass1", "[0.0001, 1000000] kg"},
      {"'bearings.stiffness_x1=1e-300 N/m'", "bearings.stiffness_x1", "[0.001, 1e16] N/m"},
      {shafts("motor_inertia") + " --set 'shafts.motor_inertia=1e-300 kg*m^2'",
       "shafts.motor_inertia", "[1e-12, 1000000]"},
      {shafts("load_stiffness") + " --set 'shafts.load_stiffness=1e300 N*m/rad'",
       "shafts.load_stiffness", "[0.001, 1000000000000]"},
  };
  for (const Refused& r : refused) {
    for (const std::string& command :
         {"simulate --case-file " + rig + " --t-end 1ms", "modes " + rig + " --out never-made"}) {
      CAPTURE(command);
      CAPTURE(r.set);
      const std::string set = r.set.rfind(" --set", 0) == 0 ? r.set : " --set " + r.set;
      const CommandResult result = run_command(cli(command + set));
      check_refusal(result, r.key);
      CHECK(result.err.find(r.range) != std::string::npos);
      CHECK_FALSE(fs::exists("never-made"));
    }
  }
}

TEST_CASE("an output folder that is a link or holds the current folder is refused before work") {
  Scratch scratch("hostile-out");
  const fs::path real = scratch.dir / "real";
  const fs::path inner = scratch.dir / "sub" / "inner";
  // ../link from inner: sub/link.
  fs::create_directories(real);
  fs::create_directories(inner);
  std::ofstream(real / "kept.txt") << "an earlier run's file\n";
  fs::create_directory_symlink(real, scratch.dir / "sub" / "link");
  const std::string rig = (kExamples / "rig_17_38.toml").string();
  // Once "Not a directory" and "Device or resource busy", after the work.
  for (const std::string& out : {std::string("../link"), std::string(".."), std::string(".")}) {
    CAPTURE(out);
    const CommandResult r =
        run_command("cd " + single_quoted(inner.string()) + " && " +
                    cli("modes " + rig + " --no-plots --overwrite --out " + single_quoted(out)));
    check_refusal(r, "cannot write the folder " + out + ": it");
  }
  CHECK(fs::exists(real / "kept.txt"));
  CHECK(fs::is_symlink(scratch.dir / "sub" / "link"));
  CHECK(entries(scratch.dir / "sub") == std::set<std::string>{"inner", "link"});
  CHECK(entries(inner).empty());
}

TEST_CASE("a gear with every tooth missing is refused under faults before work") {
  // Once `simulate` ran it with only an overlap warning while `ste` refused it.
  Scratch scratch("hostile-missing");
  const std::string healthy = read(kExamples / "cracked_pinion.toml");
  const std::string gears = healthy.substr(0, healthy.find("[[faults]]"));
  const auto all_missing = [&](const std::string& gear, int teeth, int skip) {
    std::string text = gears;
    for (int i = 0; i < teeth; ++i) {
      if (i == skip) continue;
      text += "\n[[faults]]\ngear = \"" + gear + "\"\ntooth = " + std::to_string(i) +
              "\nkind = \"missing\"\n";
    }
    return text;
  };
  const std::string out = (scratch.dir / "out").string();
  const std::string run =
      " --set torque1.kind=constant --set 'torque1.value=10 N*m' --set torque2.kind=constant "
      "--set 'torque2.value=40 N*m' --set 'integrator.end_time=1 ms' --out " +
      out;
  for (const auto& [gear, teeth] : {std::pair{"pinion", 20}, std::pair{"wheel", 80}}) {
    const fs::path file = scratch.dir / (std::string(gear) + ".toml");
    std::ofstream(file) << all_missing(gear, teeth, -1);
    for (const std::string& command : {"ste " + file.string() + " --torque '10 N*m' --out " + out,
                                       "simulate --case-file " + file.string() + run}) {
      CAPTURE(command);
      const CommandResult r = run_command(cli(command));
      check_refusal(r, "faults = all " + std::to_string(teeth) + " " + gear + " teeth missing");
      CHECK(r.err.find("no tooth is left to carry the load") != std::string::npos);
      CHECK(entries(scratch.dir) == std::set<std::string>{std::string(gear) + ".toml"});
    }
    fs::remove(file);
  }
  // Positive control: one pinion tooth left carries the load.
  const fs::path one_left = scratch.dir / "one_left.toml";
  std::ofstream(one_left) << all_missing("pinion", 20, 7);
  const CommandResult r =
      run_command(cli("ste " + one_left.string() + " --torque '10 N*m' --out " + out));
  CHECK(r.err.find("no tooth is left") == std::string::npos);
}

TEST_CASE("sweep-friction takes --set as docs/usage.md lists it, but not of the f it sweeps") {
  const CommandResult set = run_command(cli(
      "sweep-friction --from 0.01 --to 0.01 --step 0.01 --set model.restitution_coefficient=0.5"));
  INFO(set.err);
  CHECK(set.exit_code == 0);
  CHECK(set.out.rfind("f,ratio_case1,ratio_case2,ratio_case3\n0.01,", 0) == 0);
  CHECK(set.out.find("nan") == std::string::npos);
  // The same run without --set: the key changes the ratios, so --set was applied.
  const CommandResult plain = run_command(cli("sweep-friction --from 0.01 --to 0.01 --step 0.01"));
  CHECK(plain.exit_code == 0);
  CHECK(plain.out != set.out);
  check_refusal(run_command(cli("sweep-friction --set model.friction_coefficient=0.1")),
                "--set = model.friction_coefficient=0.1");
  check_refusal(run_command(cli("sweep-friction --set model.nonsense=1")), "model.nonsense");
}

TEST_CASE("a bearing damper faster than the step can follow is refused before work") {
  // c/m of 1e6 N*s/m on the rig's bearing mass is 4.2e6 1/s: h c/m = 4.2 at the rig's 1 us,
  // past RK4's real-axis limit 2.785, so the run once diverged to nan.
  const std::string rig = (kExamples / "rig_17_38.toml").string();
  for (const char* key : {"bearings.damping_x1", "bearings.damping_y2"}) {
    CAPTURE(key);
    const CommandResult r = run_command(
        cli("simulate --case-file " + rig + " --t-end 1ms --set '" + key + "=1e6 N*s/m'"));
    check_refusal(r, "integrator.step");
    CHECK(r.err.find(std::string(key) + " alone decays its centre") != std::string::npos);
  }
  // Positive control: the rig's own 500 N*s/m is far inside the bound.
  const CommandResult r = run_command(cli("simulate --case-file " + rig + " --t-end 0.05ms"));
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("nan") == std::string::npos);
}
