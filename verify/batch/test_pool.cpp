// The run pool under a process that cannot start every thread it asks for: it
// runs with the workers it got (never terminates the process), and runs are
// still computed once per distinct case.
#include <doctest/doctest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <future>

#include "gearimpact/batch/pool.hpp"
#include "gearimpact/paper/table1.hpp"

using namespace gearimpact;

TEST_CASE("a pool asked for more threads than the system gives runs with those it started") {
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reserves terabytes of address space, so an address-space
  // limit cannot be set under it.
  MESSAGE("skipped under AddressSanitizer");
#else
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    // 8 MiB a thread stack: about 30 threads fit in 256 MiB of address space
    // beside the program.
    const rlimit limit{256u << 20, 256u << 20};
    if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(2);
    try {
      RunPool pool(1000);
      if (pool.threads_asked() != 1000) _exit(3);
      if (pool.threads() == 0 || pool.threads() >= 1000) _exit(4);
      // The workers it has still run tasks.
      std::future<int> answer = pool.run([] { return 42; });
      _exit(answer.get() == 42 ? 0 : 5);
    } catch (...) {
      _exit(6);
    }
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  // A terminate() would end the child by SIGABRT.
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
#endif
}

TEST_CASE("the same case asked for twice is computed once") {
  RunPool pool(2);
  SimulationCase c = paper_case(1);
  c.integrator.end_time_s = 1e-4;
  const auto a = pool.submit(c, false);
  SimulationCase renamed = c;
  renamed.name = "another name";
  const auto b = pool.submit(renamed, false);
  CHECK(a.get().summary.steps == b.get().summary.steps);
  CHECK(pool.requested() == 2);
  CHECK(pool.computed() == 1);
  c.integrator.end_time_s = 2e-4;
  pool.submit(c, false).get();
  CHECK(pool.computed() == 2);
}
