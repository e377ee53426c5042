#include "gearimpact/stiffness/mesh_tables.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <utility>

#include "gearimpact/error.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "pair_crack_change.hpp"

namespace gearimpact {

namespace {

// The terms of the teeth of one class of one gear at the positions the
// tables ask for, each computed once: the tables meet the same teeth at the
// same Chebyshev nodes (a healthy wheel tooth beside every cracked pinion
// tooth). A cracked tooth is its gear's healthy tooth plus what the crack
// changes (PairCrackChange), integrated over the cut sections only; every
// other tooth is faulted_pair_tooth_terms, as mesh_stiffness computes it.
class ClassTerms {
 public:
  ClassTerms(const GearPair& pair, const StiffnessModel& model, Gear gear, const ToothState& state,
             ClassTerms* healthy)
      : pair_(pair), model_(model), gear_(gear), state_(state), healthy_(healthy) {
    if (state.kind == ToothKind::root_crack) crack_.emplace(pair, model, gear, state.crack);
  }

  // The terms at x1 when they are known already (a healthy tooth at a node of
  // the healthy table). The foundation's extrapolation flag is not kept there:
  // false, as the tables read only the compliances.
  void know(double x1_m, const Compliances& terms) {
    terms_.emplace(x1_m, ToothTerms{terms, false});
  }

  // Where the cracked tooth's terms kink along the segment (none for the
  // other kinds, whose edges fault_breaks gives).
  std::vector<double> kinks() const {
    return crack_ ? crack_->kinks_x1_m() : std::vector<double>{};
  }

  const ToothTerms& at(double x1_m) {
    const auto found = terms_.find(x1_m);
    if (found != terms_.end()) return found->second;
    ToothTerms t;
    if (crack_) {
      t = healthy_->at(x1_m);
      const Compliances change = crack_->at(x1_m);
      for (Term term : {Term::bending, Term::shear, Term::axial}) {
        t.terms.of(term) += change.of(term);
      }
    } else {
      t = faulted_pair_tooth_terms(pair_, gear_, x1_m, model_, state_);
    }
    return terms_.emplace(x1_m, t).first->second;
  }

