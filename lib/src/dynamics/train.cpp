// The torsional gear train (train.hpp) as a system of the run loop: its
// bodies' angles and speeds, one MeshLine per mesh, shafts; the run's books
// (the mode and its changes, impacts, the energy ledger, the output rows) as
// the torsional Run keeps them for its one mesh, here for each mesh.
#include "gearimpact/dynamics/train.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adaptive_loop.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/dynamics/drive.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/geometry/planetary.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/helical_faults.hpp"
#include "gearimpact/stiffness/internal_tooth.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "ledger.hpp"
#include "run_parts.hpp"
#include "stall.hpp"
#include "step_methods.hpp"
#include "train_planar.hpp"

namespace gearimpact {

namespace {

// The bodies' angles, then their speeds, then the ledger's integrals as the
// two-gear State has them: torque work, damping loss, friction loss,
// parametric work (its continuous part), the mesh dampers' loss; then each
// mesh's own three losses (damping, friction, mesh damper) for its summary.
// The train's totals are integrated as they were, so that adding the meshes'
// own changes none of their bits.
enum LedgerIndex : std::size_t { kWork, kDamping, kFriction, kParametric, kMeshDamping };
enum MeshLossIndex : std::size_t { kMeshDampingLoss, kMeshFrictionLoss, kMeshDamperLoss };
// The state's layout for at most Bodies bodies and Meshes meshes, with or
// without meshes in a carrier's frame: a train that fits the small layout
// runs in it, so that the planetary stage's sizes cost today's trains nothing
// (the integrator sweeps the whole state at every stage).
template <int Bodies, int Meshes, bool Carriers>
struct TrainLayout {
  static constexpr std::size_t kBodies = Bodies;
  static constexpr std::size_t kMeshes = Meshes;
  static constexpr bool kCarriers = Carriers;
  static constexpr std::size_t kLedger = 2 * kBodies;
  static constexpr std::size_t kMeshLosses = kLedger + 5;
  // A train of one mesh: the mesh's own losses are the train's, integrated
  // from the same powers, so the state holds them once.
  static constexpr bool kOwnLosses = kMeshes > 1;
  static constexpr std::size_t mesh_loss_of(std::size_t mesh, MeshLossIndex loss) {
    if (!kOwnLosses) {
      return kLedger + (loss == kMeshDampingLoss    ? kDamping
                        : loss == kMeshFrictionLoss ? kFriction
                                                    : kMeshDamping);
    }
    return kMeshLosses + 3 * mesh + loss;
  }
  static constexpr std::size_t theta_of(int body) { return static_cast<std::size_t>(body); }
  static constexpr std::size_t w_of(int body) { return kBodies + static_cast<std::size_t>(body); }
  using State = std::array<double, kMeshLosses + (kOwnLosses ? 3 * kMeshes : 0)>;
  struct ModeSet {
    std::array<Mode, kMeshes> mesh{};
  };
  struct Memory {
    std::array<ContactMemory, kMeshes> mesh{};
  };
  struct Forces {
    std::array<ContactTotals, kMeshes> mesh{};
  };
  using Events = std::array<double, kMeshes * kMaxMeshEvents>;
};
// A two-gear case's train (two bodies, one mesh: 9 values, as the two-gear
// model's), today's trains (the sizes before planetary stages),
// the largest, and a train of helical slices.
using PairTrain = TrainLayout<2, 1, false>;
using SmallTrain = TrainLayout<6, 4, false>;
using LargeTrain = TrainLayout<kMaxTrainBodies, kMaxTrainMeshes, true>;
using SlicedTrain = TrainLayout<kMaxTrainBodies, kMaxTrainLines, true>;

// The layout's names inside the system and the run.
#define GEARIMPACT_TRAIN_LAYOUT_NAMES                                               \
  using TrainState = typename L::State;                                             \
  using TrainMode = typename L::ModeSet;                                            \
  using TrainMemory = typename L::Memory;                                           \
  using TrainForces = typename L::Forces;                                           \
  using TrainEvents = typename L::Events;                                           \
  static constexpr std::size_t kBodies = L::kBodies;                                \
  static constexpr std::size_t kLedger = L::kLedger;                                \
  static constexpr std::size_t theta_of(int body) {                                 \
    return L::theta_of(body);                                                       \
  }                                                                                 \
  static constexpr std::size_t w_of(int body) {                                     \
    return L::w_of(body);                                                           \
  }                                                                                 \
  static constexpr std::size_t mesh_loss_of(std::size_t mesh, MeshLossIndex loss) { \
    return L::mesh_loss_of(mesh, loss);                                             \
  }

bool kinematic_driver(const Torque& t) {
  return t.kind == Torque::Kind::prescribed_speed;
}

const char* name_of_torque(const Torque& t) {
  switch (t.kind) {
    case Torque::Kind::prescribed_speed:
      return "prescribed-speed";
    case Torque::Kind::speed_controlled:
      return "speed-controlled";
    default:
      return "a torque other than none";
  }
}
bool carrier_mesh(const TrainMesh& m) {
  return m.carrier >= 0;
}
bool internal_mesh(const TrainMesh& m) {
  return m.kind == TrainMesh::Kind::internal;
}
// An internal mesh whose pairs take the potential-energy route
// (internal_tooth.hpp) rather than ISO 6336-1's table.
bool ring_by_potential_energy(const TrainMesh& m) {
  return internal_mesh(m) && m.pair.model.stiffness.kind == StiffnessModelKind::potential_energy;
}
bool helical_mesh(const TrainMesh& m) {
  return m.pair.gears.helix_angle_rad != 0.0;
}
// The lines a mesh runs as: N slices by route A, else one.
int line_count(const TrainMesh& m) {
  return runs_by_slices(m) ? m.pair.model.stiffness.face_slices : 1;
}

// Route A's refusals of a helical mesh with modifications, before its pair's
// other checks (which see it without them): tooth errors, whose numbering a
// slice's shift along the line would move by whole teeth; a frozen Hertzian
// damping stiffness, which a slice would take unprojected; the adaptive step
// bound, which is a face-wide pair's; then the modifications themselves on
// the helical pair (validate_modifications, as the helical STE checks them).
void validate_sliced_mesh(const std::string& prefix, const TrainMesh& mesh,
                          const IntegratorSettings& integrator) {
  const SimulationCase& c = mesh.pair;
  const std::string why =
      ": a helical mesh with modifications runs by slices (route A of docs/helical.md), whose "
      "shifts along the line renumber the teeth";
  for (const Gear gear : {Gear::one, Gear::two}) {
    const GearModifications& g = gear == Gear::one ? c.modifications.gear1 : c.modifications.gear2;
    const std::string n = gear == Gear::one ? "1" : "2";
    const auto refuse = [&](const std::string& key, const std::vector<double>& list) {
      if (!list.empty()) {
        throw InputError(prefix + "modifications." + key + n,
                         std::to_string(list.size()) + " values", "none" + why);
      }
    };
    refuse("pitch_deviations", g.pitch_m);
    refuse("thickness_deviations", g.thickness_m);
    refuse("profile_slope_deviations", g.profile_slope_m);
    if (g.iso1328_class != 0) {
      throw InputError(prefix + "modifications.iso1328_class" + n, std::to_string(g.iso1328_class),
                       "0" + why);
    }
  }
  if (c.model.damping_stiffness == DampingStiffness::hertz) {
    throw InputError(prefix + "model.damping_stiffness", "hertz",
                     "current-pair or pitch-pair-at-impact with a helical mesh run by slices: a "
                     "slice's frozen Hertzian stiffness would miss the inclined line's "
                     "projection");
  }
  if (integrator.kind == IntegratorKind::adaptive) {
    throw InputError("integrator.kind", "adaptive",
                     "a fixed-step integrator with a helical mesh run by slices (" + mesh.name +
                         "): the adaptive step bound is a face-wide pair's");
  }
  if (mesh.table) {
    throw InputError(prefix + "table", "a table given",
                     "none: a helical mesh run by slices builds its slices' table");
  }
}

// Slice j's (of n) modifications (helical_slice_meshes): the pair's reliefs,
// and its lead gaps at y_j on the two flanks as one pitch and thickness
// deviation on every tooth of gear 1.
Modifications slice_modifications(const SimulationCase& c, int j, int n,
                                  double working_pressure_angle_rad) {
  const double b = c.gears.face_width_m;
  const double y = (j + 0.5) * (b / n);
  const double drive = lead_gap_m(c.modifications, Region::n1, b, working_pressure_angle_rad, y);
  const double coast = lead_gap_m(c.modifications, Region::n2, b, working_pressure_angle_rad, y);
  Modifications m = c.modifications;
  m.gear1.lead = {};
  m.gear2.lead = {};
  m.misalignment = {};
  if (drive != 0.0 || coast != 0.0) {
    // +f pitch is a gap +f on N1 and -f on N2, +f thickness +f on both (modifications.hpp).
    const auto teeth = static_cast<std::size_t>(c.gears.teeth1);
    m.gear1.pitch_m.assign(teeth, 0.5 * (drive - coast));
    m.gear1.thickness_m.assign(teeth, 0.5 * (drive + coast));
  }
  return m;
}

// A sliced mesh's modifications on its helical pair (as the helical STE
// checks them), then each slice's gaps against the play (validate_gaps),
// named as the pair's keys.
void validate_slice_gaps(const SimulationCase& c) {
  validate_modifications(c.gears, c.modifications);
  const int n = c.model.stiffness.face_slices;
  const double alpha_wt = helical_geometry(c.gears).working_pressure_angle_rad;
  SimulationCase slice = c;
  slice.gears = transverse_pair(c.gears);
  for (int j = 0; j < n; ++j) {
    slice.modifications = slice_modifications(c, j, n, alpha_wt);
    validate_gaps(slice);
  }
}

// An internal mesh's pair keys: what it cannot take refused, its geometry
// checked (the problems named under the mesh, the ring as gears.teeth1).
void validate_internal_mesh(const std::string& prefix, const TrainMesh& mesh) {
  const SimulationCase& c = mesh.pair;
  if (!carrier_mesh(mesh)) {
    throw InputError(prefix + "kind", "internal",
                     "external, or an internal mesh in a carrier's frame (carrier >= 0)");
  }
  if (c.gears.profile_shift1 != 0.0 || c.gears.profile_shift2 != 0.0) {
    throw InputError(
        prefix + "gears.profile_shift" + (c.gears.profile_shift1 != 0.0 ? "1" : "2"),
        c.gears.profile_shift1 != 0.0 ? c.gears.profile_shift1 : c.gears.profile_shift2,
        "0: an internal mesh takes unshifted teeth");
  }
  if (c.model.friction_law != FrictionLaw::constant || c.model.friction_coefficient != 0.0) {
    throw InputError(prefix + "model.friction_coefficient", c.model.friction_coefficient,
                     "0 under the constant law: an internal mesh's friction (lever arms on "
                     "one side of the pitch point) is not modelled");
  }
  // A missing tooth takes its pair out; ISO's table has no tooth profile a crack, a spall or a
  // chip could change.
  for (std::size_t i = 0; i < c.faults.size(); ++i) {
    const ToothFault& f = c.faults[i];
    const std::string field = prefix + "faults[" + std::to_string(i) + "].";
    if (f.state.kind != ToothKind::missing) {
      throw InputError(field + "kind", "not missing",
                       "missing: an internal mesh's ISO 6336-1 table has no tooth profile for "
                       "a crack, a spall or a chip to change");
    }
    const int teeth = f.gear == Gear::one ? c.gears.teeth1 : c.gears.teeth2;
    if (f.tooth < 0 || f.tooth >= teeth) {
      throw InputError(field + "tooth", f.tooth,
                       "0 to " + std::to_string(teeth - 1) + ", a tooth of its gear");
    }
  }
  if (!is_unmodified(c.modifications)) {
    throw InputError(prefix + "modifications", "set", "none on an internal mesh");
  }
  try {
    const RingLine ring = ring_line(c);
    if (ring_by_potential_energy(mesh)) {
      check_planet_form_circle(c.gears, ring.geometry);
      // Both ends of the segment on both teeth's flanks (the planet's
      // involute above its form circle), before any table is built.
      for (const double x : {ring.line.start_m, ring.line.end_m}) {
        internal_mesh_stiffness(c.gears, ring.geometry, x, c.model.stiffness);
      }
    }
  } catch (const InputError& e) {
    std::vector<Problem> problems;
    for (const Problem& p : e.problems()) {
      const std::string field = p.field == "ring_teeth"     ? "gears.teeth1"
                                : p.field == "planet_teeth" ? "gears.teeth2"
                                : p.field == "rack_tip_radius_coefficient"
                                    ? "gears.rack_tip_radius_coefficient"
                                    : p.field;
      problems.push_back(p.renamed(prefix + field, p.value));
    }
    throw InputError(std::move(problems));
  }
}

// Which of the train's degrees of freedom each body is: bodies joined by
// rigid shafts are one, numbered in the order of their first body.
std::vector<int> degrees_of_freedom(const GearTrain& train) {
  const std::size_t n = train.bodies.size();
  std::vector<std::size_t> root(n);
  std::iota(root.begin(), root.end(), std::size_t{0});
  const auto find = [&](std::size_t i) {
    while (root[i] != i) i = root[i];
    return i;
  };
  for (const TrainShaft& shaft : train.shafts) {
    if (shaft.kind != TrainShaft::Kind::rigid) continue;
    const std::size_t a = find(static_cast<std::size_t>(shaft.body_a));
    const std::size_t b = find(static_cast<std::size_t>(shaft.body_b));
    root[std::max(a, b)] = std::min(a, b);
  }
  std::vector<int> dof(n, -1);
  int count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = find(i);
    if (dof[r] < 0) dof[r] = count++;
    dof[i] = dof[r];
  }
  return dof;
}

}  // namespace

