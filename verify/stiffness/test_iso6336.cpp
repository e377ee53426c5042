// docs/stiffness-models.md section 4: ISO 6336-1 method B, checked against the
// worked example of ISO/TR 6336-30 Annex A, and the potential-energy model
// compared with it as with a band.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "rack_pairs.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::check_refused;
using gearimpact::verify::degree;
using gearimpact::verify::relative_difference;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();
// ISO's N/(mm um) per unit face width in N/m^2.
constexpr double n_per_mm_um = 1e9;

// ISO/TR 6336-30 Annex A (docs/stiffness-models.md section 4): helical, m_n 8 mm,
// z 17/103, x 0.145/0, beta 15.8 deg, alpha_n 20 deg, h_fP 1.4 m_n, a_w
// 500 mm, tip diameters 159.66 / 872.35 mm as the example rounds them.
Iso6336Pair annex_a() {
  Iso6336Pair p;
  p.normal_module_m = 8e-3;
  p.normal_pressure_angle_rad = 20.0 * degree;
  p.helix_angle_rad = 15.8 * degree;
  p.centre_distance_m = 500e-3;
  p.gear1.teeth = 17;
  p.gear2.teeth = 103;
  p.gear1.profile_shift_coefficient = 0.145;
  p.gear2.profile_shift_coefficient = 0.0;
  p.gear1.tip_diameter_m = 159.66e-3;
  p.gear2.tip_diameter_m = 872.35e-3;
  p.gear1.rack_dedendum_coefficient = p.gear2.rack_dedendum_coefficient = 1.4;
  p.gear1.rack_pressure_angle_rad = p.gear2.rack_pressure_angle_rad = 20.0 * degree;
  return p;
}

// |value - printed| within half a unit of the printed value's last digit.
bool to_printed_digits(double value, double printed, double last_digit) {
  return std::fabs(value - printed) <= 0.5 * last_digit;
}

// ISO's input for a rack-generated spur pair: same rack for both gears.
Iso6336Pair iso_of(const GearPair& rack, const RackGearPairGeometry& g) {
  Iso6336Pair p;
  p.normal_module_m = rack.module_m;
  p.normal_pressure_angle_rad = rack.pressure_angle_rad;
  p.centre_distance_m = g.centre_distance_m;
  const std::pair<Iso6336Gear*, Gear> gears[] = {{&p.gear1, Gear::one}, {&p.gear2, Gear::two}};
  for (const auto& [iso, gear] : gears) {
    iso->teeth = teeth(rack, gear);
    iso->profile_shift_coefficient = profile_shift(rack, gear);
    iso->rack_dedendum_coefficient = rack.dedendum_coefficient;
    iso->rack_pressure_angle_rad = rack.pressure_angle_rad;
  }
  p.gear1.tip_diameter_m = 2.0 * g.gear1.tip_radius_m;
  p.gear2.tip_diameter_m = 2.0 * g.gear2.tip_radius_m;
  return p;
}

}  // namespace

TEST_CASE("ISO/TR 6336-30 Annex A: zn, c'_th, c', c_gamma_alpha to the printed digits") {
  const Iso6336Stiffness r = iso6336_method_b(annex_a());
  CHECK(to_printed_digits(r.virtual_teeth1, 18.905, 1e-3));
  CHECK(to_printed_digits(r.virtual_teeth2, 114.543, 1e-3));
  CHECK(to_printed_digits(r.theoretical_single_stiffness_n_per_m2 / n_per_mm_um, 17.85584, 1e-5));
  CHECK(to_printed_digits(r.single_stiffness_n_per_m2 / n_per_mm_um, 12.37047, 1e-5));
  CHECK(to_printed_digits(r.mesh_stiffness_n_per_m2 / n_per_mm_um, 17.46485, 1e-5));
  // c_gamma_beta = 0.85 c_gamma_alpha: 14.84512 in a peer's transcription of the
  // example (gfsReboucas/Drivetrain MATISO_6336.m), not read in the TR itself.
  CHECK(to_printed_digits(iso6336_face_mesh_stiffness(r) / n_per_mm_um, 14.84512, 1e-5));
  // C_B = 1 + 0.5 (1.2 - 1.4) = 0.9 exactly for the 20 deg rack.
  CHECK(std::fabs(r.basic_rack_factor - 0.9) <= 4.0 * eps);
  CHECK(r.low_load_factor == 1.0);
  MESSAGE("Annex A: zn " << r.virtual_teeth1 << " / " << r.virtual_teeth2 << ", c'_th "
                         << r.theoretical_single_stiffness_n_per_m2 / n_per_mm_um << ", c' "
                         << r.single_stiffness_n_per_m2 / n_per_mm_um << ", eps_alpha "
                         << r.transverse_contact_ratio << ", c_gamma_alpha "
                         << r.mesh_stiffness_n_per_m2 / n_per_mm_um << " N/(mm um)");
}

