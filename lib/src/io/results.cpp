#include "gearimpact/io/results.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <map>
#include <string>

#include "gearimpact/constants.hpp"

namespace gearimpact {

std::string format_data_number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

std::string series_csv_header() {
  return "t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,s_m,delta_m,region,pairs,normal_force_N,"
         "friction_force_N\n";
}

void append_series_row(std::string& out, const SeriesRow& r) {
  char line[512];
  const int n = std::snprintf(
      line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d,%.17g,%.17g\n", r.t_s,
      r.theta1_rad, r.theta2_rad, r.w1_rad_per_s, r.w2_rad_per_s, r.s_m, r.delta_m, r.region,
      r.pairs, r.normal_force_n, r.friction_force_n);
  out.append(line, static_cast<std::size_t>(n));
}

std::string planar_series_csv_header() {
  return "t_s,x1_m,y1_m,theta1_rad,x2_m,y2_m,theta2_rad,vx1_m_s,vy1_m_s,w1_rad_s,vx2_m_s,vy2_m_s,"
         "w2_rad_s,theta_motor_rad,theta_load_rad,w_motor_rad_s,w_load_rad_s,bearing_fx1_N,"
         "bearing_fy1_N,bearing_fx2_N,bearing_fy2_N,drive_force_N,coast_force_N,"
         "drive_penetration_m,coast_penetration_m\n";
}

namespace {

// Numbers as a CSV line, each "%.17g": a time, the planar state in the
// column order both planar headers share, then the row's own values.
void append_numbers(std::string& out, double t, const PlanarState& q,
                    std::initializer_list<double> rest) {
  const double state[] = {t,
                          q.x1_m,
                          q.y1_m,
                          q.theta1_rad,
                          q.x2_m,
                          q.y2_m,
                          q.theta2_rad,
                          q.vx1_m_s,
                          q.vy1_m_s,
                          q.w1_rad_per_s,
                          q.vx2_m_s,
                          q.vy2_m_s,
                          q.w2_rad_per_s,
                          q.theta_motor_rad,
                          q.theta_load_rad,
                          q.w_motor_rad_per_s,
                          q.w_load_rad_per_s};
  char number[32];
  bool first = true;
  const auto append = [&](double v) {
    if (!first) out += ',';
    first = false;
    const int n = std::snprintf(number, sizeof number, "%.17g", v);
    out.append(number, static_cast<std::size_t>(n));
  };
  for (const double v : state) append(v);
  for (const double v : rest) append(v);
  out += '\n';
}

}  // namespace

void append_planar_row(std::string& out, const PlanarRow& r) {
  append_numbers(out, r.t_s, r.state,
                 {r.bearing_fx1_n, r.bearing_fy1_n, r.bearing_fx2_n, r.bearing_fy2_n,
                  r.drive_force_n, r.coast_force_n, r.drive_penetration_m, r.coast_penetration_m});
}

std::string planar_samples_csv_header() {
  return "t_s,x1_m,y1_m,theta1_rad,x2_m,y2_m,theta2_rad,vx1_m_s,vy1_m_s,w1_rad_s,vx2_m_s,vy2_m_s,"
         "w2_rad_s,theta_motor_rad,theta_load_rad,w_motor_rad_s,w_load_rad_s,ax1_m_per_s2,"
         "ay1_m_per_s2,alpha1_rad_per_s2,ax2_m_per_s2,ay2_m_per_s2,alpha2_rad_per_s2,"
         "bearing_fx1_N,bearing_fy1_N,bearing_fx2_N,bearing_fy2_N,dte_m,drive_force_N,"
         "coast_force_N,sensor_acceleration_m_per_s2\n";
}

void append_planar_sample(std::string& out, const PlanarSample& r) {
  append_numbers(
      out, r.t_s, r.state,
      {r.ax1_m_per_s2, r.ay1_m_per_s2, r.alpha1_rad_per_s2, r.ax2_m_per_s2, r.ay2_m_per_s2,
       r.alpha2_rad_per_s2, r.bearing_fx1_n, r.bearing_fy1_n, r.bearing_fx2_n, r.bearing_fy2_n,
       r.dte_m, r.drive_force_n, r.coast_force_n, r.sensor_acceleration_m_per_s2});
}

std::string samples_csv_header() {
  return "t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,w1_dot_rad_s2,w2_dot_rad_s2,s_m,dte_m,"
         "normal_force_n1_N,normal_force_n2_N,region,pairs\n";
}

void append_sample_row(std::string& out, const SampleRow& r) {
  char line[512];
  const int n =
      std::snprintf(line, sizeof line,
                    "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d\n",
                    r.t_s, r.theta1_rad, r.theta2_rad, r.w1_rad_per_s, r.w2_rad_per_s,
                    r.acceleration1_rad_per_s2, r.acceleration2_rad_per_s2, r.s_m, r.dte_m,
                    r.normal_force_n1_n, r.normal_force_n2_n, r.region, r.pairs);
  out.append(line, static_cast<std::size_t>(n));
}

std::string series_csv(const std::vector<SeriesRow>& rows) {
  std::string out = series_csv_header();
  out.reserve(out.size() + rows.size() * 220);
  for (const SeriesRow& r : rows) append_series_row(out, r);
  return out;
}

namespace {

void json_number(std::string& out, const char* key, double value, bool last = false) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "  \"%s\": %.17g%s\n", key, value, last ? "" : ",");
  out += buffer;
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

std::vector<TrainColumn> train_series_columns(const GearTrain& train) {
  std::vector<TrainColumn> columns;
  columns.push_back({"t_s", "s", false, [](const TrainRow& r) { return r.t_s; }});
  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    const std::string& body = train.bodies[i].name;
    columns.push_back({"theta_" + body + "_rad", "rad", false,
                       [i](const TrainRow& r) { return r.theta_rad[i]; }});
    columns.push_back({"w_" + body + "_rad_per_s", "rad/s", false,
                       [i](const TrainRow& r) { return r.w_rad_per_s[i]; }});
  }
  for (std::size_t k = 0; k < train.meshes.size(); ++k) {
    const std::string& mesh = train.meshes[k].name;
    columns.push_back(
        {"s_" + mesh + "_m", "m", false, [k](const TrainRow& r) { return r.meshes[k].s_m; }});
    columns.push_back({"delta_" + mesh + "_m", "m", false,
                       [k](const TrainRow& r) { return r.meshes[k].delta_m; }});
    columns.push_back({"region_" + mesh, "", true,
                       [k](const TrainRow& r) { return static_cast<double>(r.meshes[k].region); }});
    columns.push_back({"pairs_" + mesh, "", true,
                       [k](const TrainRow& r) { return static_cast<double>(r.meshes[k].pairs); }});
    columns.push_back({"normal_force_" + mesh + "_N", "N", false,
                       [k](const TrainRow& r) { return r.meshes[k].normal_force_n; }});
    columns.push_back({"friction_force_" + mesh + "_N", "N", false,
                       [k](const TrainRow& r) { return r.meshes[k].friction_force_n; }});
  }
  return columns;
}

