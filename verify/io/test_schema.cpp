// The case schema: one range per key, whoever asks. The reader (parse_case)
// and the library's checks (validate_fields, then validate_implied as simulate()
// runs it) must accept and refuse the same values at every bound of every
// numeric key; the ranges the two validators used to disagree on are pinned to
// the values chosen (restitution exponent (0, 1], adaptive tolerance
// [1e-14, 1e-3], at most kMostSteps steps); set_field reads text with and
// without units to the same doubles as the unit parser; errors name the key
// as section.key; and the docs' tables are the program's.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/named_values.hpp"
#include "gearimpact/numerics/quadrature.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "run_command.hpp"

using namespace gearimpact;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Case 3 of Table 1: torque1 sinusoidal, torque2 constant, so every key of
// the schema applies to one of the two torques.
SimulationCase every_key_case() {
  SimulationCase c = paper_case(3);
  c.torque1.phase_rad = 0.25;
  c.initial = {1e-4, -2e-4, 12.5, -3.0};
  // The keys that may be absent, present: the bores of ROSS's run on this
  // pair (peer-values/ross-pair-a.csv), its derived rack tip radius, and
  // gear 2 of gear 1's material.
  c.gears.rack_tip_radius_coefficient = 0.38;
  c.gears.bore_diameter1_m = 20e-3;
  c.gears.bore_diameter2_m = 60e-3;
  c.gears.youngs_modulus2_pa = 206.8e9;
  c.gears.poisson_ratio2 = 0.3;
  return c;
}

// A case the row applies to: every_key_case(), for the keys of the other
// torque kinds case 2 with torque2 made sinusoidal or with a driver and a
// drag, for the planar model's keys one with elastic bearings and shafts, for the keys of the
// constant mesh stiffness, the frozen D and Benedict and Kelley's friction a
// case with those.
SimulationCase case_for(const Field& field) {
  SimulationCase c = every_key_case();
  if (applies(field, c)) return c;
  c = paper_case(2);
  c.torque2.kind = Torque::Kind::sinusoidal;
  c.torque2.amplitude_n_m = -0.3;
  c.torque2.angular_frequency_rad_per_s = 500.0;
  c.torque2.phase_rad = -1.5;
  if (applies(field, c)) return c;
  {
    // The loose gear's keys: a kinematic driver on gear 1, a drag on gear 2.
    SimulationCase d = paper_case(2);
    d.torque1 = Torque{};
    d.torque1.kind = Torque::Kind::prescribed_speed;
    d.torque1.mean_speed_rad_per_s = 100.0;
    d.torque1.driver_orders = {2.0};
    d.torque1.driver_speed_amplitudes_rad_per_s = {5.0};
    d.torque1.harmonic_phases_rad = {0.0};
    d.initial.w1_rad_per_s = 100.0;
    d.torque2 = Torque{};
    d.torque2.kind = Torque::Kind::drag;
    d.torque2.drag_constant_n_m = 0.5;
    d.torque2.drag_viscous_n_m_s = 1e-4;
    if (applies(field, d)) return d;
  }
  {
    // The drive's keys: a speed controller with a speed profile, an
    // induction motor, a load profile.
    SimulationCase d = paper_case(2);
    d.torque1 = Torque{};
    d.torque1.kind = Torque::Kind::speed_controlled;
    d.torque1.mean_speed_rad_per_s = 100.0;
    d.torque1.speed_profile_times_s = {0.0, 0.01};
    d.torque1.speed_profile_speeds_rad_per_s = {100.0, 120.0};
    d.torque2 = Torque{};
    d.torque2.kind = Torque::Kind::profile;
    d.torque2.profile_times_s = {0.0, 0.01};
    d.torque2.profile_torques_n_m = {-1.0, -2.0};
    if (applies(field, d)) return d;
    d.torque1 = Torque{};
    d.torque1.kind = Torque::Kind::induction_motor;
    d.torque1.synchronous_speed_rad_per_s = 110.0;
    d.torque1.breakdown_torque_n_m = 3.0;
    d.torque1.breakdown_slip = 0.1;
    if (applies(field, d)) return d;
  }
  {
    // The planar model's keys: elastic bearings and shafts.
    SimulationCase p = paper_case(2);
    p.bearings.kind = BearingKind::elastic;
    p.bearings.gear1.stiffness_x_n_per_m = 5e8;
    p.bearings.gear2.stiffness_x_n_per_m = 7e8;
    // Every optional key given, so that each has a value to read back.
    for (GearBearing* b : {&p.bearings.gear1, &p.bearings.gear2}) {
      b->stiffness_y_n_per_m = 9e8;
      b->damping_x_n_s_per_m = 150.0;
      b->damping_y_n_s_per_m = 250.0;
      b->mass_kg = 1.25;
    }
    p.shafts.kind = ShaftKind::elastic;
    p.shafts.motor_inertia_kg_m2 = 2e-3;
    p.shafts.motor_stiffness_n_m_per_rad = 5e4;
    p.shafts.load_inertia_kg_m2 = 8e-3;
    p.shafts.load_stiffness_n_m_per_rad = 9e4;
    if (applies(field, p)) return p;
  }
  c.model.mesh_stiffness = MeshStiffnessMode::constant;
  c.model.constant_mesh_stiffness_n_per_m = 3.5e8;
  c.model.damping_update = DampingUpdate::frozen;
  c.model.damping_reference_speed_m_s = 0.1;
  c.model.friction_law = FrictionLaw::benedict_kelley;
  c.model.benedict_kelley.viscosity_pa_s = 0.1;
  c.model.benedict_kelley.roughness_m = 0.4e-6;
  REQUIRE(applies(field, c));
  return c;
}

