// Fig. 7: friction loss / damping loss of each base case against the friction
// coefficient, every run on a RunPool.
#pragma once

#include <functional>
#include <future>
#include <vector>

#include "gearimpact/batch/pool.hpp"
#include "gearimpact/case/simulation_case.hpp"

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
                double step, const std::function<bool()>& should_stop = {});
  // Throws SimulationError for a run without damping loss (the ratio is then
  // undefined). While it waits, the calling thread asks should_stop too, so a
  // hook that only the caller's thread can answer (Python's signal handlers)
  // still stops the runs.
  std::vector<SweepRow> get() const;

 private:
  std::function<bool()> should_stop_;
  std::vector<double> frictions_;
  std::size_t cases_ = 0;
  std::vector<std::shared_future<SimulationResult>> runs_;  // friction-major
};

// The sweep on a pool of its own with `threads` threads (0: all cores); the
// result does not depend on the thread count. `should_stop` goes to every
// run's RunControl and is then called from several threads at once.
std::vector<SweepRow> sweep_friction(const std::vector<SimulationCase>& cases, double from,
                                     double to, double step, unsigned threads = 0,
                                     const std::function<bool()>& should_stop = {});

}  // namespace gearimpact
