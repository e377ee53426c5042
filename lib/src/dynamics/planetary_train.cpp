// The rotational planetary stage as a train (planetary_train.hpp).
#include "gearimpact/dynamics/planetary_train.hpp"

#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/geometry/train_teeth.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

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

// A stage's number against its row of the stage file ("stage.KEY").
void check_stage_value(const char* key, double value) {
  check_train_value(std::string("stage.") + key, value, key);
}

// The members' tooth-0 angles relative to the carrier (planetary_train.hpp) on
// the rigid stage whose sun has turned phi relative to the carrier: the
// planets and the ring turn -Z_s / Z_p and -Z_s / Z_r times that (Willis).
struct ToothZero {
  double sun = 0.0;
  double planet = 0.0;
  double ring = 0.0;
};
ToothZero tooth_zero(const PlanetaryTeeth& z, double gamma_sn, double gamma_rs, double phi) {
  return {phi - pi / (2.0 * z.sun),
          pi - pi / (2.0 * z.planet) + 2.0 * pi * gamma_sn / z.planet - phi * z.sun / z.planet,
          -pi / (2.0 * z.ring) - 2.0 * pi * gamma_rs / z.ring - phi * z.sun / z.ring};
}

// How planet n's two meshes number the stage's teeth: each mesh's own count
// (tooth_identity.hpp) of a member's tooth t is (offset + sense t) mod z.
struct MeshNumbering {
  int sun_offset = 0;             // at the sun mesh, sense +1
  int planet_at_sun_offset = 0;   // sense -1
  int planet_at_ring_offset = 0;  // sense -1
  int ring_offset = 0;            // sense -1
};

// Half a mesh period after a pitch-point crossing of each mesh, where the
// stage's count (stage_mesh_teeth, the tooth whose centre line crossed the
// line of centres last, a quarter period before or after) and the mesh's own
// (mesh_teeth_at) each name one tooth, a quarter period from either's change.
MeshNumbering mesh_numbering(const PlanetaryStage& stage, double psi, double gamma_sn,
                             double gamma_rn, double gamma_rs) {
  const PlanetaryTeeth& z = stage.teeth;
  MeshNumbering m;
  GearPair sun_pair = stage.mesh.gears;
  sun_pair.teeth1 = z.sun;
  sun_pair.teeth2 = z.planet;
  // The sun mesh's line sees the sun at phi - 2 pi gamma_sn / Z_s.
  double phi = 2.0 * pi * (gamma_sn + 0.5) / z.sun;
  ToothZero at = tooth_zero(z, gamma_sn, gamma_rs, phi);
  StageMeshTeeth stage_teeth = stage_mesh_teeth(z, psi, at.sun, at.planet, at.ring);
  TeethInContact own = mesh_teeth_at(sun_pair, phi - 2.0 * pi * gamma_sn / z.sun);
  m.sun_offset = own.pinion_tooth - stage_teeth.sun;
  m.planet_at_sun_offset = own.wheel_tooth + stage_teeth.planet_at_sun;
  // The ring mesh's line sees the planet (its gear 1) at Z_s phi / Z_p + 2 pi (gamma_rs -
  // gamma_rn) / Z_p, the ring as its gear 2.
  GearPair ring_pair = stage.mesh.gears;
  ring_pair.teeth1 = z.planet;
  ring_pair.teeth2 = z.ring;
  phi = 2.0 * pi * (0.5 - gamma_rs + gamma_rn) / z.sun;
  at = tooth_zero(z, gamma_sn, gamma_rs, phi);
  stage_teeth = stage_mesh_teeth(z, psi, at.sun, at.planet, at.ring);
  own = mesh_teeth_at(ring_pair,
                      phi * z.sun / z.planet + 2.0 * pi * (gamma_rs - gamma_rn) / z.planet);
  m.planet_at_ring_offset = own.pinion_tooth + stage_teeth.planet_at_ring;
  m.ring_offset = own.wheel_tooth + stage_teeth.ring;
  return m;
}

