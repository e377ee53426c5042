// The statement files of paper_data/ (see paper_data/README.md): what the
// paper states, with page and figure, and how close a reproduction must come.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace gearimpact {

struct PaperStatement {
  std::string id;
  std::string quantity;
  std::string unit;
  double paper_low = 0.0;
  double paper_high = 0.0;
  double tolerance = 0.0;
  bool relative = false;
  std::string why;  // why the tolerance has its size
  std::string page;
  std::string source;
  std::string quote;

  // Whether `ours` matches `paper` within this statement's tolerance.
  bool matches(double ours, double paper) const;
  // |ours - paper| in units of the tolerance at `paper`.
  double tolerances_off(double ours, double paper) const;
};

// Splits one CSV line; fields may be double-quoted (with commas inside).
std::vector<std::string> split_csv_line(const std::string& line);

// Reads a statement file, keyed by id. Throws Error naming the
// file and line for a missing column or a malformed number.
std::map<std::string, PaperStatement> read_statements(const std::filesystem::path& file);

}  // namespace gearimpact
