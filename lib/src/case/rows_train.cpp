// The rows of a train file (train_schema): plain Fields without a slot of SimulationCase.
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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
  row("meshes", "name", FieldKind::text, true, "the mesh's name, one no other mesh has")
      .range.note = no_dot;
  row("meshes", "body_a", FieldKind::text, true,
      "the name of the body that is the pair's gear 1 (its pinion: [gears] teeth1, faults' gear "
      "= \"pinion\")");
  row("meshes", "body_b", FieldKind::text, true,
      "the name of the body that is the pair's gear 2 (teeth2, gear = \"wheel\"); it turns "
      "forward when body_a does");
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

}  // namespace gearimpact
