#include "gearimpact/dynamics/mesh_line.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

namespace {

// Grazing contacts can have Vi -> 0, where D of (32) grows without bound while
// G = D delta d(delta)/dt stays finite; the floor keeps D finite.
constexpr double kSmallestImpactSpeed_m_s = 1e-9;

}  // namespace

// What the model's keys set on either kind of line: the constant stiffness,
// the damping's stiffness and update, and the mesh force's form.
void MeshLine::read_model_settings(const SimulationCase& c) {
  constant_k_ = c.model.mesh_stiffness == MeshStiffnessMode::constant
                    ? c.model.constant_mesh_stiffness_n_per_m
                    : 0.0;
  damping_on_current_pair_ = c.model.damping_stiffness == DampingStiffness::current_pair;
  // A constant stiffness has neither the extra torque nor jumps: both forms
  // are then one, bit for bit.
  lagrangian_ = c.model.mesh_force == MeshForce::lagrangian && constant_k_ == 0.0;
  damping_update_ = resolved_damping_update(c);
}

MeshLine::MeshLine(const SimulationCase& c, const StiffnessTable& table)
    : MeshLine(c, table, 0.0) {}

MeshLine::MeshLine(const SimulationCase& c, const StiffnessTable& table, double mass_kg,
                   std::shared_ptr<const MeshTables> teeth)
    : table_(&table), model_(&c.model), gears_(&c.gears), layout_(c.gears, c.model.coast_phase) {
  const GearPair& g = c.gears;
  rb1_ = base_radius(g, Gear::one);
  rb2_ = base_radius(g, Gear::two);
  backlash_ = g.backlash_m;
  lp_ = line_of_action_length(g);
  x_pitch_ = pitch_point_position(g);
  xs_ = layout_.start_m();
  xe_ = layout_.end_m();
  const double a = operating_pressure_angle(g);
  sin_a_ = std::sin(a);
  cos_a_ = std::cos(a);
  smoothing_speed_ = c.model.friction_smoothing_speed_m_s;
  face_width_ = g.face_width_m;
  kh_ = hertz_stiffness(g);
  if (g.face_advance_m > 0.0 && c.model.stiffness.helical_hertz == HelicalHertz::projected) {
    // A helical pair's Hertzian stiffness per unit face width is c_H
    // cos(beta_b) (docs/helical.md): cos(beta_b) = b / sqrt(b^2 + W^2).
    kh_ *= g.face_width_m / std::hypot(g.face_width_m, g.face_advance_m);
  }
  swept_ = g.face_advance_m > 0.0;
  if (swept_ &&
      (c.model.friction_coefficient != 0.0 || c.model.friction_law != FrictionLaw::constant)) {
    face_friction_ = std::make_shared<const FaceFriction>(g, c.model.stiffness);
  }
  read_model_settings(c);
  MeshTeeth built = mesh_teeth(c, table, constant_k_, std::move(teeth));
  teeth_ = std::move(built.tables);
  gaps_ = std::move(built.gaps);
  kinks_ = std::move(built.kinks_m);
  // The damper's m_e is that of the pair's discs (mesh.hpp), or of the train's bodies.
  mesh_damping_ = mass_kg > 0.0 ? case_mesh_damping_n_s_per_m(c, table, teeth_.get(), mass_kg)
                                : case_mesh_damping_n_s_per_m(c, table, teeth_.get());
}

MeshLine::MeshLine(const SimulationCase& c, const StiffnessTable& table, const InternalLine& line,
                   double mass_kg)
    : table_(&table),
      model_(&c.model),
      gears_(&c.gears),
      layout_(line.pitch_point_m, line.planet_base_radius_m, line.base_pitch_m, line.start_m,
              line.end_m, c.model.coast_phase) {
  rb1_ = line.planet_base_radius_m;
  rb2_ = line.ring_base_radius_m;
  backlash_ = c.gears.backlash_m;
  // The friction's lever arms X and lp - X of an external pair do not hold
  // here (both tangent points on one side): the caller refuses friction.
  lp_ = line.tangent_points_m;
  x_pitch_ = line.pitch_point_m;
  xs_ = layout_.start_m();
  xe_ = layout_.end_m();
  sin_a_ = std::sin(line.pressure_angle_rad);
  cos_a_ = std::cos(line.pressure_angle_rad);
  smoothing_speed_ = c.model.friction_smoothing_speed_m_s;
  face_width_ = c.gears.face_width_m;
  kh_ = hertz_stiffness(c.gears);
  read_model_settings(c);
  if (std::any_of(c.faults.begin(), c.faults.end(),
                  [](const ToothFault& f) { return f.state.kind == ToothKind::missing; })) {
    absent_a_.assign(static_cast<std::size_t>(c.gears.teeth2), 0);
    absent_b_.assign(static_cast<std::size_t>(c.gears.teeth1), 0);
    for (const ToothFault& f : c.faults) {
      if (f.state.kind != ToothKind::missing) continue;
      std::vector<char>& gear = f.gear == Gear::one ? absent_b_ : absent_a_;
      gear.at(static_cast<std::size_t>(f.tooth)) = 1;
    }
  }
  const double mean_k = constant_k_ > 0.0 ? constant_k_ : line.mean_stiffness_n_per_m;
  mesh_damping_ = c.model.mesh_damping_ratio > 0.0
                      ? viscous_mesh_damping_n_s_per_m(c.model.mesh_damping_ratio, mean_k, mass_kg)
                      : 0.0;
}

