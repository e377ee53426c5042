#include "gearimpact/stiffness/static_transmission_error.hpp"

#include <algorithm>
#include <boost/math/tools/toms748_solve.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// More angles than this over the true period would take minutes and
// gigabytes; a hunting period of many mesh periods needs fewer points per mesh
// period. What an angle costs, measured on `gearimpact ste
// examples/tip_relief_20_80.toml --points 20000` (4e5 angles: 195 MB of CSV,
// 478 MB resident, 17 s): the modified and the unmodified pair's points and
// their four CSV texts, about 1.2 kB of memory and 490 bytes written. 1e6
// angles are then about 1.2 GB of memory and 0.5 GB of CSV (8e6 angles, the
// old bound's, took 9.3 GB and 3.5 minutes).
constexpr long long kMostAngles = 1'000'000;
constexpr double kMemoryBytesPerAngle = 1200.0;
constexpr double kCsvBytesPerAngle = 490.0;

// "1.2 GB", "490 MB": a size a message gives.
std::string size_text(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, bytes >= 1e9 ? "%.2g GB" : "%.0f MB",
                bytes >= 1e9 ? bytes * 1e-9 : bytes * 1e-6);
  return text;
}
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

// The balance of the drive pairs with pair 0 at X = `reference` (MeshLayout): every pair in the
// contact segment with its gap and stiffness, the deflection that carries `force_n`, and each
// pair's share; p.carried false where no pair carries anything (missing teeth).
void balance_at(const GearPair& pair, const MeshLayout& layout, const ToothGaps& gaps,
                double reference, const PairStiffnessFunction& stiffness, double force_n,
                std::vector<PairSpring>& springs, StePoint& p) {
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
    return;
  }
  p.ste_m = solve_deflection(springs, force_n);
  for (std::size_t j = 0; j < p.pairs; ++j) {
    const double penetration = p.ste_m - p.gap_m[j];
    if (penetration > 0.0) {
      p.share[j] = p.stiffness_n_per_m[j] * penetration / force_n;
      p.effective_stiffness_n_per_m += p.stiffness_n_per_m[j];
    }
  }
}

// The stiffness of pair k at X from its own table (0 for a missing tooth); at a break of the
// table, from the part below it with `below`, else from the part above (as the table reads).
double pair_stiffness(const MeshTables& tables, int k, double x_m, bool below = false) {
  const StiffnessTable* table = tables.table(Region::n1, k);
  if (!table) return 0.0;
  if (!below) return table->stiffness(x_m);
  const int part = table->part_of(x_m);
  if (part == 0 || x_m != table->part_start_m(part)) return table->stiffness(x_m);
  return table->stiffness_and_derivative_in_part(x_m, part - 1).stiffness_n_per_m;
}

