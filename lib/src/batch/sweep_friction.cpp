#include "gearimpact/batch/sweep_friction.hpp"

#include <chrono>
#include <cmath>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

std::vector<double> friction_values(double from, double to, double step) {
  if (!std::isfinite(from) || from < 0.0) throw InputError("from", from, "a finite value >= 0");
  if (!std::isfinite(to) || to < from) {
    throw InputError("to", to, "a finite value >= from = " + format_number(from));
  }
  if (!std::isfinite(step) || step <= 0.0) throw InputError("step", step, "a finite value > 0");
  const double intervals = (to - from) / step;
  if (intervals > 1e5) throw InputError("step", step, "at least (to - from) / 1e5");
  // The last value is `to` when (to - from)/step is an integer up to rounding.
  const auto count = static_cast<std::size_t>(std::floor(intervals + 1e-9)) + 1;
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) values[i] = from + static_cast<double>(i) * step;
  return values;
}

FrictionSweep::FrictionSweep(RunPool& pool, const std::vector<SimulationCase>& cases, double from,
                             double to, double step, const std::function<bool()>& should_stop)
    : should_stop_(should_stop), frictions_(friction_values(from, to, step)), cases_(cases.size()) {
  for (double f : frictions_) {
    for (SimulationCase c : cases) {
      c.model.friction_coefficient = f;
      runs_.push_back(pool.submit(c, false, should_stop));
    }
  }
}

std::vector<SweepRow> FrictionSweep::get() const {
  if (should_stop_) {
    // A stop seen here reaches the runs through their own should_stop.
    constexpr std::chrono::milliseconds poll{20};
    for (const auto& run : runs_) {
      while (run.wait_for(poll) != std::future_status::ready) should_stop_();
    }
  }
  std::vector<SweepRow> rows;
  for (std::size_t i = 0; i < frictions_.size(); ++i) {
    SweepRow row{frictions_[i], {}};
    for (std::size_t j = 0; j < cases_; ++j) {
      const SimulationSummary& s = runs_[i * cases_ + j].get().summary;
      if (!(s.damping_loss_j > 0.0)) {
        throw SimulationError("no damping loss in " + s.case_name +
                              " at f = " + format_number(frictions_[i]) +
                              ": the ratio friction loss / damping loss is undefined");
      }
      row.ratio.push_back(s.friction_loss_j / s.damping_loss_j);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::vector<SweepRow> sweep_friction(const std::vector<SimulationCase>& cases, double from,
                                     double to, double step, unsigned threads,
                                     const std::function<bool()>& should_stop) {
  RunPool pool(threads);
  return FrictionSweep(pool, cases, from, to, step, should_stop).get();
}

}  // namespace gearimpact
