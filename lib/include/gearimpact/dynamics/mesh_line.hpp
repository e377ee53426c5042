// One mesh between two bodies as an object: the line of action of a gear pair
// with its loaded pairs on the drive (N1) and coast (N2) lines, its tables
// (one per pair of teeth with faults), its gaps (with modifications), the
// touching of each pair, friction and its reversal, clipping, the event values,
// the forces of the pairs on the two bodies through their base radii, the
// stored energy and the damping set at a contact's onset. A mesh sees its
// bodies through s = Rb_a theta_a - Rb_b theta_b and the speeds w_a, w_b: body a
// is the pair's gear 1 (its pinion, whose angle places the pairs on the line),
// body b its gear 2, each angle positive in the sense its gear turns when gear 1
// drives. The two-gear torsional system (system.hpp) is one mesh between two
// bodies; a gear train (train.hpp) has one mesh per pair of gears in contact.
// The planar system (planar.cpp) sees the same mesh through PlanarMeshMotion:
// each line of action then adds the centres' motion along its normal to s and
// to its rate, and the centres' relative speed along the flanks' tangent to
// the sliding speed, and each line holds a mode and a contact of its own.
// docs/model.md, sections Contact, damping, friction and Equations of motion.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>
#include <type_traits>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

inline constexpr int kMaxPairs = MeshLayout::capacity;
// The event values of a mode: two in free flight; in contact the penetration,
// four bounds of the loaded pairs, and the friction sign and force clipping of
// each pair, and with gaps (modifications.hpp) whether each pair touches and
// the two kinks of its gap about it, and with a table cut at a fault's edges
// the two ends of the pair's part about it.
inline constexpr int kMaxMeshEvents = 2 + 4 + 7 * kMaxPairs;

// Everything that is constant during a step: which side is in contact, which
// pairs are loaded, the sign of each pair's sliding speed and whether its
// normal force is clipped at zero. The right-hand side is smooth while the mode
// holds; a change of mode is an event.
struct Mode {
  Region region = Region::free;
  int k_first = 0;
  int count = 0;
  std::array<double, kMaxPairs> slip{};  // sign of Vs, +1 or -1
  std::array<bool, kMaxPairs> clipped{};
  // With gaps: whether each pair's own penetration delta - e_k is positive
  // (a pair that does not touch carries nothing). Without gaps every pair of
  // the contact segment touches and this is not read.
  std::array<bool, kMaxPairs> touching{};
  // With gaps: how many kinks of the gap (ToothGaps::kinks_m) lie at or
  // below each pair's X, so that a step does not straddle a jump of the
  // gap's slope (the Lagrangian force and the damping force jump there).
  std::array<int, kMaxPairs> zone{};
  // With a pair's table cut at a fault's edges (a spall's, a chip's): the
  // part of the table its X lies in (StiffnessTable::part_of), whose series
  // gives its Ke while the mode holds, continued along its tangent beyond the
  // part's ends, so that a step does not straddle Ke's jump at the edge; 0
  // for a table of one part.
  std::array<int, kMaxPairs> part{};
  // Each loaded pair's table (MeshLine::pair_table, nullptr: a missing
  // tooth), found once a mode: finding it takes integer remainders, which the
  // right-hand side would otherwise pay for every pair at every stage.
  std::array<const StiffnessTable*, kMaxPairs> table{};
  // While a contact sticks (StallWatch, stall.hpp): each stage takes the
  // friction signs from its own state, and reversals are not events.
  bool slip_per_stage = false;
};

// Summed over the loaded pairs, for the time series.
struct ContactTotals {
  double normal_force_n = 0.0;
  double friction_force_n = 0.0;
  // Sum of f N over the pairs: over normal_force_n, the line's load-weighted
  // coefficient of friction.
  double friction_load_n = 0.0;
  // Sum of 1/2 Ke delta^2 over the pairs, with Ke as the force reads it
  // (MeshLine::elastic_energy_j): the planar ledger takes it from the forces.
  double elastic_energy_j = 0.0;
};

// f of (35) of a pair with normal force N, sliding speed Vs and entrainment
// speed Ve under a friction law whose f varies (Benedict-Kelley, a table).
double varying_friction_coefficient(const ModelOptions& model, double face_width_m,
                                    double normal_force_n, double vs, double ve);