DriverMotion driven_body_motion(const TrainBody& body, double t) {
  if (body.held) return {body.theta_rad, 0.0, 0.0};
  return driver_motion(body.torque, body.theta_rad, t);
}

int count_dofs(const std::vector<int>& dof) {
  return dof.empty() ? 0 : *std::max_element(dof.begin(), dof.end()) + 1;
}

std::vector<double> dof_inertias(const GearTrain& train, const std::vector<int>& dof, int dofs) {
  std::vector<double> inertia(static_cast<std::size_t>(dofs), 0.0);
  std::vector<bool> seen(static_cast<std::size_t>(dofs), false);
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    const auto d = static_cast<std::size_t>(dof[i]);
    inertia[d] =
        seen[d] ? inertia[d] + train.bodies[i].inertia_kg_m2 : train.bodies[i].inertia_kg_m2;
    seen[d] = true;
  }
  return inertia;
}

namespace {

void check_finite_field(const std::string& field, double value) {
  if (!std::isfinite(value)) throw InputError(field, value, "a finite value");
}

// A body's torque, checked by the rows of [torque1] (a drag by those of
// [torque2], where the two-gear case takes it), its problems named under the
// body: bodies.NAME.torque.KEY.
void validate_torque(const std::string& field, const Torque& t, const SimulationCase& pair) {
  SimulationCase probe = pair;
  const bool drag = t.kind == Torque::Kind::drag;
  (drag ? probe.torque2 : probe.torque1) = t;
  if (!drag) probe.torque2 = Torque{};
  const std::string section = drag ? "torque2." : "torque1.";
  std::vector<Problem> problems;
  try {
    validate_fields(probe);
  } catch (const InputError& e) {
    for (const Problem& p : e.problems()) {
      if (p.field.rfind(section, 0) == 0) {
        problems.push_back(p.renamed(field + "." + p.field.substr(section.size()), p.value));
      }
    }
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  if (t.kind == Torque::Kind::constant || t.kind == Torque::Kind::sinusoidal ||
      t.kind == Torque::Kind::harmonic) {
    check_finite_field(field + ".constant", t.constant_n_m);
    check_finite_field(field + ".mean", t.mean_n_m);
    check_finite_field(field + ".amplitude", t.amplitude_n_m);
    check_finite_field(field + ".angular_frequency", t.angular_frequency_rad_per_s);
    check_finite_field(field + ".phase", t.phase_rad);
  }
}

void validate_body_index(const std::string& field, int body, std::size_t bodies) {
  if (body < 0 || static_cast<std::size_t>(body) >= bodies) {
    throw InputError(field, std::to_string(body),
                     "the index of one of the train's " + std::to_string(bodies) + " bodies");
  }
}

// A train's samples are its sensor's (the planar train's): refused without
// one. A sample's row is about 22 bytes a number as CSV: the time, each
// body's angle, speed and centre's six, each mesh's ten, the sensor's.
void validate_train_sampling(const GearTrain& train, const RunControl& control) {
  if (!control.sample_rate_hz) return;
  if (train.sensor_body < 0) {
    throw InputError(std::vector<Problem>{
        refused_problem("sample_rate", format_number(*control.sample_rate_hz) + " Hz",
                        "a train's samples are its sensor's, and this train has none",
                        "a rate for a train with a sensor: [sensor] body = NAME (a body on "
                        "bearings) in a train file, [bearings] kind = \"elastic\" in a two-gear "
                        "file")});
  }
  const double numbers = 2.0 + 8.0 * static_cast<double>(train.bodies.size()) +
                         10.0 * static_cast<double>(train.meshes.size());
  validate_sampling(train.integrator.end_time_s, 22.0 * numbers, control);
}

// A tacho reads a body of a train on bearings, as the two-gear tacho reads a
// gear of the planar run; at least one pulse a revolution.
void validate_train_tacho(const GearTrain& train) {
  if (train.tacho_body < 0) return;
  if (static_cast<std::size_t>(train.tacho_body) >= train.bodies.size()) {
    throw InputError("tacho_body", std::to_string(train.tacho_body),
                     "a body of the train, or -1: no tacho");
  }
  const std::string body = train.bodies[static_cast<std::size_t>(train.tacho_body)].name;
  if (!has_planar_bodies(train)) {
    throw InputError(std::vector<Problem>{refused_problem(
        "tacho.body", "\"" + body + "\"",
        "a tacho runs with the planar dynamics, as the two-gear planar run's, and no body of "
        "this train has bearings",
        "a tacho in a train with a body on bearings (bodies.NAME.bearings)")});
  }
  if (train.tacho.pulses_per_revolution < 1) {
    throw InputError("tacho.pulses_per_revolution",
                     std::to_string(train.tacho.pulses_per_revolution),
                     "at least 1 with tacho.body = \"" + body + "\"");
  }
}

void validate_train(const GearTrain& train) {
  const std::size_t n = train.bodies.size();
  if (n < 2 || n > static_cast<std::size_t>(kMaxTrainBodies)) {
    throw InputError("bodies", std::to_string(n) + " bodies",
                     "2 to " + std::to_string(kMaxTrainBodies) + " bodies");
  }
  std::vector<std::string> names;
  for (std::size_t i = 0; i < n; ++i) {
    const TrainBody& b = train.bodies[i];
    if (b.name.empty() || std::find(names.begin(), names.end(), b.name) != names.end()) {
      throw InputError("bodies[" + std::to_string(i) + "].name", "\"" + b.name + "\"",
                       "a name no other body has");
    }
    names.push_back(b.name);
    check_train_value("bodies.inertia", b.inertia_kg_m2, "bodies." + b.name + ".inertia");
    check_finite_field("bodies." + b.name + ".theta", b.theta_rad);
    check_finite_field("bodies." + b.name + ".w", b.w_rad_per_s);
    if (b.held && b.w_rad_per_s != 0.0) {
      throw InputError("bodies." + b.name + ".w", b.w_rad_per_s, "0: the body is held");
    }
    if (b.held && (b.torque.kind != Torque::Kind::constant || b.torque.constant_n_m != 0.0)) {
      throw InputError("bodies." + b.name + ".torque.kind", name_of_torque(b.torque),
                       "none (a constant 0): the body is held");
    }
  }
  for (std::size_t i = 0; i < train.shafts.size(); ++i) {
    const TrainShaft& s = train.shafts[i];
    const std::string field = "shafts[" + std::to_string(i) + "]";
    validate_body_index(field + ".body_a", s.body_a, n);
    validate_body_index(field + ".body_b", s.body_b, n);
    if (s.body_a == s.body_b) {
      throw InputError(field + ".body_b", std::to_string(s.body_b), "a body other than body_a");
    }
  }
  const std::vector<int> dof = degrees_of_freedom(train);
  for (std::size_t i = 0; i < train.shafts.size(); ++i) {
    const TrainShaft& s = train.shafts[i];
    if (s.kind != TrainShaft::Kind::torsional) continue;
    const std::string field = "shafts[" + std::to_string(i) + "]";
    check_train_value("shafts.stiffness", s.stiffness_n_m_per_rad, field + ".stiffness");
    if (dof[static_cast<std::size_t>(s.body_a)] == dof[static_cast<std::size_t>(s.body_b)]) {
      throw InputError(field + ".body_b", std::to_string(s.body_b),
                       "a body not joined to body_a by rigid shafts");
    }
  }
  // Bodies on one rigid shaft turn as one: they must start as one.
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (dof[i] != dof[j]) continue;
      const TrainBody& a = train.bodies[j];
      const TrainBody& b = train.bodies[i];
      if (a.theta_rad != b.theta_rad || a.w_rad_per_s != b.w_rad_per_s) {
        throw InputError(
            "bodies." + b.name + ".w",
            format_number(b.w_rad_per_s) + " rad/s, theta " + format_number(b.theta_rad) + " rad",
            "the initial angle and speed of " + a.name + ", to which a rigid shaft joins it");
      }
    }
  }
  const std::size_t m = train.meshes.size();
  if (m < 1 || m > static_cast<std::size_t>(kMaxTrainMeshes)) {
    throw InputError("meshes", std::to_string(m) + " meshes",
                     "1 to " + std::to_string(kMaxTrainMeshes) + " meshes");
  }
  std::vector<std::string> mesh_names;
  int lines = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const TrainMesh& mesh = train.meshes[k];
    if (mesh.name.empty() ||
        std::find(mesh_names.begin(), mesh_names.end(), mesh.name) != mesh_names.end()) {
      throw InputError("meshes[" + std::to_string(k) + "].name", "\"" + mesh.name + "\"",
                       "a name no other mesh has");
    }
    mesh_names.push_back(mesh.name);
    const std::string prefix = "meshes." + mesh.name + ".";
    validate_body_index(prefix + "body_a", mesh.body_a, n);
    validate_body_index(prefix + "body_b", mesh.body_b, n);
    if (dof[static_cast<std::size_t>(mesh.body_a)] == dof[static_cast<std::size_t>(mesh.body_b)]) {
      throw InputError(prefix + "body_b", std::to_string(mesh.body_b),
                       "a body other than body_a, and not on one rigid shaft with it");
    }
    if (carrier_mesh(mesh)) {
      validate_body_index(prefix + "carrier", mesh.carrier, n);
      const int c = dof[static_cast<std::size_t>(mesh.carrier)];
      if (c == dof[static_cast<std::size_t>(mesh.body_a)] ||
          c == dof[static_cast<std::size_t>(mesh.body_b)]) {
        throw InputError(prefix + "carrier", std::to_string(mesh.carrier),
                         "a body other than body_a and body_b, and not on one rigid shaft with "
                         "either");
      }
    } else if (mesh.carrier != -1) {
      throw InputError(prefix + "carrier", std::to_string(mesh.carrier),
                       "-1 (fixed axes) or the index of one of the train's bodies");
    }
    check_finite_field(prefix + "line_offset", mesh.line_offset_m);
    if (helical_mesh(mesh) && carrier_mesh(mesh)) {
      throw InputError(prefix + "gears.helix_angle",
                       format_number(mesh.pair.gears.helix_angle_rad * 180.0 / pi) + " deg",
                       "0 on a mesh in a carrier's frame: a planetary stage's meshes are spur");
    }
    const bool sliced = runs_by_slices(mesh);
    if (sliced) validate_sliced_mesh(prefix, mesh, train.integrator);
    if (carrier_mesh(mesh) && mesh.pair.model.mesh_force == MeshForce::lagrangian) {
      // Its stored energy's jumps would be paid from one gear's absolute
      // speed, which would break the stage's angular momentum.
      throw InputError(prefix + "model.mesh_force", "lagrangian",
                       "newtonian on a mesh in a carrier's frame");
    }
    if (internal_mesh(mesh)) {
      validate_internal_mesh(prefix, mesh);
      const InternalLine line = ring_line(mesh.pair).line;
      if (mesh.table && !(mesh.table->domain_start_m() <= line.start_m &&
                          mesh.table->domain_end_m() >= line.end_m)) {
        throw InputError(prefix + "table",
                         "[" + format_number(mesh.table->domain_start_m()) + ", " +
                             format_number(mesh.table->domain_end_m()) + "] m",
                         "a table covering the internal mesh's segment [" +
                             format_number(line.start_m) + ", " + format_number(line.end_m) +
                             "] m");
      }
    }
    try {
      // An internal mesh's pair is checked as the planet's with its twin
      // (its model's keys); its ring's geometry is validate_internal_mesh's.
      SimulationCase twin;
      if (internal_mesh(mesh)) {
        twin = mesh.pair;
        twin.gears = planet_twin(mesh.pair.gears);
        // Its missing teeth, the ring's among them, are validate_internal_mesh's.
        twin.faults.clear();
      }
      // A helical mesh run by slices: its pair's checks without the
      // modifications (which the slices take), then each slice's gaps
      // against the play (validate_gaps), named as the pair's.
      SimulationCase plain;
      if (sliced) {
        plain = mesh.pair;
        plain.modifications = Modifications{};
      }
      validate(internal_mesh(mesh) ? twin : sliced ? plain : mesh.pair);
      // A helical mesh's friction as the two-gear run takes it (either route).
      refuse_helical_friction(mesh.pair);
      if (sliced) validate_slice_gaps(mesh.pair);
      // A helical pair's table is its transverse section's (dynamics_case).
      if (mesh.table && !internal_mesh(mesh)) check_table(dynamics_case(mesh.pair), *mesh.table);
    } catch (const InputError& e) {
      // The pair's keys, addressed by the mesh's name.
      std::vector<Problem> problems;
      for (const Problem& p : e.problems()) {
        problems.push_back(p.renamed(prefix + p.field, p.value));
      }
      throw InputError(std::move(problems));
    }
    if (mesh.pair.bearings.kind != BearingKind::rigid) {
      throw InputError(prefix + "bearings.kind", "elastic",
                       "rigid: a train's bearings are its bodies' (bodies.NAME.bearings)");
    }
    lines += line_count(mesh);
    if (lines > kMaxTrainLines) {
      throw InputError(prefix + "model.face_slices",
                       std::to_string(mesh.pair.model.stiffness.face_slices),
                       "at most " + std::to_string(kMaxTrainLines - (lines - line_count(mesh))) +
                           ": a train's run holds at most " + std::to_string(kMaxTrainLines) +
                           " lines, a helical mesh run by slices one per slice");
    }
  }
  // The bodies' torques, once the meshes' pairs (whose rows check them) are valid.
  std::vector<int> driven(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const TrainBody& b = train.bodies[i];
    const std::string field = "bodies." + b.name + ".torque";
    validate_torque(field, b.torque, train.meshes.front().pair);
    if (kinematic_driver(b.torque)) {
      // The driver sets the body's speed at t = 0; a different w would be ignored.
      const double w0 = driver_speed_at(b.torque, 0.0);
      if (std::fabs(b.w_rad_per_s - w0) > 1e-9 * std::fabs(w0)) {
        throw InputError("bodies." + b.name + ".w", format_number(b.w_rad_per_s) + " rad/s",
                         "the driver's speed at t = 0, " + format_number(w0) +
                             " rad/s (to 1e-9 of it), as its torque.kind = \"prescribed-speed\" "
                             "prescribes it");
      }
    }
    if (b.torque.kind == Torque::Kind::speed_controlled &&
        std::any_of(train.meshes.begin(), train.meshes.end(), carrier_mesh)) {
      throw InputError(field + ".kind", name_of_torque(b.torque),
                       "a torque other than speed-controlled in a train with a carrier's "
                       "meshes (the controller's reflected inertia assumes fixed axes)");
    }
    if (!kinematic_driver(b.torque) && b.torque.kind != Torque::Kind::speed_controlled && !b.held) {
      continue;
    }
    // One body's motion is prescribed, or followed by a controller, on a shaft.
    int& first = driven[static_cast<std::size_t>(dof[i])];
    if (first >= 0) {
      throw InputError(b.held ? "bodies." + b.name + ".held" : field + ".kind",
                       b.held ? "true" : name_of_torque(b.torque),
                       std::string(b.held ? "a body neither held, driven nor speed-controlled: "
                                          : "a torque that is neither a driver nor a speed "
                                            "controller: ") +
                           train.bodies[static_cast<std::size_t>(first)].name +
                           ", on one rigid shaft with it, is driven already");
    }
    first = static_cast<int>(i);
  }
  validate(train.integrator);
  if (has_planar_bodies(train)) {
    validate_planar_train(train);
  } else if (train.sensor_body != -1) {
    // The sensor sits on a bearing: without one it would read nothing.
    throw InputError("sensor_body", std::to_string(train.sensor_body),
                     "-1 (none) in a train without bodies on elastic bearings");
  }
  if (train.integrator.kind == IntegratorKind::adaptive &&
      std::any_of(train.meshes.begin(), train.meshes.end(), internal_mesh)) {
    throw InputError("integrator.kind", "adaptive",
                     "a fixed-step integrator (rk4): the adaptive step bound is an external "
                     "pair's, and a train with an internal mesh has none yet");
  }
}

