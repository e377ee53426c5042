// A gear train read from a case file (docs/case-files.md, A gear train). References: the train
// the file describes, built by hand in C++ from the keys as written (every field equal, a pair's
// inputs through case_key); the same train built by hand, run bit for bit as the file's; the
// messages name each refused key under its body's or mesh's name, at its line.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstddef>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planetary_train.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

using namespace gearimpact;

namespace {

const std::string kExample = std::string(GEARIMPACT_EXAMPLES_DIR) + "/pinion_idler_wheel.toml";

// The text of an example file (by default the train's, kExample).
std::string example_text(const std::string& path = kExample) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The example's text with `from` (which it holds once) replaced by `to`.
std::string edited(const std::string& from, const std::string& to) {
  std::string text = example_text();
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  REQUIRE(text.find(from, at + 1) == std::string::npos);
  return text.replace(at, from.size(), to);
}

// The example written in C++: its keys as the file writes them, the defaults its comments name.
GearTrain hand_built() {
  SimulationCase defaults;
  defaults.name = "pinion-idler-wheel";
  defaults.integrator.step_s = 0.5e-6;
  defaults.integrator.end_time_s = 20e-3;
  defaults.model.friction_coefficient = 0.04;
  defaults.gears.module_m = 2e-3;
  defaults.gears.face_width_m = 20e-3;
  defaults.gears.pressure_angle_rad = 20.0 * (pi / 180.0);  // "20 deg": the number times the unit
  defaults.gears.youngs_modulus_pa = 206.8e9;
  defaults.gears.poisson_ratio = 0.3;
  defaults.gears.density_kg_m3 = 7800.0;
  defaults.gears.backlash_m = 0.05e-3;

  TrainMesh first;
  first.name = "pinion-idler";
  first.body_a = 0;
  first.body_b = 1;
  first.pair = defaults;
  first.pair.gears.teeth1 = 20;
  first.pair.gears.teeth2 = 30;
  TrainMesh second;
  second.name = "idler-wheel";
  second.body_a = 1;
  second.body_b = 2;
  second.pair = defaults;
  second.pair.gears.teeth1 = 30;
  second.pair.gears.teeth2 = 60;
  second.pair.gears.backlash_m = 0.1e-3;
  ToothFault missing;
  missing.gear = Gear::two;
  missing.tooth = 0;
  missing.state.kind = ToothKind::missing;
  second.pair.faults = {missing};

  const auto body = [](std::string name, double inertia, double torque, double w) {
    TrainBody b;
    b.name = std::move(name);
    b.inertia_kg_m2 = inertia;
    b.torque.kind = Torque::Kind::constant;
    b.torque.constant_n_m = torque;
    b.w_rad_per_s = w;
    return b;
  };
  GearTrain train;
  train.bodies = {
      body("pinion", 3.9e-5, 20.0, 100.0),
      // Its disc as the idler of the first mesh naming it (gear 2 of pinion-idler).
      body("idler", moment_of_inertia(first.pair.gears, Gear::two), 0.0, 66.666666666666667),
      body("wheel", moment_of_inertia(second.pair.gears, Gear::two), -60.0, 33.333333333333333),
      body("brake-disc", 2e-3, 0.0, 33.333333333333333)};
  train.meshes = {first, second};
  TrainShaft shaft;
  shaft.kind = TrainShaft::Kind::rigid;
  shaft.body_a = 2;
  shaft.body_b = 3;
  train.shafts = {shaft};
  train.integrator = defaults.integrator;
  return train;
}

// The first problem of reading `text`: its field and its "file:line".
Problem first_problem(const std::string& text) {
  try {
    (void)parse_train(text, "train.toml");
  } catch (const CaseFileError& e) {
    return e.problems().front();
  }
  FAIL("the file was read without a problem");
  return {};
}

// The 1-based line of the first line of the example holding `text`.
std::string line_of(const std::string& text, const std::string& what) {
  const std::size_t at = text.find(what);
  REQUIRE(at != std::string::npos);
  const auto line = std::count(text.begin(), text.begin() + static_cast<long>(at), '\n') + 1;
  return "train.toml:" + std::to_string(line);
}

}  // namespace

