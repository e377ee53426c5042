#include "gearimpact/dynamics/planar.hpp"

#include <algorithm>
#include <array>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "adaptive_loop.hpp"
#include "event_location.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/drive.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "rk4_dense.hpp"
#include "run.hpp"
#include "stall.hpp"
#include "step_methods.hpp"

namespace gearimpact {

namespace {

// The state: positions, velocities (in the same order), then the ledger's
// integrals of the powers.
enum P : std::size_t {
  kX1,
  kY1,
  kT1,
  kX2,
  kY2,
  kT2,
  kTm,
  kTl,
  kVelocity,  // + a position's index
  kWork = 2 * kVelocity,
  kHertzLoss,
  kSlidingLoss,
  kParametric,
  kBearingLoss,
  kShaftLoss,
  kMeshDamperLoss,
  kSize
};
using Y = std::array<double, kSize>;

Y to_vector(const PlanarState& s) {
  Y y{};
  const double q[kVelocity] = {s.x1_m, s.y1_m,       s.theta1_rad,      s.x2_m,
                               s.y2_m, s.theta2_rad, s.theta_motor_rad, s.theta_load_rad};
  const double v[kVelocity] = {s.vx1_m_s, s.vy1_m_s,      s.w1_rad_per_s,      s.vx2_m_s,
                               s.vy2_m_s, s.w2_rad_per_s, s.w_motor_rad_per_s, s.w_load_rad_per_s};
  for (std::size_t i = 0; i < kVelocity; ++i) {
    y[i] = q[i];
    y[kVelocity + i] = v[i];
  }
  return y;
}

// The state of y; without shafts the motor and the load are the gears.
PlanarState to_state(const Y& y, bool shafts) {
  PlanarState s;
  s.x1_m = y[kX1];
  s.y1_m = y[kY1];
  s.theta1_rad = y[kT1];
  s.x2_m = y[kX2];
  s.y2_m = y[kY2];
  s.theta2_rad = y[kT2];
  s.theta_motor_rad = y[kTm];
  s.theta_load_rad = y[kTl];
  s.vx1_m_s = y[kVelocity + kX1];
  s.vy1_m_s = y[kVelocity + kY1];
  s.w1_rad_per_s = y[kVelocity + kT1];
  s.vx2_m_s = y[kVelocity + kX2];
  s.vy2_m_s = y[kVelocity + kY2];
  s.w2_rad_per_s = y[kVelocity + kT2];
  s.w_motor_rad_per_s = y[kVelocity + kTm];
  s.w_load_rad_per_s = y[kVelocity + kTl];
  if (!shafts) {
    s.theta_motor_rad = s.theta1_rad;
    s.theta_load_rad = s.theta2_rad;
    s.w_motor_rad_per_s = s.w1_rad_per_s;
    s.w_load_rad_per_s = s.w2_rad_per_s;
  }
  return s;
}

constexpr std::array<Region, 2> kSides{Region::n1, Region::n2};
std::size_t side_index(Region side) {
  return side == Region::n1 ? 0 : 1;
}

// What the right-hand side reports beside the derivatives.
struct Forces {
  std::array<double, 2> normal_n{};  // summed over each side's pairs
  std::array<double, 2> penetration_m{};
  double friction_n = 0.0;  // Ff of (35)-(38) summed over both sides' pairs
  // Each side's stored energy in the mode, PlanarSystem::mesh_energy's sum
  // (so that the step's ledger takes it from the next step's first stage).
  std::array<double, 2> mesh_energy_j{};
};

// What stays constant during a step on one side, as the torsional Mode does:
// whether the side is in contact, its loaded pairs, the part of each pair's
// table cut at a fault's edges, with [modifications] whether each pair's own
// penetration is positive and the zone of its gap between the reliefs' kinks,
// each pair's friction sign and whether its normal force is clipped. The
// right-hand side is smooth while every side's holds; a change is an event,
// located and stepped onto.
struct SideMode {
  bool contact = false;
  LoadedRange range;
  // Each loaded pair's table (PlanarSystem::pair_table, nullptr: a missing
  // tooth), found once a mode: finding it takes integer remainders, which the
  // right-hand side would otherwise pay for every pair at every stage.
  std::array<const StiffnessTable*, kMaxPairs> table{};
  std::array<int, kMaxPairs> part{};
  // With gaps only (without, every pair of a side in contact touches).
  std::array<bool, kMaxPairs> touching{};
  std::array<int, kMaxPairs> zone{};
  std::array<double, kMaxPairs> slip{};
  std::array<bool, kMaxPairs> clipped{};
  // For one step after the sliding of a pair turned back at once after its
  // reversal (the contact would stick, which an exact switch cannot follow):
  // each stage takes the friction signs from its own state, unlocated.
  bool slip_per_stage = false;
};
using PlanarMode = std::array<SideMode, 2>;

// The event values of a side: its contact, the four bounds of its loaded
// pairs, and per pair the two ends of its part, with gaps its own penetration
// and the two kinks around it, its sliding speed and its push; of both sides.
constexpr int kSideEvents = 5 + 7 * kMaxPairs;
using PlanarEvents = std::array<double, 2 * kSideEvents>;

// A system of the step methods (step_methods.hpp): both lines of action,
// each with its own mode and contact memory.
class PlanarSystem {
 public:
  using StateType = Y;
  using ModeType = PlanarMode;
  using MemoryType = std::array<ContactMemory, 2>;
  using EventsType = PlanarEvents;
  using ForcesType = Forces;

