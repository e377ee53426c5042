// A gear train: bodies turning on rigid bearings (or, with a bearing,
// translating on elastic ones: TrainBody::bearing), the meshes
// between them (each a MeshLine of its own gear pair, tables and backlash),
// and shafts joining two bodies, rigid (the two become one body of summed
// inertia) or a torsional spring. The state is the angle and speed of each
// body; each mesh acts on its two bodies through their base radii. A train
// runs through the same run loop as the two-gear models (run_fixed_grid of
// step_methods.hpp); the two-gear torsional case is the train of two bodies
// and one mesh (two_gear_train), and runs the same numbers bit for bit.
// A mesh may also sit in a carrier's frame (a planetary stage's, rotational
// only: every centre fixed in that frame): it then sees its bodies' angles
// relative to the carrier's and puts its reaction moment on the carrier
// (planetary_train.hpp builds such a stage). With bodies on elastic
// bearings too, such a stage runs planar (train_planar.cpp): the central
// members' centres translate in the carrier's axes on their supports, each
// planet on its pin's bearing (TrainBody::pin), and each mesh sees the
// centres' motion along its lines in the direction of its planet.
// With a body on elastic bearings the train runs the planar dynamics of
// each mesh between fixed axes (train_planar.cpp): the bodies' centres in
// the fixed frame, each mesh along its two lines of action in the direction
// of its line of centres (TrainMesh::centre_angle_rad); the two-gear planar
// case is the train of two such bodies and runs its numbers bit for bit.
// docs/architecture.md, section "A gear train"; docs/planetary.md.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/drive.hpp"
#include "gearimpact/dynamics/mesh_line.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// The most bodies (after rigid shafts join them) and meshes of a train: the
// state and the event values are fixed-size arrays.
// A planetary stage of 5 planets has 8 bodies (sun, ring, carrier, planets)
// and 10 meshes.
inline constexpr int kMaxTrainBodies = 8;
inline constexpr int kMaxTrainMeshes = 10;
// The most lines a run holds: a train's meshes after route A cut each helical
// mesh with modifications into its slices (helical_slice_meshes).
inline constexpr int kMaxTrainLines = 64;

// A body turning about its fixed axis. Its angle and speed are positive in the
// sense it turns when the train runs forward: a mesh's driven body b turns
// forward when its driving body a does.
struct TrainBody {
  std::string name;
  double inertia_kg_m2 = 0.0;
  // Its applied torque in its forward sense (constant, sinusoidal, harmonic,
  // a profile or a user function of time; none: a constant 0).
  Torque torque;
  double theta_rad = 0.0;    // initial angle
  double w_rad_per_s = 0.0;  // initial speed
  // Held at its initial angle (a removed coordinate: a planetary stage's
  // fixed member): its speed stays 0 (w must be 0, its torque a constant 0),
  // and whatever holds it does no work.
  bool held = false;
  // Its centre on elastic bearings (docs/architecture.md, "A gear train"):
  // x and y in the train's fixed (inertial) frame, each with its spring and
  // damper as the two-gear [bearings] keys mean them (stiffness_y and
  // damping_y absent: the x ones), and mass_kg, required here (a train's body
  // has no disc to take it from), the mass the bearings carry. Bodies joined
  // by rigid shafts share one centre: at most one of them has bearings, and
  // its mass is the whole shaft's. None: the centre is fixed.
  std::optional<GearBearing> bearing{};
  // A planet on its pin in a carrier (a planetary stage's planar form,
  // docs/planetary.md, "The planar stage"): `bearing` then joins its centre
  // to the pin, stiffness_x radial and stiffness_y tangential, and its centre
  // is the pin's nominal place (radius_m from the carrier's centre at
  // angle_rad from the carrier's first axis, turning with the carrier) plus
  // its displacement in the carrier's axes; its mass orbits with the carrier
  // (the carrier's inertia is then its own, without the planets' orbits).
  // None: a body about its own axis.
  struct Pin {
    int carrier = -1;
    double radius_m = 0.0;
    double angle_rad = 0.0;
  };
  std::optional<Pin> pin{};
};

