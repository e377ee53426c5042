// gearimpact: the reference program that runs the paper's cases.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"gearimpact: spur gear impact dynamics after Yang and Lin (1987)"};
  app.require_subcommand(1);
  gearimpact::cli::register_stiffness_commands(app);
  gearimpact::cli::register_reproduce_commands(app);
  gearimpact::cli::register_simulate_commands(app);
  gearimpact::cli::register_case_commands(app);
  gearimpact::cli::register_schema_commands(app);
  gearimpact::cli::register_sweep_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "gearimpact: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
