#include "gearimpact/modes/train_modes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"

namespace gearimpact {

namespace {

// The largest component by magnitude made positive.
void orient(Eigen::VectorXd& v) {
  Eigen::Index largest = 0;
  v.cwiseAbs().maxCoeff(&largest);
  if (v(largest) < 0.0) v = -v;
}

// The modes are those of the bodies' turning about fixed axes: a body on
// elastic bearings (its translation) is not in them yet, and is refused by
// name rather than left out.
void refuse_translating_bodies(const GearTrain& train) {
  for (const TrainBody& b : train.bodies) {
    if (!b.bearing) continue;
    throw InputError("bodies." + b.name + ".bearings", "given",
                     "none: a train's modes are those of its bodies turning about fixed axes "
                     "(a body's translation on its bearings is not in them yet)");
  }
}

}  // namespace

TrainLinearModel train_linear_model(const GearTrain& train,
                                    const std::vector<double>& mesh_stiffness_n_per_m) {
  check_train(train);
  refuse_translating_bodies(train);
  if (mesh_stiffness_n_per_m.size() != train.meshes.size()) {
    throw InputError("mesh_stiffness", std::to_string(mesh_stiffness_n_per_m.size()) + " values",
                     "one per mesh, " + std::to_string(train.meshes.size()));
  }
  TrainLinearModel model;
  model.body_dof = train_degrees_of_freedom(train);
  model.mesh_stiffness_n_per_m = mesh_stiffness_n_per_m;
  const Eigen::Index n = *std::max_element(model.body_dof.begin(), model.body_dof.end()) + 1;
  model.mass = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    model.mass(model.body_dof[i], model.body_dof[i]) += train.bodies[i].inertia_kg_m2;
  }
  model.stiffness = Eigen::MatrixXd::Zero(n, n);
  const auto dof = [&](int body) { return model.body_dof[static_cast<std::size_t>(body)]; };
  for (std::size_t k = 0; k < train.meshes.size(); ++k) {
    const TrainMesh& mesh = train.meshes[k];
    const double stiffness = mesh_stiffness_n_per_m[k];
    if (!std::isfinite(stiffness) || stiffness < 0.0) {
      throw InputError("meshes." + mesh.name + ".mesh_stiffness", stiffness,
                       "a finite value >= 0 in N/m");
    }
    // s = Rb_a theta_a - Rb_b theta_b, each angle in its body's forward sense.
    TrainSpring spring{TrainSpring::Kind::mesh, k, stiffness, Eigen::VectorXd::Zero(n)};
    spring.direction(dof(mesh.body_a)) += base_radius(mesh.pair.gears, Gear::one);
    spring.direction(dof(mesh.body_b)) -= base_radius(mesh.pair.gears, Gear::two);
    model.springs.push_back(std::move(spring));
  }
  for (std::size_t i = 0; i < train.shafts.size(); ++i) {
    const TrainShaft& shaft = train.shafts[i];
    if (shaft.kind != TrainShaft::Kind::torsional) continue;
    // Twisted by theta_a - theta_b.
    TrainSpring spring{TrainSpring::Kind::shaft, i, shaft.stiffness_n_m_per_rad,
                       Eigen::VectorXd::Zero(n)};
    spring.direction(dof(shaft.body_a)) += 1.0;
    spring.direction(dof(shaft.body_b)) -= 1.0;
    model.springs.push_back(std::move(spring));
  }
  for (const TrainSpring& s : model.springs) {
    model.stiffness += s.stiffness * s.direction * s.direction.transpose();
  }
  return model;
}

std::vector<double> mean_mesh_stiffnesses(const GearTrain& train) {
  check_train(train);
  std::vector<double> k;
  for (const TrainMesh& mesh : train.meshes) {
    const SimulationCase& c = mesh.pair;
    if (c.gears.helix_angle_rad != 0.0) throw_helical_not_taken(c.gears.helix_angle_rad, "modes");
    const MeshTables tables(c.gears, c.model.stiffness, c.faults, mesh.table);
    k.push_back(mean_mesh_stiffness_n_per_m(c, tables));
  }
  return k;
}

