#include "bench_support.hpp"

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <random>
#include <utility>

namespace gearimpact::bench {

namespace {

struct Registry {
  std::vector<std::pair<std::string, AccuracyCheck>> checks;
  std::map<std::string, Accuracy, std::less<>> results;
  std::vector<Target> targets;
};

Registry& registry() {
  static Registry instance;
  return instance;
}

}  // namespace

bool register_accuracy(std::string benchmark_name, AccuracyCheck check) {
  registry().checks.emplace_back(std::move(benchmark_name), std::move(check));
  return true;
}

void run_accuracy_checks(std::size_t positions) {
  std::printf("Accuracy over %zu positions (worst relative error against the reference):\n",
              positions);
  for (const auto& [name, check] : registry().checks) {
    const Accuracy accuracy = check(positions);
    registry().results[name] = accuracy;
    std::printf("  %-40s Ke %.2e  compliances %.2e\n", name.c_str(), accuracy.ke,
                accuracy.compliances);
    std::fflush(stdout);
  }
}

const Accuracy* accuracy_of(std::string_view benchmark_name) {
  const auto found = registry().results.find(benchmark_name);
  return found == registry().results.end() ? nullptr : &found->second;
}

void report_accuracy(benchmark::State& state, std::string_view benchmark_name) {
  if (const Accuracy* accuracy = accuracy_of(benchmark_name)) {
    state.counters["ke_rel_err"] = accuracy->ke;
    state.counters["compliance_rel_err"] = accuracy->compliances;
  }
}

std::vector<std::pair<std::string, Accuracy>> accuracy_results() {
  std::vector<std::pair<std::string, Accuracy>> results;
  for (const auto& check : registry().checks) {
    if (const Accuracy* accuracy = accuracy_of(check.first)) {
      results.emplace_back(check.first, *accuracy);
    }
  }
  return results;
}

bool register_target(Target target) {
  registry().targets.push_back(std::move(target));
  return true;
}

std::vector<std::string> evaluate_targets(const Figures& ns_per_iteration) {
  std::vector<std::string> lines;
  for (const Target& target : registry().targets) lines.push_back(target(ns_per_iteration));
  return lines;
}

std::vector<double> spread(double start, double end, std::size_t n) {
  std::vector<double> points(n);
  for (std::size_t i = 0; i < n; ++i) {
    points[i] = n == 1
                    ? start
                    : start + (end - start) * static_cast<double>(i) / static_cast<double>(n - 1);
  }
  if (n > 1) points.back() = end;
  return points;
}

std::vector<double> shuffled_spread(double start, double end, std::size_t n) {
  std::vector<double> points = spread(start, end, n);
  std::mt19937_64 generator(20260122);
  std::shuffle(points.begin(), points.end(), generator);
  return points;
}

double thread_cpu_s() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace gearimpact::bench