// The train as a system of the run loop (the concept of step_methods.hpp).
template <class L>
class TrainSystem {
 public:
  GEARIMPACT_TRAIN_LAYOUT_NAMES
  using StateType = TrainState;
  using ModeType = TrainMode;
  using MemoryType = TrainMemory;
  using EventsType = TrainEvents;
  using ForcesType = TrainForces;
  static constexpr std::size_t kLedgerStart = kLedger;

  TrainSystem(const GearTrain& train, const std::vector<const StiffnessTable*>& tables)
      : train_(train), body_dof_(degrees_of_freedom(train)) {
    const int dofs = count_dofs(body_dof_);
    dofs_ = static_cast<std::size_t>(dofs);
    const std::vector<double> inertia = dof_inertias(train, body_dof_, dofs);
    std::copy(inertia.begin(), inertia.end(), inertia_.begin());
    driver_.fill(-1);
    for (std::size_t i = 0; i < train.bodies.size(); ++i) {
      const TrainBody& b = train.bodies[i];
      if (kinematic_driver(b.torque) || b.held) {
        driver_[static_cast<std::size_t>(body_dof_[i])] = static_cast<int>(i);
      }
    }
    for (std::size_t k = 0; k < train.meshes.size(); ++k) {
      const TrainMesh& m = train.meshes[k];
      if (!carrier_mesh(m)) {
        Frame fixed;
        fixed.a = dof_of(m.body_a);
        fixed.b = dof_of(m.body_b);
        // The pairs move by line_offset along the line (a helical slice's
        // share of b tan(beta_b)); s is kept.
        if (m.line_offset_m != 0.0) {
          fixed.offset_a = m.line_offset_m / base_radius(m.pair.gears, Gear::one);
          fixed.offset_b = m.line_offset_m / base_radius(m.pair.gears, Gear::two);
          fixed.shifted = true;
        }
        frame_.push_back(fixed);
        // The viscous damper's m_e: that of the two bodies as they turn in the
        // train (a rigid shaft's bodies together), 1/m_e = Rb_a^2/J_a + Rb_b^2/J_b.
        const double mass = effective_mass_kg(
            base_radius(m.pair.gears, Gear::one), inertia_[static_cast<std::size_t>(fixed.a)],
            base_radius(m.pair.gears, Gear::two), inertia_[static_cast<std::size_t>(fixed.b)]);
        meshes_.emplace_back(m.pair, *tables[k], mass, m.teeth);
        continue;
      }
      // In the carrier's frame, angles about +z. The line's gear 1 turns
      // forward when it drives: an external mesh's sun counter-clockwise and
      // its planet clockwise (sense -1); an internal mesh's gear 1 is the
      // planet and its gear 2 the ring, both clockwise (sense -1), so that
      // the line's s = Rb_1 theta_1' - Rb_2 theta_2' is docs/planetary.md's
      // Rb_a (theta_a - theta_c) + kappa Rb_b (theta_b - theta_c) either way.
      const bool internal = internal_mesh(m);
      const int one = dof_of(internal ? m.body_b : m.body_a);
      const int two = dof_of(internal ? m.body_a : m.body_b);
      Frame f;
      f.a = one;
      f.b = two;
      f.carrier = dof_of(m.carrier);
      f.sense_a = internal ? -1.0 : 1.0;
      f.sense_b = -1.0;
      const RingLine ring = internal ? ring_line(m, *tables[k]) : RingLine{};
      const double rb1 =
          internal ? ring.line.planet_base_radius_m : base_radius(m.pair.gears, Gear::one);
      const double rb2 =
          internal ? ring.line.ring_base_radius_m : base_radius(m.pair.gears, Gear::two);
      // The pairs move by line_offset along the line; s is kept.
      f.offset_a = m.line_offset_m / rb1;
      f.offset_b = m.line_offset_m / rb2;
      // 1/m_e of s: each free body's lever squared over its inertia, the
      // carrier's lever Rb_2 sense_b - Rb_1 sense_a.
      const auto lever = [&](int dof, double r) {
        return driven(dof) ? 0.0 : r * r / inertia_[static_cast<std::size_t>(dof)];
      };
      const double inverse_mass =
          lever(one, rb1) + lever(two, rb2) + lever(f.carrier, rb2 * f.sense_b - rb1 * f.sense_a);
      const double mass = inverse_mass > 0.0 ? 1.0 / inverse_mass : 1.0;
      frame_.push_back(f);
      if (internal) {
        meshes_.emplace_back(m.pair, *tables[k], ring.line, mass);
      } else {
        meshes_.emplace_back(m.pair, *tables[k], mass);
      }
    }
    for (const TrainShaft& s : train.shafts) {
      if (s.kind != TrainShaft::Kind::torsional) continue;
      springs_.push_back({dof_of(s.body_a), dof_of(s.body_b), s.stiffness_n_m_per_rad});
    }
    for (std::size_t i = 0; i < train.bodies.size(); ++i) {
      const TrainBody& b = train.bodies[i];
      if (kinematic_driver(b.torque) || b.held) {
        driven_ = true;
      } else if (b.torque.kind == Torque::Kind::speed_controlled) {
        controllers_.push_back(
            {static_cast<int>(i), train_speed_controller(train, static_cast<int>(i))});
      }
    }
    // Torques that depend on neither time nor state (constants, and the
    // kinematic drivers' 0) are summed once here, as torques() sums them.
    fixed_torques_ = std::all_of(train.bodies.begin(), train.bodies.end(), [](const TrainBody& b) {
      return b.torque.kind == Torque::Kind::constant || kinematic_driver(b.torque);
    });
    if (fixed_torques_) fixed_torque_ = summed_torques(0.0, TrainState{});
    mesh_count_ = meshes_.size();
  }

