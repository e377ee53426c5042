// Reads the statement files of paper_data/ (see paper_data/README.md).
#pragma once

#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace gearimpact::verify {

struct PaperStatement {
  std::string id;
  std::string quantity;
  double paper_low = 0.0;
  double paper_high = 0.0;
  double tolerance = 0.0;
  bool relative = false;
  std::string page;
  std::string source;

  // Whether `ours` matches `paper` within this statement's tolerance.
  bool matches(double ours, double paper) const {
    const double allowed = relative ? tolerance * std::abs(paper) : tolerance;
    return std::abs(ours - paper) <= allowed;
  }
};

// Splits one CSV line; fields may be double-quoted (commas inside quotes).
inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

inline std::map<std::string, PaperStatement> read_statements(const std::string& file_name) {
  const std::string path = std::string(GEARIMPACT_PAPER_DATA_DIR) + "/" + file_name;
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_line(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  std::map<std::string, PaperStatement> statements;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv_line(line);
    PaperStatement s;
    s.id = f.at(column.at("id"));
    s.quantity = f.at(column.at("quantity"));
    s.paper_low = std::stod(f.at(column.at("paper_low")));
    s.paper_high = std::stod(f.at(column.at("paper_high")));
    s.tolerance = std::stod(f.at(column.at("tolerance")));
    s.relative = f.at(column.at("tolerance_kind")) == "rel";
    s.page = f.at(column.at("page"));
    s.source = f.at(column.at("source"));
    statements[s.id] = s;
  }
  return statements;
}

}  // namespace gearimpact::verify
