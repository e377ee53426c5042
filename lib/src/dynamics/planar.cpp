#include "gearimpact/dynamics/planar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adaptive_loop.hpp"
#include "event_location.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/drive.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/mesh_line.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/stiffness/energy.hpp"
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
  double friction_n = 0.0;           // Ff of (35)-(38) summed over both sides' pairs
  // Each side's stored energy in the mode, PlanarSystem::mesh_energy's sum
  // (so that the step's ledger takes it from the next step's first stage).
  std::array<double, 2> mesh_energy_j{};
};

// What stays constant during a step: the mesh's mode (mesh_line.hpp) on each
// line of action, the drive line's first, each free or in contact on its own
// line. The right-hand side is smooth while both hold; a change is an event,
// located and stepped onto.
using PlanarMode = std::array<Mode, 2>;

// The event values of both lines (MeshLine::line_event_values), the drive line's first.
using PlanarEvents = std::array<double, 2 * kMaxMeshEvents>;

// A system of the step methods (step_methods.hpp): the two gears' turning and
// their centres on the bearings, and the one mesh between them (MeshLine)
// seen through the centres' motion, each line of action with its own mode
// and contact memory.
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
      : c_(c), m_(m), mesh_(c, table) {
    const GearPair& g = c.gears;
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
    term_bound_ = mesh_.term_energy_bound();
    drag_ = c.torque2.kind == Torque::Kind::drag;
    driven_ = c.torque1.kind == Torque::Kind::prescribed_speed;
    // torque1 acts on the motor with shafts, so the driver turns it (and a
    // controller or a motor reads its motion).
    driven_index_ = m.shafts ? kTm : kT1;
    driver_theta0_ = driver_theta0;
    if (c.torque1.kind == Torque::Kind::speed_controlled) {
      controller_ = std::make_shared<const SpeedController>(c, driver_theta0);
    }
    induction_ = c.torque1.kind == Torque::Kind::induction_motor;
    options_ = driven_ || drag_ || controller_ || induction_;
  }

  // A kinematic driver's body (the pinion, the motor with shafts) where its
  // closed form puts it at t.
  void impose_driver(double t, Y& y) const {
    if (!driven_) return;
    const DriverMotion d = driver_motion(c_.torque1, driver_theta0_, t);
    y[driven_index_] = d.theta_rad;
    y[kVelocity + driven_index_] = d.speed_rad_per_s;
  }

  // Whether a kinematic driver sets a body's angle and speed after each step.
  bool driven() const { return driven_; }
  // Whether the mesh force is the Lagrangian one (model.mesh_force).
  bool lagrangian() const { return mesh_.lagrangian(); }
  // J1, whose kinetic energy pays a jump of the stored energy (Lagrangian).
  double pinion_inertia() const { return j1_; }
  // Whether the driver holds the pinion's speed (it then pays such a jump).
  bool drives_pinion() const { return driven_ && driven_index_ == kT1; }

  // The mesh's view of y: the gears' turning, and the pinion's centre less the wheel's.
  static PlanarMeshMotion motion(const Y& y) {
    const double* v = &y[kVelocity];
    return {{y[kT1], y[kT2], v[kT1], v[kT2]},
            y[kX1] - y[kX2],
            y[kY1] - y[kY2],
            v[kX1] - v[kX2],
            v[kY1] - v[kY2]};
  }
  // delta_d = s_d - B, delta_c = -s_c - B and their rates.
  double delta(Region side, const Y& y) const { return mesh_.delta(side, motion(y)); }
  double delta_rate(Region side, const Y& y) const {
    return line_sign(side) * mesh_.s_rate(side, motion(y));
  }
  // The largest penetration of a pair on `side` (MeshLine::contact_value).
  double contact_value(Region side, const Y& y) const {
    return mesh_.contact_value(side, motion(y));
  }

  // The mesh's stored energy of `side` at y in the side's mode m: each pair
  // that touches by its own penetration.
  double mesh_energy(const Y& y, const Mode& m) const {
    return mesh_.elastic_energy_j(motion(y), m);
  }

  // The mesh's stored energy of both sides by term of (29), as the
  // torsional ledger reports it (F = Ke delta of each pair inside the segment).
  ElasticEnergy mesh_terms(const Y& y, const PlanarMode& mode) const {
    ElasticEnergy u;
    const PlanarMeshMotion q = motion(y);
    for (const Mode& m : mode) mesh_.add_stored_energy(q, m, u);
    return u;
  }

  // Whether a term's energy at y in the mode (mesh_terms) could exceed its
  // entry of `most`: not when the mesh's bound (MeshLine::term_energy_bound)
  // stays below every entry, and the ledger then need not evaluate the terms
  // (most steps, once the largest penetration has passed).
  bool terms_may_exceed(const Y& y, const PlanarMode& mode,
                        const std::array<double, kTermCount>& most) const {
    if (!term_bound_) return true;
    double squares = 0.0;  // delta^2 summed over the loaded pairs
    for (const Region side : kSides) {
      const Mode& m = mode[side_index(side)];
      if (m.region == Region::free) continue;
      const double dl = delta(side, y);
      squares += m.count * dl * dl;
    }
    for (std::size_t i = 0; i < kTermCount; ++i) {
      if ((*term_bound_)[i] * squares > most[i]) return true;
    }
    return false;
  }

  // The side's contact, loaded pairs, their parts and with gaps which of
  // them touch and their gaps' zones at y (the forces' signs are
  // classify_forces's, once the contact memory is set).
  Mode classify_geometry(Region side, const Y& y) const {
    return mesh_.classify_line(side, motion(y));
  }

  // The friction sign and clipping of each pair of the side's mode m at y.
  void classify_forces(const Y& y, const ContactMemory& memory, Mode& m) const {
    mesh_.classify_forces(motion(y), memory, m);
  }

  // The values whose sign changes end the mode (each >= 0 while it holds):
  // those of each line in its own mode, the drive line's first. Returns how
  // many are set.
  int event_values(const Y& y, const PlanarMode& mode, const std::array<ContactMemory, 2>& memory,
                   PlanarEvents& g) const {
    const PlanarMeshMotion q = motion(y);
    int n = 0;
    for (const Region side : kSides) {
      const std::size_t i = side_index(side);
      n += mesh_.line_event_values(side, q, mode[i], memory[i], g.data() + n);
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

  // The equations of motion in the mode, with the contact memory of each side.
  void rhs(double t, const Y& y, const PlanarMode& mode, const std::array<ContactMemory, 2>& memory,
           Y& dy, Forces* forces = nullptr) const {
    if (options_) {
      equations<true>(t, y, mode, memory, dy, forces);
    } else {
      equations<false>(t, y, mode, memory, dy, forces);
    }
  }

 private:
  // The equations of motion; kOptions false compiles out the code of the
  // drives a case may not have (a driver, a controller, a motor, a drag), so
  // that a run without them pays nothing for them.
  template <bool kOptions>
  void equations(double t, const Y& y, const PlanarMode& mode,
                 const std::array<ContactMemory, 2>& memory, Y& dy, Forces* forces) const {
    const double* v = &y[kVelocity];
    const double w1 = v[kT1];
    const double w2 = v[kT2];
    // Forces on the centres (x, y) and moments about them (in theta's sense):
    // the bearings', then the mesh's.
    PlanarLoads loads;
    loads.force_a = {-m_.stiffness_x_n_per_m[0] * y[kX1] - m_.damping_x_n_s_per_m[0] * v[kX1],
                     -m_.stiffness_y_n_per_m[0] * y[kY1] - m_.damping_y_n_s_per_m[0] * v[kY1]};
    loads.force_b = {-m_.stiffness_x_n_per_m[1] * y[kX2] - m_.damping_x_n_s_per_m[1] * v[kX2],
                     -m_.stiffness_y_n_per_m[1] * y[kY2] - m_.damping_y_n_s_per_m[1] * v[kY2]};
    const double bearing_power =
        m_.damping_x_n_s_per_m[0] * v[kX1] * v[kX1] + m_.damping_y_n_s_per_m[0] * v[kY1] * v[kY1] +
        m_.damping_x_n_s_per_m[1] * v[kX2] * v[kX2] + m_.damping_y_n_s_per_m[1] * v[kY2] * v[kY2];
    const PlanarMeshMotion q = motion(y);
    MeshPowers powers;
    // Each line's pairs, in the line's own mode (whatever a stage state says:
    // the forces stay smooth within a step); the friction summed over both.
    ContactTotals totals;
    for (const Region side : kSides) {
      const std::size_t i = side_index(side);
      mesh_.add_line_forces(q, mode[i], memory[i], loads, powers,
                            forces != nullptr ? &totals : nullptr);
      if (forces != nullptr) {
        forces->normal_n[i] = totals.normal_force_n;
        forces->mesh_energy_j[i] = totals.elastic_energy_j;
        totals.normal_force_n = 0.0;
        totals.elastic_energy_j = 0.0;
      }
    }
    if (forces != nullptr) forces->friction_n = totals.friction_force_n;
    mesh_.add_damper(q, loads, powers);
    double moment1 = loads.moment_a;
    double moment2 = loads.moment_b;
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
    for (const std::size_t i : {kX1, kY1, kT1, kX2, kY2, kT2}) dy[i] = v[i];
    dy[kVelocity + kX1] = loads.force_a[0] * inverse_mass_[kX1];
    dy[kVelocity + kY1] = loads.force_a[1] * inverse_mass_[kY1];
    dy[kVelocity + kT1] = (t1 + moment1) * inverse_mass_[kT1];
    dy[kVelocity + kX2] = loads.force_b[0] * inverse_mass_[kX2];
    dy[kVelocity + kY2] = loads.force_b[1] * inverse_mass_[kY2];
    dy[kVelocity + kT2] = (t2 + moment2) * inverse_mass_[kT2];
    dy[kWork] = work;
    dy[kHertzLoss] = powers.damping_w;
    dy[kSlidingLoss] = powers.friction_w;
    dy[kParametric] = powers.parametric_w;
    dy[kBearingLoss] = bearing_power;
    dy[kShaftLoss] = shaft_power;
    dy[kMeshDamperLoss] = powers.mesh_damping_w;
    if (kOptions && driven_) dy[kVelocity + driven_index_] = driven_acceleration;
  }

  // torque_at without its call for a constant torque, the common case
  // (the call costs as much as a pair's forces).
  static double torque(const Torque& q, double t) {
    return q.kind == Torque::Kind::constant ? q.constant_n_m : torque_at(q, t);
  }

 public:
  // (32),(33) at the onset of a contact on a side at y, in the side's mode m.
  MeshLine::Onset onset(const Y& y, const Mode& m) const {
    return mesh_.damping_at_onset(motion(y), m);
  }

 private:
  const SimulationCase& c_;
  const PlanarMounting& m_;
  MeshLine mesh_;
  bool drag_ = false;    // torque2 a drag
  bool driven_ = false;  // torque1 a kinematic driver
  // torque1 a speed controller's (none otherwise) or an induction motor's,
  // from the motion of the body it acts on (driven_index_).
  std::shared_ptr<const SpeedController> controller_;
  bool induction_ = false;
  std::size_t driven_index_ = kT1;
  double driver_theta0_ = 0.0;
  bool options_ = false;  // any of the above
  double j1_ = 0.0, j2_ = 0.0;
  std::array<double, kVelocity> inverse_mass_{};  // 1/m or 1/J of each position
  // MeshLine::term_energy_bound, per term in J/m^2 (none with gaps or a constant stiffness).
  std::optional<std::array<double, kTermCount>> term_bound_;
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
  if (control.resume) {
    const RunState& r = *control.resume;
    if (!r.planar) {
      refuse("resume", "a run state without its planar state",
             "the final_state of a planar run (RunState::planar)");
    }
    const PlanarState& p = *r.planar;
    const double values[] = {p.x1_m,    p.y1_m,         p.theta1_rad,        p.x2_m,
                             p.y2_m,    p.theta2_rad,   p.theta_motor_rad,   p.theta_load_rad,
                             p.vx1_m_s, p.vy1_m_s,      p.w1_rad_per_s,      p.vx2_m_s,
                             p.vy2_m_s, p.w2_rad_per_s, p.w_motor_rad_per_s, p.w_load_rad_per_s};
    const ContactMemory memories[] = {r.contact, r.coast_contact};
    bool finite = std::isfinite(r.time_s);
    for (const double v : values) finite = finite && std::isfinite(v);
    for (const ContactMemory& d : memories) {
      finite = finite && std::isfinite(d.damping_per_stiffness_s_m) &&
               std::isfinite(d.frozen_stiffness_n_per_m) && d.damping_per_stiffness_s_m >= 0.0;
    }
    if (!finite) {
      refuse("resume", "a state with a non-finite or negative value",
             "the final_state of a planar run, finite");
    }
  }
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

  // A continued run (RunControl::resume) starts from its planar state at its
  // time, each line with its contact memory (a contact in progress is no new
  // impact); `initial` is then not used.
  PlanarRun(const SimulationCase& c, const StiffnessTable& table, const PlanarMounting& mounting,
            const PlanarState& initial, const RunControl& control)
      : c_(c),
        m_(mounting),
        control_(control),
        start_time_(control.resume ? control.resume->time_s : 0.0),
        system_(c, table, mounting, driver_start(c, mounting, initial, control)),
        y_(to_vector(control.resume ? *control.resume->planar : initial)),
        clock_(c.integrator.end_time_s, control, start_time_),
        stall_(c.integrator.step_s, c.model.friction_smoothing_speed_m_s),
        sensor_cos_(std::cos(c.bearings.sensor_angle_rad)),
        sensor_sin_(std::sin(c.bearings.sensor_angle_rad)),
        average_(control.sample == SampleKind::interval_average),
        tacho_on_(c.tacho.pulses_per_revolution > 0),
        tacho_index_(c.tacho.shaft == TachoShaft::wheel                      ? kT2
                     : c.tacho.shaft == TachoShaft::motor && mounting.shafts ? kTm
                                                                             : kT1),
        driver_theta0_(driver_start(c, mounting, initial, control)) {
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
    // A helical pair's section (face_advance_m = W > 0) reports its axial
    // force and tilting moments.
    if (c.gears.face_advance_m > 0.0) {
      thrust_.emplace(c.gears);
      s.helical_thrust = HelicalThrustMaxima{};
    }
    system_.impose_driver(start_time_, y_);
    if (control.keep_samples && clock_.on()) result_.planar_samples.reserve(clock_.reserve_rows());
    // The tacho's shaft and its edges, located on each step's continuous
    // extension (hence wants_dense with a tacho), or on a driver's closed form.
    tacho_driven_ =
        system_.driven() && tacho_index_ == (mounting.shafts ? std::size_t{kTm} : std::size_t{kT1});
    tacho_.emplace(tacho_on_ ? c.tacho : Tacho{1}, y_[tacho_index_]);
    drift_.emplace(c.torque1, c.drive.settle_s, start_time_, y_[kT1], y_[kVelocity + kT1]);
    if (control.resume) {
      memory_ = {control.resume->contact, control.resume->coast_contact};
      for (const Region side : kSides) {
        Mode& m = mode_[side_index(side)];
        m = system_.classify_geometry(side, y_);
        system_.classify_forces(y_, memory_[side_index(side)], m);
      }
    } else {
      classify(0.0);
    }
    emit_samples(start_time_, y_, mode_, [](double, Y&) {});
    PlanarEnergies& p = *s.planar;
    const double kinetic0 = system_.kinetic_energy(y_);
    const double mesh0 = mesh_energy(y_);
    s.kinetic_energy_initial_j = kinetic0;
    s.stored_energy_initial_j = mesh0;
    p.bearing_energy_initial_j = system_.bearing_energy(y_);
    p.shaft_energy_initial_j = system_.shaft_energy(y_);
    energy0_ = kinetic0 + mesh0 + p.bearing_energy_initial_j + p.shaft_energy_initial_j;
    record(start_time_);
    // k1, f(t, y) in the mode: each step's first stage, evaluated at the end
    // of the step before (after its events), where its mesh energy serves the ledger.
    system_.rhs(start_time_, y_, mode_, memory_, k1_, &at_start_);
    s.rhs_evaluations += 1;
    observe_thrust(at_start_);
  }

  // The fixed-step method whose last stage may serve as the next step's first.
  void use_stepper(const FixedStepper<PlanarSystem>* stepper) { stepper_ = stepper; }

  const PlanarSystem& system() const { return system_; }
  Y& y() { return y_; }
  const PlanarMode& mode() const { return mode_; }
  const std::array<ContactMemory, 2>& damping() const { return memory_; }
  long long& steps() { return result_.summary.steps; }
  long long& rhs_evaluations() { return result_.summary.rhs_evaluations; }
  double start_time() const { return start_time_; }
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
    clock_.emit_states(t_b, y_b, state_at, [&](double ts, const Y& y) { sample(ts, y, m); });
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
        Mode& m = mode_[side_index(side)];
        const std::array<double, kMaxPairs> slip = m.slip;
        system_.classify_forces(y_, memory_[side_index(side)], m);
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
    observe_thrust(at_start_);
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
    row.s_m = system_.delta(Region::n1, y) + c_.gears.backlash_m;
    const double dd = system_.contact_value(Region::n1, y);
    const double dc = system_.contact_value(Region::n2, y);
    row.delta_m = std::max(dd, dc);
    const bool drive = mode[0].region != Region::free;
    const bool coast = mode[1].region != Region::free;
    row.region = drive ? 1 : (coast ? -1 : 0);
    row.pairs = drive ? mode[0].count : (coast ? mode[1].count : 0);
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
    if (thrust_) {
      const HelicalThrust h = (*thrust_)(f.normal_n[0], f.normal_n[1]);
      pr.axial_force1_n = h.axial_force1_n;
      pr.axial_force2_n = h.axial_force2_n;
      pr.tilting_moment1_n_m = h.tilting_moment1_n_m;
      pr.tilting_moment2_n_m = h.tilting_moment2_n_m;
    }
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
    result_.final_state.planar = result_.planar_final_state;
    result_.final_state.coast_contact = memory_[1];
    result_.start_time_s = start_time_;
    return std::move(result_);
  }

 private:
  long long steps_taken() const { return result_.summary.steps; }

  // A helical pair's largest axial force and tilting moments, at a step's end.
  void observe_thrust(const Forces& f) {
    if (!thrust_) return;
    const HelicalThrust h = (*thrust_)(f.normal_n[0], f.normal_n[1]);
    HelicalThrustMaxima& most = *result_.summary.helical_thrust;
    most.axial_force_max_n = std::max(most.axial_force_max_n, std::fabs(h.axial_force1_n));
    most.tilting_moment1_max_n_m =
        std::max(most.tilting_moment1_max_n_m, std::fabs(h.tilting_moment1_n_m));
    most.tilting_moment2_max_n_m =
        std::max(most.tilting_moment2_max_n_m, std::fabs(h.tilting_moment2_n_m));
  }

  // The angle a kinematic driver's body (the motor with shafts, else the
  // pinion) starts from; a continued run carries it on from where it stopped,
  // whatever time it restarts at, as the torsional run does.
  static double driver_start(const SimulationCase& c, const PlanarMounting& m,
                             const PlanarState& initial, const RunControl& control) {
    if (!control.resume) return m.shafts ? initial.theta_motor_rad : initial.theta1_rad;
    const PlanarState& r = *control.resume->planar;
    const bool moved = c.torque1.kind == Torque::Kind::prescribed_speed ||
                       c.torque1.kind == Torque::Kind::speed_controlled;
    const double theta = m.shafts ? r.theta_motor_rad : r.theta1_rad;
    return moved ? theta - driver_motion(c.torque1, 0.0, control.resume->time_s).theta_rad : theta;
  }

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
    for (std::size_t i = 0; i < kSides.size(); ++i) {
      system_.classify_forces(y_, memory_[i], mode_[i]);
    }
  }

  double mesh_energy(const Y& state) const {
    return system_.mesh_energy(state, mode_[0]) + system_.mesh_energy(state, mode_[1]);
  }

  // The mode of y_ at t: each side's contact, pairs and parts; an impact
  // where a side's contact begins (its damping memory then set), its end
  // where it ends; then the forces' signs.
  void classify(double t) {
    for (const Region side : kSides) {
      const std::size_t i = side_index(side);
      const bool before = mode_[i].region != Region::free;
      mode_[i] = system_.classify_geometry(side, y_);
      const bool now = mode_[i].region != Region::free;
      if (now && !before) {
        const MeshLine::Onset onset = system_.onset(y_, mode_[i]);
        memory_[i] = onset.damping;
        impacts_.begin(side, t, onset.impact_speed_m_s, onset.restitution, result_.summary);
      } else if (!now && before) {
        impacts_.end(side, t, -system_.delta_rate(side, y_));
      }
      system_.classify_forces(y_, memory_[i], mode_[i]);
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
    ps.dte_m = system_.delta(Region::n1, state);
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
  double start_time_;
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
  std::optional<HelicalThrustLevers> thrust_;
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
