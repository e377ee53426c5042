#include "gearimpact/stiffness/time_varying_stiffness.hpp"

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

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

// The smallest value of sign * k over the piece: the best of a grid that
// includes both ends, polished by Brent's method between its neighbours.
Extreme piece_minimum(const Path& pair, const Piece& piece, double sign) {
  constexpr int grid = 64;
  const double step = (piece.to - piece.from) / grid;
  const auto f = [&](double fraction) { return sign * piece_stiffness(pair, piece, fraction); };
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
    const Extreme low = piece_minimum(pair, piece, 1.0);
    if (low.value < result.min_n_per_m) {
      result.min_n_per_m = low.value;
      result.min_at_fraction = low.at;
    }
    const Extreme high = piece_minimum(pair, piece, -1.0);
    if (-high.value > result.max_n_per_m) {
      result.max_n_per_m = -high.value;
      result.max_at_fraction = high.at;
    }
    result.mean_n_per_m +=
        integrate_gsl_qag([&](double f) { return piece_stiffness(pair, piece, f); }, piece.from,
                          piece.to, outer)
            .value;
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