// Options that leave only the torque to check: no angles are sampled over a period.
StaticTransmissionErrorOptions torque_only() {
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 2;
  options.mesh_periods = 1;
  return options;
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

double carried_force(const std::vector<PairSpring>& springs, double delta_m) {
  double sum = 0.0;
  for (const PairSpring& s : springs) sum += s.stiffness_n_per_m * std::max(0.0, delta_m - s.gap_m);
  return sum;
}

double solve_deflection_bracketed(const std::vector<PairSpring>& springs, double force_n,
                                  double relative_tolerance) {
  check_springs(springs, force_n);
  const auto residual = [&](double delta) { return carried_force(springs, delta) - force_n; };
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
  // Gaps across the face belong to a helical pair's slices: a spur pair refuses them by name.
  if (pair.helix_angle_rad == 0.0 && has_lead_gaps(m)) validate_modifications(pair, m);
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
    const double angles =
        static_cast<double>(periods) * static_cast<double>(options.points_per_mesh_period);
    throw InputError(
        "points", std::to_string(options.points_per_mesh_period),
        "at most " + std::to_string(kMostAngles / periods) +
            " per mesh period: the true period of the teeth is " + std::to_string(periods) +
            " mesh periods and at most " + std::to_string(kMostAngles) + " angles (about " +
            size_text(kMostAngles * kMemoryBytesPerAngle) + " of memory, " +
            size_text(kMostAngles * kCsvBytesPerAngle) + " of CSV) are computed; these " +
            std::to_string(static_cast<long long>(angles)) + " would take about " +
            size_text(angles * kMemoryBytesPerAngle) + " and write about " +
            size_text(angles * kCsvBytesPerAngle));
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
    balance_at(pair, layout, gaps, layout.reference_m(Region::n1, p.theta1_rad), stiffness,
               result.force_n, springs, p);
    if (!p.carried) {
      ++result.uncarried_points;
      result.points.push_back(p);
      continue;
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

std::vector<LoadShareSample> loaded_load_sharing(const GearPair& pair, const Modifications& m,
                                                 double torque1_n_m, const MeshTables& tables,
                                                 const std::vector<double>& positions, int k) {
  validate_static_transmission_error(pair, m, torque1_n_m, torque_only());
  const double force = torque1_n_m / base_radius(pair, Gear::one);
  const MeshLayout layout(pair, CoastPhase::half_base_pitch);
  const ToothGaps gaps(pair, m);
  const PairStiffnessFunction stiffness = [&tables](int pair_k, double x_m) {
    return pair_stiffness(tables, pair_k, x_m);
  };
  std::vector<LoadShareSample> shares;
  std::vector<PairSpring> springs;
  for (const double x : positions) {
    if (!(x >= layout.start_m() && x <= layout.end_m())) {
      throw InputError("positions", format_number(x) + " m",
                       "positions in the contact segment [" + format_number(layout.start_m()) +
                           ", " + format_number(layout.end_m()) + "] m");
    }
    // Pair k at X1: X_k = reference + k t0 (MeshLayout). Rounding can leave it a few ulps
    // outside the segment at its ends, where it is in contact: move the reference in.
    double reference = x - k * layout.base_pitch_m();
    while (layout.position_m(reference, k) < layout.start_m()) {
      reference = std::nextafter(reference, INFINITY);
    }
    while (layout.position_m(reference, k) > layout.end_m()) {
      reference = std::nextafter(reference, -INFINITY);
    }
    StePoint p;
    balance_at(pair, layout, gaps, reference, stiffness, force, springs, p);
    double share = 0.0;
    for (std::size_t j = 0; j < p.pairs; ++j) {
      if (p.k[j] == k) share = p.share[j];
    }
    shares.push_back({x, static_cast<int>(p.pairs), share});
  }
  return shares;
}

double quasi_static_peak_force_ratio(const GearPair& pair, const Modifications& m,
                                     double torque1_n_m, const MeshTables& tables) {
  validate_static_transmission_error(pair, m, torque1_n_m, torque_only());
  const double force = torque1_n_m / base_radius(pair, Gear::one);
  const MeshLayout layout(pair, CoastPhase::half_base_pitch);
  const ToothGaps gaps(pair, m);
  const double start = layout.start_m();
  const double end = layout.end_m();
  const double t0 = layout.base_pitch_m();
  // The pairs a whole number of base pitches from pair k at X (X itself included), on the
  // contact segment, the pair at X read from below its break with `below`.
  const auto springs_at = [&](int k, double x, bool below, bool with_k) {
    std::vector<PairSpring> springs;
    for (int side : {-1, 1}) {
      for (int j = 1;; ++j) {
        const double other = x + side * j * t0;
        if (other < start || other > end) break;
        const int k_other = k + side * j;
        const double s = pair_stiffness(tables, k_other, other);
        if (s > 0.0) springs.push_back({s, gaps.gap_m(Region::n1, k_other, other)});
      }
    }
    if (with_k) {
      const double s = pair_stiffness(tables, k, x, below);
      if (s > 0.0) springs.push_back({s, gaps.gap_m(Region::n1, k, x)});
    }
    return springs;
  };
  // The force just after an event over F, from the deflection just before it.
  double ratio = 1.0;
  const auto event = [&](const std::vector<PairSpring>& before,
                         const std::vector<PairSpring>& after) {
    if (before.empty() || after.empty()) return;
    ratio = std::max(ratio, carried_force(after, solve_deflection(before, force)) / force);
  };
  // Every pair of teeth that meets crosses the segment once in the true period: P pairs in turn,
  // k = 0, -1, ..., -(P - 1) (pair k - 1 enters a base pitch after pair k).
  const long long periods = true_period(pair, m, tables.distinct());
  for (long long i = 0; i < periods; ++i) {
    const int k = -static_cast<int>(i);
    // Its entry at X_start: the pairs after it (at X_start + j t0) before, all of them after.
    event(springs_at(k, start, false, false), springs_at(k, start, false, true));
    // Its table's breaks inside the segment: its part below before, its part above after.
    if (const StiffnessTable* table = tables.table(Region::n1, k)) {
      for (const double b : table->breaks_m()) {
        if (b <= start || b >= end) continue;
        event(springs_at(k, b, true, true), springs_at(k, b, false, true));
      }
    }
  }
  return ratio;
}

}  // namespace gearimpact
