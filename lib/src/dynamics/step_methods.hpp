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
//                                          without one).
// The torsional GearSystem (system.hpp) and the planar system (planar.cpp)
// model it.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <tuple>

#include "event_location.hpp"
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
  return earliest_event(a, b, g_a.data(), g_b.data(), n, [&](double t, int i) {
    typename System::StateType x{};
    state_at(t, x);
    typename System::EventsType g{};
    system.event_values(x, m, d, g);
    return g[static_cast<std::size_t>(i)];
  });
}

}  // namespace gearimpact
