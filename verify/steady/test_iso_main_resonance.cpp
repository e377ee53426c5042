// Where the simulated main resonance of the loaded paper pair sits in ISO 6336-1's resonance ratio
// N = n1 / n_E1 (docs/steady-state.md section 3.5), with ISO's c_gamma_alpha b set to the model's
// mean mesh stiffness k_mean.
//
// ISO's n_E1 is the relative-mode natural frequency sqrt(c_gamma_alpha / m_red) over z1; the
// model's is w_n = sqrt(k_mean / m_e). Both reduce the gears to solid discs, scaled with the gear
// ratio u: ISO on the pinion's mean diameter d_m1 = (d_a1 + d_f1) / 2, the model on the pitch
// diameter d_1 (J = rho pi r^4 L / 2). Per face width b, m_red b = m1* u^2 / (1 + u^2) with
// m1* = rho pi b d_m1^4 / (8 d_b1^2), and m_e is the same with d_1 in place of d_m1, so
//   m_red b / m_e = (d_m1 / d_1)^4   and the model's resonance z1 w1 = w_n sits at
//   N = w_n / (z1 w_E1) = sqrt(m_red b / m_e) = (d_m1 / d_1)^2,
// 0.9752 for the paper's pair (d_m1 = 39.5 mm, d_1 = 40 mm).
//
// Two excitations at the mesh frequency z1 w1:
// - constant stiffness k_mean and a torque harmonic at z1 w1 (the mesh excitation reduced to a
//   force, no Hertzian damping): a linear oscillator while the teeth stay in contact, so the DTE
//   amplitude peaks at z1 w1 = w_n sqrt(1 - 2 zeta^2) exactly, and the assertion is tight;
// - the paper's time-varying stiffness (the parametric excitation a real mesh has): its primary
//   resonance is where the free motion turns once per mesh period, and by Sturm's comparison
//   theorem that turn takes between 2 pi / w_min and 2 pi / w_max, w = sqrt(k / m_e) over the
//   stiffness's range; the bound is that band, and the measured shift is reported.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/steady/iso_resonance.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/steady/sweep.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "relative.hpp"
#include "steady_cases.hpp"

using namespace gearimpact;
using namespace gearimpact::steady_test;
using gearimpact::verify::relative_difference;

namespace {

constexpr double zeta = 0.05;  // loaded_paper_pair's viscous mesh damper

// ISO's n_E1 as a pinion speed in rad/s, by hand in ISO's units (mm, kg/mm, N/(mm um), min^-1)
// for the paper's pair with c_gamma_alpha in N/(mm um).
double iso_w_e1_by_hand(const GearPair& g, double c_gamma_alpha_n_mm_um) {
  const double module_mm = g.module_m * 1e3;
  const double u = static_cast<double>(g.teeth2) / g.teeth1;
  const double d1 = module_mm * g.teeth1;
  const double da1 = d1 + 2.0 * g.addendum_coefficient * module_mm;
  const double df1 = d1 - 2.0 * g.dedendum_coefficient * module_mm;
  const double dm1 = 0.5 * (da1 + df1);
  const double db1 = d1 * std::cos(g.pressure_angle_rad);
  const double rho_kg_mm3 = g.density_kg_m3 * 1e-9;
  const double m_red_kg_mm =
      std::numbers::pi * rho_kg_mm3 * u * u * std::pow(dm1, 4) / (8.0 * (u * u + 1.0) * db1 * db1);
  const double n_e1_per_min =
      30000.0 / (std::numbers::pi * g.teeth1) * std::sqrt(c_gamma_alpha_n_mm_um / m_red_kg_mm);
  return n_e1_per_min * 2.0 * std::numbers::pi / 60.0;
}

// (d_m1 / d_1)^2: the N of the model's undamped resonance (see the top of the file).
double mass_model_ratio(const GearPair& g) {
  const double d1 = g.module_m * g.teeth1;
  const double dm1 = d1 + (g.addendum_coefficient - g.dedendum_coefficient) * g.module_m;
  return (dm1 / d1) * (dm1 / d1);
}

// The index of the largest value.
template <typename Value>
std::size_t argmax(const std::vector<double>& grid, const Value& value) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < grid.size(); ++i) {
    if (value(i) > value(best)) best = i;
  }
  return best;
}

}  // namespace