  // driver_theta0: with a kinematic driver, the angle its body starts from.
  PlanarSystem(const SimulationCase& c, const StiffnessTable& table, const PlanarMounting& m,
               double driver_theta0)
      : c_(c), m_(m), table_(table), layout_(c.gears, c.model.coast_phase) {
    const GearPair& g = c.gears;
    rb1_ = base_radius(g, Gear::one);
    rb2_ = base_radius(g, Gear::two);
    j1_ = moment_of_inertia(g, Gear::one);
    j2_ = moment_of_inertia(g, Gear::two);
    // The inverse masses, so that each stage multiplies: a division's latency
    // sits on the path from one RK4 stage to the next.
    inverse_mass_ = {1.0 / m.mass_kg[0],
                     1.0 / m.mass_kg[0],
                     1.0 / j1_,
                     1.0 / m.mass_kg[1],
                     1.0 / m.mass_kg[1],
                     1.0 / j2_,
                     m.shafts ? 1.0 / m.motor_inertia_kg_m2 : 0.0,
                     m.shafts ? 1.0 / m.load_inertia_kg_m2 : 0.0};
    backlash_ = g.backlash_m;
    lp_ = line_of_action_length(g);
    xs_ = layout_.start_m();
    xe_ = layout_.end_m();
    const double a = operating_pressure_angle(g);
    sin_a_ = std::sin(a);
    cos_a_ = std::cos(a);
    constant_k_ = c.model.mesh_stiffness == MeshStiffnessMode::constant
                      ? c.model.constant_mesh_stiffness_n_per_m
                      : 0.0;
    MeshTeeth teeth = mesh_teeth(c, table, constant_k_);
    teeth_ = std::move(teeth.tables);
    gaps_ = std::move(teeth.gaps);
    kinks_ = std::move(teeth.kinks_m);
    if (!gaps_ && constant_k_ == 0.0) {
      // A pair stores 0.5 delta^2 c / c_total^2 in a term of compliance c
      // (F = delta / c_total): the factor's largest value over every table a
      // pair can take (with faults, each pair of teeth's) and each part it
      // carries in, sampled 16 times on each of the table's pieces (smooth
      // polynomials, which move by far less than the 5 % added between two
      // samples). A gap can be negative (pitch, thickness errors): a pair's
      // delta may then exceed the line's, and the bound is not kept with gaps.
      std::vector<const StiffnessTable*> tables{&table};
      if (teeth_) {
        for (const Region side : kSides) {
          for (int i = 0; i < g.teeth1; ++i) {
            for (int w = 0; w < g.teeth2; ++w) {
              const StiffnessTable* t = teeth_->table_of_teeth(i, w, side);
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
            for (std::size_t q = 0; q < kTermCount; ++q) {
              term_bound_[q] =
                  std::max(term_bound_[q], 1.05 * 0.5 * at.m_per_n[q] / (total * total));
            }
          }
        }
      }
      bounded_ = true;
    }
    mesh_damping_ = case_mesh_damping_n_s_per_m(c, table, teeth_.get());
    drag_ = c.torque2.kind == Torque::Kind::drag;
    damping_update_ = resolved_damping_update(c);
    driven_ = c.torque1.kind == Torque::Kind::prescribed_speed;
    // torque1 acts on the motor with shafts, so the driver turns it (and a
    // controller or a motor reads its motion).
    driven_index_ = m.shafts ? kTm : kT1;
    driver_theta0_ = driver_theta0;
    if (c.torque1.kind == Torque::Kind::speed_controlled) {
      controller_ = std::make_shared<const SpeedController>(c, driver_theta0);
    }
    induction_ = c.torque1.kind == Torque::Kind::induction_motor;
    // The Lagrangian force of a time-varying stiffness (with a constant one
    // the two forces are the same).
    lagrangian_ = c.model.mesh_force == MeshForce::lagrangian && constant_k_ == 0.0;
    options_ = gaps_ || mesh_damping_ > 0.0 || driven_ || drag_ || controller_ || induction_ ||
               lagrangian_;
  }

  // A kinematic driver's body (the pinion, the motor with shafts) where its
  // closed form puts it at t.
  void impose_driver(double t, Y& y) const {
    if (!driven_) return;
    const DriverMotion d = driver_motion(c_.torque1, driver_theta0_, t);
    y[driven_index_] = d.theta_rad;
    y[kVelocity + driven_index_] = d.speed_rad_per_s;
  }

  double rb1() const { return rb1_; }
  double rb2() const { return rb2_; }
  // Whether a kinematic driver sets a body's angle and speed after each step.
  bool driven() const { return driven_; }
  // Whether the mesh force is the Lagrangian one (model.mesh_force).
  bool lagrangian() const { return lagrangian_; }
  // J1, whose kinetic energy pays a jump of the stored energy (Lagrangian).
  double pinion_inertia() const { return j1_; }
  // Whether the driver holds the pinion's speed (it then pays such a jump).
  bool drives_pinion() const { return driven_ && driven_index_ == kT1; }

  // n of a side, (sin a, cos a) on the drive line, (-sin a, cos a) on the coast line.
  std::array<double, 2> normal(Region side) const {
    return {side == Region::n1 ? sin_a_ : -sin_a_, cos_a_};
  }
  // delta_d = s_d - B, delta_c = -s_c - B and their rates.
  std::pair<double, double> penetration(Region side, const Y& y) const {
    const auto n = normal(side);
    const double s =
        rb1_ * y[kT1] - rb2_ * y[kT2] + (y[kX1] - y[kX2]) * n[0] + (y[kY1] - y[kY2]) * n[1];
    const double rate = rb1_ * y[kVelocity + kT1] - rb2_ * y[kVelocity + kT2] +
                        (y[kVelocity + kX1] - y[kVelocity + kX2]) * n[0] +
                        (y[kVelocity + kY1] - y[kVelocity + kY2]) * n[1];
    const double sign = line_sign(side);
    return {sign * s - backlash_, sign * rate};
  }

  // Pair j of the side's mode m at X with the line's penetration dl and its
  // rate: its own penetration and rate, less the gap of its teeth with
  // [modifications]. The gap's branch is that of the zone the mode holds: a
  // stage state of a step that ends on a kink sees the zone's own gap.
  PairPenetration pair_penetration(Region side, const SideMode& m, int j, double x, double dl,
                                   double dl_rate, double x_rate) const {
    if (!gaps_) return {dl, dl_rate, 0.0};
    return pair_penetration_with_gap(*gaps_, kinks_, m.zone[j], side, m.range.k_first + j, x, dl,
                                     dl_rate, x_rate, xs_, xe_);
  }

  // The largest penetration of a pair on `side`: the line's, less the least
  // gap of its pairs with [modifications]. The side is in contact while it is
  // positive, which is while one of its pairs touches.
  double contact_value(Region side, const Y& y) const {
    const double dl = penetration(side, y).first;
    return gaps_ ? dl - least_pair_gap_m(*gaps_, layout_, side, y[kT1]) : dl;
  }

  // The table of pair k on `side`: the healthy one, or with faults that of
  // the pair's teeth (nullptr: a missing tooth, the pair carries nothing).
  const StiffnessTable* pair_table(Region side, int k) const {
    return teeth_ ? teeth_->table(side, k) : &table_;
  }

  // Whether pair j of the side's mode m can carry in its part: not with a
  // missing tooth, nor over a fault across the whole face.
  static bool carries(const SideMode& m, int j) {
    return m.table[j] != nullptr && m.table[j]->part_in_contact(m.part[j]);
  }

  // Ke of pair j of the side's mode m at X and dKe/dX, from its part
  // (SideMode::part), continued along its tangent beyond the segment or the
  // part (pair_stiffness_continued): a stage state of a step that ends on a
  // pair's entry, exit or a fault's edge reaches a hair past it.
  std::pair<double, double> pair_stiffness(const SideMode& m, int j, double x) const {
    if (constant_k_ > 0.0) return {constant_k_ / m.range.count, 0.0};
    const StiffnessTable& table = *m.table[j];
    const int part = m.part[j];
    const StiffnessAndDerivative s =
        table.part_count() > 1 ? pair_stiffness_continued(table, part, x, table.part_start_m(part),
                                                          table.part_end_m(part))
                               : pair_stiffness_continued(table, -1, x, xs_, xe_);
    return {s.stiffness_n_per_m, s.derivative_n_per_m2};
  }

  // Whether pair j of the side's mode m carries a force: it can carry (its
  // table, its part) and, with gaps, touches.
  bool pair_loaded(const SideMode& m, int j) const {
    return carries(m, j) && (!gaps_ || m.touching[j]);
  }

  // The mesh's stored energy of `side` at y in the side's mode m: each pair
  // that touches by its own penetration.
  double mesh_energy(Region side, const Y& y, const SideMode& m) const {
    if (!m.contact) return 0.0;
    const double dl = penetration(side, y).first;
    const double ref = layout_.reference_m(side, y[kT1]);
    double u = 0.0;
    for (int j = 0; j < m.range.count; ++j) {
      if (!pair_loaded(m, j)) continue;
      const double x = layout_.position_m(ref, m.range.k_first + j);
      const double dk = pair_penetration(side, m, j, x, dl, 0.0, 0.0).delta_m;
      u += 0.5 * pair_stiffness(m, j, x).first * dk * dk;
    }
    return u;
  }

  // The mesh's stored energy of both sides by term of (29), as the
  // torsional ledger reports it (F = Ke delta of each pair inside the segment).
  ElasticEnergy mesh_terms(const Y& y, const PlanarMode& mode) const {
    ElasticEnergy u;
    for (const Region side : kSides) {
      const SideMode& m = mode[side_index(side)];
      if (!m.contact) continue;
      const double line_dl = penetration(side, y).first;
      const double ref = layout_.reference_m(side, y[kT1]);
      for (int j = 0; j < m.range.count; ++j) {
        if (!pair_loaded(m, j)) continue;
        const double x = layout_.position_m(ref, m.range.k_first + j);
        const double dl = pair_penetration(side, m, j, x, line_dl, 0.0, 0.0).delta_m;
        if (constant_k_ > 0.0) {
          u.j[index_of(Term::hertz)] += 0.5 * constant_k_ / m.range.count * dl * dl;
          continue;
        }
        const StiffnessTable& table = *m.table[j];
        // At a fault's edge, the side of the pair's part: the jump between
        // the two is booked at the event.
        const Compliances c =
            table.part_count() > 1
                ? table.compliance_in_part(
                      std::clamp(x, table.part_start_m(m.part[j]), table.part_end_m(m.part[j])),
                      m.part[j])
                : table.compliance(std::clamp(x, xs_, xe_));
        const ElasticEnergy pair = pair_energy(c, dl / c.total_m_per_n());
        for (std::size_t i = 0; i < kTermCount; ++i) u.j[i] += pair.j[i];
      }
    }
    return u;
  }

  // Whether a term's energy at y in the mode (mesh_terms) could exceed its
  // entry of `most`: not when the bound above stays below every entry, and
  // the ledger then need not evaluate the terms (most steps, once the
  // largest penetration has passed).
  bool terms_may_exceed(const Y& y, const PlanarMode& mode,
                        const std::array<double, kTermCount>& most) const {
    if (!bounded_) return true;
    double squares = 0.0;  // delta^2 summed over the loaded pairs
    for (const Region side : kSides) {
      const SideMode& m = mode[side_index(side)];
      if (!m.contact) continue;
      const double dl = penetration(side, y).first;
      squares += m.range.count * dl * dl;
    }
    for (std::size_t i = 0; i < kTermCount; ++i) {
      if (term_bound_[i] * squares > most[i]) return true;
    }
    return false;
  }

  // The side's contact, loaded pairs, their parts and with gaps which of
  // them touch and their gaps' zones at y (the forces' signs are
  // classify_forces's, once the contact memory is set).
  SideMode classify_geometry(Region side, const Y& y) const {
    SideMode m;
    m.contact = contact_value(side, y) > 0.0;
    const double dl = penetration(side, y).first;
    const double ref = layout_.reference_m(side, y[kT1]);
    m.range = layout_.loaded(ref);
    for (int j = 0; j < m.range.count; ++j) {
      const int k = m.range.k_first + j;
      const double x = layout_.position_m(ref, k);
      if (gaps_) {
        // As contact_value: the side is in contact exactly when one of these touches.
        m.touching[j] = dl - gaps_->gap_m(side, k, x) > 0.0;
        m.zone[j] = gap_zone(kinks_, x);
      }
      const StiffnessTable* table = pair_table(side, k);
      m.table[j] = table;
      m.part[j] =
          table != nullptr && table->part_count() > 1 ? table->part_of(std::clamp(x, xs_, xe_)) : 0;
    }
    return m;
  }

  // The friction sign and clipping of each pair of the side's mode m at y.
  void classify_forces(Region side, const Y& y, const ContactMemory& memory, SideMode& m) const {
    if (!m.contact) return;
    const SideMotion sm = side_motion(side, y);
    for (int j = 0; j < m.range.count; ++j) {
      const PairMotion p = pair_motion(side, y, sm, memory, m, j, true);
      m.slip[j] = p.sliding_m_s >= 0.0 ? 1.0 : -1.0;
      m.clipped[j] = p.push_n < 0.0;
    }
  }

  // The values whose sign changes end the mode (each >= 0 while it holds, as
  // GearSystem::event_values): per side, its contact_value (contact begins or
  // ends), and in contact the bounds of its loaded pairs (42) and per pair
  // the ends of its part, with gaps its own penetration (it touches or lets
  // go) and the kinks of its gap around it, its sliding speed times its sign
  // and its push F + G (clipping). Returns how many are set.
  int event_values(const Y& y, const PlanarMode& mode, const std::array<ContactMemory, 2>& memory,
                   PlanarEvents& g) const {
    int n = 0;
    for (const Region side : kSides) {
      const std::size_t i = side_index(side);
      const SideMode& m = mode[i];
      if (!m.contact) {
        g[n++] = -contact_value(side, y);
        continue;
      }
      const SideMotion sm = side_motion(side, y);
      const double dl = sm.dl;
      const double dl_rate = sm.dl_rate;
      // With gaps the contact ends where the last touching pair lets go,
      // which the pairs' own values below locate.
      g[n++] = gaps_ ? 1.0 : dl;
      // Each position is ref + k t0 for its own k, as MeshLayout::loaded computes it.
      const double ref = sm.reference_m;
      const int first = m.range.k_first;
      const int last = first + m.range.count - 1;
      g[n++] = layout_.position_m(ref, first) - xs_;
      g[n++] = xs_ - layout_.position_m(ref, first - 1);
      g[n++] = xe_ - layout_.position_m(ref, last);
      g[n++] = layout_.position_m(ref, last + 1) - xe_;
      const double x_rate = line_sign(side) * rb1_ * y[kVelocity + kT1];
      for (int j = 0; j < m.range.count; ++j) {
        const StiffnessTable* table = m.table[j];
        const double x = layout_.position_m(ref, first + j);
        append_part_events(table, m.part[j], x, g.data(), n);
        if (gaps_) {
          const double dk = pair_penetration(side, m, j, x, dl, dl_rate, x_rate).delta_m;
          if (!append_gap_events(m.touching[j], m.zone[j], kinks_, x, dk, g.data(), n)) continue;
        }
        const PairMotion p = pair_motion(side, y, sm, memory[i], m, j, true);
        // A smoothed sign has no switch to locate.
        g[n++] = c_.model.friction_smoothing_speed_m_s > 0.0 || m.slip_per_stage
                     ? 1.0
                     : m.slip[j] * p.sliding_m_s;
        g[n++] = m.clipped[j] ? -p.push_n : p.push_n;
      }
    }
    return n;
  }

  bool mode_holds(const Y& y, const PlanarMode& mode,
                  const std::array<ContactMemory, 2>& memory) const {
    PlanarEvents g;
    const int n = event_values(y, mode, memory, g);
    for (int i = 0; i < n; ++i) {
      if (g[i] < 0.0) return false;
    }
    return true;
  }

  double bearing_energy(const Y& y) const {
    return 0.5 * (m_.stiffness_x_n_per_m[0] * y[kX1] * y[kX1] +
                  m_.stiffness_y_n_per_m[0] * y[kY1] * y[kY1] +
                  m_.stiffness_x_n_per_m[1] * y[kX2] * y[kX2] +
                  m_.stiffness_y_n_per_m[1] * y[kY2] * y[kY2]);
  }
  double shaft_energy(const Y& y) const {
    if (!m_.shafts) return 0.0;
    const double dm = y[kTm] - y[kT1];
    const double dl = y[kTl] - y[kT2];
    return 0.5 *
           (m_.motor_stiffness_n_m_per_rad * dm * dm + m_.load_stiffness_n_m_per_rad * dl * dl);
  }
  double kinetic_energy(const Y& y) const {
    const double* v = &y[kVelocity];
    double e = m_.mass_kg[0] * (v[kX1] * v[kX1] + v[kY1] * v[kY1]) + j1_ * v[kT1] * v[kT1] +
               m_.mass_kg[1] * (v[kX2] * v[kX2] + v[kY2] * v[kY2]) + j2_ * v[kT2] * v[kT2];
    if (m_.shafts) {
      e += m_.motor_inertia_kg_m2 * v[kTm] * v[kTm] + m_.load_inertia_kg_m2 * v[kTl] * v[kTl];
    }
    return 0.5 * e;
  }

  // What every pair of a side shares at y: the line's penetration and its
  // rate, the reference position of the pair k = 0, and the centres' share
  // of the sliding speed: sign (u1' - u2') . t, t = e_z x n. The pinion's
  // flank moves along t at w1 X on the drive line and at -w1 X on the coast
  // line (there the contact lies at -X n2 from the pinion's base circle), so
  // the sliding speed w1 X - w2 (lp - X) the side's friction sign is taken
  // from counts the centres' relative speed along +t on N1 and along -t on
  // N2 (docs/vibration.md).
  struct SideMotion {
    double dl, dl_rate, reference_m, slide_of_centres_m_s;
  };
  SideMotion side_motion(Region side, const Y& y) const {
    const double* v = &y[kVelocity];
    const auto n = normal(side);
    const auto [dl, dl_rate] = penetration(side, y);
    return {dl, dl_rate, layout_.reference_m(side, y[kT1]),
            line_sign(side) * ((v[kX1] - v[kX2]) * -n[1] + (v[kY1] - v[kY2]) * n[0])};
  }

  // Pair j of the side's mode m at y: its X, its own penetration and rate
  // (the line's less its gap), Ke and dKe/dX, elastic force F, push F + G
  // (the normal force unless clipped) and sliding speed: (36)-(38) with the
  // centres' relative speed along the flanks' common tangent t = e_z x n,
  // the speed whose product with f N is the friction's loss
  // (docs/vibration.md). A pair that carries no force (a missing tooth, no
  // contact over a fault across the face, an open gap) pushes 1.
  struct PairMotion {
    bool carries = false;
    PairPenetration own{0.0, 0.0, 0.0};
    double x_m = 0.0, ke = 0.0, dke = 0.0, elastic_n = 0.0, push_n = 1.0, sliding_m_s = 0.0;
  };
  // With sign_only, push_n has the sign and zeros of F + G only: with D
  // proportional to the pair's own Ke, F + G = Ke delta (1 + (D/K) delta'),
  // and the positive Ke need not be read (the event values and the forces'
  // classification want no more); ke, dke and elastic_n are then not set.
  // kGaps false compiles out the gaps, for the right-hand side of a run
  // without them (motion<false>). sm: side_motion(side, y).
  template <bool kGaps = true>
  PairMotion pair_motion(Region side, const Y& y, const SideMotion& sm, const ContactMemory& memory,
                         const SideMode& m, int j, bool sign_only = false) const {
    const double* v = &y[kVelocity];
    const double dl = sm.dl;
    const double dl_rate = sm.dl_rate;
    const int k = m.range.k_first + j;
    PairMotion p;
    p.x_m = layout_.position_m(sm.reference_m, k);
    p.sliding_m_s = sliding_speed(v[kT1], v[kT2], p.x_m, lp_) + sm.slide_of_centres_m_s;
    if (!carries(m, j) || (kGaps && gaps_ && !m.touching[j])) return p;
    p.carries = true;
    p.own = kGaps
                ? pair_penetration(side, m, j, p.x_m, dl, dl_rate, line_sign(side) * rb1_ * v[kT1])
                : PairPenetration{dl, dl_rate, 0.0};
    const double dk = p.own.delta_m;
    const double dk_rate = p.own.rate_m_s;
    if (sign_only && c_.model.damping_stiffness == DampingStiffness::current_pair) {
      p.push_n = dk * (1.0 + memory.damping_per_stiffness_s_m * dk_rate);
      return p;
    }
    std::tie(p.ke, p.dke) = pair_stiffness(m, j, p.x_m);
    p.elastic_n = elastic_force(p.ke, dk);
    const double d = c_.model.damping_stiffness == DampingStiffness::current_pair
                         ? memory.damping_per_stiffness_s_m * p.ke
                         : memory.damping_per_stiffness_s_m * memory.frozen_stiffness_n_per_m;
    p.push_n = p.elastic_n + hertzian_damping_force(d, dk, dk_rate);
    return p;
  }

  // The equations of motion in the mode, with the contact memory of each side.
  void rhs(double t, const Y& y, const PlanarMode& mode, const std::array<ContactMemory, 2>& memory,
           Y& dy, Forces* forces = nullptr) const {
    if (options_) {
      motion<true>(t, y, mode, memory, dy, forces);
    } else {
      motion<false>(t, y, mode, memory, dy, forces);
    }
  }

 private:
  // The equations of motion; kOptions false compiles out the code of the
  // options a case may not have (gaps, the mesh damper, a driver, a drag), so
  // that a run without them pays nothing for them.
  template <bool kOptions>
  void motion(double t, const Y& y, const PlanarMode& mode,
              const std::array<ContactMemory, 2>& memory, Y& dy, Forces* forces) const {
    const double* v = &y[kVelocity];
    const double w1 = v[kT1];
    const double w2 = v[kT2];
    // Forces on the centres (x, y) and moments about them (in theta's sense).
    double f1[2] = {-m_.stiffness_x_n_per_m[0] * y[kX1] - m_.damping_x_n_s_per_m[0] * v[kX1],
                    -m_.stiffness_y_n_per_m[0] * y[kY1] - m_.damping_y_n_s_per_m[0] * v[kY1]};
    double f2[2] = {-m_.stiffness_x_n_per_m[1] * y[kX2] - m_.damping_x_n_s_per_m[1] * v[kX2],
                    -m_.stiffness_y_n_per_m[1] * y[kY2] - m_.damping_y_n_s_per_m[1] * v[kY2]};
    const double bearing_power =
        m_.damping_x_n_s_per_m[0] * v[kX1] * v[kX1] + m_.damping_y_n_s_per_m[0] * v[kY1] * v[kY1] +
        m_.damping_x_n_s_per_m[1] * v[kX2] * v[kX2] + m_.damping_y_n_s_per_m[1] * v[kY2] * v[kY2];
    double moment1 = 0.0;
    double moment2 = 0.0;
    double hertz_power = 0.0;
    double friction_power = 0.0;
    double parametric_power = 0.0;
    for (const Region side : kSides) {
      const std::size_t i = side_index(side);
      const SideMode& m = mode[i];
      // Contact, pairs, parts, touching pairs, gaps' zones, friction signs
      // and clipping are the mode's, whatever a stage state says: the forces
      // stay smooth within a step.
      if (!m.contact) continue;
      const SideMotion sm = side_motion(side, y);
      const double dl = sm.dl;
      const double sign = line_sign(side);
      const auto n = normal(side);
      // t = e_z x n: the flanks' common tangent, along which friction acts.
      const double tx = -n[1];
      const double ty = n[0];
      const double x_rate = sign * rb1_ * w1;
      double total = 0.0;
      for (int j = 0; j < m.range.count; ++j) {
        const PairMotion p = pair_motion<kOptions>(side, y, sm, memory[i], m, j);
        // A pair that carries no force: no damping, no friction.
        if (!p.carries) continue;
        const double x = p.x_m;
        const double dk = p.own.delta_m;
        const double dke = p.dke;
        const double f_elastic = p.elastic_n;
        // A tooth pushes, never pulls: clipped at the event where F + G turns negative.
        const double normal_n = normal_force(f_elastic, p.push_n - f_elastic, m.clipped[j]);
        const double vs = p.sliding_m_s;
        const double f = pair_friction_coefficient(c_.model, c_.gears.face_width_m, normal_n, vs,
                                                   entrainment_speed(w1, w2, x, lp_));
        const double smoothing = c_.model.friction_smoothing_speed_m_s;
        const double slip = smoothing > 0.0    ? std::tanh(vs / smoothing)
                            : m.slip_per_stage ? (vs >= 0.0 ? 1.0 : -1.0)
                                               : m.slip[j];
        const double ff = friction_force(side, f, normal_n, slip);
        moment1 -= sign * (normal_n * rb1_ + ff * x);
        moment2 += sign * (normal_n * rb2_ + ff * (lp_ - x));
        // On the pinion -sign N n - Ff t, on the wheel the opposite. The
        // friction's sign does not follow the line's: Ff t at the contact
        // has the moment +Ff X about O1 on N1 (the contact at +X n1 from the
        // pinion's base circle) and -Ff X on N2 (at -X n2), so -Ff t is what
        // gives the pinion the torque -sign Ff X above on either line.
        const double fx = -sign * (normal_n * n[0] + sign * ff * tx);
        const double fy = -sign * (normal_n * n[1] + sign * ff * ty);
        f1[0] += fx;
        f1[1] += fy;
        f2[0] -= fx;
        f2[1] -= fy;
        hertz_power += (normal_n - f_elastic) * p.own.rate_m_s;
        friction_power += f * normal_n * slip * vs;
        // d/dt of 1/2 Ke(X) delta^2 at fixed delta, X a function of theta1
        // alone (dX/dtheta1 = sign Rb1), as in the torsional system.
        // Newtonian: work of the varying stiffness. Lagrangian: -dV/dtheta1
        // adds the torque -1/2 dKe/dX sign Rb1 delta^2 on the pinion, whose
        // power is minus this; a clipped pair exerts no force, so the stored
        // energy it gains or loses counts with its damping loss.
        if (!(kOptions && lagrangian_)) {
          parametric_power += 0.5 * dk * dk * dke * x_rate;
        } else if (m.clipped[j]) {
          hertz_power -= 0.5 * dk * dk * dke * x_rate;
        } else {
          moment1 -= 0.5 * dk * dk * dke * sign * rb1_;
        }
        // The gap moves with the pinion: N does the work -N de_k/dX dX/dt on
        // the pair's penetration at fixed centres and angles, the varying
        // mesh's as in the torsional system. Lagrangian: N acts on delta_k,
        // whose lever on the pinion is sign Rb1 (1 - de_k/dX).
        if (kOptions && gaps_) {
          if (!lagrangian_) {
            parametric_power -= normal_n * p.own.gap_slope * x_rate;
          } else {
            moment1 += sign * rb1_ * normal_n * p.own.gap_slope;
          }
        }
        total += normal_n;
        if (forces != nullptr) {
          forces->friction_n += ff;
          forces->mesh_energy_j[i] += 0.5 * p.ke * dk * dk;
        }
      }
      if (forces != nullptr) {
        forces->normal_n[i] = total;
        forces->penetration_m[i] = dl;
      }
    }
    double mesh_damping_power = 0.0;
    if (kOptions && mesh_damping_ > 0.0) {
      // The viscous mesh damper, half of c on each line of action on that
      // line's s' (s_d', s_c'), in contact and in the backlash alike: with the
      // centres fixed both rates are s' and the two halves are the torsional
      // c s' (docs/vibration.md). Each acts as a contact force of its line
      // would: on the pinion -f n, -f Rb1, on the wheel +f n, +f Rb2.
      const double roll = rb1_ * w1 - rb2_ * w2;
      for (const Region side : kSides) {
        const auto n = normal(side);
        const double rate = roll + (v[kX1] - v[kX2]) * n[0] + (v[kY1] - v[kY2]) * n[1];
        const double force = 0.5 * mesh_damping_ * rate;
        moment1 -= force * rb1_;
        moment2 += force * rb2_;
        f1[0] -= force * n[0];
        f1[1] -= force * n[1];
        f2[0] += force * n[0];
        f2[1] += force * n[1];
        mesh_damping_power += force * rate;
      }
    }
    // A driven body has the closed form's acceleration in every stage (its
    // angle and speed are set to the closed form after every step): the
    // driver's torque is what gives it that against the other moments on it.
    double t1 = 0.0;
    double driven_acceleration = 0.0;
    if (kOptions && driven_) {
      driven_acceleration = driver_motion(c_.torque1, driver_theta0_, t).acceleration_rad_per_s2;
      if (!m_.shafts) t1 = j1_ * driven_acceleration - moment1;
    } else if (kOptions && controller_) {
      // torque1 acts on the motor with shafts, so the controller reads it.
      t1 = controller_->torque_n_m(t, y[driven_index_], v[driven_index_]);
    } else if (kOptions && induction_) {
      t1 = induction_motor_torque_n_m(c_.torque1, v[driven_index_]);
    } else {
      t1 = torque(c_.torque1, t);
    }
    // A drag opposes the turning of the body it acts on: the load on its
    // shaft, else the wheel.
    double t2 = kOptions && drag_ ? drag_torque_n_m(c_.torque2, m_.shafts ? v[kTl] : w2)
                                  : torque(c_.torque2, t);
    double shaft_power = 0.0;
    // Without shafts the motor and the load are not bodies: their entries
    // stay as they started, and the outputs report the gears' own.
    dy[kTm] = m_.shafts ? v[kTm] : 0.0;
    dy[kTl] = m_.shafts ? v[kTl] : 0.0;
    dy[kVelocity + kTm] = 0.0;
    dy[kVelocity + kTl] = 0.0;
    double work = t1 * w1 + t2 * w2;
    if (m_.shafts) {
      const double rel_m = v[kTm] - w1;
      const double rel_l = v[kTl] - w2;
      const double shaft_m = m_.motor_stiffness_n_m_per_rad * (y[kTm] - y[kT1]) +
                             m_.motor_damping_n_m_s_per_rad * rel_m;
      const double shaft_l =
          m_.load_stiffness_n_m_per_rad * (y[kTl] - y[kT2]) + m_.load_damping_n_m_s_per_rad * rel_l;
      if (kOptions && driven_) t1 = m_.motor_inertia_kg_m2 * driven_acceleration + shaft_m;
      dy[kVelocity + kTm] = (t1 - shaft_m) * inverse_mass_[kTm];
      dy[kVelocity + kTl] = (t2 - shaft_l) * inverse_mass_[kTl];
      work = t1 * v[kTm] + t2 * v[kTl];
      shaft_power = m_.motor_damping_n_m_s_per_rad * rel_m * rel_m +
                    m_.load_damping_n_m_s_per_rad * rel_l * rel_l;
      t1 = shaft_m;
      t2 = shaft_l;
    }
    for (const std::size_t q : {kX1, kY1, kT1, kX2, kY2, kT2}) dy[q] = v[q];
    dy[kVelocity + kX1] = f1[0] * inverse_mass_[kX1];
    dy[kVelocity + kY1] = f1[1] * inverse_mass_[kY1];
    dy[kVelocity + kT1] = (t1 + moment1) * inverse_mass_[kT1];
    dy[kVelocity + kX2] = f2[0] * inverse_mass_[kX2];
    dy[kVelocity + kY2] = f2[1] * inverse_mass_[kY2];
    dy[kVelocity + kT2] = (t2 + moment2) * inverse_mass_[kT2];
    dy[kWork] = work;
    dy[kHertzLoss] = hertz_power;
    dy[kSlidingLoss] = friction_power;
    dy[kParametric] = parametric_power;
    dy[kBearingLoss] = bearing_power;
    dy[kShaftLoss] = shaft_power;
    dy[kMeshDamperLoss] = mesh_damping_power;
    if (kOptions && driven_) dy[kVelocity + driven_index_] = driven_acceleration;
  }

  // torque_at without its call for a constant torque, the common case
  // (the call costs as much as a pair's forces).
  static double torque(const Torque& q, double t) {
    return q.kind == Torque::Kind::constant ? q.constant_n_m : torque_at(q, t);
  }

 public:
  // The memory of a contact that begins on `side` at y, in the side's mode m.
  ContactMemory onset(Region side, const Y& y, const SideMode& m, double& impact_speed,
                      double& restitution) const {
    const auto [dl, dl_rate] = penetration(side, y);
    double approach = dl_rate;
    if (gaps_) {
      // The fastest approach among the pairs that touch, each at its own
      // penetration rate, as in the torsional system.
      const double ref = layout_.reference_m(side, y[kT1]);
      const double x_rate = line_sign(side) * rb1_ * y[kVelocity + kT1];
      approach = -std::numeric_limits<double>::infinity();
      for (int j = 0; j < m.range.count; ++j) {
        if (!m.touching[j]) continue;
        const double x = layout_.position_m(ref, m.range.k_first + j);
        approach =
            std::max(approach, pair_penetration(side, m, j, x, dl, dl_rate, x_rate).rate_m_s);
      }
    }
    const OnsetDamping d = onset_damping(c_.model, damping_update_, approach);
    impact_speed = d.impact_speed_m_s;
    restitution = d.restitution;
    ContactMemory memory;
    memory.damping_per_stiffness_s_m = d.damping_per_stiffness_s_m;
    if (c_.model.damping_stiffness == DampingStiffness::hertz) {
      memory.frozen_stiffness_n_per_m = hertz_stiffness(c_.gears);
    } else {
      // The loaded pair nearest the pitch point; with faults, among the
      // pairs that carry (none: the stiffness stays 0, as nothing pushes).
      const double ref = layout_.reference_m(side, y[kT1]);
      const double pitch = pitch_point_position(c_.gears);
      int nearest = -1;
      for (int j = 0; j < m.range.count; ++j) {
        if (!carries(m, j)) continue;
        if (nearest < 0 ||
            std::fabs(layout_.position_m(ref, m.range.k_first + j) - pitch) <
                std::fabs(layout_.position_m(ref, m.range.k_first + nearest) - pitch)) {
          nearest = j;
        }
      }
      if (nearest >= 0) {
        memory.frozen_stiffness_n_per_m =
            pair_stiffness(m, nearest, layout_.position_m(ref, m.range.k_first + nearest)).first;
      }
    }
    return memory;
  }

 private:
  const SimulationCase& c_;
  const PlanarMounting& m_;
  const StiffnessTable& table_;
  std::shared_ptr<const MeshTables> teeth_;
  // With [modifications]: each pair's gap (docs/faults.md) and the kinks of its slope.
  std::shared_ptr<const ToothGaps> gaps_;
  std::vector<double> kinks_;
  double mesh_damping_ = 0.0;  // c of the viscous mesh damper, N s/m; 0: none
  bool drag_ = false;          // torque2 a drag
  DampingUpdate damping_update_ = DampingUpdate::frozen;  // resolved
  bool driven_ = false;                                   // torque1 a kinematic driver
  // torque1 a speed controller's (none otherwise) or an induction motor's,
  // from the motion of the body it acts on (driven_index_).
  std::shared_ptr<const SpeedController> controller_;
  bool induction_ = false;
  std::size_t driven_index_ = kT1;
  double driver_theta0_ = 0.0;
  bool lagrangian_ = false;
  bool options_ = false;  // any of the above
  MeshLayout layout_;
  double rb1_ = 0.0, rb2_ = 0.0, j1_ = 0.0, j2_ = 0.0, backlash_ = 0.0, lp_ = 0.0;
  std::array<double, kVelocity> inverse_mass_{};  // 1/m or 1/J of each position
  double xs_ = 0.0, xe_ = 0.0, sin_a_ = 0.0, cos_a_ = 0.0, constant_k_ = 0.0;
  // The bound of terms_may_exceed per term, J/m^2 (bounded_ without gaps or
  // a constant stiffness).
  std::array<double, kTermCount> term_bound_{};
  bool bounded_ = false;
};

void require(bool ok, const char* key, double value, const char* allowed) {
  if (!ok) throw InputError(key, value, allowed);
}

void refuse(const char* key, const std::string& value, const std::string& allowed) {
  throw InputError(key, value, allowed + " with [bearings] kind = \"elastic\" (docs/vibration.md)");
}

}  // namespace

void validate_planar(const SimulationCase& /*c*/, const PlanarMounting& m,
                     const RunControl& control) {
  const char* masses[2] = {"mass1", "mass2"};
  const char* kx[2] = {"stiffness_x1", "stiffness_x2"};
  const char* ky[2] = {"stiffness_y1", "stiffness_y2"};
  const char* cx[2] = {"damping_x1", "damping_x2"};
  const char* cy[2] = {"damping_y1", "damping_y2"};
  for (std::size_t i = 0; i < 2; ++i) {
    require(std::isfinite(m.mass_kg[i]) && m.mass_kg[i] > 0.0, masses[i], m.mass_kg[i],
            "a finite mass > 0 kg");
    const char* springs = "a finite value >= 0 in N/m (0: the centre is free)";
    const char* dampers = "a finite value >= 0 in N s/m";
    require(std::isfinite(m.stiffness_x_n_per_m[i]) && m.stiffness_x_n_per_m[i] >= 0.0, kx[i],
            m.stiffness_x_n_per_m[i], springs);
    require(std::isfinite(m.stiffness_y_n_per_m[i]) && m.stiffness_y_n_per_m[i] >= 0.0, ky[i],
            m.stiffness_y_n_per_m[i], springs);
    require(std::isfinite(m.damping_x_n_s_per_m[i]) && m.damping_x_n_s_per_m[i] >= 0.0, cx[i],
            m.damping_x_n_s_per_m[i], dampers);
    require(std::isfinite(m.damping_y_n_s_per_m[i]) && m.damping_y_n_s_per_m[i] >= 0.0, cy[i],
            m.damping_y_n_s_per_m[i], dampers);
  }
  if (m.shafts) {
    const char* positive = "a finite value > 0";
    require(std::isfinite(m.motor_inertia_kg_m2) && m.motor_inertia_kg_m2 > 0.0, "motor_inertia",
            m.motor_inertia_kg_m2, positive);
    require(std::isfinite(m.load_inertia_kg_m2) && m.load_inertia_kg_m2 > 0.0, "load_inertia",
            m.load_inertia_kg_m2, positive);
    require(std::isfinite(m.motor_stiffness_n_m_per_rad) && m.motor_stiffness_n_m_per_rad > 0.0,
            "motor_stiffness", m.motor_stiffness_n_m_per_rad, positive);
    require(std::isfinite(m.load_stiffness_n_m_per_rad) && m.load_stiffness_n_m_per_rad > 0.0,
            "load_stiffness", m.load_stiffness_n_m_per_rad, positive);
    require(std::isfinite(m.motor_damping_n_m_s_per_rad) && m.motor_damping_n_m_s_per_rad >= 0.0,
            "motor_damping", m.motor_damping_n_m_s_per_rad, "a finite value >= 0");
    require(std::isfinite(m.load_damping_n_m_s_per_rad) && m.load_damping_n_m_s_per_rad >= 0.0,
            "load_damping", m.load_damping_n_m_s_per_rad, "a finite value >= 0");
  }
  if (control.resume) refuse("resume", "a run state", "none (a planar run starts afresh)");
}

// The step must resolve the fastest motion the planar system can have. Its
// largest w^2 is at most the sum over the springs of k a^T M^-1 a (each
// spring k a a^T adds at most that eigenvalue of M^-1/2 K M^-1/2), the mesh
// counted on both sides at its stiffest.
namespace {

// w^2 of that bound, and the bearing damper whose decay rate c/m is the largest.
struct PlanarFastest {
  double w2 = 0.0;
  bool load_drag = false;
  double damper_rate = 0.0;
  std::string damper_key;
};

PlanarFastest planar_fastest(const SimulationCase& c, const StiffnessTable& table,
                             const PlanarMounting& m) {
  PlanarFastest f;
  const GearPair& g = c.gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const double j1 = moment_of_inertia(g, Gear::one);
  const double j2 = moment_of_inertia(g, Gear::two);
  // The torsional bound is 1/kStepsPerContactPeriod of 2 pi / sqrt(K (Rb1^2/J1 + Rb2^2/J2)).
  const double torsional = largest_resolving_step_s(c, table);
  const double inverse_torsional = rb1 * rb1 / j1 + rb2 * rb2 / j2;
  const double w_torsional = 2.0 * pi / (kStepsPerContactPeriod * torsional);
  const double stiffest_mesh = w_torsional * w_torsional / inverse_torsional;
  double& w2 = f.w2;
  w2 = 2.0 * stiffest_mesh * (inverse_torsional + 1.0 / m.mass_kg[0] + 1.0 / m.mass_kg[1]);
  for (std::size_t i = 0; i < 2; ++i) {
    w2 += (m.stiffness_x_n_per_m[i] + m.stiffness_y_n_per_m[i]) / m.mass_kg[i];
  }
  if (m.shafts) {
    w2 += m.motor_stiffness_n_m_per_rad * (1.0 / m.motor_inertia_kg_m2 + 1.0 / j1) +
          m.load_stiffness_n_m_per_rad * (1.0 / m.load_inertia_kg_m2 + 1.0 / j2);
  }
  // A drag on the load relaxes its speed with the rate (drag_constant /
  // drag_speed_scale + drag_viscous) / J_load, which the case's check of the
  // drag bounds for the wheel only: counted as a frequency, it needs as many
  // steps per 2 pi of its time constant as that check does.
  f.load_drag = m.shafts && c.torque2.kind == Torque::Kind::drag;
  const bool load_drag = f.load_drag;
  if (load_drag) {
    const double rate = (c.torque2.drag_constant_n_m / c.torque2.drag_speed_scale_rad_per_s +
                         c.torque2.drag_viscous_n_m_s) /
                        m.load_inertia_kg_m2;
    w2 += rate * rate;
  }
  // A bearing's damper c on its mass m decays the centre's speed at the rate
  // c/m: a real eigenvalue -c/m, on which RK4 is stable only for h c/m <=
  // 2.785 (its stability limit on the negative real axis). Counted as a
  // frequency, it needs as many steps per 2 pi / (c/m) as a contact period,
  // h c/m <= 2 pi / steps (0.31 for RK4): a factor of 9 inside that limit,
  // so that the damper's decay is resolved, not only kept from diverging.
  double& damper_rate = f.damper_rate;
  std::string& damper_key = f.damper_key;
  for (std::size_t i = 0; i < 2; ++i) {
    const double cx = m.damping_x_n_s_per_m[i] / m.mass_kg[i];
    const double cy = m.damping_y_n_s_per_m[i] / m.mass_kg[i];
    w2 += cx * cx + cy * cy;
    const double rate = std::max(cx, cy);
    if (rate > damper_rate) {
      damper_rate = rate;
      damper_key =
          std::string("bearings.damping_") + (cx >= cy ? "x" : "y") + std::to_string(i + 1);
    }
  }
  return f;
}

}  // namespace

double planar_largest_step_s(const SimulationCase& c, const StiffnessTable& table,
                             const PlanarMounting& m, IntegratorKind kind) {
  return 2.0 * pi / std::sqrt(planar_fastest(c, table, m).w2) / steps_per_contact_period(kind);
}

void check_planar_step(const SimulationCase& c, const StiffnessTable& table,
                       const PlanarMounting& m) {
  const PlanarFastest f = planar_fastest(c, table, m);
  const double w2 = f.w2;
  const bool load_drag = f.load_drag;
  const double damper_rate = f.damper_rate;
  const std::string& damper_key = f.damper_key;
  const double steps = steps_per_contact_period(c.integrator.kind);
  const double largest = 2.0 * pi / std::sqrt(w2) / steps;
  // Whether the dampers alone would need a smaller step: then the message names the key.
  const bool damper_bound =
      damper_rate > 0.0 && c.integrator.step_s * damper_rate > 2.0 * pi / steps;
  if (c.integrator.step_s > largest) {
    throw InputError(
        "integrator.step", format_number(c.integrator.step_s) + " s",
        "at most " + format_number(largest) +
            " s with [bearings] kind = "
            "\"elastic\" and integrator.kind = \"" +
            std::string(name_of(kIntegratorKinds, c.integrator.kind)) + "\": 1/" +
            format_number(steps) +
            " of the shortest period the planar system can have (its stiffest "
            "springs: the mesh on both sides, the bearings" +
            std::string(m.shafts ? ", the shafts" : "") +
            std::string(load_drag ? ", the drag's relaxation of the load" : "") +
            std::string(damper_rate > 0.0 ? ", the bearings' dampers' decay rates c/m" : "") + ")" +
            (damper_bound
                 ? "; " + damper_key + " alone decays its centre at " + format_number(damper_rate) +
                       " 1/s (c/m, bearings.mass), more than 2 pi/" + format_number(steps) +
                       " per step: lower it or the step"
                 : std::string()));
  }
}

namespace {

// The force each bearing exerts on its gear, -k u - c u': x1, y1, x2, y2.
std::array<double, 4> bearing_forces(const PlanarMounting& m, const PlanarState& s) {
  return {-m.stiffness_x_n_per_m[0] * s.x1_m - m.damping_x_n_s_per_m[0] * s.vx1_m_s,
          -m.stiffness_y_n_per_m[0] * s.y1_m - m.damping_y_n_s_per_m[0] * s.vy1_m_s,
          -m.stiffness_x_n_per_m[1] * s.x2_m - m.damping_x_n_s_per_m[1] * s.vx2_m_s,
          -m.stiffness_y_n_per_m[1] * s.y2_m - m.damping_y_n_s_per_m[1] * s.vy2_m_s};
}

}  // namespace

PlanarMounting planar_mounting(const SimulationCase& c) {
  PlanarMounting m;
  const GearBearing* bearing[2] = {&c.bearings.gear1, &c.bearings.gear2};
  const Gear gear[2] = {Gear::one, Gear::two};
  for (std::size_t i = 0; i < 2; ++i) {
    m.mass_kg[i] = bearing[i]->mass_kg.value_or(disc_mass(c.gears, gear[i]));
    m.stiffness_x_n_per_m[i] = bearing[i]->stiffness_x_n_per_m;
    m.stiffness_y_n_per_m[i] = stiffness_y(*bearing[i]);
    m.damping_x_n_s_per_m[i] = bearing[i]->damping_x_n_s_per_m;
    m.damping_y_n_s_per_m[i] = damping_y(*bearing[i]);
  }
  m.shafts = c.shafts.kind == ShaftKind::elastic;
  m.motor_inertia_kg_m2 = c.shafts.motor_inertia_kg_m2;
  m.motor_stiffness_n_m_per_rad = c.shafts.motor_stiffness_n_m_per_rad;
  m.motor_damping_n_m_s_per_rad = c.shafts.motor_damping_n_m_s_per_rad;
  m.load_inertia_kg_m2 = c.shafts.load_inertia_kg_m2;
  m.load_stiffness_n_m_per_rad = c.shafts.load_stiffness_n_m_per_rad;
  m.load_damping_n_m_s_per_rad = c.shafts.load_damping_n_m_s_per_rad;
  return m;
}

PlanarState planar_initial_state(const SimulationCase& c) {
  PlanarState s;
  s.theta1_rad = c.initial.theta1_rad;
  s.theta2_rad = c.initial.theta2_rad;
  s.w1_rad_per_s = c.initial.w1_rad_per_s;
  s.w2_rad_per_s = c.initial.w2_rad_per_s;
  s.theta_motor_rad = s.theta1_rad;
  s.theta_load_rad = s.theta2_rad;
  s.w_motor_rad_per_s = s.w1_rad_per_s;
  s.w_load_rad_per_s = s.w2_rad_per_s;
  return s;
}

std::array<double, 2> planar_linear_momentum(const PlanarMounting& m, const PlanarState& s) {
  return {m.mass_kg[0] * s.vx1_m_s + m.mass_kg[1] * s.vx2_m_s,
          m.mass_kg[0] * s.vy1_m_s + m.mass_kg[1] * s.vy2_m_s};
}

double planar_angular_momentum(const SimulationCase& c, const PlanarMounting& m,
                               const PlanarState& s) {
  const GearPair& g = c.gears;
  const double centres = (base_radius(g, Gear::one) + base_radius(g, Gear::two)) /
                         std::cos(operating_pressure_angle(g));
  double l = moment_of_inertia(g, Gear::one) * s.w1_rad_per_s -
             moment_of_inertia(g, Gear::two) * s.w2_rad_per_s +
             m.mass_kg[0] * (s.x1_m * s.vy1_m_s - s.y1_m * s.vx1_m_s) +
             m.mass_kg[1] * ((centres + s.x2_m) * s.vy2_m_s - s.y2_m * s.vx2_m_s);
  if (m.shafts) {
    l += m.motor_inertia_kg_m2 * s.w_motor_rad_per_s - m.load_inertia_kg_m2 * s.w_load_rad_per_s;
  }
  return l;
}

namespace {

// The planar run: the books of run_fixed_grid (step_methods.hpp) for the
// PlanarSystem: the state and both sides' modes and contact memories, the
// impacts, the ledger with the bearings' and shafts' energies, the series,
// the samples and the tacho.
class PlanarRun {
 public:
  using System = PlanarSystem;
  // The evaluations of the step taken again to an event count in rhs_evaluations.
  static constexpr bool kCountsCutStep = true;

