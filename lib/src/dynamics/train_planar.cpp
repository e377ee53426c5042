// A gear train whose bodies may translate on elastic bearings: the planar
// dynamics of docs/vibration.md ("The planar dynamics") for any train of
// meshes between fixed axes. Each degree of freedom of rotation (bodies
// joined by rigid shafts are one) may carry a centre (x, y in the train's
// fixed frame) on its bearings; each mesh sees its two centres' motion along
// each of its two lines of action, in the frame of its line of centres
// (TrainMesh::centre_angle_rad), through the MeshLine's planar interface
// (PlanarMeshMotion, add_line_forces, add_damper, line_event_values,
// classify_line), as the two-gear planar system does, and puts its forces on
// the centres. A body that turns clockwise (seen from +z) in the train's
// forward motion sees its meshes mirrored: the mesh's frame then has its y
// axis reversed. A planetary stage (meshes in a carrier's frame) runs in the
// carrier's axes, as Lin & Parker's model (docs/planetary.md, "The planar
// stage"): each mesh sees its bodies' angles relative to the carrier's and
// the centres' motion in the direction of its planet; each planet sits on
// its pin's bearing (TrainBody::pin), its mass orbiting with the carrier;
// the axes turn with the carrier, whose Euler, Coriolis and centrifugal terms
// act on every centre of the stage. The run's books (each line's mode and
// contact memory, the impacts, the ledger with the bearings' stored and
// damped energies) are the planar run's (planar.cpp), per mesh.
#include "train_planar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/dynamics/drive.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/mesh_line.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "run_parts.hpp"
#include "stall.hpp"
#include "step_methods.hpp"

namespace gearimpact {

namespace {

constexpr std::array<Region, 2> kLines{Region::n1, Region::n2};

// The state's layout for at most Dofs degrees of freedom and Meshes meshes:
// the angles, the centres' x and y, the speeds, the centres' vx and vy (a
// degree of freedom without bearings keeps 0 there), then the ledger's
// integrals (torque work, Hertzian damping, friction, parametric work, the
// bearings' dampers, the mesh dampers) and each mesh's own three losses.
template <int Dofs, int Meshes>
struct PlanarTrainLayout {
  static constexpr std::size_t kDofs = Dofs;
  static constexpr std::size_t kMeshes = Meshes;
  static constexpr std::size_t theta(std::size_t d) { return d; }
  static constexpr std::size_t x(std::size_t d) { return kDofs + d; }
  static constexpr std::size_t y(std::size_t d) { return 2 * kDofs + d; }
  static constexpr std::size_t w(std::size_t d) { return 3 * kDofs + d; }
  static constexpr std::size_t vx(std::size_t d) { return 4 * kDofs + d; }
  static constexpr std::size_t vy(std::size_t d) { return 5 * kDofs + d; }
  static constexpr std::size_t kWork = 6 * kDofs;
  static constexpr std::size_t kHertzLoss = kWork + 1;
  static constexpr std::size_t kSlidingLoss = kWork + 2;
  static constexpr std::size_t kParametric = kWork + 3;
  static constexpr std::size_t kBearingLoss = kWork + 4;
  static constexpr std::size_t kMeshDamperLoss = kWork + 5;
  // Each mesh's Hertzian damping, friction and mesh damper losses.
  static constexpr std::size_t mesh_loss(std::size_t k, std::size_t i) {
    return kWork + 6 + 3 * k + i;
  }
  static constexpr std::size_t kSize = kWork + 6 + 3 * kMeshes;
};
// A pair of gears (a two-gear case written as a train) and a two-stage rig
// (4 bodies, 3 degrees of freedom, 2 meshes) fit layouts of their own, so
// that neither pays for a larger train's state.
using PairPlanarTrain = PlanarTrainLayout<2, 1>;
using SmallPlanarTrain = PlanarTrainLayout<4, 3>;
using LargePlanarTrain = PlanarTrainLayout<kMaxTrainBodies, kMaxTrainMeshes>;
// A train whose helical meshes run by slices: each slice a mesh of its own.
using SlicedPlanarTrain = PlanarTrainLayout<kMaxTrainBodies, kMaxTrainLines>;

// Each degree of freedom's sense of turning about +z in the train's forward
// motion: +1 for the first of each connected set, -1 across an external mesh
// between fixed axes, the same across a torsional shaft; 0 where a loop of
// meshes contradicts itself (and `conflict` set to the mesh that does).
std::vector<int> turning_senses(const GearTrain& train, const std::vector<int>& dof, int dofs,
                                int& conflict) {
  std::vector<int> sense(static_cast<std::size_t>(dofs), 0);
  conflict = -1;
  for (int start = 0; start < dofs; ++start) {
    if (sense[static_cast<std::size_t>(start)] != 0) continue;
    sense[static_cast<std::size_t>(start)] = 1;
    for (bool grew = true; grew;) {
      grew = false;
      const auto join = [&](int a, int b, int factor, int link) {
        const int sa = sense[static_cast<std::size_t>(a)];
        int& sb = sense[static_cast<std::size_t>(b)];
        if (sa == 0) return;
        if (sb == 0) {
          sb = sa * factor;
          grew = true;
        } else if (sb != sa * factor && conflict < 0) {
          conflict = link;
        }
      };
      for (std::size_t k = 0; k < train.meshes.size(); ++k) {
        const TrainMesh& m = train.meshes[k];
        if (m.carrier >= 0) continue;  // in its carrier's frame, its own senses
        const int a = dof[static_cast<std::size_t>(m.body_a)];
        const int b = dof[static_cast<std::size_t>(m.body_b)];
        join(a, b, -1, static_cast<int>(k));
        join(b, a, -1, static_cast<int>(k));
      }
      for (const TrainShaft& s : train.shafts) {
        if (s.kind != TrainShaft::Kind::torsional) continue;
        const int a = dof[static_cast<std::size_t>(s.body_a)];
        const int b = dof[static_cast<std::size_t>(s.body_b)];
        join(a, b, 1, -1);
        join(b, a, 1, -1);
      }
    }
  }
  return sense;
}

// The bearings of each degree of freedom (the one body of its rigid shaft
// that has them), -1 where its centre is fixed.
std::vector<int> bearing_bodies(const GearTrain& train, const std::vector<int>& dof, int dofs) {
  std::vector<int> body(static_cast<std::size_t>(dofs), -1);
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    if (!train.bodies[i].bearing) continue;
    body[static_cast<std::size_t>(dof[i])] = static_cast<int>(i);
  }
  return body;
}

// What each line of each mesh reports beside the derivatives.
template <class L>
struct PlanarTrainForces {
  std::array<double, 2 * L::kMeshes> normal_n{};  // each line's, summed over its pairs
  std::array<double, L::kMeshes> friction_n{};    // each mesh's, summed over both lines
  std::array<double, 2 * L::kMeshes> mesh_energy_j{};
};

// The planar train as a system of the run loop (step_methods.hpp).
template <class L>
class PlanarTrainSystem {
 public:
  using StateType = std::array<double, L::kSize>;
  // Each mesh's two lines (drive, coast), each with its own mode.
  struct ModeType {
    std::array<Mode, 2 * L::kMeshes> line{};
  };
  using MemoryType = std::array<ContactMemory, 2 * L::kMeshes>;
  using EventsType = std::array<double, 2 * L::kMeshes * kMaxMeshEvents>;
  using ForcesType = PlanarTrainForces<L>;

