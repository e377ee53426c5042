#include "report.hpp"

namespace gearimpact::cli {

std::string to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::pass:
      return "pass";
    case Verdict::fail:
      return "FAIL";
    case Verdict::known_difference:
      return "known difference";
  }
  return "FAIL";
}

std::string markdown_table(const std::vector<ReportRow>& rows) {
  std::string table =
      "| id | statement | source | paper | ours | tolerance | verdict | note |\n"
      "|---|---|---|---|---|---|---|---|\n";
  for (const ReportRow& row : rows) {
    table += "| " + row.id + " | " + row.statement + " | " + row.source + " | " + row.paper +
             " | " + row.ours + " | " + row.tolerance + " | " + to_string(row.verdict) + " | " +
             row.note + " |\n";
  }
  return table;
}

}  // namespace gearimpact::cli