TrainModes train_modes(const TrainLinearModel& model) {
  const Eigen::Index n = model.mass.rows();
  // The groups the springs of k > 0 join, by union of their ends.
  std::vector<Eigen::Index> root(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) root[static_cast<std::size_t>(i)] = i;
  const auto find = [&](Eigen::Index i) {
    while (root[static_cast<std::size_t>(i)] != i) i = root[static_cast<std::size_t>(i)];
    return i;
  };
  std::vector<std::pair<Eigen::Index, Eigen::Index>> ends;  // of each spring
  for (const TrainSpring& s : model.springs) {
    Eigen::Index a = -1;
    Eigen::Index b = -1;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (s.direction(i) == 0.0) continue;
      (a < 0 ? a : b) = i;
    }
    ends.emplace_back(a, b);
    if (s.stiffness > 0.0 && a >= 0 && b >= 0) {
      const Eigen::Index ra = find(a);
      const Eigen::Index rb = find(b);
      root[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
    }
  }
  // Each group turned without deflecting its springs: from its first degree of
  // freedom at 1 along the springs, a . q = 0 giving the far end (a mesh's
  // Rb_a q_a = Rb_b q_b, a shaft's q_a = q_b). A loop whose ratios disagree
  // deflects a spring: that group has no rigid mode.
  std::vector<Eigen::VectorXd> rigid;
  std::vector<bool> done(static_cast<std::size_t>(n), false);
  for (Eigen::Index g = 0; g < n; ++g) {
    if (find(g) != g) continue;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    std::vector<bool> set(static_cast<std::size_t>(n), false);
    v(g) = 1.0;
    set[static_cast<std::size_t>(g)] = true;
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t k = 0; k < model.springs.size(); ++k) {
        const TrainSpring& s = model.springs[k];
        const auto [a, b] = ends[k];
        if (!(s.stiffness > 0.0) || a < 0 || b < 0) continue;
        const bool sa = set[static_cast<std::size_t>(a)];
        const bool sb = set[static_cast<std::size_t>(b)];
        if (sa == sb) continue;
        if (sa) {
          v(b) = -s.direction(a) * v(a) / s.direction(b);
        } else {
          v(a) = -s.direction(b) * v(b) / s.direction(a);
        }
        set[static_cast<std::size_t>(sa ? b : a)] = true;
        grew = true;
      }
    }
    bool consistent = true;
    for (std::size_t k = 0; k < model.springs.size(); ++k) {
      const TrainSpring& s = model.springs[k];
      const auto [a, b] = ends[k];
      if (!(s.stiffness > 0.0) || a < 0 || b < 0 || !set[static_cast<std::size_t>(a)]) continue;
      const double scale = std::fabs(s.direction(a) * v(a)) + std::fabs(s.direction(b) * v(b));
      if (std::fabs(s.direction.dot(v)) > 1e-12 * scale) consistent = false;
    }
    if (!consistent) continue;
    v /= std::sqrt(v.dot(model.mass * v));
    orient(v);
    rigid.push_back(v);
  }

  TrainModes result;
  result.model = model;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(model.stiffness,
                                                                         model.mass);
  if (solver.info() != Eigen::Success) {
    throw InputError("train", "its M and K", "a train whose modes Eigen's solver finds");
  }
  for (const Eigen::VectorXd& v : rigid) {
    TrainMode mode;
    mode.rigid = true;
    mode.shape = v;
    mode.energy_share.assign(model.springs.size(), 0.0);
    result.modes.push_back(std::move(mode));
  }
  // The solver's eigenvalues ascend; the lowest as many as there are rigid
  // modes are theirs (zero to rounding).
  for (Eigen::Index i = static_cast<Eigen::Index>(rigid.size()); i < n; ++i) {
    TrainMode mode;
    Eigen::VectorXd v = solver.eigenvectors().col(i);
    v /= std::sqrt(v.dot(model.mass * v));
    orient(v);
    const double w2 = v.dot(model.stiffness * v);
    mode.angular_frequency = std::sqrt(std::max(w2, 0.0));
    mode.frequency_hz = mode.angular_frequency / (2.0 * pi);
    mode.shape = v;
    for (const TrainSpring& s : model.springs) {
      const double d = s.direction.dot(v);
      mode.energy_share.push_back(w2 > 0.0 ? s.stiffness * d * d / w2 : 0.0);
    }
    result.modes.push_back(std::move(mode));
  }
  return result;
}

TrainModes train_modes(const GearTrain& train) {
  return train_modes(train_linear_model(train, mean_mesh_stiffnesses(train)));
}

Eigen::VectorXd body_shape(const TrainLinearModel& model, const TrainMode& mode) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(model.body_dof.size()));
  for (std::size_t i = 0; i < model.body_dof.size(); ++i) {
    v(static_cast<Eigen::Index>(i)) = mode.shape(model.body_dof[i]);
  }
  return v;
}

}  // namespace gearimpact
