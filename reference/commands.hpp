// Subcommands of the gearimpact program, one registration function a group.
#pragma once

#include <CLI/CLI.hpp>

namespace gearimpact::cli {

// `stiffness`, `energy-ratios`, `mesh-stiffness`, `iso6336`: tables of the
// mesh stiffness and of Fig. 8, the stiffness over one mesh period, ISO 6336-1.
void register_stiffness_commands(CLI::App& app);

// `reproduce`: every figure of the paper and REPORT.md into a folder.
void register_reproduce_commands(CLI::App& app);
// `report CASE --out DIR`: everything that applies to one pair (pair_report.cpp).
void register_report_commands(CLI::App& app);
// `simulate` (one case of Table 1 or a case file) and `sweep-friction` (Fig. 7).
void register_simulate_commands(CLI::App& app);
// `check-case FILE`: reads and validates a case file, prints it in SI units.
void register_case_commands(CLI::App& app);
// `schema`: every case-file key with its unit, default and range, as Markdown.
void register_schema_commands(CLI::App& app);
// `ste CASE --torque T --out DIR`: the loaded static transmission error (ste_commands.cpp).
void register_ste_commands(CLI::App& app);
// `sweep` (the steady state along a parameter) and `merge` (its shards).
void register_sweep_commands(CLI::App& app);
// `signals IN.csv --column NAME --out DIR`: spectrum, order spectrum, TSA, indicators.
void register_signals_commands(CLI::App& app);
// `modes CASE --out DIR`: the linearised planar model's natural modes and Campbell diagram.
void register_modes_commands(CLI::App& app);
// `train CASE --out DIR`: a gear train's run, its series and summary (train_commands.cpp).
void register_train_commands(CLI::App& app);
// `fe-check CASE --out DIR`: the tooth compliance by finite elements (fe_commands.cpp).
void register_fe_commands(CLI::App& app);
// `dataset SPEC --out DIR` and `dataset merge`: labelled data sets (dataset_commands.cpp).
void register_dataset_commands(CLI::App& app);

}  // namespace gearimpact::cli
