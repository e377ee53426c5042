#include "gearimpact/steady/period_map.hpp"

#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

GearPeriodMap::GearPeriodMap(const SimulationCase& given, const StiffnessTable& table,
                             const SteadySettings& settings, long long steps_per_period)
    : case_(steady_dynamics_case(given)), table_(&table) {
  // A helical pair maps as its transverse section (steady_dynamics_case).
  const SimulationCase c = case_;
  const SteadyTiming timing = steady_timing(c, table, settings);
  if (resolved_damping_update(c) == DampingUpdate::each_impact) {
    throw InputError("model.damping_update", "each_impact",
                     "off or frozen for a period map: under each_impact the Hertzian D "
                     "of the last impact is part of the state");
  }
  if (resolved_damping_update(c) == DampingUpdate::frozen &&
      c.model.damping_stiffness == DampingStiffness::pitch_pair_at_impact) {
    throw InputError("model.damping_stiffness", "pitch_pair_at_impact",
                     "current_pair or hertz for a period map: the pitch pair's Ke is remembered "
                     "from the last impact, which the map's state does not carry");
  }
  if (c.model.mesh_stiffness == MeshStiffnessMode::time_varying &&
      !forcing_frequencies(c).empty()) {
    throw InputError("torque1, torque2", "a fluctuating torque with a time-varying mesh stiffness",
                     "constant torques, or model.mesh_stiffness constant: the period map "
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
  scale_ = poincare_scale(c, table);

  case_.integrator.kind = IntegratorKind::rk4;
  case_.integrator.step_s = step_s_;
  case_.integrator.end_time_s = period_s_;
  case_.integrator.output_every = 1;

  planar_ = c.bearings.kind == BearingKind::elastic;
  if (planar_) {
    // Everything a planar run of one period takes, once, before any work: the mounting and a
    // step that resolves the bearings and the shafts (each period then runs simulate_planar
    // from its own planar state, which simulate() would put at rest on the bearings).
    RunControl control;
    control.keep_series = false;
    (void)check_run(case_, std::shared_ptr<const StiffnessTable>(std::shared_ptr<void>(), &table),
                    control);
    mounting_ = planar_mounting(c);
    const double jm = mounting_.shafts ? mounting_.motor_inertia_kg_m2 : 0.0;
    const double jl = mounting_.shafts ? mounting_.load_inertia_kg_m2 : 0.0;
    rotation_mass_kg_[0] = m1;
    rotation_mass_kg_[1] = m2;
    rotation_mass_kg_[2] = jm / (rb1_ * rb1_);
    rotation_mass_kg_[3] = jl / (rb2_ * rb2_);
    const double total =
        rotation_mass_kg_[0] + rotation_mass_kg_[1] + rotation_mass_kg_[2] + rotation_mass_kg_[3];
    const PlanarState start = planar_initial_state(c);
    planar_centre_m_ = (rotation_mass_kg_[0] * rb1_ * start.theta1_rad +
                        rotation_mass_kg_[1] * rb2_ * start.theta2_rad +
                        rotation_mass_kg_[2] * rb1_ * start.theta_motor_rad +
                        rotation_mass_kg_[3] * rb2_ * start.theta_load_rad) /
                       total;
    planar_centre_speed_m_s_ = (rotation_mass_kg_[0] * rb1_ * start.w1_rad_per_s +
                                rotation_mass_kg_[1] * rb2_ * start.w2_rad_per_s +
                                rotation_mass_kg_[2] * rb1_ * start.w_motor_rad_per_s +
                                rotation_mass_kg_[3] * rb2_ * start.w_load_rad_per_s) /
                               total;
  }
}

InitialState GearPeriodMap::full_state(double s_m, double s_rate_m_s) const {
  if (planar_) {
    Eigen::VectorXd relative = Eigen::VectorXd::Zero(dimension());
    relative[0] = s_m;
    relative[1] = s_rate_m_s;
    const PlanarState p = planar_state(relative);
    return InitialState{p.theta1_rad, p.theta2_rad, p.w1_rad_per_s, p.w2_rad_per_s};
  }
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

namespace {

void require_map_state(const Eigen::VectorXd& relative, Eigen::Index dimension) {
  if (relative.size() != dimension || !relative.allFinite()) {
    throw InputError("relative state",
                     "a vector of size " + std::to_string(relative.size()) +
                         (relative.allFinite() ? "" : " with a non-finite entry"),
                     dimension == 2 ? std::string("(s_m, s_rate_m_s), two finite numbers")
                                    : std::to_string(dimension) +
                                          " finite numbers, the planar model's poincare_state");
  }
}

}  // namespace

PlanarState GearPeriodMap::planar_state(const Eigen::VectorXd& relative) const {
  if (!planar_) {
    throw InputError("bearings.kind", "\"rigid\"",
                     "\"elastic\" for a planar state: the torsional map's state is (s, s')");
  }
  require_map_state(relative, dimension());
  const Eigen::Index n = (dimension() - 2) / 2;  // displacements (and speeds) beyond (s, s')
  const std::array<double, 4>& m = rotation_mass_kg_;
  const double total = m[0] + m[1] + m[2] + m[3];
  const bool shafts = mounting_.shafts;
  // u1 = X + ((m2 + m_l) s - m_m q_m - m_l q_l) / M (period_map.hpp), u2 = u1 - s, u_m = u1 +
  // q_m, u_l = u2 + q_l; the same for the speeds.
  const auto turning = [&](double centre, double s, double qm, double ql) {
    const double u1 = centre + ((m[1] + m[3]) * s - m[2] * qm - m[3] * ql) / total;
    const double u2 = u1 - s;
    return std::array<double, 4>{u1, u2, u1 + qm, u2 + ql};
  };
  const auto u = turning(planar_centre_m_, relative[0], shafts ? relative[6] : 0.0,
                         shafts ? relative[7] : 0.0);
  const auto v = turning(planar_centre_speed_m_s_, relative[1], shafts ? relative[2 + n + 4] : 0.0,
                         shafts ? relative[2 + n + 5] : 0.0);
  PlanarState p;
  p.theta1_rad = u[0] / rb1_;
  p.theta2_rad = u[1] / rb2_;
  p.theta_motor_rad = u[2] / rb1_;
  p.theta_load_rad = u[3] / rb2_;
  p.w1_rad_per_s = v[0] / rb1_;
  p.w2_rad_per_s = v[1] / rb2_;
  p.w_motor_rad_per_s = v[2] / rb1_;
  p.w_load_rad_per_s = v[3] / rb2_;
  p.x1_m = relative[2];
  p.y1_m = relative[3];
  p.x2_m = relative[4];
  p.y2_m = relative[5];
  p.vx1_m_s = relative[2 + n];
  p.vy1_m_s = relative[3 + n];
  p.vx2_m_s = relative[4 + n];
  p.vy2_m_s = relative[5 + n];
  return p;
}

Eigen::VectorXd GearPeriodMap::map_state(const RunState& state) const {
  return poincare_state(case_, state);
}

Eigen::VectorXd GearPeriodMap::operator()(const Eigen::VectorXd& relative) const {
  require_map_state(relative, dimension());
  if (planar_) {
    RunControl control;
    control.keep_series = false;
    const SimulationResult r =
        simulate_planar(case_, *table_, mounting_, planar_state(relative), control);
    return poincare_state(case_, r.final_state);
  }
  SimulationCase run_case = case_;
  run_case.initial = full_state(relative[0], relative[1]);
  RunControl control;
  control.keep_series = false;
  const SimulationResult r = simulate(run_case, *table_, control);
  return relative_state(r.final_state.state);
}

}  // namespace gearimpact