// f of (35) of a pair under the case's friction law: the torsional and the
// planar dynamics share it. Inline, the constant law without a call: it is
// read for every loaded pair at every stage.
inline double pair_friction_coefficient(const ModelOptions& model, double face_width_m,
                                        double normal_force_n, double vs, double ve) {
  if (model.friction_law == FrictionLaw::constant) return model.friction_coefficient;
  return varying_friction_coefficient(model, face_width_m, normal_force_n, vs, ve);
}

// (32),(33) at the onset of a contact approached at d(delta)/dt = approach:
// Vi (floored, as D grows without bound as Vi -> 0), e(Vi) and D/K under the
// damping update (resolved: resolved_damping_update, never "auto").
struct OnsetDamping {
  double impact_speed_m_s = 0.0;
  double restitution = 0.0;
  double damping_per_stiffness_s_m = 0.0;
};
OnsetDamping onset_damping(const ModelOptions& model, DampingUpdate update, double approach_m_s);

// The motion of a mesh's two bodies: a drives (the pair's gear 1), b is driven.
struct MeshMotion {
  double theta_a_rad;
  double theta_b_rad;
  double w_a_rad_per_s;
  double w_b_rad_per_s;
};

// The planar model's motion of a mesh's bodies: their turning and their
// centres' motion, body a's centre less body b's, in the frame whose x runs
// from a's centre to b's and whose y is across it (docs/vibration.md).
struct PlanarMeshMotion : MeshMotion {
  double dx_m;
  double dy_m;
  double dvx_m_s;
  double dvy_m_s;
};

// The loads of a mesh on its bodies in the planar model: the moments about
// the centres (each in its body's sense) and the forces on the centres.
struct PlanarLoads {
  double moment_a = 0.0;
  double moment_b = 0.0;
  std::array<double, 2> force_a{};
  std::array<double, 2> force_b{};
};

// The powers of the ledger a mesh adds to (each accumulated, in W): the
// Hertzian damping, friction, the continuous parametric work of the varying
// stiffness, and the viscous mesh damper.
struct MeshPowers {
  double damping_w = 0.0;
  double friction_w = 0.0;
  double parametric_w = 0.0;
  double mesh_damping_w = 0.0;
};

// The line of action of an internal (ring-planet) mesh seen as a MeshLine:
// gear 1 (body a) is the planet, gear 2 (body b) the ring, each angle positive
// in the sense it turns when the planet drives (both clockwise seen from +z);
// s = Rb_p theta_p - Rb_r theta_r. Lengths along the line from the planet's
// tangent point T_b (geometry/planetary.hpp, InternalMesh).
struct InternalLine {
  double planet_base_radius_m = 0.0;
  double ring_base_radius_m = 0.0;
  double pressure_angle_rad = 0.0;  // the working one
  double pitch_point_m = 0.0;       // Rb_p tan a_w'
  double start_m = 0.0;             // where the ring's tip circle cuts the line
  double end_m = 0.0;               // where the planet's tip circle cuts it
  double base_pitch_m = 0.0;
  double tangent_points_m = 0.0;  // T_b T_a = a_w sin a_w'
  // The mean mesh stiffness over a mesh period (the viscous damper's k).
  double mean_stiffness_n_per_m = 0.0;
};

class MeshLine {
 public:
  // The mesh of c.gears under c.model, with c.faults and c.modifications; the
  // table must cover the contact segment of c.gears, and both must outlive the
  // mesh. With c.faults, each pair reads the table of its two teeth
  // (MeshTables, built here with `table` as the healthy one), and a pair with
  // a missing tooth carries nothing.
  MeshLine(const SimulationCase& c, const StiffnessTable& table);
  // A mesh whose viscous damper (model.mesh_damping_ratio) sees the m_e of the
  // two bodies it joins, mass_kg > 0 (a train's), rather than that
  // of the pair's discs. `teeth`, when given (a helical slice's with c.faults,
  // TrainMesh::teeth), are the tables its pairs read in place of the ones
  // built from c.faults; `table` must be their healthy one.
  MeshLine(const SimulationCase& c, const StiffnessTable& table, double mass_kg,
           std::shared_ptr<const MeshTables> teeth = nullptr);
  // An internal mesh on `line`, `table` over [line.start_m, line.end_m]. Of
  // c, the model (contact, damping; its friction must be 0), the backlash and
  // the Hertzian stiffness's width and materials (Kh of (4) has no curvature),
  // and of its faults the missing teeth, numbered as a train's internal mesh
  // numbers them (gear 1 the ring of c.gears.teeth1 teeth, gear 2 the planet
  // of teeth2): a pair with one carries nothing. Its other faults and its
  // modifications are not read (the caller refuses them: ISO's table has no
  // tooth profile to change).
  MeshLine(const SimulationCase& c, const StiffnessTable& table, const InternalLine& line,
           double mass_kg);

