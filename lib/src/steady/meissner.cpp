#include "gearimpact/steady/meissner.hpp"

#include <cmath>
#include <string>

#include "../require.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

using namespace checks;

void validate(const RectangularStiffness& stiffness) {
  require_finite_positive("two_pair_ratio", stiffness.two_pair_ratio, "(kappa_d = k_d / k)");
  require_finite_positive("one_pair_ratio", stiffness.one_pair_ratio, "(kappa_s = k_s / k)");
  const double d = stiffness.two_pair_fraction;
  if (!std::isfinite(d) || d < 0.0 || d > 1.0) {
    throw InputError("two_pair_fraction", d, "0 <= d <= 1 (d = eps_alpha - 1)");
  }
}

}  // namespace

Eigen::Matrix2d hill_transition_matrix(double stiffness_ratio, double damping_ratio,
                                       double duration) {
  require_finite_positive("stiffness_ratio", stiffness_ratio, "(kappa)");
  require_finite_non_negative("damping_ratio", damping_ratio, "(zeta)");
  require_finite_non_negative("duration", duration, "(dimensionless time)");
  const double zeta = damping_ratio;
  const double t = duration;
  const double mu_squared = zeta * zeta - stiffness_ratio;
  double c = 1.0;
  double s = t;
  if (mu_squared > 0.0) {
    const double mu = std::sqrt(mu_squared);
    c = std::cosh(mu * t);
    s = std::sinh(mu * t) / mu;
  } else if (mu_squared < 0.0) {
    const double w = std::sqrt(-mu_squared);
    c = std::cos(w * t);
    s = std::sin(w * t) / w;
  }
  // A + zeta I = [[zeta, 1], [-kappa, -zeta]].
  Eigen::Matrix2d m;
  m << c + s * zeta, s, -s * stiffness_ratio, c - s * zeta;
  return std::exp(-zeta * t) * m;
}

Eigen::Matrix2d meissner_monodromy(const RectangularStiffness& stiffness, double damping_ratio,
                                   double mesh_frequency_ratio) {
  validate(stiffness);
  require_finite_positive("mesh_frequency_ratio", mesh_frequency_ratio, "(Omega)");
  const double period = 2.0 * pi / mesh_frequency_ratio;
  const double two_pair_time = stiffness.two_pair_fraction * period;
  return hill_transition_matrix(stiffness.one_pair_ratio, damping_ratio, period - two_pair_time) *
         hill_transition_matrix(stiffness.two_pair_ratio, damping_ratio, two_pair_time);
}

double spectral_radius(const Eigen::Matrix2d& matrix) {
  const double half_trace = 0.5 * matrix.trace();
  const double determinant = matrix.determinant();
  const double discriminant = half_trace * half_trace - determinant;
  if (discriminant >= 0.0) return std::fabs(half_trace) + std::sqrt(discriminant);
  return std::sqrt(determinant);
}

double meissner_instability_margin(const RectangularStiffness& stiffness, double damping_ratio,
                                   double mesh_frequency_ratio) {
  const Eigen::Matrix2d m = meissner_monodromy(stiffness, damping_ratio, mesh_frequency_ratio);
  // Liouville: det M = exp(trace A T) = e^{-2 zeta T} exactly, free of the rounding of the
  // product's determinant.
  const double period = 2.0 * pi / mesh_frequency_ratio;
  return std::fabs(m.trace()) - (1.0 + std::exp(-2.0 * damping_ratio * period));
}

std::vector<FrequencyBand> meissner_unstable_bands(const RectangularStiffness& stiffness,
                                                   double damping_ratio, double omega_min,
                                                   double omega_max, std::size_t grid_points) {
  validate(stiffness);
  require_finite_non_negative("damping_ratio", damping_ratio, "(zeta)");
  require_finite_positive("omega_min", omega_min, "(Omega)");
  if (!std::isfinite(omega_max) || omega_max <= omega_min) {
    throw InputError("omega_max", omega_max,
                     "finite and > omega_min = " + format_number(omega_min));
  }
  if (grid_points < 2) {
    throw InputError("grid_points", static_cast<double>(grid_points), ">= 2");
  }
  const auto unstable = [&](double omega) {
    return meissner_instability_margin(stiffness, damping_ratio, omega) > 0.0;
  };
  // Bisection keeps `stable_side` stable and `unstable_side` unstable; the edge returned is the
  // unstable end, so that every band's ends are inside it.
  const auto edge = [&](double stable_side, double unstable_side) {
    while (std::fabs(unstable_side - stable_side) > 1e-12 * unstable_side) {
      const double middle = 0.5 * (stable_side + unstable_side);
      (unstable(middle) ? unstable_side : stable_side) = middle;
    }
    return unstable_side;
  };

  std::vector<FrequencyBand> bands;
  const double step = (omega_max - omega_min) / static_cast<double>(grid_points - 1);
  double previous_omega = omega_min;
  bool previous_unstable = unstable(omega_min);
  double band_start = omega_min;
  for (std::size_t i = 1; i < grid_points; ++i) {
    const double omega =
        i + 1 == grid_points ? omega_max : omega_min + step * static_cast<double>(i);
    const bool now_unstable = unstable(omega);
    if (now_unstable && !previous_unstable) band_start = edge(previous_omega, omega);
    if (!now_unstable && previous_unstable) {
      bands.push_back({band_start, edge(omega, previous_omega)});
    }
    previous_omega = omega;
    previous_unstable = now_unstable;
  }
  if (previous_unstable) bands.push_back({band_start, omega_max});
  return bands;
}

}  // namespace gearimpact
