#include "gearimpact/stiffness/static_transmission_error.hpp"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// More angles than this over the true period would take minutes and
// gigabytes of output; a hunting period of many mesh periods needs fewer
// points per mesh period.
constexpr long long kMostAngles = 10'000'000;
constexpr int kMostPointsPerMeshPeriod = 100000;

void check_springs(const std::vector<PairSpring>& springs, double force_n) {
  if (springs.empty()) throw InputError("springs", "none", "at least one pair in contact");
  if (!(force_n > 0.0) || !std::isfinite(force_n)) {
    throw InputError("force", force_n, "a finite force > 0 N");
  }
  for (const PairSpring& s : springs) {
    if (!(s.stiffness_n_per_m > 0.0) || !std::isfinite(s.stiffness_n_per_m)) {
      throw InputError("stiffness", s.stiffness_n_per_m, "a finite pair stiffness > 0 N/m");
    }
    if (!std::isfinite(s.gap_m)) throw InputError("gap", s.gap_m, "a finite gap, m");
  }
}

// The true period of the modifications' and the faults' distinct teeth.
long long true_period(const GearPair& pair, const Modifications& m, DistinctTeeth faulted) {
  DistinctTeeth distinct = distinct_teeth(m);
  distinct.pinion = distinct.pinion || faulted.pinion;
  distinct.wheel = distinct.wheel || faulted.wheel;
  return true_period_mesh_periods(pair, distinct);
}

}  // namespace

double solve_deflection(const std::vector<PairSpring>& springs, double force_n) {
  check_springs(springs, force_n);
  std::vector<PairSpring> sorted = springs;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const PairSpring& a, const PairSpring& b) { return a.gap_m < b.gap_m; });
  // delta_m is the mean of delta_{m-1} and e_m weighted by the stiffnesses,
  // so once delta passes a gap it stays above it: the first m whose delta_m
  // does not reach the next gap is the answer.
  double stiffness = 0.0;
  double moment = 0.0;  // sum k_i e_i
  double delta = 0.0;
  for (std::size_t m = 0; m < sorted.size(); ++m) {
    stiffness += sorted[m].stiffness_n_per_m;
    moment += sorted[m].stiffness_n_per_m * sorted[m].gap_m;
    delta = (force_n + moment) / stiffness;
    if (m + 1 == sorted.size() || delta <= sorted[m + 1].gap_m) break;
  }
  return delta;
}

double solve_deflection_bracketed(const std::vector<PairSpring>& springs, double force_n,
                                  double relative_tolerance) {
  check_springs(springs, force_n);
  const auto residual = [&](double delta) {
    double sum = 0.0;
    for (const PairSpring& s : springs) {
      sum += s.stiffness_n_per_m * std::max(0.0, delta - s.gap_m);
    }
    return sum - force_n;
  };
  const auto least =
      std::min_element(springs.begin(), springs.end(),
                       [](const PairSpring& a, const PairSpring& b) { return a.gap_m < b.gap_m; });
  const double low = least->gap_m;
  // Twice the deflection at which the pair of the least gap alone carries F,
  // so that rounding cannot leave the residual below 0 there.
  const double high = low + 2.0 * force_n / least->stiffness_n_per_m;
  const double f_high = residual(high);
  if (f_high == 0.0) return high;
  const auto close_enough = [relative_tolerance](double a, double b) {
    return std::fabs(b - a) <= relative_tolerance * std::max(std::fabs(a), std::fabs(b));
  };
  std::uintmax_t iterations = 200;
  const std::pair<double, double> bracket = boost::math::tools::toms748_solve(
      residual, low, high, -force_n, f_high, close_enough, iterations);
  return 0.5 * (bracket.first + bracket.second);
}

void validate_static_transmission_error(const GearPair& pair, const Modifications& m,
                                        double torque1_n_m,
                                        StaticTransmissionErrorOptions options) {
  if (!(torque1_n_m > 0.0) || !std::isfinite(torque1_n_m)) {
    throw InputError("torque", format_number(torque1_n_m) + " N*m",
                     "a finite pinion torque > 0 N*m: it loads the drive flanks (line N1)");
  }
  if (options.points_per_mesh_period < 2 ||
      options.points_per_mesh_period > kMostPointsPerMeshPeriod) {
    throw InputError(
        "points", std::to_string(options.points_per_mesh_period),
        "an integer in [2, " + std::to_string(kMostPointsPerMeshPeriod) + "] per mesh period");
  }
  if (options.mesh_periods < 0) {
    throw InputError("mesh_periods", std::to_string(options.mesh_periods),
                     "0 (the true period of the teeth) or a number of mesh periods >= 1");
  }
  const long long periods =
      options.mesh_periods > 0 ? options.mesh_periods : true_period(pair, m, options.faulted);
  if (periods > kMostAngles / options.points_per_mesh_period) {
    throw InputError("points", std::to_string(options.points_per_mesh_period),
                     "at most " + std::to_string(kMostAngles / periods) +
                         " per mesh period: the true period of the teeth is " +
                         std::to_string(periods) + " mesh periods and at most " +
                         std::to_string(kMostAngles) + " angles are computed");
  }
}

