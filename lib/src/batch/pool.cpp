#include "gearimpact/batch/pool.hpp"

#include <algorithm>
#include <string>
#include <system_error>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// What the stiffness table depends on: the gear pair and the stiffness model.
// (A run's own identity is case_key of the whole case: every input but its
// name; a run with no text form, a user torque function, has an empty key
// and is never shared.)
std::string table_key(const SimulationCase& c) {
  SimulationCase only;
  only.gears = c.gears;
  only.model.stiffness = c.model.stiffness;
  return case_key(only);
}

}  // namespace

RunPool::RunPool(unsigned threads)
    : threads_asked_(threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads) {
  try {
    for (unsigned i = 0; i < threads_asked_; ++i) workers_.emplace_back([this] { work(); });
  } catch (const std::system_error& e) {
    // A process or thread limit (ulimit -u, a cluster's cgroup) ends the start
    // here; the pool runs with the workers it got, and without any it cannot run.
    if (workers_.empty()) {
      throw Error("cannot start a worker thread (" + std::string(e.what()) +
                  "): " + std::to_string(threads_asked_) + " asked for");
    }
  }
}

RunPool::~RunPool() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  ready_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void RunPool::enqueue(std::function<void()> task) {
  {
    const std::lock_guard lock(mutex_);
    queue_.push_back(std::move(task));
  }
  ready_.notify_one();
}

std::shared_ptr<const StiffnessTable> RunPool::table_for(const SimulationCase& c) {
  const std::string key = table_key(c);
  {
    const std::lock_guard lock(mutex_);
    if (const auto found = tables_.find(key); found != tables_.end()) return found->second;
  }
  // Built outside the lock (it takes milliseconds); a race builds it twice
  // and keeps the first, which is the same table.
  auto table = run_table(c);
  const std::lock_guard lock(mutex_);
  return tables_.emplace(key, std::move(table)).first->second;
}

std::shared_future<SimulationResult> RunPool::submit(const SimulationCase& c, bool keep_series,
                                                     std::function<bool()> should_stop) {
  const std::string inputs = case_key(c);
  // The rows kept matter only with the series.
  const std::string series =
      keep_series ? "series every " + std::to_string(c.integrator.output_every) : "summary";
  const std::string key = inputs.empty() ? std::string() : inputs + "|" + series;
  auto promise = std::make_shared<std::promise<SimulationResult>>();
  std::shared_future<SimulationResult> result = promise->get_future().share();
  {
    const std::lock_guard lock(mutex_);
    ++requested_;
    if (!key.empty()) {
      if (const auto found = runs_.find(key); found != runs_.end()) return found->second;
      if (!keep_series) {
        // Any run with the series and the same inputs has this summary.
        const std::string with_series = inputs + "|series";
        const auto found_series = runs_.lower_bound(with_series);
        if (found_series != runs_.end() &&
            found_series->first.compare(0, with_series.size(), with_series) == 0) {
          return found_series->second;
        }
      }
      // Claimed before the lock is released, so that a run asked for by two
      // threads at once is still computed once.
      runs_.emplace(key, result);
    }
    ++computed_;
  }
  RunControl control;
  control.keep_series = keep_series;
  control.should_stop = std::move(should_stop);
  std::shared_ptr<const CheckedRun> run;
  try {
    // Checked here, once (check_run: the torsional and the planar model
    // alike), so that a bad case throws InputError to the caller; the checks
    // that need the mesh stiffness use the pool's table, without a quadrature
    // of their own.
    // The fields before the table, which a pair outside its ranges cannot build.
    validate_absent_run_keys(c);
    validate_fields(c);
    refuse_helical_run(c);
    run = std::make_shared<const CheckedRun>(check_run(c, table_for(c), control));
  } catch (...) {
    promise->set_exception(std::current_exception());
    throw;
  }
  enqueue([promise, run] {
    try {
      promise->set_value(simulate(*run));
    } catch (...) {
      promise->set_exception(std::current_exception());
    }
  });
  return result;
}

std::size_t RunPool::requested() const {
  const std::lock_guard lock(mutex_);
  return requested_;
}

std::size_t RunPool::computed() const {
  const std::lock_guard lock(mutex_);
  return computed_;
}

void RunPool::work() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    task();
  }
}

}  // namespace gearimpact