  PlanarTrainSystem(const GearTrain& train, const std::vector<const StiffnessTable*>& tables)
      : train_(train), body_dof_(train_degrees_of_freedom(train)) {
    const int dofs = count_dofs(body_dof_);
    dofs_ = static_cast<std::size_t>(dofs);
    const std::vector<double> inertia = dof_inertias(train, body_dof_, dofs);
    const std::vector<int> bearing = bearing_bodies(train, body_dof_, dofs);
    int conflict = -1;
    const std::vector<int> sense = turning_senses(train, body_dof_, dofs, conflict);
    for (int d = 0; d < dofs; ++d) {
      const auto u = static_cast<std::size_t>(d);
      inertia_[u] = inertia[u];
      inverse_inertia_[u] = 1.0 / inertia[u];
      if (bearing[u] < 0) continue;
      const GearBearing& b = *train.bodies[static_cast<std::size_t>(bearing[u])].bearing;
      translating_[u] = true;
      mass_[u] = *b.mass_kg;
      inverse_mass_[u] = 1.0 / mass_[u];
      kx_[u] = b.stiffness_x_n_per_m;
      ky_[u] = stiffness_y(b);
      cx_[u] = b.damping_x_n_s_per_m;
      cy_[u] = damping_y(b);
    }
    // Each degree of freedom's bodies in the train's order, so that their
    // torques add in that order.
    first_body_.fill(-1);
    next_body_.fill(-1);
    for (std::size_t i = train.bodies.size(); i-- > 0;) {
      const auto d = static_cast<std::size_t>(body_dof_[i]);
      next_body_[i] = first_body_[d];
      first_body_[d] = static_cast<int>(i);
    }
    for (std::size_t i = 0; i < train.bodies.size(); ++i) {
      if (train.bodies[i].torque.kind != Torque::Kind::speed_controlled) continue;
      controller_[i] = train_speed_controller(train, static_cast<int>(i));
    }
    pin_carrier_.fill(-1);
    turning_with_.fill(-1);
    for (std::size_t i = 0; i < train.bodies.size(); ++i) {
      if (!train.bodies[i].pin) continue;
      const TrainBody::Pin& pin = *train.bodies[i].pin;
      const auto u = static_cast<std::size_t>(body_dof_[i]);
      pin_carrier_[u] = dof_of(pin.carrier);
      turning_with_[u] = pin_carrier_[u];
      pin_radius_[u] = pin.radius_m;
      pin_cos_[u] = std::cos(pin.angle_rad);
      pin_sin_[u] = std::sin(pin.angle_rad);
    }
    driver_.fill(-1);
    for (std::size_t i = 0; i < train.bodies.size(); ++i) {
      if (train.bodies[i].torque.kind == Torque::Kind::prescribed_speed || train.bodies[i].held) {
        driver_[static_cast<std::size_t>(body_dof_[i])] = static_cast<int>(i);
        driven_ = true;
      }
    }
    for (std::size_t k = 0; k < train.meshes.size(); ++k) {
      const TrainMesh& m = train.meshes[k];
      if (m.carrier >= 0) {
        add_carrier_mesh(m, *tables[k]);
        for (const int body : {m.body_a, m.body_b, m.carrier}) {
          turning_with_[static_cast<std::size_t>(dof_of(body))] = dof_of(m.carrier);
        }
        continue;
      }
      Frame f;
      f.a = body_dof_[static_cast<std::size_t>(m.body_a)];
      f.b = body_dof_[static_cast<std::size_t>(m.body_b)];
      f.cos = std::cos(m.centre_angle_rad);
      f.sin = std::sin(m.centre_angle_rad);
      f.sense = sense[static_cast<std::size_t>(f.a)];
      // The two-gear planar model's frame itself: its arithmetic, bit for bit.
      f.aligned = m.centre_angle_rad == 0.0 && f.sense == 1;
      if (m.line_offset_m != 0.0) {
        f.offset_a = m.line_offset_m / base_radius(m.pair.gears, Gear::one);
        f.offset_b = m.line_offset_m / base_radius(m.pair.gears, Gear::two);
      }
      frames_[meshes_.size()] = f;
      // The viscous damper's m_e: the two bodies' as they turn in the train.
      const double mass = effective_mass_kg(
          base_radius(m.pair.gears, Gear::one), inertia_[static_cast<std::size_t>(f.a)],
          base_radius(m.pair.gears, Gear::two), inertia_[static_cast<std::size_t>(f.b)]);
      meshes_.emplace_back(m.pair, *tables[k], mass, m.teeth);
    }
    for (const TrainShaft& s : train.shafts) {
      if (s.kind != TrainShaft::Kind::torsional) continue;
      springs_.push_back({dof_of(s.body_a), dof_of(s.body_b), s.stiffness_n_m_per_rad});
    }
    mesh_count_ = meshes_.size();
    for (std::size_t k = 0; k < mesh_count_; ++k) term_bound_[k] = meshes_[k].term_energy_bound();
    turning_ =
        std::any_of(turning_with_.begin(), turning_with_.end(), [](int c) { return c >= 0; });
    // Each degree of freedom's constant torques summed in the train's order,
    // as rhs would add them.
    plain_ = !driven_ && !turning_;
    for (std::size_t d = 0; d < dofs_; ++d) {
      for (int i = first_body_[d]; i >= 0; i = next_body_[static_cast<std::size_t>(i)]) {
        const Torque& torque = train.bodies[static_cast<std::size_t>(i)].torque;
        plain_ = plain_ && torque.kind == Torque::Kind::constant;
        constant_torque_[d] =
            i == first_body_[d] ? torque.constant_n_m : constant_torque_[d] + torque.constant_n_m;
      }
    }
  }

  int dof_of(int body) const { return body_dof_[static_cast<std::size_t>(body)]; }
  // The body whose kinematic driver (or hold) sets degree of freedom d (-1: none).
  int driver_of(std::size_t d) const { return driver_[d]; }
  bool translating(int dof) const { return translating_[static_cast<std::size_t>(dof)]; }
  std::size_t mesh_count() const { return mesh_count_; }
  const MeshLine& mesh(std::size_t k) const { return meshes_[k]; }
  bool driven() const { return driven_; }

  // The mesh's view of y: its bodies' turning (shifted by its line offset)
  // and its centre a less centre b in the frame of its line of centres.
  PlanarMeshMotion motion(std::size_t k, const StateType& y) const {
    const Frame& f = frames_[k];
    const auto a = static_cast<std::size_t>(f.a);
    const auto b = static_cast<std::size_t>(f.b);
    PlanarMeshMotion q;
    if (f.carrier >= 0) {
      const auto c = static_cast<std::size_t>(f.carrier);
      q.theta_a_rad = f.sense_a * (y[L::theta(a)] - y[L::theta(c)]) + f.offset_a;
      q.theta_b_rad = f.sense_b * (y[L::theta(b)] - y[L::theta(c)]) + f.offset_b;
      q.w_a_rad_per_s = f.sense_a * (y[L::w(a)] - y[L::w(c)]);
      q.w_b_rad_per_s = f.sense_b * (y[L::w(b)] - y[L::w(c)]);
    } else {
      q.theta_a_rad = y[L::theta(a)] + f.offset_a;
      q.theta_b_rad = y[L::theta(b)] + f.offset_b;
      q.w_a_rad_per_s = y[L::w(a)];
      q.w_b_rad_per_s = y[L::w(b)];
    }
    const double ux = y[L::x(a)] - y[L::x(b)];
    const double uy = y[L::y(a)] - y[L::y(b)];
    const double vx = y[L::vx(a)] - y[L::vx(b)];
    const double vy = y[L::vy(a)] - y[L::vy(b)];
    if (f.aligned) {
      q.dx_m = ux;
      q.dy_m = uy;
      q.dvx_m_s = vx;
      q.dvy_m_s = vy;
    } else {
      q.dx_m = f.cos * ux + f.sin * uy;
      q.dy_m = f.sense * (f.cos * uy - f.sin * ux);
      q.dvx_m_s = f.cos * vx + f.sin * vy;
      q.dvy_m_s = f.sense * (f.cos * vy - f.sin * vx);
    }
    return q;
  }

  // Whether the meshes' stored energy at y in the mode may exceed an entry
  // of `most` in some term: not when the sum over the meshes of each one's
  // bound (MeshLine::term_energy_bound) times its loaded pairs' delta^2 is
  // below every entry, which spares the terms' sums on most steps.
  bool terms_may_exceed(const StateType& y, const ModeType& mode,
                        const std::array<double, kTermCount>& most) const {
    std::array<double, kTermCount> bound{};
    for (std::size_t k = 0; k < L::kMeshes && k < mesh_count_; ++k) {
      if (!term_bound_[k]) return true;
      const PlanarMeshMotion q = motion(k, y);
      double squares = 0.0;  // delta^2 summed over the loaded pairs of both lines
      for (std::size_t i = 0; i < 2; ++i) {
        const Mode& m = mode.line[2 * k + i];
        if (m.region == Region::free) continue;
        const double dl = meshes_[k].delta(kLines[i], q);
        squares += m.count * dl * dl;
      }
      for (std::size_t i = 0; i < kTermCount; ++i) bound[i] += (*term_bound_[k])[i] * squares;
    }
    for (std::size_t i = 0; i < kTermCount; ++i) {
      if (bound[i] > most[i]) return true;
    }
    return false;
  }

  // A prescribed-speed body's closed form written into y at time t.
  void impose_driver(double t, StateType& y) const {
    if (!driven_) return;
    for (std::size_t d = 0; d < L::kDofs && d < dofs_; ++d) {
      const int body = driver_[d];
      if (body < 0) continue;
      const DriverMotion m = driven_body_motion(train_.bodies[static_cast<std::size_t>(body)], t);
      y[L::theta(d)] = m.theta_rad;
      y[L::w(d)] = m.speed_rad_per_s;
    }
  }

  // The equations of motion in the mode: the bearings' forces on the
  // centres, then each mesh's two lines and its damper (in the order the
  // two-gear planar system adds them), the torsional shafts, the torques.
  void rhs(double t, const StateType& y, const ModeType& mode, const MemoryType& memory,
           StateType& dy, ForcesType* forces = nullptr) const {
    if (plain_) {
      equations<true>(t, y, mode, memory, dy, forces);
    } else {
      equations<false>(t, y, mode, memory, dy, forces);
    }
  }

