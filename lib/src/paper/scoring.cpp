#include "gearimpact/paper/scoring.hpp"

#include <algorithm>
#include <cmath>

#include "gearimpact/error.hpp"

namespace gearimpact {

std::string fig7_statement_id(int case_number, bool at_largest_friction) {
  return "fig7_case" + std::to_string(case_number) + (at_largest_friction ? "_f009" : "_f001");
}

double damping_over_friction(const std::vector<SweepRow>& rows, std::size_t case_index, double f) {
  if (rows.empty()) throw InputError("rows", "none", "at least one row of a friction sweep");
  const auto row =
      std::min_element(rows.begin(), rows.end(), [&](const SweepRow& a, const SweepRow& b) {
        return std::abs(a.friction_coefficient - f) < std::abs(b.friction_coefficient - f);
      });
  return 1.0 / row->ratio.at(case_index);
}

double linearity_spread(const std::vector<SweepRow>& rows, std::size_t case_index) {
  if (rows.empty()) throw InputError("rows", "none", "at least one row of a friction sweep");
  double low = rows.front().ratio.at(case_index) / rows.front().friction_coefficient;
  double high = low;
  for (const SweepRow& row : rows) {
    const double slope = row.ratio.at(case_index) / row.friction_coefficient;
    low = std::min(low, slope);
    high = std::max(high, slope);
  }
  return (high - low) / (0.5 * (high + low));
}

bool impacts_alternate_first(const std::vector<ImpactRecord>& impacts) {
  return impacts.size() >= 2 && impacts[0].line != impacts[1].line;
}

double range_tolerances_off(const PaperStatement& s, double low, double high) {
  return std::max(s.tolerances_off(low, s.paper_low), s.tolerances_off(high, s.paper_high));
}

void StatementTally::add(const PaperStatement& s, double ours, double paper) {
  const double off = s.tolerances_off(ours, paper);
  worst_tolerances_off = std::max(worst_tolerances_off, off);
  sum_tolerances_off += off;
  met += off <= 1.0;
  ++count;
}

}  // namespace gearimpact