StaticTransmissionError static_transmission_error(const GearPair& pair, const Modifications& m,
                                                  double torque1_n_m,
                                                  const PairStiffnessFunction& stiffness,
                                                  StaticTransmissionErrorOptions options) {
  validate_static_transmission_error(pair, m, torque1_n_m, options);
  StaticTransmissionError result;
  result.torque1_n_m = torque1_n_m;
  result.force_n = torque1_n_m / base_radius(pair, Gear::one);
  result.mesh_periods =
      options.mesh_periods > 0 ? options.mesh_periods : true_period(pair, m, options.faulted);
  const long long angles = result.mesh_periods * options.points_per_mesh_period;
  const double mesh_period_rad = 2.0 * pi / teeth(pair, Gear::one);
  result.period_rad = static_cast<double>(result.mesh_periods) * mesh_period_rad;
  const MeshLayout layout(pair, CoastPhase::half_base_pitch);
  const ToothGaps gaps(pair, m);
  result.points.reserve(static_cast<std::size_t>(angles));
  std::vector<PairSpring> springs;
  double sum = 0.0;
  double least = std::numeric_limits<double>::infinity();
  double most = -least;
  for (long long i = 0; i < angles; ++i) {
    StePoint p;
    p.theta1_rad = result.period_rad * static_cast<double>(i) / static_cast<double>(angles);
    const double reference = layout.reference_m(Region::n1, p.theta1_rad);
    const LoadedRange range = layout.loaded(reference);
    p.pairs = static_cast<std::size_t>(range.count);
    springs.clear();
    p.kte_m = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < p.pairs; ++j) {
      const int k = range.k_first + static_cast<int>(j);
      p.k[j] = k;
      p.x_m[j] = layout.position_m(reference, k);
      p.gap_m[j] = gaps.gap_m(Region::n1, k, p.x_m[j]);
      p.stiffness_n_per_m[j] = stiffness(k, p.x_m[j]);
      p.teeth[j] = teeth_of_pair(pair, Region::n1, k);
      p.kte_m = std::min(p.kte_m, p.gap_m[j]);
      // A pair that carries nothing (a missing tooth) takes no part in the balance.
      if (p.stiffness_n_per_m[j] > 0.0) springs.push_back({p.stiffness_n_per_m[j], p.gap_m[j]});
    }
    if (springs.empty()) {
      p.carried = false;
      ++result.uncarried_points;
      result.points.push_back(p);
      continue;
    }
    p.ste_m = solve_deflection(springs, result.force_n);
    for (std::size_t j = 0; j < p.pairs; ++j) {
      const double penetration = p.ste_m - p.gap_m[j];
      if (penetration > 0.0) {
        p.share[j] = p.stiffness_n_per_m[j] * penetration / result.force_n;
        p.effective_stiffness_n_per_m += p.stiffness_n_per_m[j];
      }
    }
    sum += p.ste_m;
    least = std::min(least, p.ste_m);
    most = std::max(most, p.ste_m);
    result.points.push_back(p);
  }
  const long long carried = angles - static_cast<long long>(result.uncarried_points);
  if (carried == 0) {
    throw InputError("[[faults]]", "missing teeth",
                     "faults that leave a pair of teeth in contact at some angle: at every angle "
                     "every pair in the contact segment has a missing tooth");
  }
  result.ste_mean_m = sum / static_cast<double>(carried);
  result.ste_peak_to_peak_m = most - least;
  return result;
}

StaticTransmissionError static_transmission_error(const GearPair& pair, const Modifications& m,
                                                  double torque1_n_m, const StiffnessTable& table,
                                                  StaticTransmissionErrorOptions options) {
  return static_transmission_error(
      pair, m, torque1_n_m, [&table](int, double x_m) { return table.stiffness(x_m); }, options);
}

StaticTransmissionError static_transmission_error(const GearPair& pair, const Modifications& m,
                                                  double torque1_n_m, const MeshTables& tables,
                                                  StaticTransmissionErrorOptions options) {
  options.faulted = tables.distinct();
  return static_transmission_error(
      pair, m, torque1_n_m,
      [&tables](int k, double x_m) {
        const StiffnessTable* table = tables.table(Region::n1, k);
        return table ? table->stiffness(x_m) : 0.0;
      },
      options);
}

}  // namespace gearimpact
