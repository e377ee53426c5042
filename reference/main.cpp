// gearimpact: the reference program that runs the paper's cases.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "gearimpact/io/atomic_file.hpp"

namespace {

// Every option of `app` and its subcommands that takes a value refuses an empty one (which
// was taken for the option left out: its default, or nothing written), and a number refuses
// what is not plain decimal: CLI11 reads "0x10" as 16 and "0b11" as 3 into an integer, and
// "0x1p4", "inf" and "nan" into a double.
void refuse_empty_and_non_decimal(CLI::App& app) {
  for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
    for (CLI::Option* option : command->get_options([](const CLI::Option*) { return true; })) {
      if (option->get_expected_max() == 0 || option->get_type_size_max() == 0) continue;
      const std::string type = option->get_type_name();
      const bool integral = type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0;
      const bool floating = type.rfind("FLOAT", 0) == 0;
      // An empty description keeps the option's type in --help as it was.
      option->check(CLI::Validator(
          [integral, floating](std::string& value) -> std::string {
            if (value.empty()) {
              return "an empty value; give one, or leave the option out for its default";
            }
            const std::string allowed = integral ? "0123456789+-" : "0123456789+-.eE";
            if ((integral || floating) && value.find_first_not_of(allowed) != std::string::npos) {
              return "\"" + value + "\" is not a " +
                     (integral ? "whole number in decimal digits" : "decimal number") +
                     " (no 0x or 0b, no infinity or NaN)";
            }
            return "";
          },
          ""));
    }
    refuse_empty_and_non_decimal(*command);
  }
}

}  // namespace

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
  gearimpact::cli::register_train_commands(app);
  gearimpact::cli::register_sweep_commands(app);
  gearimpact::cli::register_signals_commands(app);
  gearimpact::cli::register_ste_commands(app);
  gearimpact::cli::register_modes_commands(app);
  gearimpact::cli::register_fe_commands(app);
  gearimpact::cli::register_dataset_commands(app);
  refuse_empty_and_non_decimal(app);
  int status = 0;
  try {
    // CLI11 says only "A subcommand is required" of a misspelt one.
    std::string known;
    bool found = false;
    for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
      known += (known.empty() ? "" : ", ") + command->get_name();
      found = found || (argc > 1 && command->check_name(argv[1]));
    }
    if (argc > 1 && argv[1][0] != '-' && !found) {
      throw std::runtime_error("no command \"" + std::string(argv[1]) +
                               "\"; the commands: " + known + " (see --help)");
    }
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
