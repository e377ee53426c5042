#include "gearimpact/io/results.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <map>
#include <string>
#include <tuple>

#include "gearimpact/constants.hpp"

namespace gearimpact {

std::string format_data_number(double value) {
  std::string out;
  append_real(out, value);
  return out;
}

Columns<SeriesRow> series_columns() {
  return {member_column("t_s", "s", &SeriesRow::t_s),
          member_column("theta1_rad", "rad", &SeriesRow::theta1_rad),
          member_column("theta2_rad", "rad", &SeriesRow::theta2_rad),
          member_column("w1_rad_s", "rad/s", &SeriesRow::w1_rad_per_s),
          member_column("w2_rad_s", "rad/s", &SeriesRow::w2_rad_per_s),
          member_column("s_m", "m", &SeriesRow::s_m),
          member_column("delta_m", "m", &SeriesRow::delta_m),
          member_column("region", &SeriesRow::region),
          member_column("pairs", &SeriesRow::pairs),
          member_column("normal_force_N", "N", &SeriesRow::normal_force_n),
          member_column("friction_force_N", "N", &SeriesRow::friction_force_n)};
}

std::string series_csv_header() {
  return csv_header(series_columns());
}

void append_series_row(std::string& out, const SeriesRow& r) {
  static const Columns<SeriesRow> columns = series_columns();
  append_csv_row(out, columns, r);
}

Columns<SampleRow> sample_columns() {
  return {member_column("t_s", "s", &SampleRow::t_s),
          member_column("theta1_rad", "rad", &SampleRow::theta1_rad),
          member_column("theta2_rad", "rad", &SampleRow::theta2_rad),
          member_column("w1_rad_s", "rad/s", &SampleRow::w1_rad_per_s),
          member_column("w2_rad_s", "rad/s", &SampleRow::w2_rad_per_s),
          member_column("w1_dot_rad_s2", "rad/s^2", &SampleRow::acceleration1_rad_per_s2),
          member_column("w2_dot_rad_s2", "rad/s^2", &SampleRow::acceleration2_rad_per_s2),
          member_column("s_m", "m", &SampleRow::s_m),
          member_column("dte_m", "m", &SampleRow::dte_m),
          member_column("normal_force_n1_N", "N", &SampleRow::normal_force_n1_n),
          member_column("normal_force_n2_N", "N", &SampleRow::normal_force_n2_n),
          member_column("region", &SampleRow::region),
          member_column("pairs", &SampleRow::pairs)};
}

std::string samples_csv_header() {
  return csv_header(sample_columns());
}

void append_sample_row(std::string& out, const SampleRow& r) {
  static const Columns<SampleRow> columns = sample_columns();
  append_csv_row(out, columns, r);
}

namespace {

// The planar state's columns, in the order both planar tables share after t_s: the positions,
// their rates, the motor's and the load's angles and speeds. A member of the row's state,
// which a view by the row's stride cannot reach: computed.
template <typename Row>
void add_planar_state(Columns<Row>& columns) {
  const auto state = [&](const char* name, const char* unit, double PlanarState::*member) {
    columns.push_back(
        computed_column<Row>(name, unit, [member](const Row& r) { return r.state.*member; }));
  };
  state("x1_m", "m", &PlanarState::x1_m);
  state("y1_m", "m", &PlanarState::y1_m);
  state("theta1_rad", "rad", &PlanarState::theta1_rad);
  state("x2_m", "m", &PlanarState::x2_m);
  state("y2_m", "m", &PlanarState::y2_m);
  state("theta2_rad", "rad", &PlanarState::theta2_rad);
  state("vx1_m_s", "m/s", &PlanarState::vx1_m_s);
  state("vy1_m_s", "m/s", &PlanarState::vy1_m_s);
  state("w1_rad_s", "rad/s", &PlanarState::w1_rad_per_s);
  state("vx2_m_s", "m/s", &PlanarState::vx2_m_s);
  state("vy2_m_s", "m/s", &PlanarState::vy2_m_s);
  state("w2_rad_s", "rad/s", &PlanarState::w2_rad_per_s);
  state("theta_motor_rad", "rad", &PlanarState::theta_motor_rad);
  state("theta_load_rad", "rad", &PlanarState::theta_load_rad);
  state("w_motor_rad_s", "rad/s", &PlanarState::w_motor_rad_per_s);
  state("w_load_rad_s", "rad/s", &PlanarState::w_load_rad_per_s);
}

}  // namespace

Columns<PlanarRow> planar_series_columns(bool helical) {
  Columns<PlanarRow> columns{member_column("t_s", "s", &PlanarRow::t_s)};
  add_planar_state(columns);
  for (auto column : {member_column("bearing_fx1_N", "N", &PlanarRow::bearing_fx1_n),
                      member_column("bearing_fy1_N", "N", &PlanarRow::bearing_fy1_n),
                      member_column("bearing_fx2_N", "N", &PlanarRow::bearing_fx2_n),
                      member_column("bearing_fy2_N", "N", &PlanarRow::bearing_fy2_n),
                      member_column("drive_force_N", "N", &PlanarRow::drive_force_n),
                      member_column("coast_force_N", "N", &PlanarRow::coast_force_n),
                      member_column("drive_penetration_m", "m", &PlanarRow::drive_penetration_m),
                      member_column("coast_penetration_m", "m", &PlanarRow::coast_penetration_m)}) {
    columns.push_back(std::move(column));
  }
  if (!helical) return columns;
  for (auto column :
       {member_column("axial_force1_N", "N", &PlanarRow::axial_force1_n),
        member_column("axial_force2_N", "N", &PlanarRow::axial_force2_n),
        member_column("tilting_moment1_N_m", "N*m", &PlanarRow::tilting_moment1_n_m),
        member_column("tilting_moment2_N_m", "N*m", &PlanarRow::tilting_moment2_n_m)}) {
    columns.push_back(std::move(column));
  }
  return columns;
}

std::string planar_series_csv_header(bool helical) {
  return csv_header(planar_series_columns(helical));
}

void append_planar_row(std::string& out, const PlanarRow& r, bool helical) {
  static const Columns<PlanarRow> spur = planar_series_columns(false);
  static const Columns<PlanarRow> with_thrust = planar_series_columns(true);
  append_csv_row(out, helical ? with_thrust : spur, r);
}

Columns<PlanarSample> planar_sample_columns() {
  using S = PlanarSample;
  Columns<S> columns{member_column("t_s", "s", &S::t_s)};
  add_planar_state(columns);
  for (auto column :
       {member_column("ax1_m_per_s2", "m/s^2", &S::ax1_m_per_s2),
        member_column("ay1_m_per_s2", "m/s^2", &S::ay1_m_per_s2),
        member_column("alpha1_rad_per_s2", "rad/s^2", &S::alpha1_rad_per_s2),
        member_column("ax2_m_per_s2", "m/s^2", &S::ax2_m_per_s2),
        member_column("ay2_m_per_s2", "m/s^2", &S::ay2_m_per_s2),
        member_column("alpha2_rad_per_s2", "rad/s^2", &S::alpha2_rad_per_s2),
        member_column("bearing_fx1_N", "N", &S::bearing_fx1_n),
        member_column("bearing_fy1_N", "N", &S::bearing_fy1_n),
        member_column("bearing_fx2_N", "N", &S::bearing_fx2_n),
        member_column("bearing_fy2_N", "N", &S::bearing_fy2_n),
        member_column("dte_m", "m", &S::dte_m),
        member_column("drive_force_N", "N", &S::drive_force_n),
        member_column("coast_force_N", "N", &S::coast_force_n),
        member_column("sensor_acceleration_m_per_s2", "m/s^2", &S::sensor_acceleration_m_per_s2)}) {
    columns.push_back(std::move(column));
  }
  return columns;
}

std::string planar_samples_csv_header() {
  return csv_header(planar_sample_columns());
}

void append_planar_sample(std::string& out, const PlanarSample& r) {
  static const Columns<PlanarSample> columns = planar_sample_columns();
  append_csv_row(out, columns, r);
}

std::string series_csv(const std::vector<SeriesRow>& rows) {
  std::string out = series_csv_header();
  out.reserve(out.size() + rows.size() * 220);
  for (const SeriesRow& r : rows) append_series_row(out, r);
  return out;
}

namespace {

void json_number(std::string& out, const char* key, double value, bool last = false) {
  out += "  \"";
  out += key;
  out += "\": ";
  append_real(out, value);
  out += last ? "\n" : ",\n";
}

// A JSON string literal: quotes, backslashes and control characters escaped.
std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      char buffer[8];
      std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(ch));
      out += buffer;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

void json_optional(std::string& out, const char* key, const std::optional<double>& value) {
  if (value) {
    json_number(out, key, *value);
  } else {
    out += std::string("  \"") + key + "\": null,\n";
  }
}

// The energy ledger's terms of a run, two-gear or train: kinetic and stored energy at both
// ends, the torques' work, the losses and the parametric work.
void json_energy_terms(std::string& out, const SimulationSummary& s) {
  json_number(out, "kinetic_energy_initial_J", s.kinetic_energy_initial_j);
  json_number(out, "kinetic_energy_final_J", s.kinetic_energy_final_j);
  json_number(out, "stored_energy_initial_J", s.stored_energy_initial_j);
  json_number(out, "stored_energy_final_J", s.stored_energy_final_j);
  json_number(out, "torque_work_J", s.torque_work_j);
  json_number(out, "damping_loss_J", s.damping_loss_j);
  json_number(out, "friction_loss_J", s.friction_loss_j);
  // The viscous mesh damper's loss, its own term of the ledger (damping_loss_J
  // is the Hertzian damping's of (32)); only with a damper, so that other
  // runs' summaries keep their bytes.
  if (s.mesh_damper) json_number(out, "mesh_damper_loss_J", s.mesh_damping_loss_j);
  json_number(out, "parametric_work_J", s.parametric_work_j);
  json_number(out, "parametric_jump_work_J", s.parametric_jump_work_j);
}

// How well the ledger closed: its residual at the end and its largest, and its scale.
void json_ledger_residual(std::string& out, const SimulationSummary& s) {
  json_number(out, "ledger_residual_J", s.ledger_residual_j);
  json_number(out, "ledger_residual_max_J", s.ledger_residual_max_j);
  json_number(out, "ledger_scale_J", s.ledger_scale_j);
}

}  // namespace

