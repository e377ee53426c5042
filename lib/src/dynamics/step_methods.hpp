// The step methods of a run, written once for any system of the dynamics.
//
// The system concept. A type S that the step methods (and the run's event
// location) drive provides:
//   S::StateType   std::array<double, N>: positions, velocities, then the
//                  ledger's integrals of the powers (torque work, losses,
//                  parametric work), integrated with the motion;
//   S::ModeType    what stays constant during a step (each line's contact,
//                  loaded pairs, parts, touching, zones, friction signs,
//                  clipping): the right-hand side is smooth while it holds;
//   S::MemoryType  what a contact remembers from its onset (the damping
//                  factor of (32)-(33) and its stiffness);
//   S::EventsType  std::array<double, M> of event values;
//   void rhs(double t, const StateType& y, const ModeType& m, const MemoryType& d,
//            StateType& dydt) const       the equations of motion in the mode;
//   int event_values(const StateType& y, const ModeType& m, const MemoryType& d,
//                    EventsType& g) const  the values whose sign change ends
//                                          the mode (each >= 0 while it holds),
//                                          returning how many are set;
//   bool mode_holds(const StateType& y, const ModeType& m, const MemoryType& d) const;
//   void impose_driver(double t, StateType& y) const   a kinematic driver's
//                                          closed form on its body (nothing
//                                          without one);
//   S::ForcesType  what the right-hand side reports beside the derivatives,
//                  through rhs(t, y, m, d, dydt, ForcesType*).
// The torsional GearSystem (system.hpp) and the planar system (planar.cpp)
// model it.
#pragma once

#include <algorithm>
#include <array>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <cmath>
#include <cstddef>
#include <functional>
#include <tuple>
#include <vector>

#include "event_location.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "rk4_dense.hpp"