TEST_CASE("the example train file reads into the train built by hand, field by field") {
  const GearTrain read = read_train_file(kExample);
  const GearTrain hand = hand_built();
  REQUIRE(read.bodies.size() == hand.bodies.size());
  for (std::size_t i = 0; i < hand.bodies.size(); ++i) {
    const TrainBody& a = read.bodies[i];
    const TrainBody& b = hand.bodies[i];
    CAPTURE(b.name);
    CHECK(a.name == b.name);
    CHECK(a.inertia_kg_m2 == b.inertia_kg_m2);
    CHECK(a.torque.kind == b.torque.kind);
    CHECK(a.torque.constant_n_m == b.torque.constant_n_m);
    CHECK(a.theta_rad == b.theta_rad);
    CHECK(a.w_rad_per_s == b.w_rad_per_s);
  }
  REQUIRE(read.meshes.size() == hand.meshes.size());
  for (std::size_t k = 0; k < hand.meshes.size(); ++k) {
    const TrainMesh& a = read.meshes[k];
    const TrainMesh& b = hand.meshes[k];
    CAPTURE(b.name);
    CHECK(a.name == b.name);
    CHECK(a.body_a == b.body_a);
    CHECK(a.body_b == b.body_b);
    // Every input of the pair, one line per schema row, its faults included.
    CHECK(case_key(a.pair) == case_key(b.pair));
    CHECK(a.pair.faults == b.pair.faults);
    CHECK(a.pair.run_keys_absent.empty());
  }
  REQUIRE(read.shafts.size() == 1);
  CHECK(read.shafts[0].kind == hand.shafts[0].kind);
  CHECK(read.shafts[0].body_a == hand.shafts[0].body_a);
  CHECK(read.shafts[0].body_b == hand.shafts[0].body_b);
  CHECK(read.integrator.step_s == hand.integrator.step_s);
  CHECK(read.integrator.end_time_s == hand.integrator.end_time_s);
  CHECK(read.integrator.kind == hand.integrator.kind);
  CHECK(read.integrator.output_every == hand.integrator.output_every);
}

TEST_CASE("a train run from the file is the run of the train built by hand, bit for bit") {
  GearTrain read = read_train_file(kExample);
  GearTrain hand = hand_built();
  // 2 ms: the pinion turns a third of a revolution, both meshes pass pairs in and out.
  read.integrator.end_time_s = hand.integrator.end_time_s = 2e-3;
  const TrainResult a = simulate_train(read);
  const TrainResult b = simulate_train(hand);
  REQUIRE(a.series.size() == b.series.size());
  REQUIRE(a.series.size() > 100);
  for (std::size_t i = 0; i < a.series.size(); ++i) {
    const TrainRow& x = a.series[i];
    const TrainRow& y = b.series[i];
    bool same = x.t_s == y.t_s && x.theta_rad == y.theta_rad && x.w_rad_per_s == y.w_rad_per_s;
    for (std::size_t k = 0; k < x.meshes.size(); ++k) {
      same = same && x.meshes[k].s_m == y.meshes[k].s_m &&
             x.meshes[k].normal_force_n == y.meshes[k].normal_force_n &&
             x.meshes[k].friction_force_n == y.meshes[k].friction_force_n &&
             x.meshes[k].region == y.meshes[k].region && x.meshes[k].pairs == y.meshes[k].pairs;
    }
    if (!same) {
      INFO("row " << i);
      REQUIRE(same);
    }
  }
  // Pairs enter and leave both meshes: the run crosses events, each cut alike.
  REQUIRE(a.summary.events > 10);
  CHECK(a.summary.events == b.summary.events);
  CHECK(a.summary.ledger_residual_max_j == b.summary.ledger_residual_max_j);
  CHECK(a.meshes[1].impacts == b.meshes[1].impacts);
}

