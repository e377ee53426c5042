// The linearised planar model of docs/vibration.md: the gears on their
// bearings (and a motor and a load behind torsional shafts) with the mesh as
// one spring of the mean mesh stiffness along the drive line of action; its
// mass and stiffness matrices, natural frequencies, mass-normalised mode
// shapes and the share of each mode's strain energy stored in each spring;
// and where the mesh harmonics cross the natural frequencies as the pinion
// speeds up (a Campbell diagram).
//
// Frame: origin at the pinion centre O1, e_x from O1 to O2, e_y = e_z x e_x;
// theta1 about +z, theta2 about -z (clockwise), so that rolling is
// Rb1 w1 = Rb2 w2. The drive line's unit vector is n1 = (sin a_w, cos a_w),
// a_w the working pressure angle, and its deflection
//   s_d = Rb1 theta1 - Rb2 theta2 + (u1 - u2) . n1.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"

namespace gearimpact {

// The degrees of freedom, in the order of the matrices: the translations only
// on elastic bearings, the motor and the load only on elastic shafts.
enum class Dof { x1, y1, theta1, x2, y2, theta2, theta_motor, theta_load };

// "x1", "theta_motor", ... as the columns of modes.csv begin.
std::string_view dof_name(Dof dof);
// True for theta1, theta2, theta_motor, theta_load (rad), false for x, y (m).
bool is_rotation(Dof dof);

// Where a spring stores its strain energy.
enum class SpringPart { mesh, bearing1, bearing2, motor_shaft, load_shaft };
inline constexpr std::size_t kSpringParts = 5;
// "mesh", "bearing1", ... as the share columns of modes.csv end.
std::string_view part_name(SpringPart part);

// Everything the linearised model reads, in SI. From a case by
// linear_parameters(); a library caller may set any of it (a mesh stiffness of
// 0 separates the gears).
struct LinearParameters {
  double base_radius1_m = 0.0;
  double base_radius2_m = 0.0;
  double working_pressure_angle_rad = 0.0;
  double inertia1_kg_m2 = 0.0;  // J1, J2 of the torsional model
  double inertia2_kg_m2 = 0.0;
  double mesh_stiffness_n_per_m = 0.0;  // >= 0
  BearingKind bearings = BearingKind::rigid;
  std::array<double, 2> mass_kg{};  // per gear, elastic bearings only
  std::array<double, 2> bearing_stiffness_x_n_per_m{};
  std::array<double, 2> bearing_stiffness_y_n_per_m{};
  ShaftKind shafts = ShaftKind::none;
  double motor_inertia_kg_m2 = 0.0;
  double motor_stiffness_n_m_per_rad = 0.0;
  double load_inertia_kg_m2 = 0.0;
  double load_stiffness_n_m_per_rad = 0.0;
};

// One linear spring: stores k (a . q)^2 / 2 at the displacement q.
struct LinearSpring {
  SpringPart part;
  double stiffness;           // N/m for a force, N m/rad for a torque
  Eigen::VectorXd direction;  // a: its deflection per unit of each DOF
};

struct LinearModel {
  LinearParameters parameters;  // what it was built from
  std::vector<Dof> dofs;
  Eigen::MatrixXd mass;       // M: kg on x, y; kg m^2 on the angles
  Eigen::MatrixXd stiffness;  // K = sum of k a a^T over the springs
  std::vector<LinearSpring> springs;
  // Modes without strain energy: one (the pair rolling) when the mesh
  // stiffness is > 0, two (each gear with its shaft) when it is 0.
  std::size_t rigid_modes = 0;
};

// The parameters of a case at the mean mesh stiffness k (from
// mean_mesh_stiffness_n_per_m of dynamics/mesh.hpp): the masses of absent
// [bearings] massN the discs of moment_of_inertia (disc_mass), absent
// stiffness_yN / damping_yN their x values.
LinearParameters linear_parameters(const SimulationCase& c, double mesh_stiffness_n_per_m);

// M and K of the parameters. Throws InputError naming the parameter unless
// every mass, inertia, radius and spring of the chosen DOFs is finite and
// > 0 (the mesh stiffness >= 0) and the pressure angle in (0, pi/2).
LinearModel linear_model(const LinearParameters& p);

struct NaturalMode {
  bool rigid = false;              // no strain energy; frequency 0
  double angular_frequency = 0.0;  // w, rad/s
  double frequency_hz = 0.0;       // w / (2 pi)
  // v with v^T M v = 1 (units 1/sqrt(kg) on x, y; rad/(sqrt(kg) m) on the
  // angles), its largest component by magnitude positive.
  Eigen::VectorXd shape;
  // The share of v^T K v = w^2 stored in each SpringPart, each in [0, 1],
  // summing to 1; all 0 for a rigid mode.
  std::array<double, kSpringParts> energy_share{};
};

struct Modes {
  LinearModel model;
  std::vector<NaturalMode> modes;  // ascending frequency, the rigid ones first
};

// A mode's shape in lengths that compare across its DOFs: x and y as they
// are, each rotation times the base radius of its gear (the motor's Rb1, the
// load's Rb2), the motion of a point of that base circle along the line of
// action; scaled so that its largest magnitude is 1 (the largest component
// keeps its positive sign). A mass-normalised shape mixes 1/sqrt(kg) and
// rad/(sqrt(kg) m), which a figure cannot put on one axis.
Eigen::VectorXd base_circle_shape(const LinearModel& model, const NaturalMode& mode);

// K v = w^2 M v by Eigen's GeneralizedSelfAdjointEigenSolver.
Modes natural_modes(const LinearModel& model);

// The case's modes at its mean mesh stiffness over the true period
// (MeshTables), after validate_fields. Throws as both.
Modes natural_modes(const SimulationCase& c);

// A mesh harmonic k f_m (f_m = Z1 n1, n1 the pinion's turns per second) at a
// natural frequency f: n1 = f / (k Z1).
struct CampbellCrossing {
  int harmonic = 0;      // k, from 1
  std::size_t mode = 0;  // index into Modes::modes
  double frequency_hz = 0.0;
  double pinion_speed_rad_per_s = 0.0;
};

// Every crossing of the harmonics 1..harmonics with the elastic modes at a
// pinion speed up to max_pinion_speed_rad_per_s, by harmonic then mode.
// Throws InputError unless teeth1 >= 1, harmonics >= 1, the speed > 0 and finite.
std::vector<CampbellCrossing> campbell_crossings(const Modes& modes, int teeth1, int harmonics,
                                                 double max_pinion_speed_rad_per_s);

}  // namespace gearimpact