 private:
  const GearPair& pair_;
  const StiffnessModel& model_;
  Gear gear_;
  ToothState state_;
  ClassTerms* healthy_;
  std::optional<PairCrackChange> crack_;
  std::map<double, ToothTerms> terms_;
};

// One ClassTerms per state of `gear`, the healthy one (state 0) first.
std::vector<std::unique_ptr<ClassTerms>> class_terms(const GearPair& pair,
                                                     const StiffnessModel& model, Gear gear,
                                                     const std::vector<ToothState>& states) {
  std::vector<std::unique_ptr<ClassTerms>> terms;
  for (const ToothState& state : states) {
    terms.push_back(std::make_unique<ClassTerms>(pair, model, gear, state,
                                                 terms.empty() ? nullptr : terms.front().get()));
  }
  return terms;
}

// The table of teeth in states s1, s2 on the line whose flank is `flank`
// over the contact segment of `pair`, cut at the faults' edges and a crack's
// kinks; across the whole face a spall's or a chip's part beyond its edge has
// no contact.
std::shared_ptr<const StiffnessTable> teeth_table(const GearPair& pair, const StiffnessModel& model,
                                                  const ToothState& s1, const ToothState& s2,
                                                  ClassTerms& t1, ClassTerms& t2, CrackFlank flank,
                                                  StiffnessTableOptions options) {
  std::vector<double> breaks = fault_breaks(pair, Gear::one, s1);
  const std::vector<double> breaks2 = fault_breaks(pair, Gear::two, s2);
  breaks.insert(breaks.end(), breaks2.begin(), breaks2.end());
  // A crack's kinks too: a piece fitted across one misses the 1e-12.
  for (const ClassTerms* t : {&t1, &t2}) {
    const std::vector<double> kinks = t->kinks();
    breaks.insert(breaks.end(), kinks.begin(), kinks.end());
  }
  const ContactSegment segment = contact_segment(pair);
  const ComplianceFunction compliance = [&](double x1_m) {
    if (!(pair_contact_length_m(pair, x1_m, s1, s2, flank) > 0.0)) {
      return MeshStiffness{}.included;
    }
    return mesh_stiffness_of_teeth(pair, x1_m, model, s1, s2, flank, t1.at(x1_m), t2.at(x1_m))
        .included;
  };
  return breaks.empty() ? std::make_shared<const StiffnessTable>(segment.start_m, segment.end_m,
                                                                 compliance, options)
                        : std::make_shared<const StiffnessTable>(segment.start_m, segment.end_m,
                                                                 compliance, breaks, options);
}

// The state across the whole face whose slices are a band's: a spall's or a
// chip's width the face width.
ToothState across_face(ToothState s, double face_width_m) {
  s.face_start_m = 0.0;
  if (s.kind == ToothKind::spall) s.spall.width_m = face_width_m;
  if (s.kind == ToothKind::tip_chip) s.chip.width_m = face_width_m;
  return s;
}

// The most sub-bands a crack whose depth varies across the face is cut into:
// each builds one table of the transverse section.
constexpr int kMostCrackSubBands = 64;

// One piece [y0, y1) of the face in which a helical tooth's slices share one
// state, given across the whole face (the transverse section's state).
struct FacePiece {
  double start_m;
  double end_m;
  ToothState state;
};

// The pieces of the face a helical tooth's state covers (none for a healthy
// tooth): a spall's or a chip's band from face_start over its width; a
// uniform crack the whole face. A crack whose depth varies across the face
// (partial-width over [0, W_c), full-width over [0, b), z = y as
// faults.face_start's y) is cut into n = min(model.face_slices, 64) sub-bands
// of equal width, each a uniform crack of the profile's depth at its middle
// (the midpoint rule in y); neighbours of equal depth are one piece, so that
// a full-width crack with q2 = q0 is the uniform crack's single band.
std::vector<FacePiece> covered_pieces(const ToothState& s, double face_width_m, int face_slices) {
  if (s.kind == ToothKind::healthy) return {};
  if (s.kind == ToothKind::spall) {
    return {{s.face_start_m, s.face_start_m + s.spall.width_m, across_face(s, face_width_m)}};
  }
  if (s.kind == ToothKind::tip_chip) {
    return {{s.face_start_m, s.face_start_m + s.chip.width_m, across_face(s, face_width_m)}};
  }
  if (s.kind != ToothKind::root_crack || s.crack.profile == CrackProfile::uniform) {
    return {{0.0, face_width_m, across_face(s, face_width_m)}};
  }
  const double extent =
      s.crack.profile == CrackProfile::partial_width ? s.crack.width_m : face_width_m;
  const int n = std::clamp(face_slices, 1, kMostCrackSubBands);
  std::vector<FacePiece> pieces;
  for (int i = 0; i < n; ++i) {
    const double y0 = extent * i / n;
    const double y1 = i + 1 == n ? extent : extent * (i + 1) / n;
    ToothState q = s;
    q.crack.profile = CrackProfile::uniform;
    q.crack.depth_m = crack_depth_at(s.crack, 0.5 * (y0 + y1), face_width_m);
    q.crack.end_depth_m = 0.0;
    q.crack.width_m = 0.0;
    if (!pieces.empty() && pieces.back().state.crack.depth_m == q.crack.depth_m) {
      pieces.back().end_m = y1;
    } else {
      pieces.push_back({y0, y1, q});
    }
  }
  return pieces;
}

// The piece of `pieces` whose interior holds y, or -1.
int piece_at(const std::vector<FacePiece>& pieces, double y) {
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (y > pieces[i].start_m && y < pieces[i].end_m) return static_cast<int>(i);
  }
  return -1;
}

// A fault that changes no slice of a helical tooth: a uniform crack of depth 0
// (the healthy tooth exactly, docs/faults.md): its pair reads the healthy
// table, to the bit.
bool changes_nothing(const ToothState& s) {
  return s.kind == ToothKind::healthy ||
         (s.kind == ToothKind::root_crack && s.crack.profile == CrackProfile::uniform &&
          s.crack.depth_m == 0.0);
}

}  // namespace

