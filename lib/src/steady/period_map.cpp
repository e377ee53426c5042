#include "gearimpact/steady/period_map.hpp"

#include <cmath>
#include <string>

#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

GearPeriodMap::GearPeriodMap(const SimulationCase& c, const StiffnessTable& table,
                             const SteadySettings& settings, long long steps_per_period)
    : case_(c), table_(&table) {
  // The map's state is the torsional relative motion (s, s'): the planar
  // model's centres and shafts are not in it.
  refuse_planar(c);
  const SteadyTiming timing = steady_timing(c, table, settings);
  if (resolved_damping_update(c) == DampingUpdate::each_impact) {
    throw InputError("model.damping_update", "each_impact",
                     "off or frozen for a period map of (s, s'): under each_impact the Hertzian D "
                     "of the last impact is part of the state");
  }
  if (resolved_damping_update(c) == DampingUpdate::frozen &&
      c.model.damping_stiffness == DampingStiffness::pitch_pair_at_impact) {
    throw InputError("model.damping_stiffness", "pitch_pair_at_impact",
                     "current_pair or hertz for a period map of (s, s'): the pitch pair's Ke is "
                     "remembered from the last impact, a state (s, s') does not carry");
  }
  if (c.model.mesh_stiffness == MeshStiffnessMode::time_varying &&
      !forcing_frequencies(c).empty()) {
    throw InputError("torque1, torque2", "a fluctuating torque with a time-varying mesh stiffness",
                     "constant torques, or model.mesh_stiffness constant: the map of (s, s') "
                     "starts every period at the same mesh position, which only the mesh "
                     "period of a constant-torque case guarantees");
  }
  if (steps_per_period < 0) {
    throw InputError("steps_per_period", static_cast<double>(steps_per_period),
                     "0 (the step of steady_timing) or a whole number of RK4 steps > 0");
  }
  period_s_ = timing.excitation_period_s;
  steps_per_period_ = steps_per_period > 0 ? steps_per_period : timing.steps_per_period;
  step_s_ = period_s_ / static_cast<double>(steps_per_period_);

  const GearPair& g = c.gears;
  rb1_ = base_radius(g, Gear::one);
  rb2_ = base_radius(g, Gear::two);
  const double m1 = moment_of_inertia(g, Gear::one) / (rb1_ * rb1_);
  const double m2 = moment_of_inertia(g, Gear::two) / (rb2_ * rb2_);
  relative_share1_ = m2 / (m1 + m2);
  relative_share2_ = m1 / (m1 + m2);
  const InitialState& y = c.initial;
  centre_m_ = (m1 * rb1_ * y.theta1_rad + m2 * rb2_ * y.theta2_rad) / (m1 + m2);
  centre_speed_m_s_ = (m1 * rb1_ * y.w1_rad_per_s + m2 * rb2_ * y.w2_rad_per_s) / (m1 + m2);
  scale_ = state_scale(c, table);

  case_.integrator.kind = IntegratorKind::rk4;
  case_.integrator.step_s = step_s_;
  case_.integrator.end_time_s = period_s_;
  case_.integrator.output_every = 1;
}

InitialState GearPeriodMap::full_state(double s_m, double s_rate_m_s) const {
  const double u1 = centre_m_ + relative_share1_ * s_m;
  const double u2 = centre_m_ - relative_share2_ * s_m;
  const double v1 = centre_speed_m_s_ + relative_share1_ * s_rate_m_s;
  const double v2 = centre_speed_m_s_ - relative_share2_ * s_rate_m_s;
  return InitialState{u1 / rb1_, u2 / rb2_, v1 / rb1_, v2 / rb2_};
}

Eigen::Vector2d GearPeriodMap::relative_state(const InitialState& state) const {
  return Eigen::Vector2d(rb1_ * state.theta1_rad - rb2_ * state.theta2_rad,
                         rb1_ * state.w1_rad_per_s - rb2_ * state.w2_rad_per_s);
}

Eigen::VectorXd GearPeriodMap::operator()(const Eigen::VectorXd& relative) const {
  if (relative.size() != 2 || !relative.allFinite()) {
    throw InputError("relative state",
                     "a vector of size " + std::to_string(relative.size()) +
                         (relative.allFinite() ? "" : " with a non-finite entry"),
                     "(s_m, s_rate_m_s), two finite numbers");
  }
  SimulationCase run_case = case_;
  run_case.initial = full_state(relative[0], relative[1]);
  RunControl control;
  control.keep_series = false;
  const SimulationResult r = simulate(run_case, *table_, control);
  return relative_state(r.final_state.state);
}

}  // namespace gearimpact