 private:
  // rhs; kPlain where the train has no driver, no carrier and only constant
  // torques (plain_), whose branches it then leaves out of every call.
  template <bool kPlain>
  [[gnu::flatten]] void equations(double t, const StateType& y, const ModeType& mode,
                                  const MemoryType& memory, StateType& dy,
                                  ForcesType* forces) const {
    dy = StateType{};
    // The centres' forces start at -0, the sum's neutral element (-0 + x is x, -0 too), so
    // that a bearing's force added to them keeps its sign of zero, as the two-gear planar
    // run's, which sets it.
    std::array<double, L::kDofs> fx;
    std::array<double, L::kDofs> fy;
    fx.fill(-0.0);
    fy.fill(-0.0);
    std::array<double, L::kDofs> moment{};
    double bearing_power = 0.0;
    for (std::size_t d = 0; d < L::kDofs && d < dofs_; ++d) {
      if (!translating_[d]) continue;
      if (!kPlain && pin_carrier_[d] >= 0) {
        // The bearing between the planet and its pin: its force on the
        // planet, the opposite on the carrier's centre.
        const PinDeflection p = pin_deflection(d, y);
        const std::array<double, 2> force = pin_force(d, y);
        const auto c = static_cast<std::size_t>(pin_carrier_[d]);
        fx[d] += force[0];
        fy[d] += force[1];
        fx[c] -= force[0];
        fy[c] -= force[1];
        bearing_power += cx_[d] * p.radial_rate * p.radial_rate;
        bearing_power += cy_[d] * p.tangential_rate * p.tangential_rate;
        continue;
      }
      const double vx = y[L::vx(d)];
      const double vy = y[L::vy(d)];
      fx[d] += -kx_[d] * y[L::x(d)] - cx_[d] * vx;
      fy[d] += -ky_[d] * y[L::y(d)] - cy_[d] * vy;
      bearing_power += cx_[d] * vx * vx;
      bearing_power += cy_[d] * vy * vy;
    }
    MeshPowers powers;
    for (std::size_t k = 0; k < L::kMeshes && k < mesh_count_; ++k) {
      const MeshPowers before = powers;
      const Frame& f = frames_[k];
      const auto a = static_cast<std::size_t>(f.a);
      const auto b = static_cast<std::size_t>(f.b);
      const PlanarMeshMotion q = motion(k, y);
      PlanarLoads loads;
      if (f.carrier < 0) {
        loads.moment_a = moment[a];
        loads.moment_b = moment[b];
      }
      if (f.aligned) {
        loads.force_a = {fx[a], fy[a]};
        loads.force_b = {fx[b], fy[b]};
      }
      ContactTotals totals;
      for (std::size_t i = 0; i < 2; ++i) {
        meshes_[k].add_line_forces(q, mode.line[2 * k + i], memory[2 * k + i], loads, powers,
                                   forces != nullptr ? &totals : nullptr);
        if (forces != nullptr) {
          forces->normal_n[2 * k + i] = totals.normal_force_n;
          forces->mesh_energy_j[2 * k + i] = totals.elastic_energy_j;
          totals.normal_force_n = 0.0;
          totals.elastic_energy_j = 0.0;
        }
      }
      if (forces != nullptr) forces->friction_n[k] = totals.friction_force_n;
      meshes_[k].add_damper(q, loads, powers);
      if (f.carrier >= 0) {
        // The line's moments in its gears' senses, about +z on the bodies;
        // the carrier, whose frame the angles are taken in, minus their sum.
        moment[a] += f.sense_a * loads.moment_a;
        moment[b] += f.sense_b * loads.moment_b;
        moment[static_cast<std::size_t>(f.carrier)] -=
            f.sense_a * loads.moment_a + f.sense_b * loads.moment_b;
      } else {
        moment[a] = loads.moment_a;
        moment[b] = loads.moment_b;
      }
      if (f.aligned) {
        fx[a] = loads.force_a[0];
        fy[a] = loads.force_a[1];
        fx[b] = loads.force_b[0];
        fy[b] = loads.force_b[1];
      } else {
        // The mesh frame's (x, y) in the fixed frame: e_x = (cos, sin),
        // e_y = sense (-sin, cos).
        const auto add = [&](std::size_t d, const std::array<double, 2>& force) {
          fx[d] += f.cos * force[0] - f.sense * f.sin * force[1];
          fy[d] += f.sin * force[0] + f.sense * f.cos * force[1];
        };
        add(a, loads.force_a);
        add(b, loads.force_b);
      }
      dy[L::mesh_loss(k, 0)] = powers.damping_w - before.damping_w;
      dy[L::mesh_loss(k, 1)] = powers.friction_w - before.friction_w;
      dy[L::mesh_loss(k, 2)] = powers.mesh_damping_w - before.mesh_damping_w;
    }
    for (const Spring& s : springs_) {
      // The shaft twisted by theta_a - theta_b pulls b forward and a back.
      const auto a = static_cast<std::size_t>(s.a);
      const auto b = static_cast<std::size_t>(s.b);
      const double torque_on_b = s.stiffness * (y[L::theta(a)] - y[L::theta(b)]);
      moment[a] -= torque_on_b;
      moment[b] += torque_on_b;
    }
    double work = 0.0;
    for (std::size_t d = 0; d < L::kDofs && d < dofs_; ++d) {
      double torque = kPlain ? constant_torque_[d] : 0.0;
      for (int i = first_body_[d]; !kPlain && i >= 0; i = next_body_[static_cast<std::size_t>(i)]) {
        const double value =
            body_torque(static_cast<std::size_t>(i), t, y[L::theta(d)], y[L::w(d)]);
        torque = i == first_body_[d] ? value : torque + value;
      }
      // The centres in this carrier's turning axes, each at r (its speed
      // u' + Omega e_z x r): the kinetic energy's cross terms give the carrier
      // J_c theta_c'' = M_c - sum (r x F)_z, F the force on each centre and
      // J_c the carrier's own (docs/planetary.md, The turning axes).
      for (std::size_t e = 0; !kPlain && turning_ && e < L::kDofs && e < dofs_; ++e) {
        if (turning_with_[e] != static_cast<int>(d) || !translating_[e]) continue;
        const std::array<double, 2> r = turning_position(e, y);
        moment[d] -= r[0] * fy[e] - r[1] * fx[e];
      }
      double acceleration = 0.0;
      const bool driven = !kPlain && driver_[d] >= 0;
      if (driven) {
        // The driver applies the torque that gives its body the prescribed
        // acceleration against the rest; its work is the torque work. A held
        // body's is what holds it still.
        acceleration = driven_body_motion(train_.bodies[static_cast<std::size_t>(driver_[d])], t)
                           .acceleration_rad_per_s2;
        torque = inertia_[d] * acceleration - moment[d];
      }
      const double w = y[L::w(d)];
      work = d == 0 ? torque * w : work + torque * w;
      dy[L::theta(d)] = w;
      dy[L::w(d)] = driven ? acceleration : (torque + moment[d]) * inverse_inertia_[d];
      if (!translating_[d]) continue;
      dy[L::x(d)] = y[L::vx(d)];
      dy[L::y(d)] = y[L::vy(d)];
      dy[L::vx(d)] = fx[d] * inverse_mass_[d];
      dy[L::vy(d)] = fy[d] * inverse_mass_[d];
    }
    for (std::size_t e = 0; !kPlain && turning_ && e < L::kDofs && e < dofs_; ++e) {
      if (turning_with_[e] < 0 || !translating_[e]) continue;
      // The rest of m r'' in the axes turning at Omega: u'' = F/m - Omega'
      // e_z x r - 2 Omega e_z x u' + Omega^2 r, e_z x (a, b) = (-b, a); on a
      // pin the Euler term's R Omega' e_eta carries the planet round.
      const auto c = static_cast<std::size_t>(turning_with_[e]);
      const double omega = y[L::w(c)];
      const double omega_rate = dy[L::w(c)];
      const std::array<double, 2> r = turning_position(e, y);
      dy[L::vx(e)] += omega_rate * r[1] + 2.0 * omega * y[L::vy(e)] + omega * omega * r[0];
      dy[L::vy(e)] += -omega_rate * r[0] - 2.0 * omega * y[L::vx(e)] + omega * omega * r[1];
    }
    dy[L::kWork] = work;
    dy[L::kHertzLoss] = powers.damping_w;
    dy[L::kSlidingLoss] = powers.friction_w;
    dy[L::kParametric] = powers.parametric_w;
    dy[L::kBearingLoss] = bearing_power;
    dy[L::kMeshDamperLoss] = powers.mesh_damping_w;
  }