  PlanarRun(const SimulationCase& c, const StiffnessTable& table, const PlanarMounting& mounting,
            const PlanarState& initial, const RunControl& control)
      : c_(c),
        m_(mounting),
        control_(control),
        system_(c, table, mounting, mounting.shafts ? initial.theta_motor_rad : initial.theta1_rad),
        y_(to_vector(initial)),
        clock_(c, control, 0.0),
        stall_(c.integrator.step_s, c.model.friction_smoothing_speed_m_s),
        sensor_cos_(std::cos(c.bearings.sensor_angle_rad)),
        sensor_sin_(std::sin(c.bearings.sensor_angle_rad)),
        average_(control.sample == SampleKind::interval_average),
        tacho_on_(c.tacho.pulses_per_revolution > 0),
        tacho_index_(c.tacho.shaft == TachoShaft::wheel                      ? kT2
                     : c.tacho.shaft == TachoShaft::motor && mounting.shafts ? kTm
                                                                             : kT1),
        driver_theta0_(mounting.shafts ? initial.theta_motor_rad : initial.theta1_rad) {
    SimulationSummary& s = result_.summary;
    s.case_name = c.name;
    s.integrator = name_of(kIntegratorKinds, c.integrator.kind);
    s.damping_update = resolved_damping_update(c);
    s.friction_coefficient = c.model.friction_coefficient;
    s.friction_law = c.model.friction_law;
    s.mesh_damper = c.model.mesh_damping_ratio > 0.0;
    s.step_s = c.integrator.step_s;
    s.stiffness_model = c.model.stiffness.kind;
    s.planar = PlanarEnergies{};
    system_.impose_driver(0.0, y_);
    if (control.keep_samples && clock_.on()) result_.planar_samples.reserve(clock_.reserve_rows());
    // The tacho's shaft and its edges, located on each step's continuous
    // extension (hence wants_dense with a tacho), or on a driver's closed form.
    tacho_driven_ =
        system_.driven() && tacho_index_ == (mounting.shafts ? std::size_t{kTm} : std::size_t{kT1});
    tacho_.emplace(tacho_on_ ? c.tacho : Tacho{1}, y_[tacho_index_]);
    drift_.emplace(c, 0.0, y_[kT1], y_[kVelocity + kT1]);
    classify(0.0);
    emit_samples(0.0, y_, mode_, [](double, Y&) {});
    PlanarEnergies& p = *s.planar;
    const double kinetic0 = system_.kinetic_energy(y_);
    const double mesh0 = mesh_energy(y_);
    s.kinetic_energy_initial_j = kinetic0;
    s.stored_energy_initial_j = mesh0;
    p.bearing_energy_initial_j = system_.bearing_energy(y_);
    p.shaft_energy_initial_j = system_.shaft_energy(y_);
    energy0_ = kinetic0 + mesh0 + p.bearing_energy_initial_j + p.shaft_energy_initial_j;
    record(0.0);
    // k1, f(t, y) in the mode: each step's first stage, evaluated at the end
    // of the step before (after its events), where its mesh energy serves the ledger.
    system_.rhs(0.0, y_, mode_, memory_, k1_, &at_start_);
    s.rhs_evaluations += 1;
  }