TEST_CASE("a train file's [drive] sets its drift check, as a two-gear file's does") {
  std::string text = example_text();
  const GearTrain plain = parse_train(text, "train.toml");
  CHECK(plain.drive.settle_s == Drive{}.settle_s);
  text += "\n[drive]\nsettle = \"20 ms\"\nspeed_tolerance = 2e-3\n";
  const GearTrain set = parse_train(text, "train.toml");
  CHECK(set.drive.settle_s == 20e-3);
  CHECK(set.drive.speed_tolerance == 2e-3);
  // Its rows' ranges hold here too.
  CHECK_THROWS_WITH_AS(parse_train(example_text() + "\n[drive]\nsettle = \"-1 s\"\n", "train.toml"),
                       doctest::Contains("drive.settle"), CaseFileError);
}

TEST_CASE("a train file's [tacho] names its body, its other keys the pair's [tacho] rows") {
  const std::string text = example_text() +
                           "\n[tacho]\nbody = \"wheel\"\npulses_per_revolution = 60\n"
                           "offset = \"10 deg\"\njitter = \"1 us\"\nseed = 7\n";
  const GearTrain t = parse_train(text, "train.toml");
  REQUIRE(t.tacho_body >= 0);
  CHECK(t.bodies[static_cast<std::size_t>(t.tacho_body)].name == "wheel");
  CHECK(t.tacho.pulses_per_revolution == 60);
  // The unit's conversion may round its product in another order than this one: a few ulps.
  CHECK(t.tacho.offset_rad == doctest::Approx(10.0 * pi / 180.0).scale(0).epsilon(1e-15));
  CHECK(t.tacho.jitter_s == 1e-6);
  CHECK(t.tacho.seed == 7);
  // The pairs keep none: the train's bodies carry it.
  for (const TrainMesh& m : t.meshes) CHECK(m.pair.tacho.pulses_per_revolution == 0);
  CHECK(parse_train(example_text(), "train.toml").tacho_body == -1);
  // --set reaches the train's own sections as the file would write them.
  const GearTrain set = parse_train(example_text(), "train.toml",
                                    {"tacho.body=wheel", "tacho.pulses_per_revolution=60",
                                     "tacho.offset=10 deg", "tacho.jitter=1 us", "tacho.seed=7"});
  CHECK(set.tacho_body == t.tacho_body);
  CHECK(set.tacho.pulses_per_revolution == 60);
  CHECK(set.tacho.offset_rad == t.tacho.offset_rad);
  CHECK(parse_train(example_text(), "train.toml", {"sensor.body=idler"}).sensor_body == 1);
  const auto refusal = [](const std::string& tacho) {
    try {
      (void)parse_train(example_text() + "\n[tacho]\n" + tacho, "train.toml");
    } catch (const CaseFileError& e) {
      return std::string(e.what());
    }
    return std::string("none");
  };
  CHECK(refusal("pulses_per_revolution = 1\n").find("tacho.body is missing") != std::string::npos);
  CHECK(refusal("body = \"whel\"\n").find("tacho.body = \"whel\" names no body") !=
        std::string::npos);
  CHECK(refusal("body = \"wheel\"\nshaft = \"wheel\"\n").find("tacho.shaft is not read") !=
        std::string::npos);
  CHECK(refusal("body = \"wheel\"\npulses_per_revolution = -1\n")
            .find("tacho.pulses_per_revolution") != std::string::npos);
}

