// The step policy of the planar run (docs/vibration.md, "Step policy"): on the
// test-rig-like pair of examples/rig_17_38.toml with a root crack of q = 0.5 h_c
// in pinion tooth 0, halving the step moves the RMS of the sensor's
// acceleration (the pinion bearing's, across the centre line) by less than
// 1e-4 of it, over the record from 0.05 s to 0.45 s (16 pinion revolutions
// after the start's ringing has decayed) sampled at 51.2 kHz. The bar is
// asserted at each method's step and shown to fail a little above it: the
// steps sit just below where the bar is crossed, with about a third to spare.
// And the rig's samples are the same bits run again and run on two threads.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <future>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planar_state.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "rig_drive.hpp"

using namespace gearimpact;

namespace {

constexpr double kRecordStartS = 0.05;
constexpr double kRecordEndS = 0.45;
constexpr double kSampleRateHz = 51200.0;
constexpr double kBar = 1e-4;

SimulationCase cracked_rig() {
  SimulationCase c = read_case_file(std::string(GEARIMPACT_EXAMPLES_DIR) + "/rig_17_38.toml");
  // The drive and the reading the policy was set with: constant torques
  // balancing friction's 17.592 W at 40 Hz and D set at each impact. The
  // example's own drive (a speed controller) and frozen D converge faster:
  // halving dopri5's 4 us moves the RMS by 5.7e-6, its 4.5 us by 1.0e-5 and
  // RK4's 2.5 us by 3.5e-6, so the guards above the bar would not fail there.
  gearimpact::verify::use_rig_constant_drive(c);
  ToothFault crack;
  crack.gear = Gear::one;
  crack.tooth = 0;
  crack.state.kind = ToothKind::root_crack;
  crack.state.crack.angle_rad = pi / 4.0;
  const PlacedCrack placed = place_crack(crack.state.crack, rack_gear_pair_geometry(c.gears).gear1,
                                         c.model.stiffness.kind, c.gears.face_width_m);
  crack.state.crack.depth_m = 0.5 * placed.start_half_thickness_m;
  c.faults = {crack};
  c.integrator.end_time_s = kRecordEndS;
  return c;
}

// The RMS of the sensor's acceleration over the record, by `kind` at `step`.
double sensor_rms(const SimulationCase& rig, const StiffnessTable& table, IntegratorKind kind,
                  double step_s) {
  SimulationCase c = rig;
  c.integrator.kind = kind;
  c.integrator.step_s = step_s;
  RunControl control;
  control.keep_series = false;
  control.keep_samples = false;
  control.sample_rate_hz = kSampleRateHz;
  double sum = 0.0;
  long long count = 0;
  control.on_planar_sample = [&](const PlanarSample& s) {
    if (s.t_s < kRecordStartS || s.t_s >= kRecordEndS) return;
    sum += s.sensor_acceleration_m_per_s2 * s.sensor_acceleration_m_per_s2;
    ++count;
  };
  simulate(c, table, control);
  // 0.4 s at 51.2 kHz: 20480 samples, the start's t = n / fs rounding aside.
  CHECK(std::abs(count - 20480) <= 1);
  return std::sqrt(sum / static_cast<double>(count));
}

// |RMS(h) - RMS(h/2)| / RMS(h/2).
double halving_change(const SimulationCase& rig, const StiffnessTable& table, IntegratorKind kind,
                      double step_s) {
  const double coarse = sensor_rms(rig, table, kind, step_s);
  const double fine = sensor_rms(rig, table, kind, step_s / 2.0);
  MESSAGE(name_of(kIntegratorKinds, kind)
          << " at " << step_s * 1e6 << " us: RMS " << coarse << " m/s^2, at half the step " << fine
          << " m/s^2, change " << std::fabs(coarse - fine) / fine);
  return std::fabs(coarse - fine) / fine;
}

}  // namespace

TEST_CASE("the planar step policy: the largest steps whose halving moves the sensor's RMS < 1e-4") {
  const SimulationCase rig = cracked_rig();
  const StiffnessTable table(rig.gears, rig.model.stiffness);
  SUBCASE("Dormand-Prince at 4 us") {
    CHECK(halving_change(rig, table, IntegratorKind::dopri5, 4e-6) < kBar);
    // 4.25 us still meets it (9.7e-5), 4.5 us does not.
    CHECK(halving_change(rig, table, IntegratorKind::dopri5, 4.5e-6) > kBar);
  }
  SUBCASE("RK4 at 1.75 us") {
    CHECK(halving_change(rig, table, IntegratorKind::rk4, 1.75e-6) < kBar);
    CHECK(halving_change(rig, table, IntegratorKind::rk4, 2e-6) > kBar);
  }
  SUBCASE("RK4 at 2.5 us, the step an earlier policy chose, fails the bar") {
    // Its measure was the RMS of the bearing's force over the pinion's mass,
    // which the mesh force's fluctuation does not reach: that moved by 7e-5
    // when 2.5 us halved, the sensor by 2.7e-4.
    CHECK(halving_change(rig, table, IntegratorKind::rk4, 2.5e-6) > 2.0 * kBar);
  }
}

TEST_CASE("the rig's samples are bit-identical across reruns and threads") {
  // Nothing of a run is shared but the healthy table, read only: a run on
  // another thread, beside a second one, gives the same bits as alone.
  SimulationCase rig = cracked_rig();
  rig.integrator.end_time_s = 0.02;
  const StiffnessTable table(rig.gears, rig.model.stiffness);
  for (const IntegratorKind kind : {IntegratorKind::dopri5, IntegratorKind::rk4}) {
    CAPTURE(name_of(kIntegratorKinds, kind));
    SimulationCase c = rig;
    c.integrator.kind = kind;
    c.integrator.step_s = kind == IntegratorKind::dopri5 ? 4e-6 : 1.75e-6;
    const auto run = [&] {
      RunControl control;
      control.keep_series = false;
      control.sample_rate_hz = kSampleRateHz;
      return simulate(c, table, control).planar_samples;
    };
    const std::vector<PlanarSample> alone = run();
    const std::vector<PlanarSample> again = run();
    auto first = std::async(std::launch::async, run);
    auto second = std::async(std::launch::async, run);
    const std::vector<PlanarSample> threaded[2] = {first.get(), second.get()};
    REQUIRE(alone.size() == 1024);  // interval averages: n = 1 ... 1024 of 0.02 s at 51.2 kHz
    for (const std::vector<PlanarSample>* other : {&again, &threaded[0], &threaded[1]}) {
      REQUIRE(other->size() == alone.size());
      // PlanarSample holds doubles only: equal bytes are equal bits.
      CHECK(std::memcmp(other->data(), alone.data(), alone.size() * sizeof(PlanarSample)) == 0);
    }
  }
}
