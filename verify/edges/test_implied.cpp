// Inputs whose harm shows only in what they imply together: a torque whose static deflection is
// past the tooth model, a speed the step cannot resolve, a step no contact period allows, a
// friction or restitution coefficient beyond physics, a torque kind without its keys, a sweep
// end far out, a pair without backlash, energy ratios of terms that are off. Each refusal exits 1
// with one message that names the key as the user wrote it and its bound, and never prints nan;
// each check has a positive control, the paper's cases and the sharded sweep's case.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/stiffness/energy.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "relative.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

namespace fs = std::filesystem;
using namespace gearimpact;
using gearimpact::verify::cli;
using gearimpact::verify::CommandResult;
using gearimpact::verify::relative_difference;
using gearimpact::verify::run_command;
using gearimpact::verify::Scratch;

namespace {

constexpr double kPi = 3.141592653589793;
const std::string kSweepCase = GEARIMPACT_SWEEP_CASE;

// One refusal: exit 1, one "gearimpact: error:" line that names `key`, no nan or empty range.
void check_refusal(const CommandResult& r, const std::string& key) {
  INFO(r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.err.rfind("gearimpact: error: ", 0) == 0);
  CHECK(r.err.find(key) != std::string::npos);
  CHECK(r.err.find("nan") == std::string::npos);
  CHECK(r.err.find("(0, 0]") == std::string::npos);
  CHECK(r.err.find("inf ") == std::string::npos);
  CHECK(r.out.empty());
}

// The number that follows `label` in `text`.
double number_after(const std::string& text, const std::string& label) {
  const std::size_t at = text.find(label);
  REQUIRE(at != std::string::npos);
  return std::strtod(text.c_str() + at + label.size(), nullptr);
}

// The printed numbers carry 4 significant digits: half a unit of the 4th is 5e-4 relative.
constexpr double kPrinted = 5e-4;

std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string error_of(const SimulationCase& c) {
  try {
    validate(c);
  } catch (const InputError& e) {
    return e.field();
  }
  return {};
}

}  // namespace

TEST_CASE("a torque whose static deflection is past the tooth model is refused, naming it") {
  const CommandResult r =
      run_command(cli("simulate --case 1 --t-end 1ms --set 'torque1.value=1e300 N*m'"));
  check_refusal(r, "--set torque1.value = 1e300 N*m");
  CHECK(r.err.find("lower the torque") != std::string::npos);
  // The tooth load is |T1| / Rb1 with Rb1 = m Z1 cos(a0) / 2 (2 mm, 20 teeth, 20 deg).
  const double rb1 = 0.002 * 20 / 2.0 * std::cos(20.0 * kPi / 180.0);
  const double load = number_after(r.err, "|T1|/Rb1 = ");
  CHECK(relative_difference(load, 1e300 / rb1) <= kPrinted);
  // The deflection printed is that load over the stiffness printed, and the bound is a tenth
  // of the module times that stiffness times Rb1.
  const double stiffness = number_after(r.err, "smallest mesh stiffness ");
  CHECK(relative_difference(number_after(r.err, "static deflection of "), load / stiffness) <=
        2 * kPrinted);
  CHECK(relative_difference(number_after(r.err, "|T1| <= "), 0.1 * 0.002 * stiffness * rb1) <=
        2 * kPrinted);
  // A steel spur pair of 10 mm face width: the single-pair mesh stiffness is some 1e8 N/m.
  CHECK(stiffness > 1e8);
  CHECK(stiffness < 1e9);

  // A soft material implies the same: the sweep's loaded case at E = 1e-300 Pa.
  check_refusal(run_command(cli("simulate --case-file " + kSweepCase +
                                " --set 'gears.youngs_modulus=1e-300 Pa'")),
                "torque1.value");

  // The library refuses it alike (Python sees the same error).
  SimulationCase c = paper_case(2);
  c.torque1.constant_n_m = 1e300;
  CHECK(error_of(c) == "torque1.value");
  c = paper_case(3);
  c.torque1.amplitude_n_m = 1e300;
  CHECK(error_of(c) == "torque1.amplitude");
}

