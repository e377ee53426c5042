// The natural modes of a torsional gear train (dynamics/train.hpp) at
// constant mesh stiffness: each mesh a spring of its mean mesh stiffness (or
// of its pair's constant one, model.mesh_stiffness = "constant") along its
// line, each torsional shaft a spring between its two bodies, bodies joined by
// a rigid shaft one degree of freedom of their summed inertia. Frequencies,
// mass-normalised shapes, the strain-energy share of each mesh and shaft, and
// the rigid modes flagged (docs/planetary.md, "Modes of a torsional train").
//
// Angles are the train's: each body's positive in its forward sense, the
// sense it turns when the train runs forward, so that a mesh between bodies a
// and b deflects by s = Rb_a theta_a - Rb_b theta_b (mesh_line.hpp). For a
// chain of external meshes a body's forward sense is +z or -z as the number of
// meshes between it and the first body is even or odd; about +z throughout,
// s = Rb_a theta_a + Rb_b theta_b and every shape's sign follows.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <vector>

#include "gearimpact/dynamics/train.hpp"

namespace gearimpact {

// Where a spring of the train stores its strain energy.
struct TrainSpring {
  enum class Kind { mesh, shaft };
  Kind kind = Kind::mesh;
  std::size_t index = 0;   // into GearTrain::meshes or GearTrain::shafts
  double stiffness = 0.0;  // N/m for a mesh, N m/rad for a shaft
  // a: the spring's deflection per unit of each degree of freedom (m/rad for
  // a mesh: its base radii; 1 for a shaft); it stores k (a . q)^2 / 2.
  Eigen::VectorXd direction;
};

struct TrainLinearModel {
  // Each body's degree of freedom (bodies on one rigid shaft share one),
  // numbered in the order of their first body.
  std::vector<int> body_dof;
  std::vector<double> mesh_stiffness_n_per_m;  // per mesh, the springs' k
  Eigen::MatrixXd mass;                        // diag(J) per degree of freedom, kg m^2
  Eigen::MatrixXd stiffness;                   // sum of k a a^T over `springs`
  std::vector<TrainSpring> springs;            // the meshes, then the torsional shafts
};

// M and K of a valid train (simulate_train's refusals, InputError naming the
// field) with the given stiffness per mesh (finite, >= 0: a mesh of 0
// separates its bodies).
TrainLinearModel train_linear_model(const GearTrain& train,
                                    const std::vector<double>& mesh_stiffness_n_per_m);

// Each mesh's mean mesh stiffness (mean_mesh_stiffness_n_per_m of its pair
// over the true period with faults; the constant k of a constant-stiffness
// pair), from the mesh's table when it has one.
std::vector<double> mean_mesh_stiffnesses(const GearTrain& train);

struct TrainMode {
  bool rigid = false;              // no strain energy; frequency 0
  double angular_frequency = 0.0;  // rad/s
  double frequency_hz = 0.0;
  // v with v^T M v = 1, per degree of freedom (rad/sqrt(kg m^2)), its largest
  // component by magnitude positive. A rigid mode turns one connected group of
  // bodies as the train rolls without deflection, the rest still.
  Eigen::VectorXd shape;
  // v^T K v shared among the springs (in the order of TrainLinearModel::springs),
  // each in [0, 1], summing to 1; all 0 for a rigid mode.
  std::vector<double> energy_share;
};

struct TrainModes {
  TrainLinearModel model;
  std::vector<TrainMode> modes;  // ascending frequency, the rigid ones first
};

// The rigid modes: one for each group of degrees of freedom that the springs
// join and whose meshes roll consistently (a closed loop of meshes whose
// ratios disagree has none), its shape set from the base radii; the elastic
// ones by Eigen's generalised self-adjoint solver, K v = w^2 M v.
TrainModes train_modes(const TrainLinearModel& model);

// At each mesh's mean mesh stiffness.
TrainModes train_modes(const GearTrain& train);

// A mode's shape per body (a rigid shaft's bodies the same), in the order of
// GearTrain::bodies.
Eigen::VectorXd body_shape(const TrainLinearModel& model, const TrainMode& mode);

}  // namespace gearimpact
