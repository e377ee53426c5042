#include "gearimpact/stiffness/helical_faults.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "face_load_book.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/numerics/quadrature.hpp"
#include "gearimpact/stiffness/helical.hpp"

namespace gearimpact {

namespace {

// The pairs k whose mid-face contact X_k = reference + k p may lie on
// [start, end].
struct PairSpan {
  int first;
  int last;
};
PairSpan pairs_on(double reference_m, double pitch_m, double start_m, double end_m) {
  return {static_cast<int>(std::floor((start_m - reference_m) / pitch_m)) - 1,
          static_cast<int>(std::ceil((end_m - reference_m) / pitch_m)) + 1};
}

// Ke of pair k at X from its teeth's table, 0 for a missing tooth.
double pair_ke(const MeshTables& tables, int k, double x_m) {
  const StiffnessTable* table = tables.table(Region::n1, k);
  return table ? table->stiffness(x_m) : 0.0;
}

// The integral of a table's Ke over its domain, piece by piece between its
// breaks (smooth on each), to 1e-12 relative as the run's mean stiffness.
double ke_integral(const StiffnessTable& table) {
  QuadratureTolerance tolerance;
  tolerance.relative = 1e-12;
  std::vector<double> ends{table.domain_start_m()};
  for (double x : table.breaks_m()) {
    if (x > table.domain_start_m() && x < table.domain_end_m()) ends.push_back(x);
  }
  ends.push_back(table.domain_end_m());
  double sum = 0.0;
  for (std::size_t i = 1; i < ends.size(); ++i) {
    sum += integrate_gsl_qag([&](double x) { return table.stiffness(x); }, ends[i - 1], ends[i],
                             tolerance)
               .value;
  }
  return sum;
}

std::string period_kind(DistinctTeeth distinct) {
  return distinct.pinion && distinct.wheel ? "hunting"
         : distinct.pinion                 ? "pinion-revolution"
         : distinct.wheel                  ? "wheel-revolution"
                                           : "mesh";
}

}  // namespace

MeshTables helical_mesh_tables(const GearPair& pair, const StiffnessModel& model,
                               const std::vector<ToothFault>& faults) {
  if (!(pair.helix_angle_rad > 0.0)) {
    throw InputError("gears.helix_angle", format_number(pair.helix_angle_rad * 180.0 / pi) + " deg",
                     "(0, 45] deg for a helical pair's tables: a spur pair's are "
                     "MeshTables(pair, model, faults)");
  }
  const GearPair swept = swept_transverse_pair(pair);
  // Every refusal before the pair table's quadrature.
  check_tooth_faults(swept, model, faults);
  return MeshTables(swept, model, faults,
                    std::make_shared<const StiffnessTable>(helical_pair_table(pair, model)));
}

TruePeriodMeshStiffness helical_true_period_mesh_stiffness(const GearPair& pair,
                                                           const StiffnessModel& model,
                                                           const std::vector<ToothFault>& faults,
                                                           std::size_t samples_per_mesh_period) {
  if (samples_per_mesh_period < 2) {
    throw InputError("samples", std::to_string(samples_per_mesh_period),
                     "an integer >= 2 per mesh period");
  }
  const GearPair swept = swept_transverse_pair(pair);
  {
    // The bound on the samples before any table is built.
    check_tooth_faults(swept, model, faults);
    std::vector<int> classes;
    const DistinctTeeth distinct{tooth_classes(faults, Gear::one, pair.teeth1, classes).size() > 1,
                                 tooth_classes(faults, Gear::two, pair.teeth2, classes).size() > 1};
    const auto periods = static_cast<std::size_t>(true_period_mesh_periods(swept, distinct));
    if (samples_per_mesh_period > kMostTruePeriodSamples / periods) {
      throw InputError("samples", std::to_string(samples_per_mesh_period),
                       "at most " + std::to_string(kMostTruePeriodSamples / periods) +
                           " per mesh period: the true period holds " + std::to_string(periods) +
                           " mesh periods (" + period_kind(distinct) + "), and at most " +
                           std::to_string(kMostTruePeriodSamples) + " samples are computed");
    }
  }
  const MeshTables tables = helical_mesh_tables(pair, model, faults);
  TruePeriodMeshStiffness result;
  result.mesh_periods = tables.true_period_mesh_periods();
  result.period_kind = period_kind(tables.distinct());
  result.simulation_theta1_offset_rad = 0.0;
  const MeshLayout layout(swept, CoastPhase::half_base_pitch);
  const StiffnessTable& healthy = tables.healthy();
  const double start = healthy.domain_start_m();
  const double end = healthy.domain_end_m();
  const double pitch = layout.base_pitch_m();
  const std::size_t n = samples_per_mesh_period;
  const auto periods = static_cast<std::size_t>(result.mesh_periods);
  const std::size_t count = n * periods;
  const double period_rad = static_cast<double>(periods) * 2.0 * pi / swept.teeth1;
  result.samples.reserve(count);
  double least = std::numeric_limits<double>::infinity();
  double most = -least;
  for (std::size_t i = 0; i < count; ++i) {
    TruePeriodSample sample{};
    sample.fraction = static_cast<double>(i) / static_cast<double>(count);
    sample.theta1_rad = sample.fraction * period_rad;
    const double reference = layout.reference_m(Region::n1, sample.theta1_rad);
    const PairSpan span = pairs_on(reference, pitch, start, end);
    for (int k = span.first; k <= span.last; ++k) {
      const double x = layout.position_m(reference, k);
      if (!(x >= start && x <= end)) continue;
      const double ke = pair_ke(tables, k, x);
      sample.teeth.push_back(teeth_of_pair(swept, Region::n1, k));
      sample.pair_ke_n_per_m.push_back(ke);
      sample.ke_n_per_m += ke;
      sample.healthy_ke_n_per_m += healthy.stiffness(x);
    }
    if (sample.ke_n_per_m < least) {
      least = sample.ke_n_per_m;
      result.min_at_fraction = sample.fraction;
    }
    if (sample.ke_n_per_m > most) {
      most = sample.ke_n_per_m;
      result.max_at_fraction = sample.fraction;
    }
    result.samples.push_back(std::move(sample));
  }
  result.min_n_per_m = least;
  result.max_n_per_m = most;
  // Every pair of the true period crosses the widened segment once: the mean
  // is the sum of its tables' integrals over N p_bt, each table integrated once.
  double sum = 0.0;
  for (const auto& [table, repeats] : tables.table_repeats(result.mesh_periods))
    sum += static_cast<double>(repeats) * ke_integral(*table);
  const double healthy_integral = ke_integral(healthy);
  result.mean_n_per_m = sum / (static_cast<double>(result.mesh_periods) * pitch);
  result.healthy_mean_n_per_m = healthy_integral / pitch;
  return result;
}

HelicalStaticTransmissionError helical_static_transmission_error(
    const GearPair& pair, double torque1_n_m, const StiffnessModel& model, const MeshTables& tables,
    StaticTransmissionErrorOptions options) {
  if (options.mesh_periods == 0) options.mesh_periods = tables.true_period_mesh_periods();
  validate_helical_static_transmission_error(pair, Modifications{}, torque1_n_m, model.face_slices,
                                             options);
  const GearPair swept = swept_transverse_pair(pair);
  const StiffnessTable* section = tables.healthy_section();
  if (section == nullptr) {
    throw InputError("tables", "a spur pair's",
                     "the tables of the helical pair (helical_mesh_tables)");
  }
  const MeshLayout layout(swept, CoastPhase::half_base_pitch);
  const StiffnessTable& healthy = tables.healthy();
  const double start = healthy.domain_start_m();
  const double end = healthy.domain_end_m();
  const double path_start = section->domain_start_m();
  const double path_end = section->domain_end_m();
  const double pitch = layout.base_pitch_m();
  const double b = pair.face_width_m;
  const int n = model.face_slices;
  const double db = b / n;
  const double tan_bb = swept.face_advance_m / b;
  const int sigma = hand_sign(pair.helix_hand);

  HelicalStaticTransmissionError result;
  result.torque1_n_m = torque1_n_m;
  result.force_n = torque1_n_m / base_radius(swept, Gear::one);
  result.face_slices = n;
  result.face_width_m = b;
  result.face_route = true;
  result.mesh_periods = options.mesh_periods;
  result.period_rad = static_cast<double>(result.mesh_periods) * 2.0 * pi / swept.teeth1;
  result.slice_y_m.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) result.slice_y_m[static_cast<std::size_t>(j)] = (j + 0.5) * db;
  const long long angles = result.mesh_periods * options.points_per_mesh_period;
  FaceLoadBook book(result, angles);
  for (long long i = 0; i < angles; ++i) {
    HelicalStePoint p;
    p.theta1_rad = result.period_rad * static_cast<double>(i) / static_cast<double>(angles);
    p.load_per_width_n_per_m.assign(static_cast<std::size_t>(n), 0.0);
    const double reference = layout.reference_m(Region::n1, p.theta1_rad);
    const PairSpan span = pairs_on(reference, pitch, start, end);
    for (int k = span.first; k <= span.last; ++k) {
      const double x = layout.position_m(reference, k);
      if (x >= start && x <= end) p.effective_stiffness_n_per_m += pair_ke(tables, k, x);
    }
    if (!(p.effective_stiffness_n_per_m > 0.0)) {
      throw InputError("[[faults]]", "missing teeth",
                       "faults that leave a pair of teeth in contact at every angle: at " +
                           format_number(p.theta1_rad) +
                           " rad every pair on the path of contact has a missing tooth");
    }
    // Every slice at the same deflection: delta = F / K_B, as the healthy route B.
    p.ste_m = result.force_n / p.effective_stiffness_n_per_m;
    p.kte_m = 0.0;
    for (int k = span.first; k <= span.last; ++k) {
      const double xk = layout.position_m(reference, k);
      if (!(xk >= start && xk <= end) || tables.table(Region::n1, k) == nullptr) continue;
      const std::vector<FaceBand>& bands = tables.face_bands(Region::n1, k);
      for (int j = 0; j < n; ++j) {
        const double y = result.slice_y_m[static_cast<std::size_t>(j)];
        const double x = xk + sigma * (y - 0.5 * b) * tan_bb;
        if (!(x >= path_start && x <= path_end)) continue;
        ++p.elements;
        ++p.loaded_elements;
        p.load_per_width_n_per_m[static_cast<std::size_t>(j)] +=
            helical_slice_stiffness(swept, model.helical_hertz, *section, bands, j * db,
                                    j + 1 == n ? b : (j + 1) * db, x)
                .kappa_n_per_m2 *
            p.ste_m;
      }
    }
    book.add(std::move(p));
  }
  book.finish();
  return result;
}

}  // namespace gearimpact
