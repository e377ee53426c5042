#include "gearimpact/dynamics/sliced_pair.hpp"

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/named_values.hpp"
#include "gearimpact/stiffness/fillet_foundation.hpp"

namespace gearimpact {

namespace {

// The name two_gear_train gives the pair's mesh: the train's refusals address the pair's keys
// by it ("meshes.mesh.model.face_slices"), which the two-gear case file has without it.
const std::string kMeshPrefix = "meshes.mesh.";

// Runs `check`, its refusals renamed to the keys as a two-gear case file has them.
template <typename Check>
auto named_as_pair(Check check) {
  try {
    return check();
  } catch (const InputError& e) {
    std::vector<Problem> problems;
    for (const Problem& p : e.problems()) {
      const bool pair_key = p.field.compare(0, kMeshPrefix.size(), kMeshPrefix) == 0;
      problems.push_back(pair_key ? p.renamed(p.field.substr(kMeshPrefix.size()), p.value) : p);
    }
    throw InputError(std::move(problems));
  }
}

// What route A refuses of the two-gear run beyond the train's own checks.
void refuse_in_sliced_run(const SimulationCase& c, const RunControl& control) {
  const std::string why =
      "a helical pair with modifications runs by slices (route A of "
      "docs/helical.md) as a gear train's meshes";
  if (c.bearings.kind == BearingKind::elastic) {
    // The planar train holds the two gears on their bearings, not a motor and a load behind
    // shafts, nor a tacho's edges, nor a speed controller.
    if (c.shafts.kind == ShaftKind::elastic) {
      throw InputError(std::vector<Problem>{refused_problem(
          "shafts.kind", "\"elastic\"",
          why + " on their bearings, without a motor and a load behind shafts",
          "\"none\" with modifications on a helical pair",
          "shafts.kind = \"none\", or no modifications (route B runs with shafts)")});
    }
    if (c.tacho.pulses_per_revolution > 0) {
      throw InputError(std::vector<Problem>{refused_problem(
          "tacho.pulses_per_revolution", std::to_string(c.tacho.pulses_per_revolution),
          why + ", whose loop locates no tacho edges",
          "0 (no tacho) with modifications on a helical pair")});
    }
    for (const Torque* t : {&c.torque1, &c.torque2}) {
      if (t->kind != Torque::Kind::speed_controlled) continue;
      throw InputError(std::vector<Problem>{refused_problem(
          t == &c.torque1 ? "torque1.kind" : "torque2.kind", "\"speed-controlled\"",
          why + ", which on elastic bearings take no speed controller yet",
          "a torque other than speed-controlled with modifications on a helical pair on "
          "elastic bearings")});
    }
  }
  if (c.torque1.kind == Torque::Kind::prescribed_speed) {
    throw InputError(std::vector<Problem>{refused_problem(
        "torque1.kind", "\"prescribed-speed\"",
        why + ": the rattle summary of a kinematic driver is a single contact's",
        "a torque other than prescribed-speed with modifications on a helical pair")});
  }
  if (control.sample_rate_hz) {
    throw InputError("sample_rate", format_number(*control.sample_rate_hz) + " Hz",
                     "none: " + why + ", whose loop keeps the integrator's rows only");
  }
  if (control.resume) {
    throw InputError("resume", "a state to continue from",
                     "none: " + why + ", whose run starts from the case's initial state");
  }
  if (!control.locate_events) {
    throw InputError("locate_events", "false", "true: " + why + ", whose loop cuts at events");
  }
}

// The two-gear row of the train's row (simulate_by_slices' series, sliced_pair.hpp).
SeriesRow pair_row(const TrainRow& r) {
  SeriesRow row{};
  row.t_s = r.t_s;
  row.theta1_rad = r.theta_rad[0];
  row.theta2_rad = r.theta_rad[1];
  row.w1_rad_per_s = r.w_rad_per_s[0];
  row.w2_rad_per_s = r.w_rad_per_s[1];
  row.s_m = r.meshes.front().s_m;
  row.region = static_cast<int>(Region::free);
  bool pressed = false;
  for (const TrainMeshRow& m : r.meshes) {
    row.pairs += m.pairs;
    row.normal_force_n += m.normal_force_n;
    row.friction_force_n += m.friction_force_n;
    if (m.region == static_cast<int>(Region::free)) continue;
    if (!pressed || m.delta_m > row.delta_m) {
      row.delta_m = m.delta_m;
      row.region = m.region;
      pressed = true;
    }
  }
  return row;
}

// The planar row of the train's row (simulate_by_slices' planar series): the two bodies'
// centres and bearing forces, each line's force summed over the slices and its penetration the
// largest of theirs, the thrust of those summed forces as route B reports it.
PlanarRow planar_row(const TrainRow& r, const HelicalThrustLevers& thrust) {
  PlanarRow row;
  row.t_s = r.t_s;
  PlanarState& p = row.state;
  const TrainCentreRow& c1 = r.centres[0];
  const TrainCentreRow& c2 = r.centres[1];
  p.x1_m = c1.x_m;
  p.y1_m = c1.y_m;
  p.theta1_rad = r.theta_rad[0];
  p.x2_m = c2.x_m;
  p.y2_m = c2.y_m;
  p.theta2_rad = r.theta_rad[1];
  p.theta_motor_rad = p.theta1_rad;
  p.theta_load_rad = p.theta2_rad;
  p.vx1_m_s = c1.vx_m_s;
  p.vy1_m_s = c1.vy_m_s;
  p.w1_rad_per_s = r.w_rad_per_s[0];
  p.vx2_m_s = c2.vx_m_s;
  p.vy2_m_s = c2.vy_m_s;
  p.w2_rad_per_s = r.w_rad_per_s[1];
  p.w_motor_rad_per_s = p.w1_rad_per_s;
  p.w_load_rad_per_s = p.w2_rad_per_s;
  row.bearing_fx1_n = c1.bearing_fx_n;
  row.bearing_fy1_n = c1.bearing_fy_n;
  row.bearing_fx2_n = c2.bearing_fx_n;
  row.bearing_fy2_n = c2.bearing_fy_n;
  for (std::size_t k = 0; k < r.meshes.size(); ++k) {
    const TrainMeshRow& m = r.meshes[k];
    row.drive_force_n += m.line_force_n[0];
    row.coast_force_n += m.line_force_n[1];
    row.drive_penetration_m = k == 0 ? m.line_penetration_m[0]
                                     : std::max(row.drive_penetration_m, m.line_penetration_m[0]);
    row.coast_penetration_m = k == 0 ? m.line_penetration_m[1]
                                     : std::max(row.coast_penetration_m, m.line_penetration_m[1]);
  }
  const HelicalThrust h = thrust(row.drive_force_n, row.coast_force_n);
  row.axial_force1_n = h.axial_force1_n;
  row.axial_force2_n = h.axial_force2_n;
  row.tilting_moment1_n_m = h.tilting_moment1_n_m;
  row.tilting_moment2_n_m = h.tilting_moment2_n_m;
  return row;
}

}  // namespace

bool runs_by_slices(const SimulationCase& c) {
  return c.gears.helix_angle_rad != 0.0 && !is_unmodified(c.modifications);
}

SimulationResult simulate_by_slices(const SimulationCase& c, const RunControl& control,
                                    const std::function<void()>& fields_checked) {
  if (!runs_by_slices(c)) {
    throw InputError("modifications", "none, or gears.helix_angle = 0",
                     "a helical pair with modifications (route A); simulate() runs the others");
  }
  // The two-gear run's checks of its keys, its helical refusals but the modifications (which
  // the slices take), then route A's own and the train's, all before any work.
  validate_absent_run_keys(c);
  validate_fields(c);
  SimulationCase plain = c;
  plain.modifications = Modifications{};
  refuse_helical_run(plain);
  refuse_in_sliced_run(c, control);
  const SimulationCase d = dynamics_case(c);
  refuse_planar_simulation(d);
  const bool planar = c.bearings.kind == BearingKind::elastic;
  if (planar) validate_planar(d, planar_mounting(d), {});
  validate_run_control(d, control);
  const GearTrain train = two_gear_train(c);
  named_as_pair([&] {
    check_train(train);
    return 0;
  });
  if (fields_checked) fields_checked();

  SimulationResult result;
  RunControl run_control;
  run_control.keep_series = false;
  run_control.should_stop = control.should_stop;
  std::optional<HelicalThrustLevers> thrust;
  if (planar) thrust.emplace(d.gears);
  if (control.keep_series || control.on_row || (planar && control.on_planar_row)) {
    run_control.on_train_row = [&](const TrainRow& r) {
      const SeriesRow row = pair_row(r);
      if (control.on_row) control.on_row(row);
      if (control.keep_series) result.series.push_back(row);
      if (!planar) return;
      const PlanarRow planar_series_row = planar_row(r, *thrust);
      if (control.on_planar_row) control.on_planar_row(planar_series_row);
      if (control.keep_series) result.planar_series.push_back(planar_series_row);
    };
  }
  TrainResult run = named_as_pair([&] { return simulate_train(train, run_control); });

  // The outputs name the slices as the train's run does.
  const GearTrain sliced = dynamics_train(train);
  SimulationSummary& s = result.summary;
  s = run.summary;
  s.case_name = c.name;
  s.damping_update = resolved_damping_update(c);
  s.stiffness_model = c.model.stiffness.kind;
  s.friction_coefficient = c.model.friction_coefficient;
  s.friction_law = c.model.friction_law;
  s.foundation_extrapolations = foundation_extrapolations(d.gears, c.model.stiffness);
  s.foundation_extrapolated = !s.foundation_extrapolations.empty();
  s.max_penetration_m = 0.0;
  for (std::size_t k = 0; k < run.meshes.size(); ++k) {
    const TrainMeshSummary& m = run.meshes[k];
    SliceSummary slice;
    slice.name = sliced.meshes[k].name;
    for (const ImpactRecord& impact : run.impacts[k]) {
      (impact.line == Region::n1 ? slice.impacts_n1 : slice.impacts_n2) += 1;
      result.impacts.push_back(impact);
    }
    slice.max_penetration_m = m.max_penetration_m;
    slice.damping_loss_j = m.damping_loss_j;
    slice.mesh_damping_loss_j = m.mesh_damping_loss_j;
    s.max_penetration_m = std::max(s.max_penetration_m, m.max_penetration_m);
    s.slices.push_back(std::move(slice));
  }
  std::stable_sort(
      result.impacts.begin(), result.impacts.end(),
      [](const ImpactRecord& a, const ImpactRecord& b) { return a.start_s < b.start_s; });
  // final_state stays empty: a run by route A is not continued (resume is refused).
  return result;
}

}  // namespace gearimpact
