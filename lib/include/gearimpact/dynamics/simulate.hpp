// The gear impact dynamics of (1)-(3), (31)-(45): MODEL.md, sections Contact,
// damping, friction; Equations of motion; Energies. State [theta1, theta2, w1, w2]
// plus four ledger integrals (torque work, damping loss, friction loss,
// parametric work), integrated by fixed-step classical RK4 with every
// discontinuity of the right-hand side located and stepped onto, or by Boost.Odeint's
// dense-output Dormand-Prince 5(4) with the same event location.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gearimpact/dynamics/simulation_case.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// A run that cannot continue: a non-finite state, or event location that stalls.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run ended early because its RunControl::should_stop asked for it.
class SimulationStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Which side of the backlash the teeth are on, (31). Written as 1, 0, -1.
enum class Region { n2 = -1, free = 0, n1 = 1 };

// One row of the time series. normal_force_n and friction_force_n are summed
// over the loaded pairs; friction_force_n carries the sign of Ff in (35)-(38).
struct SeriesRow {
  double t_s;
  double theta1_rad;
  double theta2_rad;
  double w1_rad_s;
  double w2_rad_s;
  double s_m;
  double delta_m;
  int region;
  int pairs;
  double normal_force_n;
  double friction_force_n;
};

// One impact: a contact that begins at `start_s` with approach speed Vi on
// `line`; it ends (if it ends within the run) with separation speed `end_speed_m_s`.
// A run that starts in contact counts that contact as an impact at t = 0.
struct ImpactRecord {
  Region line;
  double start_s;
  double impact_speed_m_s;  // Vi, d(delta)/dt at onset
  double restitution;       // e(Vi) of (33)
  std::optional<double> end_s;
  std::optional<double> end_speed_m_s;  // -d(delta)/dt when the contact ends
};

struct SimulationSummary {
  std::string case_name;
  std::string integrator;
  double friction_coefficient = 0.0;
  double end_time_s = 0.0;
  double step_s = 0.0;
  int impacts_n1 = 0;
  int impacts_n2 = 0;
  std::optional<double> first_impact_s;
  std::optional<double> first_impact_speed_m_s;
  std::optional<double> last_n1_impact_s;
  std::optional<double> last_n2_impact_s;
  double max_penetration_m = 0.0;
  // Energies, J. Losses and works are integrals from 0 to end_time_s.
  double kinetic_energy_initial_j = 0.0;
  double kinetic_energy_final_j = 0.0;
  double stored_energy_initial_j = 0.0;
  double stored_energy_final_j = 0.0;
  double torque_work_j = 0.0;
  double damping_loss_j = 0.0;
  double friction_loss_j = 0.0;
  // Work of the time-varying stiffness: the integral of 0.5 delta^2 dKe/dX dX/dt
  // plus the jumps of stored energy when a pair enters or leaves under load.
  double parametric_work_j = 0.0;
  double parametric_jump_work_j = 0.0;
  double hertz_energy_max_j = 0.0;
  double bending_energy_max_j = 0.0;
  double axial_energy_max_j = 0.0;
  // (kinetic + stored)(t) - (kinetic + stored)(0) - torque work + losses -
  // parametric work: zero for the exact solution. Final value and largest |value|.
  double ledger_residual_j = 0.0;
  double ledger_residual_max_j = 0.0;
  // The largest kinetic + stored energy of the run, the scale of the residual.
  double ledger_scale_j = 0.0;
  double final_w1_rad_s = 0.0;
  double final_w2_rad_s = 0.0;
  long long steps = 0;   // accepted steps, including those cut at events
  long long events = 0;  // mode changes located
  long long rhs_evaluations = 0;
};

struct SimulationResult {
  std::vector<SeriesRow> series;
  std::vector<ImpactRecord> impacts;
  SimulationSummary summary;
};

// Controls that are not part of the physical case.
struct RunControl {
  bool keep_series = true;
  // false: no event location, the mode (region, pairs, friction sign) is
  // re-evaluated at every RK4 stage. Exists only to show what the cut buys.
  bool locate_events = true;
  // > 0: a constant-stiffness variant of the mesh, Ke of each of the n loaded
  // pairs replaced by this total / n, so the mesh stiffness never changes.
  double constant_mesh_stiffness_n_m = 0.0;
  // When set, asked every kStepsBetweenStopChecks steps; true ends the run
  // with SimulationStopped. Lets a caller cancel a long run (an interactive
  // session's Ctrl-C, a time limit); it may also throw its own exception.
  std::function<bool()> should_stop;
};
// Often enough to stop within about a millisecond of the paper's cases, rarely
// enough that the check costs nothing next to the steps.
inline constexpr long long kStepsBetweenStopChecks = 16384;

// Throws InputError naming the first field outside its range.
void validate(const SimulationCase& c);

SimulationResult simulate(const SimulationCase& c, const RunControl& control = {});
// Same, with a stiffness table already built for c.gears and c.model.stiffness.
SimulationResult simulate(const SimulationCase& c, const StiffnessTable& table,
                          const RunControl& control = {});

// CSV with header t_s,theta1_rad,...,friction_force_N, 17 significant digits.
std::string series_csv(const std::vector<SeriesRow>& rows);
// The summary as a JSON object (absent optional values as null).
std::string summary_json(const SimulationSummary& summary);

// Fig. 7: friction loss / damping loss of each base case for f = from, from +
// step, ..., to. Runs are independent and spread over `threads` threads (0: all
// cores); the result does not depend on the thread count. `should_stop` goes
// to every run's RunControl and is then called from several threads at once.
struct SweepRow {
  double friction_coefficient;
  std::vector<double> ratio;  // one per base case, in order
};
std::vector<SweepRow> sweep_friction(const std::vector<SimulationCase>& cases, double from,
                                     double to, double step, unsigned threads = 0,
                                     const std::function<bool()>& should_stop = {});

}  // namespace gearimpact
