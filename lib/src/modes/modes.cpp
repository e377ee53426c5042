#include "gearimpact/modes/modes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"

namespace gearimpact {

namespace {

void require_positive(const char* name, double value, const char* unit) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InputError(name, value, std::string("a finite value > 0 in ") + unit);
  }
}

// The index of `dof` in `dofs`; every caller asks for one the model has.
Eigen::Index index_of(const std::vector<Dof>& dofs, Dof dof) {
  return static_cast<Eigen::Index>(std::find(dofs.begin(), dofs.end(), dof) - dofs.begin());
}

}  // namespace

std::string_view dof_name(Dof dof) {
  switch (dof) {
    case Dof::x1:
      return "x1";
    case Dof::y1:
      return "y1";
    case Dof::theta1:
      return "theta1";
    case Dof::x2:
      return "x2";
    case Dof::y2:
      return "y2";
    case Dof::theta2:
      return "theta2";
    case Dof::theta_motor:
      return "theta_motor";
    case Dof::theta_load:
      return "theta_load";
  }
  return "";
}

bool is_rotation(Dof dof) {
  return dof == Dof::theta1 || dof == Dof::theta2 || dof == Dof::theta_motor ||
         dof == Dof::theta_load;
}

Eigen::VectorXd base_circle_shape(const LinearModel& model, const NaturalMode& mode) {
  Eigen::VectorXd v = mode.shape;
  for (std::size_t k = 0; k < model.dofs.size(); ++k) {
    const Dof dof = model.dofs[k];
    const bool pinion_side = dof == Dof::theta1 || dof == Dof::theta_motor;
    const bool wheel_side = dof == Dof::theta2 || dof == Dof::theta_load;
    const auto i = static_cast<Eigen::Index>(k);
    if (pinion_side) v(i) *= model.parameters.base_radius1_m;
    if (wheel_side) v(i) *= model.parameters.base_radius2_m;
  }
  const double largest = v.cwiseAbs().maxCoeff();
  return largest > 0.0 ? Eigen::VectorXd(v / largest) : v;
}

std::string_view part_name(SpringPart part) {
  switch (part) {
    case SpringPart::mesh:
      return "mesh";
    case SpringPart::bearing1:
      return "bearing1";
    case SpringPart::bearing2:
      return "bearing2";
    case SpringPart::motor_shaft:
      return "motor_shaft";
    case SpringPart::load_shaft:
      return "load_shaft";
  }
  return "";
}

LinearParameters linear_parameters(const SimulationCase& c, double mesh_stiffness_n_per_m) {
  LinearParameters p;
  p.base_radius1_m = base_radius(c.gears, Gear::one);
  p.base_radius2_m = base_radius(c.gears, Gear::two);
  p.working_pressure_angle_rad = operating_pressure_angle(c.gears);
  p.inertia1_kg_m2 = moment_of_inertia(c.gears, Gear::one);
  p.inertia2_kg_m2 = moment_of_inertia(c.gears, Gear::two);
  p.mesh_stiffness_n_per_m = mesh_stiffness_n_per_m;
  p.bearings = c.bearings.kind;
  const GearBearing* bearing[2] = {&c.bearings.gear1, &c.bearings.gear2};
  const Gear gear[2] = {Gear::one, Gear::two};
  for (std::size_t i = 0; i < 2; ++i) {
    p.mass_kg[i] = bearing[i]->mass_kg.value_or(disc_mass(c.gears, gear[i]));
    p.bearing_stiffness_x_n_per_m[i] = bearing[i]->stiffness_x_n_per_m;
    p.bearing_stiffness_y_n_per_m[i] = stiffness_y(*bearing[i]);
  }
  p.shafts = c.shafts.kind;
  p.motor_inertia_kg_m2 = c.shafts.motor_inertia_kg_m2;
  p.motor_stiffness_n_m_per_rad = c.shafts.motor_stiffness_n_m_per_rad;
  p.load_inertia_kg_m2 = c.shafts.load_inertia_kg_m2;
  p.load_stiffness_n_m_per_rad = c.shafts.load_stiffness_n_m_per_rad;
  return p;
}