MeshTables::MeshTables(const GearPair& pair, const StiffnessModel& model,
                       std::vector<ToothFault> faults,
                       std::shared_ptr<const StiffnessTable> healthy, StiffnessTableOptions options)
    : pair_(pair), faults_(std::move(faults)), healthy_(std::move(healthy)) {
  check_tooth_faults(pair_, model, faults_);
  if (!healthy_ && pair_.face_advance_m > 0.0) {
    throw InputError("healthy", "none",
                     "a helical pair's section needs its pair table (helical_pair_table)");
  }
  if (!healthy_) healthy_ = std::make_shared<const StiffnessTable>(pair_, model, options);
  const int z1 = teeth(pair_, Gear::one);
  const int z2 = teeth(pair_, Gear::two);
  const std::vector<ToothState> pinion = tooth_classes(faults_, Gear::one, z1, pinion_class_);
  const std::vector<ToothState> wheel = tooth_classes(faults_, Gear::two, z2, wheel_class_);
  wheel_states_ = wheel.size();
  distinct_ = {pinion.size() > 1, wheel.size() > 1};
  const std::size_t combinations = pinion.size() * wheel_states_;
  // The combinations that meet: pinion tooth i meets wheel tooth j on N1 when
  // i = j mod gcd(z1, z2), on N2 when j = i + 1 mod gcd (teeth_of_pair); so
  // every pair of one hunting period on each line.
  std::array<std::vector<bool>, 2> meets{std::vector<bool>(combinations, false),
                                         std::vector<bool>(combinations, false)};
  const int period = static_cast<int>(std::lcm(z1, z2));
  for (int n = 0; n < period; ++n) {
    meets[0][combination(teeth_of_pair(pair_, Region::n1, -n))] = true;
    meets[1][combination(teeth_of_pair(pair_, Region::n2, n))] = true;
  }
  const std::vector<std::unique_ptr<ClassTerms>> pinion_terms =
      class_terms(pair_, model, Gear::one, pinion);
  const std::vector<std::unique_ptr<ClassTerms>> wheel_terms =
      class_terms(pair_, model, Gear::two, wheel);
  // The healthy teeth at the healthy table's nodes, which are the fault
  // tables' too where they have no breaks (and the same options); only from
  // a table known to be of this pair and model.
  if (healthy_->built_for(pair_, model)) {
    for (const NodeTeeth& node : healthy_->node_teeth()) {
      pinion_terms.front()->know(node.x1_m, node.tooth1);
      wheel_terms.front()->know(node.x1_m, node.tooth2);
    }
  }
  for (auto& line : tables_) line.assign(combinations, nullptr);
  if (pair_.face_advance_m > 0.0) {
    for (auto& line : face_bands_) line.assign(combinations, {});
  }
  // A helical pair's section (swept_transverse_pair, face_advance_m = W > 0):
  // each tooth pair reads a table over its widened segment, the healthy one
  // given (helical_pair_table), a faulted one the face integral of its slices,
  // each band of the face in its own state (helical_faulted_pair_table). The
  // bands' states across the whole face are tables of the transverse section.
  const bool helical = pair_.face_advance_m > 0.0;
  GearPair section = pair_;
  section.face_advance_m = 0.0;
  std::shared_ptr<const StiffnessTable> section_healthy;
  // Each class's pieces of the face (covered_pieces), and the section's
  // teeth in each piece's state, made when first asked for: (class, piece)
  // -> its terms; the healthy tooth's under (0, 0).
  std::vector<std::vector<FacePiece>> pinion_pieces;
  std::vector<std::vector<FacePiece>> wheel_pieces;
  std::map<std::array<std::size_t, 2>, std::unique_ptr<ClassTerms>> pinion_across;
  std::map<std::array<std::size_t, 2>, std::unique_ptr<ClassTerms>> wheel_across;
  // (pinion class or 0, its piece + 1 or 0, wheel class or 0, its piece + 1
  // or 0, line) -> the section's table.
  std::map<std::array<std::size_t, 5>, std::shared_ptr<const StiffnessTable>> section_tables;
  const double b_face = pair_.face_width_m;
  if (helical) {
    section_healthy = std::make_shared<const StiffnessTable>(section, model, options);
    for (const ToothState& s : pinion) {
      pinion_pieces.push_back(covered_pieces(s, b_face, model.face_slices));
    }
    for (const ToothState& s : wheel) {
      wheel_pieces.push_back(covered_pieces(s, b_face, model.face_slices));
    }
    pinion_across.emplace(
        std::array<std::size_t, 2>{0, 0},
        std::make_unique<ClassTerms>(section, model, Gear::one, ToothState{}, nullptr));
    wheel_across.emplace(
        std::array<std::size_t, 2>{0, 0},
        std::make_unique<ClassTerms>(section, model, Gear::two, ToothState{}, nullptr));
    for (const NodeTeeth& node : section_healthy->node_teeth()) {
      pinion_across.at({0, 0})->know(node.x1_m, node.tooth1);
      wheel_across.at({0, 0})->know(node.x1_m, node.tooth2);
    }
  }
  // The section's teeth of `gear` in piece p of class k's pieces (the healthy
  // tooth for p < 0).
  const auto across_terms = [&](Gear gear, std::size_t k, int p) -> ClassTerms& {
    auto& terms = gear == Gear::one ? pinion_across : wheel_across;
    const std::array<std::size_t, 2> key{p < 0 ? 0 : k,
                                         p < 0 ? 0 : static_cast<std::size_t>(p) + 1};
    auto found = terms.find(key);
    if (found == terms.end()) {
      const auto& pieces = gear == Gear::one ? pinion_pieces : wheel_pieces;
      found =
          terms
              .emplace(key, std::make_unique<ClassTerms>(
                                section, model, gear, pieces[k][static_cast<std::size_t>(p)].state,
                                terms.at({0, 0}).get()))
              .first;
    }
    return *found->second;
  };
  const auto add_helical = [&](std::size_t a, std::size_t b, std::size_t c) {
    const ToothState& s1 = pinion[a];
    const ToothState& s2 = wheel[b];
    if (changes_nothing(s1) && changes_nothing(s2)) {
      for (std::size_t line = 0; line < 2; ++line) {
        if (meets[line][c]) tables_[line][c] = healthy_;
      }
      return;
    }
    static const std::vector<FacePiece> none;
    const std::vector<FacePiece>& pieces1 = changes_nothing(s1) ? none : pinion_pieces[a];
    const std::vector<FacePiece>& pieces2 = changes_nothing(s2) ? none : wheel_pieces[b];
    std::vector<double> cuts{0.0, b_face};
    for (const auto* pieces : {&pieces1, &pieces2}) {
      for (const FacePiece& piece : *pieces) {
        cuts.push_back(piece.start_m);
        cuts.push_back(piece.end_m);
      }
    }
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t line = 0; line < 2; ++line) {
      if (!meets[line][c]) continue;
      const CrackFlank flank = line == 0 ? CrackFlank::loaded : CrackFlank::unloaded;
      std::vector<FaceBand> bands;
      for (std::size_t i = 1; i < cuts.size(); ++i) {
        const double y0 = std::max(cuts[i - 1], 0.0);
        const double y1 = std::min(cuts[i], b_face);
        if (!(y1 > y0)) continue;
        const double mid = 0.5 * (y0 + y1);
        const int p1 = piece_at(pieces1, mid);
        const int p2 = piece_at(pieces2, mid);
        if (p1 < 0 && p2 < 0) continue;
        const std::array<std::size_t, 5> key{p1 < 0 ? 0 : a, static_cast<std::size_t>(p1 + 1),
                                             p2 < 0 ? 0 : b, static_cast<std::size_t>(p2 + 1),
                                             line};
        auto found = section_tables.find(key);
        if (found == section_tables.end()) {
          const ToothState q1 = p1 < 0 ? ToothState{} : pieces1[static_cast<std::size_t>(p1)].state;
          const ToothState q2 = p2 < 0 ? ToothState{} : pieces2[static_cast<std::size_t>(p2)].state;
          found =
              section_tables
                  .emplace(key, teeth_table(section, model, q1, q2, across_terms(Gear::one, a, p1),
                                            across_terms(Gear::two, b, p2), flank, options))
                  .first;
        }
        // Neighbouring intervals in one piece of each tooth are one band.
        if (!bands.empty() && bands.back().end_m == y0 &&
            bands.back().section == found->second.get()) {
          bands.back().end_m = y1;
        } else {
          bands.push_back({y0, y1, found->second.get()});
        }
      }
      face_bands_[line][c] = bands;
      tables_[line][c] = std::make_shared<const StiffnessTable>(
          helical_faulted_pair_table(pair_, model.helical_hertz, *healthy_, *section_healthy, bands,
                                     line == 0 ? Region::n1 : Region::n2, options));
      ++fault_tables_;
    }
  };
  section_healthy_ = section_healthy;
  for (std::size_t a = 0; a < pinion.size(); ++a) {
    for (std::size_t b = 0; b < wheel_states_; ++b) {
      const std::size_t c = a * wheel_states_ + b;
      if (pinion[a].kind == ToothKind::missing || wheel[b].kind == ToothKind::missing) continue;
      if (a == 0 && b == 0) {
        for (std::size_t line = 0; line < 2; ++line) {
          if (meets[line][c]) tables_[line][c] = healthy_;
        }
        continue;
      }
      const ToothState& s1 = pinion[a];
      const ToothState& s2 = wheel[b];
      if (helical) {
        add_helical(a, b, c);
        continue;
      }
      // Only a spall's Hertzian length depends on the flank the contact is on.
      const bool by_line = s1.kind == ToothKind::spall || s2.kind == ToothKind::spall;
      for (std::size_t line = 0; line < 2; ++line) {
        if (!meets[line][c]) continue;
        if (line == 1 && !by_line && tables_[0][c]) {
          tables_[1][c] = tables_[0][c];
          continue;
        }
        const CrackFlank flank = line == 0 ? CrackFlank::loaded : CrackFlank::unloaded;
        tables_[line][c] =
            teeth_table(pair_, model, s1, s2, *pinion_terms[a], *wheel_terms[b], flank, options);
        ++fault_tables_;
      }
    }
  }
  // The faulted tables' bands point to these (face_bands).
  for (auto& [key, table] : section_tables) section_tables_.push_back(std::move(table));
}