  int dof_of(int body) const { return body_dof_[static_cast<std::size_t>(body)]; }
  double inertia_of_dof(int dof) const { return inertia_[static_cast<std::size_t>(dof)]; }
  std::size_t mesh_count() const { return mesh_count_; }
  const MeshLine& mesh(std::size_t k) const { return meshes_[k]; }
  int mesh_a(std::size_t k) const { return frame_[k].a; }
  [[gnu::always_inline]] MeshMotion motion(std::size_t k, const TrainState& y) const {
    const Frame& f = frame_[k];
    const int a = f.a;
    const int b = f.b;
    if (!L::kCarriers || f.carrier < 0) {
      if (f.shifted) {
        return {y[theta_of(a)] + f.offset_a, y[theta_of(b)] + f.offset_b, y[w_of(a)], y[w_of(b)]};
      }
      return {y[theta_of(a)], y[theta_of(b)], y[w_of(a)], y[w_of(b)]};
    }
    const double theta_c = y[theta_of(f.carrier)];
    const double w_c = y[w_of(f.carrier)];
    return {f.sense_a * (y[theta_of(a)] - theta_c) + f.offset_a,
            f.sense_b * (y[theta_of(b)] - theta_c) + f.offset_b, f.sense_a * (y[w_of(a)] - w_c),
            f.sense_b * (y[w_of(b)] - w_c)};
  }
  // Whether a kinematic driver holds the degree of freedom's motion.
  bool driven(int dof) const { return driver_[static_cast<std::size_t>(dof)] >= 0; }

  // A prescribed-speed body's closed form (driver_motion from its initial
  // angle) written into y at time t, as the two-gear system writes its pinion's;
  // with `acceleration`, each driven degree of freedom's acceleration there
  // (0 for a held body).
  void impose_driver(double t, TrainState& y,
                     std::array<double, kBodies>* acceleration = nullptr) const {
    if (!driven_) return;
    for (int d = 0; d < static_cast<int>(dofs_); ++d) {
      const int body = driver_[static_cast<std::size_t>(d)];
      if (body < 0) continue;
      const DriverMotion m = driven_body_motion(train_.bodies[static_cast<std::size_t>(body)], t);
      y[theta_of(d)] = m.theta_rad;
      y[w_of(d)] = m.speed_rad_per_s;
      if (acceleration != nullptr)
        (*acceleration)[static_cast<std::size_t>(d)] = m.acceleration_rad_per_s2;
    }
  }

  // The applied torque on each degree of freedom at (t, y): its bodies'
  // summed, a drag's and a motor's from its speed, a controller's from its
  // angle and speed; a kinematic driver's is set by rhs against the rest.
  std::array<double, kBodies> torques(double t, const TrainState& y) const {
    return fixed_torques_ ? fixed_torque_ : summed_torques(t, y);
  }
  std::array<double, kBodies> summed_torques(double t, const TrainState& y) const {
    std::array<double, kBodies> torque{};
    std::array<bool, kBodies> seen{};
    for (std::size_t i = 0; i < train_.bodies.size(); ++i) {
      const auto d = static_cast<std::size_t>(body_dof_[i]);
      const double value = body_torque(static_cast<int>(i), t, y);
      torque[d] = seen[d] ? torque[d] + value : value;
      seen[d] = true;
    }
    return torque;
  }

