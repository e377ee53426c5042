// The gear pair as a dynamical system: the state, the mode (which side of the
// backlash, which pairs are loaded, the friction sign and force clipping of
// each), the right-hand side of the equations of motion (1)-(3), (43)-(45) in a
// mode, and the event functions whose sign changes end a mode. The integrators
// (rk4.cpp, adaptive.cpp) and the energy ledger (ledger.hpp) work on it.
// docs/model.md, sections Contact, damping, friction and Equations of motion.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/drive.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// theta1, theta2, w1, w2, then the ledger integrals: torque work, damping
// loss, friction loss, parametric work (its continuous part), the loss in the
// viscous mesh damper.
inline constexpr std::size_t kStateSize = 9;
using State = std::array<double, kStateSize>;
enum StateIndex : std::size_t {
  kTheta1,
  kTheta2,
  kW1,
  kW2,
  kTorqueWork,
  kDampingLoss,
  kFrictionLoss,
  kParametricWork,
  kMeshDampingLoss
};

inline constexpr int kMaxPairs = MeshLayout::capacity;
// The event values of a mode: two in free flight; in contact the penetration,
// four bounds of the loaded pairs, and the friction sign and force clipping of
// each pair, and with gaps (modifications.hpp) whether each pair touches and
// the two kinks of its gap about it, and with a table cut at a fault's edges
// the two ends of the pair's part about it.
inline constexpr int kMaxEvents = 2 + 4 + 7 * kMaxPairs;
using EventValues = std::array<double, kMaxEvents>;

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
  // Each loaded pair's table (GearSystem::pair_table, nullptr: a missing
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
};

// T(t) of one torque.
double torque_at(const Torque& torque, double t_s);
// The torque of a drag (Torque::Kind::drag) on a gear turning at w:
// -(drag_constant tanh(w / drag_speed_scale) + drag_viscous w).
double drag_torque_n_m(const Torque& drag, double w_rad_per_s);
// Its mean T_m over time: the constant, or the mean its fluctuation is added
// to. Throws InputError for a user function, whose mean is not known.
double mean_torque_n_m(const Torque& torque, const char* field);

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

class GearSystem {
 public:
  // The system concept of the step methods (src/dynamics/step_methods.hpp).
  using StateType = State;
  using ModeType = Mode;
  using MemoryType = ContactMemory;
  using EventsType = EventValues;
  using ForcesType = ContactTotals;

  // The table must cover the contact segment of c.gears; both must outlive the system.
  // With c.faults, each pair reads the table of its two teeth (MeshTables,
  // built here with `table` as the healthy one), and a pair with a missing
  // tooth carries nothing.
  GearSystem(const SimulationCase& c, const StiffnessTable& table, const RunControl& control);

  // J1, for the impulse that pays a jump of the stored energy under the
  // Lagrangian mesh force.
  double pinion_inertia() const { return j1_; }
  // mesh_force = "lagrangian" with a stiffness that varies: the pinion feels
  // -1/2 dKe/dtheta1 delta^2 and pays the stored energy's jumps.
  bool lagrangian() const { return lagrangian_; }
  // [torque1] kind = "prescribed-speed": theta1 and w1 are the driver's
  // closed form, which impose_driver writes into y at time t (nothing
  // otherwise); the integrators call it on every state they accept.
  bool driven() const { return driven_; }
  void impose_driver(double t, State& y) const;

  double kinetic_energy(const State& y) const {
    return 0.5 * j1_ * y[kW1] * y[kW1] + 0.5 * j2_ * y[kW2] * y[kW2];
  }
  // s = Rb1 theta1 - Rb2 theta2 and its rate.
  double s(const State& y) const { return rb1_ * y[kTheta1] - rb2_ * y[kTheta2]; }
  double s_rate(const State& y) const { return rb1_ * y[kW1] - rb2_ * y[kW2]; }
  // (31)
  double delta(Region r, const State& y) const { return penetration(r, s(y), backlash_); }
  double pair_position(const Mode& m, const State& y, int j) const {
    return layout_.position_m(layout_.reference_m(m.region, y[kTheta1]), m.k_first + j);
  }
  // Whether the case's modifications put a gap between the flanks of a pair.
  bool has_gaps() const { return static_cast<bool>(gaps_); }

  // The equations of motion in the mode m, and the powers of the ledger.
  void rhs(double t, const State& y, const Mode& m, const ContactMemory& d, State& dydt,
           ContactTotals* totals = nullptr) const;

