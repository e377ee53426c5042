#include "gearimpact/dynamics/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/numerics/quadrature.hpp"

namespace gearimpact {

double inverse_effective_mass_per_kg(double base_radius1_m, double inertia1_kg_m2,
                                     double base_radius2_m, double inertia2_kg_m2) {
  return base_radius1_m * base_radius1_m / inertia1_kg_m2 +
         base_radius2_m * base_radius2_m / inertia2_kg_m2;
}

double effective_mass_kg(double base_radius1_m, double inertia1_kg_m2, double base_radius2_m,
                         double inertia2_kg_m2) {
  return 1.0 / inverse_effective_mass_per_kg(base_radius1_m, inertia1_kg_m2, base_radius2_m,
                                             inertia2_kg_m2);
}

double inverse_effective_mass_per_kg(const GearPair& pair) {
  return inverse_effective_mass_per_kg(
      base_radius(pair, Gear::one), moment_of_inertia(pair, Gear::one),
      base_radius(pair, Gear::two), moment_of_inertia(pair, Gear::two));
}

double effective_mass_kg(const GearPair& pair) {
  return 1.0 / inverse_effective_mass_per_kg(pair);
}

double viscous_mesh_damping_n_s_per_m(double damping_ratio, double mesh_stiffness_n_per_m,
                                      double effective_mass_kg) {
  if (!std::isfinite(damping_ratio) || damping_ratio < 0.0) {
    throw InputError("damping_ratio", damping_ratio, "a finite value >= 0 (dimensionless)");
  }
  if (!std::isfinite(mesh_stiffness_n_per_m) || mesh_stiffness_n_per_m <= 0.0) {
    throw InputError("mesh_stiffness", mesh_stiffness_n_per_m, "a finite value > 0 in N/m");
  }
  if (!std::isfinite(effective_mass_kg) || effective_mass_kg <= 0.0) {
    throw InputError("effective_mass", effective_mass_kg, "a finite value > 0 in kg");
  }
  return 2.0 * damping_ratio * std::sqrt(mesh_stiffness_n_per_m * effective_mass_kg);
}

int gap_zone(const std::vector<double>& kinks_m, double x_m) {
  return static_cast<int>(std::upper_bound(kinks_m.begin(), kinks_m.end(), x_m) - kinks_m.begin());
}

PairPenetration pair_penetration_with_gap(const ToothGaps& gaps, const std::vector<double>& kinks_m,
                                          int zone, Region line, int k, double x_m, double dl_m,
                                          double dl_rate_m_s, double x_rate_m_s, double start_m,
                                          double end_m) {
  const auto z = static_cast<std::size_t>(zone);
  const double lo = z > 0 ? kinks_m[z - 1] : start_m;
  const double hi = z < kinks_m.size() ? kinks_m[z] : end_m;
  const double margin = 1e-6 * (hi - lo);
  const double slope = gaps.gap_and_slope(line, k, std::clamp(x_m, lo + margin, hi - margin)).slope;
  const double edge = std::clamp(x_m, lo, hi);
  const double gap = gaps.gap_m(line, k, edge) + slope * (x_m - edge);
  return {dl_m - gap, dl_rate_m_s - slope * x_rate_m_s, slope};
}

double least_pair_gap_m(const ToothGaps& gaps, const MeshLayout& layout, Region line,
                        double theta1_rad) {
  const double ref = layout.reference_m(line, theta1_rad);
  const LoadedRange range = layout.loaded(ref);
  double least = std::numeric_limits<double>::infinity();
  for (int j = 0; j < range.count; ++j) {
    const int k = range.k_first + j;
    least = std::min(least, gaps.gap_m(line, k, layout.position_m(ref, k)));
  }
  return least;
}

namespace {

// Int Ke(X) dX of one table over the segment a pair is in contact over
// (pair_contact_segment: a helical pair's, widened). Ke is smooth between
// the table's breaks (a fault's edges, where it may jump; a helical pair's
// kinks; none for healthy spur teeth), so the adaptive rule meets 1e-12
// relative on each part.
double stiffness_integral(const SimulationCase& c, const StiffnessTable& table) {
  const ContactSegment segment = pair_contact_segment(c.gears);
  QuadratureTolerance tolerance;
  tolerance.relative = 1e-12;
  std::vector<double> ends{segment.start_m};
  for (double x : table.breaks_m()) {
    if (x > segment.start_m && x < segment.end_m) ends.push_back(x);
  }
  ends.push_back(segment.end_m);
  double sum = 0.0;
  for (std::size_t i = 1; i < ends.size(); ++i) {
    sum += integrate_gsl_qag([&](double x) { return table.stiffness(x); }, ends[i - 1], ends[i],
                             tolerance)
               .value;
  }
  return sum;
}

}  // namespace

double mean_mesh_stiffness_n_per_m(const SimulationCase& c, const StiffnessTable& table) {
  if (c.model.mesh_stiffness == MeshStiffnessMode::constant) {
    return c.model.constant_mesh_stiffness_n_per_m;
  }
  return stiffness_integral(c, table) / base_pitch(c.gears);
}

double mean_mesh_stiffness_n_per_m(const SimulationCase& c, const MeshTables& tables) {
  if (c.model.mesh_stiffness == MeshStiffnessMode::constant) {
    return c.model.constant_mesh_stiffness_n_per_m;
  }
  if (!tables.has_faults()) return mean_mesh_stiffness_n_per_m(c, tables.healthy());
  // Each table integrated once, times how often its pair comes in a period;
  // summed in the order the pairs come, so that the sum does not depend on
  // where the tables lie in memory.
  const long long periods = tables.true_period_mesh_periods();
  double sum = 0.0;
  for (const auto& [table, times] : tables.table_repeats(periods)) {
    sum += static_cast<double>(times) * stiffness_integral(c, *table);
  }
  return sum / (static_cast<double>(periods) * base_pitch(c.gears));
}

double case_mesh_damping_n_s_per_m(const SimulationCase& c, const StiffnessTable& table,
                                   const MeshTables* teeth) {
  if (c.model.mesh_damping_ratio <= 0.0) return 0.0;
  return case_mesh_damping_n_s_per_m(c, table, teeth, effective_mass_kg(c.gears));
}

double case_mesh_damping_n_s_per_m(const SimulationCase& c, const StiffnessTable& table,
                                   const MeshTables* teeth, double mass_kg) {
  if (c.model.mesh_damping_ratio <= 0.0) return 0.0;
  // With faults the damper sees the mean over the true period.
  const double mean_k =
      teeth ? mean_mesh_stiffness_n_per_m(c, *teeth) : mean_mesh_stiffness_n_per_m(c, table);
  return viscous_mesh_damping_n_s_per_m(c.model.mesh_damping_ratio, mean_k, mass_kg);
}

double natural_frequency_rad_per_s(const SimulationCase& c, const StiffnessTable& table) {
  return std::sqrt(mean_mesh_stiffness_n_per_m(c, table) / effective_mass_kg(c.gears));
}

MeshTeeth mesh_teeth(const SimulationCase& c, const StiffnessTable& table, double constant_k,
                     std::shared_ptr<const MeshTables> given) {
  MeshTeeth teeth;
  if (given && !c.faults.empty() && constant_k == 0.0) {
    teeth.tables = std::move(given);
  } else if (!c.faults.empty() && constant_k == 0.0) {
    teeth.tables = std::make_shared<const MeshTables>(
        c.gears, c.model.stiffness, c.faults,
        std::shared_ptr<const StiffnessTable>(&table, [](const StiffnessTable*) {}));
  }
  if (!is_unmodified(c.modifications)) {
    teeth.gaps = std::make_shared<const ToothGaps>(c.gears, c.modifications);
    teeth.kinks_m = teeth.gaps->kinks_m();
  }
  return teeth;
}

}  // namespace gearimpact