TEST_CASE("a file without [[bodies]] is the two-gear case it always was") {
  const std::string text = write_case_file(paper_case(2));
  const GearTrain train = parse_train(text, "case2.toml");
  const SimulationCase c = parse_case(text, "case2.toml");
  REQUIRE(train.bodies.size() == 2);
  REQUIRE(train.meshes.size() == 1);
  CHECK(train.two_gear_case);
  CHECK_FALSE(parse_train(example_text(), "train.toml").two_gear_case);
  CHECK(case_key(train.meshes[0].pair) == case_key(c));
  CHECK(train.bodies[0].w_rad_per_s == c.initial.w1_rad_per_s);
  CHECK(train.bodies[1].inertia_kg_m2 == moment_of_inertia(c.gears, Gear::two));
}

TEST_CASE("a refused key of each kind is named under its body's or mesh's name, at its line") {
  SUBCASE("a body's key out of its range") {
    const std::string text =
        edited("name = \"idler\"\n", "name = \"idler\"\ninertia = \"-1 kg*m^2\"\n");
    const Problem p = first_problem(text);
    CHECK(p.field == "bodies.idler.inertia");
    CHECK(p.where == line_of(text, "inertia = \"-1"));
  }
  SUBCASE("a mesh's pair key out of its range") {
    const std::string text = edited("backlash = \"0.1 mm\"", "backlash = \"-0.1 mm\"");
    const Problem p = first_problem(text);
    CHECK(p.field == "meshes.idler-wheel.gears.backlash");
    CHECK(p.where == line_of(text, "backlash = \"-0.1"));
    CHECK(p.message.find("meshes.idler-wheel.gears.backlash") == 0);
  }
  SUBCASE("a default of every mesh refused under each mesh that reads it") {
    const std::string text = edited("module = \"2 mm\"", "module = \"-2 mm\"");
    const Problem p = first_problem(text);
    CHECK(p.field == "meshes.pinion-idler.gears.module");
    CHECK(p.where == line_of(text, "module = \"-2"));
  }
  SUBCASE("a mesh naming no body") {
    const std::string text = edited("body_b = \"wheel\"", "body_b = \"whel\"");
    const Problem p = first_problem(text);
    CHECK(p.field == "meshes.idler-wheel.body_b");
    CHECK(p.where == line_of(text, "body_b = \"whel\""));
    CHECK(p.message.find("\"pinion\", \"idler\", \"wheel\", \"brake-disc\"") != std::string::npos);
  }
  SUBCASE("a key of a body's torque table, by its [torque2] row, under the body") {
    const std::string text =
        edited("torque = \"-60 N*m\"", "torque = {kind = \"drag\", drag_constant = \"-5 N*m\"}");
    const Problem p = first_problem(text);
    CHECK(p.field == "bodies.wheel.torque.drag_constant");
    CHECK(p.where == line_of(text, "drag_constant = \"-5"));
    CHECK(p.message.find("bodies.wheel.torque.drag_constant") == 0);
  }
  SUBCASE("a driven body whose w is not its driver's") {
    const std::string text = edited(
        "torque = \"20 N*m\"", "torque = {kind = \"prescribed-speed\", mean_speed = \"90 rad/s\"}");
    const Problem p = first_problem(text);
    CHECK(p.field == "bodies.pinion.w");
    CHECK(p.fix == "bodies.pinion.w = \"90 rad/s\"");
  }
  SUBCASE("an unknown key of a body") {
    const std::string text = edited("torque = \"20 N*m\"", "torke = \"20 N*m\"");
    const Problem p = first_problem(text);
    CHECK(p.field == "bodies.pinion.torke");
    CHECK(p.where == line_of(text, "torke"));
  }
  SUBCASE("a body's name with a dot, which would split its keys' names") {
    const std::string text = edited("name = \"idler\"", "name = \"idler.1\"");
    const Problem p = first_problem(text);
    CHECK(p.field == "bodies[1].name");
    CHECK(p.where == line_of(text, "idler.1"));
  }
  SUBCASE("a torsional shaft without its stiffness") {
    const std::string text = edited("kind = \"rigid\"", "kind = \"torsional\"");
    const Problem p = first_problem(text);
    CHECK(p.field == "shafts[0].stiffness");
  }
  SUBCASE("a two-gear section a train does not read") {
    const std::string text =
        example_text() + "\n[torque1]\nkind = \"constant\"\nvalue = \"1 N*m\"\n";
    const Problem p = first_problem(text);
    CHECK(p.field == "torque1");
    CHECK(p.where == line_of(text, "[torque1]"));
  }
  SUBCASE("the train's end time missing") {
    const std::string text = edited("end_time = \"20 ms\"\n", "");
    const Problem p = first_problem(text);
    CHECK(p.field == "integrator.end_time");
  }
  SUBCASE("a body without inertia that no mesh names") {
    const std::string text = edited("inertia = \"2e-3 kg*m^2\"\n", "");
    const Problem p = first_problem(text);
    CHECK(p.field == "bodies.brake-disc.inertia");
  }
}