  // (1)-(3), (43)-(45) of each mesh on its two bodies, the shafts' springs,
  // J w' = the sum of the moments on each body; the ledger's powers.
  // Flattened: every call inside is inlined (the tables' Ke reads among
  // them, which the compiler left out of line here and inlined in the
  // two-gear model's right-hand side), the same arithmetic in fewer
  // instructions.
  [[gnu::flatten]] void rhs(double t, const TrainState& y_in, const TrainMode& m,
                            const TrainMemory& d, TrainState& dydt,
                            TrainForces* forces = nullptr) const {
    // A driven body is where its closed form puts it, whatever the stage
    // state; its acceleration, from the same closed form, is kept for below.
    TrainState driven_state;
    std::array<double, kBodies> acceleration{};
    if (driven_) {
      driven_state = y_in;
      impose_driver(t, driven_state, &acceleration);
    }
    const TrainState& y = driven_ ? driven_state : y_in;
    std::array<double, kBodies> torque = torques(t, y);
    std::array<double, kBodies> moment = torque;
    MeshPowers powers;
    for (std::size_t k = 0; k < L::kMeshes && k < mesh_count_; ++k) {
      const MeshPowers before = powers;
      const Frame& f = frame_[k];
      if (!L::kCarriers || f.carrier < 0) {
        meshes_[k].add_forces(motion(k, y), m.mesh[k], d.mesh[k],
                              moment[static_cast<std::size_t>(f.a)],
                              moment[static_cast<std::size_t>(f.b)], powers,
                              forces != nullptr ? &forces->mesh[k] : nullptr);
      } else {
        // The line's moments in its gears' senses, about +z on the bodies;
        // the carrier that holds both centres takes minus their sum.
        double moment_a = 0.0;
        double moment_b = 0.0;
        meshes_[k].add_forces(motion(k, y), m.mesh[k], d.mesh[k], moment_a, moment_b, powers,
                              forces != nullptr ? &forces->mesh[k] : nullptr);
        moment[static_cast<std::size_t>(f.a)] += f.sense_a * moment_a;
        moment[static_cast<std::size_t>(f.b)] += f.sense_b * moment_b;
        moment[static_cast<std::size_t>(f.carrier)] -= f.sense_a * moment_a + f.sense_b * moment_b;
      }
      if constexpr (L::kOwnLosses) {
        // Each mesh's own powers: what it added to the train's, which keep their order of addition.
        dydt[mesh_loss_of(k, kMeshDampingLoss)] = powers.damping_w - before.damping_w;
        dydt[mesh_loss_of(k, kMeshFrictionLoss)] = powers.friction_w - before.friction_w;
        dydt[mesh_loss_of(k, kMeshDamperLoss)] = powers.mesh_damping_w - before.mesh_damping_w;
      } else {
        static_cast<void>(before);
      }
    }
    for (const Spring& s : springs_) {
      // The shaft twisted by theta_a - theta_b pulls b forward and a back.
      const double torque_on_b = s.stiffness * (y[theta_of(s.a)] - y[theta_of(s.b)]);
      moment[static_cast<std::size_t>(s.a)] -= torque_on_b;
      moment[static_cast<std::size_t>(s.b)] += torque_on_b;
    }
    if (driven_) {
      for (std::size_t u = 0; u < kBodies && u < dofs_; ++u) {
        if (driver_[u] < 0) continue;
        // The driver applies the torque that gives its body the prescribed
        // acceleration against the rest: J w' = T_driver + moment. Its work is
        // the ledger's torque work.
        const double driver = inertia_[u] * acceleration[u] - moment[u];
        moment[u] += driver;
        torque[u] += driver;
      }
    }
    double work = torque[0] * y[w_of(0)];
    for (std::size_t u = 0; u < kBodies && u < dofs_; ++u) {
      const auto i = static_cast<int>(u);
      dydt[theta_of(i)] = y[w_of(i)];
      dydt[w_of(i)] = moment[u] / inertia_[u];
      if (i > 0) work += torque[u] * y[w_of(i)];
    }
    dydt[kLedger + kWork] = work;
    dydt[kLedger + kDamping] = powers.damping_w;
    dydt[kLedger + kFriction] = powers.friction_w;
    dydt[kLedger + kParametric] = powers.parametric_w;
    dydt[kLedger + kMeshDamping] = powers.mesh_damping_w;
    // The layout's places beyond the train's degrees of freedom and meshes.
    for (std::size_t i = dofs_; i < kBodies; ++i) {
      dydt[theta_of(static_cast<int>(i))] = 0.0;
      dydt[w_of(static_cast<int>(i))] = 0.0;
    }
    if constexpr (L::kOwnLosses) {
      std::fill(dydt.begin() +
                    static_cast<std::ptrdiff_t>(mesh_loss_of(meshes_.size(), kMeshDampingLoss)),
                dydt.end(), 0.0);
    }
  }

  int event_values(const TrainState& y, const TrainMode& m, const TrainMemory& d,
                   TrainEvents& g) const {
    int n = 0;
    for (std::size_t k = 0; k < L::kMeshes && k < mesh_count_; ++k) {
      n += meshes_[k].event_values(motion(k, y), m.mesh[k], d.mesh[k],
                                   g.data() + static_cast<std::size_t>(n));
    }
    return n;
  }
  bool mode_holds(const TrainState& y, const TrainMode& m, const TrainMemory& d) const {
    TrainEvents g;
    const int n = event_values(y, m, d, g);
    for (int i = 0; i < n; ++i) {
      if (g[static_cast<std::size_t>(i)] < 0.0) return false;
    }
    return true;
  }

  double kinetic_energy(const TrainState& y) const {
    double e = 0.5 * inertia_[0] * y[w_of(0)] * y[w_of(0)];
    for (std::size_t u = 1; u < kBodies && u < dofs_; ++u) {
      const std::size_t w = w_of(static_cast<int>(u));
      e += 0.5 * inertia_[u] * y[w] * y[w];
    }
    return e;
  }
  // The meshes' stored energy by term, and the shafts' springs' 1/2 k twist^2.
  ElasticEnergy stored_energy(const TrainState& y, const TrainMode& m) const {
    ElasticEnergy u = meshes_[0].stored_energy(motion(0, y), m.mesh[0]);
    for (std::size_t k = 1; k < L::kMeshes && k < mesh_count_; ++k) {
      const ElasticEnergy e = meshes_[k].stored_energy(motion(k, y), m.mesh[k]);
      for (std::size_t i = 0; i < kTermCount; ++i) u.j[i] += e.j[i];
    }
    return u;
  }
  double shaft_energy_j(const TrainState& y) const {
    double e = 0.0;
    for (const Spring& s : springs_) {
      const double twist = y[theta_of(s.a)] - y[theta_of(s.b)];
      e += 0.5 * s.stiffness * twist * twist;
    }
    return e;
  }

 private:
  struct Spring {
    int a;
    int b;
    double stiffness;
  };
  // Body i's applied torque at (t, y); 0 for a kinematic driver (rhs sets it).
  double body_torque(int i, double t, const TrainState& y) const {
    const Torque& torque = train_.bodies[static_cast<std::size_t>(i)].torque;
    const std::size_t d = w_of(dof_of(i));
    switch (torque.kind) {
      case Torque::Kind::prescribed_speed:
        return 0.0;
      case Torque::Kind::drag:
        return drag_torque_n_m(torque, y[d]);
      case Torque::Kind::induction_motor:
        return induction_motor_torque_n_m(torque, y[d]);
      case Torque::Kind::speed_controlled:
        for (const Controlled& c : controllers_) {
          if (c.body == i) return c.controller->torque_n_m(t, y[theta_of(dof_of(i))], y[d]);
        }
        break;
      default:
        break;
    }
    return torque_at(torque, t);
  }

  struct Controlled {
    int body;
    std::shared_ptr<const SpeedController> controller;
  };
  // A mesh's place in the train: the degrees of freedom of its line's gears
  // 1 and 2 (a and b), its carrier's (-1: fixed axes), the gears' senses
  // about +z and their angle offsets in the line. One record a mesh, so that
  // a right-hand side reads one array for all of them.
  struct Frame {
    int a = 0;
    int b = 0;
    int carrier = -1;
    double sense_a = 1.0;
    double sense_b = 1.0;
    double offset_a = 0.0;
    double offset_b = 0.0;
    bool shifted = false;  // a mesh between fixed axes with a line offset
  };
  const GearTrain& train_;
  std::vector<int> body_dof_;
  // The degrees of freedom's count, read by the hot loops with the layout's
  // bound beside it, so that a small layout's loops unroll.
  std::size_t dofs_ = 0;
  std::array<double, kBodies> inertia_{};
  std::vector<MeshLine> meshes_;
  std::vector<Frame> frame_;
  // The meshes' count again (meshes_.size()), read by the hot loops with the
  // layout's bound beside it, so that a small layout's loops unroll.
  std::size_t mesh_count_ = 0;
  std::vector<Spring> springs_;
  // Per degree of freedom, the body whose kinematic driver holds it (-1: none).
  std::array<int, kBodies> driver_{};
  bool driven_ = false;
  std::vector<Controlled> controllers_;
  // Whether every body's torque is fixed (a constant, or a driver's 0), and their sums then.
  bool fixed_torques_ = false;
  std::array<double, kBodies> fixed_torque_{};
};

// The train's run: the books of run_fixed_grid (step_methods.hpp), as the
// torsional Run (run.hpp) keeps them, for each mesh.
template <class L>
class TrainRun {
 public:
  GEARIMPACT_TRAIN_LAYOUT_NAMES
  using System = TrainSystem<L>;
  static constexpr bool kCountsCutStep = false;

