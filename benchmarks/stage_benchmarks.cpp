// The speed of a planetary stage run and of the train loop it runs in
// (docs/planetary.md, "Speed").
//
// The stage: the rotational stage of dynamics/planetary_train.hpp with four
// equally spaced 24-tooth planets between a 24-tooth sun and a 72-tooth ring
// (module 2 mm, 20 mm wide, 0.05 mm backlash, steel discs on the pitch
// circles, the ring four times its disc, the carrier 2e-3 kg m^2 and each
// planet 0.3 kg on its orbit), ring held, the sun driven at 300 rad/s,
// f = 0.04 on the sun meshes, a viscous mesh damper of 0.02 of critical on
// every mesh, the contact damping D of (32) frozen at the reference speed
// (model.damping_update = "frozen", as signal runs take it) and a light load
// of 0.5 N m on the carrier: the ring meshes lose contact and strike again
// all through the run (about 1500 impacts a carrier turn). RK4 at 1, 2 and
// 4 us; docs/planetary.md ("Speed") shows 4 us converged for this case (the
// ring sensor's RMS over a carrier turn and the impacts a turn move by less
// than 0.1 % and 2 % when it halves) and why, with D set by each impact's
// speed, the impact count depends on the step. Seconds of signal per CPU
// second for a 0.2 s record with its
// set-up (the two stiffness tables, about 4 ms) and beyond it (the
// difference of the 0.2 s and 0.1 s runs), CPU time by clock_gettime of the
// calling thread.
//
// The train loop's own cost: the paper's case 2 run as a two-gear train
// (two_gear_train) against the two-gear model (simulate), the table built
// beforehand, alternated within each iteration so that both see the same
// machine state; the ratio of their CPU times.

#include <string>

#include "bench_support.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planetary_train.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact::bench {

namespace {

PlanetaryStage four_planet_stage(double step_s, double end_s) {
  PlanetaryStage s;
  s.teeth = {24, 24, 72};
  s.mesh.gears.module_m = 2.0e-3;
  s.mesh.gears.face_width_m = 20.0e-3;
  s.mesh.gears.backlash_m = 0.05e-3;
  s.mesh.model.friction_coefficient = 0.04;  // the ring meshes take none (planetary_train)
  s.mesh.model.mesh_damping_ratio = 0.02;
  s.mesh.model.damping_update = DampingUpdate::frozen;
  s.planets = 4;
  const auto disc = [&](int z) {
    const double r = 0.5 * s.mesh.gears.module_m * z;
    return s.mesh.gears.density_kg_m3 * pi * r * r * r * r * s.mesh.gears.face_width_m / 2.0;
  };
  s.sun_inertia_kg_m2 = disc(24);
  s.planet_inertia_kg_m2 = disc(24);
  s.ring_inertia_kg_m2 = 4.0 * disc(72);
  s.carrier_inertia_kg_m2 = 2.0e-3;
  s.planet_mass_kg = 0.3;
  s.held = HeldMember::ring;
  s.input_speed_rad_per_s = 300.0;
  s.sun_torque.kind = Torque::Kind::prescribed_speed;
  s.sun_torque.mean_speed_rad_per_s = 300.0;
  s.carrier_torque.kind = Torque::Kind::constant;
  s.carrier_torque.constant_n_m = -0.5;
  s.integrator.kind = IntegratorKind::rk4;
  s.integrator.step_s = step_s;
  s.integrator.end_time_s = end_s;
  return s;
}

// One iteration: the 0.1 s and the 0.2 s record, each a whole run (tables included).
void stage_run(benchmark::State& state, double step_s) {
  RunControl control;
  control.keep_series = false;
  const GearTrain half = planetary_train(four_planet_stage(step_s, 0.1));
  const GearTrain whole = planetary_train(four_planet_stage(step_s, 0.2));
  TrainResult r;
  const auto [cpu_half, cpu_whole] = alternated_cpu_s(
      state, [&] { benchmark::DoNotOptimize(simulate_train(half, control).summary.steps); },
      [&] {
        r = simulate_train(whole, control);
        benchmark::DoNotOptimize(r.summary.steps);
      });
  const auto n = static_cast<double>(state.iterations());
  state.counters["signal_per_cpu_s"] = 0.2 / (cpu_whole / n);
  state.counters["beyond_setup_per_cpu_s"] = 0.1 / ((cpu_whole - cpu_half) / n);
  state.counters["steps"] = static_cast<double>(r.summary.steps);
  state.counters["rhs_per_step"] =
      static_cast<double>(r.summary.rhs_evaluations) / static_cast<double>(r.summary.steps);
  state.counters["events"] = static_cast<double>(r.summary.events);
  state.counters["impacts"] = static_cast<double>(r.summary.impacts_n1 + r.summary.impacts_n2);
  state.counters["ns_per_step"] = cpu_whole / n * 1e9 / static_cast<double>(r.summary.steps);
}

// Case 2 (30 ms, RK4 at 0.1 us) by both paths, the table shared.
void two_gear_as_train(benchmark::State& state) {
  SimulationCase c = paper_case(2);
  auto table = std::make_shared<const StiffnessTable>(c.gears, c.model.stiffness);
  GearTrain train = two_gear_train(c);
  train.meshes.front().table = table;
  RunControl control;
  control.keep_series = false;
  long long steps = 0;
  const auto [cpu_model, cpu_train] = alternated_cpu_s(
      state, [&] { steps = simulate(c, *table, control).summary.steps; },
      [&] { benchmark::DoNotOptimize(simulate_train(train, control).summary.steps); });
  const auto n = static_cast<double>(state.iterations());
  state.counters["model_ns_per_step"] = cpu_model / n * 1e9 / static_cast<double>(steps);
  state.counters["train_ns_per_step"] = cpu_train / n * 1e9 / static_cast<double>(steps);
  state.counters["ratio"] = cpu_train / cpu_model;
}

const bool registered = [] {
  for (const double step_us : {1.0, 2.0, 4.0}) {
    const std::string name =
        "stage/four_planets_rk4_" + std::to_string(static_cast<int>(step_us * 1000.0)) + "ns";
    benchmark::RegisterBenchmark(name.c_str(),
                                 [step_us](benchmark::State& s) { stage_run(s, step_us * 1e-6); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  }
  benchmark::RegisterBenchmark("stage/two_gear_as_train", two_gear_as_train)
      ->Unit(benchmark::kMillisecond)
      ->Iterations(3);
  return true;
}();

}  // namespace

}  // namespace gearimpact::bench