  // The fixed-step method whose last stage may serve as the next step's first.
  void use_stepper(const FixedStepper<PlanarSystem>* stepper) { stepper_ = stepper; }

  const PlanarSystem& system() const { return system_; }
  Y& y() { return y_; }
  const PlanarMode& mode() const { return mode_; }
  const std::array<ContactMemory, 2>& damping() const { return memory_; }
  long long& steps() { return result_.summary.steps; }
  long long& rhs_evaluations() { return result_.summary.rhs_evaluations; }
  double start_time() const { return 0.0; }
  long long grid_steps() const {
    return static_cast<long long>(
        std::ceil(c_.integrator.end_time_s / c_.integrator.step_s - 1e-9));
  }
  bool wants_dense() const { return clock_.on() || tacho_on_; }
  bool records() const {
    return control_.keep_series || static_cast<bool>(control_.on_row) ||
           static_cast<bool>(control_.on_planar_row);
  }
  bool sampling() const { return clock_.on(); }
  const Y& first_stage(double) const { return k1_; }
  void check_finite(double t, const Y& y) const { check_finite_state(t, steps_taken(), y); }
  void poll_stop(double t) const { poll_stop_request(control_, steps_taken(), t); }

  // The samples not yet taken up to t_b, the end of a step in mode m at y_b:
  // one at t_b is y_b itself, one before it the step's continuous extension.
  template <typename StateAt>
  void emit_samples(double t_b, const Y& y_b, const PlanarMode& m, StateAt state_at) {
    clock_.emit(
        t_b, [&](double ts) { sample(ts, y_b, m); },
        [&](double ts) {
          Y x{};
          state_at(ts, x);
          sample(ts, x, m);
        });
  }

