#include "gearimpact/stiffness/time_varying_stiffness.hpp"

#include <algorithm>
#include <array>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/numerics/quadrature.hpp"

namespace gearimpact {

namespace {

void require_fraction(double fraction) {
  if (!(fraction >= 0.0 && fraction < 1.0)) {
    throw InputError("mesh period fraction", fraction, "[0, 1)");
  }
}

// The path of contact and the stiffness of one pair along it, whichever
// model computes it.
struct Path {
  double start_m;  // s_SAP
  double end_m;    // s_EAP
  double base_pitch_m;
  double contact_ratio;
  int teeth1;
  std::function<double(double)> pair_stiffness_n_per_m;  // of s
};

Path path_of(const RackGearPairGeometry& pair, const StiffnessModel& model) {
  return {pair.start_of_active_profile_m,
          pair.end_of_active_profile_m,
          pair.base_pitch_m,
          pair.contact_ratio,
          pair.gear1.teeth,
          [&pair, &model](double s) { return pair_stiffness(pair, model, s).stiffness_n_per_m; }};
}

// A stretch of the period with a constant number of pairs: pair k (k = 0 ..
// pairs - 1) sits at s_SAP + (f + k) p_b for every f in [from, to].
struct Piece {
  double from;
  double to;
  int pairs;
};

std::vector<Piece> pieces_of_period(const Path& pair) {
  const double ratio = pair.contact_ratio;
  const int whole = static_cast<int>(std::floor(ratio));
  const double leave = ratio - whole;  // f_e, where the leading pair reaches s_EAP
  if (leave == 0.0) return {{0.0, 1.0, whole}};
  return {{0.0, leave, whole + 1}, {leave, 1.0, whole}};
}

// The stiffness of a piece's pairs at f, continued to the piece's ends (an
// end of a piece puts its leading pair at s_EAP or its trailing pair at
// s_SAP, up to rounding, which the clamp absorbs).
double piece_stiffness(const Path& pair, const Piece& piece, double fraction) {
  double sum = 0.0;
  for (int k = 0; k < piece.pairs; ++k) {
    const double s =
        std::clamp(pair.start_m + (fraction + k) * pair.base_pitch_m, pair.start_m, pair.end_m);
    sum += pair.pair_stiffness_n_per_m(s);
  }
  return sum;
}

struct Extreme {
  double value;
  double at;
};

// The smallest value of sign * stiffness(f) over the piece: the best of a grid that
// includes both ends, polished by Brent's method between its neighbours.
template <typename Stiffness>
Extreme piece_minimum(const Piece& piece, double sign, const Stiffness& stiffness) {
  constexpr int grid = 64;
  const double step = (piece.to - piece.from) / grid;
  const auto f = [&](double fraction) { return sign * stiffness(fraction); };
  Extreme best{f(piece.from), piece.from};
  int best_index = 0;
  for (int i = 1; i <= grid; ++i) {
    const double at = i == grid ? piece.to : piece.from + i * step;
    const double value = f(at);
    if (value < best.value) {
      best = {value, at};
      best_index = i;
    }
  }
  if (best_index > 0 && best_index < grid) {
    // Half the digits of a double is all a minimum's position can carry; the
    // value there is then exact to rounding.
    constexpr int bits = std::numeric_limits<double>::digits / 2;
    const auto polished = boost::math::tools::brent_find_minima(
        f, piece.from + (best_index - 1) * step, piece.from + (best_index + 1) * step, bits);
    if (polished.second < best.value) best = {polished.second, polished.first};
  }
  return best;
}

std::vector<double> path_positions(const Path& pair, double fraction) {
  require_fraction(fraction);
  std::vector<double> positions;
  for (int k = 0;; ++k) {
    const double s = pair.start_m + (fraction + k) * pair.base_pitch_m;
    if (s > pair.end_m) break;
    positions.push_back(s);
  }
  return positions;
}

TimeVaryingMeshStiffness time_varying(const Path& pair, double relative_tolerance,
                                      std::size_t sample_count) {
  TimeVaryingMeshStiffness result{};
  result.samples.reserve(sample_count);
  for (std::size_t i = 0; i < sample_count; ++i) {
    const double fraction = static_cast<double>(i) / static_cast<double>(sample_count);
    const std::vector<double> positions = path_positions(pair, fraction);
    double k = 0.0;
    for (double s : positions) k += pair.pair_stiffness_n_per_m(s);
    result.samples.push_back(
        {fraction, fraction * 2.0 * pi / pair.teeth1, static_cast<int>(positions.size()), k});
  }

  // The inner compliances carry the model's tolerance; the outer quadrature
  // asks a hundred times less so that their rounding cannot stall it.
  const QuadratureTolerance outer{std::max(1e-10, 100.0 * relative_tolerance), 0.0};
  result.min_n_per_m = std::numeric_limits<double>::infinity();
  result.max_n_per_m = -std::numeric_limits<double>::infinity();
  result.mean_n_per_m = 0.0;
  for (const Piece& piece : pieces_of_period(pair)) {
    const auto stiffness = [&](double f) { return piece_stiffness(pair, piece, f); };
    const Extreme low = piece_minimum(piece, 1.0, stiffness);
    if (low.value < result.min_n_per_m) {
      result.min_n_per_m = low.value;
      result.min_at_fraction = low.at;
    }
    const Extreme high = piece_minimum(piece, -1.0, stiffness);
    if (-high.value > result.max_n_per_m) {
      result.max_n_per_m = -high.value;
      result.max_at_fraction = high.at;
    }
    result.mean_n_per_m += integrate_gsl_qag(stiffness, piece.from, piece.to, outer).value;
  }
  return result;
}

void require_samples(std::size_t sample_count) {
  if (sample_count < 2) {
    throw InputError("samples", std::to_string(sample_count), "an integer >= 2");
  }
}

}  // namespace

std::vector<double> contact_positions(const RackGearPairGeometry& pair, double fraction) {
  const StiffnessModel unused;
  return path_positions(path_of(pair, unused), fraction);
}

double mesh_stiffness_at(const RackGearPairGeometry& pair, const StiffnessModel& model,
                         double fraction) {
  double sum = 0.0;
  for (double s : contact_positions(pair, fraction)) {
    sum += pair_stiffness(pair, model, s).stiffness_n_per_m;
  }
  return sum;
}

TimeVaryingMeshStiffness time_varying_mesh_stiffness(const RackGearPairGeometry& pair,
                                                     const StiffnessModel& model,
                                                     std::size_t sample_count) {
  require_samples(sample_count);
  validate(model, pair);
  TimeVaryingMeshStiffness result =
      time_varying(path_of(pair, model), model.relative_tolerance, sample_count);
  result.foundation_extrapolations = foundation_extrapolations(pair, model);
  return result;
}

TimeVaryingMeshStiffness time_varying_mesh_stiffness(const GearPair& pair,
                                                     const StiffnessModel& model,
                                                     std::size_t sample_count) {
  require_samples(sample_count);
  validate_terms(model);
  const ContactSegment segment = contact_segment(pair);
  const Path path{segment.start_m,
                  segment.end_m,
                  base_pitch(pair),
                  contact_ratio(pair),
                  pair.teeth1,
                  [&pair, &model](double x1_m) {
                    return mesh_stiffness(pair, x1_m, model).ke; }};
  TimeVaryingMeshStiffness result = time_varying(path, model.relative_tolerance, sample_count);
  result.foundation_extrapolations = foundation_extrapolations(pair, model);
  return result;
}

namespace {

// What one smooth piece of one mesh period gives for one set of pairs.
struct PieceFigures {
  Extreme low;
  Extreme high;  // of -k, as piece_minimum returns it
  double integral;
};

}  // namespace

TruePeriodMeshStiffness true_period_mesh_stiffness(const GearPair& pair,
                                                   const StiffnessModel& model,
                                                   const std::vector<ToothFault>& faults,
                                                   std::size_t samples_per_mesh_period) {
  require_samples(samples_per_mesh_period);
  validate_terms(model);
  check_tooth_faults(pair, model, faults);
  std::vector<int> pinion_class;
  std::vector<int> wheel_class;
  const std::vector<ToothState> pinion =
      tooth_classes(faults, Gear::one, pair.teeth1, pinion_class);
  const std::vector<ToothState> wheel = tooth_classes(faults, Gear::two, pair.teeth2, wheel_class);
  const DistinctTeeth distinct{pinion.size() > 1, wheel.size() > 1};
  TruePeriodMeshStiffness result;
  result.mesh_periods = true_period_mesh_periods(pair, distinct);
  result.period_kind = distinct.pinion && distinct.wheel ? "hunting"
                       : distinct.pinion                 ? "pinion-revolution"
                       : distinct.wheel                  ? "wheel-revolution"
                                                         : "mesh";
  const std::size_t n = samples_per_mesh_period;
  const std::size_t periods = static_cast<std::size_t>(result.mesh_periods);
  if (n > kMostTruePeriodSamples / periods) {
    throw InputError("samples", std::to_string(n),
                     "at most " + std::to_string(kMostTruePeriodSamples / periods) +
                         " per mesh period: the true period holds " + std::to_string(periods) +
                         " mesh periods (" + result.period_kind + "), and at most " +
                         std::to_string(kMostTruePeriodSamples) + " samples are computed");
  }
  const MeshLayout layout(pair, CoastPhase::half_base_pitch);
  result.simulation_theta1_offset_rad =
      (layout.start_m() - layout.reference_m(Region::n1, 0.0)) / base_radius(pair, Gear::one);

  const ContactSegment segment = contact_segment(pair);
  const Path path{segment.start_m,
                  segment.end_m,
                  base_pitch(pair),
                  contact_ratio(pair),
                  pair.teeth1,
                  [&pair, &model](double x1_m) { return mesh_stiffness(pair, x1_m, model).ke; }};
  // The pair that entered e-th (e = 0: pinion tooth 0 against wheel tooth 0): its classes.
  struct Classes {
    int pinion;
    int wheel;
  };
  const auto classes_of = [&](long long entered) {
    const TeethInContact t = teeth_of_pair(pair, Region::n1, static_cast<int>(-entered));
    return Classes{pinion_class[static_cast<std::size_t>(t.pinion_tooth)],
                   wheel_class[static_cast<std::size_t>(t.wheel_tooth)]};
  };
  // Ke of a pair of these classes at x: the healthy pair as time_varying_mesh_stiffness reads
  // it, a faulted one with its states, 0 with a missing tooth.
  const auto pair_ke = [&](Classes c, double x1_m) {
    if (c.pinion == 0 && c.wheel == 0) return path.pair_stiffness_n_per_m(x1_m);
    const ToothState& s1 = pinion[static_cast<std::size_t>(c.pinion)];
    const ToothState& s2 = wheel[static_cast<std::size_t>(c.wheel)];
    if (s1.kind == ToothKind::missing || s2.kind == ToothKind::missing) return 0.0;
    return mesh_stiffness(pair, x1_m, model, s1, s2).ke;
  };

  // Each mesh period's samples sit where those of one mesh period do: each pair's Ke is
  // computed once per (classes, sample, place in the segment).
  std::map<std::array<long long, 4>, double> known;
  const auto cached_ke = [&](Classes c, std::size_t r, int k, double x1_m) {
    const std::array<long long, 4> key{c.pinion, c.wheel, static_cast<long long>(r), k};
    const auto found = known.find(key);
    if (found != known.end()) return found->second;
    const double value = pair_ke(c, x1_m);
    known.emplace(key, value);
    return value;
  };
  const std::size_t count = n * periods;
  result.samples.reserve(count);
  for (std::size_t m = 0; m < periods; ++m) {
    for (std::size_t r = 0; r < n; ++r) {
      TruePeriodSample sample{};
      const std::size_t i = m * n + r;
      sample.fraction = static_cast<double>(i) / static_cast<double>(count);
      sample.theta1_rad = sample.fraction * static_cast<double>(periods) * 2.0 * pi / pair.teeth1;
      const double fraction = static_cast<double>(r) / static_cast<double>(n);
      const std::vector<double> positions = path_positions(path, fraction);
      for (std::size_t k = 0; k < positions.size(); ++k) {
        const long long entered = static_cast<long long>(m) - static_cast<long long>(k);
        const Classes c = classes_of(entered);
        const double ke = cached_ke(c, r, static_cast<int>(k), positions[k]);
        sample.teeth.push_back(teeth_of_pair(pair, Region::n1, static_cast<int>(-entered)));
        sample.pair_ke_n_per_m.push_back(ke);
        sample.ke_n_per_m += ke;
        sample.healthy_ke_n_per_m += cached_ke({0, 0}, r, static_cast<int>(k), positions[k]);
      }
      result.samples.push_back(std::move(sample));
    }
  }

  // The extremes and the mean, piece by piece of each mesh period; pieces whose pairs have the
  // same classes give the same figures, computed once.
  const QuadratureTolerance outer{std::max(1e-10, 100.0 * model.relative_tolerance), 0.0};
  const std::vector<Piece> pieces = pieces_of_period(path);
  std::map<std::vector<int>, PieceFigures> figures_of;
  const auto figures = [&](std::size_t piece_index, const std::vector<Classes>& pairs) {
    std::vector<int> key{static_cast<int>(piece_index)};
    for (const Classes& c : pairs) {
      key.push_back(c.pinion);
      key.push_back(c.wheel);
    }
    const auto found = figures_of.find(key);
    if (found != figures_of.end()) return found->second;
    const Piece& piece = pieces[piece_index];
    const auto stiffness = [&](double f) {
      double sum = 0.0;
      for (int k = 0; k < piece.pairs; ++k) {
        const double s =
            std::clamp(path.start_m + (f + k) * path.base_pitch_m, path.start_m, path.end_m);
        sum += pair_ke(pairs[static_cast<std::size_t>(k)], s);
      }
      return sum;
    };
    const PieceFigures value{piece_minimum(piece, 1.0, stiffness),
                             piece_minimum(piece, -1.0, stiffness),
                             integrate_gsl_qag(stiffness, piece.from, piece.to, outer).value};
    figures_of.emplace(key, value);
    return value;
  };
  result.min_n_per_m = std::numeric_limits<double>::infinity();
  result.max_n_per_m = -std::numeric_limits<double>::infinity();
  double integral = 0.0;
  double healthy_integral = 0.0;
  const double whole = static_cast<double>(periods);
  for (std::size_t m = 0; m < periods; ++m) {
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      std::vector<Classes> pairs;
      for (int k = 0; k < pieces[p].pairs; ++k) {
        pairs.push_back(classes_of(static_cast<long long>(m) - k));
      }
      const PieceFigures f = figures(p, pairs);
      if (f.low.value < result.min_n_per_m) {
        result.min_n_per_m = f.low.value;
        result.min_at_fraction = (static_cast<double>(m) + f.low.at) / whole;
      }
      if (-f.high.value > result.max_n_per_m) {
        result.max_n_per_m = -f.high.value;
        result.max_at_fraction = (static_cast<double>(m) + f.high.at) / whole;
      }
      integral += f.integral;
      healthy_integral += figures(p, std::vector<Classes>(pairs.size(), Classes{0, 0})).integral;
    }
  }
  result.mean_n_per_m = integral / whole;
  result.healthy_mean_n_per_m = healthy_integral / whole;
  result.foundation_extrapolations = foundation_extrapolations(pair, model);
  return result;
}