  double base_radius_a() const { return rb1_; }
  double base_radius_b() const { return rb2_; }
  // mesh_force = "lagrangian" with a stiffness that varies: body a feels
  // -1/2 dKe/dtheta_a delta^2 and pays the stored energy's jumps.
  bool lagrangian() const { return lagrangian_; }
  // Whether the case's modifications put a gap between the flanks of a pair.
  bool has_gaps() const { return static_cast<bool>(gaps_); }

  // s = Rb_a theta_a - Rb_b theta_b and its rate.
  double s(const MeshMotion& q) const { return rb1_ * q.theta_a_rad - rb2_ * q.theta_b_rad; }
  double s_rate(const MeshMotion& q) const {
    return rb1_ * q.w_a_rad_per_s - rb2_ * q.w_b_rad_per_s;
  }
  // The unit normal of `line` in the frame of PlanarMeshMotion: (sin a, cos a)
  // on the drive line N1, (-sin a, cos a) on the coast line N2, a the
  // operating pressure angle.
  std::array<double, 2> normal(Region line) const {
    return {line == Region::n1 ? sin_a_ : -sin_a_, cos_a_};
  }
  // s of `line`: with rigid centres the same on both lines; in the planar
  // model s_d, s_c of docs/vibration.md, which add the centres' relative
  // displacement along the line's normal (the backlash breathes), and their rates.
  double s(Region, const MeshMotion& q) const { return s(q); }
  double s_rate(Region, const MeshMotion& q) const { return s_rate(q); }
  double s(Region line, const PlanarMeshMotion& q) const {
    const std::array<double, 2> n = normal(line);
    return rb1_ * q.theta_a_rad - rb2_ * q.theta_b_rad + q.dx_m * n[0] + q.dy_m * n[1];
  }
  double s_rate(Region line, const PlanarMeshMotion& q) const {
    const std::array<double, 2> n = normal(line);
    return rb1_ * q.w_a_rad_per_s - rb2_ * q.w_b_rad_per_s + q.dvx_m_s * n[0] + q.dvy_m_s * n[1];
  }
  // (31)
  template <typename Motion>
  double delta(Region r, const Motion& q) const {
    return penetration(r, s(r, q), backlash_);
  }
  // The largest penetration of a pair on `line`: the line's, less the least
  // gap of its pairs with modifications. The line is in contact while it is
  // positive, which is while one of its pairs touches (classify_line).
  template <typename Motion>
  double contact_value(Region line, const Motion& q) const {
    const double dl = delta(line, q);
    return gaps_ ? dl - least_gap_m(line, q.theta_a_rad) : dl;
  }
  template <typename Motion>
  double pair_position(const Mode& m, const Motion& q, int j) const {
    return layout_.position_m(layout_.reference_m(m.region, q.theta_a_rad), m.k_first + j);
  }