TEST_CASE("every row of a train table has its unit, help and range or choices") {
  for (const Field& row : train_schema()) {
    CAPTURE(row.name());
    CHECK(!row.help.empty());
    if (row.kind == FieldKind::quantity) CHECK(!row.unit.empty());
    // shafts.kind: rigid, torsional; stage.held: ring, carrier, sun; faults.member: sun,
    // planet1 ... planet5, ring.
    if (row.kind == FieldKind::choice) {
      CHECK(row.choices.size() == (row.name() == "stage.held"      ? 3U
                                   : row.name() == "faults.member" ? 7U
                                                                   : 2U));
    }
  }
  CHECK(find_train_field("bodies.inertia") != nullptr);
  CHECK(find_train_field("meshes.body_a") != nullptr);
  CHECK(find_train_field("shafts.stiffness") != nullptr);
}

TEST_CASE("a --set of a train's key reads as the file edited to say so") {
  const std::string text = example_text();
  const GearTrain set = parse_train(text, "train.toml",
                                    {"meshes.idler-wheel.gears.backlash=0.2 mm",
                                     "bodies.pinion.w=50 rad/s", "integrator.end_time=2 ms"});
  std::string edited_text = text;
  const auto replace = [&edited_text](const std::string& from, const std::string& to) {
    const std::size_t at = edited_text.find(from);
    REQUIRE(at != std::string::npos);
    edited_text.replace(at, from.size(), to);
  };
  replace("backlash = \"0.1 mm\"", "backlash = \"0.2 mm\"");
  replace("w = \"100 rad/s\"", "w = \"50 rad/s\"");
  replace("end_time = \"20 ms\"", "end_time = \"2 ms\"");
  const GearTrain file = parse_train(edited_text, "train.toml");
  CHECK(set.bodies[0].w_rad_per_s == file.bodies[0].w_rad_per_s);
  CHECK(set.integrator.end_time_s == file.integrator.end_time_s);
  for (std::size_t k = 0; k < file.meshes.size(); ++k) {
    CHECK(case_key(set.meshes[k].pair) == case_key(file.meshes[k].pair));
  }
  CHECK(set.meshes[1].pair.gears.backlash_m == 0.2e-3);
}

TEST_CASE("a body's default inertia follows a --set of its mesh's gears") {
  const GearTrain before = parse_train(example_text(), "train.toml");
  const GearTrain after =
      parse_train(example_text(), "train.toml", {"meshes.pinion-idler.gears.face_width=30 mm"});
  CHECK(after.meshes[0].pair.gears.face_width_m == 30e-3);
  // The idler's disc, gear 2 of pinion-idler: J of a disc is proportional to its width.
  CHECK(after.bodies[1].inertia_kg_m2 == moment_of_inertia(after.meshes[0].pair.gears, Gear::two));
  CHECK(after.bodies[1].inertia_kg_m2 != before.bodies[1].inertia_kg_m2);
}