// The InputError of `check`, or nothing.
std::optional<InputError> error_of(const std::function<void()>& check) {
  try {
    check();
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

// The library's checks of a case, as simulate() makes them. A mesh
// stiffness that cannot be computed (QuadratureError) refuses the case too.
bool library_accepts(const SimulationCase& c) {
  try {
    validate_fields(c);
    validate_implied(c);
  } catch (const InputError&) {
    return false;
  } catch (const QuadratureError&) {
    return false;
  }
  return true;
}

bool reader_accepts(const SimulationCase& c) {
  const std::string text = write_case_file(c, CaseUnits::si);
  try {
    parse_case(text, "bound.toml");
  } catch (const CaseFileError&) {
    return false;
  }
  return true;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream stream(path);
  std::stringstream buffer;
  buffer << stream.rdbuf();
  return buffer.str();
}

// The text between the line holding `begin` and the line holding `end`.
std::string between(const std::string& text, const std::string& begin, const std::string& end) {
  const std::size_t a = text.find(begin);
  REQUIRE(a != std::string::npos);
  const std::size_t start = text.find('\n', a) + 1;
  const std::size_t stop = text.find(end, start);
  REQUIRE(stop != std::string::npos);
  return text.substr(start, stop - start);
}

}  // namespace

TEST_CASE("a default-constructed case and the paper's cases pass every row") {
  CHECK_FALSE(error_of([] { validate_fields(SimulationCase{}); }).has_value());
  for (int n = 1; n <= 3; ++n) {
    CAPTURE(n);
    CHECK_FALSE(error_of([&] { validate_fields(paper_case(n)); }).has_value());
  }
}

TEST_CASE("the reader and the library accept and refuse the same values at every bound") {
  // Each finite bound, the doubles either side of it, and for a key without
  // bounds a huge value of either sign: the two paths must agree on each.
  int compared = 0;
  int refused = 0;
  for (const Field& field : case_schema()) {
    if (field.kind != FieldKind::quantity && field.kind != FieldKind::number &&
        field.kind != FieldKind::integer) {
      continue;
    }
    std::vector<double> values;
    for (const std::optional<Bound>& bound : {field.range.lower, field.range.upper}) {
      if (!bound) continue;
      values.push_back(bound->value);
      if (field.kind == FieldKind::integer) {
        values.push_back(bound->value - 1.0);
        values.push_back(bound->value + 1.0);
      } else {
        values.push_back(std::nextafter(bound->value, -1e300));
        values.push_back(std::nextafter(bound->value, 1e300));
      }
    }
    if (values.empty()) values = {-1e30, 1e30};
    for (double value : values) {
      SimulationCase c = case_for(field);
      field.set(c, value);
      CAPTURE(field.name());
      CAPTURE(value);
      const bool library = library_accepts(c);
      CHECK(reader_accepts(c) == library);
      ++compared;
      if (!library) ++refused;
    }
  }
  // 2 or 3 values a bound over some 30 numeric keys; about a third are
  // outside their range (one of the three values at each bound).
  CHECK(compared > 80);
  CHECK(refused > 25);
}

TEST_CASE("the ranges the two validators disagreed on: one range, both paths") {
  struct Probe {
    const char* key;
    double value;
    bool allowed;
  };
  // Restitution exponent: (0, 1] (e falls with Vi; the published laws have
  // p from 1/5 to 1). Adaptive tolerance: [1e-14, 1e-3]. Steps: the paper's
  // 1e-7 s step allows end_time up to kMostSteps * 1e-7 s = 200 s.
  const double longest_s = static_cast<double>(kMostSteps) * 1e-7;
  for (const Probe& probe : {Probe{"model.restitution_exponent", 2.0, false},
                             Probe{"model.restitution_exponent", 1.0, true},
                             Probe{"model.restitution_exponent", std::nextafter(1.0, 2.0), false},
                             Probe{"model.restitution_exponent", 0.0, false},
                             Probe{"integrator.relative_tolerance", 5e-3, false},
                             Probe{"integrator.relative_tolerance", 1e-3, true},
                             Probe{"integrator.relative_tolerance", 1e-14, true},
                             Probe{"integrator.end_time", longest_s, true},
                             Probe{"integrator.end_time", std::nextafter(longest_s, 1e9), false}}) {
    CAPTURE(probe.key);
    CAPTURE(probe.value);
    SimulationCase c = paper_case(1);
    find_field(probe.key)->set(c, probe.value);
    CHECK(library_accepts(c) == probe.allowed);
    CHECK(reader_accepts(c) == probe.allowed);
    const std::optional<InputError> error = error_of([&] { validate_fields(c); });
    CHECK(error.has_value() == !probe.allowed);
    if (error) CHECK(error->field() == probe.key);
  }
  CHECK(allowed_text(*find_field("model.restitution_exponent")) == "(0, 1]");
  CHECK(allowed_text(*find_field("integrator.relative_tolerance")) == "[1e-14, 1e-3]");
}

TEST_CASE("library errors name the key as section.key, cross-key checks included") {
  struct Fault {
    std::function<void(SimulationCase&)> apply;
    std::string field;
    std::string part;  // of the allowed range
  };
  const std::vector<Fault> faults{
      {[](SimulationCase& c) { c.gears.teeth1 = 3; }, "gears.teeth1", "[4, 100000]"},
      // 2 ha / sin^2(20 deg) = 17.097: the undercut limit, a check across keys.
      {[](SimulationCase& c) { c.gears.teeth1 = 17; }, "gears.teeth1", "17.097"},
      {[](SimulationCase& c) { c.gears.addendum_coefficient = 0.4; }, "gears.contact_ratio",
       "[1, 3)"},
      // At 0.26 rad the 20-tooth pinion is undercut before its root interferes.
      {[](SimulationCase& c) { c.gears.pressure_angle_rad = 0.26; }, "gears.teeth1", "undercuts"},
      {[](SimulationCase& c) { c.gears.youngs_modulus_pa = 0.0; }, "gears.youngs_modulus",
       "> 0 Pa"},
      {[](SimulationCase& c) { c.model.restitution.exponent = 2.0; }, "model.restitution_exponent",
       "(0, 1]"},
      {[](SimulationCase& c) { c.integrator.adaptive_relative_tolerance = 5e-3; },
       "integrator.relative_tolerance", "[1e-14, 1e-3]"},
      {[](SimulationCase& c) { c.integrator.end_time_s = 1000.0; }, "integrator.end_time",
       "at most 2e9 steps"},
      {[](SimulationCase& c) { c.integrator.output_every = 0; }, "integrator.output_every",
       "[1, 2147483647]"},
      {[](SimulationCase& c) { c.torque1.constant_n_m = std::nan(""); }, "torque1.value",
       "any finite value"},
      {[](SimulationCase& c) {
         c.model.stiffness.terms.set(Term::hertz, false);
         c.model.stiffness.terms.set(Term::bending, false);
         c.model.stiffness.terms.set(Term::axial, false);
       },
       "model.hertz_term", "at least one term of (29)"},
      {[](SimulationCase& c) { c.model.damping_form = static_cast<DampingForm>(7); },
       "model.damping_form", "\"lee-wang\""},
      {[](SimulationCase& c) { c.name = "a/b"; }, "name", "letters, digits"},
  };
  for (const Fault& fault : faults) {
    CAPTURE(fault.field);
    SimulationCase c = paper_case(2);
    fault.apply(c);
    const std::optional<InputError> error = error_of([&] { validate_fields(c); });
    REQUIRE(error.has_value());
    CHECK(error->field() == fault.field);
    CHECK(contains(error->allowed(), fault.part));
    CHECK(contains(error->what(), fault.field + " = "));
  }
}

TEST_CASE("set_field reads text as the unit parser does; get_numeric_field reads it back") {
  SimulationCase c = paper_case(1);
  // A plain number is SI; a unit converts by the same exact decimal shift.
  set_field(c, "integrator.end_time", "20 ms");
  CHECK(c.integrator.end_time_s == 20e-3);
  set_field(c, "integrator.end_time", "0.02");
  CHECK(c.integrator.end_time_s == 0.02);
  set_field(c, "integrator.step", "0.05us");
  CHECK(c.integrator.step_s == 0.05e-6);
  set_field(c, "gears.pressure_angle", "25 deg");
  CHECK(c.gears.pressure_angle_rad == 25.0 * (std::numbers::pi / 180.0));
  set_field(c, "gears.teeth2", "81");
  CHECK(c.gears.teeth2 == 81);
  set_field(c, "model.damping_stiffness", "pitch-pair-at-impact");
  CHECK(c.model.damping_stiffness == DampingStiffness::pitch_pair_at_impact);
  set_field(c, "model.axial_term", "off");
  CHECK_FALSE(c.model.stiffness.terms.has(Term::axial));
  set_field(c, "name", "run-7");
  CHECK(c.name == "run-7");
  CHECK(get_numeric_field(c, "gears.teeth2") == 81.0);
  CHECK(get_numeric_field(c, "integrator.step") == 0.05e-6);

  // Every numeric key of a case with every field changed: its SI value
  // written as the shortest decimal sets the same double on another case.
  int keys = 0;
  for (const Field& field : case_schema()) {
    if (field.kind != FieldKind::quantity && field.kind != FieldKind::number &&
        field.kind != FieldKind::integer) {
      continue;
    }
    CAPTURE(field.name());
    const SimulationCase from = case_for(field);
    SimulationCase to = from;
    field.set(to, 0.0);
    set_field(to, field.name(), shortest_decimal(field.get(from)));
    CHECK(get_numeric_field(to, field.name()) == field.get(from));
    ++keys;
  }
  CHECK(keys >= 30);
}

TEST_CASE("set_field refuses with the key or the name the caller gives, and the allowed range") {
  SimulationCase c = paper_case(1);
  const auto refused = [&](const char* key, const char* text, const char* name = "") {
    const std::optional<InputError> error = error_of([&] { set_field(c, key, text, name); });
    REQUIRE(error.has_value());
    return *error;
  };
  const InputError zero = refused("integrator.end_time", "0");
  CHECK(zero.field() == "integrator.end_time");
  CHECK(zero.allowed() == "a time > 0 s");
  // A plain number is in SI: 20 read as rad is refused, and since 20 deg is
  // in the range the message says how to write it; 90 rad, out of the range
  // in deg too, gets no such hint.
  CHECK(refused("gears.pressure_angle", "20").allowed() ==
        "an angle in (0, 0.7853981633974483] rad, i.e. (0, 45] deg; a plain number is read in "
        "rad: \"20 deg\" gives it in deg");
  CHECK(!contains(refused("gears.pressure_angle", "90").allowed(), "plain number"));
  CHECK(refused("integrator.end_time", "0 ms", "--t-end").field() == "--t-end");
  CHECK(contains(refused("integrator.end_time", "nan").allowed(), "> 0 s"));
  CHECK(contains(refused("integrator.end_time", "20 furlong").what(), "unknown unit"));
  CHECK(contains(refused("model.friction_coefficient", "0.04 mm").allowed(), "no unit"));
  CHECK(contains(refused("gears.teeth1", "20.5").allowed(), "an integer in [4, 100000]"));
  CHECK(contains(refused("model.damping_stiffness", "pair").allowed(), "\"current-pair\""));
  CHECK(contains(refused("torque1.kind", "user").allowed(), "\"sinusoidal\""));
  CHECK(contains(refused("torque1.amplitude", "1 N*m").allowed(), "kind = \"sinusoidal\""));
  CHECK(contains(refused("no.such_key", "1").allowed(), "gearimpact schema"));
  CHECK(contains(refused("name", "a b").allowed(), "letters, digits"));
  set_field(c, "torque1.kind", "sinusoidal");
  set_field(c, "torque1.amplitude", "1 N*m");
  CHECK(c.torque1.amplitude_n_m == 1.0);
  set_field(c, "torque1.mean", "3 N*m");
  CHECK(c.torque1.mean_n_m == 3.0);
  // A list: comma separated, each element with a unit or a plain SI number.
  CHECK(contains(refused("torque1.amplitudes", "1 N*m").allowed(), "\"harmonic\""));
  set_field(c, "torque1.kind", "harmonic");
  set_field(c, "torque1.amplitudes", "10 N*mm, 2 kgf*mm,0.5");
  CHECK(c.torque1.harmonic_amplitudes_n_m ==
        std::vector<double>{10e-3, 2.0 * (9.80665 * 1e-3), 0.5});
  CHECK(c.torque1.mean_n_m == 3.0);
  const InputError element = refused("torque1.angular_frequencies", "1000 rad/s, -5 Hz");
  CHECK(element.field() == "torque1.angular_frequencies[1]");
  CHECK(contains(element.allowed(), ">= 0 rad/s"));
  set_field(c, "torque1.angular_frequencies", "1000 rad/s");
  set_field(c, "torque1.phases", "0 deg, 90 deg, 0");
  // One harmonic is one element of each list: the shorter list is named.
  const std::optional<InputError> lengths = error_of([&] { validate_fields(c); });
  REQUIRE(lengths.has_value());
  CHECK(lengths->field() == "torque1.angular_frequencies");
  CHECK(contains(lengths->allowed(), "as many values as torque1.amplitudes (3)"));
  set_field(c, "torque1.angular_frequencies", "1000, 2000, 3000 rad/s");
  CHECK_FALSE(error_of([&] { validate_fields(c); }).has_value());
  CHECK_THROWS_AS(get_numeric_field(c, "torque1.amplitudes"), InputError);
  // The stiffness unit: N/um = kN/mm = 1e6 N/m, by an exact decimal shift.
  set_field(c, "model.mesh_stiffness", "constant");
  set_field(c, "model.constant_mesh_stiffness", "350 N/um");
  CHECK(c.model.constant_mesh_stiffness_n_per_m == 3.5e8);
  set_field(c, "model.constant_mesh_stiffness", "0.35 kN/mm");
  CHECK(c.model.constant_mesh_stiffness_n_per_m == 3.5e5);
  c.model.damping_update = DampingUpdate::each_impact;
  CHECK(contains(refused("model.damping_reference_speed", "1 m/s").allowed(),
                 "damping_update = \"frozen\""));
  CHECK_THROWS_AS(get_numeric_field(c, "model.damping_form"), InputError);
  CHECK_THROWS_AS(get_numeric_field(c, "name"), InputError);
}

TEST_CASE("the writer writes exactly the keys that apply, each a row of the schema") {
  const SimulationCase c = every_key_case();
  std::set<std::string> written;
  std::string section;
  std::istringstream lines(write_case_file(c));
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line.front() == '#') continue;
    if (line.front() == '[') {
      section = line.substr(1, line.find(']') - 1) + ".";
      continue;
    }
    written.insert(section + line.substr(0, line.find(' ')));
  }
  std::set<std::string> expected;
  for (const Field& field : case_schema()) {
    // The keys added after case files were written are left out at their
    // defaults; a key that may be absent is left out when it is.
    const bool at_default =
        !absent(field, c) && value_text(field, c) == value_text(field, SimulationCase{});
    if (applies(field, c) && !absent(field, c) && (field.written_at_default || !at_default)) {
      expected.insert(field.name());
    }
  }
  CHECK(written == expected);
  // Case 3: torque1 sinusoidal (4 keys, its zero mean left out), torque2
  // constant (2), 18 [gears] (the paper's 10, dedendum, two shifts and the
  // five that may be absent), 4 [initial], 17 [model] (with stiffness_model and
  // five term switches; the steady-state keys at their defaults left out),
  // 5 [integrator], name.
  CHECK(written.size() == 51);
}