  // The forces of the mesh in the mode m on its bodies, added to their
  // moments (moment_a, moment_b, in their own senses), and the powers of the
  // ledger added to `powers`; the totals over the loaded pairs when asked.
  // Inlined into the systems' right-hand sides, always: a call there costs
  // as much as a stage of free flight.
  [[gnu::always_inline]] void add_forces(const MeshMotion& q, const Mode& m, const ContactMemory& d,
                                         double& moment_a, double& moment_b, MeshPowers& powers,
                                         ContactTotals* totals) const;
  // The planar model's: the forces of the pairs of one line's mode m (the
  // other line holds a mode of its own) on the bodies' turning and on their
  // centres, added to `loads`, the powers to `powers`, the totals when asked.
  // The viscous mesh damper is add_damper's.
  [[gnu::always_inline]] void add_line_forces(const PlanarMeshMotion& q, const Mode& m,
                                              const ContactMemory& d, PlanarLoads& loads,
                                              MeshPowers& powers, ContactTotals* totals) const;
  // The planar model's viscous mesh damper: half of c on each line of action
  // on that line's s' (s_d', s_c'), in contact and in the backlash alike; with
  // the centres fixed both rates are s' and the two halves are the torsional
  // c s' (docs/vibration.md). Each acts as a contact force of its line would.
  void add_damper(const PlanarMeshMotion& q, PlanarLoads& loads, MeshPowers& powers) const;

  // The mesh's event values in mode m, written from g[0]: each >= 0 while
  // the mode holds. Returns how many are set (at most kMaxMeshEvents).
  int event_values(const MeshMotion& q, const Mode& m, const ContactMemory& d, double* g) const;
  // The planar model's event values of `line` in its own mode m: in free
  // flight minus contact_value (the line's contact begins), in contact those
  // of event_values. Returns how many are set.
  int line_event_values(Region line, const PlanarMeshMotion& q, const Mode& m,
                        const ContactMemory& d, double* g) const;

  // Region and loaded pairs of the motion, (31) and (42), with the same tests as event_values.
  Mode classify_geometry(const MeshMotion& q) const;
  // The planar model's: the contact of `line` alone (free, or `line` with its
  // loaded pairs), with the same test as line_event_values.
  Mode classify_line(Region line, const PlanarMeshMotion& q) const;
  // Friction signs and clipping of the pairs of m at the motion.
  template <typename Motion>
  void classify_forces(const Motion& q, const ContactMemory& d, Mode& m) const;
  // After a mode change that kept the region: `now` (classified afresh) with the friction sign
  // and clipping of each pair that stays loaded carried over from `old`, unless this event is
  // theirs (an event value of the carried mode is then negative, and `now` stands).
  Mode carry_pair_signs(const MeshMotion& q, const Mode& old, const Mode& now,
                        const ContactMemory& d) const;

  // (32),(33) at the onset of a contact in mode m: Vi (floored), e(Vi) and D.
  struct Onset {
    double impact_speed_m_s;
    double restitution;
    ContactMemory damping;
  };
  template <typename Motion>
  Onset damping_at_onset(const Motion& q, const Mode& m) const;

  // (5),(16),(17),(28) of the loaded pairs, F = Ke delta each.
  ElasticEnergy stored_energy(const MeshMotion& q, const Mode& m) const {
    ElasticEnergy u;
    add_stored_energy(q, m, u);
    return u;
  }
  // The same added to u.
  template <typename Motion>
  void add_stored_energy(const Motion& q, const Mode& m, ElasticEnergy& u) const;
  // 1/2 Ke delta^2 of the loaded pairs with Ke as the force reads it (continued
  // along its tangent beyond the segment, pair_stiffness): the potential of
  // the elastic forces of add_forces, which the planar ledger books.
  template <typename Motion>
  double elastic_energy_j(const Motion& q, const Mode& m) const;

  // A bound b_i such that each term i of (29) of the stored energy in any mode
  // is at most b_i times the sum over the loaded pairs of the line's delta^2:
  // the largest 1/2 c_i / c_total^2 (a pair stores 1/2 delta^2 c_i / c_total^2
  // in a term of compliance c_i) over every table a pair can take and each
  // part it carries in, sampled 16 times on each of the table's pieces (smooth
  // polynomials, which move by far less than the 5 % added between two
  // samples). None with gaps (a gap can be negative, pitch and thickness
  // errors: a pair's delta may then exceed the line's) or a constant stiffness.
  std::optional<std::array<double, kTermCount>> term_energy_bound() const;

