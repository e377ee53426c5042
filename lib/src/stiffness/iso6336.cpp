#include "gearimpact/stiffness/iso6336.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../require.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

constexpr double degree = pi / 180.0;
// ISO 6336-1 method B: c' holds for F_t K_A / b >= 100 N/mm; below, it is multiplied by
// (F_t K_A / b / 100 N/mm)^0.25. The load in N/m.
constexpr double reference_specific_load_n_per_m = 100.0e3;

// Transverse quantities of ISO 21771 for a helix angle beta.
struct Transverse {
  double pressure_angle_rad;  // alpha_t: tan alpha_t = tan alpha_n / cos beta
  double module_m;            // m_t = m_n / cos beta
};

Transverse transverse(const Iso6336Pair& pair) {
  const double cos_beta = std::cos(pair.helix_angle_rad);
  return {std::atan(std::tan(pair.normal_pressure_angle_rad) / cos_beta),
          pair.normal_module_m / cos_beta};
}

void validate(const Iso6336Pair& pair) {
  checks::require_finite_positive("normal_module", pair.normal_module_m, "m");
  const double an = pair.normal_pressure_angle_rad;
  if (!std::isfinite(an) || an <= 0.0 || an > 45.0 * degree) {
    throw InputError("normal_pressure_angle", an, "(0, 45] deg in rad");
  }
  const double beta = pair.helix_angle_rad;
  if (!std::isfinite(beta) || beta < 0.0 || beta > 45.0 * degree) {
    throw InputError("helix_angle", beta, "[0, 45] deg in rad");
  }
  checks::require_finite_positive("mesh_factor", pair.mesh_factor, "(C_M)");
  checks::require_finite_positive("blank_factor", pair.blank_factor, "(C_R)");
  if (pair.specific_load_n_per_m) {
    checks::require_finite_positive("specific_load", *pair.specific_load_n_per_m,
                                    "N/m (F_t K_A / b)");
  }
  const Transverse t = transverse(pair);
  const Iso6336Gear* gears[] = {&pair.gear1, &pair.gear2};
  double base_diameter_sum = 0.0;
  for (int i = 0; i < 2; ++i) {
    const Iso6336Gear& g = *gears[i];
    const std::string p = i == 0 ? "gear1." : "gear2.";
    if (g.teeth < 4) throw InputError(p + "teeth", std::to_string(g.teeth), "an integer >= 4");
    if (!std::isfinite(g.profile_shift_coefficient)) {
      throw InputError(p + "profile_shift_coefficient", g.profile_shift_coefficient,
                       "a finite value");
    }
    checks::require_finite_positive(p + "rack_dedendum_coefficient", g.rack_dedendum_coefficient,
                                    "(h_fP / m_n)");
    const double ap = g.rack_pressure_angle_rad;
    if (!std::isfinite(ap) || ap <= 0.0 || ap > 45.0 * degree) {
      throw InputError(p + "rack_pressure_angle", ap, "(0, 45] deg in rad");
    }
    const double base_diameter = g.teeth * t.module_m * std::cos(t.pressure_angle_rad);
    base_diameter_sum += base_diameter;
    if (!std::isfinite(g.tip_diameter_m) || g.tip_diameter_m <= base_diameter) {
      throw InputError(p + "tip_diameter", g.tip_diameter_m,
                       "values above the base diameter " + format_number(base_diameter) + " m");
    }
  }
  if (!std::isfinite(pair.centre_distance_m) || 2.0 * pair.centre_distance_m <= base_diameter_sum) {
    throw InputError(
        "centre_distance", pair.centre_distance_m,
        "values above (d_b1 + d_b2) / 2 = " + format_number(0.5 * base_diameter_sum) + " m");
  }
}

// C_B of one basic rack: [1 + 0.5 (1.2 - h_fP/m_n)] [1 - 0.02 (20 deg - alpha_Pn)],
// the angle in degrees (ISO 6336-1 method B).
double basic_rack_factor(const Iso6336Gear& gear) {
  return (1.0 + 0.5 * (1.2 - gear.rack_dedendum_coefficient)) *
         (1.0 - 0.02 * (20.0 - gear.rack_pressure_angle_rad / degree));
}

}  // namespace

double iso6336_flexibility(double zn1, double zn2, double x1, double x2) {
  // ISO 6336-1 method B, C1 .. C9.
  constexpr double c[9] = {0.04723,  0.15551,  0.25791, -0.00635, -0.11654,
                           -0.00193, -0.24188, 0.00529, 0.00182};
  return c[0] + c[1] / zn1 + c[2] / zn2 + c[3] * x1 + c[4] * x1 / zn1 + c[5] * x2 +
         c[6] * x2 / zn2 + c[7] * x1 * x1 + c[8] * x2 * x2;
}

