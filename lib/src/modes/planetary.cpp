#include "gearimpact/modes/planetary.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

void require_positive(const std::string& name, double value, const char* unit) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InputError(name, value, std::string("a finite value > 0 in ") + unit);
  }
}

void require_non_negative(const std::string& name, double value, const char* unit) {
  if (!std::isfinite(value) || value < 0.0) {
    throw InputError(name, value, std::string("a finite value >= 0 in ") + unit);
  }
}

void require_member(const std::string& name, const CentralMember& m) {
  require_positive(name + "_mass", m.mass_kg, "kg");
  require_positive(name + "_rotational_mass", m.rotational_mass_kg, "kg (I / r^2)");
  require_non_negative(name + "_support_stiffness", m.support_stiffness_n_per_m, "N/m");
  require_non_negative(name + "_torsional_support", m.torsional_support_n_per_m,
                       "N/m (k_theta / r^2)");
}

void require_angle(const std::string& name, double alpha) {
  if (!std::isfinite(alpha) || alpha <= 0.0 || alpha >= 0.5 * pi) {
    throw InputError(name, alpha, "an angle in (0, pi/2) rad");
  }
}

Eigen::Index planets_of(const PlanetaryModel& model) {
  return static_cast<Eigen::Index>(model.parameters.planet_angles_rad.size());
}

// The rows whose product with a shape must vanish for a mode of `type`.
Eigen::MatrixXd type_constraints(const PlanetaryModel& model, StageModeType type) {
  const Eigen::Index n = model.mass.rows();
  const Eigen::Index planets = planets_of(model);
  std::vector<Eigen::VectorXd> rows;
  const auto select = [&](Eigen::Index i) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
    r(i) = 1.0;
    rows.push_back(r);
  };
  const StageMember members[3] = {StageMember::carrier, StageMember::ring, StageMember::sun};
  switch (type) {
    case StageModeType::planet:
      for (StageMember m : members) {
        for (int j = 0; j < 3; ++j) select(central_index(m, j));
      }
      break;
    case StageModeType::rotational:
      for (StageMember m : members) {
        for (int j = 0; j < 2; ++j) select(central_index(m, j));
      }
      for (Eigen::Index p = 1; p < planets; ++p) {
        for (int j = 0; j < 3; ++j) {
          Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
          r(planet_index(static_cast<int>(p), j)) = 1.0;
          r(planet_index(0, j)) = -1.0;
          rows.push_back(r);
        }
      }
      break;
    case StageModeType::translational:
      for (StageMember m : members) select(central_index(m, 2));
      break;
    case StageModeType::mixed:
      break;
  }
  Eigen::MatrixXd c(static_cast<Eigen::Index>(rows.size()), n);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    c.row(static_cast<Eigen::Index>(i)) = rows[i].transpose();
  }
  return c;
}

}  // namespace

Eigen::Index central_index(StageMember member, int coordinate) {
  return 3 * static_cast<Eigen::Index>(member) + coordinate;
}

Eigen::Index planet_index(int planet, int coordinate) {
  return 9 + 3 * static_cast<Eigen::Index>(planet) + coordinate;
}

std::string_view stage_spring_name(StageSpring kind) {
  switch (kind) {
    case StageSpring::sun_mesh:
      return "sun_mesh";
    case StageSpring::ring_mesh:
      return "ring_mesh";
    case StageSpring::planet_bearing:
      return "planet_bearing";
    case StageSpring::sun_support:
      return "sun_support";
    case StageSpring::ring_support:
      return "ring_support";
    case StageSpring::carrier_support:
      return "carrier_support";
  }
  return "";
}

std::string_view stage_mode_type_name(StageModeType type) {
  switch (type) {
    case StageModeType::rotational:
      return "rotational";
    case StageModeType::translational:
      return "translational";
    case StageModeType::planet:
      return "planet";
    case StageModeType::mixed:
      return "mixed";
  }
  return "";
}