  TrainRun(const GearTrain& train, const std::vector<const StiffnessTable*>& tables,
           const RunControl& control)
      : train_(train),
        control_(control),
        system_(train, tables),
        stall_(train.integrator.step_s, least_smoothing(train)),
        impacts_(train.meshes.size()),
        ledger_(make_ledger()),
        drift_(train.bodies.front().torque, train.drive.settle_s, 0.0,
               train.bodies.front().theta_rad, train.bodies.front().w_rad_per_s) {
    book_keep(0.0);
    if (records()) record(0.0);
  }

  const System& system() const { return system_; }
  TrainState& y() { return y_; }
  const TrainMode& mode() const { return mode_; }
  const TrainMemory& damping() const { return damping_; }
  long long& steps() { return result_.summary.steps; }
  long long& rhs_evaluations() { return result_.summary.rhs_evaluations; }
  double start_time() const { return 0.0; }
  long long grid_steps() const {
    return static_cast<long long>(
        std::ceil(train_.integrator.end_time_s / train_.integrator.step_s * (1.0 - 1e-12)));
  }
  bool wants_dense() const { return false; }
  bool records() const { return control_.keep_series || static_cast<bool>(control_.on_train_row); }
  bool sampling() const { return false; }
  const TrainState& first_stage(double t) {
    system_.rhs(t, y_, mode_, damping_, k1_);
    ++result_.summary.rhs_evaluations;
    return k1_;
  }
  template <typename StateAt>
  void emit_samples(double, const TrainState&, const TrainMode&, StateAt) {}
  template <typename Dense>
  void observe_step(double, const TrainState&, double, const TrainState&, const Dense&) {}
  void check_finite(double t, const TrainState& y) const {
    check_finite_state(t, result_.summary.steps, y);
  }
  void poll_stop(double t) const { poll_stop_request(control_, result_.summary.steps, t); }

  // As Run::check_progress, each mesh's friction signs on their own.
  bool check_progress(double t_from, double t_to, bool event) {
    bool changed = false;
    for (std::size_t k = 0; k < L::kMeshes && k < system_.mesh_count(); ++k) {
      changed = classify_stage_signs(event, mode_.mesh[k],
                                     [&](Mode& m) {
                                       system_.mesh(k).classify_forces(system_.motion(k, y_),
                                                                       damping_.mesh[k], m);
                                     }) ||
                changed;
    }
    if (stall_.after_step(event, t_from, t_to,
                          [&] { return where(t_from, result_.summary.steps); })) {
      for (std::size_t k = 0; k < system_.mesh_count(); ++k) {
        changed = take_stage_signs(mode_.mesh[k]) || changed;
      }
    }
    return changed;
  }

  // The mode changed at (t, y_): each mesh classified again as Run::change_mode
  // classifies its one, impacts and the stored energy's jumps booked (under
  // the Lagrangian mesh force paid by the mesh's body a).
  void change_mode(double t) {
    ++result_.summary.events;
    for (std::size_t k = 0; k < system_.mesh_count(); ++k) {
      const MeshLine& mesh = system_.mesh(k);
      const Mode old = mode_.mesh[k];
      const Mode next = mesh.classify_geometry(system_.motion(k, y_));
      if (old.region != Region::free && next.region != old.region) {
        impacts_[k].end(old.region, t, -line_sign(old.region) * mesh.s_rate(system_.motion(k, y_)));
      }
      const double before = mesh.stored_energy(system_.motion(k, y_), old).total_j();
      mode_.mesh[k] = next;
      const double after = mesh.stored_energy(system_.motion(k, y_), next).total_j();
      if (mesh.lagrangian()) pay_stored_energy_jump(k, t, old, before, after);
      // The motion after the jump is paid, as Run's contact begins from it.
      const MeshMotion q = system_.motion(k, y_);
      if (old.region != next.region && next.region != Region::free) begin_contact(k, t);
      Mode& now = mode_.mesh[k];
      mesh.classify_forces(q, damping_.mesh[k], now);
      if (next.region == old.region) now = mesh.carry_pair_signs(q, old, now, damping_.mesh[k]);
      // Stored energy appears or vanishes with a pair entering or leaving
      // under load: work of the time-varying stiffness.
      if (!mesh.lagrangian()) ledger_.mode_changed(before, after);
    }
  }

  void book_keep(double t) {
    SimulationSummary& s = result_.summary;
    drift_.observe(t, y_[theta_of(system_.dof_of(0))]);
    ledger_.observe(y_, mode_, s);
    for (std::size_t k = 0; k < L::kMeshes && k < system_.mesh_count(); ++k) {
      const Mode& m = mode_.mesh[k];
      if (m.region == Region::free) continue;
      TrainMeshSummary& mesh = result_.meshes[k];
      mesh.max_penetration_m =
          std::max(mesh.max_penetration_m, system_.mesh(k).delta(m.region, system_.motion(k, y_)));
      if (mesh.max_penetration_m > half_base_pitch_m_[k]) {
        throw SimulationError("the teeth of mesh " + train_.meshes[k].name + " overlap by " +
                              format_number(mesh.max_penetration_m) +
                              " m on the line of action at " + where(t, s.steps) +
                              ", more than half a base pitch (" +
                              format_number(half_base_pitch_m_[k]) +
                              " m): the model's contact on the line of action no longer holds");
      }
    }
  }

  void record(double t) { record(t, y_, mode_); }
  void record(double t, const TrainState& y, const TrainMode& mode) {
    TrainForces forces;
    TrainState dydt{};
    system_.rhs(t, y, mode, damping_, dydt, &forces);
    TrainRow row;
    row.t_s = t;
    // One allocation per list: growing them by push_back reallocated each (a profile of the
    // paper's case 1 as a train: 28 % of the run's instructions in those reallocations).
    row.theta_rad.reserve(train_.bodies.size());
    row.w_rad_per_s.reserve(train_.bodies.size());
    row.meshes.reserve(system_.mesh_count());
    for (std::size_t i = 0; i < train_.bodies.size(); ++i) {
      const int d = system_.dof_of(static_cast<int>(i));
      row.theta_rad.push_back(y[theta_of(d)]);
      row.w_rad_per_s.push_back(y[w_of(d)]);
    }
    for (std::size_t k = 0; k < system_.mesh_count(); ++k) {
      const Mode& m = mode.mesh[k];
      const MeshMotion q = system_.motion(k, y);
      const MeshLine& mesh = system_.mesh(k);
      TrainMeshRow own;
      own.s_m = mesh.s(q);
      own.delta_m = m.region == Region::free ? 0.0 : mesh.delta(m.region, q);
      own.region = static_cast<int>(m.region);
      own.pairs = m.count;
      own.normal_force_n = forces.mesh[k].normal_force_n;
      own.friction_force_n = forces.mesh[k].friction_force_n;
      row.meshes.push_back(own);
    }
    if (control_.on_train_row) control_.on_train_row(row);
    if (control_.keep_series) result_.series.push_back(std::move(row));
  }

  TrainResult finish(double t, const char* integrator) {
    SimulationSummary& s = result_.summary;
    s.integrator = integrator;
    s.end_time_s = t;
    s.step_s = train_.integrator.step_s;
    ledger_.finish(y_, mode_, s);
    s.mesh_damper = std::any_of(train_.meshes.begin(), train_.meshes.end(), [](const TrainMesh& m) {
      return m.pair.model.mesh_damping_ratio > 0.0;
    });
    bool lagrangian = false;
    for (std::size_t k = 0; k < system_.mesh_count(); ++k) {
      lagrangian = lagrangian || system_.mesh(k).lagrangian();
    }
    if (lagrangian) s.stored_energy_jumps_j = stored_energy_jumps_;
    s.speed_drift_max_rel = drift_.max_relative_drift();
    s.final_w1_rad_per_s = y_[w_of(system_.dof_of(0))];
    s.final_w2_rad_per_s = y_[w_of(system_.dof_of(1))];
    for (std::size_t k = 0; k < system_.mesh_count(); ++k) {
      TrainMeshSummary& mesh = result_.meshes[k];
      mesh.damping_loss_j = y_[mesh_loss_of(k, kMeshDampingLoss)];
      mesh.friction_loss_j = y_[mesh_loss_of(k, kMeshFrictionLoss)];
      mesh.mesh_damping_loss_j = y_[mesh_loss_of(k, kMeshDamperLoss)];
      mesh.impacts = static_cast<int>(impacts_[k].records().size());
      result_.impacts.push_back(impacts_[k].take());
    }
    result_.bodies.resize(train_.bodies.size());
    for (std::size_t i = 0; i < train_.bodies.size(); ++i) {
      result_.bodies[i].final_w_rad_per_s = y_[w_of(system_.dof_of(static_cast<int>(i)))];
    }
    return std::move(result_);
  }

 private:
  // The stall watch's exact switch: a train whose meshes all smooth the sign has none.
  static double least_smoothing(const GearTrain& train) {
    double least = train.meshes.front().pair.model.friction_smoothing_speed_m_s;
    for (const TrainMesh& m : train.meshes) {
      least = std::min(least, m.pair.model.friction_smoothing_speed_m_s);
    }
    return least;
  }

  // The start: the bodies' initial state at t = 0, a driver's closed form on
  // its body, each mesh classified (a contact there counts as an impact).
  EnergyLedgerOf<System> make_ledger() {
    result_.meshes.resize(train_.meshes.size());
    for (const TrainMesh& m : train_.meshes) {
      half_base_pitch_m_.push_back(0.5 * base_pitch(m.pair.gears));
    }
    for (std::size_t i = 0; i < train_.bodies.size(); ++i) {
      const int d = system_.dof_of(static_cast<int>(i));
      y_[theta_of(d)] = train_.bodies[i].theta_rad;
      y_[w_of(d)] = train_.bodies[i].w_rad_per_s;
    }
    system_.impose_driver(0.0, y_);
    for (std::size_t k = 0; k < system_.mesh_count(); ++k) {
      const MeshMotion q = system_.motion(k, y_);
      mode_.mesh[k] = system_.mesh(k).classify_geometry(q);
      if (mode_.mesh[k].region != Region::free) begin_contact(k, 0.0);
      system_.mesh(k).classify_forces(q, damping_.mesh[k], mode_.mesh[k]);
    }
    return EnergyLedgerOf<System>(system_, y_, mode_, result_.summary);
  }

