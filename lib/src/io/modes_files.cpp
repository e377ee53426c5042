#include "gearimpact/io/modes_files.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/named_values.hpp"

namespace gearimpact {

namespace {

using Json = nlohmann::ordered_json;

constexpr double kRpm = 60.0 / (2.0 * pi);

// The unit of a mass-normalised shape's component: v^T M v = 1 in kg m^2 / rad^2 and kg.
std::string shape_column(Dof dof) {
  return std::string(dof_name(dof)) + (is_rotation(dof) ? "_rad_per_sqrt_kg_m" : "_per_sqrt_kg");
}

// A base-circle shape's column: a rotation named with the base radius it is scaled by.
std::string base_circle_column(Dof dof) {
  switch (dof) {
    case Dof::theta1:
      return "rb1_theta1";
    case Dof::theta2:
      return "rb2_theta2";
    case Dof::theta_motor:
      return "rb1_theta_motor";
    case Dof::theta_load:
      return "rb2_theta_load";
    default:
      return std::string(dof_name(dof));
  }
}

}  // namespace

std::vector<ModeRow> mode_rows(const Modes& modes) {
  std::vector<ModeRow> rows;
  for (std::size_t i = 0; i < modes.modes.size(); ++i) {
    rows.push_back(
        {static_cast<int>(i + 1), modes.modes[i], base_circle_shape(modes.model, modes.modes[i])});
  }
  return rows;
}

Columns<ModeRow> mode_shapes_columns(const LinearModel& model) {
  Columns<ModeRow> columns{
      computed_column<ModeRow>(
          "mode", "", [](const ModeRow& r) { return static_cast<double>(r.number); }, true),
      boolean_column<ModeRow>("rigid", [](const ModeRow& r) { return r.mode.rigid; }),
      computed_column<ModeRow>("frequency_hz", "Hz",
                               [](const ModeRow& r) { return r.mode.frequency_hz; })};
  for (std::size_t k = 0; k < model.dofs.size(); ++k) {
    columns.push_back(computed_column<ModeRow>(
        base_circle_column(model.dofs[k]), "",
        [k](const ModeRow& r) { return r.base_circle(static_cast<Eigen::Index>(k)); }));
  }
  return columns;
}

std::string mode_shapes_csv(const Modes& modes) {
  return csv_of(mode_shapes_columns(modes.model), mode_rows(modes));
}

Columns<ModeRow> modes_columns(const LinearModel& model) {
  Columns<ModeRow> columns{
      computed_column<ModeRow>(
          "mode", "", [](const ModeRow& r) { return static_cast<double>(r.number); }, true),
      boolean_column<ModeRow>("rigid", [](const ModeRow& r) { return r.mode.rigid; }),
      computed_column<ModeRow>("frequency_hz", "Hz",
                               [](const ModeRow& r) { return r.mode.frequency_hz; }),
      computed_column<ModeRow>("angular_frequency_rad_per_s", "rad/s",
                               [](const ModeRow& r) { return r.mode.angular_frequency; })};
  for (std::size_t part = 0; part < kSpringParts; ++part) {
    columns.push_back(computed_column<ModeRow>(
        "share_" + std::string(part_name(static_cast<SpringPart>(part))), "",
        [part](const ModeRow& r) { return r.mode.energy_share[part]; }));
  }
  for (std::size_t k = 0; k < model.dofs.size(); ++k) {
    columns.push_back(computed_column<ModeRow>(
        shape_column(model.dofs[k]), "",
        [k](const ModeRow& r) { return r.mode.shape(static_cast<Eigen::Index>(k)); }));
  }
  return columns;
}

std::string modes_csv(const Modes& modes) {
  return csv_of(modes_columns(modes.model), mode_rows(modes));
}

Columns<CampbellCrossing> campbell_columns() {
  using C = CampbellCrossing;
  return {computed_column<C>(
              "harmonic", "", [](const C& c) { return static_cast<double>(c.harmonic); }, true),
          computed_column<C>(
              "mode", "", [](const C& c) { return static_cast<double>(c.mode + 1); }, true),
          member_column("frequency_hz", "Hz", &C::frequency_hz),
          member_column("pinion_speed_rad_per_s", "rad/s", &C::pinion_speed_rad_per_s),
          computed_column<C>("pinion_speed_rpm", "rpm",
                             [](const C& c) { return c.pinion_speed_rad_per_s * kRpm; })};
}

std::string campbell_csv(const std::vector<CampbellCrossing>& crossings) {
  return csv_of(campbell_columns(), crossings);
}

std::string modes_summary_json(const ModesSummary& s, const Modes& modes,
                               const std::vector<CampbellCrossing>& crossings) {
  const LinearModel& m = modes.model;
  Json j;
  j["case"] = s.case_name;
  Json dofs = Json::array();
  for (Dof dof : m.dofs) dofs.push_back(std::string(dof_name(dof)));
  j["dofs"] = dofs;
  const LinearParameters& p = m.parameters;
  j["mean_mesh_stiffness_n_per_m"] = p.mesh_stiffness_n_per_m;
  j["working_pressure_angle_rad"] = p.working_pressure_angle_rad;
  // The torsional model's one elastic mode, the limit of rigid bearings.
  const double me =
      effective_mass_kg(p.base_radius1_m, p.inertia1_kg_m2, p.base_radius2_m, p.inertia2_kg_m2);
  j["effective_mass_kg"] = me;
  j["torsional_frequency_hz"] = std::sqrt(p.mesh_stiffness_n_per_m / me) / (2.0 * pi);
  j["rigid_modes"] = m.rigid_modes;
  Json frequencies = Json::array();
  for (const NaturalMode& mode : modes.modes) {
    if (!mode.rigid) frequencies.push_back(mode.frequency_hz);
  }
  j["natural_frequencies_hz"] = frequencies;
  j["teeth1"] = s.teeth1;
  j["harmonics"] = s.harmonics;
  j["max_pinion_speed_rad_per_s"] = s.max_pinion_speed_rad_per_s;
  j["max_pinion_speed_rpm"] = s.max_pinion_speed_rad_per_s * kRpm;
  j["crossings"] = crossings.size();
  return j.dump(2) + "\n";
}

std::vector<StageModeRow> stage_mode_rows(const PlanetaryModes& modes) {
  std::vector<StageModeRow> rows;
  const std::vector<StageSpringTerm>& springs = modes.model.springs;
  for (std::size_t i = 0; i < modes.modes.size(); ++i) {
    const StageMode& mode = modes.modes[i];
    StageModeRow row;
    row.number = static_cast<int>(i) + 1;
    row.frequency_hz = mode.frequency_hz;
    row.multiplicity = static_cast<int>(mode.multiplicity);
    row.rigid = mode.rigid;
    row.type = mode.type;
    for (std::size_t s = 0; s < springs.size() && s < mode.energy_share.size(); ++s) {
      for (std::size_t k = 0; k < kStageSpringKindCount; ++k) {
        if (springs[s].kind == kStageSpringKinds[k]) row.share[k] += mode.energy_share[s];
      }
    }
    rows.push_back(row);
  }
  return rows;
}

Columns<StageModeRow> stage_modes_columns() {
  Columns<StageModeRow> columns;
  columns.push_back(member_column<StageModeRow>("mode", &StageModeRow::number));
  columns.push_back(member_column<StageModeRow>("frequency_hz", "Hz", &StageModeRow::frequency_hz));
  columns.push_back(member_column<StageModeRow>("multiplicity", &StageModeRow::multiplicity));
  columns.push_back(
      boolean_column<StageModeRow>("rigid", [](const StageModeRow& r) { return r.rigid; }));
  columns.push_back(text_column<StageModeRow>(
      "type", [](const StageModeRow& r) { return std::string(stage_mode_type_name(r.type)); }));
  for (std::size_t k = 0; k < kStageSpringKindCount; ++k) {
    columns.push_back(computed_column<StageModeRow>(
        "share_" + std::string(stage_spring_name(kStageSpringKinds[k])), "",
        [k](const StageModeRow& r) { return r.share[k]; }));
  }
  return columns;
}

std::string stage_modes_summary_json(const std::string& case_name, const PlanetaryModes& modes) {
  const PlanetaryModel& m = modes.model;
  Json j;
  j["case"] = case_name;
  j["planets"] = m.parameters.planet_angles_rad.size();
  Json angles = Json::array();
  for (double psi : m.parameters.planet_angles_rad) angles.push_back(psi);
  j["planet_angles_rad"] = angles;
  j["dofs"] = m.mass.rows();
  std::size_t rigid = 0;
  for (const StageMode& mode : modes.modes) rigid += mode.rigid ? 1 : 0;
  j["rigid_modes"] = rigid;
  // One entry per distinct frequency (a cluster's modes are consecutive, its multiplicity >= 1).
  Json distinct = Json::array();
  for (std::size_t i = 0; i < modes.modes.size(); i += modes.modes[i].multiplicity) {
    const StageMode& mode = modes.modes[i];
    Json entry;
    entry["frequency_hz"] = mode.frequency_hz;
    entry["multiplicity"] = mode.multiplicity;
    // The cluster's types, each once ("translational"; "planet+rotational" where two
    // types meet at one frequency).
    std::string types;
    for (std::size_t k = i; k < i + mode.multiplicity && k < modes.modes.size(); ++k) {
      const std::string type(stage_mode_type_name(modes.modes[k].type));
      if (("+" + types + "+").find("+" + type + "+") == std::string::npos) {
        types += (types.empty() ? "" : "+") + type;
      }
    }
    entry["type"] = types;
    distinct.push_back(entry);
  }
  j["frequencies"] = distinct;
  return j.dump(2) + "\n";
}

std::vector<TrainModeRow> train_mode_rows(const TrainModes& modes) {
  std::vector<TrainModeRow> rows;
  for (std::size_t i = 0; i < modes.modes.size(); ++i) {
    rows.push_back(
        {static_cast<int>(i + 1), modes.modes[i], body_shape(modes.model, modes.modes[i])});
  }
  return rows;
}

Columns<TrainModeRow> train_modes_columns(const GearTrain& train) {
  Columns<TrainModeRow> columns;
  columns.push_back(member_column<TrainModeRow>("mode", &TrainModeRow::number));
  columns.push_back(
      boolean_column<TrainModeRow>("rigid", [](const TrainModeRow& r) { return r.mode.rigid; }));
  columns.push_back(computed_column<TrainModeRow>(
      "frequency_hz", "Hz", [](const TrainModeRow& r) { return r.mode.frequency_hz; }));
  columns.push_back(computed_column<TrainModeRow>(
      "angular_frequency_rad_per_s", "rad/s",
      [](const TrainModeRow& r) { return r.mode.angular_frequency; }));
  // The springs' order of train_linear_model: the meshes, then the torsional shafts.
  std::size_t spring = 0;
  for (const TrainMesh& mesh : train.meshes) {
    columns.push_back(
        computed_column<TrainModeRow>("share_" + mesh.name, "", [spring](const TrainModeRow& r) {
          return r.mode.energy_share.empty() ? 0.0 : r.mode.energy_share[spring];
        }));
    ++spring;
  }
  for (const TrainShaft& shaft : train.shafts) {
    if (shaft.kind != TrainShaft::Kind::torsional) continue;
    const std::string name = "share_shaft_" +
                             train.bodies[static_cast<std::size_t>(shaft.body_a)].name + "_" +
                             train.bodies[static_cast<std::size_t>(shaft.body_b)].name;
    columns.push_back(computed_column<TrainModeRow>(name, "", [spring](const TrainModeRow& r) {
      return r.mode.energy_share.empty() ? 0.0 : r.mode.energy_share[spring];
    }));
    ++spring;
  }
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    const auto at = static_cast<Eigen::Index>(i);
    columns.push_back(computed_column<TrainModeRow>(
        "theta_" + train.bodies[i].name + "_rad_per_sqrt_kg_m", "rad/(sqrt(kg) m)",
        [at](const TrainModeRow& r) { return r.body_shape(at); }));
  }
  return columns;
}