 private:
  void read_model_settings(const SimulationCase& c);
  // True for the planar model's motion: the centres move.
  template <typename Motion>
  static constexpr bool kCentres = std::is_same_v<Motion, PlanarMeshMotion>;
  // The sliding speed of a pair at X: (36)-(38), and in the planar model the
  // centres' relative speed along the flanks' common tangent t = e_z x n,
  // sign (u_a' - u_b') . t. The pinion's flank moves along t at w1 X on the
  // drive line and at -w1 X on the coast line (there the contact lies at
  // -X n2 from the pinion's base circle), so the sliding speed w1 X - w2 (lp
  // - X) the line's friction sign is taken from counts the centres' relative
  // speed along +t on N1 and along -t on N2 (docs/vibration.md).
  double centres_slide(Region line, const MeshMotion&) const {
    static_cast<void>(line);
    return 0.0;
  }
  double centres_slide(Region line, const PlanarMeshMotion& q) const {
    const std::array<double, 2> n = normal(line);
    return line_sign(line) * (q.dvx_m_s * -n[1] + q.dvy_m_s * n[0]);
  }
  template <typename Motion>
  double pair_sliding(const Motion& q, double x, double slide) const {
    if constexpr (kCentres<Motion>) {
      return sliding_speed(q.w_a_rad_per_s, q.w_b_rad_per_s, x, lp_) + slide;
    } else {
      static_cast<void>(slide);
      return sliding_speed(q.w_a_rad_per_s, q.w_b_rad_per_s, x, lp_);
    }
  }
  // The event values of a mode in contact, from g[0]; returns how many.
  template <typename Motion>
  int contact_event_values(const Motion& q, const Mode& m, const ContactMemory& d, double* g) const;
  // The contact of `line` at the motion, free when none of its pairs touches.
  template <typename Motion>
  Mode line_contact(Region line, const Motion& q) const;
  // The pairs' forces of a mode in contact, added to the moments and, in the
  // planar model, to the centres' forces `centres` (a's; b's the opposite).
  template <typename Motion>
  [[gnu::always_inline]] void add_pair_forces(const Motion& q, const Mode& m,
                                              const ContactMemory& d, double& moment_a,
                                              double& moment_b, PlanarLoads* centres,
                                              MeshPowers& powers, ContactTotals* totals) const;
  // The table of pair k on `line`: the healthy one, or with faults that of
  // the pair's teeth (nullptr: a missing tooth, the pair carries nothing).
  const StiffnessTable* pair_table(Region line, int k) const {
    if (teeth_) return teeth_->table(line, k);
    if (!absent_b_.empty()) {
      // An internal mesh with missing teeth: its planet is the line's gear 1.
      const TeethInContact t = teeth_of_pair(static_cast<int>(absent_a_.size()),
                                             static_cast<int>(absent_b_.size()), line, k);
      const bool gone = absent_a_[static_cast<std::size_t>(t.pinion_tooth)] != 0 ||
                        absent_b_[static_cast<std::size_t>(t.wheel_tooth)] != 0;
      return gone ? nullptr : table_;
    }
    return table_;
  }
  // Whether a pair on `table` in its part `part` can carry: not with a
  // missing tooth (no table), nor over the extent of a fault across the whole
  // face (a part without contact).
  static bool carries(const StiffnessTable* table, int part) {
    return table != nullptr && table->part_in_contact(part);
  }
  // Ke and dKe/dX of one of `count` loaded pairs at X, read from `table`
  // (from its part `part`, Mode::part).
  [[gnu::always_inline]] void pair_stiffness(const StiffnessTable& table, int part, double x,
                                             int count, double& ke, double& dke) const;
  // Mode::table and Mode::part of each pair of m at the motion.
  template <typename Motion>
  void set_parts(const Motion& q, Mode& m) const;
  double damping_factor(const ContactMemory& d, double ke) const;
  // f of (35) of a pair with normal force N, sliding speed Vs and entrainment
  // speed Ve, under the case's friction law.
  double friction_coefficient(double normal_force_n, double vs, double ve) const;
  double push_sign_function(const StiffnessTable* table, int part, double x, int count,
                            const ContactMemory& d, double dl, double dl_rate) const;
  // Pair j of mode m at X with the line's penetration dl and its rate: its
  // own penetration dl - e_k(X) and rate dl_rate - de_k/dX dX/dt, and the
  // slope de_k/dX, on the branch of the pair's zone (Mode::zone). Without
  // gaps, the line's own penetration and rate and a slope of 0.
  PairPenetration pair_penetration(const Mode& m, int j, double x, double dl, double dl_rate,
                                   double x_rate) const;
  // The least gap of the pairs in the contact segment of `line` at theta_a:
  // the line's contact begins where its penetration passes it.
  double least_gap_m(Region line, double theta_a) const;

