// The simulations of a reproduction, run once each on a fixed set of worker
// threads (one a core). Sections of the report ask for runs and wait for them;
// a run asked for twice (the same case under the same settings, e.g. the
// default reading of the readings comparison and the Fig. 7 sweep) is computed
// once, and every run of one gear pair shares one stiffness table.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/simulation_case.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact::cli {

class SimulationPool {
 public:
  // threads = 0: one per core.
  explicit SimulationPool(unsigned threads = 0);
  // Finishes the queued runs, then joins the workers.
  ~SimulationPool();
  SimulationPool(const SimulationPool&) = delete;
  SimulationPool& operator=(const SimulationPool&) = delete;

  // The run of c, with its time series when keep_series. A run without the
  // series is served by an equal run with it, whose summary is the same.
  std::shared_future<SimulationResult> submit(const SimulationCase& c, bool keep_series);

  unsigned threads() const { return static_cast<unsigned>(workers_.size()); }
  // Runs asked for and runs computed, so far.
  std::size_t requested() const;
  std::size_t computed() const;

 private:
  void work();

  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<std::function<void()>> queue_;
  bool stopping_ = false;
  std::map<std::string, std::shared_future<SimulationResult>> runs_;
  std::map<std::string, std::shared_ptr<const StiffnessTable>> tables_;
  std::size_t requested_ = 0;
  std::size_t computed_ = 0;
  std::vector<std::thread> workers_;
};

}  // namespace gearimpact::cli