double iso6336_transverse_contact_ratio(const Iso6336Pair& pair) {
  validate(pair);
  const Transverse t = transverse(pair);
  const double cos_at = std::cos(t.pressure_angle_rad);
  const double db1 = pair.gear1.teeth * t.module_m * cos_at;
  const double db2 = pair.gear2.teeth * t.module_m * cos_at;
  const double da1 = pair.gear1.tip_diameter_m;
  const double da2 = pair.gear2.tip_diameter_m;
  const double awt = std::acos((db1 + db2) / (2.0 * pair.centre_distance_m));
  // ISO 21771: the path of contact over the transverse base pitch pi m_t cos alpha_t.
  const double path = 0.5 * std::sqrt(da1 * da1 - db1 * db1) +
                      0.5 * std::sqrt(da2 * da2 - db2 * db2) -
                      pair.centre_distance_m * std::sin(awt);
  return path / (pi * t.module_m * cos_at);
}

Iso6336Stiffness iso6336_method_b(const Iso6336Pair& pair) {
  validate(pair);
  Iso6336Stiffness r{};
  const Transverse t = transverse(pair);
  const double cos_beta = std::cos(pair.helix_angle_rad);
  r.base_helix_angle_rad =
      std::atan(std::tan(pair.helix_angle_rad) * std::cos(t.pressure_angle_rad));
  const double cos_bb = std::cos(r.base_helix_angle_rad);
  // zn = z / (cos^2 beta_b cos beta): the virtual spur gear of the normal section.
  r.virtual_teeth1 = pair.gear1.teeth / (cos_bb * cos_bb * cos_beta);
  r.virtual_teeth2 = pair.gear2.teeth / (cos_bb * cos_bb * cos_beta);
  r.flexibility_mm_um_per_n =
      iso6336_flexibility(r.virtual_teeth1, r.virtual_teeth2, pair.gear1.profile_shift_coefficient,
                          pair.gear2.profile_shift_coefficient);
  // c'_th = 1 / q', converted once from N/(mm um) to N/m^2.
  constexpr double n_per_mm_um = 1.0e9;
  r.theoretical_single_stiffness_n_per_m2 = n_per_mm_um / r.flexibility_mm_um_per_n;
  // The mean of the two racks' factors when they differ.
  r.basic_rack_factor = 0.5 * (basic_rack_factor(pair.gear1) + basic_rack_factor(pair.gear2));
  r.low_load_factor = 1.0;
  if (pair.specific_load_n_per_m && *pair.specific_load_n_per_m < reference_specific_load_n_per_m) {
    r.low_load_factor =
        std::pow(*pair.specific_load_n_per_m / reference_specific_load_n_per_m, 0.25);
  }
  // c' = c'_th C_M C_R C_B cos beta.
  r.single_stiffness_n_per_m2 = r.theoretical_single_stiffness_n_per_m2 * pair.mesh_factor *
                                pair.blank_factor * r.basic_rack_factor * cos_beta *
                                r.low_load_factor;
  r.transverse_contact_ratio = iso6336_transverse_contact_ratio(pair);
  // c_gamma_alpha = c' (0.75 eps_alpha + 0.25).
  r.mesh_stiffness_n_per_m2 =
      r.single_stiffness_n_per_m2 * (0.75 * r.transverse_contact_ratio + 0.25);
  return r;
}

Iso6336Pair iso6336_pair(const GearPair& pair, double helix_angle_rad) {
  if (!std::isfinite(helix_angle_rad) || helix_angle_rad < 0.0 || helix_angle_rad > 45.0 * degree) {
    throw InputError("helix_angle", helix_angle_rad, "[0, 45] deg in rad");
  }
  Iso6336Pair iso;
  iso.normal_module_m = pair.module_m;
  iso.normal_pressure_angle_rad = pair.pressure_angle_rad;
  iso.helix_angle_rad = helix_angle_rad;
  const double cos_beta = std::cos(helix_angle_rad);
  const double alpha_t = std::atan(std::tan(pair.pressure_angle_rad) / cos_beta);
  const double z_sum = static_cast<double>(pair.teeth1) + static_cast<double>(pair.teeth2);
  const double x_sum = pair.profile_shift1 + pair.profile_shift2;
  // A spur pair keeps the operating pressure angle of its own geometry.
  const double alpha_wt =
      helix_angle_rad == 0.0
          ? operating_pressure_angle(pair)
          : inverse_involute(involute_function(alpha_t) +
                             2.0 * std::tan(pair.pressure_angle_rad) * x_sum / z_sum);
  iso.centre_distance_m =
      pair.module_m * z_sum * std::cos(alpha_t) / (2.0 * cos_beta * std::cos(alpha_wt));
  for (Gear gear : {Gear::one, Gear::two}) {
    Iso6336Gear& g = gear == Gear::one ? iso.gear1 : iso.gear2;
    g.teeth = teeth(pair, gear);
    g.profile_shift_coefficient = profile_shift(pair, gear);
    g.tip_diameter_m =
        pair.module_m * g.teeth / cos_beta +
        2.0 * (pair.addendum_coefficient + g.profile_shift_coefficient) * pair.module_m;
    g.rack_dedendum_coefficient = pair.dedendum_coefficient;
    g.rack_pressure_angle_rad = pair.pressure_angle_rad;
  }
  return iso;
}