MeshTables MeshTables::slice(double y0_m, double y1_m,
                             std::shared_ptr<const StiffnessTable> healthy_slice,
                             HelicalHertz hertz) const {
  const double b = pair_.face_width_m;
  if (!section_healthy_) {
    throw InputError("tables", "a spur pair's", "a helical pair's tables (helical_mesh_tables)");
  }
  if (!(y0_m >= 0.0 && y1_m > y0_m && y1_m <= b) || !healthy_slice) {
    throw InputError(
        "slice", "[" + format_number(y0_m) + ", " + format_number(y1_m) + ") m",
        "a slice within the face [0, " + format_number(b) + "] m with its healthy table");
  }
  MeshTables s;
  s.pair_ = pair_;
  s.pair_.face_advance_m = 0.0;
  s.pair_.face_width_m = y1_m - y0_m;
  s.faults_ = faults_;
  s.healthy_ = healthy_slice;
  s.pinion_class_ = pinion_class_;
  s.wheel_class_ = wheel_class_;
  s.wheel_states_ = wheel_states_;
  s.distinct_ = distinct_;
  const StiffnessTable& section = *section_healthy_;
  const double start = healthy_slice->domain_start_m();
  const double end = healthy_slice->domain_end_m();
  for (std::size_t line = 0; line < 2; ++line) {
    s.tables_[line].assign(tables_[line].size(), nullptr);
    for (std::size_t c = 0; c < tables_[line].size(); ++c) {
      if (!tables_[line][c]) continue;
      const std::vector<FaceBand>& bands = face_bands_[line][c];
      std::vector<double> breaks = section.breaks_m();
      bool reaches = false;
      for (const FaceBand& band : bands) {
        if (!(std::min(band.end_m, y1_m) - std::max(band.start_m, y0_m) > 0.0)) continue;
        reaches = true;
        if (!band.section) continue;
        // A fault's edges, where its section's Ke jumps or kinks.
        const std::vector<double> edges = band.section->breaks_m();
        breaks.insert(breaks.end(), edges.begin(), edges.end());
      }
      if (!reaches) {
        s.tables_[line][c] = healthy_slice;
        continue;
      }
      s.tables_[line][c] = std::make_shared<const StiffnessTable>(
          start, end,
          [&](double x) {
            return helical_slice_stiffness(pair_, hertz, section, bands, y0_m, y1_m, x).compliance;
          },
          breaks);
      ++s.fault_tables_;
    }
  }
  return s;
}

