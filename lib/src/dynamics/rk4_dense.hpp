// The continuous extension of a classical RK4 step, for a state of any size:
// the torsional run (rk4.cpp) and the planar one (planar.cpp) sample with it.
#pragma once

#include <array>
#include <cstddef>

namespace gearimpact {

// k1 ... k4 of a classical RK4 step of a state of N components.
template <std::size_t N>
using Rk4StagesOf = std::array<std::array<double, N>, 4>;

// The continuous extension of the RK4 step of length h from y with stages k,
// at y(t + theta h), 0 <= theta <= 1: y + h sum b_i(theta) k_i with
// b1 = theta - 3 theta^2/2 + 2 theta^3/3, b2 = b3 = theta^2 - 2 theta^3/3,
// b4 = -theta^2/2 + 2 theta^3/3 (Hairer, Norsett & Wanner, Solving ODE I,
// II.6): order 3, a local error O(h^4), the classical weights at theta = 1.
// Cubic in theta, it is exact for a state that is.
template <std::size_t N>
void rk4_dense(const std::array<double, N>& y, double h, const Rk4StagesOf<N>& k, double theta,
               std::array<double, N>& out) {
  const double b1 = theta * (1.0 - theta * (1.5 - theta * (2.0 / 3.0)));
  const double b23 = theta * theta * (1.0 - theta * (2.0 / 3.0));
  const double b4 = theta * theta * (theta * (2.0 / 3.0) - 0.5);
  for (std::size_t i = 0; i < N; ++i) {
    out[i] = y[i] + h * (b1 * k[0][i] + b23 * (k[1][i] + k[2][i]) + b4 * k[3][i]);
  }
}

}  // namespace gearimpact
