// The fixed-step classical RK4 of the paper's runs, with every event of the
// mode (contact onset and loss, a pair entering or leaving, friction reversal,
// force clipping) located inside the step and stepped onto, after which the
// fixed grid resumes: a step that straddles an event loses the order of RK4.
#include "rk4.hpp"

#include <cmath>

#include "event_location.hpp"
#include "run.hpp"

namespace gearimpact {

// The classical RK4 step from (t, y) with k1 = f(t, y) already evaluated:
// event location tries many step sizes from the same start.
void rk4_step_from(const GearSystem& system, double t, const State& y, const State& k1, double h,
                   const Mode& m, const ContactMemory& d, State& out) {
  // Not zeroed: rhs writes every component.
  State k2, k3, k4, tmp;
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
  system.rhs(t + 0.5 * h, tmp, m, d, k2);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
  system.rhs(t + 0.5 * h, tmp, m, d, k3);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + h * k3[i];
  system.rhs(t + h, tmp, m, d, k4);
  for (std::size_t i = 0; i < kStateSize; ++i) {
    out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
}

void rk4_step(const GearSystem& system, double t, const State& y, double h, const Mode& m,
              const ContactMemory& d, State& out, State& k1) {
  system.rhs(t, y, m, d, k1);
  rk4_step_from(system, t, y, k1, h, m, d, out);
}

// The classical RK4 step with the mode re-evaluated at every stage: what a
// fixed-step integration without event location does.
void rk4_step_unlocated(const GearSystem& system, double t, const State& y, double h,
                        const ContactMemory& d, State& out) {
  State k1{}, k2{}, k3{}, k4{}, tmp{};
  const auto f = [&](double tt, const State& x, State& dx) {
    Mode m = system.classify_geometry(x);
    system.classify_forces(x, d, m);
    system.rhs(tt, x, m, d, dx);
  };
  f(t, y, k1);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
  f(t + 0.5 * h, tmp, k2);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
  f(t + 0.5 * h, tmp, k3);
  for (std::size_t i = 0; i < kStateSize; ++i) tmp[i] = y[i] + h * k3[i];
  f(t + h, tmp, k4);
  for (std::size_t i = 0; i < kStateSize; ++i) {
    out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
}

SimulationResult run_rk4(const SimulationCase& c, const StiffnessTable& table,
                         const RunControl& control) {
  Run run(c, table, control);
  const GearSystem& system = run.system();
  const double h = c.integrator.step_s;
  const double t0 = run.start_time();
  const double end = t0 + c.integrator.end_time_s;
  const auto grid_steps =
      static_cast<long long>(std::ceil(c.integrator.end_time_s / h * (1.0 - 1e-12)));
  const long long every = c.integrator.output_every;
  double t = t0;
  long long k = 0;
  int stalled = 0;
  State next{};
  while (k < grid_steps) {
    const double target = k + 1 == grid_steps ? end : t0 + static_cast<double>(k + 1) * h;
    const double step = target - t;
    const State& y = run.y();
    if (!control.locate_events) {
      rk4_step_unlocated(system, t, y, step, run.damping(), next);
      run.rhs_evaluations() += 4;
      run.check_finite(target, next);
      run.y() = next;
      t = target;
      ++k;
      ++run.steps();
      run.set_mode_without_events(t);
    } else {
      State k1;
      rk4_step(system, t, y, step, run.mode(), run.damping(), next, k1);
      run.rhs_evaluations() += 4;
      run.check_finite(target, next);
      if (system.mode_holds(next, run.mode(), run.damping())) {
        run.y() = next;
        t = target;
        ++k;
        ++run.steps();
        stalled = 0;
      } else {
        EventValues g_a{}, g_b{};
        const int n = system.event_values(y, run.mode(), run.damping(), g_a);
        system.event_values(next, run.mode(), run.damping(), g_b);
        const State start = y;
        const Mode mode = run.mode();
        const ContactMemory damping = run.damping();
        long long evaluations = 0;
        const auto state_at = [&](double tau, State& x) {
          rk4_step_from(system, t, start, k1, tau - t, mode, damping, x);
          evaluations += 3;
        };
        const double t_event =
            earliest_event(system, mode, damping, t, target, g_a, g_b, n, state_at);
        run.rhs_evaluations() += evaluations;
        if (t_event < target) {
          state_at(t_event, next);
          run.check_finite(t_event, next);
        }
        stalled = t_event - t <= 1e-9 * h ? stalled + 1 : 0;
        if (stalled > kMostStalledEvents) {
          throw SimulationError("event location stalled at " + where(t, run.steps()) +
                                ": the mode changes back and forth without time advancing");
        }
        run.y() = next;
        ++run.steps();
        if (t_event >= target) {
          t = target;
          ++k;
        } else {
          t = t_event;
        }
        run.change_mode(t);
      }
    }
    run.book_keep();
    if (run.records() && t == target && (k % every == 0 || k == grid_steps)) run.record(t);
    run.poll_stop(t);
  }
  return run.finish(t, "rk4");
}

}  // namespace gearimpact