 public:
  int event_values(const StateType& y, const ModeType& mode, const MemoryType& memory,
                   EventsType& g) const {
    int n = 0;
    for (std::size_t k = 0; k < L::kMeshes && k < mesh_count_; ++k) {
      const PlanarMeshMotion q = motion(k, y);
      for (std::size_t i = 0; i < 2; ++i) {
        n += meshes_[k].line_event_values(kLines[i], q, mode.line[2 * k + i], memory[2 * k + i],
                                          g.data() + n);
      }
    }
    return n;
  }
  bool mode_holds(const StateType& y, const ModeType& mode, const MemoryType& memory) const {
    EventsType g;
    const int n = event_values(y, mode, memory, g);
    for (int i = 0; i < n; ++i) {
      if (g[static_cast<std::size_t>(i)] < 0.0) return false;
    }
    return true;
  }

  // The force the bearings of degree of freedom d exert on its centre, -k u - c u'.
  std::array<double, 2> bearing_force(std::size_t d, const StateType& y) const {
    if (!translating_[d]) return {0.0, 0.0};
    if (pin_carrier_[d] >= 0) return pin_force(d, y);
    return {-kx_[d] * y[L::x(d)] - cx_[d] * y[L::vx(d)],
            -ky_[d] * y[L::y(d)] - cy_[d] * y[L::vy(d)]};
  }
  double bearing_energy(const StateType& y) const {
    double e = 0.0;
    for (std::size_t d = 0; d < L::kDofs && d < dofs_; ++d) {
      if (!translating_[d]) continue;
      if (pin_carrier_[d] >= 0) {
        const PinDeflection p = pin_deflection(d, y);
        e += kx_[d] * p.radial * p.radial;
        e += ky_[d] * p.tangential * p.tangential;
        continue;
      }
      e += kx_[d] * y[L::x(d)] * y[L::x(d)];
      e += ky_[d] * y[L::y(d)] * y[L::y(d)];
    }
    return 0.5 * e;
  }
  double shaft_energy(const StateType& y) const {
    double e = 0.0;
    for (const Spring& s : springs_) {
      const double twist =
          y[L::theta(static_cast<std::size_t>(s.a))] - y[L::theta(static_cast<std::size_t>(s.b))];
      e += 0.5 * s.stiffness * twist * twist;
    }
    return e;
  }
  double kinetic_energy(const StateType& y) const {
    double e = 0.0;
    for (std::size_t d = 0; d < L::kDofs && d < dofs_; ++d) {
      if (translating_[d]) {
        double vx = y[L::vx(d)];
        double vy = y[L::vy(d)];
        if (turning_with_[d] >= 0) {
          // Carried round by the turning axes, Omega e_z x r (on a pin, the
          // planet's orbit R Omega e_eta with it).
          const double omega = y[L::w(static_cast<std::size_t>(turning_with_[d]))];
          const std::array<double, 2> r = turning_position(d, y);
          vx -= omega * r[1];
          vy += omega * r[0];
        }
        e += mass_[d] * (vx * vx + vy * vy);
      }
      e += inertia_[d] * y[L::w(d)] * y[L::w(d)];
    }
    return 0.5 * e;
  }

 private:
  struct Frame {
    int a = 0;
    int b = 1;
    double cos = 1.0;
    double sin = 0.0;
    int sense = 1;
    bool aligned = true;
    double offset_a = 0.0;
    double offset_b = 0.0;
    // In a carrier's frame: the carrier's degree of freedom (-1: fixed
    // axes) and the senses of the line's gears 1 and 2 about +z.
    int carrier = -1;
    double sense_a = 1.0;
    double sense_b = 1.0;
  };
  struct Spring {
    int a;
    int b;
    double stiffness;
  };
  // A mesh in a carrier's frame, as the rotational stage's (train.cpp): the
  // line's gear 1 (the sun, or an internal mesh's planet) and gear 2 (the
  // planet, or the ring) turn relative to the carrier in their senses about
  // +z, so that s = Rb_a (theta_a - theta_c) + kappa Rb_b (theta_b - theta_c);
  // its frame's x runs along the planet's direction e_zeta on the carrier
  // and its y along e_eta = e_z x e_zeta for an external mesh, -e_eta for an
  // internal one, so that the line's normals are Lin & Parker's (modes/
  // planetary.hpp): the sun mesh's drive normal sin(a) e_zeta + cos(a)
  // e_eta, the ring mesh's -sin(a) e_zeta + cos(a) e_eta from the ring.
  void add_carrier_mesh(const TrainMesh& m, const StiffnessTable& table) {
    const bool internal = m.kind == TrainMesh::Kind::internal;
    const int planet = m.body_b;
    const TrainBody::Pin& pin = *train_.bodies[static_cast<std::size_t>(planet)].pin;
    Frame f;
    f.a = dof_of(internal ? m.body_b : m.body_a);
    f.b = dof_of(internal ? m.body_a : m.body_b);
    f.carrier = dof_of(m.carrier);
    f.sense_a = internal ? -1.0 : 1.0;
    f.sense_b = -1.0;
    f.cos = std::cos(pin.angle_rad);
    f.sin = std::sin(pin.angle_rad);
    f.sense = internal ? -1 : 1;
    f.aligned = false;
    const RingLine ring = internal ? ring_line(m, table) : RingLine{};
    const double rb1 =
        internal ? ring.line.planet_base_radius_m : base_radius(m.pair.gears, Gear::one);
    const double rb2 =
        internal ? ring.line.ring_base_radius_m : base_radius(m.pair.gears, Gear::two);
    f.offset_a = m.line_offset_m / rb1;
    f.offset_b = m.line_offset_m / rb2;
    frames_[meshes_.size()] = f;
    // The viscous damper's m_e as the rotational stage's: each free body's
    // lever squared over its inertia, the carrier's with the planets' orbits.
    const auto lever = [&](int dof, double r, double inertia) {
      return driver_[static_cast<std::size_t>(dof)] >= 0 ? 0.0 : r * r / inertia;
    };
    const double inverse_mass =
        lever(f.a, rb1, inertia_[static_cast<std::size_t>(f.a)]) +
        lever(f.b, rb2, inertia_[static_cast<std::size_t>(f.b)]) +
        lever(f.carrier, rb2 * f.sense_b - rb1 * f.sense_a, carrier_inertia_with_orbits(f.carrier));
    const double mass = inverse_mass > 0.0 ? 1.0 / inverse_mass : 1.0;
    if (internal) {
      meshes_.emplace_back(m.pair, table, ring.line, mass);
    } else {
      meshes_.emplace_back(m.pair, table, mass);
    }
  }
  // The carrier's inertia with m R^2 of each planet pinned on it.
  double carrier_inertia_with_orbits(int carrier) const {
    double inertia = inertia_[static_cast<std::size_t>(carrier)];
    for (std::size_t u = 0; u < dofs_; ++u) {
      if (pin_carrier_[u] == carrier) inertia += mass_[u] * pin_radius_[u] * pin_radius_[u];
    }
    return inertia;
  }
  // A centre's place r in its carrier's turning axes: its displacement u,
  // from its pin's nominal place R e_zeta on a pin.
  std::array<double, 2> turning_position(std::size_t d, const StateType& y) const {
    if (pin_carrier_[d] < 0) return {y[L::x(d)], y[L::y(d)]};
    return {y[L::x(d)] + pin_radius_[d] * pin_cos_[d], y[L::y(d)] + pin_radius_[d] * pin_sin_[d]};
  }
  // A pinned planet's bearing: its deflection from its pin (its centre less
  // the carrier's) along e_zeta (radial) and e_eta (tangential), and their rates.
  struct PinDeflection {
    double radial, tangential, radial_rate, tangential_rate;
  };
  PinDeflection pin_deflection(std::size_t d, const StateType& y) const {
    const auto c = static_cast<std::size_t>(pin_carrier_[d]);
    const double dx = y[L::x(d)] - y[L::x(c)];
    const double dy = y[L::y(d)] - y[L::y(c)];
    const double vx = y[L::vx(d)] - y[L::vx(c)];
    const double vy = y[L::vy(d)] - y[L::vy(c)];
    const double co = pin_cos_[d];
    const double si = pin_sin_[d];
    return {co * dx + si * dy, co * dy - si * dx, co * vx + si * vy, co * vy - si * vx};
  }
  // The force of a pinned planet's bearing on the planet, in the carrier's axes.
  std::array<double, 2> pin_force(std::size_t d, const StateType& y) const {
    const PinDeflection p = pin_deflection(d, y);
    const double radial = -kx_[d] * p.radial - cx_[d] * p.radial_rate;
    const double tangential = -ky_[d] * p.tangential - cy_[d] * p.tangential_rate;
    return {pin_cos_[d] * radial - pin_sin_[d] * tangential,
            pin_sin_[d] * radial + pin_cos_[d] * tangential};
  }

