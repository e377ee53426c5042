// Tooth stiffness by ISO 6336-1 method B, the engineering standard's
// empirical fit, for comparison with the models (docs/stiffness-models.md,
// section 4). Spur and helical external gears.
//
// ISO states these quantities in N/(mm um) per unit face width; here they
// are in SI, N/m per metre of face width (N/m^2): 1 N/(mm um) = 1e9 N/m^2.
// The flexibility q' of the fit is kept in the fit's own unit, mm um/N.
#pragma once

#include <optional>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

struct Iso6336Gear {
  int teeth = 20;
  double profile_shift_coefficient = 0.0;               // x
  double tip_diameter_m = 0.0;                          // d_a, for the transverse contact ratio
  double rack_dedendum_coefficient = 1.25;              // h_fP / m_n of the basic rack
  double rack_pressure_angle_rad = 0.3490658503988659;  // alpha_Pn of the basic rack (20 deg)
};

struct Iso6336Pair {
  double normal_module_m = 2.0e-3;                        // m_n
  double normal_pressure_angle_rad = 0.3490658503988659;  // alpha_n
  double helix_angle_rad = 0.0;                           // beta (0: spur)
  double centre_distance_m = 0.0;                         // a_w
  Iso6336Gear gear1;
  Iso6336Gear gear2;
  double mesh_factor = 0.8;   // C_M
  double blank_factor = 1.0;  // C_R, 1 for solid blanks
  // F_t K_A / b in N/m. Absent: at least 100 N/mm, no low-load correction.
  // Below 100 N/mm, c' is multiplied by (F_t K_A / b / 100 N/mm)^0.25, ISO
  // 6336-1 method B's correction for lightly loaded teeth; c' as stated holds
  // from 100 N/mm up (the bound of the standard's own validity statement for
  // c', the same 100 N/mm as its N_S of the resonance range).
  std::optional<double> specific_load_n_per_m;
};

struct Iso6336Stiffness {
  double virtual_teeth1;  // zn = z / (cos^2 beta_b cos beta)
  double virtual_teeth2;
  double base_helix_angle_rad;                   // tan beta_b = tan beta cos alpha_t
  double flexibility_mm_um_per_n;                // q'
  double theoretical_single_stiffness_n_per_m2;  // c'_th = 1 / q'
  double basic_rack_factor;                      // C_B
  double low_load_factor;                        // 1 unless specific_load_n_per_m < 100 N/mm
  double single_stiffness_n_per_m2;              // c' = c'_th C_M C_R C_B cos beta (x low load)
  double transverse_contact_ratio;               // eps_alpha
  double mesh_stiffness_n_per_m2;                // c_gamma_alpha = c' (0.75 eps_alpha + 0.25)
};

// Throws InputError naming the first field out of range (counts, module,
// angles, face-width-free factors, tip diameters outside the base circles,
// a centre distance the base circles do not fit).
Iso6336Stiffness iso6336_method_b(const Iso6336Pair& pair);

// A GearPair's gears as ISO sees them, with the helix angle beta (0: the
// spur pair itself): its module and pressure angle as the normal ones, its
// rack's dedendum, the shifts, and in the transverse plane (ISO 21771)
// tan alpha_t = tan alpha_n / cos beta, inv alpha_wt = inv alpha_t + 2 tan
// alpha_n (x1 + x2) / (z1 + z2), a_w = m_n (z1 + z2) cos alpha_t / (2 cos beta
// cos alpha_wt), d_a = m_n z / cos beta + 2 (ha + x) m_n.
Iso6336Pair iso6336_pair(const GearPair& pair, double helix_angle_rad);

// q' = C1 + C2/zn1 + C3/zn2 + C4 x1 + C5 x1/zn1 + C6 x2 + C7 x2/zn2 + C8 x1^2 + C9 x2^2,
// mm um/N (ISO 6336-1 method B; constants of docs/stiffness-models.md section 4).
double iso6336_flexibility(double virtual_teeth1, double virtual_teeth2, double x1, double x2);

// eps_alpha = [sqrt(d_a1^2 - d_b1^2) / 2 + sqrt(d_a2^2 - d_b2^2) / 2 - a_w sin alpha_wt] / p_bt,
// in the transverse plane (ISO 21771), cos alpha_wt = (d_b1 + d_b2) / (2 a_w).
double iso6336_transverse_contact_ratio(const Iso6336Pair& pair);

// c_gamma_beta = 0.85 c_gamma_alpha, the mesh stiffness ISO 6336-1 uses for
// the face-load factor, N/m^2.
double iso6336_face_mesh_stiffness(const Iso6336Stiffness& stiffness);

// K_Hbeta of ISO 6336-1 for an effective mismatch F_betay (m), c_gamma_beta
// (N/m^2) and the load per face width F_m / b = F_t K_A K_v / b (N/m):
// 1 + F_betay c_gamma_beta / (2 F_m/b) while that is <= 2 (contact across the
// whole face), else sqrt(2 F_betay c_gamma_beta / (F_m/b)). Throws InputError
// naming the argument out of range.
double iso6336_face_load_factor(double mismatch_m, double face_mesh_stiffness_n_per_m2,
                                double load_per_width_n_per_m);

// An internal (ring-planet) spur mesh by ISO 6336-1 method B, the documented
// first version of the ring's stiffness (docs/planetary.md): q' with the
// internal gear's virtual tooth count taken as infinite (ISO 6336-1's rule for
// an internal gear: C3/zn2 and C7 x2/zn2 vanish), both gears unshifted,
// c' = c'_th C_M C_R C_B with C_M = 0.8, C_R = 1 (solid ring rim) and C_B of
// the rack, c_gamma_alpha = c' (0.75 eps_alpha + 0.25). eps_alpha is the
// internal mesh's contact ratio (geometry/planetary.hpp). Throws InputError
// naming contact_ratio unless 1.2 <= eps_alpha < 2 (the range the fit is
// stated for), and planet_teeth unless >= 4.
struct Iso6336Internal {
  double flexibility_mm_um_per_n;    // q'
  double single_stiffness_n_per_m2;  // c'
  double contact_ratio;              // eps_alpha
  double mesh_stiffness_n_per_m2;    // c_gamma_alpha
};
Iso6336Internal iso6336_internal_method_b(int planet_teeth, double contact_ratio,
                                          double rack_dedendum_coefficient,
                                          double rack_pressure_angle_rad);

// The per-pair stiffness of an internal mesh as a table in the contact
// position X over its segment [start, end] (base pitch t0, eps = (end -
// start) / t0 in [1, 2)): 0.875 c' b in the two double-contact zones (X within
// (eps - 1) t0 of either end) and c' b in the single-contact zone between, so
// that the mesh is c' b with one pair, 1.75 c' b with two, and its mean over a
// mesh period is c' b (0.75 eps + 0.25) = c_gamma_alpha b. The table is cut at
// the zones' edges (StiffnessTable's parts); the whole compliance is booked
// under the bending term (ISO's fit does not split it).
StiffnessTable iso6336_internal_pair_table(double start_m, double end_m, double base_pitch_m,
                                           double single_stiffness_n_per_m);

}  // namespace gearimpact
