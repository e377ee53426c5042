// The gear pair as a dynamical system: two bodies, the pinion and the wheel,
// and the one mesh between them (MeshLine, mesh_line.hpp: the mode, the
// forces, the event values and classification, the stored energy); the state,
// the torques and drivers, and the right-hand side of the equations of motion
// (1)-(3), (43)-(45) in a mode. The integrators (rk4.cpp, adaptive.cpp) and the
// energy ledger (ledger.hpp) work on it.
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
#include "gearimpact/dynamics/mesh_line.hpp"
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

// The event values of a mode: those of its one mesh (MeshLine::event_values).
inline constexpr int kMaxEvents = kMaxMeshEvents;
using EventValues = std::array<double, kMaxEvents>;

// T(t) of one torque.
double torque_at(const Torque& torque, double t_s);
// The torque of a drag (Torque::Kind::drag) on a gear turning at w:
// -(drag_constant tanh(w / drag_speed_scale) + drag_viscous w).
double drag_torque_n_m(const Torque& drag, double w_rad_per_s);
// Its mean T_m over time: the constant, or the mean its fluctuation is added
// to. Throws InputError for a user function, whose mean is not known.
double mean_torque_n_m(const Torque& torque, const char* field);

class GearSystem {
 public:
  // The system concept of the step methods (src/dynamics/step_methods.hpp).
  using StateType = State;
  using ModeType = Mode;
  using MemoryType = ContactMemory;
  using EventsType = EventValues;
  using ForcesType = ContactTotals;
  // Where the ledger's integrals begin in the state (ledger.hpp).
  static constexpr std::size_t kLedgerStart = kTorqueWork;

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
  bool lagrangian() const { return mesh_.lagrangian(); }
  // [torque1] kind = "prescribed-speed": theta1 and w1 are the driver's
  // closed form, which impose_driver writes into y at time t (nothing
  // otherwise); the integrators call it on every state they accept.
  bool driven() const { return driven_; }
  void impose_driver(double t, State& y) const;

  double kinetic_energy(const State& y) const {
    return 0.5 * j1_ * y[kW1] * y[kW1] + 0.5 * j2_ * y[kW2] * y[kW2];
  }
  // The pair's one mesh, and the motion it sees in y: the pinion drives.
  const MeshLine& mesh() const { return mesh_; }
  static MeshMotion motion(const State& y) { return {y[kTheta1], y[kTheta2], y[kW1], y[kW2]}; }
  // s = Rb1 theta1 - Rb2 theta2 and its rate.
  double s(const State& y) const { return mesh_.s(motion(y)); }
  double s_rate(const State& y) const { return mesh_.s_rate(motion(y)); }
  // (31)
  double delta(Region r, const State& y) const { return mesh_.delta(r, motion(y)); }
  double pair_position(const Mode& m, const State& y, int j) const {
    return mesh_.pair_position(m, motion(y), j);
  }
  // Whether the case's modifications put a gap between the flanks of a pair.
  bool has_gaps() const { return mesh_.has_gaps(); }

  // The equations of motion in the mode m, and the powers of the ledger.
  void rhs(double t, const State& y, const Mode& m, const ContactMemory& d, State& dydt,
           ContactTotals* totals = nullptr) const;

  // The mode holds while every value is >= 0; an event is a value turning
  // negative. Returns how many values are set.
  int event_values(const State& y, const Mode& m, const ContactMemory& d, EventValues& g) const {
    return mesh_.event_values(motion(y), m, d, g.data());
  }
  bool mode_holds(const State& y, const Mode& m, const ContactMemory& d) const;

  // Region and loaded pairs of y, (31) and (42), with the same tests as event_values.
  Mode classify_geometry(const State& y) const { return mesh_.classify_geometry(motion(y)); }
  // Friction signs and clipping of the pairs of m at y.
  void classify_forces(const State& y, const ContactMemory& d, Mode& m) const {
    mesh_.classify_forces(motion(y), d, m);
  }

  // (32),(33) at the onset of a contact in mode m: Vi (floored), e(Vi) and D.
  using Onset = MeshLine::Onset;
  Onset damping_at_onset(const State& y, const Mode& m) const {
    return mesh_.damping_at_onset(motion(y), m);
  }

  // (5),(16),(17),(28) of the loaded pairs, F = Ke delta each.
  ElasticEnergy stored_energy(const State& y, const Mode& m) const {
    return mesh_.stored_energy(motion(y), m);
  }
  // The stored energy beside the mesh's: none (a train's shaft springs, ledger.hpp).
  static double shaft_energy_j(const State&) { return 0.0; }

 private:
  // T1(t), T2(t). An RK4 step asks for its middle time twice and for its end
  // time again as the next step's start: the last answer is kept, so a
  // sinusoid costs two sines a step instead of four (the same values).
  std::pair<double, double> torques(double t) const;

  const SimulationCase& case_;
  MeshLine mesh_;
  double j1_ = 0.0, j2_ = 0.0;
  bool driven_ = false;  // torque1 a kinematic driver
  // theta1(t) = driver_theta0_ + the driver's closed form from 0 to t.
  double driver_theta0_ = 0.0;
  bool drag_ = false;  // torque2 a drag, from w2
  // torque1 a speed controller's (none otherwise) or an induction motor's, from theta1 and w1.
  std::shared_ptr<const SpeedController> controller_;
  bool induction_ = false;
  // Both torques constant: torque_values_ holds them from the start.
  bool constant_torques_ = false;
  // A system belongs to one run, so one thread.
  mutable double torque_time_ = std::numeric_limits<double>::quiet_NaN();
  mutable std::pair<double, double> torque_values_{0.0, 0.0};
};

}  // namespace gearimpact
