// The library call that gearimpact.simulate(1) makes, timed in C++: the
// baseline of python/benchmark/overhead.py. Prints the least processor time of
// `repeats` runs of case 1 with and without the time series, in seconds:
// processor time, as the machine is shared and wall time counts the others' work.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

#include "gearimpact/gearimpact.hpp"

namespace {

double fastest_seconds(int repeats, bool keep_series) {
  const gearimpact::SimulationCase c = gearimpact::paper_case(1);
  gearimpact::RunControl control;
  control.keep_series = keep_series;
  std::vector<double> seconds;
  for (int i = 0; i < repeats; ++i) {
    const std::clock_t start = std::clock();
    const gearimpact::SimulationResult result = gearimpact::simulate(c, control);
    seconds.push_back(static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC);
    if (result.summary.steps == 0) std::abort();
  }
  return *std::min_element(seconds.begin(), seconds.end());
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 21;
  std::printf("{\"series\": %.9g, \"summary_only\": %.9g}\n", fastest_seconds(repeats, true),
              fastest_seconds(repeats, false));
  return 0;
}