TEST_CASE("a speed the step cannot resolve is refused with the largest allowed speed") {
  const CommandResult r =
      run_command(cli("simulate --case 1 --t-end 1ms --set 'initial.w1=1e300 rad/s'"));
  check_refusal(r, "--set initial.w1 = 1e300 rad/s");
  // 20 steps of 0.1 us per mesh period 2 pi / (20 |w1|).
  CHECK(relative_difference(number_after(r.err, "|w1| <= "), 2 * kPi / (20 * 20 * 1e-7)) <=
        kPrinted);
  check_refusal(run_command(cli("simulate --case 1 --t-end 1ms --set 'initial.w2=-1e7 rad/s'")),
                "--set initial.w2");

  SimulationCase c = paper_case(1);
  c.initial.w1_rad_per_s = 1.6e5;
  CHECK(error_of(c) == "initial.w1");
  c.initial.w1_rad_per_s = 1.5e5;
  CHECK(error_of(c).empty());
}

TEST_CASE("a forcing the step cannot resolve is refused with the largest allowed frequency") {
  const CommandResult r = run_command(
      cli("simulate --case 3 --t-end 1ms --set 'torque1.angular_frequency=1e300 rad/s'"));
  check_refusal(r, "--set torque1.angular_frequency = 1e300 rad/s");
  // 20 steps of 0.1 us per forcing period 2 pi / W.
  CHECK(relative_difference(number_after(r.err, "at most "), 2 * kPi / (20 * 1e-7)) <= kPrinted);

  SimulationCase c = paper_case(3);
  c.torque1.angular_frequency_rad_per_s = 3.2e6;
  CHECK(error_of(c) == "torque1.angular_frequency");
  c.torque1.angular_frequency_rad_per_s = 3.1e6;
  CHECK(error_of(c).empty());
  c.torque1.kind = Torque::Kind::harmonic;
  c.torque1.harmonic_amplitudes_n_m = {1.0, 1.0};
  c.torque1.harmonic_angular_frequencies_rad_per_s = {1e3, 3.2e6};
  c.torque1.harmonic_phases_rad = {0.0, 0.0};
  CHECK(error_of(c) == "torque1.angular_frequencies[1]");
}

TEST_CASE("a friction or restitution coefficient beyond physics is refused by its row") {
  const CommandResult f =
      run_command(cli("simulate --case 1 --t-end 1ms --set model.friction_coefficient=1e300"));
  check_refusal(f, "--set model.friction_coefficient");
  CHECK(f.err.find("[0, 1]") != std::string::npos);
  const CommandResult e =
      run_command(cli("simulate --case 1 --t-end 1ms --set model.restitution_coefficient=1e300"));
  check_refusal(e, "--set model.restitution_coefficient");
  CHECK(e.err.find("[0, 1]") != std::string::npos);
  // The ends themselves are allowed.
  CHECK(run_command(cli("simulate --case 1 --t-end 0.1ms --set model.friction_coefficient=1 "
                        "--set model.restitution_coefficient=1"))
            .exit_code == 0);
}

TEST_CASE("a contact period too short for any step names the keys that set it") {
  const CommandResult r =
      run_command(cli("simulate --case 1 --t-end 1ms --set 'gears.density=1e-300 kg/m^3'"));
  check_refusal(r, "integrator.step");
  CHECK(r.err.find("gears.density") != std::string::npos);
  CHECK(r.err.find("gears.youngs_modulus") != std::string::npos);

  // A step merely too large prints the contact period and the bound 1/20 of it.
  const CommandResult big =
      run_command(cli("simulate --case 1 --t-end 1ms --set integrator.step=10us"));
  check_refusal(big, "integrator.step");
  const double bound = number_after(big.err, "<= ");
  const double period = number_after(big.err, "that period is ");
  CHECK(relative_difference(period, 20 * bound) <= kPrinted);
  // The paper's pair: 2 pi sqrt(m_e / K) with m_e = 0.052 kg of the discs and K some 1e8 N/m
  // puts the period near 0.1 ms.
  CHECK(period > 1e-5);
  CHECK(period < 1e-3);
}

TEST_CASE("a torque kind set on the command line requires its keys") {
  const CommandResult r =
      run_command(cli("simulate --case 2 --t-end 1ms --set torque1.kind=sinusoidal"));
  check_refusal(r, "--set torque1.kind = sinusoidal");
  CHECK(r.err.find("torque1.amplitude") != std::string::npos);
  CHECK(r.err.find("torque1.angular_frequency") != std::string::npos);
  CHECK(r.err.find("--set 'torque1.amplitude=...'") != std::string::npos);
  // With them it runs; an unchanged kind needs nothing.
  CHECK(run_command(cli("simulate --case 2 --t-end 0.1ms --set torque1.kind=sinusoidal "
                        "--set 'torque1.amplitude=1 N*m' --set 'torque1.angular_frequency=100'"))
            .exit_code == 0);
  CHECK(run_command(cli("simulate --case 2 --t-end 0.1ms --set torque1.kind=constant")).exit_code ==
        0);

  // A case file's kind without its keys is refused by the reader, naming the key.
  Scratch scratch("implied-kind");
  std::string text = read(std::string(GEARIMPACT_PAPER_DATA_DIR) + "/case2.toml");
  const std::size_t at = text.find("kind = \"constant\"");
  REQUIRE(at != std::string::npos);
  text.replace(at, 17, "kind = \"sinusoidal\"");
  const std::size_t value = text.find("value = ", at);
  text.erase(value, text.find('\n', value) - value);
  std::ofstream(scratch.dir / "kind.toml") << text;
  check_refusal(run_command(cli("check-case " + (scratch.dir / "kind.toml").string())),
                "torque1.amplitude");
}