  // Body i's applied torque at t with its degree of freedom's angle theta
  // and speed w; 0 for a kinematic driver (rhs sets it).
  double body_torque(std::size_t i, double t, double theta, double w) const {
    const Torque& torque = train_.bodies[i].torque;
    switch (torque.kind) {
      case Torque::Kind::speed_controlled:
        return controller_[i]->torque_n_m(t, theta, w);
      case Torque::Kind::constant:
        return torque.constant_n_m;
      case Torque::Kind::prescribed_speed:
        return 0.0;
      case Torque::Kind::drag:
        return drag_torque_n_m(torque, w);
      case Torque::Kind::induction_motor:
        return induction_motor_torque_n_m(torque, w);
      default:
        break;
    }
    return torque_at(torque, t);
  }

  const GearTrain& train_;
  std::vector<int> body_dof_;
  std::size_t dofs_ = 0;
  std::size_t mesh_count_ = 0;
  // Each degree of freedom's first body and each body's next on the same
  // degree of freedom (-1: none), in the train's order. Arrays by body are
  // as long as the layout's degrees of freedom: run_planar_train picks the
  // layout by the train's bodies.
  std::array<int, L::kDofs> first_body_{};
  std::array<int, L::kDofs> next_body_{};
  std::array<double, L::kDofs> inertia_{};
  std::array<double, L::kDofs> inverse_inertia_{};
  std::array<bool, L::kDofs> translating_{};
  std::array<double, L::kDofs> mass_{};
  std::array<double, L::kDofs> inverse_mass_{};
  std::array<double, L::kDofs> kx_{}, ky_{}, cx_{}, cy_{};
  std::array<int, L::kDofs> driver_{};
  // Each body's controller (train_speed_controller; null: not speed-controlled).
  std::array<std::shared_ptr<const SpeedController>, L::kDofs> controller_{};
  bool driven_ = false;
  // A pinned planet's carrier (-1: none), its pin's radius and direction.
  std::array<int, L::kDofs> pin_carrier_{};
  std::array<double, L::kDofs> pin_radius_{}, pin_cos_{}, pin_sin_{};
  // The carrier in whose turning axes each degree of freedom's centre moves:
  // a planet's pin's, and a stage mesh's for its members (-1: fixed axes).
  std::array<int, L::kDofs> turning_with_{};
  bool turning_ = false;                            // some centre moves in a carrier's turning axes
  bool plain_ = false;                              // no driver, no carrier, only constant torques
  std::array<double, L::kDofs> constant_torque_{};  // their sum on each degree of freedom
  std::vector<MeshLine> meshes_;
  std::array<Frame, L::kMeshes> frames_{};
  // Each mesh's MeshLine::term_energy_bound, per term in J/m^2.
  std::array<std::optional<std::array<double, kTermCount>>, L::kMeshes> term_bound_{};
  std::vector<Spring> springs_;
};

// The planar train's run: the books of run_fixed_grid as the two-gear planar
// run keeps them (planar.cpp), for each mesh's two lines.
template <class L>
class PlanarTrainRun {
 public:
  using System = PlanarTrainSystem<L>;
  using State = typename System::StateType;
  using ModeSet = typename System::ModeType;
  using Memory = typename System::MemoryType;
  using Forces = typename System::ForcesType;
  static constexpr bool kCountsCutStep = true;

  PlanarTrainRun(const GearTrain& train, const std::vector<const StiffnessTable*>& tables,
                 const RunControl& control)
      : train_(train),
        control_(control),
        system_(train, tables),
        stall_(train.integrator.step_s, least_smoothing(train)),
        impacts_(train.meshes.size()),
        clock_(train.integrator.end_time_s, control, 0.0),
        drift_(train.bodies.front().torque, train.drive.settle_s, 0.0,
               train.bodies.front().theta_rad, train.bodies.front().w_rad_per_s),
        sensor_cos_(std::cos(train.sensor_angle_rad)),
        sensor_sin_(std::sin(train.sensor_angle_rad)) {
    SimulationSummary& s = result_.summary;
    s.planar = PlanarEnergies{};
    s.step_s = train.integrator.step_s;
    result_.meshes.resize(train.meshes.size());
    for (const TrainMesh& m : train.meshes) {
      half_base_pitch_m_.push_back(0.5 * base_pitch(m.pair.gears));
    }
    for (std::size_t i = 0; i < train.bodies.size(); ++i) {
      const auto d = static_cast<std::size_t>(system_.dof_of(static_cast<int>(i)));
      y_[L::theta(d)] = train.bodies[i].theta_rad;
      y_[L::w(d)] = train.bodies[i].w_rad_per_s;
    }
    system_.impose_driver(0.0, y_);
    classify(0.0);
    if (control.keep_samples && clock_.on()) result_.samples.reserve(clock_.reserve_rows());
    emit_samples(0.0, y_, mode_, [](double, State&) {});
    if (train.tacho_body >= 0) {
      // The tacho's body's angle, and its driver, whose closed form it then reads.
      const auto d = static_cast<std::size_t>(system_.dof_of(train.tacho_body));
      tacho_index_ = L::theta(d);
      const int driver = system_.driver_of(d);
      if (driver >= 0) tacho_driver_ = &train.bodies[static_cast<std::size_t>(driver)];
      tacho_.emplace(train.tacho, y_[tacho_index_]);
    }
    PlanarEnergies& p = *s.planar;
    const double kinetic0 = system_.kinetic_energy(y_);
    const double mesh0 = mesh_energy(y_);
    s.kinetic_energy_initial_j = kinetic0;
    s.stored_energy_initial_j = mesh0;
    p.bearing_energy_initial_j = system_.bearing_energy(y_);
    p.shaft_energy_initial_j = system_.shaft_energy(y_);
    energy0_ = kinetic0 + mesh0 + p.bearing_energy_initial_j + p.shaft_energy_initial_j;
    if (records()) record(0.0);
    system_.rhs(0.0, y_, mode_, memory_, k1_, &at_start_);
    s.rhs_evaluations += 1;
  }

  const System& system() const { return system_; }
  State& y() { return y_; }
  const ModeSet& mode() const { return mode_; }
  const Memory& damping() const { return memory_; }
  long long& steps() { return result_.summary.steps; }
  long long& rhs_evaluations() { return result_.summary.rhs_evaluations; }
  double start_time() const { return 0.0; }
  long long grid_steps() const {
    return static_cast<long long>(
        std::ceil(train_.integrator.end_time_s / train_.integrator.step_s - 1e-9));
  }
  bool wants_dense() const { return clock_.on() || tacho_.has_value(); }
  bool records() const { return control_.keep_series || static_cast<bool>(control_.on_train_row); }
  bool sampling() const { return clock_.on(); }
  const State& first_stage(double) const { return k1_; }
  // The sensor's samples not yet taken up to t_b, the end of a step in mode
  // m at y_b: one at t_b is y_b itself, one before it the step's continuous
  // extension (the two-gear planar run's).
  template <typename StateAt>
  void emit_samples(double t_b, const State& y_b, const ModeSet& m, StateAt state_at) {
    clock_.emit_states(t_b, y_b, state_at, [&](double ts, const State& y) { sample(ts, y, m); });
  }
  // The tacho's edges inside the step from (t_a, y_a) to (t_b, y_b), as the
  // two-gear planar run's: on its continuous extension, or a driver's closed form.
  template <typename Dense>
  void observe_step(double t_a, const State& y_a, double t_b, const State& y_b,
                    const Dense& dense) {
    if (!tacho_) return;
    tacho_->step(t_a, y_a[tacho_index_], t_b, y_b[tacho_index_], [&](double tau) {
      if (tacho_driver_ != nullptr) return driven_body_motion(*tacho_driver_, tau).theta_rad;
      State x{};
      dense(tau, x);
      return x[tacho_index_];
    });
  }
  void check_finite(double t, const State& y) const {
    check_finite_state(t, result_.summary.steps, y);
  }
  void poll_stop(double t) const { poll_stop_request(control_, result_.summary.steps, t); }

  // The mode changed at (t, y_): each line classified again; the stored
  // energy before, for the jump's work.
  void change_mode(double t) {
    ++result_.summary.events;
    before_ = mesh_energy(y_);
    classify(t);
    event_ = true;
  }

  // As the planar run's: the friction signs per stage while a contact sticks.
  bool check_progress(double t_from, double t_to, bool event) {
    const bool sticks = stall_.after_step(event, t_from, t_to,
                                          [&] { return where(t_from, result_.summary.steps); });
    const std::size_t lines = 2 * system_.mesh_count();
    stepped_per_stage_ = !event && mode_.line[0].slip_per_stage;
    if (stepped_per_stage_) {
      bool sticking = false;
      for (std::size_t i = 0; i < lines; ++i) {
        Mode& m = mode_.line[i];
        const std::array<double, kMaxPairs> slip = m.slip;
        system_.mesh(i / 2).classify_forces(system_.motion(i / 2, y_), memory_[i], m);
        sticking = sticking || slip != m.slip;
      }
      for (std::size_t i = 0; i < lines; ++i) mode_.line[i].slip_per_stage = sticking;
    }
    if (sticks) {
      for (std::size_t i = 0; i < lines; ++i) mode_.line[i].slip_per_stage = true;
    }
    return stepped_per_stage_ || sticks;
  }