double iso6336_face_mesh_stiffness(const Iso6336Stiffness& stiffness) {
  // c_gamma_beta = 0.85 c_gamma_alpha.
  return 0.85 * stiffness.mesh_stiffness_n_per_m2;
}

double iso6336_face_load_factor(double mismatch_m, double c_gamma_beta, double load_per_width) {
  if (!(mismatch_m >= 0.0) || !std::isfinite(mismatch_m)) {
    throw InputError("F_betay", format_number(mismatch_m) + " m", "a finite value >= 0 m");
  }
  checks::require_finite_positive("c_gamma_beta", c_gamma_beta, "N/m^2");
  checks::require_finite_positive("F_m/b", load_per_width, "N/m");
  // The uncoupled face of uniform stiffness: contact over the whole face while
  // the mismatch's share stays below the mean load, else over part of it.
  const double full_contact = 1.0 + mismatch_m * c_gamma_beta / (2.0 * load_per_width);
  if (full_contact <= 2.0) return full_contact;
  return std::sqrt(2.0 * mismatch_m * c_gamma_beta / load_per_width);
}

Iso6336Internal iso6336_internal_method_b(int planet_teeth, double contact_ratio,
                                          double rack_dedendum_coefficient,
                                          double rack_pressure_angle_rad) {
  if (planet_teeth < 4) {
    throw InputError("planet_teeth", std::to_string(planet_teeth), "an integer >= 4");
  }
  if (!(contact_ratio >= 1.2 && contact_ratio < 2.0)) {
    throw InputError("contact_ratio", contact_ratio,
                     "[1.2, 2): the ring-planet mesh's eps_alpha, the range of ISO 6336-1 "
                     "method B's c_gamma_alpha = c' (0.75 eps_alpha + 0.25)");
  }
  Iso6336Gear rack;
  rack.rack_dedendum_coefficient = rack_dedendum_coefficient;
  rack.rack_pressure_angle_rad = rack_pressure_angle_rad;
  Iso6336Internal r{};
  // zn2 infinite: its two terms vanish (a division by infinity gives 0).
  r.flexibility_mm_um_per_n =
      iso6336_flexibility(planet_teeth, std::numeric_limits<double>::infinity(), 0.0, 0.0);
  constexpr double n_per_mm_um = 1.0e9;
  constexpr double mesh_factor = 0.8;   // C_M
  constexpr double blank_factor = 1.0;  // C_R
  r.single_stiffness_n_per_m2 = n_per_mm_um / r.flexibility_mm_um_per_n * mesh_factor *
                                blank_factor * basic_rack_factor(rack);
  r.contact_ratio = contact_ratio;
  r.mesh_stiffness_n_per_m2 = r.single_stiffness_n_per_m2 * (0.75 * contact_ratio + 0.25);
  return r;
}

StiffnessTable iso6336_internal_pair_table(double start_m, double end_m, double base_pitch_m,
                                           double single_stiffness_n_per_m) {
  const double double_zone = end_m - start_m - base_pitch_m;  // (eps - 1) t0
  if (!(double_zone >= 0.0 && double_zone < base_pitch_m)) {
    throw InputError("contact_ratio", (end_m - start_m) / base_pitch_m,
                     "[1, 2) for the internal mesh's per-pair table");
  }
  const double first_edge = start_m + double_zone;
  const double second_edge = end_m - double_zone;
  const ComplianceFunction compliance = [=](double x) {
    const bool two = x < first_edge || x > second_edge;
    Compliances c;
    c.of(Term::bending) = 1.0 / ((two ? 0.875 : 1.0) * single_stiffness_n_per_m);
    return c;
  };
  // A constant on each part: the lowest order and one piece fit it exactly.
  StiffnessTableOptions options;
  options.pieces = 1;
  options.order = 2;
  std::vector<double> breaks;
  if (double_zone > 0.0) breaks = {first_edge, second_edge};
  return StiffnessTable(start_m, end_m, compliance, breaks, options);
}

}  // namespace gearimpact