std::string train_series_csv(const GearTrain& train, const std::vector<TrainRow>& rows) {
  const std::vector<TrainColumn> columns = train_series_columns(train);
  std::string out;
  for (std::size_t c = 0; c < columns.size(); ++c) out += (c > 0 ? "," : "") + columns[c].name;
  out += "\n";
  for (const TrainRow& row : rows) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c > 0) out += ',';
      const double value = columns[c].value(row);
      out += columns[c].integral ? std::to_string(static_cast<long long>(value))
                                 : format_data_number(value);
    }
    out += '\n';
  }
  return out;
}

std::string train_summary_json(const GearTrain& train, const TrainResult& result) {
  const SimulationSummary& s = result.summary;
  std::string out = "{\n";
  out += "  \"integrator\": " + json_string(s.integrator) + ",\n";
  json_number(out, "end_time_s", s.end_time_s);
  json_number(out, "step_s", s.step_s);
  out += "  \"steps\": " + std::to_string(s.steps) + ",\n";
  out += "  \"events\": " + std::to_string(s.events) + ",\n";
  json_energy_terms(out, s);
  json_ledger_residual(out, s);
  out += "  \"meshes\": [";
  for (std::size_t k = 0; k < train.meshes.size(); ++k) {
    const TrainMeshSummary& m = result.meshes[k];
    char penetration[64];
    std::snprintf(penetration, sizeof penetration, "%.17g", m.max_penetration_m);
    out += std::string(k > 0 ? ",\n" : "\n") +
           "    {\"name\": " + json_string(train.meshes[k].name) +
           ", \"impacts\": " + std::to_string(m.impacts) +
           ", \"max_penetration_m\": " + penetration + "}";
  }
  out += "\n  ]\n}\n";
  return out;
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
  out += "  \"steps\": " + std::to_string(s.steps) + ",\n";
  out += "  \"events\": " + std::to_string(s.events) + ",\n";
  out += "  \"rhs_evaluations\": " + std::to_string(s.rhs_evaluations) + "\n";
  out += "}\n";
  return out;
}

