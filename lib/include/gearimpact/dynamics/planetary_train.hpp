// A planetary stage as a gear train (train.hpp): rotational (the sun's,
// ring's and carrier's centres and the planet pins rigid, every centre
// fixed in the carrier's frame; the state the angle and speed of the sun,
// ring, carrier and each planet, all about +z), or planar with `supports`
// (each central member's centre translating on its supports in the
// carrier's axes, each planet's on its bearing: Lin & Parker's coordinates). Each sun-planet mesh
// is an external mesh and each ring-planet mesh an internal one (ISO 6336-1 method B per-pair
// stiffness), both in the carrier's frame; their phases come from the stage's geometry
// (geometry/planetary.hpp), never entered. docs/planetary.md, sections "Nonlinear rotational stage"
// and "The planar stage".
#pragma once

#include <optional>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/geometry/planetary.hpp"
#include "gearimpact/geometry/train_teeth.hpp"
#include "gearimpact/signals/planet_pass.hpp"

namespace gearimpact {

// A faulted tooth of a stage's member (docs/planetary.md, "Faults on a stage's
// members"): the member, for a planet its number n (1 ... N), the tooth's
// number in the stage's count (geometry/train_teeth.hpp, stage_mesh_teeth;
// the members' teeth 0 placed as planetary_train says), and its state, of
// the fault tables (stiffness/tooth_state.hpp). A sun tooth's fault acts on
// every sun-planet mesh it passes through, a planet's on its sun mesh (and
// a missing planet tooth on its ring mesh too); a ring tooth can only be
// missing (the ring meshes' ISO 6336-1 table has no tooth profile), and is
// missing at every ring-planet mesh.
enum class FaultMember { sun, planet, ring };
struct StageFault {
  FaultMember member = FaultMember::sun;
  int planet = 1;  // read for member == planet
  int tooth = 0;
  ToothState state;
};

// The planar stage's members on their springs (docs/planetary.md, "The
// planar stage"), the keys of the linear model's planetary file
// (modes/planetary.hpp): each central member's mass and its support's
// stiffness on x and on y of the carrier's axes (0: it floats), each
// planet's bearing, radial and tangential (its mass the stage's
// planet_mass, required). Each support and bearing may have a viscous damper
// in parallel (N*s/m, the same on x and on y; 0: none), which the linear
// model's modes leave out (they are the undamped system's).
struct StageSupports {
  double sun_mass_kg = 0.0;
  double ring_mass_kg = 0.0;
  double carrier_mass_kg = 0.0;
  double sun_support_n_per_m = 0.0;
  double ring_support_n_per_m = 0.0;
  double carrier_support_n_per_m = 0.0;
  double planet_bearing_n_per_m = 0.0;
  double sun_support_damping_n_s_per_m = 0.0;
  double ring_support_damping_n_s_per_m = 0.0;
  double carrier_support_damping_n_s_per_m = 0.0;
  double planet_bearing_damping_n_s_per_m = 0.0;
};

struct PlanetaryStage {
  PlanetaryTeeth teeth;
  // The meshes' keys: of its gears the module, pressure angle, addendum and
  // dedendum coefficients, face width, materials and backlash (the tooth
  // counts are the stage's; unshifted teeth), and its model (the ring meshes
  // take it without friction); its faults must be none (the stage's faults
  // are `faults`, by member).
  SimulationCase mesh;
  // Planet positions psi_n (psi_1 = 0, counter-clockwise); empty: `planets`
  // equally spaced.
  std::vector<double> planet_angles_rad;
  int planets = 3;
  double sun_inertia_kg_m2 = 0.0;
  double ring_inertia_kg_m2 = 0.0;
  double carrier_inertia_kg_m2 = 0.0;
  double planet_inertia_kg_m2 = 0.0;
  // Each planet's mass: its orbit adds m_p R_c^2 to the carrier's inertia
  // (absent: the carrier's inertia is taken as given).
  std::optional<double> planet_mass_kg;
  // The member held still (its angle a removed coordinate), and the torques
  // on the other two (the held member's must stay none).
  HeldMember held = HeldMember::ring;
  Torque sun_torque;
  Torque ring_torque;
  Torque carrier_torque;
  // The planar stage's supports and bearings (none: the rotational stage).
  // The carrier's inertia is then its own: each planet's mass orbits on
  // its bearing.
  std::optional<StageSupports> supports;
  // Faulted teeth, at most one per tooth (none: every tooth healthy).
  std::vector<StageFault> faults;
  // Every body starts at angle 0 turning at the Willis speeds with the input
  // member (the sun, or the ring when the sun is held) at this speed.
  double input_speed_rad_per_s = 0.0;
  IntegratorSettings integrator;
};

// The bodies' and meshes' order in planetary_train's GearTrain.
inline constexpr int kSunBody = 0;
inline constexpr int kRingBody = 1;
inline constexpr int kCarrierBody = 2;
inline constexpr int kFirstPlanetBody = 3;
// Meshes: sun-planet n at n - 1, ring-planet n at N + n - 1 (n = 1..N).

// The stage as a train: bodies sun, ring, carrier, planet1..planetN (with
// `supports`, the central members on bearings of their support stiffness,
// isotropic, and each planet on a pin of the carrier at R_c and psi_n with
// its bearing: TrainBody::pin); meshes
// sun_planetN (external: the sun's line, its phase -gamma_sn base pitches)
// and ring_planetN (internal: the planet's line, its phase gamma_rs -
// gamma_rn, so that each planet's sun mesh crosses its pitch point gamma_rs
// after its ring mesh). Throws InputError naming the stage's key
// (sun_teeth, planets, planet_angles[i], held, faults[i].tooth, ...) or the
// train's.
//
// The faults go to each mesh's pair as that mesh numbers its teeth (its
// pairs' count, tooth_identity.hpp): the stage's tooth of a member is found
// at each of its meshes by stage_mesh_teeth at a state of the rigid stage
// half a mesh period after a pitch-point crossing of that mesh, where it
// and the mesh's own count (mesh_teeth_at) each name one tooth, and the
// two counts run on from there, the sun's both forward, a planet's and the
// ring's in opposite senses. The members' teeth 0, relative to the carrier
// with every body at angle 0: the sun's centre line at -pi / (2 Z_s) from
// e1, planet n's at pi - pi / (2 Z_p) + 2 pi gamma_sn / Z_p from its
// e_zeta, the ring's at -pi / (2 Z_r) - 2 pi gamma_rs / Z_r from e1 (each a
// quarter pitch behind the line of centres where its driven flank meets the
// pitch point, unshifted teeth: the sun's tooth 0 and planet 1's tooth 0 at
// planet 1's sun-mesh pitch point at t = 0, the ring's tooth 0 at planet 1's
// ring-mesh pitch point when that mesh first crosses it).
GearTrain planetary_train(const PlanetaryStage& stage);

// The rigid speeds (Willis) of the stage's members at its input speed.
StageSpeeds planetary_rigid_speeds(const PlanetaryStage& stage);

// The Willis relation Z_s (w_s - w_c) + Z_r (w_r - w_c) = 0 (geometry/planetary.hpp,
// rigid_speeds) on a run's mean speeds, each the member's angle turned over the run divided by the
// run's time (first row to last). With r_b = m Z cos(alpha) / 2 the numerator times that time is
// 2 (s_sp(T) - s_sp(0) + s_rp(T) - s_rp(0)) / (m cos alpha) for any planet's two meshes (r_bs phi_s
// + r_bp phi_p and r_br phi_r - r_bp phi_p are their displacements along the lines, phi = theta -
// theta_c): the elastic stage breaks the relation by no more than its meshes' displacements.
// residual = |Z_s (w_s - w_c) + Z_r (w_r - w_c)| / (Z_s |w_s - w_c| + Z_r |w_r - w_c|), in [0, 1]
// (0 when the stage turns as one block). Throws InputError naming `run` unless it has two rows
// or more, of the stage's bodies.
struct StageWillis {
  double sun_rad_per_s = 0.0;
  double ring_rad_per_s = 0.0;
  double carrier_rad_per_s = 0.0;
  double residual = 0.0;
};
StageWillis planetary_willis(const PlanetaryStage& stage, const TrainResult& run);

// Tooth identity on a run (docs/planetary.md, "Tooth identity on a run"): the
// teeth at planet n's two meshes in one row of simulate_train(planetary_train(
// stage)), element n - 1 of the result: stage_mesh_teeth (the tooth whose
// centre line crossed the mesh's line of centres last, in the stage's count
// that the faults use) at the members' teeth 0 placed as planetary_train
// says, each carried on by its body's angle relative to the carrier's in the
// row (theta - theta_c, deflections included). A sun tooth at sun mesh n
// pairs with the planet tooth there; the pairing of a sun mesh repeats after
// lcm(Z_s, Z_p) mesh periods, of a ring mesh after lcm(Z_p, Z_r)
// (hunting_period_mesh_periods). Throws InputError naming `row` unless it
// holds the stage's bodies.
std::vector<StageMeshTeeth> planetary_mesh_teeth(const PlanetaryStage& stage, const TrainRow& row);

// The same at every row of a run: its time and the teeth at each planet's meshes.
struct StageTeethRow {
  double t_s = 0.0;
  std::vector<StageMeshTeeth> planets;  // planet n at n - 1
};
std::vector<StageTeethRow> planetary_teeth_series(const PlanetaryStage& stage,
                                                  const TrainResult& run);

// The ring-housing sensor's y(t) (signals/planet_pass.hpp, ring_sensor_signal)
// at each row of `run`, the series of simulate_train(planetary_train(stage)):
// phi_n = theta_c + psi_n with theta_c the carrier's angle in the row and
// psi_n the stage's planet positions; planet n's F_d,rn - F_c,rn is its ring
// mesh's contact force (TrainMeshRow::normal_force_n, summed over the loaded
// pairs, never negative) signed by the line in contact: + on the drive line
// (region n1), - on the coast line (n2), 0 in the backlash. The viscous mesh
// damper's force (c s', acting in the backlash too) is not a tooth contact
// force and is not in the row, so it is left out. Throws InputError naming
// `run` when its rows do not hold the stage's bodies and 2 N meshes.
std::vector<double> planetary_ring_sensor(const PlanetaryStage& stage, const TrainResult& run,
                                          const signals::RingSensor& sensor = {});

}  // namespace gearimpact