// The stage's faults checked, each by its own key faults[i].KEY, before any mesh is built.
void check_stage_faults(const PlanetaryStage& stage, std::size_t planets) {
  const PlanetaryTeeth& z = stage.teeth;
  GearPair sun_pair = stage.mesh.gears;
  sun_pair.teeth1 = z.sun;
  sun_pair.teeth2 = z.planet;
  for (std::size_t i = 0; i < stage.faults.size(); ++i) {
    const StageFault& f = stage.faults[i];
    const std::string name = "faults[" + std::to_string(i) + "]";
    if (f.member == FaultMember::planet &&
        (f.planet < 1 || static_cast<std::size_t>(f.planet) > planets)) {
      throw InputError(name + ".member", "planet" + std::to_string(f.planet),
                       "sun, ring or planet1 to planet" + std::to_string(planets));
    }
    const int teeth = f.member == FaultMember::sun      ? z.sun
                      : f.member == FaultMember::planet ? z.planet
                                                        : z.ring;
    if (f.tooth < 0 || f.tooth >= teeth) {
      throw InputError(name + ".tooth", f.tooth,
                       "0 to " + std::to_string(teeth - 1) + ", a tooth of its member");
    }
    for (std::size_t j = 0; j < i; ++j) {
      const StageFault& g = stage.faults[j];
      if (g.member == f.member && g.tooth == f.tooth &&
          (f.member != FaultMember::planet || g.planet == f.planet)) {
        throw InputError(name + ".tooth", f.tooth,
                         "a tooth not already faulted: faults[" + std::to_string(j) + "] is on it");
      }
    }
    if (f.member == FaultMember::ring) {
      if (f.state.kind != ToothKind::missing) {
        throw InputError(name + ".kind", "not missing",
                         "missing: a ring tooth can only be missing (the ring meshes' ISO "
                         "6336-1 table has no tooth profile for a crack, a spall or a chip)");
      }
      continue;
    }
    // A sun or a planet tooth on the sun meshes' pair: the pair's own checks (the crack fits its
    // tooth, ...), named under the stage's fault.
    try {
      check_tooth_faults(
          sun_pair, stage.mesh.model.stiffness,
          {ToothFault{f.member == FaultMember::sun ? Gear::one : Gear::two, 0, f.state}});
    } catch (const InputError& e) {
      std::vector<Problem> problems;
      for (const Problem& p : e.problems()) {
        std::string field = p.field;
        if (field.rfind("faults[0]", 0) == 0) field = name + field.substr(9);
        problems.push_back(p.renamed(field, p.value));
      }
      throw InputError(std::move(problems));
    }
  }
}

// The planar stage's keys, each by its own name.
void check_supports(const PlanetaryStage& stage) {
  const StageSupports& k = *stage.supports;
  if (!stage.planet_mass_kg) {
    throw InputError("planet_mass", "absent",
                     "a mass > 0 kg with the stage's supports (each planet's centre translates "
                     "on its bearing)");
  }
  for (const auto& [key, value] :
       {std::pair<const char*, double>{"sun_mass", k.sun_mass_kg},
        {"ring_mass", k.ring_mass_kg},
        {"carrier_mass", k.carrier_mass_kg},
        {"planet_bearing", k.planet_bearing_n_per_m},
        {"sun_support", k.sun_support_n_per_m},
        {"ring_support", k.ring_support_n_per_m},
        {"carrier_support", k.carrier_support_n_per_m},
        {"sun_support_damping", k.sun_support_damping_n_s_per_m},
        {"ring_support_damping", k.ring_support_damping_n_s_per_m},
        {"carrier_support_damping", k.carrier_support_damping_n_s_per_m},
        {"planet_bearing_damping", k.planet_bearing_damping_n_s_per_m}}) {
    check_stage_value(key, value);
  }
}

}  // namespace

