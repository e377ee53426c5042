// The mesh stiffness of one pair as a precomputed function of the contact
// position, for use in the time integration where adaptive quadrature per call
// would dominate the cost. Built once from the adaptive quadrature of
// stiffness.hpp as piecewise Chebyshev series (GSL's gsl_cheb) over the
// contact segment [X_start, X_end].
#pragma once

#include <memory>
#include <vector>

#include "gearimpact/gear_pair.hpp"
#include "gearimpact/stiffness.hpp"

namespace gearimpact {

// The series compliances of one pair at a contact position, m/N.
struct PairCompliance {
  double hertz_m_per_n;    // 1/Kh
  double bending_m_per_n;  // 1/Kb1 + 1/Kb2
  double axial_m_per_n;    // 1/Ka1 + 1/Ka2
  double total_m_per_n() const { return hertz_m_per_n + bending_m_per_n + axial_m_per_n; }
};

struct StiffnessTableOptions {
  int pieces = 16;  // equal subintervals of the contact segment
  int order = 20;   // Chebyshev order on each
};

class StiffnessTable {
 public:
  explicit StiffnessTable(const GearPair& pair, const StiffnessModel& model = {},
                          StiffnessTableOptions options = {});
  StiffnessTable(StiffnessTable&&) noexcept;
  StiffnessTable& operator=(StiffnessTable&&) noexcept;
  ~StiffnessTable();

  double domain_start_m() const { return start_; }
  double domain_end_m() const { return end_; }

  // Throws InputError for x1 outside [X_start, X_end].
  PairCompliance compliance(double x1_m) const;
  // Ke = 1 / total compliance, N/m.
  double stiffness(double x1_m) const;
  // dKe/dX1, N/m^2, from the differentiated series.
  double stiffness_derivative(double x1_m) const;

 private:
  struct Series;
  std::size_t piece_of(double x1_m) const;

  double start_ = 0.0;
  double end_ = 0.0;
  double piece_width_ = 0.0;
  double hertz_compliance_ = 0.0;
  std::vector<std::unique_ptr<Series>> pieces_;
};

}  // namespace gearimpact