TEST_CASE("an unknown key's nearest key: edit distance over the schema's names") {
  CHECK(edit_distance("kitten", "sitting") == 3);
  CHECK(edit_distance("", "abc") == 3);
  CHECK(edit_distance("ab", "ba") == 1);  // a swap of neighbours is one edit
  CHECK(edit_distance("poisson_ratio", "poisson_ratio") == 0);
  CHECK(nearest_key("gears.poison_ratio") == std::optional<std::string>("gears.poisson_ratio"));
  CHECK(nearest_key("gears.modul") == std::optional<std::string>("gears.module"));
  CHECK(nearest_key("integrator.end_tiem") == std::optional<std::string>("integrator.end_time"));
  // A key under the wrong section, and a bare key.
  CHECK(nearest_key("gears.friction_coefficient") ==
        std::optional<std::string>("model.friction_coefficient"));
  CHECK(nearest_key("backlash") == std::optional<std::string>("gears.backlash"));
  // Nothing near: no suggestion rather than a wild one.
  CHECK(!nearest_key("zebra.stripes"));
  CHECK(!nearest_key("x"));
  // set_field and get_numeric_field suggest it as the fix.
  SimulationCase c;
  try {
    set_field(c, "gears.modul", "3 mm");
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(e.fix() == "did you mean gears.module?");
    CHECK(std::string(e.what()).find("; fix: did you mean gears.module?") != std::string::npos);
  }
}

