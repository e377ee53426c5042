// The band-limited sample (RunControl::sample = interval-average, docs/signals.md "The sensor's
// sample"): each acceleration is the mean over the interval ending at its sample. Checked against
// the velocities of the same run's point samples (the velocity difference over the interval, and
// its telescoping sum), against a closed-form tone (a prescribed driver, and a linear oscillator
// it drives on the forced solution: gain sinc(f T), delay T / 2), and on the rig's record, whose
// first mesh harmonic converges with the sample rate where the point sample's does not.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/paper/table1.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

SimulationResult sampled(const SimulationCase& c, double rate, SampleKind kind) {
  RunControl control;
  control.keep_series = false;
  control.sample_rate_hz = rate;
  control.sample = kind;
  return simulate(c, control);
}

double sinc(double x) {
  return x == 0.0 ? 1.0 : std::sin(pi * x) / (pi * x);
}

// The driver's mean speed W, its harmonic's order n and speed amplitude a, the drag T_d (as the
// rattle suite's forced solution, there derived): w1 = W + a cos(w t), w = n W.
constexpr double kMeanSpeed = 200.0;
constexpr double kOrder = 10.0;
constexpr double kAmplitude = 0.4;  // half the rigid limit's separating amplitude, 0.80 rad/s
constexpr double kDrag = 2.0;

// Case 1's pair without friction or damping, a constant mesh stiffness k, its pinion driven by
// w1 = W + a cos(w t) against a constant drag on the wheel, started on the forced solution of
// the wheel on the spring: u = Rb2 theta2 moves as Rb1 (W t + (a / w) sin(w t) / (1 - r^2)) +
// const, r^2 = m2 w^2 / k, so w2 = (Rb1 / Rb2) (W + a cos(w t) / (1 - r^2)).
SimulationCase driven_oscillator(double k) {
  SimulationCase c = driven_loose_gear(k, kMeanSpeed, kOrder, kAmplitude, kDrag);
  const double m2 = moment_of_inertia(c.gears, Gear::two) /
                    (base_radius(c.gears, Gear::two) * base_radius(c.gears, Gear::two));
  c.integrator.end_time_s = 0.03;
  c.integrator.step_s = std::min(2.0 * pi / std::sqrt(k / m2) / 40.0, 2e-6);
  return c;
}

}  // namespace

TEST_CASE("an interval-average sample times its interval is the velocity difference over it") {
  // Sampling leaves the run as it is, so the point run's velocities are the interval run's.
  SimulationCase c = paper_case(3);
  c.integrator.end_time_s = 0.004;
  const double fs = 3.3e5;  // unrelated to the step: most samples inside steps, some at events
  const SimulationResult point = sampled(c, fs, SampleKind::point);
  const SimulationResult average = sampled(c, fs, SampleKind::interval_average);
  REQUIRE(average.samples.size() + 1 == point.samples.size());
  double scale = 0.0;
  for (const SampleRow& r : point.samples) scale = std::max(scale, std::fabs(r.w1_rad_per_s));
  double sum1 = 0.0;
  double sum2 = 0.0;
  for (std::size_t i = 0; i < average.samples.size(); ++i) {
    const SampleRow& a = average.samples[i];
    const SampleRow& before = point.samples[i];
    const SampleRow& after = point.samples[i + 1];
    REQUIRE(a.t_s == after.t_s);
    const double interval = after.t_s - before.t_s;
    // Rounding: the velocities' last bits (scale eps) and one division and product.
    CHECK(std::fabs(a.acceleration1_rad_per_s2 * interval -
                    (after.w1_rad_per_s - before.w1_rad_per_s)) <= 4e-16 * scale);
    CHECK(std::fabs(a.acceleration2_rad_per_s2 * interval -
                    (after.w2_rad_per_s - before.w2_rad_per_s)) <= 4e-16 * scale);
    // The other columns are the point values of the state at t_n.
    CHECK(a.w1_rad_per_s == after.w1_rad_per_s);
    CHECK(a.dte_m == after.dte_m);
    sum1 += a.acceleration1_rad_per_s2 * interval;
    sum2 += a.acceleration2_rad_per_s2 * interval;
  }
  // The sum telescopes: the velocity change over the record, to rounding over its samples.
  const double n = static_cast<double>(average.samples.size());
  CHECK(std::fabs(sum1 - (point.samples.back().w1_rad_per_s -
                          point.samples.front().w1_rad_per_s)) <= 4e-16 * scale * n);
  CHECK(std::fabs(sum2 - (point.samples.back().w2_rad_per_s -
                          point.samples.front().w2_rad_per_s)) <= 4e-16 * scale * n);
}