// A mesh between bodies a (its pair's gear 1) and b (gear 2). Of `pair`, the
// mesh reads the keys of the pair: gears (geometry, backlash), model (the
// stiffness, contact, damping and friction), faults and modifications; its
// torques, initial state and integrator are the train's. `table`: the
// stiffness table of the pair, built by the run when none is given.
//
// A mesh in a carrier's frame (carrier >= 0, the index of the carrier body):
// the angles of its bodies and of the carrier are all about +z (the stage's
// one sign rule), and its deflection is that of docs/planetary.md,
// s = Rb_a (theta_a - theta_c) + kappa Rb_b (theta_b - theta_c): kappa = +1
// for an external mesh (a the sun, b a planet, pair.gears.teeth1 and teeth2
// theirs), kappa = -1 for an internal one (a the ring, an internal gear of
// pair.gears.teeth1 teeth, b the planet of teeth2, at the standard centre
// distance m (teeth1 - teeth2) / 2; its stiffness table is ISO 6336-1 method
// B's, iso6336_internal_pair_table, built by the run; unshifted, without
// friction, faults or modifications). The mesh's force puts the moments
// -F Rb_a and -kappa F Rb_b on a and b and minus their sum on the carrier.
// line_offset_m shifts the loaded pairs along the line (the mesh's phase
// times the base pitch), X measured from the tangent point of the sun (an
// external mesh) or the planet (an internal one); planetary_train sets it
// from the stage's geometry. On a mesh between fixed axes it shifts them the
// same way (a helical mesh's slice by its share of b tan(beta_b)); s is kept.
//
// A helical pair (pair.gears.helix_angle > 0) runs as the two-gear model
// runs it (docs/helical.md, Dynamics): without modifications by route B, its
// transverse section (dynamics_case) reading the extended pair table
// (run_table); with modifications (reliefs, lead modifications,
// misalignment) by route A, as model.face_slices = N slice meshes between
// the same two bodies (helical_slice_meshes), each with its own gaps.
struct TrainMesh {
  enum class Kind { external, internal };
  std::string name;
  int body_a = 0;
  int body_b = 1;
  SimulationCase pair;
  std::shared_ptr<const StiffnessTable> table;
  int carrier = -1;
  Kind kind = Kind::external;
  double line_offset_m = 0.0;
  // Between fixed axes: the direction of the line of centres, from body a's
  // centre to body b's, in the train's fixed frame (from +x towards +y). With
  // a body on elastic bearings the mesh sees the centres' motion along each
  // of its lines of action in that direction and puts its forces on them
  // (docs/vibration.md, "The planar dynamics"); 0 is the two-gear planar
  // model's frame, x along O1 -> O2.
  double centre_angle_rad = 0.0;
  // A helical slice's (helical_slice_meshes) with the pair's faults: the
  // tables of its pairs' teeth over the slice (MeshTables::slice); none
  // otherwise. `table` is their healthy one.
  std::shared_ptr<const MeshTables> teeth = nullptr;
};

// A shaft between bodies a and b on one axis (both turn in the same sense).
struct TrainShaft {
  enum class Kind { rigid, torsional };
  Kind kind = Kind::rigid;
  int body_a = 0;
  int body_b = 1;
  double stiffness_n_m_per_rad = 0.0;  // torsional: T = k (theta_a - theta_b) on b
};

struct GearTrain {
  std::vector<TrainBody> bodies;
  std::vector<TrainMesh> meshes;
  std::vector<TrainShaft> shafts;
  // The accelerometer on a body's bearing (a body with `bearing`): its
  // centre's acceleration along the direction at sensor_angle_rad from +x
  // towards +y, as the two-gear [bearings] sensor's (docs/vibration.md).
  // -1: none.
  int sensor_body = -1;
  double sensor_angle_rad = pi / 2.0;
  // A tacho on body tacho_body's angle (-1: none; [tacho] body = NAME): its
  // edges where that angle crosses offset + 2 pi k / pulses_per_revolution
  // upward, located on each step's continuous extension (or a driver's
  // closed form) as the two-gear planar run locates them (TachoEdges); a
  // train on bearings only, as the two-gear tacho. tacho.shaft is not read:
  // the body says which.
  int tacho_body = -1;
  Tacho tacho;
  // kind (rk4: the event-cut RK4 at the fixed step), step, end time, output_every.
  IntegratorSettings integrator;
  // Written from a two-gear case (two_gear_train): its keys are the pair's
  // (torque1 for the pinion's torque), which its messages name.
  bool two_gear_case = false;
  // The drift check's settling time and bound ([drive]): the first body's
  // speed over each whole revolution after settle_s against its reference
  // (SpeedDriftMonitor; SimulationSummary::speed_drift_max_rel).
  Drive drive;
};

