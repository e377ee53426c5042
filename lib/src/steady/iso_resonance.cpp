#include "gearimpact/steady/iso_resonance.hpp"

#include <cmath>
#include <memory>
#include <string>

#include "../require.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"

namespace gearimpact {

namespace {

using namespace checks;

// Table 8 for perfect gears: the coefficients that multiply B_k = 1, and C_v7.
struct PerfectGearCoefficients {
  double c_v3;
  double c_v4;
  double c_v7;
};

PerfectGearCoefficients table8(double eps_gamma) {
  PerfectGearCoefficients c{0.23, 0.90, 0.75};
  if (eps_gamma > 2.0) {
    c.c_v3 = 0.096 / (eps_gamma - 1.56);
    c.c_v4 = (0.57 - 0.05 * eps_gamma) / (eps_gamma - 1.44);
  }
  if (eps_gamma > 2.5) {
    c.c_v7 = 1.0;
  } else if (eps_gamma > 1.5) {
    c.c_v7 = 0.125 * std::sin(pi * (eps_gamma - 2.0)) + 0.875;
  }
  return c;
}

}  // namespace

double iso_reduced_mass_kg_per_m(double density_kg_per_m3, double gear_ratio,
                                 double mean_diameter1_m, double base_diameter1_m) {
  require_finite_positive("density", density_kg_per_m3, "in kg/m^3");
  require_finite_positive("gear_ratio", gear_ratio, "(u = z2 / z1)");
  require_finite_positive("mean_diameter1", mean_diameter1_m, "in m (d_m1 = (d_a1 + d_f1) / 2)");
  require_finite_positive("base_diameter1", base_diameter1_m, "in m");
  const double u2 = gear_ratio * gear_ratio;
  const double dm2 = mean_diameter1_m * mean_diameter1_m;
  return pi * density_kg_per_m3 * u2 * dm2 * dm2 /
         (8.0 * (u2 + 1.0) * base_diameter1_m * base_diameter1_m);
}

double iso_resonance_speed_rad_per_s(int pinion_teeth, double mesh_stiffness_per_width_n_per_m2,
                                     double reduced_mass_kg_per_m) {
  if (pinion_teeth < 1) {
    throw InputError("pinion_teeth", static_cast<double>(pinion_teeth), ">= 1 (z1)");
  }
  require_finite_positive("mesh_stiffness_per_width", mesh_stiffness_per_width_n_per_m2,
                          "in N/m^2 (c_gamma_alpha; 1 N/(mm um) = 1e9 N/m^2)");
  require_finite_positive("reduced_mass", reduced_mass_kg_per_m, "in kg/m (m_red)");
  return std::sqrt(mesh_stiffness_per_width_n_per_m2 / reduced_mass_kg_per_m) / pinion_teeth;
}

double iso_resonance_ratio(double pinion_speed_rad_per_s, double resonance_speed_rad_per_s) {
  if (!std::isfinite(pinion_speed_rad_per_s) || pinion_speed_rad_per_s < 0.0) {
    throw InputError("pinion_speed", pinion_speed_rad_per_s, "a finite value >= 0 in rad/s");
  }
  require_finite_positive("resonance_speed", resonance_speed_rad_per_s, "in rad/s");
  return pinion_speed_rad_per_s / resonance_speed_rad_per_s;
}

IsoDynamicFactor iso_dynamic_factor_perfect_gears(double resonance_ratio,
                                                  double total_contact_ratio,
                                                  double line_load_n_per_m) {
  if (!std::isfinite(resonance_ratio) || resonance_ratio < 0.0) {
    throw InputError("resonance_ratio", resonance_ratio, "a finite value >= 0 (N = n1 / n_E1)");
  }
  if (!std::isfinite(total_contact_ratio) || total_contact_ratio <= 1.0) {
    throw InputError("total_contact_ratio", total_contact_ratio,
                     "a finite value > 1 (eps_gamma; ISO's Table 8 starts above 1)");
  }
  require_finite_positive("line_load", line_load_n_per_m, "in N/m (F_t K_A / b)");

  const PerfectGearCoefficients c = table8(total_contact_ratio);
  const double line_load_n_per_mm = line_load_n_per_m * 1e-3;
  const double n_s =
      line_load_n_per_mm >= 100.0 ? 0.85 : 0.5 + 0.35 * std::sqrt(line_load_n_per_mm / 100.0);
  const double n = resonance_ratio;
  const double resonance_value = 1.0 + c.c_v4;
  if (n <= n_s) return {1.0 + c.c_v3 * n, IsoSpeedRange::subcritical};
  if (n <= 1.15) return {resonance_value, IsoSpeedRange::main_resonance};
  if (n >= 1.5) return {c.c_v7, IsoSpeedRange::supercritical};
  return {c.c_v7 + (resonance_value - c.c_v7) * (1.5 - n) / 0.35, IsoSpeedRange::intermediate};
}

double quasi_static_force_ratio(const SimulationCase& c, const StiffnessTable& table) {
  if (c.model.mesh_stiffness == MeshStiffnessMode::constant) return 1.0;
  if (!is_unmodified(c.modifications) || !c.faults.empty()) {
    // Gaps and faulted teeth: the peak of the pair's own loaded static transmission error, under
    // the mean load on the drive flanks. `table` is the healthy pair's, shared without a copy.
    const MeshTables tables(
        c.gears, c.model.stiffness, c.faults,
        std::shared_ptr<const StiffnessTable>(std::shared_ptr<const StiffnessTable>(), &table));
    return quasi_static_peak_force_ratio(c.gears, c.modifications,
                                         std::fabs(mean_torque_n_m(c.torque1, "torque1")), tables);
  }
  const ContactSegment segment = contact_segment(c.gears);
  const double t0 = base_pitch(c.gears);
  double before = 0.0;
  for (int k = 1; segment.start_m + k * t0 <= segment.end_m; ++k) {
    before += table.stiffness(segment.start_m + k * t0);
  }
  return (before + table.stiffness(segment.start_m)) / before;
}

std::optional<IsoScale> iso_scale(const SimulationCase& c, const StiffnessTable& table) {
  const GearPair& g = c.gears;
  const double r1 = pitch_radius(g, Gear::one);
  const double line_load = std::fabs(mean_torque_n_m(c.torque1, "torque1")) / (r1 * g.face_width_m);
  if (!(line_load > 0.0)) return std::nullopt;
  // d_m1 = (d_a1 + d_f1) / 2, the tip and root circles of the rack-cut pinion.
  const RackGearGeometry pinion = rack_gear_pair_geometry(g).gear1;
  const double mean_diameter1 = pinion.tip_radius_m + pinion.root_radius_m;
  const double m_red =
      iso_reduced_mass_kg_per_m(g.density_kg_m3, static_cast<double>(g.teeth2) / g.teeth1,
                                mean_diameter1, 2.0 * base_radius(g, Gear::one));
  const Iso6336Stiffness iso = iso6336_method_b(iso6336_pair(g, 0.0));
  IsoScale scale;
  scale.resonance_speed_rad_per_s = iso_resonance_speed_rad_per_s(
      g.teeth1, mean_mesh_stiffness_n_per_m(c, table) / g.face_width_m, m_red);
  scale.resonance_speed_iso_stiffness_rad_per_s =
      iso_resonance_speed_rad_per_s(g.teeth1, iso.mesh_stiffness_n_per_m2, m_red);
  scale.contact_ratio = iso.transverse_contact_ratio;
  scale.line_load_n_per_m = line_load;
  scale.quasi_static_force_ratio = quasi_static_force_ratio(c, table);
  return scale;
}

}  // namespace gearimpact
