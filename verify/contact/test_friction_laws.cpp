// The friction laws of docs/model.md (section Contact, damping, friction): Benedict and
// Kelley's coefficient against a hand computation, its clip, the constant law unchanged, the
// ledger under the varying f, the smoothed sign converging to the exact switch, and the keys'
// refusals. Every expected value comes from the formula worked by hand or from the exact-switch
// run, never from this code's earlier output.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/paper/table1.hpp"

using namespace gearimpact;

namespace {

// The imperial units of the formula, written out here independently of the library.
constexpr double kInch = 0.0254;              // m
constexpr double kPoundPerInch = 175.126835;  // N/m, 4.4482216 N / 0.0254 m to 9 digits
constexpr double kCentipoise = 1e-3;          // Pa s
constexpr double kMicroinch = 0.0254e-6;      // m

double relative_difference(double a, double b) {
  const double scale = std::max(std::fabs(a), std::fabs(b));
  return scale == 0.0 ? 0.0 : std::fabs(a - b) / scale;
}

BenedictKelleyLaw law_at(double roughness_uin, double viscosity_cp, double f_max = 0.1) {
  BenedictKelleyLaw law;
  law.viscosity_pa_s = viscosity_cp * kCentipoise;
  law.roughness_m = roughness_uin * kMicroinch;
  law.most_coefficient = f_max;
  return law;
}

// Paper case 2 for 10 ms, the summary only.
SimulationCase case2() {
  SimulationCase c = paper_case(2);
  c.integrator.end_time_s = 10e-3;
  return c;
}

SimulationSummary run_summary(const SimulationCase& c) {
  RunControl control;
  control.keep_series = false;
  return simulate(c, control).summary;
}

// A lubricant of 100 cP (an ISO VG 100 oil near 40 C) and flanks of 0.4 um (15.7 micro-inches).
SimulationCase case2_benedict_kelley() {
  SimulationCase c = case2();
  c.model.friction_law = FrictionLaw::benedict_kelley;
  c.model.benedict_kelley.viscosity_pa_s = 100.0 * kCentipoise;
  c.model.benedict_kelley.roughness_m = 0.4e-6;
  return c;
}

std::string error_of(const std::string& toml) {
  try {
    parse_case(toml, "friction.toml");
  } catch (const Error& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST_CASE("Benedict and Kelley's f at a hand-computed point") {
  // W/F = 1000 lbf/in, nu0 = 10 cP, Vs = 50 in/s, Ve = 400 in/s, S = 16 micro-inches:
  // C_R = 50 / (50 - 16) = 1.470588235; the log argument 3.17e8 x 1000 / (10 x 50 x 400^2)
  // = 3.17e11 / 8e7 = 3962.5, log10(3962.5) = 3 + log10(3.9625) = 3.597969275;
  // f = 0.0127 x 1.470588235 x 3.597969275 = 0.0671973673.
  const BenedictKelleyLaw law = law_at(16.0, 10.0);
  const double f =
      benedict_kelley_coefficient(law, 1000.0 * kPoundPerInch, 50.0 * kInch, 400.0 * kInch);
  // kPoundPerInch has 9 digits: a relative error of 3e-10 in W moves f by
  // 3e-10 / (ln 10 x 3.6) ~ 4e-11 of itself.
  CHECK(relative_difference(f, 0.0671973673) < 1e-9);
  // The sign of the speeds does not matter: |Vs| and |Ve| enter.
  CHECK(benedict_kelley_coefficient(law, 1000.0 * kPoundPerInch, -50.0 * kInch, -400.0 * kInch) ==
        f);
}

TEST_CASE("Benedict and Kelley's units: lbf/in, cP, in/s and micro-inches each enter once") {
  const BenedictKelleyLaw law = law_at(16.0, 10.0);
  const double w = 1000.0 * kPoundPerInch;
  const double vs = 50.0 * kInch;
  const double ve = 400.0 * kInch;
  const double f = benedict_kelley_coefficient(law, w, vs, ve);
  const double decade = 0.0127 * 50.0 / 34.0;  // f per factor 10 in the log argument
  // W/F = 1 lbf/in: the argument is 1000 times smaller, f three decades lower:
  // 0.0127 x 1.470588235 x log10(3.9625) = 0.018676471 x 0.597969275 = 0.0111679556.
  CHECK(relative_difference(benedict_kelley_coefficient(law, kPoundPerInch, vs, ve), 0.0111679556) <
        1e-8);
  // 1 cP = 1e-3 Pa s: 100 cP puts f one decade lower.
  CHECK(std::fabs(benedict_kelley_coefficient(law_at(16.0, 100.0), w, vs, ve) - (f - decade)) <
        1e-12);
  // 1 in/s = 0.0254 m/s: Vs 10 times and Ve sqrt(10) times faster, one decade each.
  CHECK(std::fabs(benedict_kelley_coefficient(law, w, 10.0 * vs, ve) - (f - decade)) < 1e-12);
  CHECK(std::fabs(benedict_kelley_coefficient(law, w, vs, std::sqrt(10.0) * ve) - (f - decade)) <
        1e-12);
  // S = 0: C_R = 1, f = 0.0127 x 3.597969275 = 0.0456942098.
  CHECK(relative_difference(benedict_kelley_coefficient(law_at(0.0, 10.0), w, vs, ve),
                            0.0456942098) < 1e-9);
  // The case file reads viscosities in Pa*s, mPa*s and cP.
  CHECK(parse_quantity("10 cP", Dimension::viscosity, "x") == 0.01);
  CHECK(parse_quantity("10 mPa*s", Dimension::viscosity, "x") == 0.01);
  CHECK(parse_quantity("0.01 Pa*s", Dimension::viscosity, "x") == 0.01);
}

TEST_CASE("Benedict and Kelley's f is clipped to [0, f_max]") {
  const BenedictKelleyLaw law = law_at(16.0, 10.0, 0.1);
  const double w = 1000.0 * kPoundPerInch;
  // At the pitch point the formula diverges: f = f_max.
  CHECK(benedict_kelley_coefficient(law, w, 0.0, 400.0 * kInch) == 0.1);
  CHECK(benedict_kelley_coefficient(law, w, 50.0 * kInch, 0.0) == 0.1);
  // Vs = 1e-6 in/s: 0.0127 x 1.470588 x log10(3.17e11 / (10 x 1e-6 x 400^2)) = 0.211 > f_max.
  CHECK(benedict_kelley_coefficient(law, w, 1e-6 * kInch, 400.0 * kInch) == 0.1);
  // 1 lbf/in, 100 cP, 1000 in/s each: argument 3.17e8 / 1e11 = 3.2e-3 < 1, the formula < 0.
  CHECK(benedict_kelley_coefficient(law_at(16.0, 100.0), kPoundPerInch, 1000.0 * kInch,
                                    1000.0 * kInch) == 0.0);
  // No load: no friction, even at the pitch point (the argument would be 0 / 0).
  CHECK(benedict_kelley_coefficient(law, 0.0, 0.0, 400.0 * kInch) == 0.0);
  CHECK(benedict_kelley_coefficient(law, 0.0, 50.0 * kInch, 400.0 * kInch) == 0.0);
}

TEST_CASE("the constant law written out is the run without the key, every column bit for bit") {
  SimulationCase c = case2();
  const std::string text = write_case_file(c);
  REQUIRE(text.find("friction_law") == std::string::npos);
  REQUIRE(text.find("friction_smoothing_speed") == std::string::npos);
  std::string with_keys = text;
  const std::string anchor = "[model]\n";
  const std::size_t at = with_keys.find(anchor);
  REQUIRE(at != std::string::npos);
  with_keys.insert(at + anchor.size(),
                   "friction_law = \"constant\"\nfriction_smoothing_speed = \"0 m/s\"\n");
  const SimulationCase explicit_constant = parse_case(with_keys, "case2.toml");
  const SimulationResult a = simulate(c);
  const SimulationResult b = simulate(explicit_constant);
  REQUIRE(a.series.size() == b.series.size());
  REQUIRE(a.series.size() > 1000);
  bool same = true;
  for (std::size_t i = 0; i < a.series.size() && same; ++i) {
    const SeriesRow& p = a.series[i];
    const SeriesRow& q = b.series[i];
    same = p.t_s == q.t_s && p.theta1_rad == q.theta1_rad && p.theta2_rad == q.theta2_rad &&
           p.w1_rad_per_s == q.w1_rad_per_s && p.w2_rad_per_s == q.w2_rad_per_s && p.s_m == q.s_m &&
           p.delta_m == q.delta_m && p.region == q.region && p.pairs == q.pairs &&
           p.normal_force_n == q.normal_force_n && p.friction_force_n == q.friction_force_n;
    if (!same) CAPTURE(i);
  }
  CHECK(same);
  CHECK(a.summary.friction_loss_j == b.summary.friction_loss_j);
}

TEST_CASE("the ledger closes under Benedict and Kelley's f as under the constant f") {
  // At case 2's slow sliding (w1 = 50 rad/s) the formula gives f of 0.1 to 0.3 over most of the
  // mesh: f_max = 0.1 (the default) clips it nearly everywhere, 0.3 leaves the formula acting.
  SimulationCase wide = case2_benedict_kelley();
  wide.model.benedict_kelley.most_coefficient = 0.3;
  const SimulationSummary constant = run_summary(case2());
  const SimulationSummary clipped = run_summary(case2_benedict_kelley());
  const SimulationSummary bk = run_summary(wide);
  for (const SimulationSummary* s : {&constant, &clipped, &bk}) {
    const double throughput =
        s->kinetic_energy_initial_j + s->stored_energy_initial_j + std::fabs(s->torque_work_j);
    // The bound of the ledger tests of the dynamics suite: 1e-7 of the energy through the run.
    const double bound = 1e-7 * throughput;
    MESSAGE("residual " << s->ledger_residual_max_j << " J of " << throughput
                        << " J, friction loss " << s->friction_loss_j << " J");
    CHECK(s->ledger_residual_max_j < bound);
    // A friction loss the ledger could miss would be below its bound.
    CHECK(s->friction_loss_j > 100.0 * bound);
  }
  // The clip acts: a wider f_max lets f, and the loss, grow.
  CHECK(bk.friction_loss_j > 1.1 * clipped.friction_loss_j);
}

TEST_CASE("the smoothed sign converges to the exact switch as v_s shrinks") {
  const double exact = run_summary(case2()).friction_loss_j;
  double previous = 0.0;
  for (double vs : {1e-2, 1e-3, 1e-4}) {
    SimulationCase c = case2();
    c.model.friction_smoothing_speed_m_s = vs;
    const SimulationSummary s = run_summary(c);
    // The ledger books the smoothed friction as the moments feel it (the bound of the
    // dynamics suite's ledger tests).
    const double throughput =
        s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
    CHECK(s.ledger_residual_max_j < 1e-7 * throughput);
    const double difference = std::fabs(s.friction_loss_j - exact);
    MESSAGE("v_s = " << vs << " m/s: friction loss " << s.friction_loss_j << " J, exact " << exact
                     << " J, difference " << difference << " J");
    // tanh(Vs / v_s) < 1 in magnitude: the smoothed friction takes less.
    if (previous > 0.0) CHECK(difference < previous);
    previous = difference;
  }
  // At v_s = 1e-4 m/s the smoothed band is a few steps wide: within 1 % of the exact loss.
  CHECK(previous < 1e-2 * exact);
}

TEST_CASE("a smoothing speed the step cannot resolve is refused before work, naming the bound") {
  // The band 2 v_s of tanh(Vs / v_s) must span 20 fixed steps of the sliding
  // speed's sweep by the rolling, Rb1 |w1| (|w1| + |w2|) at the initial
  // speeds: v_s >= 10 h Rb1 |w1| (|w1| + |w2|).
  SimulationCase c = case2();
  c.integrator.end_time_s = 2e-4;
  const double rb1 = base_radius(c.gears, Gear::one);
  const double w1 = c.initial.w1_rad_per_s;
  const double w2 = c.initial.w2_rad_per_s;
  const double least =
      10.0 * c.integrator.step_s * rb1 * std::fabs(w1) * (std::fabs(w1) + std::fabs(w2));
  const auto refusal = [](const SimulationCase& run) -> std::string {
    try {
      run_summary(run);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(accepted)";
  };
  c.model.friction_smoothing_speed_m_s = 0.9 * least;
  const std::string text = refusal(c);
  CHECK(text.find("model.friction_smoothing_speed") != std::string::npos);
  CHECK(text.find("integrator.step") != std::string::npos);
  // Just above the bound it runs; and at a step ten times smaller the refused
  // speed runs too.
  c.model.friction_smoothing_speed_m_s = 1.1 * least;
  CHECK(refusal(c) == "(accepted)");
  c.model.friction_smoothing_speed_m_s = 0.9 * least;
  c.integrator.step_s /= 10.0;
  CHECK(refusal(c) == "(accepted)");
  // The adaptive integrator's error control resolves the band by itself; and
  // without friction there is nothing to smooth.
  c.integrator.step_s *= 10.0;
  c.integrator.kind = IntegratorKind::adaptive;
  CHECK(refusal(c) == "(accepted)");
  c.integrator.kind = IntegratorKind::rk4;
  c.model.friction_coefficient = 0.0;
  CHECK(refusal(c) == "(accepted)");
  // The example: 1e-5 m/s at case 2's step 1e-7 s (bound 4.7e-5).
  SimulationCase example = case2();
  example.model.friction_smoothing_speed_m_s = 1e-5;
  CHECK(refusal(example).find("model.friction_smoothing_speed") != std::string::npos);
}

TEST_CASE("a smoothing speed beyond the sliding speeds is refused by its row") {
  // tanh(Vs / v_s) with v_s far above the sliding speeds is f N Vs / v_s:
  // friction all but gone, silently. The row bounds v_s at 0.1 m/s.
  const std::string base = write_case_file(case2());
  const auto with = [&](const std::string& line) {
    std::string text = base;
    text.insert(text.find("[model]\n") + 8, line);
    return error_of(text);
  };
  for (const char* value : {"1e300 m/s", "0.2 m/s"}) {
    CAPTURE(value);
    const std::string text = with(std::string("friction_smoothing_speed = \"") + value + "\"\n");
    CHECK(text.find("friction_smoothing_speed") != std::string::npos);
    CHECK(text.find("0.1 m/s") != std::string::npos);
  }
  CHECK(with("friction_smoothing_speed = \"0.1 m/s\"\n") == "(accepted)");
}

TEST_CASE("bad friction-law inputs are refused, naming the key and its range") {
  const std::string base = write_case_file(case2());
  const auto with = [&](const std::string& lines) {
    std::string text = base;
    text.insert(text.find("[model]\n") + 8, lines);
    return error_of(text);
  };
  const std::string unknown = with("friction_law = \"coulomb\"\n");
  CHECK(unknown.find("friction_law") != std::string::npos);
  CHECK(unknown.find("benedict-kelley") != std::string::npos);
  const std::string missing =
      with("friction_law = \"benedict-kelley\"\nsurface_roughness = \"0.4 um\"\n");
  CHECK(missing.find("lubricant_viscosity") != std::string::npos);
  const std::string rough = with(
      "friction_law = \"benedict-kelley\"\nlubricant_viscosity = \"10 cP\"\n"
      "surface_roughness = \"1.27 um\"\n");
  CHECK(rough.find("surface_roughness") != std::string::npos);
  CHECK(rough.find("50 micro-inches") != std::string::npos);
  const std::string viscosity = with(
      "friction_law = \"benedict-kelley\"\nlubricant_viscosity = \"0 cP\"\n"
      "surface_roughness = \"0.4 um\"\n");
  CHECK(viscosity.find("lubricant_viscosity") != std::string::npos);
  const std::string most = with(
      "friction_law = \"benedict-kelley\"\nlubricant_viscosity = \"10 cP\"\n"
      "surface_roughness = \"0.4 um\"\nfriction_coefficient_max = 0\n");
  CHECK(most.find("friction_coefficient_max") != std::string::npos);
  const std::string smoothing = with("friction_smoothing_speed = \"-1 mm/s\"\n");
  CHECK(smoothing.find("friction_smoothing_speed") != std::string::npos);
  // A key of the other law is refused, not ignored.
  const std::string stray = with("lubricant_viscosity = \"10 cP\"\n");
  CHECK(stray.find("lubricant_viscosity") != std::string::npos);
  // A library call goes through the same rows.
  SimulationCase c = case2();
  c.model.friction_law = FrictionLaw::benedict_kelley;
  try {
    validate_fields(c);
    FAIL("a zero viscosity was accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "model.lubricant_viscosity");
  }
}

TEST_CASE("the table law: f interpolated by hand, constant beyond the ends") {
  FrictionTable table;
  table.slide_to_roll = {-1.0, 0.0, 0.5};
  table.coefficient = {0.08, 0.02, 0.06};
  // Between the entries: f_i + (r - r_i) / (r_{i+1} - r_i) (f_{i+1} - f_i).
  CHECK(table_friction_coefficient(table, -0.5) == doctest::Approx(0.05).epsilon(1e-15));
  CHECK(table_friction_coefficient(table, 0.25) == doctest::Approx(0.04).epsilon(1e-15));
  CHECK(table_friction_coefficient(table, 0.1) == doctest::Approx(0.028).epsilon(1e-15));
  // At the entries, the entries.
  CHECK(table_friction_coefficient(table, -1.0) == 0.08);
  CHECK(table_friction_coefficient(table, 0.0) == 0.02);
  CHECK(table_friction_coefficient(table, 0.5) == 0.06);
  // Beyond the ends, the end values.
  CHECK(table_friction_coefficient(table, -1.5) == 0.08);
  CHECK(table_friction_coefficient(table, 2.0) == 0.06);
  // The slide-to-roll ratio 2 Vs / Ve: Vs = 1, Ve = 4 m/s give 0.5; flanks
  // that do not roll give +-infinity, i.e. the end values.
  CHECK(slide_to_roll_ratio(1.0, 4.0) == 0.5);
  CHECK(slide_to_roll_ratio(-1.0, 4.0) == -0.5);
  CHECK(slide_to_roll_ratio(0.0, 0.0) == 0.0);
  CHECK(table_friction_coefficient(table, slide_to_roll_ratio(1.0, 0.0)) == 0.06);
  CHECK(table_friction_coefficient(table, slide_to_roll_ratio(-1.0, 0.0)) == 0.08);
}

TEST_CASE("a table of one entry, or of two equal ones, is the constant law to rounding") {
  const SimulationSummary constant = run_summary(case2());
  for (const FrictionTable& table :
       {FrictionTable{{0.0}, {0.04}}, FrictionTable{{-1.0, 1.0}, {0.04, 0.04}}}) {
    SimulationCase c = case2();
    c.model.friction_law = FrictionLaw::table;
    c.model.friction_table = table;
    const SimulationSummary s = run_summary(c);
    // f is the same double at every point, so the run is the same run.
    CHECK(s.friction_loss_j == constant.friction_loss_j);
    CHECK(s.damping_loss_j == constant.damping_loss_j);
    CHECK(s.final_w1_rad_per_s == constant.final_w1_rad_per_s);
  }
}

TEST_CASE("the ledger closes under the table law") {
  // f from 0.09 where the pinion's flank slides back (r = -1) through 0.01 at
  // the pitch point to 0.06 (r = 1): f varies along every mesh cycle.
  SimulationCase c = case2();
  c.model.friction_law = FrictionLaw::table;
  c.model.friction_table = {{-1.0, 0.0, 1.0}, {0.09, 0.01, 0.06}};
  const SimulationSummary s = run_summary(c);
  const SimulationSummary constant = run_summary(case2());
  const double throughput =
      s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
  const double bound = 1e-7 * throughput;
  MESSAGE("residual " << s.ledger_residual_max_j << " J of " << throughput << " J, friction loss "
                      << s.friction_loss_j << " J (constant f = 0.04: " << constant.friction_loss_j
                      << " J)");
  CHECK(s.ledger_residual_max_j < bound);
  CHECK(s.friction_loss_j > 100.0 * bound);
  // The table acts: another loss than the constant law's.
  CHECK(relative_difference(s.friction_loss_j, constant.friction_loss_j) > 1e-3);
}

TEST_CASE("bad friction tables are refused, naming the key, the index and the value") {
  const std::string base = write_case_file(case2());
  const auto with = [&](const std::string& lines) {
    std::string text = base;
    text.insert(text.find("[model]\n") + 8, lines);
    return error_of(text);
  };
  const std::string order = with(
      "friction_law = \"table\"\nfriction_table_slide_to_roll = [0.0, 0.5, 0.5]\n"
      "friction_table_coefficients = [0.01, 0.02, 0.03]\n");
  CHECK(order.find("friction_table_slide_to_roll[2]") != std::string::npos);
  CHECK(order.find("0.5") != std::string::npos);
  CHECK(order.find("strictly increasing") != std::string::npos);
  const std::string large = with(
      "friction_law = \"table\"\nfriction_table_slide_to_roll = [0.0, 0.5]\n"
      "friction_table_coefficients = [0.01, 1.5]\n");
  CHECK(large.find("friction_table_coefficients[1]") != std::string::npos);
  CHECK(large.find("1.5") != std::string::npos);
  CHECK(large.find("[0, 1]") != std::string::npos);
  const std::string lengths = with(
      "friction_law = \"table\"\nfriction_table_slide_to_roll = [0.0, 0.5]\n"
      "friction_table_coefficients = [0.01]\n");
  CHECK(lengths.find("friction_table_coefficients") != std::string::npos);
  CHECK(lengths.find("as many values") != std::string::npos);
  const std::string empty = with(
      "friction_law = \"table\"\nfriction_table_slide_to_roll = []\n"
      "friction_table_coefficients = []\n");
  CHECK(empty.find("friction_table_slide_to_roll") != std::string::npos);
  const std::string unit = with(
      "friction_law = \"table\"\nfriction_table_slide_to_roll = [\"0.5 mm\"]\n"
      "friction_table_coefficients = [0.01]\n");
  CHECK(unit.find("friction_table_slide_to_roll[0]") != std::string::npos);
  const std::string missing = with("friction_law = \"table\"\n");
  CHECK(missing.find("friction_table_slide_to_roll") != std::string::npos);
  // The command line's --set goes through the same rows.
  SimulationCase c = case2();
  set_field(c, "model.friction_law", "table");
  set_field(c, "model.friction_table_slide_to_roll", "-1, 0, 1");
  set_field(c, "model.friction_table_coefficients", "0.09, 0.01, 0.06");
  CHECK(c.model.friction_table.coefficient[2] == 0.06);
  CHECK_THROWS_AS(set_field(c, "model.friction_table_coefficients", "0.1, -0.2"), InputError);
  // A table written out reads back to the same doubles.
  const SimulationCase back = parse_case(write_case_file(c), "back.toml");
  CHECK(back.model.friction_table.slide_to_roll == c.model.friction_table.slide_to_roll);
  CHECK(back.model.friction_table.coefficient == c.model.friction_table.coefficient);
}

TEST_CASE("the summary's coefficient: the constant f, or the law's mean and max over loaded time") {
  // Under the constant law the summary's f is the case's, and nothing else is said.
  const SimulationSummary constant = run_summary(case2());
  CHECK(constant.friction_law == FrictionLaw::constant);
  CHECK(constant.friction_coefficient == case2().model.friction_coefficient);
  CHECK(!constant.friction_coefficient_mean.has_value());
  const std::string constant_json = summary_json(constant);
  CHECK(constant_json.find("\"friction_law\"") == std::string::npos);
  CHECK(constant_json.find("\"friction_coefficient\": 0.04") != std::string::npos);
  // A constant table: every pair's f is 0.04, so the line's sum(f N) / sum(N) is 0.04 to the
  // rounding of one product and quotient per step (a few ulp, the max), and the mean sums about
  // 1e5 steps' f dt (their rounding, 1e5 x 1.1e-16 = 1e-11 at most).
  SimulationCase flat = case2();
  flat.model.friction_law = FrictionLaw::table;
  flat.model.friction_table = {{-1.0, 1.0}, {0.04, 0.04}};
  const SimulationSummary table = run_summary(flat);
  REQUIRE(table.friction_coefficient_mean.has_value());
  REQUIRE(table.friction_coefficient_max.has_value());
  CHECK(std::fabs(*table.friction_coefficient_mean / 0.04 - 1.0) <= 1e-11);
  CHECK(std::fabs(*table.friction_coefficient_max / 0.04 - 1.0) <= 1e-15);
  const std::string table_json = summary_json(table);
  CHECK(table_json.find("\"friction_coefficient\": null") != std::string::npos);
  CHECK(table_json.find("\"friction_law\": \"table\"") != std::string::npos);
  CHECK(table_json.find("\"friction_coefficient_mean\": 0.0") != std::string::npos);
  // The same run as the constant law: observing f does not touch the state.
  CHECK(table.friction_loss_j == constant.friction_loss_j);
  CHECK(table.final_w1_rad_per_s == constant.final_w1_rad_per_s);
  // Benedict and Kelley: f in [0, f_max] at every pair, so its load-weighted mean over the line
  // is too; at case 2's slow sliding the clip acts over most of the mesh (docs/model.md), so
  // the largest value is f_max itself and the mean is near it but below (f falls off near the
  // ends of the path, where the sliding is fastest).
  const SimulationSummary bk = run_summary(case2_benedict_kelley());
  REQUIRE(bk.friction_coefficient_mean.has_value());
  REQUIRE(bk.friction_coefficient_max.has_value());
  const double most = case2_benedict_kelley().model.benedict_kelley.most_coefficient;
  MESSAGE("Benedict-Kelley: mean f " << *bk.friction_coefficient_mean << ", max "
                                     << *bk.friction_coefficient_max << ", f_max " << most);
  // f_max to the few ulp of sum(f N) / sum(N) where every pair is clipped.
  CHECK(*bk.friction_coefficient_max <= most * (1.0 + 4e-16));
  CHECK(*bk.friction_coefficient_max >= most * (1.0 - 4e-16));
  CHECK(*bk.friction_coefficient_mean > 0.0);
  CHECK(*bk.friction_coefficient_mean <= *bk.friction_coefficient_max);
  CHECK(summary_json(bk).find("\"friction_law\": \"benedict-kelley\"") != std::string::npos);
}

TEST_CASE(
    "a heavy load sticks the exact friction switch at the pitch point: the run carries on with "
    "each stage's own signs, and its friction loss is the smoothed law's limit") {
  // The paper's pair at 20 N*m (about 1060 N on the line of action) rolling at 50 rad/s: at the
  // pitch point rho1 times the jump of the pinion's acceleration, 2 f N X / J1, exceeds the
  // kinematic rate of the sliding speed, (w1 + w2) Rb1 w1, so the exact switch cannot reverse:
  // the contact sticks. The run (torsional, as the planar one) then takes each stage's own
  // friction signs across the sticking (src/dynamics/stall.hpp) instead of stalling on events.
  SimulationCase c = paper_case(2);
  c.torque1.constant_n_m = 20.0;
  c.torque2.constant_n_m =
      -20.0 * base_radius(c.gears, Gear::two) / base_radius(c.gears, Gear::one);
  c.initial.w2_rad_per_s =
      c.initial.w1_rad_per_s * base_radius(c.gears, Gear::one) / base_radius(c.gears, Gear::two);
  c.integrator.end_time_s = 0.01;
  RunControl control;
  control.keep_series = false;
  const SimulationSummary exact = simulate(c, control).summary;
  CHECK(exact.friction_loss_j > 0.0);
  // The remedy the message names runs it, and its friction loss converges as v_s shrinks.
  // The smoothed sign tanh(Vs / v_s), an independent formulation with no switch at all, converges
  // as v_s shrinks; the exact switch with the fallback is its limit.
  c.model.friction_smoothing_speed_m_s = 1e-3;
  const double coarse = simulate(c, control).summary.friction_loss_j;
  c.model.friction_smoothing_speed_m_s = 1e-4;
  const double fine = simulate(c, control).summary.friction_loss_j;
  CHECK(fine > 0.0);
  CHECK(std::abs(coarse - fine) / fine < 1e-4);
  MESSAGE("exact switch with per-stage signs: friction loss "
          << exact.friction_loss_j << " J; smoothed at 1e-4 m/s " << fine << " J, at 1e-3 m/s "
          << coarse << " J (differences " << exact.friction_loss_j - fine << ", " << coarse - fine
          << " J); residual " << exact.ledger_residual_max_j << " J");
  // The smoothed law's own error falls with v_s (1e-3 to 1e-4 m/s moves it by |coarse - fine|,
  // and the remaining distance to its limit is smaller): the exact switch, crossing the sticking
  // with each stage's own signs, lies nearer the fine smoothing than the coarse one does
  // (measured 2.2e-8 J against 1.9e-7 J).
  CHECK(std::abs(exact.friction_loss_j - fine) < std::abs(coarse - fine));
  // The ledger closes through the sticking: the per-stage signs err by O(h) over the steps that
  // cross it (measured 5e-8 of the friction loss), not at the energies' scale.
  CHECK(exact.ledger_residual_max_j < 1e-6 * exact.friction_loss_j);
  // The adaptive integrator shares the run's stall watch and its fallback.
  c.model.friction_smoothing_speed_m_s = 0.0;
  c.integrator.kind = IntegratorKind::adaptive;
  const SimulationSummary adaptive = simulate(c, control).summary;
  MESSAGE("adaptive: friction loss " << adaptive.friction_loss_j << " J, difference "
                                     << adaptive.friction_loss_j - fine << " J");
  CHECK(std::abs(adaptive.friction_loss_j - fine) < std::abs(coarse - fine));
}
