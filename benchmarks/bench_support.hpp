// Shared by the benchmark sources: the positions the benchmarks run over, the
// accuracy of each method (measured once by main before any timing, never
// timed) and the targets checked against the figures of one run. A source
// file registers its benchmarks with Google Benchmark's macros and its
// accuracy checks and targets here, at static initialisation.
#pragma once

#include <benchmark/benchmark.h>

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gearimpact::bench {

// Worst relative errors of one method over the accuracy positions, against
// the adaptive reference.
struct Accuracy {
  double ke = std::numeric_limits<double>::quiet_NaN();
  // The worst over the compliances the method returns.
  double compliances = std::numeric_limits<double>::quiet_NaN();
};

// The calling thread's CPU time in seconds (clock_gettime), which other
// threads' and processes' load does not count into.
double thread_cpu_s();

// Two runs alternated within each iteration of `state`, so that both see the
// same machine state: their CPU seconds (thread_cpu_s), each summed over the
// iterations.
template <class First, class Second>
std::pair<double, double> alternated_cpu_s(benchmark::State& state, First first, Second second) {
  std::pair<double, double> cpu{0.0, 0.0};
  for (auto _ : state) {
    double start = thread_cpu_s();
    first();
    cpu.first += thread_cpu_s() - start;
    start = thread_cpu_s();
    second();
    cpu.second += thread_cpu_s() - start;
  }
  return cpu;
}

// Runs over `positions` points and returns the method's worst errors.
using AccuracyCheck = std::function<Accuracy(std::size_t positions)>;

// `benchmark_name` is the exact name of the benchmark that reports the result
// as its counters. Returns a dummy so that it can initialise a static.
bool register_accuracy(std::string benchmark_name, AccuracyCheck check);

// Runs every registered check (in registration order), printing a line each.
void run_accuracy_checks(std::size_t positions);

// Sets the counters ke_rel_err and compliance_rel_err of the benchmark from
// its check, if one ran.
void report_accuracy(benchmark::State& state, std::string_view benchmark_name);
const Accuracy* accuracy_of(std::string_view benchmark_name);
// Every check's result, in registration order.
std::vector<std::pair<std::string, Accuracy>> accuracy_results();

// Looks up what one run measured (NaN when it did not run): "name" gives the
// CPU nanoseconds per iteration of the named benchmark, "name:real" its wall
// nanoseconds per iteration, "name:key" its counter `key`.
using Figures = std::function<double(std::string_view benchmark_name)>;
// A performance target, as a line of the report: returns the line, which
// says the figures and whether the target is met.
using Target = std::function<std::string(const Figures& ns_per_iteration)>;
bool register_target(Target target);
std::vector<std::string> evaluate_targets(const Figures& ns_per_iteration);

// n points evenly spread over [start, end], both ends included.
std::vector<double> spread(double start, double end, std::size_t n);
// The same points in a fixed pseudo-random order, so that successive calls
// jump across the segment as they would between the pairs of a mesh.
std::vector<double> shuffled_spread(double start, double end, std::size_t n);

}  // namespace gearimpact::bench