TEST_CASE("ISO spur: zn = z, and the paper's pair gives c' b = 1.34e8 N/m") {
  const GearPair rack = verify::ross_pair_a();
  const RackGearPairGeometry g = rack_gear_pair_geometry(rack);
  const Iso6336Stiffness r = iso6336_method_b(iso_of(rack, g));
  CHECK(r.virtual_teeth1 == 20.0);
  CHECK(r.virtual_teeth2 == 80.0);
  // ISO's contact ratio from the diameters equals the rack pair's from the
  // line of action (two formulations of one length over one pitch).
  CHECK(relative_difference(r.transverse_contact_ratio, g.contact_ratio) <= 16.0 * eps);
  // docs/stiffness-models.md: "ISO 6336-1 gives a single-tooth stiffness c' b =
  // 1.34e8 N/m" for this pair, to its three digits.
  CHECK(std::fabs(r.single_stiffness_n_per_m2 * g.contact_width_m - 1.34e8) <= 0.005e8);
}

TEST_CASE("ISO low-load correction: (F_t K_A / b / 100 N/mm)^0.25 below 100 N/mm only") {
  Iso6336Pair p = annex_a();
  const double full = iso6336_method_b(p).single_stiffness_n_per_m2;
  p.specific_load_n_per_m = 25e3;  // a quarter of 100 N/mm
  const Iso6336Stiffness low = iso6336_method_b(p);
  CHECK(relative_difference(low.low_load_factor, std::sqrt(std::sqrt(0.25))) <= 4.0 * eps);
  CHECK(relative_difference(low.single_stiffness_n_per_m2, full * low.low_load_factor) <=
        4.0 * eps);
  // The threshold: at 100 N/mm c' holds as stated; just below, the factor (1 - 1e-6)^0.25.
  p.specific_load_n_per_m = 100e3;
  CHECK(iso6336_method_b(p).single_stiffness_n_per_m2 == full);
  CHECK(iso6336_method_b(p).low_load_factor == 1.0);
  p.specific_load_n_per_m = 100e3 * (1.0 - 1e-6);
  CHECK(relative_difference(iso6336_method_b(p).low_load_factor, std::pow(1.0 - 1e-6, 0.25)) <=
        4.0 * eps);
  CHECK(iso6336_method_b(p).low_load_factor < 1.0);
  // 424 N/mm (an earlier, unfounded threshold) and above: no correction.
  p.specific_load_n_per_m = 300e3;
  CHECK(iso6336_method_b(p).single_stiffness_n_per_m2 == full);
}

TEST_CASE("potential-energy against ISO 6336-1 method B, as a band") {
  // ISO's c' is an empirical fit to measurements and finite-element results
  // whose scatter the standard does not state; the models here include the
  // gear body (the foundation term) with a finite bore, ISO's C_R = 1 a
  // solid blank. What can be asserted is agreement within a band wide enough
  // for that and narrow enough to catch a factor in the model (a width, a
  // unit, a term counted twice or lost): +-25 %. The gaps are reported.
  constexpr double band = 0.25;
  for (const auto& named : verify::varied_rack_pairs()) {
    const RackGearPairGeometry g = rack_gear_pair_geometry(named.pair);
    const Iso6336Stiffness iso = iso6336_method_b(iso_of(named.pair, g));
    const double b = g.contact_width_m;
    StiffnessModel model;
    model.kind = StiffnessModelKind::potential_energy;
    // The single-pair plateau: the highest single-pair stiffness over the
    // single-pair zone [s_EAP - p_b, s_SAP + p_b], on 101 points (ISO's c'
    // is the single pair's maximum).
    const double from = g.end_of_active_profile_m - g.base_pitch_m;
    const double to = g.start_of_active_profile_m + g.base_pitch_m;
    double plateau = 0.0;
    for (int i = 0; i <= 100; ++i) {
      plateau = std::max(
          plateau, pair_stiffness(g, model, from + (to - from) * i / 100.0).stiffness_n_per_m);
    }
    const TimeVaryingMeshStiffness t = time_varying_mesh_stiffness(g, model, 10);
    const double single_gap = plateau / (iso.single_stiffness_n_per_m2 * b) - 1.0;
    const double mean_gap = t.mean_n_per_m / (iso.mesh_stiffness_n_per_m2 * b) - 1.0;
    CAPTURE(named.name);
    CHECK(std::fabs(single_gap) <= band);
    CHECK(std::fabs(mean_gap) <= band);
    MESSAGE(named.name << ": single-pair plateau " << plateau << " N/m vs c' b "
                       << iso.single_stiffness_n_per_m2 * b << " (" << 100.0 * single_gap
                       << " %); TVMS mean " << t.mean_n_per_m << " vs c_gamma_alpha b "
                       << iso.mesh_stiffness_n_per_m2 * b << " (" << 100.0 * mean_gap << " %)");
  }
}

TEST_CASE("ISO: bad input is refused naming the field") {
  Iso6336Pair p = annex_a();
  p.gear1.tip_diameter_m = 100e-3;
  check_refused([&] { iso6336_method_b(p); }, "gear1.tip_diameter", "above the base diameter");
  p = annex_a();
  p.centre_distance_m = 400e-3;
  check_refused([&] { iso6336_method_b(p); }, "centre_distance", "above (d_b1 + d_b2) / 2");
  p = annex_a();
  p.helix_angle_rad = 50.0 * degree;
  check_refused([&] { iso6336_method_b(p); }, "helix_angle", "[0, 45] deg");
  p = annex_a();
  p.specific_load_n_per_m = 0.0;
  check_refused([&] { iso6336_method_b(p); }, "specific_load", "> 0");
}
