#include "gearimpact/dynamics/planar.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"

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
};

class PlanarSystem {
 public:
  PlanarSystem(const SimulationCase& c, const StiffnessTable& table, const PlanarMounting& m)
      : c_(c), m_(m), table_(table), layout_(c.gears, c.model.coast_phase) {
    const GearPair& g = c.gears;
    rb1_ = base_radius(g, Gear::one);
    rb2_ = base_radius(g, Gear::two);
    j1_ = moment_of_inertia(g, Gear::one);
    j2_ = moment_of_inertia(g, Gear::two);
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
    if (!c.faults.empty() && constant_k_ == 0.0) {
      teeth_ = std::make_shared<const MeshTables>(
          g, c.model.stiffness, c.faults,
          std::shared_ptr<const StiffnessTable>(&table, [](const StiffnessTable*) {}));
    }
    if (!teeth_ && constant_k_ == 0.0) {
      // A pair stores 0.5 delta^2 c / c_total^2 in a term of compliance c
      // (F = delta / c_total): the factor's largest value over the segment,
      // sampled 16 times on each of the table's pieces (smooth polynomials,
      // which move by far less than the 5 % added between two samples).
      const int samples = 16 * table.pieces();
      for (int j = 0; j <= samples; ++j) {
        const double x = std::min(xs_ + (xe_ - xs_) * j / samples, xe_);
        const Compliances at = table.compliance(x);
        const double total = at.total_m_per_n();
        for (std::size_t i = 0; i < kTermCount; ++i) {
          term_bound_[i] = std::max(term_bound_[i], 1.05 * 0.5 * at.m_per_n[i] / (total * total));
        }
      }
      bounded_ = true;
    }
  }

  double rb1() const { return rb1_; }
  double rb2() const { return rb2_; }

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

  LoadedRange loaded(Region side, double theta1) const {
    return layout_.loaded(layout_.reference_m(side, theta1));
  }

  // The table of pair k on `side`: the healthy one, or with faults that of
  // the pair's teeth (nullptr: a missing tooth, the pair carries nothing).
  const StiffnessTable* pair_table(Region side, int k) const {
    return teeth_ ? teeth_->table(side, k) : &table_;
  }

  // Ke of pair k of `count` loaded pairs on `side` at X, continued along its
  // tangent beyond the segment (a stage state of a step may reach a hair past
  // it), and dKe/dX; 0 for a pair with a missing tooth.
  std::pair<double, double> pair_stiffness(Region side, int k, int count, double x) const {
    if (constant_k_ > 0.0) return {constant_k_ / count, 0.0};
    const StiffnessTable* table = pair_table(side, k);
    if (table == nullptr) return {0.0, 0.0};
    const StiffnessAndDerivative s = pair_stiffness_continued(*table, -1, x, xs_, xe_);
    return {s.stiffness_n_per_m, s.derivative_n_per_m2};
  }

  // The mesh's stored energy of `side` at y with the pairs of `range`.
  double mesh_energy(Region side, const Y& y, LoadedRange range) const {
    const double dl = penetration(side, y).first;
    if (dl <= 0.0) return 0.0;
    const double ref = layout_.reference_m(side, y[kT1]);
    double u = 0.0;
    for (int j = 0; j < range.count; ++j) {
      const int k = range.k_first + j;
      u += 0.5 * pair_stiffness(side, k, range.count, layout_.position_m(ref, k)).first * dl * dl;
    }
    return u;
  }

