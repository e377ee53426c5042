#include <gsl/gsl_version.h>

#include <Eigen/Core>
#include <boost/version.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <future>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "data_location.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "program.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

std::string number(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

ReportRow statement_row(const PaperStatement& s, const std::string& ours, bool matches) {
  ReportRow row;
  row.id = s.id;
  row.statement = s.quantity + (s.unit == "1" ? "" : " (" + s.unit + ")");
  row.source = "p. " + s.page + ", " + s.source;
  row.paper = s.paper_low == s.paper_high
                  ? number(s.paper_low, 4)
                  : number(s.paper_low, 4) + " to " + number(s.paper_high, 4);
  row.ours = ours;
  row.tolerance =
      (s.relative ? number(100.0 * s.tolerance, 3) + " %" : "± " + number(s.tolerance, 3)) + ": " +
      s.why;
  row.verdict = matches ? Verdict::pass : Verdict::fail;
  return row;
}

namespace {

struct ReproduceOptions {
  std::string out;
  std::string paper_data;  // empty: found by paper_data_dir
  bool fe = false;
};

std::string software_versions() {
  std::string text;
#if defined(__clang__)
  text += "- compiler: clang " + std::string(__clang_version__) + "\n";
#elif defined(__GNUC__)
  text += "- compiler: GCC " + std::string(__VERSION__) + "\n";
#endif
  text += "- GSL " + std::string(GSL_VERSION) + ", Boost " + std::string(BOOST_LIB_VERSION) +
          ", Eigen " + std::to_string(EIGEN_WORLD_VERSION) + "." +
          std::to_string(EIGEN_MAJOR_VERSION) + "." + std::to_string(EIGEN_MINOR_VERSION) + "\n";
  FILE* pipe = ::popen("gnuplot --version 2>/dev/null", "r");
  if (pipe != nullptr) {
    char line[128] = {};
    if (std::fgets(line, sizeof line, pipe) != nullptr) text += "- " + std::string(line);
    ::pclose(pipe);
  }
  return text;
}

}  // namespace

std::filesystem::path reproduce(const std::filesystem::path& out,
                                const std::string& paper_data_option, bool with_fe) {
  const auto started = std::chrono::steady_clock::now();
  const std::filesystem::path paper_data = paper_data_dir(paper_data_option);
  RunPool pool;
  ReproduceContext context{out, paper_data, &pool};
  std::filesystem::create_directories(context.out);
  struct Part {
    const char* what;
    ReportSection (*run)(const ReproduceContext&);
  };
  std::vector<Part> parts{{"Figs. 4-6 time histories of cases 1-3", reproduce_time_histories},
                          {"Fig. 7 friction sweep, 27 runs", reproduce_fig7},
                          {"Fig. 8 energy ratios", reproduce_fig8},
                          {"stiffness models and ISO 6336-1", reproduce_stiffness},
                          {"the open readings side by side", reproduce_readings},
                          {"case 3 ensemble", reproduce_case3_ensemble},
                          {"steady state of the loaded pair", reproduce_steady_state},
                          {"rattle map of a loose gear, 512 runs", reproduce_rattle},
                          {"tooth faults and modifications", reproduce_faults},
                          {"vibration of a healthy and a cracked pinion", reproduce_vibration},
                          {"planetary stage: modes and the ring sensor", reproduce_planetary}};
  if (with_fe) parts.push_back({"finite-element check of the tooth compliance", reproduce_fe});
  // The parts run side by side: each submits its simulations to the one pool
  // and waits for them, so the cores stay busy until the last run is done.
  std::vector<std::future<std::pair<ReportSection, double>>> running;
  for (const Part& part : parts) {
    running.push_back(std::async(std::launch::async, [&context, &started, part] {
      ReportSection section = part.run(context);
      return std::make_pair(
          std::move(section),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    }));
  }
  std::vector<ReportSection> sections;
  std::cerr << "reproduce: " << pool.threads()
            << " simulation threads; the parts run side by side, each time is when it was done\n";
  for (std::size_t i = 0; i < parts.size(); ++i) {
    auto [section, done_s] = running[i].get();
    sections.push_back(std::move(section));
    std::cerr << "reproduce: " << parts[i].what << " ... " << number(done_s, 3) << " s\n";
  }
  std::cerr << "reproduce: " << pool.computed() << " simulations run for " << pool.requested()
            << " asked for\n";
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::string report = "# gearimpact: reproduction of Yang and Lin (1987)\n\n";
  report +=
      "Each row is a quantitative statement of the paper, kept with its page in `paper_data/`. "
      "Verdict `known difference` marks a statement this implementation misses for a reason "
      "given in the note; `FAIL` one it misses without an explanation.\n\n";
  int unexplained = 0;
  for (const ReportSection& section : sections) {
    report += "## " + section.title + "\n\n" + section.text + "\n";
    if (!section.rows.empty()) report += markdown_table(section.rows) + "\n";
    for (const ReportRow& row : section.rows) unexplained += row.verdict == Verdict::fail;
  }
  report += "## Run\n\n" + software_versions() + "- wall time: " + number(wall_s, 3) + " s\n";
  report += "- unexplained failures: " + std::to_string(unexplained) + "\n";
  write_file_atomically((context.out / "REPORT.md").string(), report);
  std::cerr << "reproduce: wrote " << (context.out / "REPORT.md").string() << " in "
            << number(wall_s, 3) << " s\n";
  return context.out / "REPORT.md";
}

void register_reproduce_commands(CLI::App& app) {
  auto options = std::make_shared<ReproduceOptions>();
  CLI::App* command = app.add_subcommand(
      "reproduce", "Reproduce the paper's figures and statements into a folder, with REPORT.md");
  command->add_option("--out", options->out, "output folder (created if missing)")->required();
  command->add_option("--paper-data", options->paper_data,
                      "folder of the paper's statements (default: $GEARIMPACT_PAPER_DATA, else "
                      "share/gearimpact/paper_data beside the program's folder)");
  command->add_flag("--fe", options->fe,
                    "add the finite-element check of the tooth compliance (gmsh, CalculiX; "
                    "minutes): the paper's wheel healthy and cracked, the rig pair's spall in 3-D");
  command->callback([options] { reproduce(options->out, options->paper_data, options->fe); });
}

}  // namespace gearimpact::cli