Columns<TrainRow> train_series_columns(const GearTrain& train) {
  Columns<TrainRow> columns{member_column("t_s", "s", &TrainRow::t_s)};
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    const std::string& body = train.bodies[i].name;
    columns.push_back(computed_column<TrainRow>("theta_" + body + "_rad", "rad",
                                                [i](const TrainRow& r) { return r.theta_rad[i]; }));
    columns.push_back(computed_column<TrainRow>(
        "w_" + body + "_rad_per_s", "rad/s", [i](const TrainRow& r) { return r.w_rad_per_s[i]; }));
  }
  for (std::size_t k = 0; k < train.meshes.size(); ++k) {
    const std::string& mesh = train.meshes[k].name;
    columns.push_back(computed_column<TrainRow>(
        "s_" + mesh + "_m", "m", [k](const TrainRow& r) { return r.meshes[k].s_m; }));
    columns.push_back(computed_column<TrainRow>(
        "delta_" + mesh + "_m", "m", [k](const TrainRow& r) { return r.meshes[k].delta_m; }));
    columns.push_back(computed_column<TrainRow>(
        "region_" + mesh, "",
        [k](const TrainRow& r) { return static_cast<double>(r.meshes[k].region); }, true));
    columns.push_back(computed_column<TrainRow>(
        "pairs_" + mesh, "",
        [k](const TrainRow& r) { return static_cast<double>(r.meshes[k].pairs); }, true));
    columns.push_back(
        computed_column<TrainRow>("normal_force_" + mesh + "_N", "N",
                                  [k](const TrainRow& r) { return r.meshes[k].normal_force_n; }));
    columns.push_back(
        computed_column<TrainRow>("friction_force_" + mesh + "_N", "N",
                                  [k](const TrainRow& r) { return r.meshes[k].friction_force_n; }));
  }
  // A body on elastic bearings: its centre and its bearings' force, after the
  // meshes' columns, so that a train without bearings keeps its columns.
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    if (!train.bodies[i].bearing) continue;
    const std::string& body = train.bodies[i].name;
    columns.push_back(computed_column<TrainRow>(
        "x_" + body + "_m", "m", [i](const TrainRow& r) { return r.centres[i].x_m; }));
    columns.push_back(computed_column<TrainRow>(
        "y_" + body + "_m", "m", [i](const TrainRow& r) { return r.centres[i].y_m; }));
    columns.push_back(
        computed_column<TrainRow>("bearing_fx_" + body + "_N", "N",
                                  [i](const TrainRow& r) { return r.centres[i].bearing_fx_n; }));
    columns.push_back(
        computed_column<TrainRow>("bearing_fy_" + body + "_N", "N",
                                  [i](const TrainRow& r) { return r.centres[i].bearing_fy_n; }));
  }
  if (train.sensor_body >= 0) {
    columns.push_back(member_column("sensor_acceleration_m_per_s2", "m/s^2",
                                    &TrainRow::sensor_acceleration_m_per_s2));
  }
  return columns;
}