  // The Lagrangian mesh force of mesh k: its stored energy jumps by
  // after - before where a pair enters or leaves, at fixed angles, and its
  // body a (whose angle places the pairs) pays it as the two-gear pinion does
  // (pinion_speed_after_jump); a kinematic driver pays it as work.
  void pay_stored_energy_jump(std::size_t k, double t, const Mode& old, double before,
                              double after) {
    const double jump = after - before;
    if (jump == 0.0) return;
    stored_energy_jumps_ += std::fabs(jump);
    const int a = system_.mesh_a(k);
    if (system_.driven(a)) {
      y_[kLedger + kWork] += jump;
      return;
    }
    const double j = system_.inertia_of_dof(a);
    const double w = y_[w_of(a)];
    const bool pays = jump <= 0.5 * j * w * w;
    std::string change;
    if (!pays) {
      const MeshMotion q = system_.motion(k, y_);
      change = "mesh " + train_.meshes[k].name + ": " +
               pair_change_text(old, mode_.mesh[k], [&](const Mode& m, int i) {
                 return system_.mesh(k).pair_position(m, q, i);
               });
    }
    y_[w_of(a)] = pinion_speed_after_jump(jump, j, w, where(t, result_.summary.steps), change);
  }

  // A contact of mesh k begins at (t, y_): its damping from the approach speed, an impact booked.
  void begin_contact(std::size_t k, double t) {
    const MeshLine::Onset onset =
        system_.mesh(k).damping_at_onset(system_.motion(k, y_), mode_.mesh[k]);
    damping_.mesh[k] = onset.damping;
    impacts_[k].begin(mode_.mesh[k].region, t, onset.impact_speed_m_s, onset.restitution,
                      result_.summary);
  }

  const GearTrain& train_;
  const RunControl& control_;
  System system_;
  StallWatch stall_;
  std::vector<double> half_base_pitch_m_;
  TrainState y_{};
  TrainState k1_{};
  TrainMode mode_;
  TrainMemory damping_;
  TrainResult result_;
  // Each mesh's contacts (their counts and first and last times the train's summary's).
  std::vector<ImpactBook> impacts_;
  // After the state above: its construction sets it (make_ledger).
  EnergyLedgerOf<System> ledger_;
  SpeedDriftMonitor drift_;  // of the first body
  // Under the Lagrangian mesh force: the sum of |dU| of the jumps paid.
  double stored_energy_jumps_ = 0.0;
};

// The adaptive integrator's largest step: that of the stiffest contact of
// any mesh (largest_resolving_step_s of its pair, whose period scales with
// sqrt(m_e)), with m_e of the mesh's two bodies as they turn in the train.
double largest_resolving_step_s(const GearTrain& train) {
  const std::vector<int> dof = degrees_of_freedom(train);
  const std::vector<double> inertia = dof_inertias(train, dof, count_dofs(dof));
  double largest = 0.0;
  for (std::size_t k = 0; k < train.meshes.size(); ++k) {
    const TrainMesh& m = train.meshes[k];
    const GearPair& g = m.pair.gears;
    const double own = inverse_effective_mass_per_kg(
        base_radius(g, Gear::one),
        inertia[static_cast<std::size_t>(dof[static_cast<std::size_t>(m.body_a)])],
        base_radius(g, Gear::two),
        inertia[static_cast<std::size_t>(dof[static_cast<std::size_t>(m.body_b)])]);
    const double step =
        largest_resolving_step_s(m.pair) * std::sqrt(inverse_effective_mass_per_kg(g) / own);
    largest = k == 0 ? step : std::min(largest, step);
  }
  return largest;
}

// The tables a train's meshes read that the train does not give: built once
// for each distinct input. A table is a function of its mesh's kind (external
// or internal), gears and stiffness model alone, so the meshes of a stage's
// planets, equal in these, read one table, the same one each would build.
class BuiltTables {
 public:
  const StiffnessTable* table_for(const TrainMesh& m) {
    for (const Built& b : built_) {
      if (b.internal == internal_mesh(m) && b.gears == m.pair.gears &&
          b.stiffness == m.pair.model.stiffness) {
        return b.table.get();
      }
    }
    built_.push_back({internal_mesh(m), m.pair.gears, m.pair.model.stiffness, build(m)});
    return built_.back().table.get();
  }

 private:
  struct Built {
    bool internal;
    GearPair gears;
    StiffnessModel stiffness;
    std::shared_ptr<const StiffnessTable> table;
  };
  static std::shared_ptr<const StiffnessTable> build(const TrainMesh& m) {
    if (ring_by_potential_energy(m)) {
      return std::make_shared<const StiffnessTable>(internal_potential_energy_table(
          m.pair.gears, ring_line(m.pair).geometry, m.pair.model.stiffness));
    }
    if (internal_mesh(m)) {
      const RingLine ring = ring_line(m.pair);
      return std::make_shared<const StiffnessTable>(
          iso6336_internal_pair_table(ring.line.start_m, ring.line.end_m, ring.line.base_pitch_m,
                                      ring.single_stiffness_n_per_m));
    }
    return run_table(m.pair);
  }
  std::vector<Built> built_;
};

template <class L>
TrainResult run_train(const GearTrain& train, const std::vector<const StiffnessTable*>& tables,
                      const RunControl& control) {
  TrainRun<L> run(train, tables, control);
  if (train.integrator.kind == IntegratorKind::adaptive) {
    return run.finish(run_adaptive_loop(run, train.integrator, largest_resolving_step_s(train)),
                      "adaptive");
  }
  FixedStepper<TrainSystem<L>> stepper(run.system(), train.integrator.kind);
  const double t = run_fixed_grid(run, stepper, train.integrator);
  return run.finish(t, name_of(kIntegratorKinds, train.integrator.kind).c_str());
}

#undef GEARIMPACT_TRAIN_LAYOUT_NAMES

}  // namespace

RingLine ring_line(const SimulationCase& pair) {
  const GearPair& g = pair.gears;
  const PlanetaryTeeth teeth{1, g.teeth2, g.teeth1};
  const PlanetaryToothing toothing{g.module_m, g.pressure_angle_rad, g.addendum_coefficient};
  const double centre = 0.5 * g.module_m * (g.teeth1 - g.teeth2);
  const InternalMesh mesh = internal_mesh(teeth, toothing, centre);
  const Iso6336Internal iso = iso6336_internal_method_b(
      g.teeth2, mesh.contact_ratio, g.dedendum_coefficient, g.pressure_angle_rad);
  RingLine r;
  r.geometry = mesh;
  r.line.planet_base_radius_m = mesh.planet_base_radius_m;
  r.line.ring_base_radius_m = mesh.ring_base_radius_m;
  r.line.pressure_angle_rad = mesh.working_pressure_angle_rad;
  r.line.pitch_point_m = mesh.pitch_point_m;
  r.line.start_m = mesh.segment_start_m;
  r.line.end_m = mesh.segment_end_m;
  r.line.base_pitch_m = mesh.base_pitch_m;
  r.line.tangent_points_m = centre * std::sin(mesh.working_pressure_angle_rad);
  r.line.mean_stiffness_n_per_m = iso.mesh_stiffness_n_per_m2 * g.face_width_m;
  r.single_stiffness_n_per_m = iso.single_stiffness_n_per_m2 * g.face_width_m;
  return r;
}

RingLine ring_line(const TrainMesh& mesh, const StiffnessTable& table) {
  RingLine ring = ring_line(mesh.pair);
  if (ring_by_potential_energy(mesh)) {
    ring.line.mean_stiffness_n_per_m = internal_mean_mesh_stiffness(table, ring.line.base_pitch_m);
  }
  return ring;
}

GearTrain two_gear_train(const SimulationCase& c) {
  GearTrain train;
  // A helical pair's discs are those of the section it runs as.
  const SimulationCase d = dynamics_case(c);
  const GearPair& discs = d.gears;
  TrainBody pinion;
  pinion.name = "pinion";
  pinion.inertia_kg_m2 = moment_of_inertia(discs, Gear::one);
  pinion.torque = c.torque1;
  pinion.theta_rad = c.initial.theta1_rad;
  pinion.w_rad_per_s = c.initial.w1_rad_per_s;
  TrainBody wheel;
  wheel.name = "wheel";
  wheel.inertia_kg_m2 = moment_of_inertia(discs, Gear::two);
  wheel.torque = c.torque2;
  wheel.theta_rad = c.initial.theta2_rad;
  wheel.w_rad_per_s = c.initial.w2_rad_per_s;
  train.bodies = {pinion, wheel};
  TrainMesh mesh;
  mesh.name = "mesh";
  mesh.body_a = 0;
  mesh.body_b = 1;
  mesh.pair = c;
  train.meshes = {mesh};
  train.integrator = c.integrator;
  train.drive = c.drive;
  train.two_gear_case = true;
  if (c.bearings.kind == BearingKind::elastic) {
    // On elastic bearings each gear's centre translates: the bodies carry the
    // bearings, with the planar model's masses (planar_mounting: a disc's
    // where none is given), and its sensor; the mesh turns about fixed axes.
    const PlanarMounting m = planar_mounting(d);
    const GearBearing* bearing[2] = {&c.bearings.gear1, &c.bearings.gear2};
    for (std::size_t i = 0; i < 2; ++i) {
      GearBearing b = *bearing[i];
      b.mass_kg = m.mass_kg[i];
      train.bodies[i].bearing = b;
    }
    train.meshes[0].pair.bearings = Bearings{};
    train.sensor_body = c.bearings.sensor_gear - 1;
    train.sensor_angle_rad = c.bearings.sensor_angle_rad;
  }
  if (c.tacho.pulses_per_revolution > 0) {
    // The train's, on the body its shaft names (without shafts the motor's angle is the
    // pinion's); the mesh's pair keeps none, as its bearings.
    train.tacho_body = c.tacho.shaft == TachoShaft::wheel ? 1 : 0;
    train.tacho = c.tacho;
    train.meshes[0].pair.tacho = Tacho{};
  }
  return train;
}

