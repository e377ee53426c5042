// The fixed-step classical RK4 of the paper's runs, with every event of the
// mode (contact onset and loss, a pair entering or leaving, friction reversal,
// force clipping) located inside the step and stepped onto, after which the
// fixed grid resumes: a step that straddles an event loses the order of RK4.
#include "rk4.hpp"

#include <cmath>

#include "event_location.hpp"
#include "run.hpp"

namespace gearimpact {

void rk4_step(const GearSystem& system, double t, const State& y, double h, const Mode& m,
              const ContactMemory& d, State& out, State& k1, Rk4Stages* stages) {
  system.rhs(t, y, m, d, k1);
  rk4_step_from(system, t, y, k1, h, m, d, out, stages);
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

namespace {

// One RK4 step from t towards `target` in the run's mode, cut at the first
// event inside it: the time reached (`target`, or the event's), whether an
// event ends the step (the mode is not yet classified again), and what the
// dense output of the accepted step needs.
struct CutStep {
  double reached;
  bool event;
  State start;
  double h;
  Rk4Stages stages;
};

CutStep event_cut_step(Run& run, double t, double target, bool want_stages) {
  const GearSystem& system = run.system();
  const State y = run.y();
  const Mode mode = run.mode();
  const ContactMemory damping = run.damping();
  CutStep step{target, false, y, target - t, {}};
  Rk4Stages* stages = want_stages ? &step.stages : nullptr;
  State k1;
  State next{};
  rk4_step(system, t, y, target - t, mode, damping, next, k1, stages);
  system.impose_driver(target, next);
  run.rhs_evaluations() += 4;
  run.check_finite(target, next);
  ++run.steps();
  if (system.mode_holds(next, mode, damping)) {
    run.y() = next;
    return step;
  }
  EventValues g_a{}, g_b{};
  const int n = system.event_values(y, mode, damping, g_a);
  system.event_values(next, mode, damping, g_b);
  long long evaluations = 0;
  const auto state_at = [&](double tau, State& x) {
    rk4_step_from(system, t, y, k1, tau - t, mode, damping, x);
    system.impose_driver(tau, x);
    evaluations += 3;
  };
  const double t_event = earliest_event_of(system, mode, damping, t, target, g_a, g_b, n, state_at);
  run.rhs_evaluations() += evaluations;
  if (t_event < target) {
    // The same step as state_at's, keeping its stages.
    rk4_step_from(system, t, y, k1, t_event - t, mode, damping, next, stages);
    system.impose_driver(t_event, next);
    run.check_finite(t_event, next);
    step.reached = t_event;
    step.h = t_event - t;
  }
  run.y() = next;
  step.event = true;
  return step;
}

}  // namespace

SimulationResult run_rk4(const SimulationCase& c, const StiffnessTable& table,
                         const RunControl& control) {
  Run run(c, table, control);
  const double h = c.integrator.step_s;
  const double t0 = run.start_time();
  const double end = t0 + c.integrator.end_time_s;
  const auto grid_steps =
      static_cast<long long>(std::ceil(c.integrator.end_time_s / h * (1.0 - 1e-12)));
  const long long every = c.integrator.output_every;
  double t = t0;
  long long k = 0;
  while (k < grid_steps) {
    const double target = k + 1 == grid_steps ? end : t0 + static_cast<double>(k + 1) * h;
    if (!control.locate_events) {
      State next{};
      rk4_step_unlocated(run.system(), t, run.y(), target - t, run.damping(), next);
      run.system().impose_driver(target, next);
      run.rhs_evaluations() += 4;
      run.check_finite(target, next);
      run.y() = next;
      ++run.steps();
      t = target;
      run.set_mode_without_events(t);
    } else {
      const CutStep step = event_cut_step(run, t, target, run.sampling());
      if (run.sampling()) {
        // Before the mode changes at an event: the step's samples are its own mode's.
        run.emit_samples(step.reached, run.y(), run.mode(), [&](double tau, State& x) {
          rk4_dense(step.start, step.h, step.stages, (tau - t) / step.h, x);
        });
      }
      if (step.event) run.change_mode(step.reached);
      run.check_progress(t, step.reached, step.event);
      t = step.reached;
    }
    if (t == target) ++k;
    run.book_keep(t);
    if (run.records() && t == target && (k % every == 0 || k == grid_steps)) run.record(t);
    run.poll_stop(t);
  }
  return run.finish(t, "rk4");
}

}  // namespace gearimpact