StageSpeeds planetary_rigid_speeds(const PlanetaryStage& stage) {
  check_stage_value("input_speed", stage.input_speed_rad_per_s);
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
  check_stage_value("sun_inertia", stage.sun_inertia_kg_m2);
  check_stage_value("ring_inertia", stage.ring_inertia_kg_m2);
  check_stage_value("carrier_inertia", stage.carrier_inertia_kg_m2);
  check_stage_value("planet_inertia", stage.planet_inertia_kg_m2);
  if (stage.planet_mass_kg) check_stage_value("planet_mass", *stage.planet_mass_kg);
  const StageSpeeds w = planetary_rigid_speeds(stage);
  const std::size_t n = psi.size();
  if (!stage.mesh.faults.empty()) {
    // One pair's faults would land on every mesh alike: a stage's are its members'.
    throw InputError("mesh.faults", std::to_string(stage.mesh.faults.size()) + " faults",
                     "none: a stage's faulted teeth are its faults, by member");
  }
  check_stage_faults(stage, n);

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
  if (stage.supports) check_supports(stage);
  if (stage.planet_mass_kg && !stage.supports) {
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
    if (stage.supports) {
      p.bearing = GearBearing{};
      p.bearing->stiffness_x_n_per_m = stage.supports->planet_bearing_n_per_m;
      p.bearing->damping_x_n_s_per_m = stage.supports->planet_bearing_damping_n_s_per_m;
      p.bearing->mass_kg = *stage.planet_mass_kg;
      p.pin = TrainBody::Pin{kCarrierBody, carrier_radius, psi[i]};
    }
    train.bodies.push_back(p);
  }
  if (stage.supports) {
    const StageSupports& k = *stage.supports;
    const auto support = [&](int member, double mass, double stiffness, double damping) {
      GearBearing b;
      b.stiffness_x_n_per_m = stiffness;
      b.damping_x_n_s_per_m = damping;
      b.mass_kg = mass;
      train.bodies[static_cast<std::size_t>(member)].bearing = b;
    };
    support(kSunBody, k.sun_mass_kg, k.sun_support_n_per_m, k.sun_support_damping_n_s_per_m);
    support(kRingBody, k.ring_mass_kg, k.ring_support_n_per_m, k.ring_support_damping_n_s_per_m);
    support(kCarrierBody, k.carrier_mass_kg, k.carrier_support_n_per_m,
            k.carrier_support_damping_n_s_per_m);
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
      const double gamma_sn = sun_mesh_phase(stage.teeth.sun, psi[i]);
      const double gamma_rn = ring_mesh_phase(stage.teeth.ring, psi[i]);
      if (internal) {
        m.kind = TrainMesh::Kind::internal;
        m.pair.model.friction_coefficient = 0.0;
        m.pair.model.friction_law = FrictionLaw::constant;
        m.line_offset_m = (gamma_rs - gamma_rn) * t0;
      } else {
        m.line_offset_m = -gamma_sn * t0;
      }
      m.pair.faults.clear();
      if (!stage.faults.empty()) {
        const MeshNumbering number = mesh_numbering(stage, psi[i], gamma_sn, gamma_rn, gamma_rs);
        const int planet = static_cast<int>(i) + 1;
        for (const StageFault& f : stage.faults) {
          if (f.member == FaultMember::planet && f.planet != planet) continue;
          const bool missing = f.state.kind == ToothKind::missing;
          ToothFault t;
          t.state = f.state;
          if (!internal && f.member == FaultMember::sun) {
            t.gear = Gear::one;
            t.tooth = tooth_number(number.sun_offset + f.tooth, stage.teeth.sun);
          } else if (!internal && f.member == FaultMember::planet) {
            t.gear = Gear::two;
            t.tooth = tooth_number(number.planet_at_sun_offset - f.tooth, stage.teeth.planet);
          } else if (internal && f.member == FaultMember::ring) {
            t.gear = Gear::one;
            t.tooth = tooth_number(number.ring_offset - f.tooth, stage.teeth.ring);
          } else if (internal && f.member == FaultMember::planet && missing) {
            // A missing planet tooth is gone from both flanks; its other faults act on the sun
            // mesh's flank only (the ring mesh's table has no tooth profile).
            t.gear = Gear::two;
            t.tooth = tooth_number(number.planet_at_ring_offset - f.tooth, stage.teeth.planet);
          } else {
            continue;
          }
          m.pair.faults.push_back(t);
        }
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

std::vector<StageMeshTeeth> planetary_mesh_teeth(const PlanetaryStage& stage, const TrainRow& row) {
  const std::vector<double> psi = planet_angles(stage);
  const std::size_t n = psi.size();
  if (row.theta_rad.size() != kFirstPlanetBody + n) {
    throw InputError(
        "row", std::to_string(row.theta_rad.size()) + " bodies",
        "a row of the stage's run: " + std::to_string(kFirstPlanetBody + n) + " bodies");
  }
  const PlanetaryToothing toothing = toothing_of(stage);
  const double carrier_radius = standard_carrier_radius(stage.teeth, toothing);
  const WorkingAngles angles = working_angles(stage.teeth, toothing, carrier_radius);
  const double gamma_rs = sun_ring_phase(stage.teeth, toothing, angles.sun_rad, angles.ring_rad);
  const double carrier = row.theta_rad[kCarrierBody];
  std::vector<StageMeshTeeth> teeth;
  teeth.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    // The teeth 0 where every body is at angle 0 (tooth_zero at phi = 0), carried on by each
    // body's own turn relative to the carrier in the row, the meshes' deflections included.
    const ToothZero at =
        tooth_zero(stage.teeth, sun_mesh_phase(stage.teeth.sun, psi[i]), gamma_rs, 0.0);
    teeth.push_back(stage_mesh_teeth(stage.teeth, psi[i],
                                     at.sun + row.theta_rad[kSunBody] - carrier,
                                     at.planet + row.theta_rad[kFirstPlanetBody + i] - carrier,
                                     at.ring + row.theta_rad[kRingBody] - carrier));
  }
  return teeth;
}

std::vector<StageTeethRow> planetary_teeth_series(const PlanetaryStage& stage,
                                                  const TrainResult& run) {
  std::vector<StageTeethRow> rows;
  rows.reserve(run.series.size());
  for (const TrainRow& row : run.series)
    rows.push_back({row.t_s, planetary_mesh_teeth(stage, row)});
  return rows;
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