  const StiffnessTable* table_;
  // With faults: the table of each pair's teeth.
  std::shared_ptr<const MeshTables> teeth_;
  // An internal mesh with missing teeth: whether each tooth of the line's gear
  // 1 (the planet) and gear 2 (the ring) is missing; both empty otherwise.
  std::vector<char> absent_a_;
  std::vector<char> absent_b_;
  // With modifications: each pair's gap (docs/faults.md); none without, so
  // that an unmodified case runs the code it ran before, bit for bit.
  std::shared_ptr<const ToothGaps> gaps_;
  std::vector<double> kinks_;  // gaps_->kinks_m()
  const ModelOptions* model_;
  const GearPair* gears_;
  MeshLayout layout_;
  double rb1_ = 0.0, rb2_ = 0.0, backlash_ = 0.0, lp_ = 0.0;
  double x_pitch_ = 0.0, xs_ = 0.0, xe_ = 0.0;
  double sin_a_ = 0.0, cos_a_ = 0.0;  // of the operating pressure angle
  double kh_ = 0.0, constant_k_ = 0.0;
  double smoothing_speed_ = 0.0;  // v_s of tanh(Vs / v_s); 0: the exact sign
  double face_width_ = 0.0;
  double mesh_damping_ = 0.0;  // c of the viscous mesh damper, N s/m
  bool damping_on_current_pair_ = true;
  bool lagrangian_ = false;
  // A helical pair's transverse section (GearPair::face_advance_m > 0): its
  // table is cut at its kinks, and its energy split by the terms' shares.
  bool swept_ = false;
  // A helical pair with friction: the face sums of its pairs' friction
  // (route B); none otherwise, so that a spur pair runs the code it ran
  // before, bit for bit.
  std::shared_ptr<const FaceFriction> face_friction_;
  DampingUpdate damping_update_ = DampingUpdate::each_impact;  // resolved
};

// The force's functions, inline: the systems' right-hand sides call them for
// every loaded pair at every stage.

inline double MeshLine::friction_coefficient(double normal_force_n, double vs, double ve) const {
  return pair_friction_coefficient(*model_, face_width_, normal_force_n, vs, ve);
}

inline PairPenetration MeshLine::pair_penetration(const Mode& m, int j, double x, double dl,
                                                  double dl_rate, double x_rate) const {
  if (!gaps_) return {dl, dl_rate, 0.0};
  // The zone's branch, as the mode holds it: a stage state of a step that
  // ends on a kink sees the zone's own gap.
  return pair_penetration_with_gap(*gaps_, kinks_, m.zone[j], m.region, m.k_first + j, x, dl,
                                   dl_rate, x_rate, xs_, xe_);
}

inline double MeshLine::damping_factor(const ContactMemory& d, double ke) const {
  return damping_on_current_pair_ ? d.damping_per_stiffness_s_m * ke
                                  : d.damping_per_stiffness_s_m * d.frozen_stiffness_n_per_m;
}

// Ke continued along its tangent beyond the segment, or beyond the ends of
// the pair's part at a fault's edge (pair_stiffness_continued).
inline void MeshLine::pair_stiffness(const StiffnessTable& table, int part, double x, int count,
                                     double& ke, double& dke) const {
  if (constant_k_ > 0.0) {
    ke = constant_k_ / count;
    dke = 0.0;
    return;
  }
  const StiffnessAndDerivative k =
      table.part_count() > 1 ? pair_stiffness_continued(table, part, x, table.part_start_m(part),
                                                        table.part_end_m(part))
                             : pair_stiffness_continued(table, -1, x, xs_, xe_);
  ke = k.stiffness_n_per_m;
  dke = k.derivative_n_per_m2;
}

