// Where the program finds the paper's data (the statements of paper_data/),
// with no path compiled in: the same layout serves the build tree and an
// installed prefix.
#pragma once

#include <filesystem>
#include <string>

namespace gearimpact::cli {

// The folder that holds dynamics_statements.csv, from the first of:
// `flag_value` (--paper-data) when not empty; the environment variable
// GEARIMPACT_PAPER_DATA when set and not empty; <folder of the program>/../
// share/gearimpact/paper_data (an installed prefix; the build tree links it to
// the source tree's paper_data). A choice that lacks the file is an error
// naming where it looked; there is no fallback past an explicit choice.
std::filesystem::path paper_data_dir(const std::string& flag_value);

}  // namespace gearimpact::cli