  // The mode holds while every value is >= 0; an event is a value turning
  // negative. Returns how many values are set.
  int event_values(const State& y, const Mode& m, const ContactMemory& d, EventValues& g) const;
  bool mode_holds(const State& y, const Mode& m, const ContactMemory& d) const;

  // Region and loaded pairs of y, (31) and (42), with the same tests as event_values.
  Mode classify_geometry(const State& y) const;
  // Friction signs and clipping of the pairs of m at y.
  void classify_forces(const State& y, const ContactMemory& d, Mode& m) const;

  // (32),(33) at the onset of a contact in mode m: Vi (floored), e(Vi) and D.
  struct Onset {
    double impact_speed_m_s;
    double restitution;
    ContactMemory damping;
  };
  Onset damping_at_onset(const State& y, const Mode& m) const;

  // (5),(16),(17),(28) of the loaded pairs, F = Ke delta each.
  ElasticEnergy stored_energy(const State& y, const Mode& m) const;

 private:
  // The helpers of the right-hand side and the event values, used only in
  // system.cpp.
  //
  // T1(t), T2(t). An RK4 step asks for its middle time twice and for its end
  // time again as the next step's start: the last answer is kept, so a
  // sinusoid costs two sines a step instead of four (the same values).
  std::pair<double, double> torques(double t) const;
  // The table of pair k on `line`: the healthy one, or with faults that of
  // the pair's teeth (nullptr: a missing tooth, the pair carries nothing).
  const StiffnessTable* pair_table(Region line, int k) const {
    return teeth_ ? teeth_->table(line, k) : &table_;
  }
  // Whether a pair on `table` in its part `part` can carry: not with a
  // missing tooth (no table), nor over the extent of a fault across the whole
  // face (a part without contact).
  static bool carries(const StiffnessTable* table, int part) {
    return table != nullptr && table->part_in_contact(part);
  }
  // Ke and dKe/dX of one of `count` loaded pairs at X, read from `table`
  // (from its part `part`, Mode::part).
  void pair_stiffness(const StiffnessTable& table, int part, double x, int count, double& ke,
                      double& dke) const;
  // Mode::table and Mode::part of each pair of m at y.
  void set_parts(const State& y, Mode& m) const;
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
  // The least gap of the pairs in the contact segment of `line` at theta1:
  // the line's contact begins where its penetration passes it.
  double least_gap_m(Region line, double theta1) const;

  const StiffnessTable& table_;
  // With faults: the table of each pair's teeth.
  std::shared_ptr<const MeshTables> teeth_;
  // With modifications: each pair's gap (docs/faults.md); none without, so
  // that an unmodified case runs the code it ran before, bit for bit.
  std::shared_ptr<const ToothGaps> gaps_;
  std::vector<double> kinks_;  // gaps_->kinks_m()
  const SimulationCase& case_;
  MeshLayout layout_;
  double rb1_ = 0.0, rb2_ = 0.0, j1_ = 0.0, j2_ = 0.0, backlash_ = 0.0, lp_ = 0.0;
  double x_pitch_ = 0.0, t0_ = 0.0, xs_ = 0.0, xe_ = 0.0;
  double kh_ = 0.0, constant_k_ = 0.0;
  double smoothing_speed_ = 0.0;  // v_s of tanh(Vs / v_s); 0: the exact sign
  double face_width_ = 0.0;
  double mesh_damping_ = 0.0;  // c of the viscous mesh damper, N s/m
  bool damping_on_current_pair_ = true;
  bool lagrangian_ = false;
  bool driven_ = false;  // torque1 a kinematic driver
  // theta1(t) = driver_theta0_ + the driver's closed form from 0 to t.
  double driver_theta0_ = 0.0;
  bool drag_ = false;  // torque2 a drag, from w2
  // torque1 a speed controller's (none otherwise) or an induction motor's, from theta1 and w1.
  std::shared_ptr<const SpeedController> controller_;
  bool induction_ = false;
  DampingUpdate damping_update_ = DampingUpdate::each_impact;  // resolved
  // Both torques constant: torque_values_ holds them from the start.
  bool constant_torques_ = false;
  // A system belongs to one run, so one thread.
  mutable double torque_time_ = std::numeric_limits<double>::quiet_NaN();
  mutable std::pair<double, double> torque_values_{0.0, 0.0};
};

}  // namespace gearimpact