std::vector<LoadShareSample> load_sharing(const GearPair& pair, const StiffnessModel& model,
                                          int points) {
  if (points < 2) throw InputError("points", std::to_string(points), "an integer >= 2");
  validate_terms(model);
  const ContactSegment segment = contact_segment(pair);
  const double t0 = base_pitch(pair);
  std::vector<LoadShareSample> shares;
  for (double x : contact_positions(pair, points)) {
    const double own = mesh_stiffness(pair, x, model).ke;
    double sum = own;
    int pairs = 1;
    // The other pairs, a whole number of base pitches either side, while on the segment.
    for (int side : {-1, 1}) {
      for (int k = 1;; ++k) {
        const double other = x + side * k * t0;
        if (other < segment.start_m || other > segment.end_m) break;
        sum += mesh_stiffness(pair, other, model).ke;
        ++pairs;
      }
    }
    shares.push_back({x, pairs, own / sum});
  }
  return shares;
}

double path_mean_mesh_stiffness(const RackGearPairGeometry& pair, const StiffnessModel& model) {
  validate(model, pair);
  const QuadratureTolerance outer{std::max(1e-10, 100.0 * model.relative_tolerance), 0.0};
  const double integral =
      integrate_boost_gauss_kronrod(
          [&](double s) { return pair_stiffness(pair, model, s).stiffness_n_per_m; },
          pair.start_of_active_profile_m, pair.end_of_active_profile_m, outer)
          .value;
  return integral / pair.base_pitch_m;
}

}  // namespace gearimpact
