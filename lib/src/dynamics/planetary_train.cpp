// The rotational planetary stage as a train (planetary_train.hpp).
#include "gearimpact/dynamics/planetary_train.hpp"

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

namespace {

PlanetaryToothing toothing_of(const PlanetaryStage& stage) {
  const GearPair& g = stage.mesh.gears;
  return {g.module_m, g.pressure_angle_rad, g.addendum_coefficient};
}

std::vector<double> planet_angles(const PlanetaryStage& stage) {
  if (stage.planet_angles_rad.empty()) {
    if (stage.planets < 1 || stage.planets > kMaxTrainBodies - kFirstPlanetBody) {
      throw InputError("planets", std::to_string(stage.planets),
                       "1 to " + std::to_string(kMaxTrainBodies - kFirstPlanetBody) + " planets");
    }
    return equal_planet_angles(stage.teeth, toothing_of(stage), stage.planets);
  }
  const int n = static_cast<int>(stage.planet_angles_rad.size());
  if (n > kMaxTrainBodies - kFirstPlanetBody) {
    throw InputError("planet_angles", std::to_string(n) + " angles",
                     "1 to " + std::to_string(kMaxTrainBodies - kFirstPlanetBody) + " planets");
  }
  return checked_planet_angles(stage.teeth, toothing_of(stage), stage.planet_angles_rad);
}

void require_positive(const char* field, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InputError(field, value, "a finite value > 0");
  }
}

}  // namespace

StageSpeeds planetary_rigid_speeds(const PlanetaryStage& stage) {
  if (!std::isfinite(stage.input_speed_rad_per_s)) {
    throw InputError("input_speed", stage.input_speed_rad_per_s, "a finite value in rad/s");
  }
  return willis_speeds(stage.teeth, stage.held, stage.input_speed_rad_per_s);
}

GearTrain planetary_train(const PlanetaryStage& stage) {
  const PlanetaryToothing toothing = toothing_of(stage);
  if (stage.mesh.gears.profile_shift1 != 0.0 || stage.mesh.gears.profile_shift2 != 0.0) {
    throw InputError("profile_shift", "set", "0: the stage takes unshifted teeth");
  }
  // Refuses Z_r != Z_s + 2 Z_p (the two meshes at one centre distance).
  const double carrier_radius = standard_carrier_radius(stage.teeth, toothing);
  const WorkingAngles angles = working_angles(stage.teeth, toothing, carrier_radius);
  const std::vector<double> psi = planet_angles(stage);
  require_positive("sun_inertia", stage.sun_inertia_kg_m2);
  require_positive("ring_inertia", stage.ring_inertia_kg_m2);
  require_positive("carrier_inertia", stage.carrier_inertia_kg_m2);
  require_positive("planet_inertia", stage.planet_inertia_kg_m2);
  if (stage.planet_mass_kg) require_positive("planet_mass", *stage.planet_mass_kg);
  const StageSpeeds w = planetary_rigid_speeds(stage);
  const std::size_t n = psi.size();

  GearTrain train;
  const auto body = [](const char* name, double inertia, const Torque& torque, double speed) {
    TrainBody b;
    b.name = name;
    b.inertia_kg_m2 = inertia;
    b.torque = torque;
    b.w_rad_per_s = speed;
    return b;
  };
  double carrier_inertia = stage.carrier_inertia_kg_m2;
  if (stage.planet_mass_kg) {
    // The planets' orbits: m_p R_c^2 each about the housing's centre.
    carrier_inertia +=
        static_cast<double>(n) * *stage.planet_mass_kg * carrier_radius * carrier_radius;
  }
  train.bodies = {body("sun", stage.sun_inertia_kg_m2, stage.sun_torque, w.sun),
                  body("ring", stage.ring_inertia_kg_m2, stage.ring_torque, w.ring),
                  body("carrier", carrier_inertia, stage.carrier_torque, w.carrier)};
  const int held = stage.held == HeldMember::sun    ? kSunBody
                   : stage.held == HeldMember::ring ? kRingBody
                                                    : kCarrierBody;
  train.bodies[static_cast<std::size_t>(held)].held = true;
  for (std::size_t i = 0; i < n; ++i) {
    TrainBody p = body("planet", stage.planet_inertia_kg_m2, Torque{}, w.planet);
    p.name += std::to_string(i + 1);
    train.bodies.push_back(p);
  }

  // Phases (geometry/planetary.hpp), for the sun turning counter-clockwise
  // relative to the carrier: each mesh's pairs cross its pitch point when
  // Rb_s (theta_s - theta_c) + line_offset is a whole number of base pitches.
  const double t0 = base_pitch(stage.mesh.gears);
  const double gamma_rs = sun_ring_phase(stage.teeth, toothing, angles.sun_rad, angles.ring_rad);
  for (int internal = 0; internal < 2; ++internal) {
    for (std::size_t i = 0; i < n; ++i) {
      TrainMesh m;
      m.name = std::string(internal ? "ring_planet" : "sun_planet") + std::to_string(i + 1);
      m.carrier = kCarrierBody;
      m.body_a = internal ? kRingBody : kSunBody;
      m.body_b = kFirstPlanetBody + static_cast<int>(i);
      m.pair = stage.mesh;
      m.pair.gears.teeth1 = internal ? stage.teeth.ring : stage.teeth.sun;
      m.pair.gears.teeth2 = stage.teeth.planet;
      if (internal) {
        m.kind = TrainMesh::Kind::internal;
        m.pair.model.friction_coefficient = 0.0;
        m.pair.model.friction_law = FrictionLaw::constant;
        m.line_offset_m = (gamma_rs - ring_mesh_phase(stage.teeth.ring, psi[i])) * t0;
      } else {
        m.line_offset_m = -sun_mesh_phase(stage.teeth.sun, psi[i]) * t0;
      }
      train.meshes.push_back(m);
    }
  }
  train.integrator = stage.integrator;
  return train;
}