TEST_CASE("validate_fields reports every refused row at once, and no relation of a refused row") {
  SimulationCase c = paper_case(1);
  c.gears.module_m = -2e-3;
  c.model.friction_coefficient = 2.0;
  c.integrator.step_s = 0.0;
  try {
    validate_fields(c);
    FAIL("no error");
  } catch (const InputError& e) {
    std::string fields;
    for (const Problem& p : e.problems()) fields += p.field + ";";
    // No geometry of a negative module, no step count of a zero step.
    CHECK(fields == "gears.module;model.friction_coefficient;integrator.step;");
    CHECK(e.field() == "gears.module");
    CHECK(std::string(e.what()).find("model.friction_coefficient = 2 is outside") !=
          std::string::npos);
  }
}

TEST_CASE("docs/case-files.md holds the program's schema and flag tables") {
  const std::string docs =
      read_text(std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / ".." / "docs" / "case-files.md");
  const verify::CommandResult schema = verify::run_command(verify::cli("schema"));
  REQUIRE(schema.exit_code == 0);
  CHECK(schema.out == schema_markdown());
  CHECK(between(docs, "<!-- schema table:", "<!-- end of schema table -->") == schema.out);
  const verify::CommandResult flags = verify::run_command(verify::cli("schema --flags"));
  REQUIRE(flags.exit_code == 0);
  CHECK(between(docs, "<!-- flag table:", "<!-- end of flag table -->") == flags.out);
  // One table row per key, after the header and the rule.
  CHECK(static_cast<std::size_t>(std::count(schema.out.begin(), schema.out.end(), '\n')) ==
        case_schema().size() + fault_schema().size() + train_schema().size() +
            planetary_schema().size() + 2);
}