  // The tacho's edges inside the step from (t_a, y_a) to (t_b, y_b).
  template <typename Dense>
  void observe_step(double t_a, const Y& y_a, double t_b, const Y& y_b, const Dense& dense) {
    if (!tacho_on_) return;
    tacho_->step(t_a, y_a[tacho_index_], t_b, y_b[tacho_index_], [&](double tau) {
      if (tacho_driven_) return driver_motion(c_.torque1, driver_theta0_, tau).theta_rad;
      Y x{};
      dense(tau, x);
      return x[tacho_index_];
    });
  }

  // The mode changed at (t, y_): classify again; the stored energy before,
  // for the jump's work.
  void change_mode(double t) {
    ++result_.summary.events;
    before_ = mesh_energy(y_);
    classify(t);
    if (system_.lagrangian()) pay_stored_energy_jump(t, mesh_energy(y_) - before_);
    event_ = true;
  }

  // After a step from t_from to t_to (stall.hpp): a step taken with each
  // stage's friction signs classifies them again and keeps them per stage
  // while one of them changed; events that stall make the steps take them so.
  bool check_progress(double t_from, double t_to, bool event) {
    const bool sticks =
        stall_.after_step(event, t_from, t_to, [&] { return where(t_from, steps_taken()); });
    stepped_per_stage_ = !event && mode_[0].slip_per_stage;
    if (stepped_per_stage_) {
      // The sticking goes on while a pair's sliding still changed sign over
      // the step; once every pair slid one way through a whole step, its
      // reversals are events again.
      bool sticking = false;
      for (const Region side : kSides) {
        SideMode& m = mode_[side_index(side)];
        const std::array<double, kMaxPairs> slip = m.slip;
        system_.classify_forces(side, y_, memory_[side_index(side)], m);
        sticking = sticking || slip != m.slip;
      }
      mode_[0].slip_per_stage = sticking;
      mode_[1].slip_per_stage = sticking;
    }
    if (sticks) {
      mode_[0].slip_per_stage = true;
      mode_[1].slip_per_stage = true;
    }
    return stepped_per_stage_ || sticks;
  }

