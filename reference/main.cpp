// gearimpact: the reference program that runs the paper's cases.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>

#include "commands.hpp"
#include "gearimpact/io/atomic_file.hpp"

int main(int argc, char** argv) {
  // An interrupted run leaves no temporary file, and a file-size limit is an
  // error with a message, not a silent SIGXFSZ.
  gearimpact::remove_temporaries_on_signals();
  CLI::App app{"gearimpact: spur gear impact dynamics after Yang and Lin (1987)"};
  app.require_subcommand(1);
  gearimpact::cli::register_stiffness_commands(app);
  gearimpact::cli::register_reproduce_commands(app);
  gearimpact::cli::register_report_commands(app);
  gearimpact::cli::register_simulate_commands(app);
  gearimpact::cli::register_case_commands(app);
  gearimpact::cli::register_schema_commands(app);
  gearimpact::cli::register_sweep_commands(app);
  gearimpact::cli::register_signals_commands(app);
  gearimpact::cli::register_ste_commands(app);
  gearimpact::cli::register_modes_commands(app);
  gearimpact::cli::register_fe_commands(app);
  int status = 0;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {
      // --help and --version.
      status = app.exit(e);
    } else {
      // One prefix and one exit status for every refusal, the parser's too.
      std::cerr << "gearimpact: error: " << e.what() << " (see --help)\n";
      status = 1;
    }
  } catch (const std::exception& e) {
    std::cerr << "gearimpact: error: " << e.what() << '\n';
    status = 1;
  }
  // A write to standard output that failed (a full disk behind a redirection,
  // a closed pipe) is an error, not a success with the output lost.
  std::cout.flush();
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::cerr << "gearimpact: error: cannot write standard output: " << std::strerror(errno)
              << '\n';
    return 1;
  }
  return status;
}
