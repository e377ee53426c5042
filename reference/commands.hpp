// Subcommands of the gearimpact program, one registration function a group.
#pragma once

#include <CLI/CLI.hpp>

namespace gearimpact::cli {

// `stiffness` and `energy-ratios`: tables of the mesh stiffness and of Fig. 8.
void register_stiffness_commands(CLI::App& app);

// `check-case FILE`: reads and validates a case file, prints it in SI units.
void register_case_commands(CLI::App& app);

}  // namespace gearimpact::cli