  // After an accepted step ending at t: the next step's first stage, the
  // jump's work at an event, the largest penetrations and the ledger.
  void book_keep(double t) {
    SimulationSummary& s = result_.summary;
    drift_.observe(t, y_[L::theta(static_cast<std::size_t>(system_.dof_of(0)))]);
    at_start_ = Forces{};
    system_.rhs(t, y_, mode_, memory_, k1_, &at_start_);
    s.rhs_evaluations += 1;
    double mesh = 0.0;
    for (std::size_t i = 0; i < 2 * system_.mesh_count(); ++i) mesh += at_start_.mesh_energy_j[i];
    // A pair that entered or left takes or releases its stored energy: work
    // of the time-varying stiffness, booked at the event.
    if (event_) jump_work_ += mesh - before_;
    event_ = false;
    stepped_per_stage_ = false;
    for (std::size_t k = 0; k < L::kMeshes && k < system_.mesh_count(); ++k) {
      const MeshLine& line = system_.mesh(k);
      const PlanarMeshMotion q = system_.motion(k, y_);
      const double penetration =
          std::max(line.contact_value(Region::n1, q), line.contact_value(Region::n2, q));
      s.max_penetration_m = std::max(s.max_penetration_m, penetration);
      TrainMeshSummary& own = result_.meshes[k];
      own.max_penetration_m = std::max(own.max_penetration_m, penetration);
      if (own.max_penetration_m > half_base_pitch_m_[k]) {
        throw SimulationError("the teeth of mesh " + train_.meshes[k].name + " overlap by " +
                              format_number(own.max_penetration_m) +
                              " m on the line of action at " + where(t, s.steps) +
                              ", more than half a base pitch (" +
                              format_number(half_base_pitch_m_[k]) +
                              " m): the model's contact on the line of action no longer holds");
      }
    }
    if (system_.terms_may_exceed(y_, mode_, s.energy_max_j)) {
      ElasticEnergy terms;
      for (std::size_t k = 0; k < L::kMeshes && k < system_.mesh_count(); ++k) {
        const PlanarMeshMotion q = system_.motion(k, y_);
        for (std::size_t i = 0; i < 2; ++i) {
          system_.mesh(k).add_stored_energy(q, mode_.line[2 * k + i], terms);
        }
      }
      for (std::size_t i = 0; i < kTermCount; ++i) {
        s.energy_max_j[i] = std::max(s.energy_max_j[i], terms.j[i]);
      }
    }
    const double energy =
        system_.kinetic_energy(y_) + mesh + system_.bearing_energy(y_) + system_.shaft_energy(y_);
    book_ledger_residual(
        energy, energy0_, y_[L::kWork],
        {y_[L::kHertzLoss], y_[L::kSlidingLoss], y_[L::kBearingLoss], 0.0, y_[L::kMeshDamperLoss]},
        y_[L::kParametric], jump_work_, s);
  }

  void record(double t) { record(t, y_, mode_); }
  void record(double t, const State& y, const ModeSet& mode) {
    State dy{};
    TrainRow row = row_at(t, y, mode, dy);
    row.sensor_acceleration_m_per_s2 = sensor_acceleration(dy);
    if (control_.on_train_row) control_.on_train_row(row);
    if (control_.keep_series) result_.series.push_back(std::move(row));
  }

  // A sample of the sensor at ts (SampleKind): its row at the sampled state,
  // whose sensor acceleration is the point value or the mean over the
  // interval ending at ts; an interval-average run's first sample only
  // begins the first interval.
  void sample(double ts, const State& state, const ModeSet& m) {
    const auto d = static_cast<std::size_t>(system_.dof_of(train_.sensor_body));
    const auto v = [&](std::size_t i) { return state[i == 0 ? L::vx(d) : L::vy(d)]; };
    const bool average = control_.sample == SampleKind::interval_average;
    if (average && clock_.first()) {
      average_.start(ts, v);
      return;
    }
    State dy{};
    TrainRow row = row_at(ts, state, m, dy);
    if (average) {
      average_.next(ts, v,
                    [&](std::size_t i) -> double& { return dy[i == 0 ? L::vx(d) : L::vy(d)]; });
    }
    row.sensor_acceleration_m_per_s2 = sensor_acceleration(dy);
    if (control_.on_train_sample) control_.on_train_sample(row);
    if (control_.keep_samples) result_.samples.push_back(std::move(row));
  }

  // The sensor's acceleration from the derivatives dy: its centre's along
  // the sensor's direction (0 without a sensor).
  double sensor_acceleration(const State& dy) const {
    if (train_.sensor_body < 0) return 0.0;
    const auto d = static_cast<std::size_t>(system_.dof_of(train_.sensor_body));
    return dy[L::vx(d)] * sensor_cos_ + dy[L::vy(d)] * sensor_sin_;
  }

  // The row at (t, y) in the mode, its derivatives in dy; the sensor's
  // acceleration left to the caller.
  TrainRow row_at(double t, const State& y, const ModeSet& mode, State& dy) const {
    Forces f;
    system_.rhs(t, y, mode, memory_, dy, &f);
    TrainRow row;
    row.t_s = t;
    // One allocation per list, as the rotational train's row (dynamics/train.cpp).
    row.theta_rad.reserve(train_.bodies.size());
    row.w_rad_per_s.reserve(train_.bodies.size());
    row.centres.reserve(train_.bodies.size());
    row.meshes.reserve(system_.mesh_count());
    for (std::size_t i = 0; i < train_.bodies.size(); ++i) {
      const auto d = static_cast<std::size_t>(system_.dof_of(static_cast<int>(i)));
      row.theta_rad.push_back(y[L::theta(d)]);
      row.w_rad_per_s.push_back(y[L::w(d)]);
      const std::array<double, 2> bearing = system_.bearing_force(d, y);
      row.centres.push_back(
          {y[L::x(d)], y[L::y(d)], y[L::vx(d)], y[L::vy(d)], bearing[0], bearing[1]});
    }
    for (std::size_t k = 0; k < L::kMeshes && k < system_.mesh_count(); ++k) {
      const MeshLine& line = system_.mesh(k);
      const PlanarMeshMotion q = system_.motion(k, y);
      // As the two-gear planar row: the drive line's s_d, the larger
      // penetration of a pair, the side in contact (the drive side when both are).
      const double dd = line.contact_value(Region::n1, q);
      const double dc = line.contact_value(Region::n2, q);
      const Mode& drive = mode.line[2 * k];
      const Mode& coast = mode.line[2 * k + 1];
      const bool on_drive = drive.region != Region::free;
      const bool on_coast = coast.region != Region::free;
      row.meshes.push_back({line.delta(Region::n1, q) + train_.meshes[k].pair.gears.backlash_m,
                            std::max(dd, dc),
                            on_drive ? 1 : (on_coast ? -1 : 0),
                            on_drive ? drive.count : (on_coast ? coast.count : 0),
                            f.normal_n[2 * k] + f.normal_n[2 * k + 1],
                            f.friction_n[k],
                            {f.normal_n[2 * k], f.normal_n[2 * k + 1]},
                            {dd, dc}});
    }
    return row;
  }

  TrainResult finish(double t, const char* integrator) {
    SimulationSummary& s = result_.summary;
    PlanarEnergies& p = *s.planar;
    s.integrator = integrator;
    s.end_time_s = t;
    book_ledger_totals(system_.kinetic_energy(y_), mesh_energy(y_), y_[L::kWork], y_[L::kHertzLoss],
                       y_[L::kSlidingLoss], y_[L::kMeshDamperLoss], y_[L::kParametric], jump_work_,
                       s);
    s.mesh_damper = std::any_of(train_.meshes.begin(), train_.meshes.end(), [](const TrainMesh& m) {
      return m.pair.model.mesh_damping_ratio > 0.0;
    });
    p.bearing_energy_final_j = system_.bearing_energy(y_);
    p.bearing_damping_loss_j = y_[L::kBearingLoss];
    p.shaft_energy_final_j = system_.shaft_energy(y_);
    s.speed_drift_max_rel = drift_.max_relative_drift();
    if (tacho_) result_.tacho_times_s = tacho_->times();
    s.final_w1_rad_per_s = y_[L::w(static_cast<std::size_t>(system_.dof_of(0)))];
    s.final_w2_rad_per_s = y_[L::w(static_cast<std::size_t>(system_.dof_of(1)))];
    for (std::size_t k = 0; k < L::kMeshes && k < system_.mesh_count(); ++k) {
      TrainMeshSummary& mesh = result_.meshes[k];
      mesh.damping_loss_j = y_[L::mesh_loss(k, 0)];
      mesh.friction_loss_j = y_[L::mesh_loss(k, 1)];
      mesh.mesh_damping_loss_j = y_[L::mesh_loss(k, 2)];
      mesh.impacts = static_cast<int>(impacts_[k].records().size());
      result_.impacts.push_back(impacts_[k].take());
    }
    result_.bodies.resize(train_.bodies.size());
    for (std::size_t i = 0; i < train_.bodies.size(); ++i) {
      result_.bodies[i].final_w_rad_per_s =
          y_[L::w(static_cast<std::size_t>(system_.dof_of(static_cast<int>(i))))];
    }
    return std::move(result_);
  }

