// Runs an outside program (gnuplot, gmsh, CalculiX) from an argument vector:
// no shell ever sees a path or a user's string.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gearimpact::cli {

struct ProgramCall {
  std::vector<std::string> argv;  // argv[0] is looked up on PATH
  std::filesystem::path dir;      // the program's working folder
  std::string shown;              // what the messages name: "gnuplot on DIR/NAME.gp"
  std::string missing_hint;       // added when the program is not found
  // Extra "NAME=value" entries of its environment (they replace the same names).
  std::vector<std::string> environment;
  // Its standard output goes with its standard error into the messages (else to /dev/null).
  bool capture_output = false;
};

// Runs the call to its end with its standard input from /dev/null and returns
// its messages (standard error, and standard output when captured). Throws
// std::runtime_error "cannot run PROGRAM on ...: REASON (HINT)" where it
// cannot start, or "PROGRAM failed on ...: MESSAGES" where it exits otherwise
// than with status 0.
std::string run_program(const ProgramCall& call);

// The program `name` is found on PATH (an executable file of that name).
bool on_path(const std::string& name);

}  // namespace gearimpact::cli