std::vector<double> fault_breaks(const GearPair& pair, Gear which, const ToothState& state) {
  std::vector<double> radii;
  if (state.kind == ToothKind::spall)
    radii = {state.spall.start_radius_m, state.spall.end_radius_m};
  if (state.kind == ToothKind::tip_chip) radii = {state.chip.radius_m};
  const double rb = base_radius(pair, which);
  const double lp = line_of_action_length(pair);
  std::vector<double> breaks;
  for (double r : radii) {
    if (!(r > rb)) continue;
    // The roll distance sqrt(r^2 - Rb^2) as (r - Rb)(r + Rb), as
    // surface_faults.cpp places the band; the wheel's is measured from C2.
    const double roll = std::sqrt((r - rb) * (r + rb));
    breaks.push_back(which == Gear::one ? roll : lp - roll);
  }
  return breaks;
}

long long MeshTables::true_period_mesh_periods() const {
  return gearimpact::true_period_mesh_periods(pair_, distinct_);
}

std::vector<std::pair<const StiffnessTable*, long long>> MeshTables::table_repeats(
    long long periods) const {
  std::vector<std::pair<const StiffnessTable*, long long>> count;
  for (long long n = 0; n < periods; ++n) {
    const StiffnessTable* t = table(Region::n1, static_cast<int>(-n));
    if (t == nullptr) continue;
    auto seen = count.begin();
    while (seen != count.end() && seen->first != t) ++seen;
    if (seen == count.end()) {
      count.emplace_back(t, 1);
    } else {
      ++seen->second;
    }
  }
  return count;
}

}  // namespace gearimpact