TEST_CASE("constant k_mean and a torque harmonic at the mesh frequency: resonance at ISO's N") {
  const SimulationCase loaded = loaded_paper_pair(6000.0);
  const GearPair& g = loaded.gears;
  auto table = std::make_shared<const StiffnessTable>(g, loaded.model.stiffness);
  const double k_mean = mean_mesh_stiffness_n_per_m(loaded, *table);
  const double me = effective_mass_kg(g);
  const double w_n = std::sqrt(k_mean / me);
  const double rb1 = base_radius(g, Gear::one);
  const double j1 = moment_of_inertia(g, Gear::one);

  // The derived ratio against the library's m_red and m_e: the same quantities by another
  // route, so rounding only.
  const double dm1 =
      g.module_m * g.teeth1 + (g.addendum_coefficient - g.dedendum_coefficient) * g.module_m;
  const double m_red_b =
      iso_reduced_mass_kg_per_m(g.density_kg_m3, static_cast<double>(g.teeth2) / g.teeth1, dm1,
                                2.0 * rb1) *
      g.face_width_m;
  CHECK(relative_difference(std::sqrt(m_red_b / me), mass_model_ratio(g)) <= 1e-13);

  const double c_gamma_alpha = k_mean / g.face_width_m * 1e-9;  // N/(mm um)
  const double w_e1 = iso_w_e1_by_hand(g, c_gamma_alpha);

  // F_a = 0.05 F_m: the linear peak amplitude F_a / (2 zeta sqrt(1 - zeta^2)) ~ 0.5 F_m stays
  // below the static deflection F_m, so the drive flank never separates.
  const double static_force_n = 1000.0;
  const double force_amplitude_n = 0.05 * static_force_n;
  const auto point = [&](double w1) {
    SimulationCase c = loaded_paper_pair(w1);
    c.model.mesh_stiffness = MeshStiffnessMode::constant;
    c.model.constant_mesh_stiffness_n_per_m = k_mean;
    c.model.damping_update = DampingUpdate::off;
    c.initial.theta1_rad = (g.backlash_m + static_force_n / k_mean) / rb1;
    c.torque1 = Torque{};
    c.torque1.kind = Torque::Kind::sinusoidal;
    c.torque1.mean_n_m = static_force_n * rb1;
    c.torque1.amplitude_n_m = force_amplitude_n * j1 / (me * rb1);  // F_a = m_e Rb1 dT1 / J1
    c.torque1.angular_frequency_rad_per_s = g.teeth1 * w1;
    const SteadyPoint p = find_steady_state(c, *table, SteadySettings{});
    REQUIRE(p.converged);
    REQUIRE(p.regime == Regime::no_impact);
    return *p.dte_amplitude_m;
  };
  // Coarse in Omega = z1 w1 / w_n, step 0.02, then 0.001 around the coarse peak.
  const auto scan = [&](double from, double to, int points) {
    const std::vector<double> omega = sweep_grid(from, to, points, "from", "to", "points");
    std::vector<double> amplitude;
    for (const double o : omega) amplitude.push_back(point(o * w_n / g.teeth1));
    return omega[argmax(omega, [&](std::size_t i) { return amplitude[i]; })];
  };
  const double coarse = scan(0.8, 1.2, 21);
  const double fine_step = 0.001;
  const double omega_peak = scan(coarse - 0.02, coarse + 0.02, 41);
  const double n_peak = omega_peak * w_n / g.teeth1 / w_e1;
  const double n_expected = mass_model_ratio(g) * std::sqrt(1.0 - 2.0 * zeta * zeta);
  MESSAGE("constant k_mean = " << k_mean << " N/m, w_n = " << w_n << " rad/s, c_gamma_alpha = "
                               << c_gamma_alpha << " N/(mm um), w_E1 = " << w_e1
                               << " rad/s: DTE peak at Omega " << omega_peak << ", N_peak "
                               << n_peak << " (expected " << n_expected << ")");
  // The peak of A = F_a / sqrt((1 - Omega^2)^2 + (2 zeta Omega)^2) is at Omega^2 = 1 - 2 zeta^2;
  // the grid's largest value lies within half a fine step of it (1e-9 for rounding).
  CHECK(std::fabs(omega_peak - std::sqrt(1.0 - 2.0 * zeta * zeta)) <= 0.5 * fine_step + 1e-9);
  CHECK(std::fabs(n_peak - n_expected) <= 0.5 * fine_step * mass_model_ratio(g) + 1e-9);
}