std::string train_series_csv(const GearTrain& train, const std::vector<TrainRow>& rows) {
  return csv_of(train_series_columns(train), rows);
}

namespace {

// A train's summary; with `willis`, a stage's: "stage" after "bodies".
std::string train_or_stage_summary_json(const GearTrain& train, const TrainResult& result,
                                        const StageWillis* willis) {
  const SimulationSummary& s = result.summary;
  std::string out = "{\n";
  out += "  \"integrator\": " + json_string(s.integrator) + ",\n";
  json_number(out, "end_time_s", s.end_time_s);
  json_number(out, "step_s", s.step_s);
  out += "  \"steps\": " + std::to_string(s.steps) + ",\n";
  out += "  \"events\": " + std::to_string(s.events) + ",\n";
  json_energy_terms(out, s);
  json_ledger_residual(out, s);
  if (s.planar) {
    // A train with bodies on bearings only, so that other trains' summaries keep their bytes.
    json_number(out, "bearing_energy_initial_J", s.planar->bearing_energy_initial_j);
    json_number(out, "bearing_energy_final_J", s.planar->bearing_energy_final_j);
    json_number(out, "bearing_damping_loss_J", s.planar->bearing_damping_loss_j);
  }
  // Once a revolution after drive.settle is measured, so that shorter runs keep their bytes.
  if (s.speed_drift_max_rel) json_optional(out, "speed_drift_max_rel", s.speed_drift_max_rel);
  out += "  \"meshes\": [";
  for (std::size_t k = 0; k < train.meshes.size(); ++k) {
    const TrainMeshSummary& m = result.meshes[k];
    out += std::string(k > 0 ? ",\n" : "\n") +
           "    {\"name\": " + json_string(train.meshes[k].name) +
           ", \"impacts\": " + std::to_string(m.impacts) +
           ", \"max_penetration_m\": " + format_data_number(m.max_penetration_m) +
           ", \"damping_loss_J\": " + format_data_number(m.damping_loss_j) +
           ", \"friction_loss_J\": " + format_data_number(m.friction_loss_j);
    // The viscous mesh damper's loss only for a mesh that has one, as the two-gear summary.
    if (train.meshes[k].pair.model.mesh_damping_ratio > 0.0) {
      out += ", \"mesh_damper_loss_J\": " + format_data_number(m.mesh_damping_loss_j);
    }
    out += "}";
  }
  out += "\n  ],\n  \"bodies\": [";
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    out +=
        std::string(i > 0 ? ",\n" : "\n") + "    {\"name\": " + json_string(train.bodies[i].name) +
        ", \"final_w_rad_per_s\": " + format_data_number(result.bodies[i].final_w_rad_per_s) + "}";
  }
  out += "\n  ]";
  if (willis != nullptr) {
    out +=
        ",\n  \"stage\": {\"mean_w_sun_rad_per_s\": " + format_data_number(willis->sun_rad_per_s) +
        ", \"mean_w_ring_rad_per_s\": " + format_data_number(willis->ring_rad_per_s) +
        ", \"mean_w_carrier_rad_per_s\": " + format_data_number(willis->carrier_rad_per_s) +
        ", \"willis_residual\": " + format_data_number(willis->residual) + "}";
  }
  out += "\n}\n";
  return out;
}

}  // namespace

std::string train_summary_json(const GearTrain& train, const TrainResult& result) {
  return train_or_stage_summary_json(train, result, nullptr);
}

std::string stage_summary_json(const GearTrain& train, const TrainResult& result,
                               const StageWillis& willis) {
  return train_or_stage_summary_json(train, result, &willis);
}

std::string ring_sensor_csv(const std::vector<TrainRow>& rows, const std::vector<double>& y) {
  std::string out = "t_s,ring_sensor_y_N\n";
  for (std::size_t i = 0; i < rows.size() && i < y.size(); ++i) {
    out += format_data_number(rows[i].t_s) + "," + format_data_number(y[i]) + "\n";
  }
  return out;
}