  // The mesh's stored energy of both sides by term of (29), as the
  // torsional ledger reports it (F = Ke delta of each pair inside the segment),
  // with the pairs of `ranges` (those loaded at y).
  ElasticEnergy mesh_terms(const Y& y, const std::array<LoadedRange, 2>& ranges) const {
    ElasticEnergy u;
    for (const Region side : kSides) {
      const double dl = penetration(side, y).first;
      if (dl <= 0.0) continue;
      const double ref = layout_.reference_m(side, y[kT1]);
      const LoadedRange range = ranges[side_index(side)];
      for (int j = 0; j < range.count; ++j) {
        const int k = range.k_first + j;
        if (constant_k_ > 0.0) {
          u.j[index_of(Term::hertz)] += 0.5 * constant_k_ / range.count * dl * dl;
          continue;
        }
        const StiffnessTable* table = pair_table(side, k);
        if (table == nullptr) continue;
        const Compliances c = table->compliance(std::clamp(layout_.position_m(ref, k), xs_, xe_));
        const ElasticEnergy pair = pair_energy(c, dl / c.total_m_per_n());
        for (std::size_t i = 0; i < kTermCount; ++i) u.j[i] += pair.j[i];
      }
    }
    return u;
  }

  // Whether a term's energy at y (mesh_terms) could exceed its entry of
  // `most`: not when the bound above stays below every entry, and the ledger
  // then need not evaluate the terms (most steps, once the largest
  // penetration has passed).
  bool terms_may_exceed(const Y& y, const std::array<LoadedRange, 2>& ranges,
                        const std::array<double, kTermCount>& most) const {
    if (!bounded_) return true;
    double squares = 0.0;  // delta^2 summed over the loaded pairs
    for (const Region side : kSides) {
      const double dl = penetration(side, y).first;
      if (dl > 0.0) squares += ranges[side_index(side)].count * dl * dl;
    }
    for (std::size_t i = 0; i < kTermCount; ++i) {
      if (term_bound_[i] * squares > most[i]) return true;
    }
    return false;
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

  // The equations of motion with the contact memory of each side.
  void rhs(double t, const Y& y, const std::array<ContactMemory, 2>& memory, Y& dy,
           Forces* forces = nullptr) const {
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
      const auto [dl, dl_rate] = penetration(side, y);
      if (dl <= 0.0) continue;
      const std::size_t i = side_index(side);
      const double sign = line_sign(side);
      const auto n = normal(side);
      // t = e_z x n: the flanks' common tangent, along which friction acts.
      const double tx = -n[1];
      const double ty = n[0];
      // The centres' relative speed along t adds to the flanks' sliding.
      const double slide_of_centres = (v[kX1] - v[kX2]) * tx + (v[kY1] - v[kY2]) * ty;
      const double ref = layout_.reference_m(side, y[kT1]);
      const LoadedRange range = layout_.loaded(ref);
      const double x_rate = sign * rb1_ * w1;
      double total = 0.0;
      for (int j = 0; j < range.count; ++j) {
        const int k = range.k_first + j;
        const double x = layout_.position_m(ref, k);
        // A pair with a missing tooth: no force, no damping, no friction.
        if (pair_table(side, k) == nullptr) continue;
        const auto [ke, dke] = pair_stiffness(side, k, range.count, x);
        const double f_elastic = elastic_force(ke, dl);
        const double d =
            c_.model.damping_stiffness == DampingStiffness::current_pair
                ? memory[i].damping_per_stiffness_s_m * ke
                : memory[i].damping_per_stiffness_s_m * memory[i].frozen_stiffness_n_per_m;
        const double pushed = f_elastic + hertzian_damping_force(d, dl, dl_rate);
        // A tooth pushes, never pulls: the clipping is not located, each
        // stage takes it from its own state.
        const double normal_n = normal_force(f_elastic, pushed - f_elastic, pushed < 0.0);
        // (36)-(38) with the centres' sliding: the speed whose product with
        // f N is the friction's loss (docs/vibration.md).
        const double vs = sliding_speed(w1, w2, x, lp_) + slide_of_centres;
        const double f = pair_friction_coefficient(c_.model, c_.gears.face_width_m, normal_n, vs,
                                                   entrainment_speed(w1, w2, x, lp_));
        const double smoothing = c_.model.friction_smoothing_speed_m_s;
        const double slip = smoothing > 0.0 ? std::tanh(vs / smoothing) : (vs >= 0.0 ? 1.0 : -1.0);
        const double ff = friction_force(side, f, normal_n, slip);
        moment1 -= sign * (normal_n * rb1_ + ff * x);
        moment2 += sign * (normal_n * rb2_ + ff * (lp_ - x));
        // On the pinion -sign N n - sign Ff t, on the wheel the opposite.
        const double fx = -sign * (normal_n * n[0] + ff * tx);
        const double fy = -sign * (normal_n * n[1] + ff * ty);
        f1[0] += fx;
        f1[1] += fy;
        f2[0] -= fx;
        f2[1] -= fy;
        hertz_power += (normal_n - f_elastic) * dl_rate;
        friction_power += f * normal_n * slip * vs;
        parametric_power += 0.5 * dl * dl * dke * x_rate;
        total += normal_n;
        if (forces != nullptr) forces->friction_n += ff;
      }
      if (forces != nullptr) {
        forces->normal_n[i] = total;
        forces->penetration_m[i] = dl;
      }
    }
    double t1 = torque(c_.torque1, t);
    double t2 = torque(c_.torque2, t);
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
      dy[kVelocity + kTm] = (t1 - shaft_m) / m_.motor_inertia_kg_m2;
      dy[kVelocity + kTl] = (t2 - shaft_l) / m_.load_inertia_kg_m2;
      work = t1 * v[kTm] + t2 * v[kTl];
      shaft_power = m_.motor_damping_n_m_s_per_rad * rel_m * rel_m +
                    m_.load_damping_n_m_s_per_rad * rel_l * rel_l;
      t1 = shaft_m;
      t2 = shaft_l;
    }
    for (const std::size_t q : {kX1, kY1, kT1, kX2, kY2, kT2}) dy[q] = v[q];
    dy[kVelocity + kX1] = f1[0] / m_.mass_kg[0];
    dy[kVelocity + kY1] = f1[1] / m_.mass_kg[0];
    dy[kVelocity + kT1] = (t1 + moment1) / j1_;
    dy[kVelocity + kX2] = f2[0] / m_.mass_kg[1];
    dy[kVelocity + kY2] = f2[1] / m_.mass_kg[1];
    dy[kVelocity + kT2] = (t2 + moment2) / j2_;
    dy[kWork] = work;
    dy[kHertzLoss] = hertz_power;
    dy[kSlidingLoss] = friction_power;
    dy[kParametric] = parametric_power;
    dy[kBearingLoss] = bearing_power;
    dy[kShaftLoss] = shaft_power;
  }

  // torque_at without its call for a constant torque, the common case
  // (the call costs as much as a pair's forces).
  static double torque(const Torque& q, double t) {
    return q.kind == Torque::Kind::constant ? q.constant_n_m : torque_at(q, t);
  }

  // The memory of a contact that begins on `side` at y.
  ContactMemory onset(Region side, const Y& y, double& impact_speed, double& restitution) const {
    const OnsetDamping d = onset_damping(c_.model, penetration(side, y).second);
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
      const LoadedRange range = layout_.loaded(ref);
      const double pitch = pitch_point_position(c_.gears);
      int nearest = -1;
      for (int k = range.k_first; k < range.k_first + range.count; ++k) {
        if (pair_table(side, k) == nullptr) continue;
        if (nearest < 0 || std::fabs(layout_.position_m(ref, k) - pitch) <
                               std::fabs(layout_.position_m(ref, nearest) - pitch)) {
          nearest = k;
        }
      }
      if (nearest >= 0) {
        memory.frozen_stiffness_n_per_m =
            pair_stiffness(side, nearest, range.count, layout_.position_m(ref, nearest)).first;
      }
    }
    return memory;
  }

 private:
  const SimulationCase& c_;
  const PlanarMounting& m_;
  const StiffnessTable& table_;
  std::shared_ptr<const MeshTables> teeth_;
  MeshLayout layout_;
  double rb1_ = 0.0, rb2_ = 0.0, j1_ = 0.0, j2_ = 0.0, backlash_ = 0.0, lp_ = 0.0;
  double xs_ = 0.0, xe_ = 0.0, sin_a_ = 0.0, cos_a_ = 0.0, constant_k_ = 0.0;
  // The bound of terms_may_exceed per term, J/m^2 (bounded_ with the healthy table).
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

