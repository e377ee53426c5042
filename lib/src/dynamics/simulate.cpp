#include "gearimpact/dynamics/simulate.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/schema.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "rk4.hpp"

namespace gearimpact {

namespace {

// The options of the steady-state model: the torques' harmonics, the mesh
// stiffness, the mesh damper and the damping update.
void validate_model_options(const SimulationCase& c) {
  for (const auto& [name, torque] : {std::pair<const char*, const Torque&>{"torque1", c.torque1},
                                     std::pair<const char*, const Torque&>{"torque2", c.torque2}}) {
    if (torque.kind == Torque::Kind::constant || torque.kind == Torque::Kind::user) continue;
    if (!std::isfinite(torque.mean_n_m)) {
      throw InputError(std::string(name) + ".mean", torque.mean_n_m, "a finite torque in N m");
    }
    if (torque.kind != Torque::Kind::harmonic) continue;
    const std::size_t n = torque.harmonic_amplitudes_n_m.size();
    if (torque.harmonic_angular_frequencies_rad_s.size() != n ||
        torque.harmonic_phases_rad.size() != n) {
      throw InputError(std::string(name) + ".harmonics",
                       std::to_string(n) + " amplitudes, " +
                           std::to_string(torque.harmonic_angular_frequencies_rad_s.size()) +
                           " angular frequencies, " +
                           std::to_string(torque.harmonic_phases_rad.size()) + " phases",
                       "as many angular frequencies and phases as amplitudes");
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(torque.harmonic_amplitudes_n_m[i]) ||
          !std::isfinite(torque.harmonic_angular_frequencies_rad_s[i]) ||
          !std::isfinite(torque.harmonic_phases_rad[i])) {
        throw InputError(std::string(name) + ".harmonics[" + std::to_string(i) + "]",
                         "a non-finite amplitude, angular frequency or phase",
                         "finite values in N m, rad/s and rad");
      }
    }
  }
  const ModelOptions& m = c.model;
  if (m.mesh_stiffness == MeshStiffnessMode::constant &&
      (!std::isfinite(m.constant_mesh_stiffness_n_m) || m.constant_mesh_stiffness_n_m <= 0.0)) {
    throw InputError("model.constant_mesh_stiffness", m.constant_mesh_stiffness_n_m,
                     "a finite value > 0 N/m when mesh_stiffness = constant");
  }
  if (!std::isfinite(m.mesh_damping_ratio) || m.mesh_damping_ratio < 0.0) {
    throw InputError("model.mesh_damping_ratio", m.mesh_damping_ratio,
                     "a finite value >= 0 (zeta of c = 2 zeta sqrt(k_mean m_e); 0 is off)");
  }
  if (m.damping_update == DampingUpdate::frozen &&
      (!std::isfinite(m.damping_reference_speed_m_s) || m.damping_reference_speed_m_s <= 0.0)) {
    throw InputError("model.damping_reference_speed", m.damping_reference_speed_m_s,
                     "a finite speed > 0 m/s when damping_update = frozen");
  }
}

void validate_control(const SimulationCase& c, const RunControl& control) {
  if (control.resume) {
    const RunState& r = *control.resume;
    const InitialState& y = r.state;
    if (!std::isfinite(r.time_s) || !std::isfinite(y.theta1_rad) || !std::isfinite(y.theta2_rad) ||
        !std::isfinite(y.w1_rad_s) || !std::isfinite(y.w2_rad_s) ||
        !std::isfinite(r.contact.damping_per_stiffness_s_m) ||
        !std::isfinite(r.contact.frozen_stiffness_n_m) ||
        r.contact.damping_per_stiffness_s_m < 0.0) {
      throw InputError("resume", "a state with a non-finite or negative value",
                       "the final_state of a run of " + c.name + ", finite");
    }
  }
}

// A table built for a pair and model must be this case's; one built from a
// function must at least cover the contact segment.
void check_table(const SimulationCase& c, const StiffnessTable& table) {
  if (table.knows_origin()) {
    if (!table.built_for(c.gears, c.model.stiffness)) {
      throw InputError("table", "a StiffnessTable built for another gear pair or stiffness model",
                       "the table of this case: StiffnessTable(c.gears, c.model.stiffness)");
    }
    return;
  }
  const ContactSegment segment = contact_segment(c.gears);
  if (table.domain_start_m() > segment.start_m || table.domain_end_m() < segment.end_m) {
    throw InputError("table",
                     "a table over [" + format_number(table.domain_start_m()) + ", " +
                         format_number(table.domain_end_m()) + "] m",
                     "one that covers the contact segment [" + format_number(segment.start_m) +
                         ", " + format_number(segment.end_m) + "] m of " + c.name);
  }
}

}  // namespace

void validate(const SimulationCase& c) {
  validate_fields(c);
  validate_model_options(c);
  validate_step(c, largest_resolving_step_s(c));
}

SimulationResult simulate(const SimulationCase& c, const RunControl& control) {
  validate_fields(c);
  validate_model_options(c);
  const StiffnessTable table(c.gears, c.model.stiffness);
  return simulate(c, table, control);
}

SimulationResult simulate(const SimulationCase& c, const StiffnessTable& table,
                          const RunControl& control) {
  validate_fields(c);
  validate_model_options(c);
  check_table(c, table);
  validate_step(c, largest_resolving_step_s(c, table));
  validate_control(c, control);
  SimulationResult result = c.integrator.kind == IntegratorKind::rk4
                                ? run_rk4(c, table, control)
                                : run_adaptive(c, table, control);
  const StiffnessModel& k = c.model.stiffness;
  if (provides(k.kind, Term::foundation) && k.terms.has(Term::foundation)) {
    // The fit's inputs (h_f, theta_f) are the teeth's, the same at every position.
    result.summary.foundation_extrapolated =
        mesh_stiffness(c.gears, contact_segment(c.gears).start_m, k).foundation_extrapolated;
  }
  return result;
}

}  // namespace gearimpact