Columns<StageTeethRow> stage_teeth_columns(std::size_t planets) {
  Columns<StageTeethRow> columns{member_column("t_s", "s", &StageTeethRow::t_s)};
  const auto tooth = [&columns](const std::string& name, std::size_t i,
                                int StageMeshTeeth::*which) {
    columns.push_back(computed_column<StageTeethRow>(
        name, "",
        [i, which](const StageTeethRow& r) { return static_cast<double>(r.planets[i].*which); },
        true));
  };
  for (std::size_t i = 0; i < planets; ++i) {
    const std::string planet = "planet" + std::to_string(i + 1);
    tooth("sun_tooth_at_sun_" + planet, i, &StageMeshTeeth::sun);
    tooth(planet + "_tooth_at_sun_" + planet, i, &StageMeshTeeth::planet_at_sun);
    tooth(planet + "_tooth_at_ring_" + planet, i, &StageMeshTeeth::planet_at_ring);
    tooth("ring_tooth_at_ring_" + planet, i, &StageMeshTeeth::ring);
  }
  return columns;
}

std::string stage_teeth_csv(std::size_t planets, const std::vector<StageTeethRow>& rows) {
  return csv_of(stage_teeth_columns(planets), rows);
}

std::string tacho_csv(const std::vector<double>& true_times_s,
                      const std::vector<double>& emitted_times_s) {
  std::string out = "pulse,t_s,t_emitted_s\n";
  for (std::size_t k = 0; k < true_times_s.size(); ++k) {
    out += std::to_string(k) + "," + format_data_number(true_times_s[k]) + "," +
           format_data_number(emitted_times_s[k]) + "\n";
  }
  return out;
}

std::string summary_json(const SimulationSummary& s) {
  std::string out = "{\n";
  out += "  \"case\": " + json_string(s.case_name) + ",\n";
  out += "  \"integrator\": " + json_string(s.integrator) + ",\n";
  out += "  \"damping_update\": " + json_string(name_of(kDampingUpdates, s.damping_update)) + ",\n";
  if (s.friction_law == FrictionLaw::constant) {
    json_number(out, "friction_coefficient", s.friction_coefficient);
  } else {
    // The constant f is not the coefficient of a law whose f varies.
    out += "  \"friction_coefficient\": null,\n";
    out += "  \"friction_law\": " + json_string(name_of(kFrictionLaws, s.friction_law)) + ",\n";
    json_optional(out, "friction_coefficient_mean", s.friction_coefficient_mean);
    json_optional(out, "friction_coefficient_max", s.friction_coefficient_max);
  }
  json_number(out, "end_time_s", s.end_time_s);
  json_number(out, "step_s", s.step_s);
  out += "  \"impacts_n1\": " + std::to_string(s.impacts_n1) + ",\n";
  out += "  \"impacts_n2\": " + std::to_string(s.impacts_n2) + ",\n";
  json_optional(out, "first_impact_s", s.first_impact_s);
  json_optional(out, "first_impact_speed_m_s", s.first_impact_speed_m_s);
  json_optional(out, "last_n1_impact_s", s.last_n1_impact_s);
  json_optional(out, "last_n2_impact_s", s.last_n2_impact_s);
  json_number(out, "max_penetration_m", s.max_penetration_m);
  json_energy_terms(out, s);
  // Under the Lagrangian mesh force only, so that other runs' summaries keep their bytes.
  if (s.stored_energy_jumps_j) json_optional(out, "stored_energy_jumps_J", s.stored_energy_jumps_j);
  for (const TermInfo& t : kTerms) {
    if (!provides(s.stiffness_model, t.term)) continue;
    json_number(out, (std::string(t.id) + "_energy_max_J").c_str(),
                s.energy_max_j[index_of(t.term)]);
  }
  if (provides(s.stiffness_model, Term::foundation)) {
    out += std::string("  \"foundation_extrapolated\": ") +
           (s.foundation_extrapolated ? "true" : "false") + ",\n";
    if (s.foundation_extrapolated) {
      out += "  \"warning\": " +
             json_string(foundation_extrapolation_warning(s.foundation_extrapolations)) + ",\n";
    }
  }
  json_ledger_residual(out, s);
  json_number(out, "final_w1_rad_s", s.final_w1_rad_per_s);
  json_number(out, "final_w2_rad_s", s.final_w2_rad_per_s);
  if (s.speed_drift_max_rel) json_optional(out, "speed_drift_max_rel", s.speed_drift_max_rel);
  if (s.equivalent_mesh_damping_ratio) {
    json_optional(out, "equivalent_mesh_damping_ratio", s.equivalent_mesh_damping_ratio);
  }
  if (s.rattle) {
    // Under a kinematic driver only, so that other runs' summaries keep their bytes.
    const RattleSummary& r = *s.rattle;
    json_number(out, "rattle_impacts_per_s_n1", r.impacts_per_s_n1);
    json_number(out, "rattle_impacts_per_s_n2", r.impacts_per_s_n2);
    json_number(out, "rattle_impact_speed_mean_m_s", r.impact_speed_mean_m_s);
    json_number(out, "rattle_impact_speed_max_m_s", r.impact_speed_max_m_s);
    json_number(out, "rattle_impact_power_W", r.impact_power_w);
    json_number(out, "rattle_rms_acceleration2_rad_s2", r.rms_acceleration2_rad_s2);
    json_optional(out, "rattle_rms_acceleration2_no_backlash_rad_s2",
                  r.rms_acceleration2_no_backlash_rad_s2);
    json_optional(out, "rattle_index", r.rattle_index);
    out += "  \"rattle_regime\": " + json_string(name_of(kRattleRegimes, r.regime)) + ",\n";
  }
  if (s.planar) {
    // With elastic bearings only, so that other runs' summaries keep their bytes.
    const PlanarEnergies& p = *s.planar;
    json_number(out, "bearing_energy_initial_J", p.bearing_energy_initial_j);
    json_number(out, "bearing_energy_final_J", p.bearing_energy_final_j);
    json_number(out, "bearing_damping_loss_J", p.bearing_damping_loss_j);
    json_number(out, "shaft_energy_initial_J", p.shaft_energy_initial_j);
    json_number(out, "shaft_energy_final_J", p.shaft_energy_final_j);
    json_number(out, "shaft_damping_loss_J", p.shaft_damping_loss_j);
  }
  if (s.helical_thrust) {
    // A helical pair on elastic bearings only, so that other runs' summaries keep their bytes.
    const HelicalThrustMaxima& h = *s.helical_thrust;
    json_number(out, "axial_force_max_N", h.axial_force_max_n);
    json_number(out, "tilting_moment1_max_N_m", h.tilting_moment1_max_n_m);
    json_number(out, "tilting_moment2_max_N_m", h.tilting_moment2_max_n_m);
  }
  if (!s.slices.empty()) {
    // A helical pair run by route A only, so that other runs' summaries keep their bytes.
    out += "  \"face_slices\": " + std::to_string(s.slices.size()) + ",\n";
    out += "  \"slices\": [";
    for (std::size_t k = 0; k < s.slices.size(); ++k) {
      const SliceSummary& slice = s.slices[k];
      out += std::string(k > 0 ? ",\n" : "\n") + "    {\"name\": " + json_string(slice.name) +
             ", \"impacts_n1\": " + std::to_string(slice.impacts_n1) +
             ", \"impacts_n2\": " + std::to_string(slice.impacts_n2) +
             ", \"max_penetration_m\": " + format_data_number(slice.max_penetration_m) +
             ", \"damping_loss_J\": " + format_data_number(slice.damping_loss_j);
      if (s.mesh_damper) {
        out += ", \"mesh_damper_loss_J\": " + format_data_number(slice.mesh_damping_loss_j);
      }
      out += "}";
    }
    out += "\n  ],\n";
  }
  out += "  \"steps\": " + std::to_string(s.steps) + ",\n";
  out += "  \"events\": " + std::to_string(s.events) + ",\n";
  out += "  \"rhs_evaluations\": " + std::to_string(s.rhs_evaluations) + "\n";
  out += "}\n";
  return out;
}