  // After an accepted step, which ends at t: the next step's first stage, the
  // jump's work at an event, the largest penetration and the ledger.
  void book_keep(double t) {
    SimulationSummary& s = result_.summary;
    drift_->observe(t, y_[kT1]);
    // The next step's first stage, in the mode the run now holds: after a step
    // that kept its mode and whose end no driver moved, Dormand-Prince's last.
    if (stepper_ != nullptr && stepper_->dopri5() && !event_ && !stepped_per_stage_ &&
        !system_.driven()) {
      k1_ = stepper_->end_slope();
      at_start_ = stepper_->end_forces();
    } else {
      at_start_ = Forces{};
      system_.rhs(t, y_, mode_, memory_, k1_, &at_start_);
      s.rhs_evaluations += 1;
    }
    const double mesh = at_start_.mesh_energy_j[0] + at_start_.mesh_energy_j[1];
    // A pair that entered or left, or crossed a fault's edge, takes or
    // releases its stored energy: work of the time-varying stiffness, booked
    // at the event.
    // Under the Lagrangian force the jump was paid at the event (change_mode).
    if (event_ && !system_.lagrangian()) jump_work_ += mesh - before_;
    event_ = false;
    stepped_per_stage_ = false;
    s.max_penetration_m = std::max({s.max_penetration_m, system_.contact_value(Region::n1, y_),
                                    system_.contact_value(Region::n2, y_)});
    const double energy =
        system_.kinetic_energy(y_) + mesh + system_.bearing_energy(y_) + system_.shaft_energy(y_);
    if (system_.terms_may_exceed(y_, mode_, s.energy_max_j)) {
      const ElasticEnergy terms = system_.mesh_terms(y_, mode_);
      for (std::size_t i = 0; i < kTermCount; ++i) {
        s.energy_max_j[i] = std::max(s.energy_max_j[i], terms.j[i]);
      }
    }
    book_ledger_residual(
        energy, energy0_, y_[kWork],
        {y_[kHertzLoss], y_[kSlidingLoss], y_[kBearingLoss], y_[kShaftLoss], y_[kMeshDamperLoss]},
        y_[kParametric], jump_work_, s);
  }

