// Fig. 7: friction loss / damping loss of each base case against the friction
// coefficient, every run on a RunPool.
#pragma once

#include <future>
#include <vector>

#include "gearimpact/batch/pool.hpp"
#include "gearimpact/dynamics/simulation_case.hpp"

namespace gearimpact {

struct SweepRow {
  double friction_coefficient;
  std::vector<double> ratio;  // one per base case, in order
};

// The friction values of a sweep: from, from + step, ... up to `to` (`to`
// itself when (to - from) / step is an integer up to rounding). Throws
// InputError naming from, to or step outside their ranges.
std::vector<double> friction_values(double from, double to, double step);

// The runs of a sweep, submitted to a pool; get() waits for them.
class FrictionSweep {
 public:
  FrictionSweep(RunPool& pool, const std::vector<SimulationCase>& cases, double from, double to,
                double step);
  // Throws SimulationError for a run without damping loss (the ratio is then undefined).
  std::vector<SweepRow> get() const;

 private:
  std::vector<double> frictions_;
  std::size_t cases_ = 0;
  std::vector<std::shared_future<SimulationResult>> runs_;  // friction-major
};

// The sweep on a pool of its own with `threads` threads (0: all cores); the
// result does not depend on the thread count.
std::vector<SweepRow> sweep_friction(const std::vector<SimulationCase>& cases, double from,
                                     double to, double step, unsigned threads = 0);

}  // namespace gearimpact