std::vector<double> planetary_ring_sensor(const PlanetaryStage& stage, const TrainResult& run,
                                          const signals::RingSensor& sensor) {
  const std::vector<double> psi = planet_angles(stage);
  const std::size_t n = psi.size();
  std::vector<std::vector<double>> forces(n);
  std::vector<double> carrier;
  carrier.reserve(run.series.size());
  for (std::vector<double>& f : forces) f.reserve(run.series.size());
  for (const TrainRow& row : run.series) {
    if (row.meshes.size() != 2 * n || row.theta_rad.size() != kFirstPlanetBody + n) {
      throw InputError("run",
                       std::to_string(row.theta_rad.size()) + " bodies and " +
                           std::to_string(row.meshes.size()) + " meshes",
                       "the stage's run: " + std::to_string(kFirstPlanetBody + n) + " bodies and " +
                           std::to_string(2 * n) + " meshes");
    }
    carrier.push_back(row.theta_rad[kCarrierBody]);
    for (std::size_t i = 0; i < n; ++i) {
      const TrainMeshRow& m = row.meshes[n + i];
      const double side = m.region == static_cast<int>(Region::n1)   ? 1.0
                          : m.region == static_cast<int>(Region::n2) ? -1.0
                                                                     : 0.0;
      forces[i].push_back(side * m.normal_force_n);
    }
  }
  return signals::ring_sensor_signal(forces, carrier, psi, sensor);
}

StageWillis planetary_willis(const PlanetaryStage& stage, const TrainResult& run) {
  const std::size_t bodies = kFirstPlanetBody + static_cast<std::size_t>(stage.planets);
  if (run.series.size() < 2 || run.series.front().theta_rad.size() != bodies ||
      run.series.back().theta_rad.size() != bodies) {
    throw InputError("run", std::to_string(run.series.size()) + " rows",
                     "the stage's run: two rows or more of " + std::to_string(bodies) + " bodies");
  }
  const TrainRow& first = run.series.front();
  const TrainRow& last = run.series.back();
  const double time = last.t_s - first.t_s;
  const auto mean = [&](int body) {
    const auto b = static_cast<std::size_t>(body);
    return (last.theta_rad[b] - first.theta_rad[b]) / time;
  };
  StageWillis w;
  w.sun_rad_per_s = mean(kSunBody);
  w.ring_rad_per_s = mean(kRingBody);
  w.carrier_rad_per_s = mean(kCarrierBody);
  const double sun = stage.teeth.sun * (w.sun_rad_per_s - w.carrier_rad_per_s);
  const double ring = stage.teeth.ring * (w.ring_rad_per_s - w.carrier_rad_per_s);
  const double scale = std::fabs(sun) + std::fabs(ring);
  // |sun + ring| <= scale: a stage turning as one block has both zero.
  w.residual = scale > 0.0 ? std::fabs(sun + ring) / scale : 0.0;
  return w;
}

}  // namespace gearimpact
