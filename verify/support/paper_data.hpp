// The statement files of paper_data/, for the suites.
#pragma once

#include <map>
#include <string>

#include "gearimpact/paper/statements.hpp"

namespace gearimpact::verify {

using gearimpact::PaperStatement;
using gearimpact::split_csv_line;

inline std::map<std::string, PaperStatement> read_statements(const std::string& file_name) {
  return gearimpact::read_statements(std::string(GEARIMPACT_PAPER_DATA_DIR) + "/" + file_name);
}

}  // namespace gearimpact::verify