Columns<ImpactRecord> rattle_impact_columns() {
  return {member_column("t_s", "s", &ImpactRecord::start_s),
          text_column<ImpactRecord>(
              "flank", [](const ImpactRecord& r) { return r.line == Region::n1 ? "N1" : "N2"; }),
          member_column("impact_speed_m_s", "m/s", &ImpactRecord::impact_speed_m_s)};
}

std::string rattle_impacts_csv(const std::vector<ImpactRecord>& struck) {
  return csv_of(rattle_impact_columns(), struck);
}

std::string impact_speed_histogram_csv(const ImpactSpeedHistogram& h) {
  std::string out = "lower_m_s,upper_m_s,count_n1,count_n2,count\n";
  for (std::size_t i = 0; i < h.lower_m_s.size(); ++i) {
    out += format_data_number(h.lower_m_s[i]) + "," + format_data_number(h.upper_m_s[i]) + "," +
           std::to_string(h.count_n1[i]) + "," + std::to_string(h.count_n2[i]) + "," +
           std::to_string(h.count_n1[i] + h.count_n2[i]) + "\n";
  }
  return out;
}

std::string friction_sweep_csv(const std::vector<SweepRow>& rows) {
  std::string out = "f";
  const std::size_t cases = rows.empty() ? 0 : rows.front().ratio.size();
  for (std::size_t j = 0; j < cases; ++j) out += ",ratio_case" + std::to_string(j + 1);
  out += "\n";
  for (const SweepRow& row : rows) {
    append_real(out, row.friction_coefficient);
    for (double ratio : row.ratio) {
      out += ',';
      append_real(out, ratio);
    }
    out += "\n";
  }
  return out;
}

std::string energy_ratios_csv(const std::vector<EnergyRatios>& rows) {
  std::string out =
      "angle_deg,pairs,hertz_over_bending_one_pair,axial_over_bending_one_pair,"
      "hertz_over_bending_system,axial_over_bending_system\n";
  for (const EnergyRatios& row : rows) {
    append_real(out, row.phi1_deg);
    out += ',';
    append_integer(out, row.pairs);
    for (double value : {row.hertz_over_bending_one_pair, row.axial_over_bending_one_pair,
                         row.hertz_over_bending_system, row.axial_over_bending_system}) {
      out += ',';
      append_real(out, value);
    }
    out += "\n";
  }
  return out;
}

namespace {

// The paper's columns first, as they were before the models beyond it:
// kb1,ka1,kb2,ka2,kh,ke; then ks1,ks2,kf1,kf2.
bool paper_term(Term term) {
  return provides(StiffnessModelKind::yang_lin_1987, term);
}

}  // namespace

std::vector<StiffnessColumn> stiffness_columns() {
  std::vector<StiffnessColumn> columns;
  for (Gear gear : {Gear::one, Gear::two}) {
    for (const TermInfo& t : kTerms) {
      if (t.per_tooth && paper_term(t.term)) {
        columns.push_back({std::string(t.column) + (gear == Gear::one ? "1" : "2"), t.term, gear});
      }
    }
  }
  for (const TermInfo& t : kTerms) {
    if (!t.per_tooth) columns.push_back({std::string(t.column), t.term, Gear::one});
  }
  columns.push_back({"ke", std::nullopt, Gear::one});
  for (const TermInfo& t : kTerms) {
    if (paper_term(t.term)) continue;
    for (Gear gear : {Gear::one, Gear::two}) {
      columns.push_back({std::string(t.column) + (gear == Gear::one ? "1" : "2"), t.term, gear});
    }
  }
  return columns;
}

double stiffness_column_value(const StiffnessColumn& column, const MeshStiffness& k,
                              const StiffnessModel& model) {
  if (!column.term) return k.ke;
  // A term switched off or absent from the model has no stiffness in Ke.
  return model.terms.has(*column.term) && provides(model.kind, *column.term)
             ? k.stiffness(*column.term, column.gear)
             : std::numeric_limits<double>::infinity();
}