// K = sum over the springs of k a a^T, each storing k (a . q)^2 / 2 with
// a . q (Lin & Parker 1999; docs/planetary.md, the linear model):
//   sun-planet n   -x_s sin(psi_n - a_s) + y_s cos(psi_n - a_s) - zeta_n sin a_s
//                  - eta_n cos a_s + u_s + u_n
//   ring-planet n  -x_r sin(psi_n + a_r) + y_r cos(psi_n + a_r) + zeta_n sin a_r
//                  - eta_n cos a_r + u_r - u_n
//   bearing n, radial       x_c cos psi_n + y_c sin psi_n - zeta_n
//   bearing n, tangential  -x_c sin psi_n + y_c cos psi_n + u_c - eta_n
// and each central member's supports on x, y (k) and u (k_u).
PlanetaryModel planetary_model(const PlanetaryParameters& p) {
  require_member("sun", p.sun);
  require_member("ring", p.ring);
  require_member("carrier", p.carrier);
  require_positive("planet_mass", p.planet_mass_kg, "kg");
  require_positive("planet_rotational_mass", p.planet_rotational_mass_kg, "kg (I / r^2)");
  require_non_negative("planet_bearing_stiffness", p.planet_bearing_stiffness_n_per_m, "N/m");
  require_non_negative("sun_mesh_stiffness", p.sun_mesh_stiffness_n_per_m, "N/m");
  require_non_negative("ring_mesh_stiffness", p.ring_mesh_stiffness_n_per_m, "N/m");
  require_angle("sun_pressure_angle", p.sun_pressure_angle_rad);
  require_angle("ring_pressure_angle", p.ring_pressure_angle_rad);
  if (p.planet_angles_rad.empty()) {
    throw InputError("planet_angles", "[]", "at least one planet angle");
  }
  for (std::size_t i = 0; i < p.planet_angles_rad.size(); ++i) {
    const double psi = p.planet_angles_rad[i];
    if (!std::isfinite(psi) || psi < 0.0 || psi >= 2.0 * pi || (i == 0 && psi != 0.0) ||
        (i > 0 && psi <= p.planet_angles_rad[i - 1])) {
      throw InputError("planet_angles[" + std::to_string(i + 1) + "]", psi,
                       "increasing angles in [0, 2 pi) rad, the first 0");
    }
  }

  PlanetaryModel m;
  m.parameters = p;
  const int planets = static_cast<int>(p.planet_angles_rad.size());
  const Eigen::Index n = 9 + 3 * static_cast<Eigen::Index>(planets);
  m.mass = Eigen::MatrixXd::Zero(n, n);
  const auto member_mass = [&](StageMember member, const CentralMember& c) {
    m.mass(central_index(member, 0), central_index(member, 0)) = c.mass_kg;
    m.mass(central_index(member, 1), central_index(member, 1)) = c.mass_kg;
    m.mass(central_index(member, 2), central_index(member, 2)) = c.rotational_mass_kg;
  };
  member_mass(StageMember::carrier, p.carrier);
  member_mass(StageMember::ring, p.ring);
  member_mass(StageMember::sun, p.sun);
  for (int q = 0; q < planets; ++q) {
    m.mass(planet_index(q, 0), planet_index(q, 0)) = p.planet_mass_kg;
    m.mass(planet_index(q, 1), planet_index(q, 1)) = p.planet_mass_kg;
    m.mass(planet_index(q, 2), planet_index(q, 2)) = p.planet_rotational_mass_kg;
  }

  const auto spring = [&](StageSpring kind, int planet, double k,
                          std::initializer_list<std::pair<Eigen::Index, double>> terms) {
    StageSpringTerm s{kind, planet, k, Eigen::VectorXd::Zero(n)};
    for (const auto& [i, a] : terms) s.direction(i) += a;
    m.springs.push_back(std::move(s));
  };
  const auto supports = [&](StageSpring kind, StageMember member, const CentralMember& c) {
    spring(kind, -1, c.support_stiffness_n_per_m, {{central_index(member, 0), 1.0}});
    spring(kind, -1, c.support_stiffness_n_per_m, {{central_index(member, 1), 1.0}});
    spring(kind, -1, c.torsional_support_n_per_m, {{central_index(member, 2), 1.0}});
  };
  supports(StageSpring::carrier_support, StageMember::carrier, p.carrier);
  supports(StageSpring::ring_support, StageMember::ring, p.ring);
  supports(StageSpring::sun_support, StageMember::sun, p.sun);

  const double as = p.sun_pressure_angle_rad;
  const double ar = p.ring_pressure_angle_rad;
  const auto s = [](StageMember member, int j) { return central_index(member, j); };
  for (int q = 0; q < planets; ++q) {
    const double psi = p.planet_angles_rad[static_cast<std::size_t>(q)];
    spring(StageSpring::sun_mesh, q, p.sun_mesh_stiffness_n_per_m,
           {{s(StageMember::sun, 0), -std::sin(psi - as)},
            {s(StageMember::sun, 1), std::cos(psi - as)},
            {planet_index(q, 0), -std::sin(as)},
            {planet_index(q, 1), -std::cos(as)},
            {s(StageMember::sun, 2), 1.0},
            {planet_index(q, 2), 1.0}});
    spring(StageSpring::ring_mesh, q, p.ring_mesh_stiffness_n_per_m,
           {{s(StageMember::ring, 0), -std::sin(psi + ar)},
            {s(StageMember::ring, 1), std::cos(psi + ar)},
            {planet_index(q, 0), std::sin(ar)},
            {planet_index(q, 1), -std::cos(ar)},
            {s(StageMember::ring, 2), 1.0},
            {planet_index(q, 2), -1.0}});
    spring(StageSpring::planet_bearing, q, p.planet_bearing_stiffness_n_per_m,
           {{s(StageMember::carrier, 0), std::cos(psi)},
            {s(StageMember::carrier, 1), std::sin(psi)},
            {planet_index(q, 0), -1.0}});
    spring(StageSpring::planet_bearing, q, p.planet_bearing_stiffness_n_per_m,
           {{s(StageMember::carrier, 0), -std::sin(psi)},
            {s(StageMember::carrier, 1), std::cos(psi)},
            {s(StageMember::carrier, 2), 1.0},
            {planet_index(q, 1), -1.0}});
  }
  m.stiffness = Eigen::MatrixXd::Zero(n, n);
  for (const StageSpringTerm& t : m.springs) {
    m.stiffness += t.stiffness * t.direction * t.direction.transpose();
  }
  return m;
}

