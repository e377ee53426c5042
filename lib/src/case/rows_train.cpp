// The rows of a train file (train_schema): plain Fields without a slot of SimulationCase.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

namespace {

// The rows of train_schema(): plain Fields without a slot of SimulationCase.
std::vector<Field> make_train_schema() {
  std::vector<Field> rows;
  const auto row = [&rows](std::string_view section, std::string_view key, FieldKind kind,
                           bool required, std::string help) -> Field& {
    rows.push_back(slotless_field(section, key, kind, required, std::move(help)));
    return rows.back();
  };
  const auto quantity = [&row](std::string_view section, std::string_view key, Dimension dimension,
                               std::string_view unit, Range range, std::string_view when_absent,
                               std::string help) -> Field& {
    Field& f = row(section, key, FieldKind::quantity, false, std::move(help));
    f.dimension = dimension;
    f.unit = unit;
    f.range = range;
    f.when_absent = when_absent;
    return f;
  };
  // A name addresses its table's keys (bodies.NAME.inertia): a dot would split it.
  constexpr std::string_view no_dot = "and no '.' (it addresses the table's keys)";
  row("bodies", "name", FieldKind::text, true, "the body's name, one no other body has")
      .range.note = no_dot;
  // The range of [shafts] motor_inertia: a watch's wheel to a mill's drive.
  quantity("bodies", "inertia", Dimension::moment_of_inertia, "kg*m^2",
           {closed(1e-12), closed(1e6), {}},
           "the disc of its gear in the first mesh that names it (required for a body no "
           "mesh names)",
           "J, the body's moment of inertia about its axis");
  quantity("bodies", "torque", Dimension::torque, "N*m", {}, "0",
           "a constant torque on the body, positive in the sense the body turns when the train "
           "runs forward (a load is negative); or a table of [torque1]'s keys (with kind = "
           "\"drag\", [torque2]'s): a driver, a speed controller, an induction motor, a drag, a "
           "torque of time");
  quantity("bodies", "theta", Dimension::angle, "deg", {}, "0", "the body's initial angle");
  quantity("bodies", "w", Dimension::angular_velocity, "rad/s", {}, "0",
           "the body's initial speed, positive forward");
  // A body's centre on elastic bearings: the two-gear [bearings] keys of one
  // gear, without its number, in the body's table `bearings` (absent: the
  // centre is fixed). The ranges are those rows' (bearing_*_range).
  quantity("bodies.bearings", "stiffness_x", Dimension::stiffness, "N/um",
           bearing_stiffness_range(), {}, "k_x of the body's bearings, along the train's x axis")
      .required = true;
  quantity("bodies.bearings", "stiffness_y", Dimension::stiffness, "N/um",
           bearing_stiffness_range(), "stiffness_x (isotropic)",
           "k_y of the body's bearings, along the train's y axis");
  quantity("bodies.bearings", "damping_x", Dimension::damping, "N*s/m", bearing_damping_range(),
           "0", "c_x of the body's bearings");
  quantity("bodies.bearings", "damping_y", Dimension::damping, "N*s/m", bearing_damping_range(),
           "damping_x (isotropic)", "c_y of the body's bearings");
  quantity("bodies.bearings", "mass", Dimension::mass, "kg", bearing_mass_range(), {},
           "m, the mass the bearings carry: the body's with what moves with its centre (on a "
           "rigid shaft, the whole shaft's; one body of a shaft has bearings)")
      .required = true;
  row("meshes", "name", FieldKind::text, true, "the mesh's name, one no other mesh has")
      .range.note = no_dot;
  row("meshes", "body_a", FieldKind::text, true,
      "the name of the body that is the pair's gear 1 (its pinion: [gears] teeth1, faults' gear "
      "= \"pinion\")");
  row("meshes", "body_b", FieldKind::text, true,
      "the name of the body that is the pair's gear 2 (teeth2, gear = \"wheel\"); it turns "
      "forward when body_a does");
  // A full turn either way, as [bearings] sensor_angle.
  quantity("meshes", "centre_angle", Dimension::angle, "deg",
           {closed(-2.0 * pi), closed(2.0 * pi), {}}, "0",
           "the direction of the line of centres, from body_a's centre to body_b's, from the "
           "train's x axis towards y: where a body on bearings sees the mesh's forces");
  // The accelerometer on a body's bearings ([bearings] sensor_gear and sensor_angle of a pair).
  row("sensor", "body", FieldKind::text, false,
      "the name of the body (with bearings, or on a rigid shaft with one) on whose bearings the "
      "accelerometer sits: gearimpact train writes its sensor_acceleration column")
      .when_absent = "no sensor (required in a [sensor] table)";
  quantity("sensor", "angle", Dimension::angle, "deg", {closed(-2.0 * pi), closed(2.0 * pi), {}},
           "90 deg", "the accelerometer's direction, from the train's x axis towards y");
  // A train's tacho reads a body ([tacho] shaft of a pair); its other keys are the pair's rows.
  row("tacho", "body", FieldKind::text, false,
      "the name of the body whose angle the tacho reads (a train with a body on bearings), its "
      "other keys the two-gear [tacho]'s but shaft: gearimpact train writes tacho.csv")
      .when_absent = "no tacho (required in a train's [tacho] table)";
  Field& kind = row("shafts", "kind", FieldKind::choice, true,
                    "a rigid shaft makes its two bodies one (their inertias summed); a torsional "
                    "one is a spring T = k (theta_a - theta_b) on body_b");
  // The codes are the reader's (the case folder comes before the dynamics' TrainShaft).
  kind.choices = {{"rigid", 0, "the two bodies turn as one", true},
                  {"torsional", 1, "a torsional spring of the shaft's stiffness", true}};
  row("shafts", "body_a", FieldKind::text, true, "the name of one body on the shaft");
  row("shafts", "body_b", FieldKind::text, true, "the name of the other body on the shaft");
  // The range of [shafts] motor_stiffness: from nearly free to stiffer than any shaft.
  Field& stiffness =
      quantity("shafts", "stiffness", Dimension::torsional_stiffness, "N*m/rad",
               {closed(1e-3), closed(1e12), {}}, {}, "k, the torsional shaft's stiffness");
  stiffness.required = true;
  stiffness.only_when = FieldCondition{"kind", {"torsional"}};
  // A nonlinear rotational planetary stage (dynamics/planetary_train.hpp): [stage] beside the
  // pair sections (every mesh's keys) and [integrator], read into a PlanetaryStage.
  // Tooth counts from a pinion's fewest to a large ring's; the geometry refuses the rest (a ring
  // that does not close, planets that overlap) by the key's name.
  const Range teeth{closed(5.0), closed(1000.0), {}};
  for (const auto& [key, help] :
       {std::pair<std::string_view, std::string>{"sun_teeth", "Z_s, the sun's tooth count"},
        {"planet_teeth", "Z_p, each planet's tooth count"},
        {"ring_teeth", "Z_r, the ring's (internal) tooth count; Z_r = Z_s + 2 Z_p"}}) {
    row("stage", key, FieldKind::integer, true, help).range = teeth;
  }
  // Up to 5 planets: the nonlinear stage's train takes no more (planetary_train).
  constexpr double kMostStagePlanets = 5.0;
  row("stage", "planets", FieldKind::integer, true, "N, the number of planets").range = {
      closed(1.0), closed(kMostStagePlanets), {}};
  // Unequal spacing: each angle in [0, 360) deg here; the reader asks one per planet, the first
  // 0, increasing, and the geometry (planetary_train) the assembly condition and the tips'
  // clearance.
  Field& angles = row("stage", "planet_angles", FieldKind::quantity_list, false,
                      "psi_n, each planet's angle counter-clockwise from planet 1's on the "
                      "carrier: one per planet, the first 0, increasing, each a multiple of "
                      "360 deg / (sun_teeth + ring_teeth) (the assembly condition)");
  planet_angles_field(angles, static_cast<std::size_t>(kMostStagePlanets));
  Field& held = row("stage", "held", FieldKind::choice, false,
                    "the member held still (its torque must be absent)");
  // The codes are the reader's (the case folder comes before the dynamics' HeldMember).
  held.choices = {{"ring", 0, "the ring is fixed: the sun drives the carrier", true},
                  {"carrier", 1, "the carrier is fixed: the sun drives the ring", true},
                  {"sun", 2, "the sun is fixed: the ring drives the carrier", true}};
  held.when_absent = "ring";
  // The inertias' range is [[bodies]] inertia's.
  for (const auto& [key, help] :
       {std::pair<std::string_view, std::string>{"sun_inertia", "J_s, the sun's moment of inertia"},
        {"ring_inertia", "J_r, the ring's moment of inertia"},
        {"carrier_inertia",
         "J_c, the carrier's moment of inertia (with planet_mass: without the planets' orbit)"},
        {"planet_inertia", "J_p, each planet's moment of inertia about its pin"}}) {
    quantity("stage", key, Dimension::moment_of_inertia, "kg*m^2", {closed(1e-12), closed(1e6), {}},
             {}, help)
        .required = true;
  }
  quantity("stage", "planet_mass", Dimension::mass, "kg", {open(0.0), closed(1e6), {}},
           "the carrier's inertia is taken as given",
           "m_p, each planet's mass: its orbit adds m_p R_c^2 to the carrier's inertia");
  // The planar stage (docs/planetary.md, "The planar stage"): the names of the planetary file's
  // keys of the linear model (rows_planetary.cpp), masses > 0 and stiffnesses >= 0 as there (a
  // planet bearing > 0: its planet would float free), bounded above as planet_mass and the
  // bearings' rows are; any of them asks for all (and planet_mass).
  for (const auto& [key, help] :
       {std::pair<std::string_view, std::string>{
            "sun_mass", "m_s, the sun's mass (the planar stage: its centre translates)"},
        {"ring_mass", "m_r, the ring's mass (the planar stage)"},
        {"carrier_mass", "m_c, the carrier's own mass (the planar stage)"}}) {
    quantity("stage", key, Dimension::mass, "kg", {open(0.0), closed(1e6), {}},
             "the rotational stage (every centre fixed)", help);
  }
  for (const auto& [key, help] :
       {std::pair<std::string_view, std::string>{
            "sun_support",
            "k_s, the sun's support stiffness on x and on y of the carrier's axes (0: it "
            "floats; the planar stage)"},
        {"ring_support", "k_r, the ring's support stiffness on x and on y (the planar stage)"},
        {"carrier_support",
         "k_c, the carrier's support stiffness on x and on y (the planar stage)"}}) {
    quantity("stage", key, Dimension::stiffness, "N/m", {closed(0.0), closed(1e15), {}},
             "the rotational stage (every centre fixed)", help);
  }
  quantity("stage", "planet_bearing", Dimension::stiffness, "N/m", {open(0.0), closed(1e15), {}},
           "the rotational stage (every centre fixed)",
           "k_p, each planet bearing's stiffness, radial and tangential, between the planet "
           "(of planet_mass) and its pin on the carrier (the planar stage)");
  // Viscous dampers in parallel with the supports and bearings (optional with the planar stage's
  // keys, each 0 when absent), in the range of a body's bearings' dampers.
  for (const auto& [key, help] :
       {std::pair<std::string_view, std::string>{
            "sun_support_damping",
            "c_s, the damper in parallel with the sun's support, on x and on y (the planar stage)"},
        {"ring_support_damping",
         "c_r, the damper in parallel with the ring's support, on x and on y (the planar stage)"},
        {"carrier_support_damping",
         "c_c, the damper in parallel with the carrier's support, on x and on y (the planar "
         "stage)"},
        {"planet_bearing_damping",
         "c_p, the damper in parallel with each planet's bearing, radial and tangential (the "
         "planar stage)"}}) {
    quantity("stage", key, Dimension::damping, "N*s/m", bearing_damping_range(), "0", help);
  }
  quantity("stage", "input_speed", Dimension::angular_velocity, "rad/s",
           {closed(-1e5), closed(1e5), {}}, "0",
           "the input member's speed at t = 0 (the sun's, or the ring's when the sun is held); "
           "every body starts at angle 0 at the Willis speeds");
  for (const std::string_view key : {"sun_torque", "ring_torque", "carrier_torque"}) {
    quantity("stage", key, Dimension::torque, "N*m", {}, "0",
             "a constant torque on the member, counter-clockwise positive; or a table of "
             "[torque1]'s keys (with kind = \"drag\", [torque2]'s), as [[bodies]] torque: a "
             "driver at input_speed, a speed controller, a motor, a drag");
  }
  // A stage file's [[faults]]: the member whose tooth it is, in place of the pair's gear; the
  // other keys are [[faults]]'s. Up to 5 planets, as stage.planets.
  Field& member = row("faults", "member", FieldKind::choice, true,
                      "in a stage file, the member whose tooth is faulted (in place of gear); its "
                      "tooth in the stage's count, 0 ... Z - 1 of that member (docs/planetary.md, "
                      "Faults on a stage's members); a ring tooth can only be missing");
  // The codes are the reader's: 0 the sun, n planet n, 6 the ring.
  member.choices = {
      {"sun", 0, "a sun tooth: every sun-planet mesh it passes through", true},
      {"planet1", 1, "a tooth of planet 1: its sun mesh (missing: both meshes)", true},
      {"planet2", 2, "a tooth of planet 2", true},
      {"planet3", 3, "a tooth of planet 3", true},
      {"planet4", 4, "a tooth of planet 4", true},
      {"planet5", 5, "a tooth of planet 5", true},
      {"ring", 6, "a ring tooth, missing: every ring-planet mesh", true}};
  return rows;
}

}  // namespace

const std::vector<Field>& train_schema() {
  static const std::vector<Field> rows = make_train_schema();
  return rows;
}

const Field* find_train_field(std::string_view section_dot_key) {
  for (const Field& field : train_schema()) {
    if (field.name() == section_dot_key) return &field;
  }
  return nullptr;
}

void check_train_value(std::string_view section_dot_key, double value, std::string_view name) {
  const Field* row = find_train_field(section_dot_key);
  if (row == nullptr) {
    throw std::logic_error("check_train_value: no row " + std::string(section_dot_key));
  }
  check_value(*row, value, name, format_number(value));
}

}  // namespace gearimpact