std::string train_modes_summary_json(const std::string& case_name, const GearTrain& train,
                                     const TrainModes& modes) {
  Json j;
  j["case"] = case_name;
  j["angles"] = "each body's forward sense: a mesh deflects by Rb_a theta_a - Rb_b theta_b";
  Json bodies = Json::array();
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    Json b;
    b["name"] = train.bodies[i].name;
    b["inertia_kg_m2"] = train.bodies[i].inertia_kg_m2;
    b["dof"] = modes.model.body_dof[i];
    bodies.push_back(b);
  }
  j["bodies"] = bodies;
  j["dofs"] = modes.model.mass.rows();
  Json meshes = Json::array();
  for (std::size_t k = 0; k < train.meshes.size(); ++k) {
    Json m;
    m["name"] = train.meshes[k].name;
    m["mesh_stiffness_n_per_m"] = modes.model.mesh_stiffness_n_per_m[k];
    meshes.push_back(m);
  }
  j["meshes"] = meshes;
  std::size_t rigid = 0;
  Json frequencies = Json::array();
  for (const TrainMode& mode : modes.modes) {
    if (mode.rigid) {
      ++rigid;
    } else {
      frequencies.push_back(mode.frequency_hz);
    }
  }
  j["rigid_modes"] = rigid;
  j["frequencies_hz"] = frequencies;
  return j.dump(2) + "\n";
}

}  // namespace gearimpact