  void record(double t) { record(t, y_, mode_); }
  void record(double t, const Y& y, const PlanarMode& mode) {
    if (!records()) return;
    Y dy{};
    Forces f;
    system_.rhs(t, y, mode, memory_, dy, &f);
    const PlanarState st = to_state(y, m_.shafts);
    SeriesRow row{};
    row.t_s = t;
    row.theta1_rad = st.theta1_rad;
    row.theta2_rad = st.theta2_rad;
    row.w1_rad_per_s = st.w1_rad_per_s;
    row.w2_rad_per_s = st.w2_rad_per_s;
    // The drive line's s_d and the larger penetration of a pair; the side in
    // contact (the drive side when both are).
    row.s_m = system_.penetration(Region::n1, y).first + c_.gears.backlash_m;
    const double dd = system_.contact_value(Region::n1, y);
    const double dc = system_.contact_value(Region::n2, y);
    row.delta_m = std::max(dd, dc);
    row.region = mode[0].contact ? 1 : (mode[1].contact ? -1 : 0);
    row.pairs = mode[0].contact ? mode[0].range.count : (mode[1].contact ? mode[1].range.count : 0);
    row.normal_force_n = f.normal_n[0] + f.normal_n[1];
    row.friction_force_n = f.friction_n;
    if (control_.on_row) control_.on_row(row);
    if (control_.keep_series) result_.series.push_back(row);
    PlanarRow pr;
    pr.t_s = t;
    pr.state = st;
    const std::array<double, 4> bearing = bearing_forces(m_, st);
    pr.bearing_fx1_n = bearing[0];
    pr.bearing_fy1_n = bearing[1];
    pr.bearing_fx2_n = bearing[2];
    pr.bearing_fy2_n = bearing[3];
    pr.drive_force_n = f.normal_n[0];
    pr.coast_force_n = f.normal_n[1];
    pr.drive_penetration_m = dd;
    pr.coast_penetration_m = dc;
    if (control_.on_planar_row) control_.on_planar_row(pr);
    if (control_.keep_series) result_.planar_series.push_back(pr);
  }