TEST_CASE("a --set naming no body, no key or a value out of range is refused by its key") {
  const auto refused = [](const std::string& assignment) {
    try {
      (void)parse_train(example_text(), "train.toml", {assignment});
    } catch (const InputError& e) {
      return e.problems().front();
    } catch (const CaseFileError& e) {
      return e.problems().front();
    }
    FAIL("the --set was taken: " << assignment);
    return Problem{};
  };
  const Problem no_body = refused("bodies.idlr.w=1 rad/s");
  CHECK(no_body.field == "bodies.idlr.w");
  CHECK(no_body.message.find("\"pinion\", \"idler\", \"wheel\", \"brake-disc\"") !=
        std::string::npos);
  CHECK(refused("meshes.idler-wheel.gears.modul=2 mm").field == "meshes.idler-wheel.gears.modul");
  CHECK(refused("bodies.idler.inertia=-1 kg*m^2").field == "bodies.idler.inertia");
  // A value the row takes but the pair refuses is the reader's: named under the mesh.
  CHECK(refused("meshes.idler-wheel.gears.teeth2=5").field.rfind("meshes.idler-wheel.", 0) == 0);
}

TEST_CASE("a body's torque table reads by the rows of [torque1], a drag's by those of [torque2]") {
  // The example's pinion driven at its speed, the wheel braked by a drag: each body's Torque is
  // the one the rows give the two-gear case's sections for the same keys.
  std::string text = edited("torque = \"20 N*m\"\n",
                            "torque = {kind = \"prescribed-speed\", mean_speed = \"100 rad/s\"}\n");
  text = text.replace(text.find("torque = \"-60 N*m\""), 18,
                      "torque = {kind = \"drag\", drag_constant = \"5 N*m\", drag_viscous = "
                      "\"1e-3 N*m*s/rad\"}");
  const GearTrain t = parse_train(text, "driven.toml");
  const Torque& driver = t.bodies[0].torque;
  CHECK(driver.kind == Torque::Kind::prescribed_speed);
  CHECK(driver.mean_speed_rad_per_s == 100.0);
  const Torque& drag = t.bodies[2].torque;
  CHECK(drag.kind == Torque::Kind::drag);
  CHECK(drag.drag_constant_n_m == 5.0);
  CHECK(drag.drag_viscous_n_m_s == 1e-3);
  CHECK(t.bodies[1].torque.kind == Torque::Kind::constant);
  CHECK(t.bodies[1].torque.constant_n_m == 0.0);
}

TEST_CASE("a train file's bodies on bearings, centre angles and sensor read as written") {
  const std::string path = std::string(GEARIMPACT_EXAMPLES_DIR) + "/two_stage_rig_bearings.toml";
  const GearTrain t = read_train_file(path);
  REQUIRE(t.bodies.size() == 4);
  // The keys as the file writes them: "200 N/um" is 2e8 N/m, the y values absent (isotropic).
  REQUIRE(t.bodies[0].bearing.has_value());
  CHECK(t.bodies[0].bearing->stiffness_x_n_per_m == 200.0 * 1e6);
  CHECK_FALSE(t.bodies[0].bearing->stiffness_y_n_per_m.has_value());
  CHECK(t.bodies[0].bearing->damping_x_n_s_per_m == 400.0);
  CHECK(t.bodies[0].bearing->mass_kg == 1.5);
  REQUIRE(t.bodies[1].bearing.has_value());
  CHECK(t.bodies[1].bearing->stiffness_y_n_per_m == 250.0 * 1e6);
  CHECK(t.bodies[1].bearing->mass_kg == 6.0);
  CHECK_FALSE(t.bodies[2].bearing.has_value());
  REQUIRE(t.bodies[3].bearing.has_value());
  CHECK(t.meshes[0].centre_angle_rad == 0.0);
  CHECK(t.meshes[1].centre_angle_rad == 60.0 * (pi / 180.0));
  CHECK(t.sensor_body == 3);
  CHECK(t.sensor_angle_rad == 150.0 * (pi / 180.0));
}