std::string stiffness_csv(const GearPair& pair, const StiffnessModel& model,
                          const std::vector<double>& x1_m) {
  const std::vector<StiffnessColumn> columns = stiffness_columns();
  std::string out = "x_m,phi1_rad";
  for (const StiffnessColumn& column : columns) out += "," + column.name;
  out += "\n";
  const auto append = [&](double value, bool first = false) {
    if (!first) out += ',';
    append_real(out, value);
  };
  for (double x : x1_m) {
    const MeshStiffness k = mesh_stiffness(pair, x, model);
    append(x, true);
    append(contact_angle(pair, Gear::one, x));
    for (const StiffnessColumn& column : columns) {
      append(stiffness_column_value(column, k, model));
    }
    out += "\n";
  }
  return out;
}

std::string mesh_stiffness_csv(const TimeVaryingMeshStiffness& tvms) {
  std::string out = "fraction,theta1_rad,pairs,ke_n_m\n";
  for (const MeshStiffnessSample& sample : tvms.samples) {
    append_real(out, sample.fraction);
    out += ',';
    append_real(out, sample.theta1_rad);
    out += ',';
    append_integer(out, sample.pairs);
    out += ',';
    append_real(out, sample.stiffness_n_per_m);
    out += "\n";
  }
  return out;
}

std::size_t most_pairs_in_contact(const TruePeriodMeshStiffness& tvms) {
  std::size_t most = 0;
  for (const TruePeriodSample& s : tvms.samples) most = std::max(most, s.teeth.size());
  return most;
}

Columns<TruePeriodSample> true_period_mesh_stiffness_columns(std::size_t most_pairs) {
  using S = TruePeriodSample;
  Columns<S> columns{
      member_column("fraction", "", &S::fraction),
      member_column("theta1_rad", "rad", &S::theta1_rad),
      computed_column<S>(
          "pairs", "", [](const S& s) { return static_cast<double>(s.teeth.size()); }, true),
      member_column("ke_n_m", "N/m", &S::ke_n_per_m),
      member_column("healthy_ke_n_m", "N/m", &S::healthy_ke_n_per_m)};
  const double none = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t j = 0; j < most_pairs; ++j) {
    const std::string p = "pair" + std::to_string(j + 1);
    columns.push_back(optional_column<S>(
        p + "_pinion_tooth", "",
        [j, none](const S& s) {
          return j < s.teeth.size() ? static_cast<double>(s.teeth[j].pinion_tooth) : none;
        },
        true));
    columns.push_back(optional_column<S>(
        p + "_wheel_tooth", "",
        [j, none](const S& s) {
          return j < s.teeth.size() ? static_cast<double>(s.teeth[j].wheel_tooth) : none;
        },
        true));
    columns.push_back(optional_column<S>(p + "_ke_n_m", "N/m", [j, none](const S& s) {
      return j < s.teeth.size() ? s.pair_ke_n_per_m[j] : none;
    }));
  }
  return columns;
}

std::string true_period_mesh_stiffness_csv(const TruePeriodMeshStiffness& tvms) {
  return csv_of(true_period_mesh_stiffness_columns(most_pairs_in_contact(tvms)), tvms.samples);
}

std::string true_period_mesh_stiffness_summary_json(const TruePeriodMeshStiffness& tvms,
                                                    double contact_ratio) {
  const bool extrapolated = !tvms.foundation_extrapolations.empty();
  std::string out = "{\n";
  json_number(out, "min_n_m", tvms.min_n_per_m);
  json_number(out, "max_n_m", tvms.max_n_per_m);
  json_number(out, "mean_n_m", tvms.mean_n_per_m);
  json_number(out, "contact_ratio", contact_ratio);
  out += "  \"period\": " + json_string(tvms.period_kind) + ",\n";
  out += "  \"mesh_periods\": " + std::to_string(tvms.mesh_periods) + ",\n";
  json_number(out, "min_at_fraction", tvms.min_at_fraction);
  json_number(out, "max_at_fraction", tvms.max_at_fraction);
  json_number(out, "healthy_mean_n_m", tvms.healthy_mean_n_per_m);
  json_number(out, "simulation_theta1_offset_rad", tvms.simulation_theta1_offset_rad);
  out += std::string("  \"extrapolated\": ") + (extrapolated ? "true" : "false");
  if (extrapolated) {
    out += ",\n  \"warning\": " +
           json_string(foundation_extrapolation_warning(tvms.foundation_extrapolations));
  }
  out += "\n}\n";
  return out;
}

Columns<HelicalMeshStiffnessSample> helical_mesh_stiffness_columns() {
  using S = HelicalMeshStiffnessSample;
  return {member_column("fraction", "", &S::fraction),
          member_column("theta1_rad", "rad", &S::theta1_rad),
          member_column("k_slices_n_m", "N/m", &S::slices_n_per_m),
          member_column("k_face_n_m", "N/m", &S::face_n_per_m),
          member_column("contact_line_length_m", "m", &S::contact_line_length_m),
          member_column("contact_line_length_slices_m", "m", &S::contact_line_length_slices_m)};
}

std::string helical_mesh_stiffness_csv(const HelicalMeshStiffnessCurve& curve) {
  return csv_of(helical_mesh_stiffness_columns(), curve.samples);
}