TEST_CASE("a sweep end far out is refused with the speed bound, never nan") {
  Scratch scratch("implied-sweep");
  const CommandResult r = run_command(
      cli("sweep " + kSweepCase +
          " --vary initial.w1 --from '2000 rad/s' --to '1e308 rad/s' --points 2 --out " +
          (scratch.dir / "s1").string() + " --no-plots"));
  check_refusal(r, "initial.w1");
  CHECK(r.err.find("an end of the sweep") != std::string::npos);
  CHECK(r.err.find("|w1| <= ") != std::string::npos);
  CHECK_FALSE(fs::exists(scratch.dir / "s1"));
}

TEST_CASE("a pair without backlash has a steady state: its scale is a thousandth of the module") {
  Scratch scratch("implied-backlash");
  const fs::path out = scratch.dir / "s2";
  const CommandResult r = run_command(
      cli("sweep " + kSweepCase + " --vary gears.backlash --from 0 --to 1e-4 --points 2 --out " +
          out.string() + " --no-plots"));
  INFO(r.err);
  CHECK(r.exit_code == 0);
  const std::string rows = read(out / "sweep.csv");
  CHECK(rows.find("nan") == std::string::npos);

  // (max(B, 1e-3 m), that times w_n): B itself while there is backlash.
  SimulationCase c = read_case_file(kSweepCase);
  const StiffnessTable table(c.gears, c.model.stiffness);
  CHECK(state_scale(c, table)(0) == c.gears.backlash_m);
  c.gears.backlash_m = 0.0;
  const Eigen::Vector2d scale = state_scale(c, table);
  CHECK(relative_difference(scale(0), 1e-3 * 0.002) <= 1e-15);
  CHECK(scale(1) > 0.0);
}

TEST_CASE("energy ratios of a term that is off are 0; without bending they are refused") {
  Scratch scratch("implied-energy");
  std::string text = read(std::string(GEARIMPACT_PAPER_DATA_DIR) + "/case1.toml");
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const std::size_t at = t.find(from);
    REQUIRE(at != std::string::npos);
    t.replace(at, from.size(), to);
    return t;
  };
  std::ofstream(scratch.dir / "no-bending.toml")
      << with("bending_term = \"on\"", "bending_term = \"off\"");
  std::ofstream(scratch.dir / "no-hertz.toml")
      << with("hertz_term = \"on\"", "hertz_term = \"off\"");
  check_refusal(run_command(cli("energy-ratios --points 3 --case-file " +
                                (scratch.dir / "no-bending.toml").string())),
                "model.bending_term");
  const CommandResult r = run_command(
      cli("energy-ratios --points 3 --case-file " + (scratch.dir / "no-hertz.toml").string()));
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("nan") == std::string::npos);
  CHECK(r.out.find("inf") == std::string::npos);

  StiffnessModel model;
  model.terms.on[index_of(Term::hertz)] = false;
  for (const EnergyRatios& row : energy_ratio_cycle(paper_gear_pair(), 5, model)) {
    CHECK(row.hertz_over_bending_one_pair == 0.0);
    CHECK(row.hertz_over_bending_system == 0.0);
    CHECK(row.axial_over_bending_one_pair > 0.0);
  }
  model.terms.on[index_of(Term::bending)] = false;
  CHECK_THROWS_AS(energy_ratio_cycle(paper_gear_pair(), 5, model), InputError);
}

