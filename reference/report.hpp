// REPORT.md of `gearimpact reproduce`: one row per quantitative statement of
// the paper, with the paper's value, ours, the tolerance and the verdict.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gearimpact::cli {

enum class Verdict { pass, fail, known_difference };

struct ReportRow {
  std::string id;         // the paper_data statement id
  std::string statement;  // the quantity, in words
  std::string source;     // page and figure/section
  std::string paper;      // the paper's value, as text
  std::string ours;       // ours, as text
  std::string tolerance;  // as text, with its kind
  Verdict verdict = Verdict::fail;
  std::string note;  // for a known difference: why, and by how much
};

struct ReportSection {
  std::string title;
  std::string text;  // Markdown before the table (may be empty)
  std::vector<ReportRow> rows;
};

std::string to_string(Verdict verdict);

// Markdown of the rows of one section, as a table.
std::string markdown_table(const std::vector<ReportRow>& rows);

}  // namespace gearimpact::cli