TEST_CASE("a tone reads A sinc(f T) at a delay of T / 2: a prescribed driver and the oscillator") {
  const GearPair g = paper_case(1).gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const double m2 = moment_of_inertia(g, Gear::two) / (rb2 * rb2);
  const double w = kOrder * kMeanSpeed;
  // r^2 = 0.04: the wheel's contact mode 5 times the driver's harmonic.
  const double k = m2 * w * w / 0.04;
  const SimulationCase c = driven_oscillator(k);
  const double wheel_gain = rb1 / rb2 / (1.0 - 0.04);
  const double f = w / (2.0 * pi);
  // f T from 0.05 to 0.45: sinc from 0.996 down to 0.23.
  for (const double ft : {0.05, 0.2, 0.45}) {
    CAPTURE(ft);
    const double fs = f / ft;
    const double T = 1.0 / fs;
    const SimulationResult r = sampled(c, fs, SampleKind::interval_average);
    REQUIRE(r.samples.size() > 10);
    double worst1 = 0.0;
    double worst2 = 0.0;
    for (const SampleRow& s : r.samples) {
      // The mean of w1' = -a w sin(w t) over [t_n - T, t_n].
      const double tone = -kAmplitude * w * sinc(ft) * std::sin(w * (s.t_s - 0.5 * T));
      worst1 = std::max(worst1, std::fabs(s.acceleration1_rad_per_s2 - tone));
      worst2 = std::max(worst2, std::fabs(s.acceleration2_rad_per_s2 - wheel_gain * tone));
    }
    // The driver is closed form: only the rounding of W + a cos(w t) (eps W) over T, 2e-13 of the
    // tone at f T = 0.05.
    CHECK(worst1 <= 8.0 * 2.2e-16 * kMeanSpeed / T);
    CHECK(worst1 / (kAmplitude * w) <= 1e-12);
    // The wheel goes through the integrator (RK4 at <= 2 us, its dense output of order 3): its
    // velocity error over T, measured 5e-9 of the tone at f T = 0.05 (the shortest T), 2e-10 at
    // 0.2 and 0.45.
    CHECK(worst2 / (wheel_gain * kAmplitude * w) <= 5e-8);
  }
}

namespace {

// The rig's sensor record from t = 0.2 s (its speed controller settled: every revolution after
// 0.2 s is within 1.9e-7 of the reference speed, test_drive) over 3 revolutions at its nominal
// 40 Hz, and the amplitude of its first mesh harmonic (680 Hz) by a DFT at that
// frequency: the window holds whole mesh periods, so the line falls on a bin.
double rig_first_mesh_harmonic(const SimulationCase& rig, double fs, SampleKind kind) {
  constexpr double start = 0.2;
  constexpr double revolutions = 3.0;
  const double f_mesh = 17.0 * 40.0;
  const double end = start + revolutions / 40.0;
  SimulationCase c = rig;
  c.integrator.end_time_s = end + 1e-4;
  std::complex<double> sum = 0.0;
  long long count = 0;
  RunControl control;
  control.keep_series = false;
  control.keep_samples = false;
  control.sample_rate_hz = fs;
  control.sample = kind;
  control.on_planar_sample = [&](const PlanarSample& s) {
    // (start, end]: half a sample's margin against the rounding of t_n.
    if (s.t_s <= start + 0.5 / fs || s.t_s > end + 0.5 / fs) return;
    sum += s.sensor_acceleration_m_per_s2 * std::polar(1.0, -2.0 * pi * f_mesh * s.t_s);
    ++count;
  };
  simulate(c, control);
  REQUIRE(count == static_cast<long long>(std::llround(revolutions / 40.0 * fs)));
  return 2.0 * std::abs(sum) / static_cast<double>(count);
}

}  // namespace