// The two-gear torsional case as a train: the pinion (J1, torque1, theta1,
// w1), the wheel (J2, torque2, theta2, w2) and one mesh between them; a
// helical pair's J1 and J2 those of the transverse section it runs as
// (dynamics_case), as the two-gear run's.
GearTrain two_gear_train(const SimulationCase& c);

// Whether a mesh runs by route A (docs/helical.md, Dynamics): a helical pair
// with modifications (a relief, a lead modification or a misalignment).
bool runs_by_slices(const TrainMesh& mesh);

// Route A: a helical mesh as N = model.face_slices slice meshes between its
// two bodies, named NAME_slice1 to NAME_sliceN. Slice j (mid-plane y_j =
// (j + 1/2) b / N) is the transverse section's spur pair (transverse_pair) of
// width b / N, shifted along the line by HelicalMesh::slice_offset_m (its
// share of W = b tan(beta_b)) on top of the mesh's own line_offset_m; its
// table gives kappa_t(X) b / N (FaceStiffness::compliance_per_width, each
// term over b / N), one table shared by the slices; its gaps are the profile
// gaps of the pair's reliefs plus the lead gap lead_gap_m at y_j on each
// flank (N1 and N2), carried as one pitch and thickness deviation on every
// tooth of gear 1 (pitch (e1 - e2) / 2, thickness (e1 + e2) / 2: e1 on the
// drive flank, e2 on the coast flank); its viscous damper's ratio zeta /
// sqrt(N), so that each slice's damper 2 zeta / sqrt(N) sqrt(k_mean / N m_e)
// is 1/N of the face's. InputError naming gears.helix_angle for a spur pair.
std::vector<TrainMesh> helical_slice_meshes(const TrainMesh& mesh);

// The train as its dynamics run it: each helical mesh by route B (its pair
// the transverse section, dynamics_case) or route A (its slice meshes,
// helical_slice_meshes, in its place); spur and internal meshes as given. A
// run's per-mesh rows and summaries (TrainResult) follow this train's meshes:
// name its outputs by it. The tables are those given (route B: none builds
// the extended pair table at the run; route A: the slices' own).
GearTrain dynamics_train(const GearTrain& train);

// One output row: each body's angle and speed (in the order of
// GearTrain::bodies; bodies on one rigid shaft have the same), and each mesh's
// s, delta, region, loaded pairs and forces, as SeriesRow has them.
struct TrainMeshRow {
  double s_m = 0.0;
  double delta_m = 0.0;
  int region = 0;
  int pairs = 0;
  double normal_force_n = 0.0;
  double friction_force_n = 0.0;
  // With bodies on elastic bearings, each line's own (drive N1, coast N2):
  // its normal force summed over its pairs (normal_force_n is their sum) and
  // the larger penetration of its pairs (delta_d = s_d - B, delta_c = -s_c -
  // B), as PlanarRow has them; 0 in a train on fixed axes.
  std::array<double, 2> line_force_n{};
  std::array<double, 2> line_penetration_m{};
};
// With bodies on elastic bearings, each body's centre (x, y in the fixed
// frame, 0 for a fixed centre) and the force its bearings exert on it,
// -k u - c u' per axis; the sensor's acceleration (GearTrain::sensor_body).
struct TrainCentreRow {
  double x_m = 0.0;
  double y_m = 0.0;
  double vx_m_s = 0.0;
  double vy_m_s = 0.0;
  double bearing_fx_n = 0.0;
  double bearing_fy_n = 0.0;
};
struct TrainRow {
  double t_s = 0.0;
  std::vector<double> theta_rad;
  std::vector<double> w_rad_per_s;
  std::vector<TrainMeshRow> meshes;
  std::vector<TrainCentreRow> centres;  // empty without bodies on bearings
  double sensor_acceleration_m_per_s2 = 0.0;
};