double type_residual(const PlanetaryModel& model, const Eigen::VectorXd& v, StageModeType type) {
  if (type == StageModeType::mixed) return 0.0;
  const double largest = v.cwiseAbs().maxCoeff();
  if (largest == 0.0) return 0.0;
  return (type_constraints(model, type) * v).cwiseAbs().maxCoeff() / largest;
}

PlanetaryModes planetary_modes(const PlanetaryModel& model) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(model.stiffness,
                                                                         model.mass);
  if (solver.info() != Eigen::Success) {
    throw Error("the generalised eigenproblem K v = w^2 M v did not converge");
  }
  PlanetaryModes result;
  result.model = model;
  const Eigen::VectorXd& lambda = solver.eigenvalues();
  const Eigen::MatrixXd& vectors = solver.eigenvectors();
  const Eigen::Index n = lambda.size();
  const double largest = std::max(lambda.cwiseAbs().maxCoeff(), 0.0);
  const auto is_rigid = [&](double l) { return l <= 1e-9 * largest; };
  // The classification's tolerance on |C v| relative to v's largest column
  // norm: far above the solver's rounding (about 1e-13 here) and far below a
  // coordinate that truly moves.
  constexpr double kVanishing = 1e-7;
  const StageModeType order[3] = {StageModeType::planet, StageModeType::rotational,
                                  StageModeType::translational};

  Eigen::Index first = 0;
  while (first < n) {
    Eigen::Index last = first + 1;
    while (last < n) {
      const double a = lambda(last - 1);
      const double b = lambda(last);
      const bool both_rigid = is_rigid(a) && is_rigid(b);
      // w within 1e-7 relative: w^2 within 2e-7.
      const bool close = !is_rigid(a) && !is_rigid(b) && b - a <= 2e-7 * b;
      if (!both_rigid && !close) break;
      ++last;
    }
    const Eigen::Index size = last - first;
    Eigen::MatrixXd basis = vectors.middleCols(first, size);
    std::vector<std::pair<StageModeType, Eigen::VectorXd>> typed;
    for (StageModeType type : order) {
      if (basis.cols() == 0) break;
      const Eigen::MatrixXd c = type_constraints(model, type) * basis;
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(c, Eigen::ComputeFullV);
      const Eigen::VectorXd& sigma = svd.singularValues();
      const double scale = basis.colwise().norm().maxCoeff();
      std::vector<Eigen::Index> null;
      std::vector<Eigen::Index> rest;
      for (Eigen::Index j = 0; j < basis.cols(); ++j) {
        const double s = j < sigma.size() ? sigma(j) : 0.0;
        (s <= kVanishing * scale ? null : rest).push_back(j);
      }
      for (Eigen::Index j : null) typed.emplace_back(type, basis * svd.matrixV().col(j));
      Eigen::MatrixXd remaining(basis.rows(), static_cast<Eigen::Index>(rest.size()));
      for (std::size_t k = 0; k < rest.size(); ++k) {
        remaining.col(static_cast<Eigen::Index>(k)) = basis * svd.matrixV().col(rest[k]);
      }
      basis = remaining;
    }
    for (Eigen::Index j = 0; j < basis.cols(); ++j) {
      typed.emplace_back(StageModeType::mixed, basis.col(j));
    }
    for (auto& [type, v] : typed) {
      StageMode mode;
      mode.type = type;
      mode.multiplicity = static_cast<std::size_t>(size);
      mode.rigid = is_rigid(lambda(first));
      Eigen::Index at = 0;
      v.cwiseAbs().maxCoeff(&at);
      mode.shape = v(at) < 0.0 ? Eigen::VectorXd(-v) : v;
      mode.energy_share.assign(model.springs.size(), 0.0);
      if (!mode.rigid) {
        double total = 0.0;
        for (std::size_t k = 0; k < model.springs.size(); ++k) {
          const double d = model.springs[k].direction.dot(mode.shape);
          mode.energy_share[k] = model.springs[k].stiffness * d * d;
          total += mode.energy_share[k];
        }
        for (double& e : mode.energy_share) e /= total;
        // w^2 = v^T K v, the springs' energies summed.
        mode.angular_frequency = std::sqrt(total);
        mode.frequency_hz = mode.angular_frequency / (2.0 * pi);
      }
      result.modes.push_back(std::move(mode));
    }
    first = last;
  }
  return result;
}

}  // namespace gearimpact
