// The contact laws of one tooth pair: the penetration on each side of the
// backlash (31), the elastic force (30), restitution (33), the damping factor
// (32) in its three published forms, the Hertzian damping force (34), the
// normal force, and friction (35)-(38). docs/model.md, section Contact, damping,
// friction.
#pragma once

#include <array>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/named_values.hpp"

namespace gearimpact {

// (32): the three published forms of the damping factor D.
enum class DampingForm {
  herbert_mcwhannell,  // D = 6 K (1 - e) / {[(2e - 1)^2 + 3] Vi}  (default)
  hunt_crossley,       // D = 3 K (1 - e) / (2 Vi)
  lee_wang,            // D = 3 K (1 - e) / (4 Vi)
};
inline constexpr std::array<NamedValue<DampingForm>, 3> kDampingForms{{
    {DampingForm::herbert_mcwhannell, "herbert-mcwhannell",
     "D = 6 K (1 - e) / {[(2e - 1)^2 + 3] Vi}"},
    {DampingForm::hunt_crossley, "hunt-crossley", "D = 3 K (1 - e) / (2 Vi)"},
    {DampingForm::lee_wang, "lee-wang", "D = 3 K (1 - e) / (4 Vi)"},
}};

// Which stiffness K enters (32).
enum class DampingStiffness {
  current_pair,          // each loaded pair's current Ke (default)
  pitch_pair_at_impact,  // Ke of the pair nearest the pitch point, frozen at impact
  hertz,                 // Kh of (4)
};
inline constexpr std::array<NamedValue<DampingStiffness>, 3> kDampingStiffnesses{{
    {DampingStiffness::current_pair, "current-pair", "each loaded pair's current Ke"},
    {DampingStiffness::pitch_pair_at_impact, "pitch-pair-at-impact",
     "Ke of the pair nearest the pitch point, frozen at impact"},
    {DampingStiffness::hertz, "hertz", "Kh of (4)"},
}};

// (33) e = 1 - c (Vi / speed_unit)^p.
struct RestitutionLaw {
  double coefficient = 0.022;
  double exponent = 0.375;         // 3/8; 0.36 is the alternative reading
  double speed_unit_m_s = 1.0e-3;  // Vi in mm/s (default); 0.0254 for in/s, 1 for m/s
};

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

// +1 on N1, -1 on N2: the sign with which a line's forces act.
inline double line_sign(Region line) {
  return line == Region::n1 ? 1.0 : -1.0;
}

// (31) delta = s - B on N1, -s - B on N2, s = Rb1 theta1 - Rb2 theta2.
inline double penetration(Region line, double s_m, double backlash_m) {
  return line_sign(line) * s_m - backlash_m;
}

// (30) F = Ke delta.
inline double elastic_force(double stiffness_n_per_m, double delta_m) {
  return stiffness_n_per_m * delta_m;
}

// Normal force of a pair: N = F + G, 0 while it is clipped (a tooth can push,
// not pull; the clipping is an event of the integration, located where F + G
// turns negative, so the force is switched, not cut off inside a step).
inline double normal_force(double elastic_force_n, double damping_force_n, bool clipped) {
  return clipped ? 0.0 : elastic_force_n + damping_force_n;
}

// (36)-(38) the sliding speed of a pair at X (from C1 on N1, from C1' on N2):
// Vs = V_A1 - V_A2 = w1 X - w2 (lp - X), with the contact-point speeds (36)
// V_A1 = w1 X and (37) V_A2 = w2 (lp - X) along the tooth profiles. Zero at the
// pitch point when the gears roll.
inline double sliding_speed(double w1_rad_per_s, double w2_rad_per_s, double x_m, double lp_m) {
  return w1_rad_per_s * x_m - w2_rad_per_s * (lp_m - x_m);
}

// The entrainment speed of a pair at X: the sum of the rolling speeds (36),
// (37) of the two flanks at the contact, Ve = V_A1 + V_A2 = w1 X + w2 (lp - X).
inline double entrainment_speed(double w1_rad_per_s, double w2_rad_per_s, double x_m, double lp_m) {
  return w1_rad_per_s * x_m + w2_rad_per_s * (lp_m - x_m);
}

// Where the friction coefficient f of (35) comes from.
enum class FrictionLaw {
  constant,         // f = friction_coefficient over the whole mesh (the paper's)
  benedict_kelley,  // f of Benedict and Kelley (1961) at each pair's load and speeds
  table,            // f of a user table against the slide-to-roll ratio of each pair
};
inline constexpr std::array<NamedValue<FrictionLaw>, 3> kFrictionLaws{{
    {FrictionLaw::constant, "constant", "f = friction_coefficient everywhere (the paper's (35))"},
    {FrictionLaw::benedict_kelley, "benedict-kelley",
     "f = 0.0127 C_R log10(3.17e8 (W/F) / (nu0 Vs Ve^2)) of Benedict and Kelley (1961), "
     "clipped to [0, friction_coefficient_max]"},
    {FrictionLaw::table, "table",
     "f interpolated linearly in a table against the slide-to-roll ratio 2 Vs / Ve, constant "
     "beyond its ends"},
}};

// The table of FrictionLaw::table: f_i at the slide-to-roll ratios r_i,
// strictly increasing, of one length (at least 1), each f_i in [0, 1].
struct FrictionTable {
  std::vector<double> slide_to_roll;
  std::vector<double> coefficient;
};

// The slide-to-roll ratio of a pair, 2 Vs / Ve: the sliding speed over the
// mean rolling speed Ve / 2 of the two flanks (Vs = 0 at the pitch point when
// the gears roll; -2 or 2 where one flank does not roll). Where the flanks do
// not roll at all (Ve = 0) it is infinite with the sign of Vs, 0 if Vs = 0 too.
double slide_to_roll_ratio(double sliding_speed_m_s, double entrainment_speed_m_s);

// f of the table at the slide-to-roll ratio r: linear between the entries,
// the first (last) coefficient below (above) the table's ends.
double table_friction_coefficient(const FrictionTable& table, double slide_to_roll);

// The lubricated contact of Benedict and Kelley's law, in SI.
struct BenedictKelleyLaw {
  double viscosity_pa_s = 0.0;    // nu0, the lubricant's dynamic viscosity, > 0
  double roughness_m = 0.0;       // S, the mean surface roughness, below 50 micro-inches
  double most_coefficient = 0.1;  // f_max, the clip of f where the formula diverges
};

// Benedict and Kelley (1961), as He, Gunda and Singh (J. Sound Vib. 2007) and
// Xu et al. (J. Tribol. 2007) restate it, in its imperial units:
//   f = 0.0127 C_R log10( 3.17e8 (W/F) / (nu0 Vs Ve^2) ),  C_R = 50 / (50 - S)
// W/F in lbf/in, nu0 in cP, |Vs| and |Ve| in in/s, S in micro-inches. The SI
// arguments are converted here and nowhere else (1 lbf/in = 175.126835 N/m,
// 1 cP = 1e-3 Pa s, 1 in/s = 0.0254 m/s, 1 micro-inch = 0.0254 um). The
// formula diverges at the pitch point (Vs -> 0) and is negative for a log
// argument below 1 (light load, fast sliding), so f is clipped to
// [0, law.most_coefficient]; without load (W = 0) f is 0.
double benedict_kelley_coefficient(const BenedictKelleyLaw& law, double load_per_width_n_per_m,
                                   double sliding_speed_m_s, double entrainment_speed_m_s);

// (35) Ff = f N against the sliding: Ff = f N sign(Vs) on N1 and
// -f N sign(Vs') on N2, `slip_sign` the sign of Vs (+1 or -1), held constant
// between friction-reversal events, or its smoothed form tanh(Vs / v_s) in
// (-1, 1).
inline double friction_force(Region line, double friction_coefficient, double normal_force_n,
                             double slip_sign) {
  return line_sign(line) * friction_coefficient * normal_force_n * slip_sign;
}

}  // namespace gearimpact
