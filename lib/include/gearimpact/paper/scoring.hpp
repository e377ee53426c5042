// How a result is scored against the paper's statements (paper_data/): the
// quantities the statements are about, computed once, for the suites of
// verify/ and for the report of `reproduce`.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "gearimpact/batch/sweep_friction.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/paper/statements.hpp"

namespace gearimpact {

// Fig. 7's statements: "fig7_case<N>_f001" at f = 0.01 and "..._f009" at 0.09.
std::string fig7_statement_id(int case_number, bool at_largest_friction);

// Damping loss / friction loss (what the text quotes) of the case_index-th
// case at the row of the sweep nearest to f.
double damping_over_friction(const std::vector<SweepRow>& rows, std::size_t case_index, double f);

// "almost linearly related": the spread (max - min) / mean of
// (friction loss / damping loss) / f over the rows; 0 for an exactly linear law.
double linearity_spread(const std::vector<SweepRow>& rows, std::size_t case_index);

// Case 2: whether the first two impacts are on different lines.
bool impacts_alternate_first(const std::vector<ImpactRecord>& impacts);

// The larger miss of a range statement's two ends, in units of its tolerance.
double range_tolerances_off(const PaperStatement& s, double low, double high);

// A tally of statements met: each counts as met within one tolerance.
struct StatementTally {
  int met = 0;
  int count = 0;
  double worst_tolerances_off = 0.0;
  double sum_tolerances_off = 0.0;
  void add(const PaperStatement& s, double ours, double paper);
  double mean_tolerances_off() const { return count == 0 ? 0.0 : sum_tolerances_off / count; }
};

}  // namespace gearimpact