TEST_CASE("time-varying stiffness: the dynamic factor's peak, in ISO's N, within Sturm's band") {
  const SimulationCase loaded = loaded_paper_pair(6000.0);
  const GearPair& g = loaded.gears;
  auto table = std::make_shared<const StiffnessTable>(g, loaded.model.stiffness);
  const double k_mean = mean_mesh_stiffness_n_per_m(loaded, *table);
  const double me = effective_mass_kg(g);
  const double w_n = std::sqrt(k_mean / me);
  const double w_e1 = iso_w_e1_by_hand(g, k_mean / g.face_width_m * 1e-9);

  // The extremes of the one- and two-pair mesh stiffness over a base pitch: Ke summed over the
  // loaded pairs at 2000 rotations of the pinion across one pitch.
  double k_min = INFINITY;
  double k_max = 0.0;
  const double pitch_rad = 2.0 * std::numbers::pi / g.teeth1;
  for (int i = 0; i < 2000; ++i) {
    const double theta1 = pitch_rad * i / 2000.0;
    const LoadedPairs pairs = loaded_pairs(g, Region::n1, theta1);
    double k = 0.0;
    for (std::size_t j = 0; j < pairs.count; ++j) k += table->stiffness(pairs.position_m[j]);
    k_min = std::min(k_min, k);
    k_max = std::max(k_max, k);
  }

  const auto sweep = [&](double from, double to, int points) {
    const std::vector<double> grid =
        sweep_grid(from * w_n / g.teeth1, to * w_n / g.teeth1, points, "from", "to", "points");
    const std::vector<SweepPointResult> up =
        sweep_line(loaded, [&](const SimulationCase&) { return table; }, "initial.w1", grid,
                   SweepDirection::up, 0, SteadySettings{}, {});
    for (const SweepPointResult& r : up) {
      REQUIRE(r.point.converged);
      // No contact loss: no softening to account for.
      REQUIRE(r.point.regime == Regime::no_impact);
    }
    const std::size_t best =
        argmax(grid, [&](std::size_t i) { return *up[i].point.dynamic_factor; });
    return std::make_pair(grid[best] * g.teeth1 / w_n, *up[best].point.dynamic_factor);
  };
  const auto [coarse, coarse_factor] = sweep(0.7, 1.2, 26);
  const double fine_step = 0.002;
  const auto [omega_peak, peak_factor] = sweep(coarse - 0.02, coarse + 0.02, 21);
  const double n_peak = omega_peak * w_n / g.teeth1 / w_e1;
  const double low = std::sqrt(k_min / k_mean);
  const double high = std::sqrt(k_max / k_mean);
  MESSAGE("time-varying stiffness " << k_min << " to " << k_max << " N/m, mean " << k_mean
                                    << ": dynamic factor " << peak_factor << " at Omega "
                                    << omega_peak << ", N_peak " << n_peak
                                    << "; Sturm band of Omega " << low << " to " << high);
  CHECK(coarse_factor <= peak_factor);
  // Sturm's band, widened by the fine grid's half step and by zeta^2 for the viscous damper's
  // shift of a peak (sqrt(1 -+ 2 zeta^2) ~ 1 -+ zeta^2).
  const double margin = 0.5 * fine_step + zeta * zeta;
  CHECK(omega_peak >= low - margin);
  CHECK(omega_peak <= high + margin);
  CHECK(n_peak >= mass_model_ratio(g) * (low - margin));
  CHECK(n_peak <= mass_model_ratio(g) * (high + margin));
}

TEST_CASE("the paper's runs at 1000 and 10000 rad/s in ISO's N") {
  const SimulationCase loaded = loaded_paper_pair(1000.0);
  const GearPair& g = loaded.gears;
  const StiffnessTable table(g, loaded.model.stiffness);
  const double k_mean = mean_mesh_stiffness_n_per_m(loaded, table);
  const Iso6336Stiffness iso = iso6336_method_b(iso6336_pair(g, 0.0));
  const double c_iso = iso.mesh_stiffness_n_per_m2 * 1e-9;  // N/(mm um)
  const double c_model = k_mean / g.face_width_m * 1e-9;
  const double w_e1_iso = iso_w_e1_by_hand(g, c_iso);
  const double w_e1_model = iso_w_e1_by_hand(g, c_model);
  for (const double w1 : {1000.0, 10000.0}) {
    const double n_iso = w1 / w_e1_iso;
    const double n_model = w1 / w_e1_model;
    MESSAGE("w1 = " << w1 << " rad/s: N = " << n_iso << " with ISO's c_gamma_alpha " << c_iso
                    << " N/(mm um), " << n_model << " with the model's mean " << c_model
                    << " N/(mm um)");
    // The library's N against the hand computation: rounding only.
    const double w_e1_library = iso_resonance_speed_rad_per_s(
        g.teeth1, iso.mesh_stiffness_n_per_m2,
        iso_reduced_mass_kg_per_m(
            g.density_kg_m3, static_cast<double>(g.teeth2) / g.teeth1,
            g.module_m * g.teeth1 + (g.addendum_coefficient - g.dedendum_coefficient) * g.module_m,
            2.0 * base_radius(g, Gear::one)));
    CHECK(relative_difference(iso_resonance_ratio(w1, w_e1_library), n_iso) <= 1e-13);
    // docs/steady-state.md quotes about 0.32 and 3.2 from ISO's usual c_gamma_alpha = 20 N/(mm um)
    // and two significant digits: the quote's rounding (0.005 of 0.315) plus the shift of N by
    // sqrt(20 / c_gamma_alpha) for this pair's own c_gamma_alpha.
    const double quoted = 0.32 * w1 / 1000.0;
    CHECK(std::fabs(n_iso / quoted - 1.0) <=
          0.005 / 0.315 + std::fabs(1.0 - std::sqrt(20.0 / c_iso)));
    // The model's mean stiffness is (k_mean / (c_gamma_alpha b)) stiffer, so N is lower by the
    // square root of that: two evaluations of one formula, rounding only.
    CHECK(relative_difference(n_model, n_iso * std::sqrt(c_iso / c_model)) <= 1e-13);
  }
}