std::string rattle_impacts_csv(const std::vector<ImpactRecord>& struck) {
  std::string out = "t_s,flank,impact_speed_m_s\n";
  for (const ImpactRecord& impact : struck) {
    out += format_data_number(impact.start_s);
    out += impact.line == Region::n1 ? ",N1," : ",N2,";
    out += format_data_number(impact.impact_speed_m_s) + "\n";
  }
  return out;
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
  char number[32];
  for (const SweepRow& row : rows) {
    std::snprintf(number, sizeof number, "%.17g", row.friction_coefficient);
    out += number;
    for (double ratio : row.ratio) {
      std::snprintf(number, sizeof number, ",%.17g", ratio);
      out += number;
    }
    out += "\n";
  }
  return out;
}

std::string energy_ratios_csv(const std::vector<EnergyRatios>& rows) {
  std::string out =
      "angle_deg,pairs,hertz_over_bending_one_pair,axial_over_bending_one_pair,"
      "hertz_over_bending_system,axial_over_bending_system\n";
  char line[256];
  for (const EnergyRatios& row : rows) {
    std::snprintf(line, sizeof line, "%.17g,%d,%.17g,%.17g,%.17g,%.17g\n", row.phi1_deg, row.pairs,
                  row.hertz_over_bending_one_pair, row.axial_over_bending_one_pair,
                  row.hertz_over_bending_system, row.axial_over_bending_system);
    out += line;
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
  char number[32];
  const auto append = [&](double value, bool first = false) {
    std::snprintf(number, sizeof number, first ? "%.17g" : ",%.17g", value);
    out += number;
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
  char line[160];
  for (const MeshStiffnessSample& sample : tvms.samples) {
    std::snprintf(line, sizeof line, "%.17g,%.17g,%d,%.17g\n", sample.fraction, sample.theta1_rad,
                  sample.pairs, sample.stiffness_n_per_m);
    out += line;
  }
  return out;
}

std::string true_period_mesh_stiffness_csv(const TruePeriodMeshStiffness& tvms) {
  std::size_t most = 0;
  for (const TruePeriodSample& s : tvms.samples) most = std::max(most, s.teeth.size());
  std::string out = "fraction,theta1_rad,pairs,ke_n_m,healthy_ke_n_m";
  for (std::size_t j = 1; j <= most; ++j) {
    const std::string p = "pair" + std::to_string(j);
    out += "," + p + "_pinion_tooth," + p + "_wheel_tooth," + p + "_ke_n_m";
  }
  out += "\n";
  char line[160];
  for (const TruePeriodSample& s : tvms.samples) {
    std::snprintf(line, sizeof line, "%.17g,%.17g,%zu,%.17g,%.17g", s.fraction, s.theta1_rad,
                  s.teeth.size(), s.ke_n_per_m, s.healthy_ke_n_per_m);
    out += line;
    for (std::size_t j = 0; j < most; ++j) {
      if (j < s.teeth.size()) {
        std::snprintf(line, sizeof line, ",%d,%d,%.17g", s.teeth[j].pinion_tooth,
                      s.teeth[j].wheel_tooth, s.pair_ke_n_per_m[j]);
        out += line;
      } else {
        out += ",,,";
      }
    }
    out += "\n";
  }
  return out;
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

std::string ste_csv(const StaticTransmissionError& ste) {
  constexpr std::size_t slots = MeshLayout::capacity;
  std::string out =
      "theta1_rad,theta1_deg,ste_m,kte_m,effective_stiffness_n_per_m,pairs,loaded_pairs";
  for (const char* column : {"share_", "gap_"}) {
    for (std::size_t j = 1; j <= slots; ++j) out += "," + std::string(column) + std::to_string(j);
  }
  out += ",teeth\n";
  for (const StePoint& p : ste.points) {
    std::size_t loaded = 0;
    for (std::size_t j = 0; j < p.pairs; ++j) loaded += p.share[j] > 0.0;
    // An angle that no pair carries has no STE and no effective stiffness: empty fields.
    const auto carried = [&p](double value) { return p.carried ? format_data_number(value) : ""; };
    out += format_data_number(p.theta1_rad) + "," + format_data_number(p.theta1_rad * 180.0 / pi) +
           "," + carried(p.ste_m) + "," + format_data_number(p.kte_m) + "," +
           carried(p.effective_stiffness_n_per_m) + "," + std::to_string(p.pairs) + "," +
           std::to_string(loaded);
    for (const auto* values : {&p.share, &p.gap_m}) {
      for (std::size_t j = 0; j < slots; ++j) {
        out += ",";
        if (j < p.pairs) out += format_data_number((*values)[j]);
      }
    }
    out += ",";
    for (std::size_t j = 0; j < p.pairs; ++j) {
      out += (j ? " " : "") + std::to_string(p.teeth[j].pinion_tooth) + "/" +
             std::to_string(p.teeth[j].wheel_tooth);
    }
    out += "\n";
  }
  return out;
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

}  // namespace gearimpact
