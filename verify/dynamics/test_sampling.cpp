// Samples of a run at exact times t0 + n / fs (RunControl::sample_rate_hz):
// the grid, the integration left as it is, the dense output's order, its value
// at a step's end, a closed form in free flight, the accelerations against the
// equations of motion, and the refusals.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/paper/table1.hpp"
#include "relative.hpp"
#include "run_command.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

SimulationResult sampled(const SimulationCase& c, double rate, bool keep_series = false) {
  RunControl control;
  control.keep_series = keep_series;
  control.sample_rate_hz = rate;
  // The point values at t_n, whose grid and dense output this suite checks (the interval
  // averages are test_sensor_sample's).
  control.sample = SampleKind::point;
  return simulate(c, control);
}

bool same_bits(const SampleRow& a, const SampleRow& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

std::string message_of(const SimulationCase& c, const RunControl& control) {
  try {
    simulate(c, control);
  } catch (const InputError& e) {
    return e.field() + " | " + e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("samples lie at t0 + n / fs exactly, strictly increasing, floor(T fs) + 1 of them") {
  for (const IntegratorKind kind : {IntegratorKind::rk4, IntegratorKind::adaptive}) {
    CAPTURE(static_cast<int>(kind));
    SimulationCase c = paper_case(1);
    c.integrator.kind = kind;
    c.integrator.end_time_s = 0.005;
    // 200 kHz: T fs = 1000 (the rounding of 0.005 * 2e5 does not reach a whole sample).
    const double fs = 2e5;
    const SimulationResult r = sampled(c, fs);
    REQUIRE(r.samples.size() == static_cast<std::size_t>(std::floor(0.005 * fs)) + 1);
    for (std::size_t n = 0; n < r.samples.size(); ++n) {
      // The one formula, written out: t0 = 0.
      CHECK(r.samples[n].t_s == 0.0 + static_cast<double>(n) / fs);
      if (n > 0) CHECK(r.samples[n].t_s > r.samples[n - 1].t_s);
    }
    CHECK(r.samples.back().t_s == c.integrator.end_time_s);
  }
}

TEST_CASE(
    "sampling leaves the run as it is: summary, series, impacts and final state bit for bit") {
  for (const int number : {1, 3}) {
    for (const IntegratorKind kind : {IntegratorKind::rk4, IntegratorKind::adaptive}) {
      CAPTURE(number);
      CAPTURE(static_cast<int>(kind));
      SimulationCase c = paper_case(number);
      c.integrator.kind = kind;
      c.integrator.end_time_s = 0.004;
      const SimulationResult plain = simulate(c);
      // A rate unrelated to the step, so that most samples fall inside steps.
      const SimulationResult with = sampled(c, 3.7e6, true);
      CHECK(with.samples.size() > 10000);
      CHECK(summary_json(with.summary) == summary_json(plain.summary));
      CHECK(series_csv(with.series) == series_csv(plain.series));
      REQUIRE(with.impacts.size() == plain.impacts.size());
      for (std::size_t i = 0; i < plain.impacts.size(); ++i) {
        CHECK(with.impacts[i].start_s == plain.impacts[i].start_s);
        CHECK(with.impacts[i].impact_speed_m_s == plain.impacts[i].impact_speed_m_s);
      }
      // Member by member: the planar state a torsional run leaves empty is an optional, whose
      // unused storage is not part of the value.
      const RunState& a = with.final_state;
      const RunState& b = plain.final_state;
      CHECK(std::memcmp(&a.time_s, &b.time_s, sizeof b.time_s) == 0);
      CHECK(std::memcmp(&a.state, &b.state, sizeof b.state) == 0);
      CHECK(std::memcmp(&a.contact, &b.contact, sizeof b.contact) == 0);
      CHECK(std::memcmp(&a.coast_contact, &b.coast_contact, sizeof b.coast_contact) == 0);
      CHECK_FALSE(a.planar);
      CHECK_FALSE(b.planar);
    }
  }
}

TEST_CASE("a sample at a step's end is that step's state bit for bit") {
  SimulationCase c = paper_case(1);
  // Steps and samples on binary fractions of a second, so that every fourth
  // step's end is a sample time exactly: h = 2^-24 s, fs = 2^22 Hz.
  c.integrator.step_s = std::ldexp(1.0, -24);
  c.integrator.end_time_s = std::ldexp(1.0, -10);
  const SimulationResult r = sampled(c, std::ldexp(1.0, 22), true);
  REQUIRE(r.samples.size() == 4097);
  std::size_t matched = 0;
  std::size_t row = 0;
  for (const SampleRow& s : r.samples) {
    while (row < r.series.size() && r.series[row].t_s < s.t_s) ++row;
    REQUIRE(row < r.series.size());
    REQUIRE(r.series[row].t_s == s.t_s);
    const SeriesRow& q = r.series[row];
    CHECK(s.theta1_rad == q.theta1_rad);
    CHECK(s.theta2_rad == q.theta2_rad);
    CHECK(s.w1_rad_per_s == q.w1_rad_per_s);
    CHECK(s.w2_rad_per_s == q.w2_rad_per_s);
    CHECK(s.s_m == q.s_m);
    ++matched;
  }
  CHECK(matched == r.samples.size());
  CHECK(r.summary.impacts_n1 + r.summary.impacts_n2 > 1);
}

TEST_CASE("RK4's dense output is of order 3: its error at mid-step falls 16-fold a halving") {
  // One step of h in an N1 contact (a spring against the approach, smooth
  // while the contact lasts), sampled at h / 2, against the
  // step of h / 2 from the same state. RK4's own local error is O(h^5); the
  // continuous extension's is O(h^4), so the difference falls as h^4.
  // The pinion approaches at 10 mm/s: started at rest, the damping each
  // impact sets would be unbounded (Vi = 0), and the run is refused.
  SimulationCase c = paper_case(1);
  const double rb1 = base_radius(c.gears, Gear::one);
  c.initial = InitialState{(c.gears.backlash_m + 1e-6) / rb1, 0.0, 0.01 / rb1, 0.0};
  std::vector<double> errors;
  for (const double h : {1e-7, 5e-8, 2.5e-8, 1.25e-8}) {
    SimulationCase coarse = c;
    coarse.integrator.step_s = h;
    coarse.integrator.end_time_s = h;
    const SimulationResult r = sampled(coarse, 2.0 / h);
    REQUIRE(r.samples.size() == 3);
    REQUIRE(r.samples[1].region == static_cast<int>(Region::n1));
    SimulationCase fine = c;
    fine.integrator.step_s = h / 2.0;
    fine.integrator.end_time_s = h / 2.0;
    RunControl quiet;
    quiet.keep_series = false;
    const SimulationResult f = simulate(fine, quiet);
    REQUIRE(f.summary.events == 0);
    // t = 1 / (2 / h) is h / 2 within a rounding; w2 = 0 at the start, so
    // the rounding moves theta2 by far less than the error measured.
    errors.push_back(std::fabs(r.samples[1].w2_rad_per_s - f.final_state.state.w2_rad_per_s));
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double ratio = errors[i - 1] / errors[i];
    CAPTURE(errors[i - 1]);
    CAPTURE(errors[i]);
    MESSAGE("mid-step error ratio a halving: ", ratio);
    // 2^4 = 16 in the limit; the next term of the error moves it by O(h).
    CHECK(ratio > 13.0);
    CHECK(ratio < 19.0);
  }
}

TEST_CASE("free flight under constant torques: the closed form of uniform acceleration") {
  SimulationCase c = paper_case(1);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double j1 = moment_of_inertia(c.gears, Gear::one);
  const double j2 = moment_of_inertia(c.gears, Gear::two);
  // s'' = Rb1 T1 / J1 - Rb2 T2 / J2 = 0: the gears stay mid-backlash, s = 0.
  const double t1 = 2.0;
  const double t2 = rb1 * t1 * j2 / (j1 * rb2);
  c.torque1 = Torque{};
  c.torque1.constant_n_m = t1;
  c.torque2 = Torque{};
  c.torque2.constant_n_m = t2;
  const double w1 = 300.0;
  c.initial = InitialState{0.0, 0.0, w1, w1 * rb1 / rb2};
  c.integrator.end_time_s = 0.002;
  const SimulationResult r = sampled(c, 123456.0);
  REQUIRE(r.summary.events == 0);
  REQUIRE(r.samples.size() == 247);
  const double a1 = t1 / j1;
  const double a2 = t2 / j2;
  double worst = 0.0;
  for (const SampleRow& s : r.samples) {
    CHECK(s.region == 0);
    CHECK(s.normal_force_n1_n == 0.0);
    CHECK(s.normal_force_n2_n == 0.0);
    const double t = s.t_s;
    worst = std::max({worst, relative_difference(s.theta1_rad, w1 * t + 0.5 * a1 * t * t),
                      relative_difference(s.theta2_rad, w1 * rb1 / rb2 * t + 0.5 * a2 * t * t),
                      relative_difference(s.w1_rad_per_s, w1 + a1 * t),
                      relative_difference(s.w2_rad_per_s, w1 * rb1 / rb2 + a2 * t)});
    // The right-hand side in free flight is T / J itself.
    CHECK(relative_difference(s.acceleration1_rad_per_s2, a1) < 1e-15);
    CHECK(relative_difference(s.acceleration2_rad_per_s2, a2) < 1e-15);
  }
  MESSAGE("largest relative difference from the closed form: ", worst);
  // RK4 and the cubic extension are exact for a quadratic; what is left is
  // the rounding of 20,000 steps' sums (each a few 1e-16): 4e-13 measured.
  CHECK(worst < 1e-12);
}

TEST_CASE("accelerations are the moments over J from the force columns (f = 0)") {
  SimulationCase c = paper_case(2);
  c.model.friction_coefficient = 0.0;
  c.integrator.end_time_s = 0.003;
  const SimulationResult r = sampled(c, 1e6);
  const double rb1 = base_radius(c.gears, Gear::one);
  const double rb2 = base_radius(c.gears, Gear::two);
  const double j1 = moment_of_inertia(c.gears, Gear::one);
  const double j2 = moment_of_inertia(c.gears, Gear::two);
  REQUIRE(c.model.mesh_force == MeshForce::newtonian);
  REQUIRE(c.model.mesh_damping_ratio == 0.0);
  int in_contact = 0;
  for (const SampleRow& s : r.samples) {
    CAPTURE(s.t_s);
    const double line = s.normal_force_n1_n - s.normal_force_n2_n;
    CHECK((s.normal_force_n1_n == 0.0 || s.normal_force_n2_n == 0.0));
    if (s.region != 0) ++in_contact;
    const double m1 = torque_at(c.torque1, s.t_s) - rb1 * line;
    const double m2 = torque_at(c.torque2, s.t_s) + rb2 * line;
    // The same sums in another order: a few roundings of the largest term.
    const double scale1 = std::max(std::fabs(torque_at(c.torque1, s.t_s)), rb1 * std::fabs(line));
    const double scale2 = std::max(std::fabs(torque_at(c.torque2, s.t_s)), rb2 * std::fabs(line));
    CHECK(std::fabs(s.acceleration1_rad_per_s2 * j1 - m1) <= 1e-14 * scale1);
    CHECK(std::fabs(s.acceleration2_rad_per_s2 * j2 - m2) <= 1e-14 * scale2);
    // DTE from the drive flank's contact: s - B.
    CHECK(s.dte_m == s.s_m - c.gears.backlash_m);
  }
  CHECK(in_contact > 100);
}

TEST_CASE("each sample lies in its step's mode: no interpolation across an event") {
  for (const IntegratorKind kind : {IntegratorKind::rk4, IntegratorKind::adaptive}) {
    CAPTURE(static_cast<int>(kind));
    SimulationCase c = paper_case(1);
    c.integrator.kind = kind;
    c.integrator.end_time_s = 0.01;
    const SimulationResult r = sampled(c, 9.1e6);
    REQUIRE(r.summary.impacts_n1 + r.summary.impacts_n2 > 3);
    const double b = c.gears.backlash_m;
    // Events are located to about 1e-12 of the backlash (the deflections'
    // scale); a sample in the wrong mode would be off by the motion over a
    // step, some 1e-4 of B.
    const double tolerance = 1e-9 * b;
    double worst = 0.0;
    for (const SampleRow& s : r.samples) {
      const double outside = s.region == 1    ? -(s.s_m - b)
                             : s.region == -1 ? -(-s.s_m - b)
                                              : std::fabs(s.s_m) - b;
      worst = std::max(worst, outside);
    }
    MESSAGE("largest step past the mode's boundary: ", worst / b, " B");
    CHECK(worst <= tolerance);
  }
}

TEST_CASE("a sampled run is bit-identical across reruns") {
  SimulationCase c = paper_case(3);
  c.integrator.end_time_s = 0.003;
  const SimulationResult a = sampled(c, 2.5e6);
  const SimulationResult b = sampled(c, 2.5e6);
  REQUIRE(a.samples.size() == b.samples.size());
  for (std::size_t i = 0; i < a.samples.size(); ++i) CHECK(same_bits(a.samples[i], b.samples[i]));
}

TEST_CASE("bad sample rates are refused before the run, naming sample_rate and its range") {
  const SimulationCase c = paper_case(1);
  for (const double rate : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    RunControl control;
    control.sample_rate_hz = rate;
    control.sample = SampleKind::point;
    const std::string m = message_of(c, control);
    CAPTURE(m);
    CHECK(m.rfind("sample_rate |", 0) == 0);
    CHECK(m.find("a finite rate > 0 Hz") != std::string::npos);
  }
  RunControl many;
  many.sample_rate_hz = 1e13;  // 3e11 samples in 30 ms
  const std::string m = message_of(c, many);
  CAPTURE(m);
  CHECK(m.rfind("sample_rate |", 0) == 0);
  CHECK(m.find("a rate in (0, ") != std::string::npos);
  CHECK(m.find("at most 50000000 samples") != std::string::npos);
  RunControl unlocated;
  unlocated.locate_events = false;
  unlocated.sample_rate_hz = 1e5;
  CHECK(message_of(c, unlocated).find("locate_events") != std::string::npos);
}

TEST_CASE(
    "simulate --sample-rate writes the samples and the same summary; refusals name the flag") {
  using gearimpact::verify::cli;
  using gearimpact::verify::run_command;
  const std::string out =
      (std::filesystem::temp_directory_path() / "gearimpact_test_samples.csv").string();
  std::filesystem::remove(out);
  const auto plain = run_command(cli("simulate --case 1 --t-end 0.001"));
  const auto r = run_command(cli("simulate --case 1 --t-end 0.001 --sample-rate 1e6 --out " + out));
  REQUIRE(r.exit_code == 0);
  CHECK(r.out == plain.out);
  std::ifstream in(out);
  std::string line;
  std::getline(in, line);
  CHECK(line ==
        "t_s,theta1_rad,theta2_rad,w1_rad_s,w2_rad_s,w1_dot_rad_s2,w2_dot_rad_s2,s_m,dte_m,"
        "normal_force_n1_N,normal_force_n2_N,region,pairs");
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  // Interval averages by default: n = 1 ... 1000 (n = 0 ends no interval).
  CHECK(rows == 1000);
  std::filesystem::remove(out);
  const auto point = run_command(
      cli("simulate --case 1 --t-end 0.001 --sample-rate 1e6 --sample point --out " + out));
  REQUIRE(point.exit_code == 0);
  std::ifstream point_in(out);
  rows = 0;
  while (std::getline(point_in, line)) ++rows;
  CHECK(rows == 1002);  // the header and n = 0 ... 1000
  std::filesystem::remove(out);
  for (const auto& [flags, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--sample-rate 0 --out " + out,
            "--sample-rate = 0 is outside the allowed range: a finite rate > 0 Hz"},
           {"--sample-rate inf --out " + out, "--sample-rate = \"inf\": no finite decimal number"},
           {"--sample-rate 1e12 --out " + out,
            "a rate in (0, 49999999000] Hz: at most 50000000 samples"},
           {"--sample-rate 1e6 --every 10 --out " + out, "--every = 10: contradicts --sample-rate"},
           {"--sample-rate 1e6", "--sample-rate = 1e6: needs --out"},
           {"--sample-rate 1e6 --sample pointy --out " + out,
            "--sample = pointy is outside the allowed range: one of interval-average, point"},
           {"--sample point --out " + out, "--sample = point: needs --sample-rate"}}) {
    CAPTURE(flags);
    const auto bad = run_command(cli("simulate --case 1 --t-end 0.001 " + flags));
    CHECK(bad.exit_code == 1);
    CHECK(bad.err.find(expected) != std::string::npos);
    CHECK(!std::filesystem::exists(out));
  }
}