double varying_friction_coefficient(const ModelOptions& model, double face_width_m,
                                    double normal_force_n, double vs, double ve) {
  switch (model.friction_law) {
    case FrictionLaw::constant:
      break;
    case FrictionLaw::benedict_kelley:
      return benedict_kelley_coefficient(model.benedict_kelley, normal_force_n / face_width_m, vs,
                                         ve);
    case FrictionLaw::table:
      return table_friction_coefficient(model.friction_table, slide_to_roll_ratio(vs, ve));
  }
  return model.friction_coefficient;
}

double MeshLine::least_gap_m(Region line, double theta1) const {
  return least_pair_gap_m(*gaps_, layout_, line, theta1);
}

int MeshLine::event_values(const MeshMotion& q, const Mode& m, const ContactMemory& d,
                           double* g) const {
  if (m.region == Region::free) {
    const double sv = s(q);
    // Region (2) ends where (31) makes delta positive on either line; with
    // gaps, where it passes the least gap of the line's pairs (a pair that
    // enters the segment already pressed in ends it at its entry).
    if (gaps_) {
      g[0] = backlash_ + least_gap_m(Region::n1, q.theta_a_rad) - sv;
      g[1] = sv + backlash_ + least_gap_m(Region::n2, q.theta_a_rad);
      return 2;
    }
    g[0] = backlash_ - sv;
    g[1] = sv + backlash_;
    return 2;
  }
  return contact_event_values(q, m, d, g);
}

int MeshLine::line_event_values(Region line, const PlanarMeshMotion& q, const Mode& m,
                                const ContactMemory& d, double* g) const {
  if (m.region == Region::free) {
    g[0] = -contact_value(line, q);
    return 1;
  }
  return contact_event_values(q, m, d, g);
}

template <typename Motion>
int MeshLine::contact_event_values(const Motion& q, const Mode& m, const ContactMemory& d,
                                   double* g) const {
  const double dl = delta(m.region, q);
  // With gaps the contact ends where the last touching pair lets go, which
  // the pairs' own values below locate.
  g[0] = gaps_ ? 1.0 : dl;
  // (42): the first and last loaded pair stay in [X_start, X_end], the
  // neighbours outside it. Each position is ref + k t0 for its own k, as
  // MeshLayout::loaded computes it: (ref + k t0) - t0 rounds differently, and
  // far from theta1 = 0 (|ref| of metres after a long run) the two could
  // disagree about a pair at the edge, which then enters a step late.
  const double ref = layout_.reference_m(m.region, q.theta_a_rad);
  const double first = layout_.position_m(ref, m.k_first);
  const double last = layout_.position_m(ref, m.k_first + m.count - 1);
  g[1] = first - xs_;
  g[2] = xs_ - layout_.position_m(ref, m.k_first - 1);
  g[3] = xe_ - last;
  g[4] = layout_.position_m(ref, m.k_first + m.count) - xe_;
  int n = 5;
  const double dl_rate = line_sign(m.region) * s_rate(m.region, q);
  const double x_rate = line_sign(m.region) * rb1_ * q.w_a_rad_per_s;
  const double slide = centres_slide(m.region, q);
  for (int j = 0; j < m.count; ++j) {
    const double x = layout_.position_m(ref, m.k_first + j);
    const StiffnessTable* table = m.table[j];
    append_part_events(table, m.part[j], x, g, n);
    const PairPenetration p = pair_penetration(m, j, x, dl, dl_rate, x_rate);
    const double dk = p.delta_m;
    const double dk_rate = p.rate_m_s;
    if (gaps_ && !append_gap_events(m.touching[j], m.zone[j], kinks_, x, dk, g, n)) {
      continue;
    }
    // A smoothed sign, one taken per stage, or a helical pair's face sum
    // (continuous through the pitch point) has no switch to locate: the value stays positive.
    g[n++] = smoothing_speed_ > 0.0 || m.slip_per_stage || face_friction_
                 ? 1.0
                 : m.slip[j] * pair_sliding(q, x, slide);
    const double push = push_sign_function(table, m.part[j], x, m.count, d, dk, dk_rate);
    g[n++] = m.clipped[j] ? -push : push;
  }
  return n;
}

