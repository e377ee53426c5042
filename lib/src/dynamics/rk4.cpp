// The fixed-step runs of the torsional model: the classical RK4 of the
// paper's runs, or Dormand-Prince 5(4) at the same fixed step (FixedStepper),
// with every event of the
// mode (contact onset and loss, a pair entering or leaving, friction reversal,
// force clipping) located inside the step and stepped onto, after which the
// fixed grid resumes (run_fixed_grid of step_methods.hpp): a step that
// straddles an event loses the order of RK4.
#include "rk4.hpp"

#include <cmath>
#include <string>

#include "event_location.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/named_values.hpp"
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

SimulationResult run_fixed_step(const SimulationCase& c, const StiffnessTable& table,
                                const RunControl& control) {
  if (!control.locate_events && c.integrator.kind != IntegratorKind::rk4) {
    throw InputError("integrator.kind", name_of(kIntegratorKinds, c.integrator.kind),
                     "\"rk4\" without event location (RunControl::locate_events false), the "
                     "run that shows what locating the events buys");
  }
  Run run(c, table, control);
  if (control.locate_events) {
    FixedStepper<GearSystem> stepper(run.system(), c.integrator.kind);
    const double t = run_fixed_grid(run, stepper, c.integrator);
    return run.finish(t, name_of(kIntegratorKinds, c.integrator.kind).c_str());
  }
  // Without event location: the mode taken again at every stage, for the
  // comparison that shows what locating the events buys.
  const double h = c.integrator.step_s;
  const double t0 = run.start_time();
  const double end = t0 + c.integrator.end_time_s;
  const long long grid_steps = run.grid_steps();
  const long long every = c.integrator.output_every;
  double t = t0;
  long long k = 0;
  while (k < grid_steps) {
    const double target = k + 1 == grid_steps ? end : t0 + static_cast<double>(k + 1) * h;
    State next{};
    rk4_step_unlocated(run.system(), t, run.y(), target - t, run.damping(), next);
    run.system().impose_driver(target, next);
    run.rhs_evaluations() += 4;
    run.check_finite(target, next);
    run.y() = next;
    ++run.steps();
    t = target;
    run.set_mode_without_events(t);
    ++k;
    run.book_keep(t);
    if (run.records() && (k % every == 0 || k == grid_steps)) run.record(t);
    run.poll_stop(t);
  }
  return run.finish(t, "rk4");
}

}  // namespace gearimpact