void validate_planar(const SimulationCase& c, const PlanarMounting& m, const RunControl& control) {
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
  for (const auto& [key, torque] :
       {std::pair<const char*, const Torque*>{"torque1.kind", &c.torque1},
        std::pair<const char*, const Torque*>{"torque2.kind", &c.torque2}}) {
    if (torque->kind == Torque::Kind::prescribed_speed || torque->kind == Torque::Kind::drag) {
      refuse(key, torque->kind == Torque::Kind::drag ? "drag" : "prescribed-speed",
             "\"constant\", \"sinusoidal\", \"harmonic\" or a user function");
    }
  }
  if (c.model.mesh_force == MeshForce::lagrangian &&
      c.model.mesh_stiffness != MeshStiffnessMode::constant) {
    refuse("model.mesh_force", "lagrangian", "\"newtonian\"");
  }
  if (c.model.mesh_damping_ratio > 0.0) {
    refuse("model.mesh_damping_ratio", format_number(c.model.mesh_damping_ratio),
           "0 (the viscous mesh damper acts on the torsional s only)");
  }
  if (!is_unmodified(c.modifications)) {
    refuse("modifications", "a relief or a tooth error", "none (the gaps are torsional only yet)");
  }
  if (c.integrator.kind != IntegratorKind::rk4) refuse("integrator.kind", "adaptive", "\"rk4\"");
  if (control.sample_rate_hz) {
    refuse("sample_rate", format_number(*control.sample_rate_hz) + " Hz",
           "none (the planar series has every integrator.output_every-th step)");
  }
  if (control.resume) refuse("resume", "a run state", "none (a planar run starts afresh)");
}