// A function with the sign and the zeros of F + G of one pair. With D
// proportional to the pair's own Ke, F + G = Ke delta (1 + (D/K) d(delta)/dt)
// and the positive factor Ke need not be evaluated.
// A pair that cannot carry (a missing tooth, no contact) never pushes nor switches: 1.
double MeshLine::push_sign_function(const StiffnessTable* table, int part, double x, int count,
                                    const ContactMemory& d, double dl, double dl_rate) const {
  if (!carries(table, part)) return 1.0;
  if (damping_on_current_pair_) {
    return dl * (1.0 + d.damping_per_stiffness_s_m * dl_rate);
  }
  double ke = 0.0;
  double dke = 0.0;
  pair_stiffness(*table, part, x, count, ke, dke);
  return elastic_force(ke, dl) + hertzian_damping_force(damping_factor(d, ke), dl, dl_rate);
}

Mode MeshLine::classify_geometry(const MeshMotion& q) const {
  const Mode drive = line_contact(Region::n1, q);
  return drive.region != Region::free ? drive : line_contact(Region::n2, q);
}

Mode MeshLine::classify_line(Region line, const PlanarMeshMotion& q) const {
  return line_contact(line, q);
}

template <typename Motion>
Mode MeshLine::line_contact(Region line, const Motion& q) const {
  Mode m;
  const double dl = delta(line, q);
  if (gaps_) {
    // The line is in contact where one of its pairs is pressed in: delta -
    // e_k > 0 (the backlash check of the case keeps the two lines of the
    // torsional model from both touching), which is where contact_value > 0.
    const double ref = layout_.reference_m(line, q.theta_a_rad);
    const LoadedRange range = layout_.loaded(ref);
    bool any = false;
    for (int j = 0; j < range.count; ++j) {
      const int k = range.k_first + j;
      const double x = layout_.position_m(ref, k);
      m.touching[j] = dl - gaps_->gap_m(line, k, x) > 0.0;
      m.zone[j] = gap_zone(kinks_, x);
      any = any || m.touching[j];
    }
    if (!any) return Mode{};
    m.region = line;
    m.k_first = range.k_first;
    m.count = range.count;
    set_parts(q, m);
    return m;
  }
  if (!(dl > 0.0)) return m;
  m.region = line;
  const LoadedRange range = layout_.loaded(layout_.reference_m(line, q.theta_a_rad));
  m.k_first = range.k_first;
  m.count = range.count;
  set_parts(q, m);
  return m;
}

template <typename Motion>
void MeshLine::set_parts(const Motion& q, Mode& m) const {
  for (int j = 0; j < m.count; ++j) {
    const StiffnessTable* table = pair_table(m.region, m.k_first + j);
    m.table[j] = table;
    // Parts: a faulted tooth's table, or a healthy table cut into parts (an
    // internal mesh's ISO zones, a helical pair's kinks); a table of one part has only part 0.
    if (!teeth_ && table_->part_count() <= 1) continue;
    m.part[j] = table != nullptr && table->part_count() > 1
                    ? table->part_of(std::clamp(pair_position(m, q, j), xs_, xe_))
                    : 0;
  }
}

Mode MeshLine::carry_pair_signs(const MeshMotion& q, const Mode& old, const Mode& now,
                                const ContactMemory& d) const {
  const int shift = now.k_first - old.k_first;
  Mode probe = now;
  for (int j = 0; j < now.count; ++j) {
    const int i = j + shift;
    if (i >= 0 && i < old.count) {
      probe.slip[static_cast<std::size_t>(j)] = old.slip[static_cast<std::size_t>(i)];
      probe.clipped[static_cast<std::size_t>(j)] = old.clipped[static_cast<std::size_t>(i)];
    }
  }
  std::array<double, kMaxMeshEvents> g{};
  const int n = event_values(q, probe, d, g.data());
  return std::all_of(g.begin(), g.begin() + n, [](double v) { return v >= 0.0; }) ? probe : now;
}

