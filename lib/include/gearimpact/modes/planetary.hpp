// The linear planetary stage of Lin & Parker (1999) (docs/planetary.md): sun,
// ring, carrier and N planets at angles psi_n, each with x, y and u = r theta
// (r the base radius; the carrier's R_c, the planets' centre circle radius),
// the planets' translations zeta_n, eta_n radial and tangential in the
// carrier's axes at psi_n; supports, planet bearings and the two meshes as
// springs along their lines at a stationary carrier. M, K, the natural
// frequencies and shapes, the type of each mode (rotational, translational,
// planet) and the strain energy in each mesh, bearing and support.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <string_view>
#include <vector>

namespace gearimpact {

// A central member's inertia and supports.
struct CentralMember {
  double mass_kg = 0.0;
  double rotational_mass_kg = 0.0;         // I / r^2
  double support_stiffness_n_per_m = 0.0;  // k on x and on y (isotropic)
  double torsional_support_n_per_m = 0.0;  // k_u = k_theta / r^2
};

// Everything the model reads, SI. Identical planets; the planets' angles set
// equal or unequal spacing.
struct PlanetaryParameters {
  CentralMember sun;
  CentralMember ring;
  CentralMember carrier;
  double planet_mass_kg = 0.0;
  double planet_rotational_mass_kg = 0.0;         // I_p / r_p^2
  std::vector<double> planet_angles_rad;          // psi_n, psi_1 = 0, increasing, < 2 pi
  double planet_bearing_stiffness_n_per_m = 0.0;  // k_p, radial and tangential
  double sun_mesh_stiffness_n_per_m = 0.0;        // k_sp
  double ring_mesh_stiffness_n_per_m = 0.0;       // k_rp
  double sun_pressure_angle_rad = 0.0;            // alpha_s
  double ring_pressure_angle_rad = 0.0;           // alpha_r
};

// The coordinates: carrier, ring, sun (x, y, u each), then planet n's
// (zeta, eta, u). Index of member coordinate j (0 x/zeta, 1 y/eta, 2 u).
enum class StageMember { carrier, ring, sun };
Eigen::Index central_index(StageMember member, int coordinate);
Eigen::Index planet_index(int planet, int coordinate);  // planet from 0

// Where a spring stores its strain energy.
enum class StageSpring {
  sun_mesh,        // of planet `planet`
  ring_mesh,       // of planet `planet`
  planet_bearing,  // radial and tangential, of planet `planet`
  sun_support,     // x, y and u
  ring_support,
  carrier_support,
};
std::string_view stage_spring_name(StageSpring kind);

struct StageSpringTerm {
  StageSpring kind;
  int planet = -1;  // 0-based for the per-planet springs, else -1
  double stiffness = 0.0;
  Eigen::VectorXd direction;  // a: its deflection a . q
};

struct PlanetaryModel {
  PlanetaryParameters parameters;
  Eigen::MatrixXd mass;       // diag(m, m, I/r^2) per member
  Eigen::MatrixXd stiffness;  // sum of k a a^T over `springs`
  std::vector<StageSpringTerm> springs;
};

// M and K. Throws InputError naming the parameter unless masses are > 0,
// stiffnesses >= 0, the pressure angles in (0, pi/2) and the angles increasing
// in [0, 2 pi) from 0.
PlanetaryModel planetary_model(const PlanetaryParameters& p);

// The mode types of Lin & Parker (1999): rotational (no central translation,
// every planet alike), translational (no central rotation), planet (central
// members still); `mixed` when none holds (unequal spacing, unlike supports).
enum class StageModeType { rotational, translational, planet, mixed };
std::string_view stage_mode_type_name(StageModeType type);

struct StageMode {
  double angular_frequency = 0.0;  // rad/s; 0 for a rigid mode
  double frequency_hz = 0.0;
  bool rigid = false;            // no strain energy
  std::size_t multiplicity = 1;  // of its frequency (the cluster it belongs to)
  StageModeType type = StageModeType::mixed;
  Eigen::VectorXd shape;  // v^T M v = 1
  // v^T K v shared among the springs (in the order of PlanetaryModel::springs),
  // summing to 1; all 0 for a rigid mode.
  std::vector<double> energy_share;
};

struct PlanetaryModes {
  PlanetaryModel model;
  std::vector<StageMode> modes;  // ascending frequency
};

// K v = w^2 M v (Eigen's generalised self-adjoint solver). Frequencies within
// 1e-7 relative (or, below, 1e-9 of the largest w^2) form one cluster; in each
// cluster the shapes are rebased so that the planet, then the rotational, then
// the translational subspace of its eigenspace are spanned by their own shapes.
PlanetaryModes planetary_modes(const PlanetaryModel& model);

// The largest magnitude, over the coordinates a type requires to vanish, of
// v relative to v's largest component (the planets-alike differences for a
// rotational mode included).
double type_residual(const PlanetaryModel& model, const Eigen::VectorXd& v, StageModeType type);

}  // namespace gearimpact