namespace {

// The step must resolve the fastest motion the planar system can have. Its
// largest w^2 is at most the sum over the springs of k a^T M^-1 a (each
// spring k a a^T adds at most that eigenvalue of M^-1/2 K M^-1/2), the mesh
// counted on both sides at its stiffest.
void check_step(const SimulationCase& c, const StiffnessTable& table, const PlanarMounting& m) {
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
  double w2 = 2.0 * stiffest_mesh * (inverse_torsional + 1.0 / m.mass_kg[0] + 1.0 / m.mass_kg[1]);
  for (std::size_t i = 0; i < 2; ++i) {
    w2 += (m.stiffness_x_n_per_m[i] + m.stiffness_y_n_per_m[i]) / m.mass_kg[i];
  }
  if (m.shafts) {
    w2 += m.motor_stiffness_n_m_per_rad * (1.0 / m.motor_inertia_kg_m2 + 1.0 / j1) +
          m.load_stiffness_n_m_per_rad * (1.0 / m.load_inertia_kg_m2 + 1.0 / j2);
  }
  const double largest = 2.0 * pi / std::sqrt(w2) / kStepsPerContactPeriod;
  if (c.integrator.step_s > largest) {
    throw InputError("integrator.step", format_number(c.integrator.step_s) + " s",
                     "at most " + format_number(largest) +
                         " s with [bearings] kind = "
                         "\"elastic\": 1/" +
                         format_number(kStepsPerContactPeriod) +
                         " of the shortest period the planar system can have (its stiffest "
                         "springs: the mesh on both sides, the bearings" +
                         std::string(m.shafts ? ", the shafts" : "") + ")");
  }
}

// The location of a contact's onset or end: at most this many trial steps,
// to a bracket of this fraction of integrator.step (the kink's integration
// error then falls far below RK4's own).
constexpr int kMostLocationIterations = 100;
constexpr double kLocationTolerance = 1e-10;

void rk4(const PlanarSystem& s, double t, const Y& y, double h,
         const std::array<ContactMemory, 2>& memory, Y& out) {
  Y k1, k2, k3, k4, stage;
  s.rhs(t, y, memory, k1);
  for (std::size_t i = 0; i < kSize; ++i) stage[i] = y[i] + 0.5 * h * k1[i];
  s.rhs(t + 0.5 * h, stage, memory, k2);
  for (std::size_t i = 0; i < kSize; ++i) stage[i] = y[i] + 0.5 * h * k2[i];
  s.rhs(t + 0.5 * h, stage, memory, k3);
  for (std::size_t i = 0; i < kSize; ++i) stage[i] = y[i] + h * k3[i];
  s.rhs(t + h, stage, memory, k4);
  for (std::size_t i = 0; i < kSize; ++i) {
    out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
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

SimulationResult simulate_planar(const SimulationCase& c, const StiffnessTable& table,
                                 const PlanarMounting& mounting, const PlanarState& initial,
                                 const RunControl& control) {
  validate_planar(c, mounting, control);
  check_step(c, table, mounting);
  const PlanarSystem system(c, table, mounting);
  SimulationResult result;
  SimulationSummary& s = result.summary;
  s.case_name = c.name;
  s.integrator = "rk4";
  s.friction_coefficient = c.model.friction_coefficient;
  s.friction_law = c.model.friction_law;
  s.step_s = c.integrator.step_s;
  s.stiffness_model = c.model.stiffness.kind;
  s.planar = PlanarEnergies{};
  PlanarEnergies& p = *s.planar;

  Y y = to_vector(initial);
  const double h = c.integrator.step_s;
  const auto steps = static_cast<long long>(std::ceil(c.integrator.end_time_s / h - 1e-9));
  std::array<ContactMemory, 2> memory{};
  std::array<bool, 2> touching{};
  std::array<LoadedRange, 2> ranges{};
  std::array<std::optional<std::size_t>, 2> open_impact;
  const auto mesh_energy = [&](const Y& state) {
    return system.mesh_energy(Region::n1, state, ranges[0]) +
           system.mesh_energy(Region::n2, state, ranges[1]);
  };
  const auto begin_contacts = [&](double t) {
    for (const Region side : kSides) {
      const std::size_t i = side_index(side);
      const bool now = system.penetration(side, y).first > 0.0;
      if (now && !touching[i]) {
        ImpactRecord impact{};
        impact.line = side;
        impact.start_s = t;
        memory[i] = system.onset(side, y, impact.impact_speed_m_s, impact.restitution);
        (side == Region::n1 ? s.impacts_n1 : s.impacts_n2) += 1;
        if (!s.first_impact_s) {
          s.first_impact_s = t;
          s.first_impact_speed_m_s = impact.impact_speed_m_s;
        }
        (side == Region::n1 ? s.last_n1_impact_s : s.last_n2_impact_s) = t;
        open_impact[i] = result.impacts.size();
        result.impacts.push_back(impact);
      } else if (!now && touching[i] && open_impact[i]) {
        ImpactRecord& impact = result.impacts[*open_impact[i]];
        impact.end_s = t;
        impact.end_speed_m_s = -system.penetration(side, y).second;
        open_impact[i].reset();
      }
      touching[i] = now;
    }
  };
  const auto record = [&](double t) {
    if (!control.keep_series && !control.on_row && !control.on_planar_row) return;
    Y dy{};
    Forces f;
    system.rhs(t, y, memory, dy, &f);
    const PlanarState st = to_state(y, mounting.shafts);
    SeriesRow row{};
    row.t_s = t;
    row.theta1_rad = st.theta1_rad;
    row.theta2_rad = st.theta2_rad;
    row.w1_rad_per_s = st.w1_rad_per_s;
    row.w2_rad_per_s = st.w2_rad_per_s;
    // The drive line's s_d and the larger penetration; the side in contact
    // (the drive side when both are).
    row.s_m = system.penetration(Region::n1, y).first + c.gears.backlash_m;
    const double dd = system.penetration(Region::n1, y).first;
    const double dc = system.penetration(Region::n2, y).first;
    row.delta_m = std::max(dd, dc);
    row.region = dd > 0.0 ? 1 : (dc > 0.0 ? -1 : 0);
    row.pairs = dd > 0.0 ? ranges[0].count : (dc > 0.0 ? ranges[1].count : 0);
    row.normal_force_n = f.normal_n[0] + f.normal_n[1];
    row.friction_force_n = f.friction_n;
    if (control.on_row) control.on_row(row);
    if (control.keep_series) result.series.push_back(row);
    PlanarRow pr;
    pr.t_s = t;
    pr.state = st;
    pr.bearing_fx1_n =
        -mounting.stiffness_x_n_per_m[0] * st.x1_m - mounting.damping_x_n_s_per_m[0] * st.vx1_m_s;
    pr.bearing_fy1_n =
        -mounting.stiffness_y_n_per_m[0] * st.y1_m - mounting.damping_y_n_s_per_m[0] * st.vy1_m_s;
    pr.bearing_fx2_n =
        -mounting.stiffness_x_n_per_m[1] * st.x2_m - mounting.damping_x_n_s_per_m[1] * st.vx2_m_s;
    pr.bearing_fy2_n =
        -mounting.stiffness_y_n_per_m[1] * st.y2_m - mounting.damping_y_n_s_per_m[1] * st.vy2_m_s;
    pr.drive_force_n = f.normal_n[0];
    pr.coast_force_n = f.normal_n[1];
    pr.drive_penetration_m = dd;
    pr.coast_penetration_m = dc;
    if (control.on_planar_row) control.on_planar_row(pr);
    if (control.keep_series) result.planar_series.push_back(pr);
  };

  for (const Region side : kSides) ranges[side_index(side)] = system.loaded(side, y[kT1]);
  begin_contacts(0.0);
  const double kinetic0 = system.kinetic_energy(y);
  const double mesh0 = mesh_energy(y);
  s.kinetic_energy_initial_j = kinetic0;
  s.stored_energy_initial_j = mesh0;
  p.bearing_energy_initial_j = system.bearing_energy(y);
  p.shaft_energy_initial_j = system.shaft_energy(y);
  const double energy0 = kinetic0 + mesh0 + p.bearing_energy_initial_j + p.shaft_energy_initial_j;
  double jump_work = 0.0;
  record(0.0);
  Y next{};
  double t = 0.0;
  const auto contact = [&](Region side, const Y& state) {
    return system.penetration(side, state).first > 0.0;
  };
  for (long long n = 1; n <= steps;) {
    const double t_grid = std::min(static_cast<double>(n) * h, c.integrator.end_time_s);
    const double full = t_grid - t;
    rk4(system, t, y, full, memory, next);
    s.rhs_evaluations += 4;
    // A side whose contact begins or ends inside the step: the step is cut
    // back to that instant (the force's kink there would cost RK4 its
    // order), located on the step's length by the Illinois method, ending
    // just past it so that the new contact state is booked.
    double length = full;
    for (const Region side : kSides) {
      if (contact(side, y) == contact(side, next)) continue;
      const bool before = contact(side, y);
      const auto value = [&](double l, Y& out) {
        rk4(system, t, y, l, memory, out);
        s.rhs_evaluations += 4;
        return system.penetration(side, out).first;
      };
      double lo = 0.0;
      double hi = length;
      Y trial{};
      double g_lo = system.penetration(side, y).first;
      double g_hi = value(hi, trial);
      if (contact(side, trial) == before) continue;  // an earlier side's cut ends before
      int stale = 0;
      for (int i = 0; i < kMostLocationIterations && hi - lo > kLocationTolerance * h; ++i) {
        double l = hi - g_hi * (hi - lo) / (g_hi - g_lo);
        if (!(l > lo && l < hi)) l = 0.5 * (lo + hi);
        const double g = value(l, trial);
        if ((g > 0.0) == before) {
          lo = l;
          g_lo = g;
          // Illinois: halve the kept end's value when the same end stays.
          if (stale++ > 0) g_hi *= 0.5;
        } else {
          hi = l;
          g_hi = g;
          stale = 0;
        }
      }
      length = hi;
    }
    if (length < full) {
      rk4(system, t, y, length, memory, next);
      s.rhs_evaluations += 4;
      ++s.events;
    }
    const double t_next = length < full ? t + length : t_grid;
    if (!std::all_of(next.begin(), next.end(), [](double v) { return std::isfinite(v); })) {
      throw SimulationError(
          "the planar run diverged: the state is not finite at t = " + format_number(t_next) +
          " s, step " + std::to_string(n) + "; a smaller integrator.step may resolve it");
    }
    y = next;
    t = t_next;
    ++s.steps;
    // A pair that entered or left during the step takes or releases its
    // stored energy: work of the time-varying stiffness, booked at the step's end.
    // Mostly none did: the energy is then the same sum, computed once.
    const std::array<LoadedRange, 2> entered{system.loaded(Region::n1, y[kT1]),
                                             system.loaded(Region::n2, y[kT1])};
    const auto same_pairs = [](LoadedRange a, LoadedRange b) {
      return a.k_first == b.k_first && a.count == b.count;
    };
    const bool same = same_pairs(entered[0], ranges[0]) && same_pairs(entered[1], ranges[1]);
    const double before = mesh_energy(y);
    ranges = entered;
    const double mesh = same ? before : mesh_energy(y);
    jump_work += mesh - before;
    begin_contacts(t);
    s.max_penetration_m = std::max({s.max_penetration_m, system.penetration(Region::n1, y).first,
                                    system.penetration(Region::n2, y).first});
    const double energy =
        system.kinetic_energy(y) + mesh + system.bearing_energy(y) + system.shaft_energy(y);
    s.ledger_scale_j = std::max(s.ledger_scale_j, energy);
    if (system.terms_may_exceed(y, ranges, s.energy_max_j)) {
      const ElasticEnergy terms = system.mesh_terms(y, ranges);
      for (std::size_t i = 0; i < kTermCount; ++i) {
        s.energy_max_j[i] = std::max(s.energy_max_j[i], terms.j[i]);
      }
    }
    const double residual = energy - energy0 - y[kWork] + y[kHertzLoss] + y[kSlidingLoss] +
                            y[kBearingLoss] + y[kShaftLoss] - y[kParametric] - jump_work;
    s.ledger_residual_j = residual;
    s.ledger_residual_max_j = std::max(s.ledger_residual_max_j, std::fabs(residual));
    if (t != t_grid) continue;  // a cut step: the grid point is still ahead
    if (n % c.integrator.output_every == 0 || n == steps) record(t);
    if (control.should_stop && n % kStepsBetweenStopChecks == 0 && control.should_stop()) {
      throw SimulationStopped("the run was stopped by its caller at t = " + format_number(t) +
                              " s, step " + std::to_string(n));
    }
    ++n;
  }
  s.end_time_s = t;
  s.kinetic_energy_final_j = system.kinetic_energy(y);
  s.stored_energy_final_j = mesh_energy(y);
  s.torque_work_j = y[kWork];
  s.damping_loss_j = y[kHertzLoss];
  s.friction_loss_j = y[kSlidingLoss];
  s.parametric_jump_work_j = jump_work;
  s.parametric_work_j = y[kParametric] + jump_work;
  s.final_w1_rad_per_s = y[kVelocity + kT1];
  s.final_w2_rad_per_s = y[kVelocity + kT2];
  p.bearing_energy_final_j = system.bearing_energy(y);
  p.bearing_damping_loss_j = y[kBearingLoss];
  p.shaft_energy_final_j = system.shaft_energy(y);
  p.shaft_damping_loss_j = y[kShaftLoss];
  result.planar_final_state = to_state(y, mounting.shafts);
  result.final_state.time_s = t;
  result.final_state.state = {y[kT1], y[kT2], y[kVelocity + kT1], y[kVelocity + kT2]};
  result.final_state.contact = memory[0];
  return result;
}

}  // namespace gearimpact
