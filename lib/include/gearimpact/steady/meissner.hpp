// Parametric stability of the meshing pair with the clearance out of play: Hill's equation
//   x'' + 2 zeta x' + kappa(tau) x = 0
// with the rectangular one-/two-pair stiffness of docs/steady-state.md section 3.4 (Meissner's
// equation): kappa = kappa_d for the fraction d = eps_alpha - 1 of each mesh period
// T = 2 pi / Omega, kappa_s for the rest. kappa = k(t)/k with the k of w_n = sqrt(k / m_e), so
// kappa's mean d kappa_d + (1 - d) kappa_s is 1 when k is the mean stiffness.
//
// Each piece has constant coefficients, so the monodromy (the state map over one period) is the
// product of two 2x2 matrix exponentials, in closed form: exact up to rounding.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <vector>

#include "gearimpact/steady/closed_forms.hpp"

namespace gearimpact {

struct RectangularStiffness {
  double two_pair_ratio = 0.0;     // kappa_d > 0
  double one_pair_ratio = 0.0;     // kappa_s > 0
  double two_pair_fraction = 0.0;  // d in [0, 1]
};

// exp(A t) for the state (x, x') of x'' + 2 zeta x' + kappa x = 0, A = [[0, 1], [-kappa,
// -2 zeta]]: with mu^2 = zeta^2 - kappa (A's eigenvalues -zeta +- mu),
//   exp(A t) = e^{-zeta t} [C I + S (A + zeta I)],
//   (C, S) = (cosh mu t, sinh(mu t)/mu), (cos w t, sin(w t)/w) with w^2 = -mu^2, or (1, t),
// the Cayley-Hamilton form of the exponential of a 2x2 matrix.
// Throws InputError unless kappa > 0, zeta >= 0 and t >= 0, all finite.
Eigen::Matrix2d hill_transition_matrix(double stiffness_ratio, double damping_ratio,
                                       double duration);

// M = exp(A_s (1 - d) T) exp(A_d d T): the period starts with the two-pair interval. A cyclic
// shift of the start changes M by a similarity, not its eigenvalues (the Floquet multipliers).
// Throws InputError for a stiffness outside its range, zeta < 0 or Omega <= 0.
Eigen::Matrix2d meissner_monodromy(const RectangularStiffness& stiffness, double damping_ratio,
                                   double mesh_frequency_ratio);

// Largest modulus of the eigenvalues of a real 2x2 matrix, from the characteristic polynomial
// lambda^2 - tr lambda + det.
double spectral_radius(const Eigen::Matrix2d& matrix);

// |tr M| - (1 + det M). For det M in (0, 1] (here det M = e^{-2 zeta T} by Liouville's formula)
// the spectral radius exceeds 1 exactly where this is > 0: complex multipliers have modulus
// sqrt(det M) <= 1, and real ones, whose product det M lies in (0, 1], leave [-1, 1] exactly when
// the characteristic polynomial is negative at +1 or -1, i.e. 1 -+ tr + det < 0. Unlike
// spectral_radius - 1 it changes sign transversally at the band edges even without damping,
// where the spectral radius is exactly 1 all over the stable zones.
double meissner_instability_margin(const RectangularStiffness& stiffness, double damping_ratio,
                                   double mesh_frequency_ratio);

// The Omega in [omega_min, omega_max] where the instability margin is > 0, found on a uniform
// grid of grid_points values and refined by bisection to 1e-12 relative in Omega. A band
// narrower than the grid step can fall between two grid points and be missed; a band cut by
// the ends of the range ends there. Throws InputError unless 0 < omega_min < omega_max (finite)
// and grid_points >= 2.
std::vector<FrequencyBand> meissner_unstable_bands(const RectangularStiffness& stiffness,
                                                   double damping_ratio, double omega_min,
                                                   double omega_max, std::size_t grid_points);

}  // namespace gearimpact