void check_train(const GearTrain& train) {
  validate_train(train);
}

std::vector<int> train_degrees_of_freedom(const GearTrain& train) {
  return degrees_of_freedom(train);
}

std::shared_ptr<const SpeedController> train_speed_controller(const GearTrain& train, int body) {
  const std::vector<int> dof_of = degrees_of_freedom(train);
  const int dofs = count_dofs(dof_of);
  const auto count = static_cast<std::size_t>(dofs);
  const std::vector<double> inertia = dof_inertias(train, dof_of, dofs);
  // Each degree of freedom's speed per unit speed of the body's: across a
  // mesh w_b = w_a Rb_a / Rb_b, across a torsional shaft the same; 0 where no
  // mesh or shaft leads.
  const int own = dof_of[static_cast<std::size_t>(body)];
  std::vector<double> ratio(count, 0.0);
  std::vector<bool> known(count, false);
  ratio[static_cast<std::size_t>(own)] = 1.0;
  known[static_cast<std::size_t>(own)] = true;
  for (bool grew = true; grew;) {
    grew = false;
    const auto join = [&](int from, int to, double factor) {
      const auto f = static_cast<std::size_t>(from);
      const auto u = static_cast<std::size_t>(to);
      if (!known[f] || known[u]) return;
      ratio[u] = ratio[f] * factor;
      known[u] = true;
      grew = true;
    };
    for (const TrainMesh& m : train.meshes) {
      const double ra = base_radius(m.pair.gears, Gear::one);
      const double rb = base_radius(m.pair.gears, Gear::two);
      const int a = dof_of[static_cast<std::size_t>(m.body_a)];
      const int b = dof_of[static_cast<std::size_t>(m.body_b)];
      join(a, b, ra / rb);
      join(b, a, rb / ra);
    }
    for (const TrainShaft& s : train.shafts) {
      if (s.kind != TrainShaft::Kind::torsional) continue;
      const int a = dof_of[static_cast<std::size_t>(s.body_a)];
      const int b = dof_of[static_cast<std::size_t>(s.body_b)];
      join(a, b, 1.0);
      join(b, a, 1.0);
    }
  }
  double reflected = inertia[static_cast<std::size_t>(own)];
  for (int d = 0; d < dofs; ++d) {
    const auto u = static_cast<std::size_t>(d);
    if (d != own) reflected += inertia[u] * ratio[u] * ratio[u];
  }
  std::vector<ReflectedLoad> loads;
  for (std::size_t j = 0; j < train.bodies.size(); ++j) {
    const auto u = static_cast<std::size_t>(dof_of[j]);
    if (static_cast<int>(j) == body || ratio[u] == 0.0) continue;
    loads.push_back({&train.bodies[j].torque, ratio[u]});
  }
  const TrainBody& b = train.bodies[static_cast<std::size_t>(body)];
  return std::make_shared<const SpeedController>(b.torque, reflected, b.theta_rad,
                                                 std::move(loads));
}

bool runs_by_slices(const TrainMesh& mesh) {
  return helical_mesh(mesh) && !is_unmodified(mesh.pair.modifications);
}

std::vector<TrainMesh> helical_slice_meshes(const TrainMesh& mesh) {
  const SimulationCase& c = mesh.pair;
  const GearPair& g = c.gears;
  const int n = c.model.stiffness.face_slices;
  if (n < 1 || n > kMostFaceSlices) {
    throw InputError("model.face_slices", std::to_string(n),
                     "an integer in [1, " + std::to_string(kMostFaceSlices) + "]");
  }
  const auto face =
      std::make_shared<const FaceStiffness>(g, c.model.stiffness, c.model.stiffness.helical_hertz);
  const HelicalMesh helical(g, *face, c.model.coast_phase);
  const double db = g.face_width_m / n;
  const HelicalGeometry geometry = helical_geometry(g);
  const double alpha_wt = geometry.working_pressure_angle_rad;
  // One table for every slice: each term of 1/kappa_t per unit width over the slice's width.
  const auto table =
      std::make_shared<const StiffnessTable>(face->start_m(), face->end_m(), [face, db](double x) {
        Compliances k = face->compliance_per_width(x);
        for (double& term : k.m_per_n) term /= db;
        return k;
      });
  SimulationCase slice = c;
  slice.gears = transverse_pair(g);
  slice.gears.face_width_m = db;
  slice.model.mesh_damping_ratio = c.model.mesh_damping_ratio / std::sqrt(static_cast<double>(n));
  // Coulomb's law on the flank's normal force, N / cos(beta_b) of a slice's
  // transverse N, as route B's face sum takes it (FaceFriction).
  slice.model.friction_coefficient =
      c.model.friction_coefficient / std::cos(geometry.base_helix_angle_rad);
  // With faults, each slice's pairs read the pair's tables over the slice: a
  // fault's band of the face where it reaches into the slice (route B's layout).
  std::optional<MeshTables> faulted;
  if (!c.faults.empty()) faulted.emplace(helical_mesh_tables(g, c.model.stiffness, c.faults));
  std::vector<TrainMesh> lines;
  for (int j = 0; j < n; ++j) {
    slice.modifications = slice_modifications(c, j, n, alpha_wt);
    TrainMesh line = mesh;
    line.name = mesh.name + "_slice" + std::to_string(j + 1);
    line.pair = slice;
    line.table = table;
    if (faulted) {
      line.teeth = std::make_shared<const MeshTables>(
          faulted->slice(j * db, j + 1 == n ? g.face_width_m : (j + 1) * db, table,
                         c.model.stiffness.helical_hertz));
    }
    line.line_offset_m = mesh.line_offset_m + helical.slice_offset_m(Region::n1, j, n);
    lines.push_back(std::move(line));
  }
  return lines;
}

GearTrain dynamics_train(const GearTrain& train) {
  GearTrain run = train;
  run.meshes.clear();
  for (const TrainMesh& m : train.meshes) {
    if (runs_by_slices(m)) {
      for (TrainMesh& line : helical_slice_meshes(m)) run.meshes.push_back(std::move(line));
      continue;
    }
    run.meshes.push_back(m);
    if (helical_mesh(m)) run.meshes.back().pair = dynamics_case(m.pair);
  }
  return run;
}

std::vector<std::string> train_warnings(const GearTrain& train, const TrainResult& result) {
  std::vector<std::string> warnings;
  const SimulationSummary& s = result.summary;
  if (s.planar && s.speed_drift_max_rel && *s.speed_drift_max_rel > train.drive.speed_tolerance) {
    const TrainBody& first = train.bodies.front();
    warnings.push_back(
        speed_drift_warning(*s.speed_drift_max_rel, train.drive.speed_tolerance, first.torque,
                            train.two_gear_case ? "the pinion" : "body " + first.name,
                            train.two_gear_case ? "torque1" : "bodies." + first.name + ".torque"));
  }
  return warnings;
}

TrainResult simulate_train(const GearTrain& train, const RunControl& control) {
  validate_train(train);
  validate_train_sampling(train, control);
  validate_train_tacho(train);
  // The train its dynamics run: a helical mesh's route B table is built from
  // its helical pair, before the pair becomes its transverse section.
  GearTrain run = train;
  run.meshes.clear();
  BuiltTables built_tables;
  std::vector<const StiffnessTable*> tables;
  for (const TrainMesh& m : train.meshes) {
    if (runs_by_slices(m)) {
      for (TrainMesh& line : helical_slice_meshes(m)) {
        tables.push_back(line.table.get());
        run.meshes.push_back(std::move(line));
      }
      continue;
    }
    tables.push_back(m.table ? m.table.get() : built_tables.table_for(m));
    run.meshes.push_back(m);
    if (helical_mesh(m)) run.meshes.back().pair = dynamics_case(m.pair);
  }
  if (has_planar_bodies(run)) {
    // Its meshes read model.damping_update = "auto" as the planar model
    // does (frozen: docs/vibration.md); their tables are built above.
    for (TrainMesh& m : run.meshes) m.pair.bearings.kind = BearingKind::elastic;
    check_planar_train_step(run, tables);
    return run_planar_train(run, tables, control);
  }
  const bool fixed_axes = std::none_of(run.meshes.begin(), run.meshes.end(), carrier_mesh);
  if (fixed_axes && run.bodies.size() <= PairTrain::kBodies &&
      run.meshes.size() <= PairTrain::kMeshes) {
    return run_train<PairTrain>(run, tables, control);
  }
  const bool small = run.bodies.size() <= SmallTrain::kBodies &&
                     run.meshes.size() <= SmallTrain::kMeshes && fixed_axes;
  if (small) return run_train<SmallTrain>(run, tables, control);
  if (run.meshes.size() <= static_cast<std::size_t>(kMaxTrainMeshes)) {
    return run_train<LargeTrain>(run, tables, control);
  }
  return run_train<SlicedTrain>(run, tables, control);
}

}  // namespace gearimpact