LinearModel linear_model(const LinearParameters& p) {
  require_positive("base_radius1", p.base_radius1_m, "m");
  require_positive("base_radius2", p.base_radius2_m, "m");
  require_positive("inertia1", p.inertia1_kg_m2, "kg m^2");
  require_positive("inertia2", p.inertia2_kg_m2, "kg m^2");
  const double alpha = p.working_pressure_angle_rad;
  if (!std::isfinite(alpha) || alpha <= 0.0 || alpha >= 0.5 * pi) {
    throw InputError("working_pressure_angle", alpha, "an angle in (0, pi/2) rad");
  }
  if (!std::isfinite(p.mesh_stiffness_n_per_m) || p.mesh_stiffness_n_per_m < 0.0) {
    throw InputError("mesh_stiffness", p.mesh_stiffness_n_per_m, "a finite value >= 0 in N/m");
  }
  const bool planar = p.bearings == BearingKind::elastic;
  const bool shafts = p.shafts == ShaftKind::elastic;
  if (planar) {
    require_positive("mass1", p.mass_kg[0], "kg");
    require_positive("mass2", p.mass_kg[1], "kg");
    require_positive("stiffness_x1", p.bearing_stiffness_x_n_per_m[0], "N/m");
    require_positive("stiffness_y1", p.bearing_stiffness_y_n_per_m[0], "N/m");
    require_positive("stiffness_x2", p.bearing_stiffness_x_n_per_m[1], "N/m");
    require_positive("stiffness_y2", p.bearing_stiffness_y_n_per_m[1], "N/m");
  }
  if (shafts) {
    require_positive("motor_inertia", p.motor_inertia_kg_m2, "kg m^2");
    require_positive("motor_stiffness", p.motor_stiffness_n_m_per_rad, "N m/rad");
    require_positive("load_inertia", p.load_inertia_kg_m2, "kg m^2");
    require_positive("load_stiffness", p.load_stiffness_n_m_per_rad, "N m/rad");
  }

  LinearModel m;
  m.parameters = p;
  m.dofs = planar ? std::vector<Dof>{Dof::x1, Dof::y1, Dof::theta1, Dof::x2, Dof::y2, Dof::theta2}
                  : std::vector<Dof>{Dof::theta1, Dof::theta2};
  if (shafts) {
    m.dofs.push_back(Dof::theta_motor);
    m.dofs.push_back(Dof::theta_load);
  }
  const auto n = static_cast<Eigen::Index>(m.dofs.size());
  const auto at = [&](Dof dof) { return index_of(m.dofs, dof); };
  m.mass = Eigen::MatrixXd::Zero(n, n);
  m.mass(at(Dof::theta1), at(Dof::theta1)) = p.inertia1_kg_m2;
  m.mass(at(Dof::theta2), at(Dof::theta2)) = p.inertia2_kg_m2;
  if (planar) {
    for (Dof d : {Dof::x1, Dof::y1}) m.mass(at(d), at(d)) = p.mass_kg[0];
    for (Dof d : {Dof::x2, Dof::y2}) m.mass(at(d), at(d)) = p.mass_kg[1];
  }
  if (shafts) {
    m.mass(at(Dof::theta_motor), at(Dof::theta_motor)) = p.motor_inertia_kg_m2;
    m.mass(at(Dof::theta_load), at(Dof::theta_load)) = p.load_inertia_kg_m2;
  }

  const auto spring = [&](SpringPart part, double k,
                          std::initializer_list<std::pair<Dof, double>> terms) {
    LinearSpring s{part, k, Eigen::VectorXd::Zero(n)};
    for (const auto& [dof, a] : terms) s.direction(at(dof)) = a;
    m.springs.push_back(std::move(s));
  };
  // The drive line: s_d = Rb1 theta1 - Rb2 theta2 + (u1 - u2) . n1.
  const double sin_a = std::sin(alpha);
  const double cos_a = std::cos(alpha);
  if (planar) {
    spring(SpringPart::mesh, p.mesh_stiffness_n_per_m,
           {{Dof::x1, sin_a},
            {Dof::y1, cos_a},
            {Dof::theta1, p.base_radius1_m},
            {Dof::x2, -sin_a},
            {Dof::y2, -cos_a},
            {Dof::theta2, -p.base_radius2_m}});
    spring(SpringPart::bearing1, p.bearing_stiffness_x_n_per_m[0], {{Dof::x1, 1.0}});
    spring(SpringPart::bearing1, p.bearing_stiffness_y_n_per_m[0], {{Dof::y1, 1.0}});
    spring(SpringPart::bearing2, p.bearing_stiffness_x_n_per_m[1], {{Dof::x2, 1.0}});
    spring(SpringPart::bearing2, p.bearing_stiffness_y_n_per_m[1], {{Dof::y2, 1.0}});
  } else {
    spring(SpringPart::mesh, p.mesh_stiffness_n_per_m,
           {{Dof::theta1, p.base_radius1_m}, {Dof::theta2, -p.base_radius2_m}});
  }
  if (shafts) {
    // The motor turns with the pinion (about +z), the load with the wheel (about -z).
    spring(SpringPart::motor_shaft, p.motor_stiffness_n_m_per_rad,
           {{Dof::theta_motor, 1.0}, {Dof::theta1, -1.0}});
    spring(SpringPart::load_shaft, p.load_stiffness_n_m_per_rad,
           {{Dof::theta2, 1.0}, {Dof::theta_load, -1.0}});
  }
  m.stiffness = Eigen::MatrixXd::Zero(n, n);
  for (const LinearSpring& s : m.springs) {
    m.stiffness += s.stiffness * s.direction * s.direction.transpose();
  }
  // Every bearing spring is > 0, so only rotations are free: the whole train
  // through the mesh, or each gear with its shaft without it.
  m.rigid_modes = p.mesh_stiffness_n_per_m > 0.0 ? 1 : 2;
  return m;
}