template <typename Motion>
inline void MeshLine::add_pair_forces(const Motion& q, const Mode& m, const ContactMemory& d,
                                      double& moment_a, double& moment_b, PlanarLoads* centres,
                                      MeshPowers& powers, ContactTotals* totals) const {
  const double w1 = q.w_a_rad_per_s;
  const double w2 = q.w_b_rad_per_s;
  const double sign = line_sign(m.region);
  const double dl = delta(m.region, q);
  const double dl_rate = sign * s_rate(m.region, q);
  const double ref = layout_.reference_m(m.region, q.theta_a_rad);
  const double x_rate = sign * rb1_ * w1;
  const double slide = centres_slide(m.region, q);
  for (int j = 0; j < m.count; ++j) {
    const StiffnessTable* table = m.table[j];
    // A pair with a missing tooth or without contact over a fault across the
    // face: no force, no damping, no friction; nor a pair whose gap is open.
    if (!carries(table, m.part[j]) || (gaps_ && !m.touching[j])) continue;
    const double x = layout_.position_m(ref, m.k_first + j);
    // The pair's own penetration and its rate: the line's, less the gap.
    const PairPenetration p = pair_penetration(m, j, x, dl, dl_rate, x_rate);
    const double dk = p.delta_m;
    const double dk_rate = p.rate_m_s;
    const double gap_slope = p.gap_slope;
    double ke = 0.0;
    double dke = 0.0;
    pair_stiffness(*table, m.part[j], x, m.count, ke, dke);
    const double f_elastic = elastic_force(ke, dk);
    const double g_damping = hertzian_damping_force(damping_factor(d, ke), dk, dk_rate);
    const double n = normal_force(f_elastic, g_damping, m.clipped[j]);
    double f = 0.0;
    double ff = 0.0;
    if (face_friction_) {
      // A helical pair: N spread along its contact line as its elastic load,
      // kappa_t(X'), each point with its own sliding sign and arms X', lp -
      // X' (docs/helical.md, Friction on a helical pair). Vs(X') = (w1 + w2)
      // X' - w2 lp plus the centres' slide is linear in X'. The sum of Ff X'
      // over the line is Ff's with the mean signed arm in place of slip X.
      // Coulomb's law on the flank's normal force N / cos(beta_b): f / cos(beta_b) of N.
      const double rate = w1 + w2;
      const double offset = sliding_speed(w1, w2, 0.0, lp_) + slide;
      const FaceSlip face = face_friction_->slip(x, rate, offset);
      f = model_->friction_coefficient * face_friction_->normal_per_transverse();
      ff = friction_force(m.region, f, n, face.slip);
      const double ff_arm = friction_force(m.region, f, n, face.arm_m);
      moment_a -= sign * (n * rb1_ + ff_arm);
      moment_b += sign * (n * rb2_ + (ff * lp_ - ff_arm));
      // f N times the load-weighted mean of |Vs| = sign(Vs) (rate X' + offset).
      powers.friction_w += f * n * (face.arm_m * rate + face.slip * offset);
    } else {
      const double vs = pair_sliding(q, x, slide);
      f = friction_coefficient(n, vs, entrainment_speed(w1, w2, x, lp_));
      const double slip = smoothing_speed_ > 0.0 ? std::tanh(vs / smoothing_speed_)
                          : m.slip_per_stage     ? (vs >= 0.0 ? 1.0 : -1.0)
                                                 : m.slip[j];
      ff = friction_force(m.region, f, n, slip);
      // (1),(3) for one pair, (43),(45) summed over the pairs the line carries:
      // on N1 J1 w1' = T1 - [N Rb1 + Ff X], J2 w2' = T2 + [N Rb2 + Ff (lp - X)];
      // every sign flips on N2. In free flight, (2),(44): J w' = T.
      moment_a -= sign * (n * rb1_ + ff * x);
      moment_b += sign * (n * rb2_ + ff * (lp_ - x));
      powers.friction_w += f * n * slip * vs;
    }
    if constexpr (kCentres<Motion>) {
      // On the pinion's centre -sign N n - Ff t, t = e_z x n the flanks'
      // common tangent, on the wheel's the opposite. The friction's sign does
      // not follow the line's: Ff t at the contact has the moment +Ff X about
      // O1 on N1 (the contact at +X n1 from the pinion's base circle) and -Ff
      // X on N2 (at -X n2), so -Ff t is what gives the pinion the torque
      // -sign Ff X above on either line.
      const std::array<double, 2> nl = normal(m.region);
      const double tx = -nl[1];
      const double ty = nl[0];
      const double fx = -sign * (n * nl[0] + sign * ff * tx);
      const double fy = -sign * (n * nl[1] + sign * ff * ty);
      centres->force_a[0] += fx;
      centres->force_a[1] += fy;
      centres->force_b[0] -= fx;
      centres->force_b[1] -= fy;
    } else {
      static_cast<void>(centres);
    }
    // The damping force is what N adds to F; with N clipped it is -F, so the
    // stored energy released while the tooth cannot push counts as damping loss.
    powers.damping_w += (n - f_elastic) * dk_rate;
    // d/dt of 1/2 Ke(X) delta^2 at fixed delta. Newtonian: work of the
    // varying stiffness. Lagrangian: -dV/dtheta1 adds the torque
    // -1/2 dKe/dX (dX/dtheta1) delta^2, dX/dtheta1 = sign Rb1, whose power is
    // minus this; a clipped pair exerts no force, so the stored energy it
    // gains or loses counts with its damping loss, as above.
    const double stiffness_power = 0.5 * dk * dk * dke * x_rate;
    if (!lagrangian_) {
      powers.parametric_w += stiffness_power;
    } else if (m.clipped[j]) {
      powers.damping_w -= stiffness_power;
    } else {
      moment_a -= 0.5 * dk * dk * dke * sign * rb1_;
    }
    if (gaps_) {
      // The gap moves with the pinion: the pair's penetration changes at
      // fixed s by -de_k/dX dX/dt, and N acting on it does the work
      // -N de_k/dX dX/dt. Newtonian: more work of the varying mesh.
      // Lagrangian: N acts on delta_k, whose lever on the pinion is
      // sign Rb1 (1 - de_k/dX), and that torque does this work on the pinion.
      if (!lagrangian_) {
        powers.parametric_w -= n * gap_slope * x_rate;
      } else {
        moment_a += sign * rb1_ * n * gap_slope;
      }
    }
    if (totals != nullptr) {
      totals->normal_force_n += n;
      totals->friction_force_n += ff;
      totals->friction_load_n += f * n;
      totals->elastic_energy_j += 0.5 * ke * dk * dk;
    }
  }
}

