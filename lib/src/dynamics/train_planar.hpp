// A gear train with bodies on elastic bearings (train.hpp, TrainBody::bearing):
// its planar system and run, which train.cpp's simulate_train dispatches to.
// docs/architecture.md, section "A gear train".
#pragma once

#include <vector>

#include "gearimpact/dynamics/mesh_line.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/geometry/planetary.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// An internal mesh's line (planet as gear 1, geometry/planetary.hpp's
// segment), its geometry and its single-pair stiffness c' b by ISO 6336-1
// method B, from its pair (teeth1 the ring's, teeth2 the planet's, standard
// centre distance).
struct RingLine {
  InternalLine line;
  InternalMesh geometry;
  double single_stiffness_n_per_m = 0.0;
};
RingLine ring_line(const SimulationCase& pair);
// The line a run gives an internal mesh: ring_line's, its mean stiffness (the
// damper's) that of the mesh's own table where the potential-energy route
// builds it, not ISO's.
RingLine ring_line(const TrainMesh& mesh, const StiffnessTable& table);

// The number of degrees of freedom of a train whose bodies are on the
// degrees of freedom `dof` (degrees_of_freedom).
int count_dofs(const std::vector<int>& dof);
// The summed inertia of each of the `dofs` degrees of freedom, its bodies' in
// their order.
std::vector<double> dof_inertias(const GearTrain& train, const std::vector<int>& dof, int dofs);

// The motion a body's kinematic driver gives it at t (driver_motion from its
// initial angle), or a held body's: still at its angle.
DriverMotion driven_body_motion(const TrainBody& body, double t);

// Whether any body of the train has its centre on elastic bearings.
bool has_planar_bodies(const GearTrain& train);

// The planar train's own checks, after validate_train's (each InputError
// naming the field as bodies.NAME.bearings.KEY, meshes.NAME.KEY, sensor_body
// or integrator.step): its bearings' values; what it does not run yet (a
// carrier's meshes, an internal mesh, the Lagrangian mesh force, the adaptive integrator, a
// speed-controlled body in a carrier's frame, two bodies with bearings on one rigid shaft); senses
// of turning that
// contradict each other around a loop of meshes; the sensor's body.
void validate_planar_train(const GearTrain& train);
// InputError naming integrator.step unless the step resolves the shortest
// period the planar train can have (as check_planar_step bounds the two-gear
// planar system's); `train` the dynamics train, `tables` its meshes' tables.
void check_planar_train_step(const GearTrain& train,
                             const std::vector<const StiffnessTable*>& tables);

// The run of a train with bodies on bearings (its dynamics train: route B
// pairs and route A's slice meshes, tables given), after validate_train and
// validate_planar_train.
TrainResult run_planar_train(const GearTrain& train,
                             const std::vector<const StiffnessTable*>& tables,
                             const RunControl& control);

}  // namespace gearimpact