TEST_CASE("a body's bearings and the sensor refuse a bad key by its name, at its line") {
  const std::string path = std::string(GEARIMPACT_EXAMPLES_DIR) + "/two_stage_rig_bearings.toml";
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto problem_of = [](const std::string& edited_text) {
    try {
      parse_train(edited_text, "edited.toml");
    } catch (const CaseFileError& e) {
      return e.problems().front();
    }
    return Problem{};
  };
  const auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = text;
    const std::size_t at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
  };
  SUBCASE("a stiffness below its row's range") {
    const Problem p =
        problem_of(replace("stiffness_x = \"200 N/um\"", "stiffness_x = \"-1 N/um\""));
    CHECK(p.field == "bodies.input.bearings.stiffness_x");
  }
  SUBCASE("a bearing without its required mass") {
    const Problem p = problem_of(replace(", mass = \"1.5 kg\"", ""));
    CHECK(p.field == "bodies.input.bearings.mass");
  }
  SUBCASE("an unknown key of a body's bearings") {
    const Problem p = problem_of(replace("damping_x = \"400 N*s/m\"", "dampin_x = \"400 N*s/m\""));
    CHECK(p.field == "bodies.input.bearings.dampin_x");
  }
  SUBCASE("a sensor naming no body") {
    const Problem p = problem_of(replace("body = \"output\"", "body = \"outptu\""));
    CHECK(p.field == "sensor.body");
  }
}

TEST_CASE(
    "a planar stage file's damping keys read in SI, 0 when absent, refused without supports") {
  const std::string examples = GEARIMPACT_EXAMPLES_DIR;
  const std::string planar = example_text(examples + "/planetary_stage_planar.toml");
  const PlanetaryStage absent = parse_stage(planar, "planar.toml");
  REQUIRE(absent.supports.has_value());
  CHECK(absent.supports->sun_support_damping_n_s_per_m == 0.0);
  CHECK(absent.supports->ring_support_damping_n_s_per_m == 0.0);
  CHECK(absent.supports->carrier_support_damping_n_s_per_m == 0.0);
  CHECK(absent.supports->planet_bearing_damping_n_s_per_m == 0.0);
  // The units as written: N*s/mm is 1000 N*s/m.
  const PlanetaryStage set = parse_stage(
      planar, "planar.toml",
      {"stage.sun_support_damping=120 N*s/m", "stage.ring_support_damping=0.5 N*s/mm",
       "stage.carrier_support_damping=7 N*s/m", "stage.planet_bearing_damping=300 N*s/m"});
  REQUIRE(set.supports.has_value());
  CHECK(set.supports->sun_support_damping_n_s_per_m == 120.0);
  CHECK(set.supports->ring_support_damping_n_s_per_m == 500.0);
  CHECK(set.supports->carrier_support_damping_n_s_per_m == 7.0);
  CHECK(set.supports->planet_bearing_damping_n_s_per_m == 300.0);
  const auto refusal = [](const std::string& text, const std::string& assignment) {
    try {
      parse_stage(text, "stage.toml", {assignment});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(read)");
  };
  // Past the row's range (that of a body's bearings' dampers), named with the range.
  for (const std::string assignment :
       {"stage.planet_bearing_damping=2e6 N*s/m", "stage.sun_support_damping=-1 N*s/m"}) {
    const std::string why = refusal(planar, assignment);
    CAPTURE(why);
    CHECK(why.find(assignment.substr(0, assignment.find('='))) != std::string::npos);
    CHECK(why.find("[0, 1000000] N*s/m") != std::string::npos);
  }
  // A damper with no support to be in parallel with (the rotational stage's file).
  const std::string why = refusal(example_text(examples + "/planetary_stage.toml"),
                                  "stage.ring_support_damping=5 N*s/m");
  CAPTURE(why);
  CHECK(why.find("stage.ring_support_damping needs the planar stage's keys") != std::string::npos);
}
