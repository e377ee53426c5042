// The contact laws of one tooth pair: restitution (33), the damping factor
// (32) in its three published forms, the Hertzian damping force (34) and the
// friction sign rule of (35)-(38). MODEL.md, section Contact, damping, friction.
#pragma once

#include "gearimpact/dynamics/simulation_case.hpp"

namespace gearimpact {

// (33) e = 1 - c (Vi / unit)^p, clipped to [0, 1]: a speed so large that the
// power law falls below zero still loses at most all of the approach energy.
double restitution_coefficient(const RestitutionLaw& law, double impact_speed_m_s);

// (32) the damping factor divided by the stiffness K that enters it, s/m:
// D = K * damping_factor_per_stiffness(form, e, Vi), with
//   Herbert-McWhannell  D = 6 K (1 - e) / {[(2e - 1)^2 + 3] Vi}
//   Hunt-Crossley       D = 3 K (1 - e) / (2 Vi)
//   Lee-Wang            D = 3 K (1 - e) / (4 Vi)
// Vi must be > 0.
double damping_factor_per_stiffness(DampingForm form, double restitution, double impact_speed_m_s);

// (34) G = D delta d(delta)/dt.
inline double hertzian_damping_force(double damping_factor, double delta_m, double delta_rate_m_s) {
  return damping_factor * delta_m * delta_rate_m_s;
}

// Normal force of a pair: N = F + G, clipped at 0 because a tooth can push, not pull.
inline double normal_force(double elastic_force_n, double damping_force_n) {
  const double n = elastic_force_n + damping_force_n;
  return n > 0.0 ? n : 0.0;
}

// Sliding speed of a pair at X (from C1 on N1, from C1' on N2), (36),(38):
// Vs = w1 X - w2 (lp - X). Zero at the pitch point when the gears roll.
inline double sliding_speed(double w1_rad_s, double w2_rad_s, double x_m, double lp_m) {
  return w1_rad_s * x_m - w2_rad_s * (lp_m - x_m);
}

}  // namespace gearimpact
