#include "gearimpact/paper/statements.hpp"

#include <cmath>
#include <fstream>

#include "gearimpact/error.hpp"

namespace gearimpact {

bool PaperStatement::matches(double ours, double paper) const {
  return tolerances_off(ours, paper) <= 1.0;
}

double PaperStatement::tolerances_off(double ours, double paper) const {
  const double allowed = relative ? tolerance * std::abs(paper) : tolerance;
  return std::abs(ours - paper) / allowed;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  return fields;
}

std::map<std::string, PaperStatement> read_statements(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error("cannot open " + file.string());
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = split_csv_line(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  std::map<std::string, PaperStatement> statements;
  int line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv_line(line);
    const auto field = [&](const char* name) -> const std::string& {
      const auto it = column.find(name);
      if (it == column.end() || it->second >= f.size()) {
        throw Error(file.string() + ":" + std::to_string(line_number) + ": no column '" + name +
                    "'");
      }
      return f[it->second];
    };
    const auto number = [&](const char* name) {
      try {
        return std::stod(field(name));
      } catch (const std::logic_error&) {
        throw Error(file.string() + ":" + std::to_string(line_number) + ": column '" + name +
                    "' is not a number: '" + field(name) + "'");
      }
    };
    PaperStatement s;
    s.id = field("id");
    s.quantity = field("quantity");
    s.unit = field("unit");
    s.paper_low = number("paper_low");
    s.paper_high = number("paper_high");
    s.tolerance = number("tolerance");
    s.relative = field("tolerance_kind") == "rel";
    s.why = field("why");
    s.page = field("page");
    s.source = field("source");
    s.quote = field("quote");
    statements[s.id] = s;
  }
  return statements;
}

}  // namespace gearimpact
