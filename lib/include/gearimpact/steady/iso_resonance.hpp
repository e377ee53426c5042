// ISO 6336-1:2006 method B (equation numbers of that edition) for a spur pair of solid gears:
// the main resonance speed and the dynamic factor K_v of perfect gears, the band a simulated
// dynamic factor is plotted beside (docs/steady-state.md section 3.5). The mean mesh stiffness per
// face width c_gamma_alpha is an input: ISO's own, c' (0.75 eps_alpha + 0.25), or the model's
// mean. ISO's n_E1 is the natural frequency of the two-disc relative mode expressed as a pinion
// speed, so with the mesh stiffness k = c_gamma_alpha b the simulated main resonance sits at N
// near 1.
//
// ISO writes these in mm, kg/mm, N/(mm um) and min^-1; here they are SI, and
//   n_E1 [min^-1] = 30000 / (pi z1) sqrt(c_gamma_alpha [N/(mm um)] / m_red [kg/mm])
// is the same quantity as w_E1 = sqrt(c_gamma_alpha / m_red) / z1 in rad/s with c_gamma_alpha in
// N/m^2 and m_red in kg/m.
#pragma once

#include <optional>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// (30), solid pinion and wheel of one density: the reduced mass per unit face width
//   m_red = pi rho u^2 d_m1^4 / (8 (u^2 + 1) d_b1^2),
// u = z2 / z1, d_m1 = (d_a1 + d_f1) / 2 the pinion's mean diameter, d_b1 its base diameter. It is
// m1* u^2 / (1 + u^2) with m1* = J1 / rb1^2 per face width of a solid disc of diameter d_m1.
// Throws InputError unless every argument is finite and > 0.
double iso_reduced_mass_kg_per_m(double density_kg_per_m3, double gear_ratio,
                                 double mean_diameter1_m, double base_diameter1_m);

// (6): the pinion speed of the main resonance, w_E1 = sqrt(c_gamma_alpha / m_red) / z1, with
// c_gamma_alpha the mean mesh stiffness per face width. Throws InputError unless z1 >= 1 and the
// others are finite and > 0.
double iso_resonance_speed_rad_per_s(int pinion_teeth, double mesh_stiffness_per_width_n_per_m2,
                                     double reduced_mass_kg_per_m);

// (9): the resonance ratio N = n1 / n_E1 (= w1 / w_E1). Throws InputError unless w1 >= 0 and
// w_E1 > 0, finite.
double iso_resonance_ratio(double pinion_speed_rad_per_s, double resonance_speed_rad_per_s);

enum class IsoSpeedRange { subcritical, main_resonance, intermediate, supercritical };

struct IsoDynamicFactor {
  double value = 1.0;
  IsoSpeedRange range = IsoSpeedRange::subcritical;
};

// K_v of method B for perfect gears: no effective pitch or profile deviation (B_p = B_f = 0) and
// no tip relief (C_a = 0, so B_k = 1):
//   subcritical     N <= N_S:         K_v = 1 + C_v3 N     (13),(14); 1 + 0.23 N
//   main resonance  N_S < N <= 1.15:  K_v = 1 + C_v4       (20); 1.90
//   supercritical   N >= 1.5:         K_v = C_v7           (21)
//   intermediate    1.15 < N < 1.5:   linear in N between K_v(1.15) and K_v(1.5)   (22)
// (11),(12): N_S = 0.85 for a line load F_t K_A / b >= 100 N/mm, else
// 0.5 + 0.35 sqrt(F_t K_A / (100 b)) with the load in N/mm.
// Table 8, eps_gamma the total contact ratio (eps_alpha for spur gears):
//   1 < eps_gamma <= 2:  C_v3 = 0.23, C_v4 = 0.90;
//   eps_gamma > 2:       C_v3 = 0.096 / (eps_gamma - 1.56),
//                        C_v4 = (0.57 - 0.05 eps_gamma) / (eps_gamma - 1.44);
//   C_v7 = 0.75 (eps_gamma <= 1.5), 0.125 sin(pi (eps_gamma - 2)) + 0.875 (1.5 < eps_gamma <=
//   2.5), 1 (eps_gamma > 2.5).
// Throws InputError unless N >= 0, eps_gamma > 1 and the line load > 0, all finite.
IsoDynamicFactor iso_dynamic_factor_perfect_gears(double resonance_ratio,
                                                  double total_contact_ratio,
                                                  double line_load_n_per_m);

// The N axis of a case, for the dynamic factor against ISO's resonance ratio N = w1 / w_E1. The
// axis uses the model's own mean mesh stiffness as c_gamma_alpha b, so that the model's main
// resonance sits near N = 1 (at (d_m1 / d_1)^2 for solid discs, verify/steady/
// test_iso_main_resonance.cpp); N with ISO's own c_gamma_alpha (stiffness/iso6336.hpp) is a fixed
// multiple of it.
struct IsoScale {
  // w_E1 of ISO's (6) with m_red of (30) on the pinion's mean diameter (d_a1 + d_f1) / 2, and
  // c_gamma_alpha b = the model's mean mesh stiffness, or ISO's c_gamma_alpha.
  double resonance_speed_rad_per_s = 0.0;
  double resonance_speed_iso_stiffness_rad_per_s = 0.0;
  double contact_ratio = 0.0;  // eps_alpha, for ISO's K_v
  // F_t / b = |T1 mean| / (r1 b): ISO's line load at the reference circle (K_A = 1).
  double line_load_n_per_m = 0.0;
  // The zero-speed limit of the simulated dynamic factor (quasi_static_force_ratio): the
  // dynamic factor over it is 1 at N -> 0, where ISO's K_v is 1.
  double quasi_static_force_ratio = 1.0;
};

// The zero-speed limit of the largest mesh force over the static load |T1| / Rb1, for the
// model's mesh stiffness: where a pair enters at X_start the loaded pairs keep their deflection
// for an instant, so the mesh force jumps by K_after / K_before, the mesh stiffness with the
// entering pair over that without it (the pairs a whole base pitch on, on the contact segment).
// The largest force of a slow run is that jump (the deflection relaxes from it; where a pair
// leaves, the force drops). 1 for a constant mesh stiffness. A pair with [modifications] or
// [[faults]] has gaps and teeth of their own: its ratio is the peak of its own loaded static
// transmission error under the mean load |T1| on the drive flanks
// (quasi_static_peak_force_ratio of stiffness/static_transmission_error.hpp, which reduces to
// the jump above without them); `table` must then be the healthy table of c's pair and model.
double quasi_static_force_ratio(const SimulationCase& c, const StiffnessTable& table);

// The scale of c's pair, or nothing when ISO's K_v has no meaning for it (no mean load).
std::optional<IsoScale> iso_scale(const SimulationCase& c, const StiffnessTable& table);

}  // namespace gearimpact