 private:
  static double least_smoothing(const GearTrain& train) {
    double least = train.meshes.front().pair.model.friction_smoothing_speed_m_s;
    for (const TrainMesh& m : train.meshes) {
      least = std::min(least, m.pair.model.friction_smoothing_speed_m_s);
    }
    return least;
  }

  // The meshes' stored energy at `state` in the run's modes, line by line.
  double mesh_energy(const State& state) const {
    double e = 0.0;
    for (std::size_t k = 0; k < L::kMeshes && k < system_.mesh_count(); ++k) {
      const PlanarMeshMotion q = system_.motion(k, state);
      for (std::size_t i = 0; i < 2; ++i) {
        e += system_.mesh(k).elastic_energy_j(q, mode_.line[2 * k + i]);
      }
    }
    return e;
  }

  // The mode of y_ at t: each line's contact, pairs and parts; an impact
  // where a line's contact begins (its damping memory then set), its end
  // where it ends; then the forces' signs.
  void classify(double t) {
    for (std::size_t k = 0; k < L::kMeshes && k < system_.mesh_count(); ++k) {
      const MeshLine& line = system_.mesh(k);
      const PlanarMeshMotion q = system_.motion(k, y_);
      for (std::size_t i = 0; i < 2; ++i) {
        const Region side = kLines[i];
        Mode& m = mode_.line[2 * k + i];
        const bool before = m.region != Region::free;
        m = line.classify_line(side, q);
        const bool now = m.region != Region::free;
        if (now && !before) {
          const MeshLine::Onset onset = line.damping_at_onset(q, m);
          memory_[2 * k + i] = onset.damping;
          impacts_[k].begin(side, t, onset.impact_speed_m_s, onset.restitution, result_.summary);
        } else if (!now && before) {
          impacts_[k].end(side, t, -line_sign(side) * line.s_rate(side, q));
        }
        line.classify_forces(q, memory_[2 * k + i], m);
      }
    }
  }

  const GearTrain& train_;
  const RunControl& control_;
  const System system_;
  StallWatch stall_;
  std::vector<ImpactBook> impacts_;
  std::vector<double> half_base_pitch_m_;
  State y_{};
  State k1_{};
  Forces at_start_;
  ModeSet mode_{};
  Memory memory_{};
  TrainResult result_;
  double energy0_ = 0.0;
  double jump_work_ = 0.0;
  bool event_ = false;
  double before_ = 0.0;
  bool stepped_per_stage_ = false;
  SampleClock clock_;
  SpeedDriftMonitor drift_;  // of the first body
  std::optional<TachoEdges> tacho_;
  std::size_t tacho_index_ = 0;              // its body's angle in the state
  const TrainBody* tacho_driver_ = nullptr;  // the driver of its body's degree of freedom
  IntervalAverage<2> average_;               // the sensor's centre's vx and vy
  double sensor_cos_;
  double sensor_sin_;
};

template <class L>
TrainResult run_layout(const GearTrain& train, const std::vector<const StiffnessTable*>& tables,
                       const RunControl& control) {
  PlanarTrainRun<L> run(train, tables, control);
  FixedStepper<PlanarTrainSystem<L>> stepper(run.system(), train.integrator.kind);
  const double t = run_fixed_grid(run, stepper, train.integrator);
  return run.finish(t, name_of(kIntegratorKinds, train.integrator.kind).c_str());
}

void check_bearing_value(const std::string& field, double value, bool positive) {
  if (!std::isfinite(value) || value < 0.0 || (positive && value == 0.0)) {
    throw InputError(field, value, positive ? "a finite value > 0" : "a finite value >= 0");
  }
}

}  // namespace

bool has_planar_bodies(const GearTrain& train) {
  return std::any_of(train.bodies.begin(), train.bodies.end(),
                     [](const TrainBody& b) { return b.bearing.has_value(); });
}

void validate_planar_train(const GearTrain& train) {
  const std::vector<int> dof = train_degrees_of_freedom(train);
  const int dofs = count_dofs(dof);
  std::vector<int> owner(static_cast<std::size_t>(dofs), -1);
  std::string named;  // a body with bearings, for the refusals below
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    const TrainBody& b = train.bodies[i];
    const std::string prefix = "bodies." + b.name + ".";
    if (!b.bearing) continue;
    if (named.empty()) named = b.name;
    const GearBearing& g = *b.bearing;
    const std::string field = prefix + "bearings.";
    if (!g.mass_kg) {
      throw InputError(field + "mass", "absent",
                       "a finite mass > 0 kg (a train's body has no disc)");
    }
    check_bearing_value(field + "mass", *g.mass_kg, true);
    check_bearing_value(field + "stiffness_x", g.stiffness_x_n_per_m, false);
    check_bearing_value(field + "stiffness_y", stiffness_y(g), false);
    check_bearing_value(field + "damping_x", g.damping_x_n_s_per_m, false);
    check_bearing_value(field + "damping_y", damping_y(g), false);
    int& first = owner[static_cast<std::size_t>(dof[i])];
    if (first >= 0) {
      throw InputError(field + "mass", "bearings on this body",
                       "bearings on one body of a rigid shaft only: " +
                           train.bodies[static_cast<std::size_t>(first)].name +
                           ", on one rigid shaft with it, has them (their centre is one)");
    }
    first = static_cast<int>(i);
    if (!b.pin) continue;
    const TrainBody::Pin& pin = *b.pin;
    if (pin.carrier < 0 || static_cast<std::size_t>(pin.carrier) >= train.bodies.size() ||
        pin.carrier == static_cast<int>(i) ||
        train.bodies[static_cast<std::size_t>(pin.carrier)].pin) {
      throw InputError(prefix + "pin.carrier", std::to_string(pin.carrier),
                       "the index of another body, itself on no pin");
    }
    if (!std::isfinite(pin.radius_m) || pin.radius_m <= 0.0) {
      throw InputError(prefix + "pin.radius", pin.radius_m, "a finite radius > 0 m");
    }
    if (!std::isfinite(pin.angle_rad)) {
      throw InputError(prefix + "pin.angle", pin.angle_rad, "a finite angle");
    }
    for (std::size_t j = 0; j < train.bodies.size(); ++j) {
      if (j != i && dof[j] == dof[i]) {
        throw InputError(prefix + "pin", "on a rigid shaft with " + train.bodies[j].name,
                         "a planet alone on its pin");
      }
    }
  }
  const std::string why = " in a train with bodies on elastic bearings (bodies." + named +
                          ".bearings; not modelled yet)";
  int frame_carrier = -1;
  for (const TrainMesh& m : train.meshes) {
    const std::string prefix = "meshes." + m.name + ".";
    if (m.carrier >= 0) {
      // A planetary stage in the carrier's axes: its planet on a pin of
      // that carrier, its central members' supports isotropic (the axes turn).
      if (frame_carrier >= 0 && m.carrier != frame_carrier) {
        throw InputError(prefix + "carrier", std::to_string(m.carrier),
                         std::to_string(frame_carrier) +
                             ", the other stage meshes' carrier: a train on elastic bearings "
                             "turns in one carrier's axes");
      }
      frame_carrier = m.carrier;
      const TrainBody& planet = train.bodies[static_cast<std::size_t>(m.body_b)];
      if (!planet.pin || planet.pin->carrier != m.carrier || !planet.bearing) {
        throw InputError(prefix + "carrier", std::to_string(m.carrier),
                         "the body whose pin holds body_b (bodies." + planet.name +
                             ".pin, with its bearing)" + why);
      }
      for (const int central : {m.body_a, m.carrier}) {
        const TrainBody& c = train.bodies[static_cast<std::size_t>(central)];
        if (!c.bearing) continue;
        const std::string field = "bodies." + c.name + ".bearings.";
        if (stiffness_y(*c.bearing) != c.bearing->stiffness_x_n_per_m) {
          throw InputError(field + "stiffness_y", stiffness_y(*c.bearing),
                           "stiffness_x: a stage's central member on isotropic supports (its "
                           "axes are the carrier's, which turn)");
        }
        if (damping_y(*c.bearing) != c.bearing->damping_x_n_s_per_m) {
          throw InputError(field + "damping_y", damping_y(*c.bearing),
                           "damping_x: a stage's central member on isotropic supports (its "
                           "axes are the carrier's, which turn)");
        }
      }
    } else if (m.kind == TrainMesh::Kind::internal) {
      throw InputError(prefix + "kind", "internal", "external" + why);
    }
    if (m.pair.model.mesh_force == MeshForce::lagrangian) {
      throw InputError(prefix + "model.mesh_force", "lagrangian", "newtonian" + why);
    }
    if (!std::isfinite(m.centre_angle_rad)) {
      throw InputError(prefix + "centre_angle", m.centre_angle_rad, "a finite angle");
    }
  }
  if (train.integrator.kind == IntegratorKind::adaptive) {
    throw InputError("integrator.kind", "adaptive", "rk4 or dopri5" + why);
  }
  int conflict = -1;
  turning_senses(train, dof, dofs, conflict);
  if (conflict >= 0) {
    throw InputError("meshes." + train.meshes[static_cast<std::size_t>(conflict)].name + ".body_b",
                     std::to_string(train.meshes[static_cast<std::size_t>(conflict)].body_b),
                     "a body whose sense of turning the train's other meshes do not already "
                     "fix the other way (a loop of external meshes between fixed axes)");
  }
  if (train.sensor_body >= 0) {
    if (static_cast<std::size_t>(train.sensor_body) >= train.bodies.size() ||
        owner[static_cast<std::size_t>(dof[static_cast<std::size_t>(train.sensor_body)])] < 0) {
      throw InputError("sensor_body", std::to_string(train.sensor_body),
                       "a body on elastic bearings (or on one rigid shaft with one)");
    }
  }
  if (!std::isfinite(train.sensor_angle_rad)) {
    throw InputError("sensor_angle", train.sensor_angle_rad, "a finite angle");
  }
}