std::string helical_mesh_stiffness_summary_json(const HelicalMeshStiffnessCurve& curve) {
  const HelicalGeometry& g = curve.geometry;
  std::string out = "{\n";
  json_number(out, "helix_angle_deg", g.helix_angle_rad * 180.0 / pi);
  json_number(out, "base_helix_angle_deg", g.base_helix_angle_rad * 180.0 / pi);
  json_number(out, "eps_alpha", g.transverse_contact_ratio);
  json_number(out, "eps_beta", g.overlap_ratio);
  json_number(out, "eps_gamma", g.total_contact_ratio);
  out += "  \"face_slices\": " + std::to_string(curve.face_slices) + ",\n";
  json_number(out, "min_face_n_m", curve.min_face_n_per_m);
  json_number(out, "max_face_n_m", curve.max_face_n_per_m);
  json_number(out, "min_slices_n_m", curve.min_slices_n_per_m);
  json_number(out, "max_slices_n_m", curve.max_slices_n_per_m);
  json_number(out, "mean_n_m", curve.mean_n_per_m);
  json_number(out, "mean_contact_line_length_m", curve.mean_contact_line_length_m);
  json_number(out, "iso_c_gamma_alpha_b_n_m", curve.iso_mesh_stiffness_n_per_m, true);
  out += "}\n";
  return out;
}

std::string iso6336_json(const Iso6336Stiffness& iso, double face_width_m,
                         std::optional<double> specific_load_n_per_m) {
  // ISO's unit N/(mm um) is 1e9 N/m^2.
  constexpr double n_per_mm_um = 1e9;
  std::string out = "{\n";
  json_number(out, "zn1", iso.virtual_teeth1);
  json_number(out, "zn2", iso.virtual_teeth2);
  json_number(out, "c_prime_th_n_mm_um", iso.theoretical_single_stiffness_n_per_m2 / n_per_mm_um);
  json_number(out, "c_prime_n_mm_um", iso.single_stiffness_n_per_m2 / n_per_mm_um);
  json_number(out, "c_gamma_alpha_n_mm_um", iso.mesh_stiffness_n_per_m2 / n_per_mm_um);
  json_number(out, "eps_alpha", iso.transverse_contact_ratio);
  json_number(out, "c_prime_b_n_m", iso.single_stiffness_n_per_m2 * face_width_m);
  json_number(out, "c_gamma_alpha_b_n_m", iso.mesh_stiffness_n_per_m2 * face_width_m,
              !specific_load_n_per_m);
  if (specific_load_n_per_m) {
    json_number(out, "specific_load_n_mm", *specific_load_n_per_m * 1e-3);
    json_number(out, "low_load_factor", iso.low_load_factor, true);
  }
  out += "}\n";
  return out;
}

namespace {

void ste_figures(std::string& out, const char* prefix, const StaticTransmissionError& ste,
                 bool last) {
  double least = std::numeric_limits<double>::infinity();
  double most = -least;
  double kte_least = least;
  double kte_most = -least;
  double stiffness = least;
  for (const StePoint& p : ste.points) {
    if (!p.carried) continue;
    least = std::min(least, p.ste_m);
    most = std::max(most, p.ste_m);
    kte_least = std::min(kte_least, p.kte_m);
    kte_most = std::max(kte_most, p.kte_m);
    stiffness = std::min(stiffness, p.effective_stiffness_n_per_m);
  }
  const std::string p(prefix);
  json_number(out, (p + "ste_mean_m").c_str(), ste.ste_mean_m);
  json_number(out, (p + "ste_min_m").c_str(), least);
  json_number(out, (p + "ste_max_m").c_str(), most);
  json_number(out, (p + "ste_peak_to_peak_m").c_str(), ste.ste_peak_to_peak_m);
  json_number(out, (p + "kte_peak_to_peak_m").c_str(), kte_most - kte_least);
  json_number(out, (p + "least_effective_stiffness_n_per_m").c_str(), stiffness);
  json_number(out, (p + "uncarried_points").c_str(), static_cast<double>(ste.uncarried_points),
              last);
}

}  // namespace

Columns<StePoint> ste_columns() {
  using P = StePoint;
  constexpr std::size_t slots = MeshLayout::capacity;
  const double none = std::numeric_limits<double>::quiet_NaN();
  // An angle that no pair carries has no STE and no effective stiffness: empty fields.
  Columns<P> columns{
      member_column("theta1_rad", "rad", &P::theta1_rad),
      computed_column<P>("theta1_deg", "deg", [](const P& p) { return p.theta1_rad * 180.0 / pi; }),
      optional_column<P>("ste_m", "m", [none](const P& p) { return p.carried ? p.ste_m : none; }),
      member_column("kte_m", "m", &P::kte_m),
      optional_column<P>(
          "effective_stiffness_n_per_m", "N/m",
          [none](const P& p) { return p.carried ? p.effective_stiffness_n_per_m : none; }),
      computed_column<P>(
          "pairs", "", [](const P& p) { return static_cast<double>(p.pairs); }, true),
      computed_column<P>(
          "loaded_pairs", "",
          [](const P& p) {
            std::size_t loaded = 0;
            for (std::size_t j = 0; j < p.pairs; ++j) loaded += p.share[j] > 0.0;
            return static_cast<double>(loaded);
          },
          true)};
  // The pairs within the contact segment, in ascending X: empty beyond `pairs`.
  for (const auto& [prefix, unit, values] :
       {std::tuple{"share_", "", &P::share}, std::tuple{"gap_", "m", &P::gap_m}}) {
    for (std::size_t j = 0; j < slots; ++j) {
      columns.push_back(optional_column<P>(
          prefix + std::to_string(j + 1), unit,
          [j, none, values = values](const P& p) { return j < p.pairs ? (p.*values)[j] : none; }));
    }
  }
  columns.push_back(text_column<P>("teeth", [](const P& p) {
    std::string teeth;
    for (std::size_t j = 0; j < p.pairs; ++j) {
      teeth += (j ? " " : "") + std::to_string(p.teeth[j].pinion_tooth) + "/" +
               std::to_string(p.teeth[j].wheel_tooth);
    }
    return teeth;
  }));
  return columns;
}

std::string ste_csv(const StaticTransmissionError& ste) {
  return csv_of(ste_columns(), ste.points);
}

