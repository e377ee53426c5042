// The loaded, running pair in the dimensionless form of docs/steady-state.md section 2, and the
// closed forms of its linear limit (section 3.1) and of the onset of contact loss (section 3.2).
//
// With s = Rb1 theta1 - Rb2 theta2 (contact on the drive flank for s > B, on the coast flank for
// s < -B, free play 2B), tau = w_n t and x = s / B the pair obeys
//   x'' + 2 zeta x' + (k(t)/k) f(x) = F_m + F_a W cos(Omega tau),
//   f(x) = x - 1 (x > 1), 0 (|x| <= 1), x + 1 (x < -1),
// with W = 1 for a torque fluctuation and W = Omega^2 for excitation by a static transmission
// error (Kahraman and Singh 1990).
#pragma once

#include <optional>

namespace gearimpact {

// Section 1, sign convention: T1 and T2 both act along the line of action in the sense of
// docs/model.md's equations of motion (J1 w1' = T1 - N Rb1, J2 w2' = T2 + N Rb2), so a driving
// pinion torque T1 > 0 is balanced by a resisting T2 < 0 with T1/Rb1 + T2/Rb2 = 0.
//
// Throws InputError naming "mean torques" and the imbalance T1/Rb1 + T2/Rb2 in N when it exceeds
// 1e-9 of max(|T1/Rb1|, |T2/Rb2|): an unbalanced mean torque accelerates the pair without bound,
// so it has no steady state. The bound passes torques typed with 10 significant digits.
void require_balanced_mean_torques(double mean_torque1_n_m, double mean_torque2_n_m,
                                   double base_radius1_m, double base_radius2_m);

// The inputs of section 2, SI.
struct LoadedPair {
  double inertia1_kg_m2 = 0.0;
  double inertia2_kg_m2 = 0.0;
  double base_radius1_m = 0.0;
  double base_radius2_m = 0.0;
  // k: the constant mesh stiffness, or the mean of a varying one.
  double mesh_stiffness_n_per_m = 0.0;
  // B of docs/model.md: contact when |s| > B, so the free play is 2B.
  double backlash_m = 0.0;
  // T_m on gear 1, balanced on gear 2 as in require_balanced_mean_torques.
  double mean_torque1_n_m = 0.0;
  // dT1 of the fluctuation dT1 cos(w t) on gear 1; >= 0 (a sign is a phase of pi).
  double torque_fluctuation1_n_m = 0.0;
  // w of that fluctuation.
  double excitation_frequency_rad_per_s = 0.0;
};

struct DimensionlessPair {
  // m_e = 1 / (Rb1^2/J1 + Rb2^2/J2).
  double effective_mass_kg = 0.0;
  // w_n = sqrt(k / m_e).
  double natural_frequency_rad_per_s = 0.0;
  // F_m = (T_m / Rb1) / (k B).
  double mean_force = 0.0;
  // F_a = m_e Rb1 dT1 / (J1 k B).
  double alternating_force = 0.0;
  // Omega = w / w_n.
  double frequency_ratio = 0.0;
};

// docs/steady-state.md section 2. Throws InputError naming the first field outside its range
// (inertias, radii, stiffness, backlash and frequency finite and > 0; torques finite; the
// fluctuation >= 0).
DimensionlessPair dimensionless_form(const LoadedPair& pair);

// How the excitation amplitude scales with frequency: W = 1 or W = Omega^2.
enum class ExcitationForm { torque_fluctuation, transmission_error };

// The dimensionless clearance oscillator with constant stiffness (k(t)/k = 1).
struct ClearanceOscillator {
  double damping_ratio = 0.0;      // zeta >= 0
  double mean_force = 0.0;         // F_m > 0
  double alternating_force = 0.0;  // F_a >= 0
  ExcitationForm form = ExcitationForm::torque_fluctuation;
};

// Section 3.1: while the drive flank never separates, y = x - 1 obeys the linear oscillator
// y'' + 2 zeta y' + y = F_m + F_a W cos(Omega tau), whose steady state is
//   y = F_m + A cos(Omega tau - phi),
//   A = F_a W / sqrt((1 - Omega^2)^2 + (2 zeta Omega)^2),
//   phi = atan2(2 zeta Omega, 1 - Omega^2) in [0, pi] (the lag behind the excitation).
struct LinearSteadyResponse {
  double amplitude = 0.0;
  double phase_rad = 0.0;
  // A < F_m: the minimum of x is 1 + F_m - A > 1, so the linear solution is the clearance
  // oscillator's (no impact, NI). When false it is not, and contact_loss_band applies.
  bool keeps_contact = false;
};

// Throws InputError for zeta < 0, F_m <= 0, F_a < 0, Omega < 0 or non-finite values, and at the
// undamped resonance (zeta = 0, Omega = 1), where no steady state exists.
LinearSteadyResponse linear_steady_response(const ClearanceOscillator& oscillator,
                                            double frequency_ratio);

// An interval of Omega; upper may be +infinity.
struct FrequencyBand {
  double lower = 0.0;
  double upper = 0.0;
};

// Section 3.2: the Omega over which the linear amplitude exceeds F_m, so that the drive flank
// separates (NI ends). With r = F_a / F_m and B0 = 1 - 2 zeta^2, A = F_m at
//   W = 1:         Omega^2 = B0 +- sqrt(B0^2 - 1 + r^2),
//   W = Omega^2:   Omega^2 = [B0 +- sqrt(B0^2 - (1 - r^2))] / (1 - r^2),
// the roots of a u^2 - 2 B0 u + c = 0 in u = Omega^2 with (a, c) = (1, 1 - r^2) and
// (1 - r^2, 1). Contact is lost where that quadratic is negative: between the roots; from 0 when
// W = 1 and r >= 1 (the quasi-static response already separates); up to +infinity when
// W = Omega^2 and r >= 1 (the response tends to F_a W / Omega^2 = F_a). nullopt: never lost.
// Throws InputError as linear_steady_response does.
std::optional<FrequencyBand> contact_loss_band(const ClearanceOscillator& oscillator);

}  // namespace gearimpact
