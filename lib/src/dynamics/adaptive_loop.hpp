// The adaptive integrator's run loop, for any run of the dynamics: Boost.Odeint's
// dense-output Dormand-Prince method (order 5, with an embedded order-4 error
// estimate), with the mode's events located on its dense output. The
// cross-check of the fixed-step runs.
#pragma once

#include <algorithm>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <exception>
#include <utility>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/error.hpp"
#include "run_parts.hpp"
#include "step_methods.hpp"

namespace gearimpact {

namespace adaptive_detail {

// The first event of the mode inside the dense-output step [a, b], located on
// the dense output; yb receives the state there.
template <typename Stepper, typename System>
double end_of_mode(Stepper& stepper, const System& system, const typename System::ModeType& mode,
                   const typename System::MemoryType& damping, double a, double b,
                   typename System::StateType& yb) {
  using State = typename System::StateType;
  typename System::EventsType g_a{}, g_b{};
  State ya{};
  stepper.calc_state(a, ya);
  const int n = system.event_values(ya, mode, damping, g_a);
  system.event_values(yb, mode, damping, g_b);
  const auto state_at = [&](double tau, State& x) { stepper.calc_state(tau, x); };
  const double t_event = earliest_event_of(system, mode, damping, a, b, g_a, g_b, n, state_at);
  stepper.calc_state(t_event, yb);
  return t_event;
}

}  // namespace adaptive_detail

// The run loop of the adaptive integrator over the run R's system (the
// books of run_fixed_grid, step_methods.hpp): Dormand-Prince steps of the
// error's size, at most largest_step_s, each ending at the first event of the
// mode on its dense output. Returns the time reached, the run's end.
template <typename R>
double run_adaptive_loop(R& run, const IntegratorSettings& integrator, double largest_step_s) {
  namespace odeint = boost::numeric::odeint;
  using System = typename R::System;
  using State = typename System::StateType;
  const System& system = run.system();
  const double h = integrator.step_s;
  const double t0 = run.start_time();
  const double end = t0 + integrator.end_time_s;
  const double output_step = h * integrator.output_every;
  const auto outputs =
      static_cast<long long>(std::floor(integrator.end_time_s / output_step * (1.0 + 1e-12)));
  long long next_output = 1;
  typename System::ModeType mode = run.mode();
  typename System::MemoryType damping = run.damping();
  long long evaluations = 0;
  const auto ode = [&](const State& x, State& dxdt, double tt) {
    system.rhs(tt, x, mode, damping, dxdt);
    ++evaluations;
  };
  const double rtol = integrator.adaptive_relative_tolerance;
  // Angles are of order 1 rad and penetrations of 1e-6 m on a 0.02 m radius:
  // an absolute tolerance 1e-4 of the relative one keeps delta resolved.
  auto stepper = odeint::make_dense_output(rtol * 1e-4, rtol, largest_step_s,
                                           odeint::runge_kutta_dopri5<State>());
  stepper.initialize(run.y(), t0, h);
  double t = t0;
  const auto emit_until = [&](double upto) {
    while (run.records() && next_output <= outputs &&
           t0 + static_cast<double>(next_output) * output_step <= upto) {
      const double to = t0 + static_cast<double>(next_output) * output_step;
      State x{};
      stepper.calc_state(to, x);
      run.record(to, x, mode);
      ++next_output;
    }
  };
  // The samples inside a step: Dormand-Prince's own dense output, of order 4
  // (Hairer, Norsett & Wanner, Solving ODE I, II.6), over the step just taken.
  const auto dense = [&](double tau, State& x) { stepper.calc_state(tau, x); };
  while (t < end) {
    std::pair<double, double> span;
    try {
      span = stepper.do_step(ode);
    } catch (const std::exception& e) {
      throw SimulationError("the adaptive integrator failed at " + where(t, run.steps()) + ": " +
                            e.what());
    }
    const double a = span.first;
    const double b = span.second;
    State yb = stepper.current_state();
    run.check_finite(b, yb);
    const bool event = !system.mode_holds(yb, mode, damping);
    const double t_next =
        event ? adaptive_detail::end_of_mode(stepper, system, mode, damping, a, b, yb) : b;
    if (t_next >= end) {
      emit_until(end);
      stepper.calc_state(end, yb);
      system.impose_driver(end, yb);
      run.emit_samples(end, yb, mode, dense);
      run.observe_step(t, run.y(), end, yb, dense);
      run.y() = yb;
      ++run.steps();
      t = end;
      run.book_keep(t);
      break;
    }
    emit_until(t_next);
    // The dense output integrates the driver's closed-form speed to the
    // tolerance; the accepted state takes the closed form itself.
    system.impose_driver(t_next, yb);
    // Before the mode changes at an event: the step's samples are its own mode's.
    run.emit_samples(t_next, yb, mode, dense);
    run.observe_step(t, run.y(), t_next, yb, dense);
    run.y() = yb;
    ++run.steps();
    const double t_from = t;
    t = t_next;
    if (event) run.change_mode(t);
    // A new mode, or the friction signs of a contact that sticks classified again: the
    // stepper starts afresh from the state, as the right-hand side may jump there.
    if (run.check_progress(t_from, t, event) || event) {
      mode = run.mode();
      damping = run.damping();
      stepper.initialize(run.y(), t, std::max(stepper.current_time_step(), 1e-3 * h));
    }
    run.book_keep(t);
    run.poll_stop(t);
  }
  run.rhs_evaluations() = evaluations;
  return t;
}

// The run of a two-gear case: its [integrator].
template <typename R>
double run_adaptive_loop(R& run, const SimulationCase& c, double largest_step_s) {
  return run_adaptive_loop(run, c.integrator, largest_step_s);
}

}  // namespace gearimpact
