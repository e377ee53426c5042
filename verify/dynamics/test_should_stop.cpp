// RunControl::should_stop, the caller's way to end a long run (the Python
// module's Ctrl-C): asked every kStepsBetweenStopChecks steps, it ends the run
// with SimulationStopped when it says so, and changes nothing when it does not.
#include <doctest/doctest.h>

#include <atomic>
#include <string>
#include <thread>

#include "gearimpact/batch/sweep_friction.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/paper/table1.hpp"

using namespace gearimpact;

namespace {

SimulationCase case_of(int number, IntegratorKind kind, double end_time_s) {
  SimulationCase c = paper_case(number);
  c.integrator.kind = kind;
  c.integrator.end_time_s = end_time_s;
  return c;
}

}  // namespace

TEST_CASE("should_stop that never stops: the same run bit for bit, asked once per interval") {
  // 5 ms of 0.1 us steps plus the steps cut at events: at least 50,000 steps.
  const SimulationCase c = case_of(2, IntegratorKind::rk4, 0.005);
  RunControl plain;
  plain.keep_series = false;
  const SimulationSummary expected = simulate(c, plain).summary;
  long long asked = 0;
  RunControl watched = plain;
  watched.should_stop = [&asked] {
    ++asked;
    return false;
  };
  const SimulationSummary s = simulate(c, watched).summary;
  CHECK(summary_json(s) == summary_json(expected));
  CHECK(asked == s.steps / kStepsBetweenStopChecks);
}

TEST_CASE("should_stop that says stop ends either integrator with SimulationStopped") {
  for (const IntegratorKind kind : {IntegratorKind::rk4, IntegratorKind::adaptive}) {
    CAPTURE(static_cast<int>(kind));
    long long asked = 0;
    RunControl control;
    control.keep_series = false;
    control.should_stop = [&asked] { return ++asked == 3; };
    // 0.3 s: far more than three intervals of steps for either integrator
    // (the adaptive one takes about 15,000 steps in 30 ms).
    const SimulationCase c = case_of(1, kind, 0.3);
    CHECK_THROWS_AS(simulate(c, control), SimulationStopped);
    CHECK(asked == 3);
  }
}

TEST_CASE("sweep_friction passes should_stop to every run") {
  std::vector<SimulationCase> cases{paper_case(1), paper_case(2)};
  for (SimulationCase& c : cases) c.integrator.end_time_s = 0.01;
  // The calling thread also asks should_stop while it waits (every 20 ms), so
  // how often it asks depends on the machine's speed; the runs ask on the
  // pool's threads, and those asks are counted apart.
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<long long> asked_by_runs{0};
  CHECK_THROWS_AS(sweep_friction(cases, 0.01, 0.03, 0.01, 2,
                                 [&asked_by_runs, caller] {
                                   if (std::this_thread::get_id() != caller) ++asked_by_runs;
                                   return true;
                                 }),
                  SimulationStopped);
  // Every one of the 6 runs reaches its first check and stops there.
  CHECK(asked_by_runs.load() == 6);
}