template <typename Motion>
void MeshLine::classify_forces(const Motion& q, const ContactMemory& d, Mode& m) const {
  if (m.region == Region::free) return;
  const double dl = delta(m.region, q);
  const double dl_rate = line_sign(m.region) * s_rate(m.region, q);
  const double x_rate = line_sign(m.region) * rb1_ * q.w_a_rad_per_s;
  const double slide = centres_slide(m.region, q);
  for (int j = 0; j < m.count; ++j) {
    const double x = pair_position(m, q, j);
    m.slip[j] = pair_sliding(q, x, slide) >= 0.0 ? 1.0 : -1.0;
    const PairPenetration p = pair_penetration(m, j, x, dl, dl_rate, x_rate);
    m.clipped[j] =
        push_sign_function(m.table[j], m.part[j], x, m.count, d, p.delta_m, p.rate_m_s) < 0.0;
  }
}

OnsetDamping onset_damping(const ModelOptions& model, DampingUpdate update, double approach_m_s) {
  OnsetDamping onset;
  onset.impact_speed_m_s = std::max(approach_m_s, kSmallestImpactSpeed_m_s);
  // DampingUpdate: e and D of (32),(33) from this impact's Vi, from the
  // case's reference speed, or none.
  const double speed =
      update == DampingUpdate::frozen ? model.damping_reference_speed_m_s : onset.impact_speed_m_s;
  onset.restitution = restitution_coefficient(model.restitution, speed);
  onset.damping_per_stiffness_s_m =
      update == DampingUpdate::off
          ? 0.0
          : damping_factor_per_stiffness(model.damping_form, onset.restitution, speed);
  return onset;
}

template <typename Motion>
MeshLine::Onset MeshLine::damping_at_onset(const Motion& q, const Mode& m) const {
  Onset onset{};
  const double line_rate = line_sign(m.region) * s_rate(m.region, q);
  double approach = line_rate;
  if (gaps_) {
    // The fastest approach among the pairs that touch, each at its own
    // penetration rate.
    const double dl = delta(m.region, q);
    const double x_rate = line_sign(m.region) * rb1_ * q.w_a_rad_per_s;
    approach = -std::numeric_limits<double>::infinity();
    for (int j = 0; j < m.count; ++j) {
      if (!m.touching[j]) continue;
      approach = std::max(
          approach, pair_penetration(m, j, pair_position(m, q, j), dl, line_rate, x_rate).rate_m_s);
    }
  }
  const OnsetDamping damping = onset_damping(*model_, damping_update_, approach);
  onset.impact_speed_m_s = damping.impact_speed_m_s;
  onset.restitution = damping.restitution;
  ContactMemory& d = onset.damping;
  d.damping_per_stiffness_s_m = damping.damping_per_stiffness_s_m;
  if (model_->damping_stiffness == DampingStiffness::hertz) {
    d.frozen_stiffness_n_per_m = kh_;
  } else if (m.count > 0) {
    // The loaded pair nearest the pitch point; with faults, among the pairs
    // that carry (none: the stiffness stays 0, as nothing pushes).
    int nearest = -1;
    for (int j = 0; j < m.count; ++j) {
      if (!carries(m.table[j], m.part[j])) continue;
      if (nearest < 0 || std::fabs(pair_position(m, q, j) - x_pitch_) <
                             std::fabs(pair_position(m, q, nearest) - x_pitch_)) {
        nearest = j;
      }
    }
    if (nearest >= 0) {
      double ke = 0.0;
      double dke = 0.0;
      pair_stiffness(*m.table[nearest], m.part[nearest], pair_position(m, q, nearest), m.count, ke,
                     dke);
      d.frozen_stiffness_n_per_m = ke;
    }
  }
  return onset;
}

