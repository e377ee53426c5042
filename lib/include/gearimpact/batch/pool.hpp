// One pool of worker threads for every multi-run command (the friction sweep,
// the reproduction, parameter sweeps): tasks of any kind, and simulations that
// are computed once per distinct case, every run of one gear pair and
// stiffness model sharing one stiffness table.
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
#include <utility>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

class RunPool {
 public:
  // threads = 0: one per core. Where the system refuses a thread (a process
  // limit), the pool runs with the workers it started (threads() < threads_asked());
  // where it refuses the first, the constructor throws Error.
  explicit RunPool(unsigned threads = 0);
  // Finishes the queued tasks, then joins the workers.
  ~RunPool();
  RunPool(const RunPool&) = delete;
  RunPool& operator=(const RunPool&) = delete;

  // Runs `task` on a worker; its result or exception reaches the future.
  template <typename Task>
  auto run(Task task) -> std::future<decltype(task())> {
    using Result = decltype(task());
    auto packaged = std::make_shared<std::packaged_task<Result()>>(std::move(task));
    std::future<Result> result = packaged->get_future();
    enqueue([packaged] { (*packaged)(); });
    return result;
  }

  // The run of c, with its time series when keep_series. The same case asked
  // for twice is computed once, and a run without the series is served by an
  // equal run with it, whose summary is the same. The case is checked here,
  // once (check_run of dynamics/simulate.hpp, with the pool's table: the
  // torsional and the planar model alike), and a case or a run that fails
  // throws InputError here, to the caller. `should_stop` goes to
  // the run's RunControl (it may be called from several threads at once).
  std::shared_future<SimulationResult> submit(const SimulationCase& c, bool keep_series,
                                              std::function<bool()> should_stop = {});

  // The stiffness table of c's gear pair and stiffness model, built once per
  // pool and shared read-only.
  std::shared_ptr<const StiffnessTable> table_for(const SimulationCase& c);

  unsigned threads() const { return static_cast<unsigned>(workers_.size()); }
  unsigned threads_asked() const { return threads_asked_; }
  // Simulations asked for and computed, so far.
  std::size_t requested() const;
  std::size_t computed() const;

 private:
  void enqueue(std::function<void()> task);
  void work();

  unsigned threads_asked_;
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

}  // namespace gearimpact
