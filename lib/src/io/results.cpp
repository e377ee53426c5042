#include "gearimpact/io/results.hpp"

#include <cstdio>
#include <string>

namespace gearimpact {

std::string series_csv(const std::vector<SeriesRow>& rows) {
  std::string out =
      "t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,s_m,delta_m,region,pairs,normal_force_N,"
      "friction_force_N\n";
  out.reserve(out.size() + rows.size() * 220);
  char line[512];
  for (const SeriesRow& r : rows) {
    const int n = std::snprintf(line, sizeof line,
                                "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d,%.17g,%.17g\n",
                                r.t_s, r.theta1_rad, r.theta2_rad, r.w1_rad_s, r.w2_rad_s, r.s_m,
                                r.delta_m, r.region, r.pairs, r.normal_force_n, r.friction_force_n);
    out.append(line, static_cast<std::size_t>(n));
  }
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

}  // namespace

std::string summary_json(const SimulationSummary& s) {
  std::string out = "{\n";
  out += "  \"case\": " + json_string(s.case_name) + ",\n";
  out += "  \"integrator\": " + json_string(s.integrator) + ",\n";
  json_number(out, "friction_coefficient", s.friction_coefficient);
  json_number(out, "end_time_s", s.end_time_s);
  json_number(out, "step_s", s.step_s);
  out += "  \"impacts_n1\": " + std::to_string(s.impacts_n1) + ",\n";
  out += "  \"impacts_n2\": " + std::to_string(s.impacts_n2) + ",\n";
  json_optional(out, "first_impact_s", s.first_impact_s);
  json_optional(out, "first_impact_speed_m_s", s.first_impact_speed_m_s);
  json_optional(out, "last_n1_impact_s", s.last_n1_impact_s);
  json_optional(out, "last_n2_impact_s", s.last_n2_impact_s);
  json_number(out, "max_penetration_m", s.max_penetration_m);
  json_number(out, "kinetic_energy_initial_J", s.kinetic_energy_initial_j);
  json_number(out, "kinetic_energy_final_J", s.kinetic_energy_final_j);
  json_number(out, "stored_energy_initial_J", s.stored_energy_initial_j);
  json_number(out, "stored_energy_final_J", s.stored_energy_final_j);
  json_number(out, "torque_work_J", s.torque_work_j);
  json_number(out, "damping_loss_J", s.damping_loss_j);
  json_number(out, "friction_loss_J", s.friction_loss_j);
  json_number(out, "parametric_work_J", s.parametric_work_j);
  json_number(out, "parametric_jump_work_J", s.parametric_jump_work_j);
  for (const TermInfo& t : kTerms) {
    json_number(out, (std::string(t.id) + "_energy_max_J").c_str(),
                s.energy_max_j[index_of(t.term)]);
  }
  json_number(out, "ledger_residual_J", s.ledger_residual_j);
  json_number(out, "ledger_residual_max_J", s.ledger_residual_max_j);
  json_number(out, "ledger_scale_J", s.ledger_scale_j);
  json_number(out, "final_w1_rad_s", s.final_w1_rad_s);
  json_number(out, "final_w2_rad_s", s.final_w2_rad_s);
  out += "  \"steps\": " + std::to_string(s.steps) + ",\n";
  out += "  \"events\": " + std::to_string(s.events) + ",\n";
  out += "  \"rhs_evaluations\": " + std::to_string(s.rhs_evaluations) + "\n";
  out += "}\n";
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

std::string stiffness_csv(const GearPair& pair, const StiffnessModel& model,
                          const std::vector<double>& x1_m) {
  std::string out = "x_m,phi1_rad";
  for (int gear = 1; gear <= 2; ++gear) {
    for (const TermInfo& t : kTerms) {
      if (t.per_tooth) out += "," + std::string(t.column) + std::to_string(gear);
    }
  }
  for (const TermInfo& t : kTerms) {
    if (!t.per_tooth) out += "," + std::string(t.column);
  }
  out += ",ke\n";
  char number[32];
  const auto append = [&](double value, bool first = false) {
    std::snprintf(number, sizeof number, first ? "%.17g" : ",%.17g", value);
    out += number;
  };
  for (double x : x1_m) {
    const MeshStiffness k = mesh_stiffness(pair, x, model);
    append(x, true);
    append(contact_angle(pair, Gear::one, x));
    for (Gear gear : {Gear::one, Gear::two}) {
      for (const TermInfo& t : kTerms) {
        if (t.per_tooth) append(k.stiffness(t.term, gear));
      }
    }
    for (const TermInfo& t : kTerms) {
      if (!t.per_tooth) append(k.stiffness(t.term));
    }
    append(k.ke);
    out += "\n";
  }
  return out;
}

}  // namespace gearimpact