namespace gearimpact {

// The number of components of a system's state.
template <typename System>
inline constexpr std::size_t state_size_v = std::tuple_size<typename System::StateType>::value;

// k1 ... k4 of a classical RK4 step of the system's state.
template <typename System>
using Rk4StagesFor = Rk4StagesOf<state_size_v<System>>;

// The classical RK4 step from (t, y) in the mode m with contact memory d,
// with k1 = f(t, y) already evaluated: event location tries many step
// lengths from the same start. `stages`, when given, receives k1 ... k4 for
// the step's dense output (rk4_dense).
template <typename System>
void rk4_step_from(const System& system, double t, const typename System::StateType& y,
                   const typename System::StateType& k1, double h,
                   const typename System::ModeType& m, const typename System::MemoryType& d,
                   typename System::StateType& out, Rk4StagesFor<System>* stages = nullptr) {
  constexpr std::size_t n = state_size_v<System>;
  // Not zeroed: rhs writes every component.
  typename System::StateType k2, k3, k4, tmp;
  for (std::size_t i = 0; i < n; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
  system.rhs(t + 0.5 * h, tmp, m, d, k2);
  for (std::size_t i = 0; i < n; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
  system.rhs(t + 0.5 * h, tmp, m, d, k3);
  for (std::size_t i = 0; i < n; ++i) tmp[i] = y[i] + h * k3[i];
  system.rhs(t + h, tmp, m, d, k4);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
  if (stages != nullptr) *stages = {k1, k2, k3, k4};
}

// The earliest time in (a, b] at which one of the n event values of the
// system's mode m turns negative (event_location), given the state as a
// function of time (a step taken again from the same start, or a dense
// output). g_a and g_b hold the values at a and b.
template <typename System>
double earliest_event_of(const System& system, const typename System::ModeType& m,
                         const typename System::MemoryType& d, double a, double b,
                         const typename System::EventsType& g_a,
                         const typename System::EventsType& g_b, int n,
                         const std::function<void(double, typename System::StateType&)>& state_at) {
  // Every value at each time tried, kept for the location's other values: the
  // state at a time is a step taken again from the same start (or the dense
  // output), the same to the bit each time, so a time tried once (the end of
  // a bracket, which the next value starts from, or the crossing times of a
  // train's identical, equally spaced planets, whose meshes' values cross
  // together) is not stepped to again.
  // The n values of the k-th time tried are values[k n ... k n + n - 1].
  std::vector<double> times;
  std::vector<double> values;
  const auto count = static_cast<std::size_t>(n);
  return earliest_event(a, b, g_a.data(), g_b.data(), n, [&](double t, int i) {
    const auto index = static_cast<std::size_t>(i);
    for (std::size_t k = 0; k < times.size(); ++k) {
      if (times[k] == t) return values[k * count + index];
    }
    typename System::StateType x{};
    state_at(t, x);
    typename System::EventsType g{};
    system.event_values(x, m, d, g);
    times.push_back(t);
    values.insert(values.end(), g.begin(), g.begin() + n);
    return g[index];
  });
}

// A fixed-step method of the run loop (integrator.kind): the classical RK4
// above, or Boost.Odeint's Dormand-Prince 5(4) at the same fixed step, its
// order-5 solution and its order-4 continuous extension (Hairer, Norsett &
// Wanner, Solving ODE I, II.5-II.6). Both take f(t, y) in the mode as their
// first stage, so that the event location, the samples and the ledger treat
// them alike.
template <typename System>
class FixedStepper {
 public:
  using StateType = typename System::StateType;
  FixedStepper(const System& system, IntegratorKind kind)
      : system_(system), dopri5_(kind == IntegratorKind::dopri5) {}
  bool dopri5() const { return dopri5_; }
  // The evaluations of f a step takes beyond its first stage: Dormand-Prince's
  // last one is f at the step's end (first same as last).
  int evaluations() const { return dopri5_ ? 6 : 3; }

  // A step of length h from (t, y) with k1 = f(t, y) in the mode into out;
  // with keep, RK4 keeps its stages for dense() (Dormand-Prince keeps those of
  // its last step in any case).
  void step(double t, const StateType& y, const StateType& k1, double h,
            const typename System::ModeType& mode, const typename System::MemoryType& memory,
            StateType& out, bool keep) {
    if (!dopri5_) {
      rk4_step_from(system_, t, y, k1, h, mode, memory, out, keep ? &stages_ : nullptr);
      return;
    }
    const auto f = [&](const StateType& x, StateType& dx, double tau) {
      end_forces_ = typename System::ForcesType{};
      system_.rhs(tau, x, mode, memory, dx, &end_forces_);
    };
    dopri5_stepper_.do_step(f, y, k1, t, out, end_slope_, h);
  }
  // Dormand-Prince's last stage f(t + h, out) in the step's mode, and the
  // forces there: the next step's first stage while the mode holds.
  const StateType& end_slope() const { return end_slope_; }
  const typename System::ForcesType& end_forces() const { return end_forces_; }

  // The last step's continuous extension at ts in [t_a, t_a + h], the step
  // from (t_a, y_a) with first stage k1 to y_b.
  void dense(double t_a, const StateType& y_a, const StateType& k1, double h, const StateType& y_b,
             double ts, StateType& x) const {
    if (!dopri5_) {
      rk4_dense(y_a, h, stages_, (ts - t_a) / h, x);
      return;
    }
    dopri5_stepper_.calc_state(ts, x, y_a, k1, t_a, y_b, end_slope_, t_a + h);
  }

 private:
  const System& system_;
  bool dopri5_;
  Rk4StagesFor<System> stages_{};
  boost::numeric::odeint::runge_kutta_dopri5<StateType> dopri5_stepper_;
  StateType end_slope_{};
  typename System::ForcesType end_forces_{};
};

// The run loop at a fixed step: the grid t0 + k h up to the run's end, each
// step cut at the first event of the mode inside it (event_location) and
// stepped onto, after which the grid resumes. RK4 locates the event on the
// step taken again from the same start; Dormand-Prince on the step's
// continuous extension, as the adaptive method does, which errs by O(h^5) at
// the event as a step does over the run. The run R (the torsional Run of
// run.hpp, the planar run of planar.cpp) keeps the state, the mode and the
// books; it provides:
//   R::System, system(), y(), mode(), damping(), start_time(), steps(),
//   rhs_evaluations(), grid_steps(), wants_dense(), records(), sampling();
//   first_stage(t): f(t, y) in the mode, the step's first stage;
//   check_finite(t, y), emit_samples(t_b, y_b, mode, dense),
//   observe_step(t_a, y_a, t_b, y_b, dense), change_mode(t),
//   check_progress(t_from, t_to, event), book_keep(t), record(t), poll_stop(t);
//   R::kCountsCutStep: whether the evaluations of the step cut at an event
//   count in rhs_evaluations (the planar run's count; the torsional run's
//   leaves them out).
// Returns the time reached, the run's end.
template <typename R>
double run_fixed_grid(R& run, FixedStepper<typename R::System>& stepper,
                      const IntegratorSettings& integrator) {
  using System = typename R::System;
  using StateType = typename System::StateType;
  const System& system = run.system();
  const double h = integrator.step_s;
  const double t0 = run.start_time();
  const double end = t0 + integrator.end_time_s;
  const long long grid_steps = run.grid_steps();
  const long long every = integrator.output_every;
  const bool dense = run.wants_dense();
  double t = t0;
  long long k = 0;
  StateType next{};
  StateType whole;
  while (k < grid_steps) {
    // The last step ends at the run's end exactly, where the last sample may be.
    const double target =
        k + 1 == grid_steps ? end : std::min(t0 + static_cast<double>(k + 1) * h, end);
    // The run's state, mode and memory hold until the step is accepted below.
    const StateType& y = run.y();
    const typename System::ModeType& mode = run.mode();
    const typename System::MemoryType& memory = run.damping();
    const StateType& k1 = run.first_stage(t);
    stepper.step(t, y, k1, target - t, mode, memory, next, dense);
    // A driven body ends each step (and each trial of the location) where
    // its closed form is: the event values see the state the step keeps.
    system.impose_driver(target, next);
    run.rhs_evaluations() += stepper.evaluations();
    run.check_finite(target, next);
    ++run.steps();
    double reached = target;
    // The step whose continuous extension gives the samples: this one, or
    // with RK4 the step cut at an event. With Dormand-Prince an event cuts
    // the step on its extension, whose end is the whole step's (`whole`).
    double dense_step = target - t;
    bool cut_on_extension = false;
    const bool event = !system.mode_holds(next, mode, memory);
    if (event) {
      typename System::EventsType g_a{}, g_b{};
      const int n = system.event_values(y, mode, memory, g_a);
      system.event_values(next, mode, memory, g_b);
      long long evaluations = 0;
      if (stepper.dopri5()) whole = next;
      const auto state_at = [&](double tau, StateType& x) {
        if (stepper.dopri5()) {
          stepper.dense(t, y, k1, target - t, whole, tau, x);
        } else {
          stepper.step(t, y, k1, tau - t, mode, memory, x, false);
          evaluations += stepper.evaluations();
        }
        system.impose_driver(tau, x);
      };
      reached = earliest_event_of(system, mode, memory, t, target, g_a, g_b, n, state_at);
      run.rhs_evaluations() += evaluations;
      if (reached < target && stepper.dopri5()) {
        state_at(reached, next);
        cut_on_extension = true;
      } else if (reached < target) {
        // The cut step's own stages, for its samples.
        stepper.step(t, y, k1, reached - t, mode, memory, next, dense);
        system.impose_driver(reached, next);
        if (R::kCountsCutStep) run.rhs_evaluations() += stepper.evaluations();
        dense_step = reached - t;
      }
      if (reached < target) run.check_finite(reached, next);
    }
    const StateType& end_state = cut_on_extension ? whole : next;
    const auto dense_at = [&](double tau, StateType& x) {
      stepper.dense(t, y, k1, dense_step, end_state, tau, x);
    };
    // Before the mode changes at an event: the step's samples are its own mode's.
    if (run.sampling()) run.emit_samples(reached, next, mode, dense_at);
    run.observe_step(t, y, reached, next, dense_at);
    run.y() = next;
    if (event) run.change_mode(reached);
    run.check_progress(t, reached, event);
    t = reached;
    if (t == target) ++k;
    run.book_keep(t);
    if (run.records() && t == target && (k % every == 0 || k == grid_steps)) run.record(t);
    run.poll_stop(t);
  }
  return t;
}

}  // namespace gearimpact