inline void MeshLine::add_forces(const MeshMotion& q, const Mode& m, const ContactMemory& d,
                                 double& moment_a, double& moment_b, MeshPowers& powers,
                                 ContactTotals* totals) const {
  if (m.region != Region::free) {
    add_pair_forces(q, m, d, moment_a, moment_b, nullptr, powers, totals);
  }
  if (mesh_damping_ > 0.0) {
    // The viscous mesh damper acts on s' at all times, in contact and in the
    // backlash alike, as the c x' of docs/steady-state.md's clearance oscillator:
    // a force c s' along the line of action in the sense of an N1 contact force.
    const double rate = s_rate(q);
    const double force = mesh_damping_ * rate;
    moment_a -= force * rb1_;
    moment_b += force * rb2_;
    powers.mesh_damping_w += force * rate;
  }
}

inline void MeshLine::add_line_forces(const PlanarMeshMotion& q, const Mode& m,
                                      const ContactMemory& d, PlanarLoads& loads,
                                      MeshPowers& powers, ContactTotals* totals) const {
  if (m.region == Region::free) return;
  add_pair_forces(q, m, d, loads.moment_a, loads.moment_b, &loads, powers, totals);
}

inline void MeshLine::add_damper(const PlanarMeshMotion& q, PlanarLoads& loads,
                                 MeshPowers& powers) const {
  if (!(mesh_damping_ > 0.0)) return;
  for (const Region line : {Region::n1, Region::n2}) {
    const std::array<double, 2> n = normal(line);
    const double rate = s_rate(line, q);
    const double force = 0.5 * mesh_damping_ * rate;
    loads.moment_a -= force * rb1_;
    loads.moment_b += force * rb2_;
    loads.force_a[0] -= force * n[0];
    loads.force_a[1] -= force * n[1];
    loads.force_b[0] += force * n[0];
    loads.force_b[1] += force * n[1];
    powers.mesh_damping_w += force * rate;
  }
}

}  // namespace gearimpact
