#include "gearimpact/stiffness/helical.hpp"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/stiffness/iso6336.hpp"

namespace gearimpact {

namespace {

// 8-point Gauss-Legendre on each piece of the table: kappa_t is smooth there
// (a ratio of degree-7 series), so the rule is exact to rounding for the
// integrals C(X) needs.
using Rule = boost::math::quadrature::gauss<double, 8>;

double base_helix_angle(const GearPair& pair) {
  const double cos_beta = std::cos(pair.helix_angle_rad);
  const double at = std::atan(std::tan(pair.pressure_angle_rad) / cos_beta);
  return std::atan(std::tan(pair.helix_angle_rad) * std::cos(at));
}

}  // namespace

FaceStiffness::FaceStiffness(const GearPair& pair, const StiffnessModel& model, HelicalHertz hertz,
                             StiffnessTableOptions options) {
  const GearPair transverse = transverse_pair(pair);
  const ContactSegment segment = contact_segment(transverse);
  start_ = segment.start_m;
  end_ = segment.end_m;
  face_width_ = pair.face_width_m;
  cos_base_helix_ = std::cos(base_helix_angle(pair));
  hertz_ = hertz;
  table_.emplace(transverse, model, options);
  const int pieces = table_->pieces();
  nodes_m_.resize(static_cast<std::size_t>(pieces) + 1);
  cumulative_at_nodes_.assign(static_cast<std::size_t>(pieces) + 1, 0.0);
  const double step = (end_ - start_) / pieces;
  for (int i = 0; i <= pieces; ++i) {
    nodes_m_[static_cast<std::size_t>(i)] = i == pieces ? end_ : start_ + i * step;
  }
  for (int i = 0; i < pieces; ++i) {
    const auto u = static_cast<std::size_t>(i);
    cumulative_at_nodes_[u + 1] =
        cumulative_at_nodes_[u] +
        Rule::integrate([this](double x) { return kappa(x); }, nodes_m_[u], nodes_m_[u + 1]);
  }
}

FaceStiffness FaceStiffness::uniform(const GearPair& pair, double kappa_n_per_m2) {
  if (!(kappa_n_per_m2 > 0.0) || !std::isfinite(kappa_n_per_m2)) {
    throw InputError("uniform stiffness", format_number(kappa_n_per_m2) + " N/m^2",
                     "a finite value > 0 N/m^2 per unit face width");
  }
  const ContactSegment segment = contact_segment(transverse_pair(pair));
  FaceStiffness face(segment.start_m, segment.end_m);
  face.face_width_ = pair.face_width_m;
  face.uniform_kappa_ = kappa_n_per_m2;
  return face;
}

double FaceStiffness::kappa(double x_m) const {
  if (!table_) {
    if (!(x_m >= start_ && x_m <= end_)) {
      throw InputError(
          "X", format_number(x_m) + " m",
          "the path of contact [" + format_number(start_) + ", " + format_number(end_) + "] m");
    }
    return uniform_kappa_;
  }
  if (hertz_ == HelicalHertz::face_width) return table_->stiffness(x_m) / face_width_;
  // Only Hertz sees the inclined line: 1/kappa_t = b (c_beam + c_hertz / cos(beta_b)),
  // the compliances at width b.
  const Compliances c = table_->compliance(x_m);
  const double hertz = c.of(Term::hertz);
  const double beam = c.total_m_per_n() - hertz;
  return 1.0 / (face_width_ * (beam + hertz / cos_base_helix_));
}

Compliances FaceStiffness::compliance_per_width(double x_m) const {
  Compliances c;
  if (!table_) {
    c.of(Term::hertz) = 1.0 / kappa(x_m);
    return c;
  }
  c = table_->compliance(x_m);
  for (double& term : c.m_per_n) term *= face_width_;
  if (hertz_ == HelicalHertz::projected) c.of(Term::hertz) /= cos_base_helix_;
  return c;
}

double FaceStiffness::cumulative(double x_m) const {
  const double x = std::clamp(x_m, start_, end_);
  if (!table_) return uniform_kappa_ * (x - start_);
  const double step = (end_ - start_) / static_cast<double>(nodes_m_.size() - 1);
  auto i = static_cast<std::size_t>(
      std::min<double>((x - start_) / step, static_cast<double>(nodes_m_.size() - 2)));
  while (i > 0 && x < nodes_m_[i]) --i;
  while (i + 2 < nodes_m_.size() && x >= nodes_m_[i + 1]) ++i;
  if (x == nodes_m_[i]) return cumulative_at_nodes_[i];
  return cumulative_at_nodes_[i] +
         Rule::integrate([this](double s) { return kappa(s); }, nodes_m_[i], x);
}

HelicalMesh::HelicalMesh(const GearPair& pair, const FaceStiffness& face, CoastPhase coast_phase)
    : face_(face) {
  if (!(pair.helix_angle_rad > 0.0)) {
    throw InputError("gears.helix_angle", format_number(pair.helix_angle_rad * 180.0 / pi) + " deg",
                     "(0, 45] deg for the slice model: a spur pair takes the spur path");
  }
  const GearPair t = transverse_pair(pair);
  x_pitch_ = pitch_point_position(t);
  rb1_ = base_radius(t, Gear::one);
  p_bt_ = base_pitch(t);
  const ContactSegment segment = contact_segment(t);
  start_ = segment.start_m;
  end_ = segment.end_m;
  b_ = pair.face_width_m;
  beta_b_ = base_helix_angle(pair);
  tan_bb_ = std::tan(beta_b_);
  half_w_ = 0.5 * b_ * tan_bb_;
  sigma_ = hand_sign(pair.helix_hand);
  coast_offset_ = coast_phase == CoastPhase::half_base_pitch ? 0.5 * p_bt_ : 0.0;
}

double HelicalMesh::mid_face_position_m(Region line, double theta1_rad, int k) const {
  if (line == Region::free) throw InputError("line", "free", "Region::n1 or Region::n2");
  const double reference = line == Region::n1 ? x_pitch_ + rb1_ * theta1_rad
                                              : x_pitch_ - rb1_ * theta1_rad + coast_offset_;
  return reference + k * p_bt_;
}

double HelicalMesh::slice_offset_m(Region line, int j, int slices) const {
  const double db = b_ / slices;
  const double y = (j + 0.5) * db;
  const double offset = sigma_ * (y - 0.5 * b_) * tan_bb_;
  return line == Region::n1 ? offset : -offset;
}

namespace {

// The pairs k whose mid-face contact lies within W/2 of the path: the ones
// that may touch.
struct PairRange {
  int first;
  int last;
};
PairRange pairs_near(double reference_m, double pitch_m, double start_m, double end_m,
                     double half_w_m) {
  return {static_cast<int>(std::floor((start_m - half_w_m - reference_m) / pitch_m)) - 1,
          static_cast<int>(std::ceil((end_m + half_w_m - reference_m) / pitch_m)) + 1};
}

void check_slices(int slices) {
  if (slices < 1 || slices > kMostFaceSlices) {
    throw InputError("model.face_slices", std::to_string(slices),
                     "an integer in [1, " + std::to_string(kMostFaceSlices) + "]");
  }
}

}  // namespace

double HelicalMesh::stiffness_slices(Region line, double theta1_rad, int slices) const {
  check_slices(slices);
  const double reference = mid_face_position_m(line, theta1_rad, 0);
  const PairRange range = pairs_near(reference, p_bt_, start_, end_, half_w_);
  const double db = b_ / slices;
  double sum = 0.0;
  for (int k = range.first; k <= range.last; ++k) {
    const double xk = reference + k * p_bt_;
    for (int j = 0; j < slices; ++j) {
      const double x = xk + slice_offset_m(line, j, slices);
      if (x >= start_ && x <= end_) sum += face_.kappa(x) * db;
    }
  }
  return sum;
}

double HelicalMesh::pair_stiffness_face(double x_mid_m) const {
  const double high = std::min(x_mid_m + half_w_, end_);
  const double low = std::max(x_mid_m - half_w_, start_);
  if (!(high > low)) return 0.0;
  return (face_.cumulative(high) - face_.cumulative(low)) / tan_bb_;
}

double HelicalMesh::stiffness_face(Region line, double theta1_rad) const {
  const double reference = mid_face_position_m(line, theta1_rad, 0);
  const PairRange range = pairs_near(reference, p_bt_, start_, end_, half_w_);
  double sum = 0.0;
  for (int k = range.first; k <= range.last; ++k) sum += pair_stiffness_face(reference + k * p_bt_);
  return sum;
}

double HelicalMesh::contact_line_length(Region line, double theta1_rad) const {
  const double reference = mid_face_position_m(line, theta1_rad, 0);
  const PairRange range = pairs_near(reference, p_bt_, start_, end_, half_w_);
  double overlap = 0.0;
  for (int k = range.first; k <= range.last; ++k) {
    const double xk = reference + k * p_bt_;
    overlap += std::max(0.0, std::min(xk + half_w_, end_) - std::max(xk - half_w_, start_));
  }
  // A line's length in the zone is its extent along X over sin(beta_b).
  return overlap / std::sin(beta_b_);
}

double HelicalMesh::contact_line_length_slices(Region line, double theta1_rad, int slices) const {
  check_slices(slices);
  const double reference = mid_face_position_m(line, theta1_rad, 0);
  const PairRange range = pairs_near(reference, p_bt_, start_, end_, half_w_);
  int count = 0;
  for (int k = range.first; k <= range.last; ++k) {
    const double xk = reference + k * p_bt_;
    for (int j = 0; j < slices; ++j) {
      const double x = xk + slice_offset_m(line, j, slices);
      if (x >= start_ && x <= end_) ++count;
    }
  }
  return count * (b_ / slices) / std::cos(beta_b_);
}

StiffnessTable helical_pair_table(const GearPair& pair, const StiffnessModel& model,
                                  StiffnessTableOptions options) {
  if (pair.helix_angle_rad == 0.0) {
    throw InputError("gears.helix_angle", "0 deg",
                     "(0, 45] deg for a helical pair's table: a spur pair's is "
                     "StiffnessTable(pair, model)");
  }
  const FaceStiffness face(pair, model, model.helical_hertz, options);
  const HelicalMesh mesh(pair, face);
  const GearPair swept = swept_transverse_pair(pair);
  const ContactSegment domain = pair_contact_segment(swept);
  const double half_w = 0.5 * swept.face_advance_m;
  const double path = face.end_m() - face.start_m();
  const ComplianceFunction compliance = [&](double x) {
    const double low = std::max(x - half_w, face.start_m());
    const double high = std::min(x + half_w, face.end_m());
    Compliances c;
    const double ke = mesh.pair_stiffness_face(x);
    if (!(high > low) || !(ke > 0.0)) return c;
    // Each term's energy share across the line, the integral of
    // kappa_t^2 c_i: 8-point Gauss-Legendre on pieces of at most a sixteenth
    // of the path (kappa_t is smooth; the shares split the energy by term
    // and do not enter Ke).
    const int pieces = std::max(1, static_cast<int>(std::ceil(16.0 * (high - low) / path)));
    const double step = (high - low) / pieces;
    Compliances share;
    const auto& abscissa = Rule::abscissa();
    const auto& weights = Rule::weights();
    const auto add = [&](double s, double weight) {
      const Compliances per_width = face.compliance_per_width(s);
      const double kappa = 1.0 / per_width.total_m_per_n();
      for (std::size_t t = 0; t < kTermCount; ++t) {
        share.m_per_n[t] += weight * kappa * kappa * per_width.m_per_n[t];
      }
    };
    for (int i = 0; i < pieces; ++i) {
      const double a = low + i * step;
      const double b = i + 1 == pieces ? high : low + (i + 1) * step;
      const double mid = 0.5 * (a + b);
      const double half = 0.5 * (b - a);
      // The 8-point rule's nodes come in pairs +-abscissa about the middle.
      for (std::size_t n = 0; n < abscissa.size(); ++n) {
        add(mid - half * abscissa[n], half * weights[n]);
        add(mid + half * abscissa[n], half * weights[n]);
      }
    }
    const double total = share.total_m_per_n();
    for (std::size_t t = 0; t < kTermCount; ++t) c.m_per_n[t] = share.m_per_n[t] / (total * ke);
    return c;
  };
  return StiffnessTable(domain.start_m, domain.end_m, compliance,
                        {face.start_m() + half_w, face.end_m() - half_w}, options);
}

namespace {

// kappa per unit face width at X of a transverse section's table (width b)
// and its terms per unit width, as FaceStiffness reads them: only Hertz sees
// the inclined line when projected. 0 and no terms where the table has no
// contact.
double per_width(const StiffnessTable& table, double x_m, double face_width_m, double cos_bb,
                 HelicalHertz hertz, Compliances& terms) {
  terms = table.compliance(x_m);
  if (!(terms.total_m_per_n() > 0.0)) return 0.0;
  for (double& term : terms.m_per_n) term *= face_width_m;
  if (hertz == HelicalHertz::projected) terms.of(Term::hertz) /= cos_bb;
  return 1.0 / terms.total_m_per_n();
}

}  // namespace

StiffnessTable helical_faulted_pair_table(const GearPair& swept, HelicalHertz hertz,
                                          const StiffnessTable& healthy_pair,
                                          const StiffnessTable& healthy_section,
                                          const std::vector<FaceBand>& bands, Region line,
                                          StiffnessTableOptions options) {
  if (!(swept.face_advance_m > 0.0)) {
    throw InputError("gears.helix_angle", "0 deg",
                     "(0, 45] deg for a helical pair's faulted table: a spur pair's is "
                     "MeshTables'");
  }
  if (line == Region::free) throw InputError("line", "free", "Region::n1 or Region::n2");
  GearPair section = swept;
  section.face_advance_m = 0.0;
  const ContactSegment path = contact_segment(section);
  const ContactSegment domain = pair_contact_segment(swept);
  const double b = swept.face_width_m;
  const double tan_bb = swept.face_advance_m / b;
  const double cos_bb = 1.0 / std::sqrt(1.0 + tan_bb * tan_bb);
  // On N1 the section at y sits sigma (y - b/2) tan(beta_b) further along, on N2 that much back.
  const double sign = (line == Region::n1 ? 1.0 : -1.0) * hand_sign(swept.helix_hand);
  const double span = path.end_m - path.start_m;
  struct Extent {
    double low;  // the band's ends along the line, from the pair's mid-face contact
    double high;
    const StiffnessTable* section;
    std::vector<double> edges;  // where kappa of the band or the healthy one may kink or jump
  };
  // The whole face: the given bands and, between them, healthy ones.
  std::vector<FaceBand> face;
  {
    std::vector<FaceBand> given = bands;
    std::sort(given.begin(), given.end(),
              [](const FaceBand& p, const FaceBand& q) { return p.start_m < q.start_m; });
    double y = 0.0;
    for (const FaceBand& band : given) {
      if (!(band.end_m > band.start_m)) continue;
      if (band.start_m < y || band.end_m > b) {
        throw InputError("bands", "overlapping or beyond the face",
                         "disjoint bands within [0, b] of the face");
      }
      if (band.start_m > y) face.push_back({y, band.start_m, &healthy_section});
      face.push_back(band);
      y = band.end_m;
    }
    if (b > y) face.push_back({y, b, &healthy_section});
  }
  std::vector<Extent> extents;
  std::vector<double> breaks = healthy_pair.breaks_m();
  for (const FaceBand& band : face) {
    if (!(band.end_m > band.start_m)) continue;
    const double a = sign * (band.start_m - 0.5 * b) * tan_bb;
    const double c = sign * (band.end_m - 0.5 * b) * tan_bb;
    Extent e{std::min(a, c), std::max(a, c), band.section, {path.start_m, path.end_m}};
    for (const StiffnessTable* t : {band.section, &healthy_section}) {
      if (t == nullptr) continue;
      for (double x : t->breaks_m()) {
        if (x > path.start_m && x < path.end_m) e.edges.push_back(x);
      }
    }
    for (double p : e.edges) {
      breaks.push_back(p - e.low);
      breaks.push_back(p - e.high);
    }
    extents.push_back(std::move(e));
  }
  const ComplianceFunction compliance = [&](double x) {
    // s_i = kappa^2 c_i integrated over the line on the path, over
    // tan(beta_b), each band's slices in their state: the terms c_i sum to
    // 1 / kappa, so K = sum of s_i and the pair's c_i = s_i / K^2.
    std::array<double, kTermCount> s{};
    const auto& abscissa = Rule::abscissa();
    const auto& weights = Rule::weights();
    for (const Extent& e : extents) {
      const double low = std::max(x + e.low, path.start_m);
      const double high = std::min(x + e.high, path.end_m);
      if (!(high > low)) continue;
      // Pieces cut at the edges inside, each at most a sixteenth of the path:
      // kappa is smooth on each (8-point Gauss-Legendre, as helical_pair_table).
      std::vector<double> ends{low, high};
      for (double p : e.edges) {
        if (p > low && p < high) ends.push_back(p);
      }
      std::sort(ends.begin(), ends.end());
      for (std::size_t i = 1; i < ends.size(); ++i) {
        const double from = ends[i - 1];
        const double to = ends[i];
        const int pieces = std::max(1, static_cast<int>(std::ceil(16.0 * (to - from) / span)));
        const double step = (to - from) / pieces;
        for (int q = 0; q < pieces; ++q) {
          const double lo = from + q * step;
          const double hi = q + 1 == pieces ? to : from + (q + 1) * step;
          const double mid = 0.5 * (lo + hi);
          const double half = 0.5 * (hi - lo);
          const auto add = [&](double at, double weight) {
            Compliances c_band;
            const double kb = e.section ? per_width(*e.section, at, b, cos_bb, hertz, c_band) : 0.0;
            if (!(kb > 0.0)) return;
            for (std::size_t t = 0; t < kTermCount; ++t) {
              s[t] += weight * kb * kb * c_band.m_per_n[t] / tan_bb;
            }
          };
          for (std::size_t n = 0; n < abscissa.size(); ++n) {
            add(mid - half * abscissa[n], half * weights[n]);
            add(mid + half * abscissa[n], half * weights[n]);
          }
        }
      }
    }
    double k = 0.0;
    for (double term : s) k += term;
    Compliances c;
    if (!(k > 0.0)) return c;
    for (std::size_t t = 0; t < kTermCount; ++t) c.m_per_n[t] = s[t] / (k * k);
    return c;
  };
  return StiffnessTable(domain.start_m, domain.end_m, compliance, breaks, options);
}

SliceStiffness helical_slice_stiffness(const GearPair& swept, HelicalHertz hertz,
                                       const StiffnessTable& healthy_section,
                                       const std::vector<FaceBand>& bands, double y0_m, double y1_m,
                                       double x_m) {
  const double b = swept.face_width_m;
  const double tan_bb = swept.face_advance_m / b;
  const double cos_bb = 1.0 / std::sqrt(1.0 + tan_bb * tan_bb);
  const double width = y1_m - y0_m;
  Compliances terms;
  // s_i: each part's share times kappa^2 c_i; they sum to kappa.
  std::array<double, kTermCount> s{};
  const auto add = [&](double share, double kappa) {
    for (std::size_t t = 0; t < kTermCount; ++t) s[t] += share * kappa * kappa * terms.m_per_n[t];
  };
  double healthy_share = 1.0;
  SliceStiffness slice;
  for (const FaceBand& band : bands) {
    const double covered = std::min(band.end_m, y1_m) - std::max(band.start_m, y0_m);
    if (!(covered > 0.0)) continue;
    const double share = covered / width;
    healthy_share -= share;
    if (!band.section) continue;
    const double kappa = per_width(*band.section, x_m, b, cos_bb, hertz, terms);
    slice.kappa_n_per_m2 += share * kappa;
    if (kappa > 0.0) add(share, kappa);
  }
  if (healthy_share > 0.0) {
    const double kappa = per_width(healthy_section, x_m, b, cos_bb, hertz, terms);
    slice.kappa_n_per_m2 += healthy_share * kappa;
    if (kappa > 0.0) add(healthy_share, kappa);
  }
  double k = 0.0;
  for (double term : s) k += term;
  if (!(k > 0.0)) return slice;
  for (std::size_t t = 0; t < kTermCount; ++t) {
    slice.compliance.m_per_n[t] = s[t] / (k * k * width);
  }
  return slice;
}

HelicalMeshStiffnessCurve helical_mesh_stiffness(const GearPair& pair, const StiffnessModel& model,
                                                 int samples) {
  if (samples < 2 || samples > 100000) {
    throw InputError("samples", std::to_string(samples),
                     "an integer in [2, 100000] per mesh period");
  }
  check_slices(model.face_slices);
  const FaceStiffness face(pair, model, model.helical_hertz);
  const HelicalMesh mesh(pair, face);
  HelicalMeshStiffnessCurve curve;
  curve.geometry = helical_geometry(pair);
  curve.face_slices = model.face_slices;
  const double period = mesh.mesh_period_rad();
  curve.samples.reserve(static_cast<std::size_t>(samples));
  for (int i = 0; i < samples; ++i) {
    HelicalMeshStiffnessSample s{};
    s.fraction = static_cast<double>(i) / samples;
    s.theta1_rad = period * s.fraction;
    s.slices_n_per_m = mesh.stiffness_slices(Region::n1, s.theta1_rad, model.face_slices);
    s.face_n_per_m = mesh.stiffness_face(Region::n1, s.theta1_rad);
    s.contact_line_length_m = mesh.contact_line_length(Region::n1, s.theta1_rad);
    s.contact_line_length_slices_m =
        mesh.contact_line_length_slices(Region::n1, s.theta1_rad, model.face_slices);
    curve.samples.push_back(s);
  }
  const auto extreme = [&](auto member, bool most) {
    double value = curve.samples.front().*member;
    for (const HelicalMeshStiffnessSample& s : curve.samples) {
      value = most ? std::max(value, s.*member) : std::min(value, s.*member);
    }
    return value;
  };
  curve.min_face_n_per_m = extreme(&HelicalMeshStiffnessSample::face_n_per_m, false);
  curve.max_face_n_per_m = extreme(&HelicalMeshStiffnessSample::face_n_per_m, true);
  curve.min_slices_n_per_m = extreme(&HelicalMeshStiffnessSample::slices_n_per_m, false);
  curve.max_slices_n_per_m = extreme(&HelicalMeshStiffnessSample::slices_n_per_m, true);
  curve.mean_n_per_m = pair.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
  curve.mean_contact_line_length_m = pair.face_width_m * curve.geometry.transverse_contact_ratio /
                                     std::cos(curve.geometry.base_helix_angle_rad);
  curve.iso_mesh_stiffness_n_per_m =
      iso6336_method_b(iso6336_pair(pair, pair.helix_angle_rad)).mesh_stiffness_n_per_m2 *
      pair.face_width_m;
  return curve;
}

FaceFriction::FaceFriction(const GearPair& swept, const StiffnessModel& model,
                           StiffnessTableOptions options) {
  if (!(swept.face_advance_m > 0.0)) {
    throw InputError("gears.helix_angle", "0 deg",
                     "(0, 45] deg for a helical pair's face friction: a spur pair's friction "
                     "is the spur mesh's");
  }
  GearPair section = swept;
  section.face_advance_m = 0.0;
  const ContactSegment path = contact_segment(section);
  start_ = path.start_m;
  end_ = path.end_m;
  half_w_ = 0.5 * swept.face_advance_m;
  face_width_ = swept.face_width_m;
  const double tan_bb = swept.face_advance_m / swept.face_width_m;
  cos_base_helix_ = 1.0 / std::sqrt(1.0 + tan_bb * tan_bb);
  hertz_ = model.helical_hertz;
  section_.emplace(section, model, options);
  // Sixteen intervals to a piece of the section's table (equal pieces of the
  // path): no interval straddles a piece's end, where kappa_t's series
  // changes, and the cubic Hermite error, h^4 / 384 times the fourth
  // derivative, stays far below the table's own fit.
  const int intervals = 16 * section_->pieces();
  step_ = (end_ - start_) / intervals;
  const auto count = static_cast<std::size_t>(intervals) + 1;
  nodes_m_.resize(count);
  kappa_.resize(count);
  for (auto& c : integral_) c.assign(count, 0.0);
  for (std::size_t i = 0; i < count; ++i) {
    nodes_m_[i] = i + 1 == count ? end_ : start_ + static_cast<double>(i) * step_;
    kappa_[i] = kappa(nodes_m_[i]);
  }
  for (std::size_t i = 0; i + 1 < count; ++i) {
    integral_[0][i + 1] = integral_[0][i] + Rule::integrate([this](double x) { return kappa(x); },
                                                            nodes_m_[i], nodes_m_[i + 1]);
    integral_[1][i + 1] =
        integral_[1][i] +
        Rule::integrate([this](double x) { return kappa(x) * x; }, nodes_m_[i], nodes_m_[i + 1]);
  }
}

double FaceFriction::kappa(double x_m) const {
  if (!(x_m >= start_ && x_m <= end_)) return 0.0;
  Compliances terms;
  return per_width(*section_, x_m, face_width_, cos_base_helix_, hertz_, terms);
}

double FaceFriction::primitive(double x_m, int which) const {
  const double x = std::clamp(x_m, start_, end_);
  const std::size_t last = nodes_m_.size() - 2;
  const auto i =
      std::min(last, static_cast<std::size_t>(std::max(0.0, std::floor((x - start_) / step_))));
  const double h = nodes_m_[i + 1] - nodes_m_[i];
  const double t = (x - nodes_m_[i]) / h;
  const std::vector<double>& c = integral_[static_cast<std::size_t>(which)];
  // The slopes: C0' = kappa_t, C1' = kappa_t X.
  const double slope0 = which == 0 ? kappa_[i] : kappa_[i] * nodes_m_[i];
  const double slope1 = which == 0 ? kappa_[i + 1] : kappa_[i + 1] * nodes_m_[i + 1];
  const double u = 1.0 - t;
  return (1.0 + 2.0 * t) * u * u * c[i] + t * u * u * h * slope0 +
         t * t * (3.0 - 2.0 * t) * c[i + 1] - t * t * u * h * slope1;
}

FaceSlip FaceFriction::slip(double x_mid_m, double rate_per_s, double offset_m_s) const {
  const double low = std::max(x_mid_m - half_w_, start_);
  const double high = std::min(x_mid_m + half_w_, end_);
  FaceSlip s;
  const auto spur = [&] {
    // No extent on the path: the limit of a line shrinking to the path's end.
    const double x = std::clamp(x_mid_m, start_, end_);
    s.weight_n_per_m = 0.0;
    s.slip = rate_per_s * x + offset_m_s >= 0.0 ? 1.0 : -1.0;
    s.arm_m = s.slip * x;
    return s;
  };
  if (!(high > low)) return spur();
  const double w0 = weight_primitive(low);
  const double w1 = weight_primitive(high);
  s.weight_n_per_m = w1 - w0;
  if (!(s.weight_n_per_m > 0.0)) return spur();
  // Vs = rate X' + offset: one sign above `split`, the other below it.
  double split = low;
  double above = offset_m_s >= 0.0 ? 1.0 : -1.0;
  if (rate_per_s != 0.0) {
    split = std::clamp(-offset_m_s / rate_per_s, low, high);
    above = rate_per_s > 0.0 ? 1.0 : -1.0;
  }
  const double ws = weight_primitive(split);
  const double m0 = moment_primitive(low);
  const double ms = moment_primitive(split);
  const double m1 = moment_primitive(high);
  s.slip = std::clamp(above * ((w1 - ws) - (ws - w0)) / s.weight_n_per_m, -1.0, 1.0);
  s.arm_m = std::clamp(above * ((m1 - ms) - (ms - m0)) / s.weight_n_per_m, -high, high);
  return s;
}

double face_load_factor_linear_gap(double c, double b, double force, double mismatch) {
  if (!(c > 0.0) || !(b > 0.0) || !(force > 0.0) || !(mismatch >= 0.0) || !std::isfinite(c) ||
      !std::isfinite(b) || !std::isfinite(force) || !std::isfinite(mismatch)) {
    throw InputError("face load", "c, b, F, F_betay",
                     "finite values, c, b and F > 0, F_betay >= 0");
  }
  // e(y) = F_betay (y/b - 1/2): the load of a deflection delta is
  // c times the integral of max(0, delta - e) over [0, b], exact for the linear gap.
  const double e_low = -0.5 * mismatch;
  const double e_high = 0.5 * mismatch;
  const auto load = [&](double delta) {
    if (delta <= e_low) return 0.0;
    if (mismatch == 0.0 || delta >= e_high) return c * b * delta;
    const double y0 = b * (delta - e_low) / mismatch;  // where e(y0) = delta
    return c * 0.5 * (delta - e_low) * y0;
  };
  // Bracket: delta = e_low carries nothing, full contact at e_high + F / (c b) carries more than F.
  double low = e_low;
  double high = e_high + force / (c * b);
  std::uintmax_t iterations = 200;
  const auto bracket = boost::math::tools::toms748_solve(
      [&](double d) { return load(d) - force; }, low, high, -force, load(high) - force,
      boost::math::tools::eps_tolerance<double>(), iterations);
  const double delta = 0.5 * (bracket.first + bracket.second);
  return c * (delta - e_low) / (force / b);
}

}  // namespace gearimpact