std::string ste_pairs_csv(const StaticTransmissionError& ste) {
  // The pairs by mesh index, each with the points it is in contact at, in
  // the order of the points.
  std::map<int, std::string> blocks;
  for (const StePoint& p : ste.points) {
    for (std::size_t j = 0; j < p.pairs; ++j) {
      blocks[p.k[j]] += std::to_string(p.k[j]) + "," + std::to_string(p.teeth[j].pinion_tooth) +
                        "," + std::to_string(p.teeth[j].wheel_tooth) + "," +
                        format_data_number(p.theta1_rad * 180.0 / pi) + "," +
                        format_data_number(p.share[j]) + "," + format_data_number(p.gap_m[j]) +
                        "," + format_data_number(p.stiffness_n_per_m[j]) + "\n";
    }
  }
  std::string out = "pair,pinion_tooth,wheel_tooth,theta1_deg,share,gap_m,stiffness_n_per_m\n";
  bool first = true;
  for (const auto& [k, rows] : blocks) {
    if (!first) out += "\n\n";
    first = false;
    out += rows;
  }
  return out;
}

std::string ste_summary_json(const StaticTransmissionError& modified,
                             const StaticTransmissionError& unmodified,
                             double quasi_static_force_ratio,
                             double unmodified_quasi_static_force_ratio) {
  std::string out = "{\n";
  json_number(out, "torque1_n_m", modified.torque1_n_m);
  json_number(out, "force_n", modified.force_n);
  json_number(out, "mesh_periods", static_cast<double>(modified.mesh_periods));
  json_number(out, "period_rad", modified.period_rad);
  json_number(out, "points", static_cast<double>(modified.points.size()));
  json_number(out, "quasi_static_force_ratio", quasi_static_force_ratio);
  json_number(out, "unmodified_quasi_static_force_ratio", unmodified_quasi_static_force_ratio);
  ste_figures(out, "", modified, false);
  ste_figures(out, "unmodified_", unmodified, true);
  out += "}\n";
  return out;
}

Columns<HelicalStePoint> helical_ste_columns() {
  using P = HelicalStePoint;
  return {
      member_column("theta1_rad", "rad", &P::theta1_rad),
      computed_column<P>("theta1_deg", "deg", [](const P& p) { return p.theta1_rad * 180.0 / pi; }),
      member_column("ste_m", "m", &P::ste_m),
      member_column("kte_m", "m", &P::kte_m),
      member_column("effective_stiffness_n_per_m", "N/m", &P::effective_stiffness_n_per_m),
      member_column("elements", &P::elements),
      member_column("loaded_elements", &P::loaded_elements),
      member_column("load_centre_m", "m", &P::load_centre_m),
      member_column("face_load_factor", "", &P::face_load_factor)};
}

std::string helical_ste_csv(const HelicalStaticTransmissionError& ste) {
  return csv_of(helical_ste_columns(), ste.points);
}

std::string helical_face_load_csv(const HelicalStaticTransmissionError& modified,
                                  const HelicalStaticTransmissionError& unmodified) {
  const double nominal = modified.force_n / modified.face_width_m;  // F_bt / b
  std::string out =
      "y_m,mean_load_per_width_n_per_m,unmodified_mean_load_per_width_n_per_m,"
      "mean_load_ratio,unmodified_mean_load_ratio\n";
  for (std::size_t j = 0; j < modified.slice_y_m.size(); ++j) {
    out += format_data_number(modified.slice_y_m[j]) + "," +
           format_data_number(modified.mean_load_per_width_n_per_m[j]) + "," +
           format_data_number(unmodified.mean_load_per_width_n_per_m[j]) + "," +
           format_data_number(modified.mean_load_per_width_n_per_m[j] / nominal) + "," +
           format_data_number(unmodified.mean_load_per_width_n_per_m[j] / nominal) + "\n";
  }
  return out;
}

namespace {

void helical_ste_figures(std::string& out, const char* prefix,
                         const HelicalStaticTransmissionError& ste, bool last) {
  double least = std::numeric_limits<double>::infinity();
  double most = -least;
  double kte_least = least;
  double kte_most = -least;
  for (const HelicalStePoint& p : ste.points) {
    least = std::min(least, p.ste_m);
    most = std::max(most, p.ste_m);
    kte_least = std::min(kte_least, p.kte_m);
    kte_most = std::max(kte_most, p.kte_m);
  }
  const std::string p = prefix;
  json_number(out, (p + "ste_mean_m").c_str(), ste.ste_mean_m);
  json_number(out, (p + "ste_min_m").c_str(), least);
  json_number(out, (p + "ste_max_m").c_str(), most);
  json_number(out, (p + "ste_peak_to_peak_m").c_str(), ste.ste_peak_to_peak_m);
  json_number(out, (p + "kte_min_m").c_str(), kte_least);
  json_number(out, (p + "kte_max_m").c_str(), kte_most);
  json_number(out, (p + "face_load_factor").c_str(), ste.face_load_factor);
  json_number(out, (p + "largest_face_load_factor").c_str(), ste.largest_face_load_factor);
  json_number(out, (p + "load_centre_m").c_str(), ste.mean_load_centre_m, last);
}

}  // namespace

std::string helical_ste_summary_json(const HelicalStaticTransmissionError& modified,
                                     const HelicalStaticTransmissionError& unmodified) {
  std::string out = "{\n";
  json_number(out, "torque1_n_m", modified.torque1_n_m);
  json_number(out, "force_n", modified.force_n);
  json_number(out, "mesh_periods", static_cast<double>(modified.mesh_periods));
  json_number(out, "period_rad", modified.period_rad);
  json_number(out, "points", static_cast<double>(modified.points.size()));
  out += "  \"face_slices\": " + std::to_string(modified.face_slices) + ",\n";
  out += std::string("  \"route\": ") + (modified.face_route ? "\"face\"" : "\"slices\"") + ",\n";
  helical_ste_figures(out, "", modified, false);
  helical_ste_figures(out, "unmodified_", unmodified, true);
  out += "}\n";
  return out;
}

}  // namespace gearimpact
