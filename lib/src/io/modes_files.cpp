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

std::string mode_shapes_csv(const Modes& modes) {
  std::string out = "mode,rigid,frequency_hz";
  for (Dof dof : modes.model.dofs) out += "," + base_circle_column(dof);
  out += "\n";
  for (std::size_t i = 0; i < modes.modes.size(); ++i) {
    const NaturalMode& m = modes.modes[i];
    out += std::to_string(i + 1) + (m.rigid ? ",true," : ",false,") +
           format_data_number(m.frequency_hz);
    const Eigen::VectorXd v = base_circle_shape(modes.model, m);
    for (Eigen::Index k = 0; k < v.size(); ++k) out += "," + format_data_number(v(k));
    out += "\n";
  }
  return out;
}

std::string modes_csv(const Modes& modes) {
  std::string out = "mode,rigid,frequency_hz,angular_frequency_rad_per_s";
  for (std::size_t part = 0; part < kSpringParts; ++part) {
    out += ",share_" + std::string(part_name(static_cast<SpringPart>(part)));
  }
  for (Dof dof : modes.model.dofs) out += "," + shape_column(dof);
  out += "\n";
  for (std::size_t i = 0; i < modes.modes.size(); ++i) {
    const NaturalMode& m = modes.modes[i];
    out += std::to_string(i + 1) + (m.rigid ? ",true," : ",false,") +
           format_data_number(m.frequency_hz) + "," + format_data_number(m.angular_frequency);
    for (double share : m.energy_share) out += "," + format_data_number(share);
    for (Eigen::Index k = 0; k < m.shape.size(); ++k) out += "," + format_data_number(m.shape(k));
    out += "\n";
  }
  return out;
}

std::string campbell_csv(const std::vector<CampbellCrossing>& crossings) {
  std::string out = "harmonic,mode,frequency_hz,pinion_speed_rad_per_s,pinion_speed_rpm\n";
  for (const CampbellCrossing& c : crossings) {
    out += std::to_string(c.harmonic) + "," + std::to_string(c.mode + 1) + "," +
           format_data_number(c.frequency_hz) + "," + format_data_number(c.pinion_speed_rad_per_s) +
           "," + format_data_number(c.pinion_speed_rad_per_s * kRpm) + "\n";
  }
  return out;
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

}  // namespace gearimpact