namespace {

// The schema row's choices, in order, as names.
std::vector<std::string> choice_names(std::string_view key) {
  const Field* field = find_field(key);
  REQUIRE(field != nullptr);
  std::vector<std::string> names;
  for (const ChoiceName& c : field->choices) names.emplace_back(c.name);
  return names;
}

template <typename E, std::size_t N>
std::vector<std::string> table_names(const std::array<NamedValue<E>, N>& table) {
  std::vector<std::string> names;
  for (const NamedValue<E>& entry : table) names.emplace_back(entry.name);
  return names;
}

}  // namespace

TEST_CASE("each choice row takes its names from its enumeration's table, and they read back") {
  CHECK(choice_names("model.stiffness_model") == table_names(kStiffnessModels));
  CHECK(choice_names("model.moment_sign") == table_names(kMomentSigns));
  CHECK(choice_names("model.xform_rule") == table_names(kQuadratureRules));
  CHECK(choice_names("model.coast_phase") == table_names(kCoastPhases));
  CHECK(choice_names("model.damping_form") == table_names(kDampingForms));
  CHECK(choice_names("model.damping_stiffness") == table_names(kDampingStiffnesses));
  CHECK(choice_names("model.mesh_stiffness") == table_names(kMeshStiffnessModes));
  CHECK(choice_names("model.damping_update") == table_names(kDampingUpdates));
  CHECK(choice_names("integrator.kind") == table_names(kIntegratorKinds));
  std::vector<std::string> methods;
  for (const StiffnessMethod& m : kStiffnessMethods) methods.emplace_back(m.name);
  CHECK(choice_names("model.stiffness_method") == methods);

  // Every name parses to its enumerator and prints back, through the
  // functions the program and the Python module call.
  for (const auto& entry : kStiffnessModels) {
    CHECK(parse_stiffness_model(entry.name, "m") == entry.value);
    CHECK(to_string(entry.value) == entry.name);
  }
  for (const auto& entry : kQuadratureRules) {
    CHECK(parse_quadrature_rule(entry.name, "r") == entry.value);
    CHECK(to_string(entry.value) == entry.name);
  }
  for (const auto& entry : kMomentSigns) {
    CHECK(parse_moment_sign(entry.name, "s") == entry.value);
    CHECK(to_string(entry.value) == entry.name);
  }
  for (const StiffnessMethod& m : kStiffnessMethods) {
    StiffnessModel model;
    model.rule = QuadratureRule::boost_tanh_sinh;
    model = with_method(model, m.name, "method");
    CHECK(model.route == m.route);
    CHECK(method_name(model) == m.name);
  }
  // An unknown name is refused with every name of the table.
  try {
    parse_moment_sign("sideways", "moment_sign");
    FAIL("accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "moment_sign");
    CHECK(std::string(e.what()).find("one of physical, flipped") != std::string::npos);
  }
}

TEST_CASE("validate(StiffnessModel): the rows' ranges, then at least one term") {
  StiffnessModel model;
  CHECK_NOTHROW(validate(model));
  model.relative_tolerance = 0.1;
  try {
    validate(model);
    FAIL("accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "stiffness_tolerance");
    CHECK(std::string(e.what()).find("[1e-14, 1e-2]") != std::string::npos);
  }
  model = StiffnessModel{};
  // The paper's model has no shear term: switching off its three leaves none.
  for (Term t : {Term::hertz, Term::bending, Term::axial}) model.terms.set(t, false);
  try {
    validate(model);
    FAIL("accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "hertz_term");
    CHECK(std::string(e.what()).find("at least one term of (29)") != std::string::npos);
  }
  model.kind = StiffnessModelKind::potential_energy;
  CHECK_NOTHROW(validate(model));
}

TEST_CASE("a list reads as a case file writes it, in brackets and quotes, as it reads bare") {
  const Field* frequencies = find_field("torque1.angular_frequencies");
  REQUIRE(frequencies != nullptr);
  const std::vector<double> bare = parse_list(*frequencies, "1000 rad/s, 50 Hz, 3000", "a");
  REQUIRE(bare.size() == 3);
  CHECK(parse_list(*frequencies, "[\"1000 rad/s\", \"50 Hz\", 3000]", "a") == bare);
  CHECK(parse_list(*frequencies, " [ \"1000 rad/s\",\"50 Hz\" , \"3000\" ] ", "a") == bare);
  CHECK(parse_list(*frequencies, "[]", "a").empty());
  // An element is still checked and named by its index; a bracket left open is no list.
  try {
    static_cast<void>(parse_list(*frequencies, "[\"1000 rad/s\", \"-5 Hz\"]", "a"));
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(e.field() == "a[1]");
  }
  CHECK_THROWS_AS(parse_list(*frequencies, "[\"1000 rad/s\", \"5 Hz\"", "a"), InputError);
  // An angle list's plain number is in rad: 120 is refused, with how to write it in degrees.
  const Field* angles = find_train_field("stage.planet_angles");
  REQUIRE(angles != nullptr);
  try {
    static_cast<void>(parse_list(*angles, "[0, 120]", "stage.planet_angles"));
    FAIL("no error");
  } catch (const InputError& e) {
    CHECK(e.field() == "stage.planet_angles[1]");
    CHECK(e.allowed().find("\"120 deg\" gives it in deg") != std::string::npos);
  }
}