TEST_CASE("the rig's first mesh harmonic converges with the sample rate under interval averages") {
  SimulationCase rig = read_case_file(std::string(GEARIMPACT_EXAMPLES_DIR) + "/rig_17_38.toml");
  // The example as it is (speed-controlled, D frozen at 1 m/s). A window from 25 ms instead
  // holds the controller's start, which is not periodic in the window: its content folds onto
  // the line's bin and moves it by 12 % from 20 to 640 kHz, under either sample.
  std::vector<double> average;
  std::vector<double> point;
  for (const double fs : {20e3, 40e3, 80e3, 160e3, 320e3, 640e3}) {
    average.push_back(rig_first_mesh_harmonic(rig, fs, SampleKind::interval_average) /
                      sinc(680.0 / fs));  // the stated droop, 0.2 % at 20 kHz, divided out
    point.push_back(rig_first_mesh_harmonic(rig, fs, SampleKind::point));
    MESSAGE("fs " << fs << " Hz: interval average " << average.back() << ", point " << point.back()
                  << " m/s^2");
  }
  for (std::size_t i = 0; i < average.size(); ++i) {
    CHECK(relative_difference(average[i], average.back()) <= 0.01);
  }
  // The point samples' folded steps move the line by more than that.
  double spread = 0.0;
  for (const double p : point) spread = std::max(spread, relative_difference(p, point.back()));
  CHECK(spread > 0.05);
}

TEST_CASE("a planar run: each interval average is its velocity difference over the interval") {
  SimulationCase c = read_case_file(std::string(GEARIMPACT_EXAMPLES_DIR) + "/rig_17_38.toml");
  c.integrator.end_time_s = 0.003;
  const double fs = 2.7e5;
  RunControl control;
  control.keep_series = false;
  control.sample_rate_hz = fs;
  control.sample = SampleKind::point;
  const SimulationResult point = simulate(c, control);
  control.sample = SampleKind::interval_average;
  const SimulationResult average = simulate(c, control);
  REQUIRE(average.planar_samples.size() + 1 == point.planar_samples.size());
  const double angle = c.bearings.sensor_angle_rad;
  for (std::size_t i = 0; i < average.planar_samples.size(); ++i) {
    const PlanarSample& a = average.planar_samples[i];
    const PlanarState& before = point.planar_samples[i].state;
    const PlanarState& after = point.planar_samples[i + 1].state;
    REQUIRE(a.t_s == point.planar_samples[i + 1].t_s);
    const double interval = a.t_s - point.planar_samples[i].t_s;
    const double dvx = c.bearings.sensor_gear == 1 ? after.vx1_m_s - before.vx1_m_s
                                                   : after.vx2_m_s - before.vx2_m_s;
    const double dvy = c.bearings.sensor_gear == 1 ? after.vy1_m_s - before.vy1_m_s
                                                   : after.vy2_m_s - before.vy2_m_s;
    const double scale = std::fabs(dvx) + std::fabs(dvy) + 1e-300;
    CHECK(std::fabs(a.ax1_m_per_s2 * interval - (after.vx1_m_s - before.vx1_m_s)) <=
          4e-16 * std::fabs(after.vx1_m_s - before.vx1_m_s));
    CHECK(std::fabs(a.alpha1_rad_per_s2 * interval - (after.w1_rad_per_s - before.w1_rad_per_s)) <=
          4e-16 * std::fabs(after.w1_rad_per_s - before.w1_rad_per_s));
    // The sensor's is the centre's along its direction: that projection of the differences.
    CHECK(std::fabs(a.sensor_acceleration_m_per_s2 * interval -
                    (dvx * std::cos(angle) + dvy * std::sin(angle))) <= 1e-15 * scale);
    CHECK(a.state.x1_m == after.x1_m);
  }
}