Modes natural_modes(const LinearModel& model) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(model.stiffness,
                                                                         model.mass);
  if (solver.info() != Eigen::Success) {
    throw Error("the generalised eigenproblem K v = w^2 M v did not converge");
  }
  Modes result;
  result.model = model;
  const Eigen::Index n = solver.eigenvalues().size();
  for (Eigen::Index i = 0; i < n; ++i) {
    NaturalMode mode;
    mode.rigid = static_cast<std::size_t>(i) < model.rigid_modes;
    mode.shape = solver.eigenvectors().col(i);
    Eigen::Index largest = 0;
    mode.shape.cwiseAbs().maxCoeff(&largest);
    if (mode.shape(largest) < 0.0) mode.shape = -mode.shape;
    if (!mode.rigid) {
      std::array<double, kSpringParts> energy{};
      double total = 0.0;
      for (const LinearSpring& s : model.springs) {
        const double deflection = s.direction.dot(mode.shape);
        const double e = s.stiffness * deflection * deflection;
        energy[static_cast<std::size_t>(s.part)] += e;
        total += e;
      }
      for (std::size_t part = 0; part < kSpringParts; ++part) {
        mode.energy_share[part] = energy[part] / total;
      }
      // w^2 = v^T K v, the springs' energy summed: the eigenvalue's own
      // rounding then never makes a frequency of a mode with energy NaN.
      mode.angular_frequency = std::sqrt(total);
      mode.frequency_hz = mode.angular_frequency / (2.0 * pi);
    }
    result.modes.push_back(std::move(mode));
  }
  return result;
}

Modes natural_modes(const SimulationCase& c) {
  if (c.gears.helix_angle_rad != 0.0) {
    // A helical pair: its transverse section at the mean of the pair table
    // its run reads, on rigid or elastic bearings (docs/helical.md, Dynamics
    // and The planar model); faults take no helical pair yet.
    if (!c.faults.empty()) {
      throw_helical_not_taken(c.gears.helix_angle_rad, "modes with faults");
    }
    validate_fields(c);
    const SimulationCase d = dynamics_case(c);
    return natural_modes(
        linear_model(linear_parameters(d, mean_mesh_stiffness_n_per_m(d, *run_table(c)))));
  }
  validate_fields(c);
  const MeshTables tables(c.gears, c.model.stiffness, c.faults);
  return natural_modes(linear_model(linear_parameters(c, mean_mesh_stiffness_n_per_m(c, tables))));
}

std::vector<CampbellCrossing> campbell_crossings(const Modes& modes, int teeth1, int harmonics,
                                                 double max_pinion_speed_rad_per_s) {
  if (teeth1 < 1) throw InputError("teeth1", teeth1, "an integer >= 1");
  if (harmonics < 1) throw InputError("harmonics", harmonics, "an integer >= 1");
  require_positive("max_pinion_speed", max_pinion_speed_rad_per_s, "rad/s");
  std::vector<CampbellCrossing> crossings;
  for (int k = 1; k <= harmonics; ++k) {
    for (std::size_t i = 0; i < modes.modes.size(); ++i) {
      const NaturalMode& mode = modes.modes[i];
      if (mode.rigid) continue;
      // k Z1 w1 / (2 pi) = f.
      const double speed = mode.angular_frequency / (static_cast<double>(k) * teeth1);
      if (speed <= max_pinion_speed_rad_per_s) {
        crossings.push_back({k, i, mode.frequency_hz, speed});
      }
    }
  }
  return crossings;
}

}  // namespace gearimpact
