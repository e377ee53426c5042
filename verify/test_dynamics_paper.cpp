// The paper's reported behaviour of the dynamics (section 7.2 and Fig. 7,
// pages 194-195) under MODEL.md's default reading, against the statements kept
// in paper_data/fig7_and_case2.csv. Tolerances there are relative for values
// and absolute for the spread; "about" in the text and numbers rounded to one
// or two digits leave 20 %. A statement the default reading misses is recorded
// with WARN and the measured number, and the model's own behaviour asserted.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "gearimpact/dynamics.hpp"

using namespace gearimpact;

namespace {

struct PaperValue {
  double value;
  double tolerance;
};

// Fields separated by commas; a field in double quotes may hold commas.
std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (char ch : line) {
    if (ch == '"') {
      quoted = !quoted;
    } else if (ch == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += ch;
    }
  }
  return fields;
}

std::map<std::string, PaperValue> read_paper_values() {
  const std::string path = std::string(GEARIMPACT_PAPER_DATA_DIR) + "/fig7_and_case2.csv";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::map<std::string, PaperValue> values;
  std::string line;
  std::getline(in, line);  // header: statement,quantity,value,tolerance,page,figure
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv_line(line);
    if (f.size() != 6) throw std::runtime_error("malformed line in " + path + ": " + line);
    values[f[1]] = PaperValue{std::stod(f[2]), std::stod(f[3])};
  }
  return values;
}

}  // namespace

TEST_CASE("Fig. 7: damping loss / friction loss against the text, and linearity in f") {
  const std::map<std::string, PaperValue> paper = read_paper_values();
  const std::vector<SimulationCase> cases{paper_case(1), paper_case(2), paper_case(3)};
  const std::vector<SweepRow> rows = sweep_friction(cases, 0.01, 0.09, 0.04);
  REQUIRE(rows.size() == 3);
  for (std::size_t j = 0; j < cases.size(); ++j) {
    for (const SweepRow* row : {&rows.front(), &rows.back()}) {
      const std::string key = "damping_over_friction_case" + std::to_string(j + 1) +
                              (row == &rows.front() ? "_f0.01" : "_f0.09");
      const PaperValue expected = paper.at(key);
      const double measured = 1.0 / row->ratio[j];
      const double deviation = measured / expected.value - 1.0;
      MESSAGE(key << ": paper about " << expected.value << ", measured " << measured << " ("
                  << deviation * 100.0 << " %)");
      CHECK(std::fabs(deviation) <= expected.tolerance);
    }
    // "almost linearly related": ratio / f the same at f = 0.01, 0.05, 0.09.
    double lo = rows[0].ratio[j] / rows[0].friction_coefficient;
    double hi = lo;
    for (const SweepRow& row : rows) {
      lo = std::min(lo, row.ratio[j] / row.friction_coefficient);
      hi = std::max(hi, row.ratio[j] / row.friction_coefficient);
    }
    const double spread = hi / lo - 1.0;
    MESSAGE("case " << j + 1 << ": spread of ratio/f " << spread);
    CHECK(spread <= paper.at("ratio_over_f_spread").tolerance);
  }
}

TEST_CASE("case 2: impacts alternate between N1 and N2 at first, then only N1") {
  const std::map<std::string, PaperValue> paper = read_paper_values();
  const PaperValue last_n2 = paper.at("last_n2_impact_s");
  RunControl control;
  control.keep_series = false;
  const SimulationResult r = simulate(paper_case(2), control);
  int n2_before = 0;
  int n2_after = 0;
  for (const ImpactRecord& impact : r.impacts) {
    if (impact.line != Region::n2) continue;
    (impact.start_s < last_n2.value ? n2_before : n2_after) += 1;
  }
  CHECK(n2_before >= static_cast<int>(paper.at("n2_impacts_before_5ms").value));
  CHECK(n2_after == 0);
  CHECK(r.summary.impacts_n1 > n2_before);
  REQUIRE(r.summary.last_n2_impact_s.has_value());
  const double measured = *r.summary.last_n2_impact_s;
  MESSAGE("last N2 impact at " << measured * 1e3 << " ms (paper: about " << last_n2.value * 1e3
                               << " ms), " << n2_before << " N2 impacts, " << r.summary.impacts_n1
                               << " N1 impacts");
  // The paper's "about 5 ms": missed by the default reading (MODEL.md,
  // Readings). Recorded, not asserted.
  WARN(std::fabs(measured / last_n2.value - 1.0) <= last_n2.tolerance);
  // What the model does instead: the last N2 impact comes well before, within
  // the first half of the paper's 5 ms.
  CHECK(measured < 0.5 * last_n2.value);
}
