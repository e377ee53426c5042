#include "gearimpact/steady/closed_forms.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "../require.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

using namespace checks;

void validate(const ClearanceOscillator& oscillator) {
  require_finite_non_negative("damping_ratio", oscillator.damping_ratio, "(dimensionless)");
  require_finite_positive("mean_force", oscillator.mean_force, "(dimensionless, F_m = F/(k B))");
  require_finite_non_negative("alternating_force", oscillator.alternating_force,
                              "(dimensionless, F_a)");
}

double excitation_weight(ExcitationForm form, double frequency_ratio) {
  return form == ExcitationForm::torque_fluctuation ? 1.0 : frequency_ratio * frequency_ratio;
}

}  // namespace

void require_balanced_mean_torques(double mean_torque1_n_m, double mean_torque2_n_m,
                                   double base_radius1_m, double base_radius2_m) {
  require_finite("mean_torque1", mean_torque1_n_m, "in N m");
  require_finite("mean_torque2", mean_torque2_n_m, "in N m");
  require_finite_positive("base_radius1", base_radius1_m, "in m");
  require_finite_positive("base_radius2", base_radius2_m, "in m");
  const double force1 = mean_torque1_n_m / base_radius1_m;
  const double force2 = mean_torque2_n_m / base_radius2_m;
  const double imbalance = force1 + force2;
  if (std::fabs(imbalance) > 1e-9 * std::max(std::fabs(force1), std::fabs(force2))) {
    throw InputError("mean torques", format_number(imbalance) + " N (T1/Rb1 + T2/Rb2)",
                     "T1/Rb1 + T2/Rb2 = 0 for a steady state (an unbalanced mean torque "
                     "accelerates the pair without bound)");
  }
}

DimensionlessPair dimensionless_form(const LoadedPair& pair) {
  require_finite_positive("inertia1", pair.inertia1_kg_m2, "in kg m^2");
  require_finite_positive("inertia2", pair.inertia2_kg_m2, "in kg m^2");
  require_finite_positive("base_radius1", pair.base_radius1_m, "in m");
  require_finite_positive("base_radius2", pair.base_radius2_m, "in m");
  require_finite_positive("mesh_stiffness", pair.mesh_stiffness_n_per_m, "in N/m");
  require_finite_positive("backlash", pair.backlash_m, "in m");
  require_finite("mean_torque1", pair.mean_torque1_n_m, "in N m");
  require_finite_non_negative("torque_fluctuation1", pair.torque_fluctuation1_n_m, "in N m");
  require_finite_positive("excitation_frequency", pair.excitation_frequency_rad_per_s, "in rad/s");

  const double rb1 = pair.base_radius1_m;
  const double rb2 = pair.base_radius2_m;
  const double k = pair.mesh_stiffness_n_per_m;
  const double b = pair.backlash_m;
  DimensionlessPair d;
  d.effective_mass_kg = effective_mass_kg(rb1, pair.inertia1_kg_m2, rb2, pair.inertia2_kg_m2);
  d.natural_frequency_rad_per_s = std::sqrt(k / d.effective_mass_kg);
  d.mean_force = (pair.mean_torque1_n_m / rb1) / (k * b);
  d.alternating_force =
      d.effective_mass_kg * rb1 * pair.torque_fluctuation1_n_m / (pair.inertia1_kg_m2 * k * b);
  d.frequency_ratio = pair.excitation_frequency_rad_per_s / d.natural_frequency_rad_per_s;
  return d;
}

LinearSteadyResponse linear_steady_response(const ClearanceOscillator& oscillator,
                                            double frequency_ratio) {
  validate(oscillator);
  require_finite_non_negative("frequency_ratio", frequency_ratio, "(Omega = w / w_n)");
  const double zeta = oscillator.damping_ratio;
  const double omega = frequency_ratio;
  const double real = 1.0 - omega * omega;
  const double imaginary = 2.0 * zeta * omega;
  const double modulus = std::hypot(real, imaginary);
  if (modulus == 0.0) {
    throw InputError("frequency_ratio", omega,
                     "Omega != 1 when damping_ratio = 0 (the undamped resonance has no steady "
                     "state)");
  }
  LinearSteadyResponse response;
  response.amplitude =
      oscillator.alternating_force * excitation_weight(oscillator.form, omega) / modulus;
  response.phase_rad = std::atan2(imaginary, real);
  response.keeps_contact = response.amplitude < oscillator.mean_force;
  return response;
}

std::optional<FrequencyBand> contact_loss_band(const ClearanceOscillator& oscillator) {
  validate(oscillator);
  const double zeta = oscillator.damping_ratio;
  const double r = oscillator.alternating_force / oscillator.mean_force;
  const double b0 = 1.0 - 2.0 * zeta * zeta;
  // A > F_m  <=>  a u^2 - 2 B0 u + c < 0 with u = Omega^2: section 3.2's quadratic.
  const bool torque = oscillator.form == ExcitationForm::torque_fluctuation;
  const double a = torque ? 1.0 : 1.0 - r * r;
  const double c = torque ? 1.0 - r * r : 1.0;
  const double infinity = std::numeric_limits<double>::infinity();

  if (a == 0.0) {
    // W = Omega^2, r = 1: -2 B0 u + 1 < 0 beyond u = 1 / (2 B0), and nowhere when B0 <= 0.
    if (b0 <= 0.0) return std::nullopt;
    return FrequencyBand{std::sqrt(c / (2.0 * b0)), infinity};
  }
  const double discriminant = b0 * b0 - a * c;
  if (discriminant <= 0.0) return std::nullopt;
  // Roots q/a and c/q with q = B0 + sign(B0) sqrt(disc): no cancellation in either.
  const double root = std::sqrt(discriminant);
  const double q = b0 >= 0.0 ? b0 + root : b0 - root;
  const double u_a = q / a;
  const double u_b = c / q;
  const double u_low = std::min(u_a, u_b);
  const double u_high = std::max(u_a, u_b);
  if (a > 0.0) {
    // Negative between the roots.
    if (u_high <= 0.0) return std::nullopt;
    return FrequencyBand{std::sqrt(std::max(u_low, 0.0)), std::sqrt(u_high)};
  }
  // a < 0 (W = Omega^2, r > 1, c = 1): the roots have opposite signs and the quadratic is
  // negative beyond the positive one.
  return FrequencyBand{std::sqrt(u_high), infinity};
}

}  // namespace gearimpact