template <typename Motion>
void MeshLine::add_stored_energy(const Motion& q, const Mode& m, ElasticEnergy& u) const {
  if (m.region == Region::free) return;
  const double line_delta = delta(m.region, q);
  for (int j = 0; j < m.count; ++j) {
    const double x = pair_position(m, q, j);
    // A pair whose gap is open stores nothing; one that touches, by its own
    // penetration.
    if (gaps_ && !m.touching[j]) continue;
    const double dl = pair_penetration(m, j, x, line_delta, 0.0, 0.0).delta_m;
    if (constant_k_ > 0.0) {
      u.j[index_of(Term::hertz)] += 0.5 * constant_k_ / m.count * dl * dl;
      continue;
    }
    const StiffnessTable* table = m.table[j];
    // A missing tooth stores nothing, nor a pair without contact over a fault across the face.
    if (!carries(table, m.part[j])) continue;
    // At a fault's edge, the side of the pair's part: the ledger books the jump between the two
    // sides at the event.
    const Compliances c =
        table->part_count() > 1
            ? table->compliance_in_part(
                  std::clamp(x, table->part_start_m(m.part[j]), table->part_end_m(m.part[j])),
                  m.part[j])
            : table->compliance(std::clamp(x, xs_, xe_));
    if (swept_) {
      // A helical pair: 1/2 Ke delta^2 with Ke as the force reads it, split
      // by the terms' shares of the compliance (helical_pair_table), whose
      // sum has a pole where a contact line enters the face.
      double ke = 0.0;
      double dke = 0.0;
      pair_stiffness(*table, m.part[j], x, m.count, ke, dke);
      const double total = c.total_m_per_n();
      for (std::size_t i = 0; i < kTermCount; ++i) {
        u.j[i] += 0.5 * ke * dl * dl * (c.m_per_n[i] / total);
      }
      continue;
    }
    // (30) F = Ke delta with 1/Ke the total compliance of (29).
    const ElasticEnergy pair = pair_energy(c, dl / c.total_m_per_n());
    for (std::size_t i = 0; i < kTermCount; ++i) u.j[i] += pair.j[i];
  }
}

template <typename Motion>
double MeshLine::elastic_energy_j(const Motion& q, const Mode& m) const {
  if (m.region == Region::free) return 0.0;
  const double dl = delta(m.region, q);
  double u = 0.0;
  for (int j = 0; j < m.count; ++j) {
    // A pair that carries nothing (a missing tooth, no contact over a fault
    // across the face, an open gap) stores nothing.
    if (!carries(m.table[j], m.part[j]) || (gaps_ && !m.touching[j])) continue;
    const double x = pair_position(m, q, j);
    const double dk = pair_penetration(m, j, x, dl, 0.0, 0.0).delta_m;
    double ke = 0.0;
    double dke = 0.0;
    pair_stiffness(*m.table[j], m.part[j], x, m.count, ke, dke);
    u += 0.5 * ke * dk * dk;
  }
  return u;
}

std::optional<std::array<double, kTermCount>> MeshLine::term_energy_bound() const {
  if (gaps_ || constant_k_ > 0.0) return std::nullopt;
  std::array<double, kTermCount> bound{};
  std::vector<const StiffnessTable*> tables{table_};
  if (teeth_) {
    for (const Region line : {Region::n1, Region::n2}) {
      for (int i = 0; i < gears_->teeth1; ++i) {
        for (int w = 0; w < gears_->teeth2; ++w) {
          const StiffnessTable* t = teeth_->table_of_teeth(i, w, line);
          if (t != nullptr && std::find(tables.begin(), tables.end(), t) == tables.end()) {
            tables.push_back(t);
          }
        }
      }
    }
  }
  for (const StiffnessTable* t : tables) {
    for (int part = 0; part < t->part_count(); ++part) {
      if (!t->part_in_contact(part)) continue;
      const bool whole = t->part_count() == 1;
      const double lo = whole ? xs_ : t->part_start_m(part);
      const double hi = whole ? xe_ : t->part_end_m(part);
      const int samples = 16 * t->pieces();
      for (int j = 0; j <= samples; ++j) {
        const double x = std::min(lo + (hi - lo) * j / samples, hi);
        const Compliances at = whole ? t->compliance(x) : t->compliance_in_part(x, part);
        const double total = at.total_m_per_n();
        for (std::size_t i = 0; i < kTermCount; ++i) {
          bound[i] = std::max(bound[i], 1.05 * 0.5 * at.m_per_n[i] / (total * total));
        }
      }
    }
  }
  return bound;
}

// The two motions a mesh is seen through: the torsional bodies' and the planar model's.
template void MeshLine::classify_forces(const MeshMotion&, const ContactMemory&, Mode&) const;
template void MeshLine::classify_forces(const PlanarMeshMotion&, const ContactMemory&, Mode&) const;
template MeshLine::Onset MeshLine::damping_at_onset(const MeshMotion&, const Mode&) const;
template MeshLine::Onset MeshLine::damping_at_onset(const PlanarMeshMotion&, const Mode&) const;
template void MeshLine::add_stored_energy(const MeshMotion&, const Mode&, ElasticEnergy&) const;
template void MeshLine::add_stored_energy(const PlanarMeshMotion&, const Mode&,
                                          ElasticEnergy&) const;
template double MeshLine::elastic_energy_j(const PlanarMeshMotion&, const Mode&) const;

}  // namespace gearimpact