  SimulationResult finish(double t) {
    SimulationSummary& s = result_.summary;
    PlanarEnergies& p = *s.planar;
    s.end_time_s = t;
    book_ledger_totals(system_.kinetic_energy(y_), mesh_energy(y_), y_[kWork], y_[kHertzLoss],
                       y_[kSlidingLoss], y_[kMeshDamperLoss], y_[kParametric], jump_work_, s);
    s.final_w1_rad_per_s = y_[kVelocity + kT1];
    s.final_w2_rad_per_s = y_[kVelocity + kT2];
    s.speed_drift_max_rel = drift_->max_relative_drift();
    if (system_.lagrangian()) s.stored_energy_jumps_j = stored_energy_jumps_;
    result_.tacho_times_s = tacho_->times();
    result_.impacts = impacts_.take();
    p.bearing_energy_final_j = system_.bearing_energy(y_);
    p.bearing_damping_loss_j = y_[kBearingLoss];
    p.shaft_energy_final_j = system_.shaft_energy(y_);
    p.shaft_damping_loss_j = y_[kShaftLoss];
    result_.planar_final_state = to_state(y_, m_.shafts);
    result_.final_state.time_s = t;
    result_.final_state.state = {y_[kT1], y_[kT2], y_[kVelocity + kT1], y_[kVelocity + kT2]};
    result_.final_state.contact = memory_[0];
    return std::move(result_);
  }

 private:
  long long steps_taken() const { return result_.summary.steps; }

  // The Lagrangian mesh force: the stored energy's jump at an event, paid by
  // the pinion's kinetic energy (pinion_speed_after_jump), or with a driver
  // on the pinion by the driver, as work of its torque; the forces' signs are
  // then those of the new speed.
  void pay_stored_energy_jump(double t, double jump) {
    if (jump == 0.0) return;
    stored_energy_jumps_ += std::fabs(jump);
    if (system_.drives_pinion()) {
      y_[kWork] += jump;
      return;
    }
    y_[kVelocity + kT1] =
        pinion_speed_after_jump(jump, system_.pinion_inertia(), y_[kVelocity + kT1],
                                where(t, steps_taken()), "the loaded pairs change");
    for (const Region side : kSides) {
      const std::size_t i = side_index(side);
      system_.classify_forces(side, y_, memory_[i], mode_[i]);
    }
  }

  double mesh_energy(const Y& state) const {
    return system_.mesh_energy(Region::n1, state, mode_[0]) +
           system_.mesh_energy(Region::n2, state, mode_[1]);
  }

  // The mode of y_ at t: each side's contact, pairs and parts; an impact
  // where a side's contact begins (its damping memory then set), its end
  // where it ends; then the forces' signs.
  void classify(double t) {
    for (const Region side : kSides) {
      const std::size_t i = side_index(side);
      const bool before = mode_[i].contact;
      mode_[i] = system_.classify_geometry(side, y_);
      if (mode_[i].contact && !before) {
        double speed = 0.0;
        double restitution = 0.0;
        memory_[i] = system_.onset(side, y_, mode_[i], speed, restitution);
        impacts_.begin(side, t, speed, restitution, result_.summary);
      } else if (!mode_[i].contact && before) {
        impacts_.end(side, t, -system_.penetration(side, y_).second);
      }
      system_.classify_forces(side, y_, memory_[i], mode_[i]);
    }
  }

  // A sample at ts of `state` in mode m (RunControl::sample_rate_hz), as the
  // torsional run takes them: the accelerations from the equations of motion
  // in the step's mode with its contact memory, so that at an event time a
  // sample is the left limit; under SampleKind::interval_average the gears'
  // mean accelerations over the interval instead.
  void sample(double ts, const Y& state, const PlanarMode& m) {
    const auto v = [&](std::size_t i) { return state[kVelocity + i]; };
    if (average_ && clock_.first()) {
      interval_average_.start(ts, v);
      return;
    }
    Y dy{};
    Forces f;
    system_.rhs(ts, state, m, memory_, dy, &f);
    if (average_) {
      interval_average_.next(ts, v, [&](std::size_t i) -> double& { return dy[kVelocity + i]; });
    }
    PlanarSample ps;
    ps.t_s = ts;
    ps.state = to_state(state, m_.shafts);
    ps.ax1_m_per_s2 = dy[kVelocity + kX1];
    ps.ay1_m_per_s2 = dy[kVelocity + kY1];
    ps.alpha1_rad_per_s2 = dy[kVelocity + kT1];
    ps.ax2_m_per_s2 = dy[kVelocity + kX2];
    ps.ay2_m_per_s2 = dy[kVelocity + kY2];
    ps.alpha2_rad_per_s2 = dy[kVelocity + kT2];
    const std::array<double, 4> bearing = bearing_forces(m_, ps.state);
    ps.bearing_fx1_n = bearing[0];
    ps.bearing_fy1_n = bearing[1];
    ps.bearing_fx2_n = bearing[2];
    ps.bearing_fy2_n = bearing[3];
    ps.dte_m = system_.penetration(Region::n1, state).first;
    ps.drive_force_n = f.normal_n[0];
    ps.coast_force_n = f.normal_n[1];
    const bool pinion = c_.bearings.sensor_gear == 1;
    ps.sensor_acceleration_m_per_s2 = (pinion ? ps.ax1_m_per_s2 : ps.ax2_m_per_s2) * sensor_cos_ +
                                      (pinion ? ps.ay1_m_per_s2 : ps.ay2_m_per_s2) * sensor_sin_;
    if (control_.keep_samples) result_.planar_samples.push_back(ps);
    if (control_.on_planar_sample) control_.on_planar_sample(ps);
  }

  const SimulationCase& c_;
  const PlanarMounting& m_;
  const RunControl& control_;
  const PlanarSystem system_;
  Y y_;
  Y k1_{};
  // The forces with k1_: its mesh energy serves the ledger.
  Forces at_start_;
  PlanarMode mode_{};
  std::array<ContactMemory, 2> memory_{};
  SimulationResult result_;
  ImpactBook impacts_;
  SampleClock clock_;
  StallWatch stall_;
  const FixedStepper<PlanarSystem>* stepper_ = nullptr;
  double energy0_ = 0.0;
  double jump_work_ = 0.0;
  // Under the Lagrangian force: the sum of |dU| of the jumps paid.
  double stored_energy_jumps_ = 0.0;
  // The step just accepted ended on an event (before_: the stored energy
  // before it), or was taken with each stage's friction signs.
  bool event_ = false;
  double before_ = 0.0;
  bool stepped_per_stage_ = false;
  double sensor_cos_, sensor_sin_;
  bool average_;
  IntervalAverage<kT2 + 1> interval_average_;
  bool tacho_on_;
  std::size_t tacho_index_;
  bool tacho_driven_ = false;
  double driver_theta0_;
  std::optional<TachoEdges> tacho_;
  std::optional<SpeedDriftMonitor> drift_;
};

}  // namespace

SimulationResult simulate_planar(const SimulationCase& c, const StiffnessTable& table,
                                 const PlanarMounting& mounting, const PlanarState& initial,
                                 const RunControl& control) {
  validate_planar(c, mounting, control);
  validate_sampling(c, control);
  check_planar_step(c, table, mounting);
  PlanarRun run(c, table, mounting, initial, control);
  if (c.integrator.kind == IntegratorKind::adaptive) {
    // Steps of the error's size, at most RK4's step bound of the planar system.
    return run.finish(run_adaptive_loop(
        run, c, planar_largest_step_s(c, table, mounting, IntegratorKind::adaptive)));
  }
  FixedStepper<PlanarSystem> stepper(run.system(), c.integrator.kind);
  run.use_stepper(&stepper);
  const double t = run_fixed_grid(run, stepper, c.integrator);
  return run.finish(t);
}

}  // namespace gearimpact