void check_planar_train_step(const GearTrain& train,
                             const std::vector<const StiffnessTable*>& tables) {
  const std::vector<int> dof = train_degrees_of_freedom(train);
  const int dofs = count_dofs(dof);
  // The step must resolve the fastest motion the planar train can have: its
  // largest w^2 is at most the sum over its springs of k a^T M^-1 a (as
  // planar.cpp bounds the two-gear system's), each mesh counted on both lines
  // at its stiffest, with each bearing damper's decay rate c/m counted as a
  // frequency.
  const std::vector<double> inertia = dof_inertias(train, dof, dofs);
  const std::vector<int> bearing = bearing_bodies(train, dof, dofs);
  const auto inverse_mass = [&](int d) {
    const int body = bearing[static_cast<std::size_t>(d)];
    return body < 0 ? 0.0 : 1.0 / *train.bodies[static_cast<std::size_t>(body)].bearing->mass_kg;
  };
  // A pinned planet's centre moves against its orbit's share of the
  // carrier's turning too (its tangential inverse mass 1/m + R^2/J_c).
  const auto orbit = [&](int d) {
    for (std::size_t i = 0; i < train.bodies.size(); ++i) {
      const TrainBody& b = train.bodies[i];
      if (dof[i] != d || !b.pin) continue;
      const double r = b.pin->radius_m;
      return r * r /
             inertia[static_cast<std::size_t>(dof[static_cast<std::size_t>(b.pin->carrier)])];
    }
    return 0.0;
  };
  double w2 = 0.0;
  for (std::size_t k = 0; k < train.meshes.size(); ++k) {
    const TrainMesh& m = train.meshes[k];
    const GearPair& g = m.pair.gears;
    if (m.carrier >= 0) {
      // A stage's mesh: its stiffest on a line taken as two pairs at the
      // table's largest Ke (sampled at 65 points; the constant stiffness
      // when the model has one), on its bodies' turning relative to the
      // carrier (each lever squared over its inertia, the carrier's lever
      // Rb_a + kappa Rb_b) and on both centres.
      double stiffest = m.pair.model.mesh_stiffness == MeshStiffnessMode::constant
                            ? m.pair.model.constant_mesh_stiffness_n_per_m
                            : 0.0;
      const StiffnessTable& table = *tables[k];
      for (int i = 0; i <= 64 && stiffest == 0.0; ++i) {
        const double x =
            table.domain_start_m() + (table.domain_end_m() - table.domain_start_m()) * i / 64.0;
        stiffest = std::max(stiffest, 2.0 * table.stiffness(x));
      }
      const bool internal = m.kind == TrainMesh::Kind::internal;
      const RingLine ring = internal ? ring_line(m.pair) : RingLine{};
      const double ra = internal ? ring.line.ring_base_radius_m : base_radius(g, Gear::one);
      const double rb = internal ? ring.line.planet_base_radius_m : base_radius(g, Gear::two);
      const auto turning = [&](int body, double r) {
        const TrainBody& b = train.bodies[static_cast<std::size_t>(body)];
        return b.held
                   ? 0.0
                   : r * r / inertia[static_cast<std::size_t>(dof[static_cast<std::size_t>(body)])];
      };
      const double lever = internal ? ra - rb : ra + rb;
      const int a = dof[static_cast<std::size_t>(m.body_a)];
      const int b = dof[static_cast<std::size_t>(m.body_b)];
      const double own = turning(m.body_a, ra) + turning(m.body_b, rb) + turning(m.carrier, lever) +
                         inverse_mass(a) + inverse_mass(b) + orbit(b);
      w2 += 2.0 * stiffest * own;
      continue;
    }
    // The pair's stiffest contact, from its own bound on its discs.
    const double torsional = largest_resolving_step_s(m.pair, *tables[k]);
    const double discs = inverse_effective_mass_per_kg(g);
    const double w_t = 2.0 * pi / (kStepsPerContactPeriod * torsional);
    const double stiffest = w_t * w_t / discs;
    const int a = dof[static_cast<std::size_t>(m.body_a)];
    const int b = dof[static_cast<std::size_t>(m.body_b)];
    const double own = inverse_effective_mass_per_kg(
        base_radius(g, Gear::one), inertia[static_cast<std::size_t>(a)], base_radius(g, Gear::two),
        inertia[static_cast<std::size_t>(b)]);
    w2 += 2.0 * stiffest * (own + inverse_mass(a) + inverse_mass(b));
  }
  for (int d = 0; d < dofs; ++d) {
    const int body = bearing[static_cast<std::size_t>(d)];
    if (body < 0) continue;
    const GearBearing& g = *train.bodies[static_cast<std::size_t>(body)].bearing;
    double im = inverse_mass(d);
    const TrainBody& owner = train.bodies[static_cast<std::size_t>(body)];
    if (owner.pin) {
      // The bearing between the planet and its pin: the carrier's centre moves too.
      const int c = dof[static_cast<std::size_t>(owner.pin->carrier)];
      im += inverse_mass(c);
      w2 += stiffness_y(g) * orbit(d);
    }
    w2 += (g.stiffness_x_n_per_m + stiffness_y(g)) * im;
    const double cx = g.damping_x_n_s_per_m * im;
    const double cy = damping_y(g) * im;
    w2 += cx * cx + cy * cy;
  }
  for (const TrainShaft& s : train.shafts) {
    if (s.kind != TrainShaft::Kind::torsional) continue;
    w2 += s.stiffness_n_m_per_rad *
          (1.0 / inertia[static_cast<std::size_t>(dof[static_cast<std::size_t>(s.body_a)])] +
           1.0 / inertia[static_cast<std::size_t>(dof[static_cast<std::size_t>(s.body_b)])]);
  }
  const double steps = steps_per_contact_period(train.integrator.kind);
  const double largest = 2.0 * pi / std::sqrt(w2) / steps;
  if (train.integrator.step_s > largest) {
    throw InputError("integrator.step", format_number(train.integrator.step_s) + " s",
                     "at most " + format_number(largest) +
                         " s with bodies on elastic bearings: 1/" + format_number(steps) +
                         " of the shortest period the planar train can have (its stiffest "
                         "springs: each mesh on both lines, the bearings, the shafts, and the "
                         "bearings' dampers' decay rates c/m)");
  }
}

TrainResult run_planar_train(const GearTrain& train,
                             const std::vector<const StiffnessTable*>& tables,
                             const RunControl& control) {
  if (train.bodies.size() <= PairPlanarTrain::kDofs &&
      train.meshes.size() <= PairPlanarTrain::kMeshes) {
    return run_layout<PairPlanarTrain>(train, tables, control);
  }
  if (train.bodies.size() <= SmallPlanarTrain::kDofs &&
      train.meshes.size() <= SmallPlanarTrain::kMeshes) {
    return run_layout<SmallPlanarTrain>(train, tables, control);
  }
  if (train.meshes.size() <= LargePlanarTrain::kMeshes) {
    return run_layout<LargePlanarTrain>(train, tables, control);
  }
  return run_layout<SlicedPlanarTrain>(train, tables, control);
}

}  // namespace gearimpact