// Per mesh: the contacts begun (a contact at the start counts), the largest
// penetration, and its losses: the Hertzian damping's of (32), the friction's
// and the viscous mesh damper's (their sums over the meshes are the train's
// damping_loss_j, friction_loss_j and mesh_damping_loss_j, to rounding).
struct TrainMeshSummary {
  int impacts = 0;
  double max_penetration_m = 0.0;
  double damping_loss_j = 0.0;
  double friction_loss_j = 0.0;
  double mesh_damping_loss_j = 0.0;
};

// Per body: its speed at the end of the run (a rigid shaft's bodies have the same).
struct TrainBodySummary {
  double final_w_rad_per_s = 0.0;
};

struct TrainResult {
  std::vector<TrainRow> series;
  // The sensor's samples (RunControl::sample_rate_hz, keep_samples): each a
  // row at t = n / sample_rate_hz from the step's continuous extension, its
  // sensor_acceleration_m_per_s2 the point value or the mean over the
  // interval ending there (RunControl::sample; an interval-average run's
  // first sample, n = 0, only begins the first interval).
  std::vector<TrainRow> samples;
  // The tacho's edge times (GearTrain::tacho_body), true: the emitted ones
  // add tacho.jitter (signals::tacho_jitter).
  std::vector<double> tacho_times_s;
  // steps, rhs_evaluations, events, end_time_s, step_s, the impacts' counts
  // and times, and the energy ledger (docs/model.md, Energies) of the whole
  // train; the shafts' springs count with the stored energy.
  SimulationSummary summary;
  std::vector<TrainMeshSummary> meshes;
  std::vector<TrainBodySummary> bodies;  // in the order of GearTrain::bodies
  // Each mesh's contacts, as SimulationResult::impacts has the one mesh's;
  // the summary's impacts_n1, impacts_n2, first and last impact times are
  // those of all the meshes together.
  std::vector<std::vector<ImpactRecord>> impacts;
};

// Refuses what simulate_train refuses (below), before any work: for a caller
// that reads the train without running it (its modes, modes/train_modes.hpp).
void check_train(const GearTrain& train);

// Which of the train's degrees of freedom each body is, in the order of
// GearTrain::bodies: bodies joined by rigid shafts are one, numbered in the
// order of their first body.
std::vector<int> train_degrees_of_freedom(const GearTrain& train);

// The speed controller of body `body` (torque.kind speed-controlled) in a
// train about fixed axes, as the torsional and the planar train run it: the
// train's inertia reflected to the body's degree of freedom, sum J_d
// ratio_d^2 (its own first; ratio_d the speed of d per unit speed of the body
// when the train rolls without slip, across a mesh Rb_a / Rb_b, across a
// torsional shaft 1), against the other bodies' torques reflected by their
// ratios (drive.hpp). The controller keeps pointers to `train`'s torques:
// `train` outlives it.
std::shared_ptr<const SpeedController> train_speed_controller(const GearTrain& train, int body);

// Validates the train (InputError naming the field: bodies.NAME.inertia,
// meshes.NAME.gears.teeth1, ...) and runs dynamics_train(train); its rows'
// and summaries' meshes are that train's (a helical mesh by route A: one per
// slice). Of `control`, keep_series, on_train_row (each row, kept or not),
// should_stop and the sensor's sampling (sample_rate_hz, sample,
// keep_samples, on_train_sample; a train with a [sensor] only, refused
// naming sample_rate before any work otherwise) are read. With a body on
// elastic bearings: the planar train (its refusals and its step bound by
// name: bodies.NAME.bearings.KEY, integrator.step, ...), its meshes reading
// model.damping_update = "auto" as the planar model does (frozen), its rows
// with each body's centre and bearing force and the sensor's acceleration,
// its summary with the bearings' energies (SimulationSummary::planar).
TrainResult simulate_train(const GearTrain& train, const RunControl& control = {});

// What a user should hear about a finished run of the train: on bearings (a signal run, as the
// two-gear planar run's), its first body's speed drifting beyond drive.speed_tolerance
// (speed_drift_warning), naming its key as a train file writes it (bodies.NAME.torque), or of a
// two-gear case (GearTrain::two_gear_case) as its file does (torque1, the pinion's: the
// two-gear run's warning word for word).
std::vector<std::string> train_warnings(const GearTrain& train, const TrainResult& result);

}  // namespace gearimpact