TEST_CASE("a start pressed into contact at rest, whose damping RK4 cannot carry, is refused") {
  // Case 2's pair and torques, the pinion turned so that s - B is about 0.37 um, both at rest:
  // the approach speed is 0, floored to 1e-9 m/s, and (32)-(33) give a damping D without bound
  // as Vi falls; with the tooth load its rate per step h D F / m_e is far past RK4's 2.785, and
  // the run used to diverge within six steps into an overlap of 1e4 m blamed on a missing tooth.
  const std::string start =
      "simulate --case 2 --set 'initial.theta1=0.00268 rad' --set 'initial.w1=0 rad/s'";
  const CommandResult r = run_command(cli(start + " --t-end 1ms"));
  check_refusal(r, "initial.theta1");
  CHECK(r.err.find("model.damping_update = \"frozen\"") != std::string::npos);
  // D is (32)'s Herbert-McWhannell factor 6 (1 - e) / (((2 e - 1)^2 + 3) Vi) at Vi = 1e-9 m/s,
  // e = 1 - 0.022 (Vi / (1 mm/s))^0.375 (33), the case's law.
  const double vi = 1e-9;
  const double e = 1.0 - 0.022 * std::pow(vi / 1e-3, 0.375);
  const double d = 6.0 * (1.0 - e) / (((2.0 * e - 1.0) * (2.0 * e - 1.0) + 3.0) * vi);
  CHECK(relative_difference(number_after(r.err, "is D = "), d) <= 1e-12);
  // The rate is h D F / m_e with h = 0.1 us and the printed load; m_e of the paper's discs
  // (bores 20 and 60 mm) is about 0.05 kg, so the rate is some 70: refused by a wide margin.
  const double rate = number_after(r.err, "h D F / m_e = ");
  const double load = number_after(r.err, "tooth load ");
  CHECK(rate > 2.785);
  CHECK(relative_difference(rate / load, 1e-7 * d / effective_mass_kg(paper_case(2).gears)) <=
        1e-12);
  // The fixed-step Dormand-Prince is refused alike: its real stability interval, [-3.3066, 0]
  // (the order-5 polynomial sum z^k / k! to k = 5 plus z^6 / 600), holds a rate of some 70 no
  // better than RK4's, and the run would diverge the same way.
  const CommandResult dopri5 =
      run_command(cli(start + " --set integrator.kind=dopri5 --t-end 1ms"));
  check_refusal(dopri5, "initial.theta1");
  CHECK(dopri5.err.find("Dormand-Prince") != std::string::npos);
  CHECK(relative_difference(number_after(dopri5.err, "h D F / m_e = "), rate) <= 1e-12);

  // The remedies the message names run the same start: a damping frozen at a reference impact
  // speed, and the adaptive integrator (without friction, whose exact reversal at rest would
  // stall its event location, a matter of its own); the ledger closes on both (its bound as the
  // dynamics suites': 1e-9 of the largest energy).
  for (const std::string fix :
       {"--set model.damping_update=frozen --t-end 1ms",
        "--set integrator.kind=adaptive --set model.friction_coefficient=0 --t-end 0.2ms"}) {
    const CommandResult ok = run_command(cli(start + " " + fix));
    INFO(fix, ok.err);
    REQUIRE(ok.exit_code == 0);
    CHECK(std::fabs(number_after(ok.out, "\"ledger_residual_max_J\": ")) <=
          1e-9 * number_after(ok.out, "\"ledger_scale_J\": "));
  }
  // A damping frozen at a reference speed near rest is known before the run: refused alike,
  // naming its key, with the same D as (32)-(33) give at that speed (4 digits printed).
  const CommandResult frozen =
      run_command(cli("simulate --case 2 --t-end 1ms --set model.damping_update=frozen --set "
                      "'model.damping_reference_speed=1e-9 m/s'"));
  check_refusal(frozen, "--set model.damping_reference_speed = 1e-9 m/s");
  CHECK(relative_difference(number_after(frozen.err, "give D = "), d) <= kPrinted);
  SimulationCase c = paper_case(2);
  c.model.damping_update = DampingUpdate::frozen;
  c.model.damping_reference_speed_m_s = 1e-9;
  CHECK(error_of(c) == "model.damping_reference_speed");
  c.model.damping_reference_speed_m_s = 1e-3;
  CHECK(error_of(c).empty());
  // Apart in the backlash the same torques run as case 2 does.
  CHECK(run_command(cli("simulate --case 2 --t-end 1ms --set 'initial.w1=0 rad/s'")).exit_code ==
        0);
}

TEST_CASE("the paper's cases and the sharded sweep's case pass every implied check") {
  for (int n = 1; n <= 3; ++n) {
    CAPTURE(n);
    CHECK(error_of(paper_case(n)).empty());
  }
  CHECK(error_of(read_case_file(kSweepCase)).empty());
  CHECK(run_command(cli("check-case " + kSweepCase)).exit_code == 0);
}
