// A train file (docs/case-files.md, A gear train): [[bodies]], [[meshes]] and [[shafts]] read
// into a GearTrain, --set written into its tables first; a two-gear case file is read as the
// train of its pair.
#include <algorithm>
#include <array>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <toml.hpp>
#include <utility>
#include <vector>

#include "case_reader.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planetary_train.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/io/case_file.hpp"
#include "toml_values.hpp"

namespace gearimpact {

using namespace case_reader;

namespace {

// ---- A train file (docs/case-files.md, A gear train) ----

// What makes a case file a train's: its [[bodies]].
bool has_bodies(const toml::value& root) {
  return root.is_table() && root.as_table().count("bodies") > 0;
}

std::string train_key_list(std::string_view section) {
  std::string names;
  for (const Field& field : train_schema()) {
    if (field.section == section) names += (names.empty() ? "" : ", ") + std::string(field.key);
  }
  return names;
}

// The tables of the array `key` ([[bodies]], ...): a problem for anything else.
std::vector<const toml::value*> array_of_tables(const Reader& reader, const toml::value& root,
                                                const std::string& key,
                                                std::vector<Problem>& problems) {
  std::vector<const toml::value*> tables;
  const auto found = root.as_table().find(key);
  if (found == root.as_table().end()) return tables;
  const toml::value& list = found->second;
  if (!list.is_array()) {
    problems.push_back(reader.problem(key, &list,
                                      key + " = " + toml_written(list) + " is " +
                                          toml_type_name(list) +
                                          ", not an array of tables: write "
                                          "one [[" +
                                          key + "]] table each, with keys " + train_key_list(key)));
    return tables;
  }
  for (std::size_t i = 0; i < list.as_array().size(); ++i) {
    const toml::value& table = list.as_array()[i];
    if (!table.is_table()) {
      const std::string name = key + "[" + std::to_string(i) + "]";
      problems.push_back(reader.problem(name, &table,
                                        name + " = " + toml_written(table) + " is " +
                                            toml_type_name(table) + ", not a [[" + key +
                                            "]] table"));
      continue;
    }
    tables.push_back(&table);
  }
  return tables;
}

// One [[bodies]], [[meshes]] or [[shafts]] table: its keys read by the rows of
// train_schema() of `section`, problems named `label`.key (bodies.idler.inertia).
class TrainTable {
 public:
  TrainTable(const Reader& reader, const toml::value& table, std::string_view section,
             std::vector<Problem>& problems)
      : reader_(reader), table_(table), section_(section), problems_(problems) {}

  const toml::value* find(std::string_view key) const {
    const auto& entries = table_.as_table();
    const auto found = entries.find(std::string(key));
    return found == entries.end() ? nullptr : &found->second;
  }

  // The table's name (its `name` key), or "" with a problem named `fallback`.name.
  std::string name(const std::string& fallback, const std::vector<std::string>& taken) {
    const std::string field = fallback + ".name";
    const toml::value* value = find("name");
    if (value == nullptr) {
      problems_.push_back(reader_.problem(
          field, &table_,
          field + " is missing (required: " +
              allowed_text(*find_train_field(std::string(section_) + ".name")) + ")"));
      return {};
    }
    // The row's rule, and no dot: a name addresses its table's keys.
    const Field& row = *find_train_field(std::string(section_) + ".name");
    bool valid = value->is_string() && !value->as_string().str.empty() &&
                 value->as_string().str.find('.') == std::string::npos;
    try {
      if (valid) check_text(row, value->as_string().str, field);
    } catch (const InputError&) {
      valid = false;
    }
    if (!valid) {
      problems_.push_back(reader_.problem(
          field, value,
          field + " = " + toml_written(*value) + " is not a name: " + allowed_text(row)));
      return {};
    }
    const std::string& text = value->as_string().str;
    if (std::find(taken.begin(), taken.end(), text) != taken.end()) {
      problems_.push_back(reader_.problem(field, value,
                                          field + " = " + toml_written(*value) +
                                              " names another [[" + std::string(section_) +
                                              "]] too; each has its own"));
      return {};
    }
    return text;
  }

  // Problems for the keys outside `known` and the rows of the section.
  void refuse_unknown(const std::string& label, const std::vector<std::string>& known,
                      const std::string& keys_text) {
    for (const auto& [key, value] : table_.as_table()) {
      if (find_train_field(std::string(section_) + "." + key) != nullptr) continue;
      if (std::find(known.begin(), known.end(), key) != known.end()) continue;
      problems_.push_back(reader_.problem(label + "." + key, &value,
                                          "unknown key " + label + "." + key + "; " + keys_text));
    }
  }

  // A quantity row's value in SI, or nothing (absent or refused: a problem).
  std::optional<double> quantity(const std::string& label, std::string_view key) {
    const toml::value* value = find(key);
    const Field& row = *find_train_field(std::string(section_) + "." + std::string(key));
    if (value == nullptr) {
      if (row.required) {
        const std::string field = label + "." + std::string(key);
        problems_.push_back(reader_.problem(
            field, &table_, field + " is missing (required: " + expected_of(row) + ")"));
      }
      return std::nullopt;
    }
    Field named = row;
    named.section = label;
    try {
      return read_value(reader_, named, *value);
    } catch (const CaseFileError& e) {
      problems_.insert(problems_.end(), e.problems().begin(), e.problems().end());
      return std::nullopt;
    }
  }

  // A list row's values in SI, or nothing (absent or refused: a problem).
  std::optional<std::vector<double>> list(const std::string& label, std::string_view key) {
    const toml::value* value = find(key);
    if (value == nullptr) return std::nullopt;
    Field named = *find_train_field(std::string(section_) + "." + std::string(key));
    named.section = label;
    try {
      return read_list(reader_, named, *value);
    } catch (const CaseFileError& e) {
      problems_.insert(problems_.end(), e.problems().begin(), e.problems().end());
      return std::nullopt;
    }
  }

  // The body a body_a/body_b key names, or -1 with a problem listing the bodies.
  int body(const std::string& label, std::string_view key, const std::vector<std::string>& bodies) {
    const std::string field = label + "." + std::string(key);
    const toml::value* value = find(key);
    std::string list;
    for (const std::string& b : bodies) list += (list.empty() ? "\"" : ", \"") + b + "\"";
    if (value == nullptr) {
      problems_.push_back(reader_.problem(
          field, &table_, field + " is missing (required: the name of a body: " + list + ")"));
      return -1;
    }
    const auto found = value->is_string()
                           ? std::find(bodies.begin(), bodies.end(), value->as_string().str)
                           : bodies.end();
    if (found == bodies.end()) {
      problems_.push_back(reader_.problem(
          field, value,
          field + " = " + toml_written(*value) + " names no body; the bodies are " + list));
      return -1;
    }
    return static_cast<int>(found - bodies.begin());
  }

 private:
  const Reader& reader_;
  const toml::value& table_;
  std::string_view section_;
  std::vector<Problem>& problems_;
};

// The sub-tables a mesh may give over the file's pair sections, and [[meshes.faults]].
constexpr std::array<std::string_view, 4> kMeshPairSections{"gears", "model", "modifications",
                                                            "bearings"};

// A problem of a mesh's pair under the mesh's name: meshes.NAME.gears.backlash. Problems of keys
// that are the train's (integrator.*, name) keep their names.
Problem under_mesh(const Problem& problem, const std::string& prefix) {
  const std::string section = problem.field.substr(0, problem.field.find_first_of(".["));
  const bool of_pair = section == "faults" ||
                       std::find(kMeshPairSections.begin(), kMeshPairSections.end(), section) !=
                           kMeshPairSections.end();
  if (!of_pair) return problem;
  Problem p = problem;
  p.field = prefix + problem.field;
  if (p.message.rfind(problem.field, 0) == 0) {
    p.message = prefix + p.message;
  } else {
    p.message = prefix.substr(0, prefix.size() - 1) + ": " + p.message;
  }
  return p;
}

// A body's torque written as a table: the keys of [torque1] (with kind = "drag", of [torque2],
// the loose gear's section that has it), read by those sections' rows beside a mesh's pair that
// read without a problem (`pair`), the body's w standing for initial.w1 (a driver's speed at
// t = 0 is checked against it). Problems are named under the body, `label`.torque.KEY (and
// `label`.w).
Torque read_body_torque(const Reader& reader, const toml::value& pair, const toml::value& torque,
                        const toml::value* w, const std::string& label, std::string_view file_name,
                        std::vector<Problem>& problems, const std::string& torque_name = {},
                        const std::string& w_name = {}) {
  const auto kind = torque.as_table().find("kind");
  const bool drag = kind != torque.as_table().end() && kind->second.is_string() &&
                    kind->second.as_string().str == "drag";
  const std::string section = drag ? "torque2" : "torque1";
  toml::value probe = pair;
  probe.as_table()[section] = torque;
  if (!drag && w != nullptr) probe.as_table()["initial"] = toml::table{{"w1", *w}};
  try {
    const SimulationCase c = read_case(reader, probe, file_name, CaseFileKind::pair);
    return drag ? c.torque2 : c.torque1;
  } catch (const CaseFileError& e) {
    // The section's names in the texts, the body's: [torque1] -> bodies.NAME.torque.
    const std::string torque_key = torque_name.empty() ? label + ".torque" : torque_name;
    const std::string w_key = w_name.empty() ? label + ".w" : w_name;
    const std::vector<std::pair<std::string, std::string>> names{{"[" + section + "]", torque_key},
                                                                 {section + ".", torque_key + "."},
                                                                 {"initial.w1", w_key}};
    const auto rename = [&](std::string text) {
      for (const auto& [from, to] : names) {
        for (std::size_t at = text.find(from); at != std::string::npos;
             at = text.find(from, at + to.size())) {
          text.replace(at, from.size(), to);
        }
      }
      return text;
    };
    for (const Problem& problem : e.problems()) {
      const bool own = problem.field.rfind(section + ".", 0) == 0 || problem.field == "initial.w1";
      Problem p = problem;
      if (!own) {
        // A relation of the torque with the pair's keys: said under the body.
        p.message = label + ": " + p.message;
        problems.push_back(std::move(p));
        continue;
      }
      p.field = rename(p.field);
      p.message = rename(p.message);
      p.allowed = rename(p.allowed);
      p.fix = rename(p.fix);
      p.reason = rename(p.reason);
      problems.push_back(std::move(p));
    }
  }
  return Torque{};
}

// A body's `bearings` table (`label`: bodies.NAME.bearings) by the rows of
// train_schema()'s bodies.bearings; nothing with a problem.
std::optional<GearBearing> read_body_bearings(const Reader& reader, const toml::value& value,
                                              const std::string& label,
                                              std::vector<Problem>& problems) {
  if (!value.is_table()) {
    problems.push_back(reader.problem(label, &value,
                                      label + " = " + toml_written(value) + " is " +
                                          toml_type_name(value) +
                                          ", not a table: write bearings = { stiffness_x = ..., "
                                          "mass = ... } (keys " +
                                          train_key_list("bodies.bearings") + ")"));
    return std::nullopt;
  }
  const std::size_t before = problems.size();
  TrainTable table(reader, value, "bodies.bearings", problems);
  table.refuse_unknown(label, {},
                       "the keys of a body's bearings are " + train_key_list("bodies.bearings"));
  GearBearing b;
  b.stiffness_x_n_per_m = table.quantity(label, "stiffness_x").value_or(0.0);
  b.stiffness_y_n_per_m = table.quantity(label, "stiffness_y");
  b.damping_x_n_s_per_m = table.quantity(label, "damping_x").value_or(0.0);
  b.damping_y_n_s_per_m = table.quantity(label, "damping_y");
  b.mass_kg = table.quantity(label, "mass");
  if (problems.size() != before) return std::nullopt;
  return b;
}

// The file's [sensor] by the rows of train_schema()'s sensor: its body named
// among the train's bodies (the dynamics checks that it has bearings).
void read_sensor(const Reader& reader, const toml::value& value,
                 const std::vector<std::string>& bodies, GearTrain& train,
                 std::vector<Problem>& problems) {
  if (!value.is_table()) {
    problems.push_back(reader.problem("sensor", &value,
                                      "sensor = " + toml_written(value) + " is " +
                                          toml_type_name(value) + ", not a table: write [sensor]"));
    return;
  }
  TrainTable table(reader, value, "sensor", problems);
  table.refuse_unknown("sensor", {}, "the keys of [sensor] are " + train_key_list("sensor"));
  if (table.find("body") == nullptr) {
    problems.push_back(reader.problem("sensor.body", &value,
                                      "sensor.body is missing (required in [sensor]: the name of "
                                      "a body on bearings)"));
    return;
  }
  train.sensor_body = table.body("sensor", "body", bodies);
  train.sensor_angle_rad = table.quantity("sensor", "angle").value_or(pi / 2.0);
}

// The body of the file's [tacho] (train_schema()'s tacho.body) among the train's bodies; the
// pair's shaft refused, as the body names what it named.
void read_tacho(const Reader& reader, const toml::value& value,
                const std::vector<std::string>& bodies, GearTrain& train,
                std::vector<Problem>& problems) {
  TrainTable table(reader, value, "tacho", problems);
  if (const toml::value* shaft = table.find("shaft"); shaft != nullptr) {
    problems.push_back(reader.problem(
        "tacho.shaft", shaft,
        "tacho.shaft is not read in a train file: a train's tacho names its body (tacho.body = "
        "NAME)"));
  }
  // Missing or naming no body, refused with the bodies' names.
  train.tacho_body = table.body("tacho", "body", bodies);
}

// ---- --set on a train file: KEY=VALUE written into the file's tables before they are read ----

// The TOML value a case file gives `row` for the text of a --set, checked by the row (InputError
// naming `name`): a quantity as a string in SI units that reads back to the same double, a
// number, an integer, a choice by its name.
toml::value toml_of(const Field& row, std::string_view text, const std::string& name) {
  if (is_list(row.kind)) {
    // The list as parse_list reads it (["0 deg", "120 deg"] as the file writes it, or bare),
    // each element checked and named NAME[i]; written back as the file's array, a quantity in
    // SI units that reads back to the same double.
    toml::array values;
    for (const double x : parse_list(row, text, name)) {
      if (row.kind == FieldKind::number_list) {
        values.push_back(toml::value(x));
      } else {
        values.push_back(toml::value(
            format_quantity(x, row.dimension, units_of(row.dimension).begin()->symbol)));
      }
    }
    return toml::value(std::move(values));
  }
  if (row.kind == FieldKind::text) {
    check_text(row, std::string(text), name);
    return toml::value(std::string(text));
  }
  const double x = parse_value(row, text, name);
  switch (row.kind) {
    case FieldKind::quantity:
      return toml::value(
          format_quantity(x, row.dimension, units_of(row.dimension).begin()->symbol));
    case FieldKind::number:
      return toml::value(x);
    case FieldKind::integer:
      return toml::value(static_cast<toml::integer>(x));
    default:
      for (const ChoiceName& c : row.choices) {
        if (c.has_text && c.code == x) return toml::value(std::string(c.name));
      }
      throw InputError(name, std::string(text), allowed_text(row));
  }
}

// The [[key]] table named `name` in `root`, or InputError naming `field` with the names there are.
toml::value& named_table(toml::value& root, const std::string& key, const std::string& name,
                         const std::string& field) {
  std::string names;
  auto found = root.as_table().find(key);
  if (found != root.as_table().end() && found->second.is_array()) {
    for (toml::value& table : found->second.as_array()) {
      if (!table.is_table()) continue;
      const auto n = table.as_table().find("name");
      if (n == table.as_table().end() || !n->second.is_string()) continue;
      if (n->second.as_string().str == name) return table;
      names += (names.empty() ? "\"" : ", \"") + n->second.as_string().str + "\"";
    }
  }
  throw InputError(field, "\"" + name + "\"",
                   "the name of one of the file's [[" + key +
                       "]]: " + (names.empty() ? std::string("it has none") : names));
}

// One `KEY=VALUE` of --set into the file's tables: bodies.NAME.KEY, meshes.NAME.KEY (body_a,
// body_b), meshes.NAME.SECTION.KEY (a mesh's pair key), or SECTION.KEY / KEY of the file
// itself (a train's integrator, every mesh's default). InputError names KEY.
void set_in_file(toml::value& root, const std::string& assignment) {
  const std::size_t equals = assignment.find('=');
  if (equals == std::string::npos) {
    throw InputError("--set", assignment, "KEY=VALUE, e.g. bodies.idler.inertia=2e-4 kg*m^2");
  }
  const std::string key = assignment.substr(0, equals);
  const std::string_view text = std::string_view(assignment).substr(equals + 1);
  const bool train = has_bodies(root);
  for (const std::string table_key : {"bodies", "meshes"}) {
    if (key.rfind(table_key + ".", 0) != 0) continue;
    if (!train) {
      throw InputError(key, std::string(text), "a key of the case file: it has no [[bodies]]");
    }
    const std::size_t name_end = key.find('.', table_key.size() + 1);
    if (name_end == std::string::npos) {
      throw InputError(key, std::string(text), table_key + ".NAME.KEY");
    }
    const std::string name = key.substr(table_key.size() + 1, name_end - table_key.size() - 1);
    const std::string rest = key.substr(name_end + 1);
    toml::value& table = named_table(root, table_key, name, key);
    if (const Field* row = find_train_field(table_key + "." + rest);
        row != nullptr && rest != "name") {
      table.as_table()[rest] = toml_of(*row, text, key);
      return;
    }
    const std::size_t dot = rest.find('.');
    const Field* row = table_key == "meshes" ? find_field(rest) : nullptr;
    if (row == nullptr || dot == std::string::npos ||
        std::find(kMeshPairSections.begin(), kMeshPairSections.end(), rest.substr(0, dot)) ==
            kMeshPairSections.end()) {
      throw InputError(key, std::string(text),
                       table_key == "bodies"
                           ? "bodies.NAME.KEY with KEY one of inertia, torque, theta, w"
                           : "meshes.NAME.body_a, body_b, or meshes.NAME.SECTION.KEY with "
                             "SECTION.KEY a key of [gears], [model], [modifications] or "
                             "[bearings]");
    }
    toml::value& section = table.as_table()[rest.substr(0, dot)];
    if (!section.is_table()) section = toml::table{};
    section.as_table()[rest.substr(dot + 1)] = toml_of(*row, text, key);
    return;
  }
  if (key.rfind("stage.", 0) == 0) {
    const Field* stage_row = find_train_field(key);
    if (stage_row == nullptr) {
      throw InputError(key, std::string(text),
                       "stage.KEY with KEY one of " + train_key_list("stage"));
    }
    toml::value& section = root.as_table()["stage"];
    if (!section.is_table()) section = toml::table{};
    section.as_table()[std::string(stage_row->key)] = toml_of(*stage_row, text, key);
    return;
  }
  // A train's own sections beside the pair's: [sensor], and [tacho]'s body.
  if (const Field* train_row = find_train_field(key);
      train && train_row != nullptr &&
      (train_row->section == "sensor" || train_row->section == "tacho")) {
    toml::value& section = root.as_table()[std::string(train_row->section)];
    if (!section.is_table()) section = toml::table{};
    section.as_table()[std::string(train_row->key)] = toml_of(*train_row, text, key);
    return;
  }
  const Field* row = find_field(key);
  if (row == nullptr) throw InputError(key, std::string(text), "a key of the case schema");
  if (row->section.empty()) {
    root.as_table()[std::string(row->key)] = toml_of(*row, text, key);
    return;
  }
  toml::value& section = root.as_table()[std::string(row->section)];
  if (!section.is_table()) section = toml::table{};
  section.as_table()[std::string(row->key)] = toml_of(*row, text, key);
}

GearTrain read_train(const Reader& reader, const toml::value& root, std::string_view file_name) {
  std::vector<Problem> problems;
  // The train's keys and every mesh's defaults: the file without its arrays of the train.
  toml::value defaults = toml::table{};
  for (const auto& [key, value] : root.as_table()) {
    if (key == "bodies" || key == "meshes" || key == "sensor" ||
        (key == "shafts" && value.is_array())) {
      continue;
    }
    if (key == "tacho" && value.is_table()) {
      // Its keys but body and shaft are the two-gear [tacho]'s, read by their rows with each
      // mesh's pair; its body is the train's (read_tacho).
      toml::value rest = value;
      rest.as_table().erase("body");
      rest.as_table().erase("shaft");
      defaults.as_table()[key] = rest;
      continue;
    }
    const Field* field = find_field(key);
    const bool top_level_key = field != nullptr && field->section.empty();
    const bool pair = std::find(kMeshPairSections.begin(), kMeshPairSections.end(), key) !=
                      kMeshPairSections.end();
    if (top_level_key || pair || key == "integrator" || key == "drive" || key == "faults") {
      defaults.as_table()[key] = value;
      continue;
    }
    std::string why;
    if (key == "torque1" || key == "torque2" || key == "initial") {
      why = "each body has its own torque, theta and w (bodies.NAME.torque, ...)";
    } else if (key == "shafts") {
      why = "a train's shafts are [[shafts]] tables joining two bodies";
    } else {
      why = "it is not a key of a train";
    }
    problems.push_back(reader.problem(
        key, &value,
        "[" + key + "] is not read in a train file: " + why +
            "; a train file has name, [integrator], [drive], the pair sections [gears], [model], "
            "[modifications], [bearings] and [[faults]] (every mesh's defaults), and [[bodies]], "
            "[[meshes]], [[shafts]]"));
  }
  // A run needs these as a run file does.
  for (const Field& field : case_schema()) {
    if (field.section != "integrator" || !field.required || field.only_when) continue;
    const auto section = defaults.as_table().find("integrator");
    const bool given = section != defaults.as_table().end() && section->second.is_table() &&
                       section->second.as_table().count(std::string(field.key)) > 0;
    if (!given) {
      problems.push_back(reader.problem(
          field.name(), section != defaults.as_table().end() ? &section->second : nullptr,
          field.name() + " is missing (required: " + expected_of(field) + ")"));
    }
  }

  GearTrain train;
  // The bodies whose torque is a table: index, table, w, label.
  struct TorqueTable {
    std::size_t body;
    const toml::value* torque;
    const toml::value* w;
    std::string label;
  };
  std::vector<TorqueTable> torque_tables;
  // The first mesh's pair that read without a problem: the sections a torque table is read beside.
  std::optional<toml::value> read_pair;
  std::vector<std::string> body_names;
  std::vector<std::optional<double>> inertias;
  const std::vector<const toml::value*> bodies = array_of_tables(reader, root, "bodies", problems);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    TrainTable table(reader, *bodies[i], "bodies", problems);
    const std::string name = table.name("bodies[" + std::to_string(i) + "]", body_names);
    const std::string label = name.empty() ? "bodies[" + std::to_string(i) + "]" : "bodies." + name;
    table.refuse_unknown(
        label, {"bearings"},
        "the keys of [[bodies]] are " + train_key_list("bodies") + " and the sub-table bearings");
    TrainBody body;
    body.name = name;
    if (const toml::value* bearings = table.find("bearings"); bearings != nullptr) {
      body.bearing = read_body_bearings(reader, *bearings, label + ".bearings", problems);
    }
    inertias.push_back(table.quantity(label, "inertia"));
    if (const toml::value* torque = table.find("torque"); torque != nullptr && torque->is_table()) {
      // Read once a mesh's pair has read (below).
      torque_tables.push_back({i, torque, table.find("w"), label});
    } else {
      body.torque.kind = Torque::Kind::constant;
      body.torque.constant_n_m = table.quantity(label, "torque").value_or(0.0);
    }
    body.theta_rad = table.quantity(label, "theta").value_or(0.0);
    body.w_rad_per_s = table.quantity(label, "w").value_or(0.0);
    body_names.push_back(name);
    train.bodies.push_back(std::move(body));
  }
  if (bodies.empty() && problems.empty()) {
    problems.push_back(reader.problem("bodies", &root.as_table().at("bodies"),
                                      "a train file has at least two [[bodies]]"));
  }

  const std::vector<const toml::value*> meshes = array_of_tables(reader, root, "meshes", problems);
  if (meshes.empty() && root.as_table().count("meshes") == 0) {
    problems.push_back(reader.problem("meshes", nullptr,
                                      "[[meshes]] is missing: a train file has at least one "
                                      "[[meshes]] table, with keys " +
                                          train_key_list("meshes")));
  }
  std::vector<std::string> mesh_names;
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    TrainTable table(reader, *meshes[k], "meshes", problems);
    const std::string name = table.name("meshes[" + std::to_string(k) + "]", mesh_names);
    mesh_names.push_back(name);
    const std::string label = name.empty() ? "meshes[" + std::to_string(k) + "]" : "meshes." + name;
    table.refuse_unknown(label, {"gears", "model", "modifications", "bearings", "faults"},
                         "a mesh has " + train_key_list("meshes") +
                             " and the sub-tables gears, model, modifications, bearings and "
                             "[[meshes.faults]]");
    TrainMesh mesh;
    mesh.name = name;
    mesh.body_a = table.body(label, "body_a", body_names);
    mesh.body_b = table.body(label, "body_b", body_names);
    mesh.centre_angle_rad = table.quantity(label, "centre_angle").value_or(0.0);
    // The pair: the file's pair sections with the mesh's keys over them.
    toml::value pair = defaults;
    bool tables_ok = true;
    for (std::string_view section : kMeshPairSections) {
      const toml::value* own = table.find(section);
      if (own == nullptr) continue;
      const std::string key(section);
      if (!own->is_table()) {
        problems.push_back(reader.problem(label + "." + key, own,
                                          label + "." + key + " = " + toml_written(*own) + " is " +
                                              toml_type_name(*own) +
                                              ", not a table: write [meshes." + key + "]"));
        tables_ok = false;
        continue;
      }
      auto& merged = pair.as_table()[key];
      if (!merged.is_table()) merged = toml::table{};
      for (const auto& [entry, value] : own->as_table()) merged.as_table()[entry] = value;
    }
    if (const toml::value* faults = table.find("faults"); faults != nullptr) {
      pair.as_table()["faults"] = *faults;
    }
    if (!tables_ok) continue;
    try {
      mesh.pair = read_case(reader, pair, file_name, CaseFileKind::pair);
      mesh.pair.run_keys_absent.clear();
    } catch (const CaseFileError& e) {
      for (const Problem& p : e.problems()) {
        Problem named = under_mesh(p, label + ".");
        const bool seen = std::any_of(problems.begin(), problems.end(), [&](const Problem& q) {
          return q.field == named.field && q.message == named.message && q.where == named.where;
        });
        if (!seen) problems.push_back(std::move(named));
      }
      continue;
    }
    if (!read_pair) read_pair = pair;
    train.integrator = mesh.pair.integrator;
    train.drive = mesh.pair.drive;
    // The tacho is the train's (read by its pair's rows): the pairs keep none, as their bearings.
    train.tacho = mesh.pair.tacho;
    mesh.pair.tacho = Tacho{};
    // A body's inertia defaults to its gear's disc in the first mesh that names it; a helical
    // gear's disc is that of the transverse section it runs as (pitch radius m_n z / (2 cos
    // beta)), as the two-gear run's; a helix angle out of range is the run's refusal.
    const GearPair& g = mesh.pair.gears;
    const bool helical = g.helix_angle_rad > 0.0 && g.helix_angle_rad <= pi / 4.0;
    const GearPair discs = helical ? transverse_pair(g) : g;
    for (const auto& [body, gear] : {std::pair{mesh.body_a, Gear::one}, {mesh.body_b, Gear::two}}) {
      if (body < 0) continue;
      const auto b = static_cast<std::size_t>(body);
      if (!inertias[b]) inertias[b] = moment_of_inertia(discs, gear);
    }
    train.meshes.push_back(std::move(mesh));
  }

  if (read_pair) {
    for (const TorqueTable& t : torque_tables) {
      train.bodies[t.body].torque =
          read_body_torque(reader, *read_pair, *t.torque, t.w, t.label, file_name, problems);
    }
  }

  std::vector<const toml::value*> shafts;
  if (const auto found = root.as_table().find("shafts");
      found != root.as_table().end() && found->second.is_array()) {
    shafts = array_of_tables(reader, root, "shafts", problems);
  }
  for (std::size_t i = 0; i < shafts.size(); ++i) {
    TrainTable table(reader, *shafts[i], "shafts", problems);
    const std::string label = "shafts[" + std::to_string(i) + "]";
    table.refuse_unknown(label, {}, "the keys of [[shafts]] are " + train_key_list("shafts"));
    TrainShaft shaft;
    const Field& kind_row = *find_train_field("shafts.kind");
    const toml::value* kind = table.find("kind");
    Field named = kind_row;
    named.section = label;
    std::optional<double> code;
    if (kind == nullptr) {
      problems.push_back(
          reader.problem(label + ".kind", shafts[i],
                         label + ".kind is missing (required: " + allowed_text(kind_row) + ")"));
    } else {
      try {
        code = read_value(reader, named, *kind);
      } catch (const CaseFileError& e) {
        problems.insert(problems.end(), e.problems().begin(), e.problems().end());
      }
    }
    shaft.body_a = table.body(label, "body_a", body_names);
    shaft.body_b = table.body(label, "body_b", body_names);
    // The codes of train_schema()'s shafts.kind: 0 rigid, 1 torsional.
    if (code && *code == 1.0) {
      shaft.kind = TrainShaft::Kind::torsional;
      shaft.stiffness_n_m_per_rad = table.quantity(label, "stiffness").value_or(0.0);
    } else if (const toml::value* stiffness = table.find("stiffness");
               code && stiffness != nullptr) {
      problems.push_back(reader.problem(label + ".stiffness", stiffness,
                                        label + ".stiffness is read only with kind = "
                                                "\"torsional\"; this shaft is rigid"));
    }
    train.shafts.push_back(shaft);
  }

  for (std::size_t i = 0; i < train.bodies.size(); ++i) {
    if (inertias[i]) {
      train.bodies[i].inertia_kg_m2 = *inertias[i];
    } else if (!train.bodies[i].name.empty() && mesh_names.size() == train.meshes.size()) {
      const std::string field = "bodies." + train.bodies[i].name + ".inertia";
      problems.push_back(reader.problem(field, bodies[i],
                                        field +
                                            " is missing (required for a body no mesh "
                                            "names: " +
                                            expected_of(*find_train_field("bodies.inertia")) +
                                            ")"));
    }
  }
  if (const auto sensor = root.as_table().find("sensor"); sensor != root.as_table().end()) {
    read_sensor(reader, sensor->second, body_names, train, problems);
  }
  if (const auto tacho = root.as_table().find("tacho");
      tacho != root.as_table().end() && tacho->second.is_table()) {
    read_tacho(reader, tacho->second, body_names, train, problems);
  }
  if (!problems.empty()) throw CaseFileError(reader.file(), std::move(problems));
  return train;
}

// What makes a case file a planetary stage's: its [stage].
bool has_stage(const toml::value& root) {
  return root.is_table() && root.as_table().count("stage") > 0;
}

// A stage file's [[faults]] (`list`): each table's member by train_schema()'s faults.member, its
// tooth checked against that member's count; a ring's tooth read here (missing only), a sun's or a
// planet's table given to the pair's reader in `pair_faults` with gear = "pinion" (the sun) or
// "wheel" (a planet), its index in the stage's list in `pair_fault_of`.
void read_stage_faults(const Reader& reader, const toml::value& list, const PlanetaryStage& stage,
                       std::vector<std::optional<StageFault>>& faults,
                       std::vector<std::size_t>& pair_fault_of, toml::value& pair_faults,
                       std::vector<Problem>& problems) {
  if (!list.is_array()) {
    problems.push_back(reader.problem(
        "faults", &list,
        "faults = " + toml_written(list) + " is " + toml_type_name(list) +
            ", not an array of tables: write one [[faults]] table per faulted tooth, with member"));
    return;
  }
  const Field& member_row = *find_train_field("faults.member");
  for (std::size_t i = 0; i < list.as_array().size(); ++i) {
    const toml::value& table = list.as_array()[i];
    const std::string name = "faults[" + std::to_string(i) + "]";
    faults.emplace_back();
    if (!table.is_table()) {
      problems.push_back(reader.problem(name, &table,
                                        name + " = " + toml_written(table) + " is " +
                                            toml_type_name(table) + ", not a [[faults]] table"));
      continue;
    }
    const auto& keys = table.as_table();
    if (const auto gear = keys.find("gear"); gear != keys.end()) {
      problems.push_back(reader.problem(
          name + ".gear", &gear->second,
          name + ".gear is not read in a stage file: member names the tooth's member (sun, "
                 "planet1 ... planetN, ring)"));
      continue;
    }
    Field named = member_row;
    named.section = name;
    const auto member = keys.find("member");
    if (member == keys.end()) {
      problems.push_back(
          reader.problem(named.name(), &table,
                         named.name() + " is missing (required: " + expected_of(named) + ")"));
      continue;
    }
    double code = 0.0;
    try {
      code = read_value(reader, named, member->second);
    } catch (const CaseFileError& e) {
      problems.insert(problems.end(), e.problems().begin(), e.problems().end());
      continue;
    }
    StageFault f;
    f.member = code == 0.0   ? FaultMember::sun
               : code == 6.0 ? FaultMember::ring
                             : FaultMember::planet;
    f.planet = static_cast<int>(code);
    if (f.member == FaultMember::planet && f.planet > stage.planets) {
      problems.push_back(reader.problem(
          named.name(), &member->second,
          named.name() + " = " + toml_written(member->second) + " names no planet of the stage: " +
              "sun, ring or planet1 ... planet" + std::to_string(stage.planets) +
              " (stage.planets = " + std::to_string(stage.planets) + ")"));
      continue;
    }
    const int teeth = f.member == FaultMember::sun      ? stage.teeth.sun
                      : f.member == FaultMember::planet ? stage.teeth.planet
                                                        : stage.teeth.ring;
    const char* count = f.member == FaultMember::sun      ? "stage.sun_teeth"
                        : f.member == FaultMember::planet ? "stage.planet_teeth"
                                                          : "stage.ring_teeth";
    const auto tooth = keys.find("tooth");
    if (tooth != keys.end() && tooth->second.is_integer() && teeth > 0 &&
        (tooth->second.as_integer() < 0 || tooth->second.as_integer() >= teeth)) {
      problems.push_back(reader.problem(
          name + ".tooth", &tooth->second,
          name + ".tooth = " + toml_written(tooth->second) +
              " is outside the allowed range: 0 ... " + std::to_string(teeth - 1) +
              ", the teeth of its member (" + count + " = " + std::to_string(teeth) + ")"));
      continue;
    }
    if (f.member != FaultMember::ring) {
      toml::value pair_table = table;
      pair_table.as_table().erase("member");
      pair_table.as_table()["gear"] =
          toml::value(f.member == FaultMember::sun ? "pinion" : "wheel");
      pair_faults.as_array().push_back(pair_table);
      pair_fault_of.push_back(i);
      faults.back() = f;
      continue;
    }
    // A ring tooth: missing, and nothing else to read (its meshes' ISO table has no profile).
    bool read = true;
    for (const auto& [key, value] : keys) {
      if (key == "member" || key == "tooth") continue;
      if (key == "kind" && value.is_string() && value.as_string().str == "missing") continue;
      read = false;
      problems.push_back(reader.problem(
          name + "." + key, &value,
          name + "." + key + " = " + toml_written(value) +
              (key == "kind" ? std::string(" is not a ring tooth's fault") : " is not read") +
              ": a ring tooth can only be missing (kind = \"missing\"; the ring meshes' ISO "
              "6336-1 table has no tooth profile for a crack, a spall or a chip)"));
    }
    for (const char* key : {"kind", "tooth"}) {
      if (keys.count(key) > 0) continue;
      read = false;
      problems.push_back(
          reader.problem(name + "." + key, &table,
                         name + "." + key + " is missing (required: " +
                             (std::string(key) == "kind"
                                  ? std::string("\"missing\" for a ring tooth")
                                  : std::string("an integer 0 ... ") + std::to_string(teeth - 1)) +
                             ")"));
    }
    if (!read) continue;
    if (!tooth->second.is_integer()) {
      problems.push_back(reader.problem(name + ".tooth", &tooth->second,
                                        name + ".tooth = " + toml_written(tooth->second) +
                                            " is not an integer: 0 ... " +
                                            std::to_string(teeth - 1)));
      continue;
    }
    f.tooth = static_cast<int>(tooth->second.as_integer());
    f.state.kind = ToothKind::missing;
    faults.back() = f;
  }
}

// A stage file: [stage] by the rows of train_schema() of "stage", the pair sections [gears] and
// [model] (the meshes' keys; the tooth counts are the stage's) and [integrator]. Every problem is
// collected before one CaseFileError.
PlanetaryStage read_stage(const Reader& reader, const toml::value& root,
                          std::string_view file_name) {
  std::vector<Problem> problems;
  toml::value pair = toml::table{};
  for (const auto& [key, value] : root.as_table()) {
    if (key == "stage") continue;
    const Field* field = find_field(key);
    const bool top_level_key = field != nullptr && field->section.empty();
    if (top_level_key || key == "gears" || key == "model" || key == "integrator") {
      pair.as_table()[key] = value;
      continue;
    }
    if (key == "faults") continue;  // read below, member by member
    // Modifications would land on every mesh alike, and the stage has no bearings (rotational
    // only).
    const bool not_yet = key == "modifications" || key == "bearings";
    problems.push_back(reader.problem(
        key, &value,
        "[" + key + "] is not read in a stage file" +
            (not_yet ? std::string(": modifications and bearings of a stage's members are not "
                                   "modelled yet")
                     : std::string()) +
            "; a stage file has name, [stage], [integrator], [gears] and [model] (every mesh's "
            "keys) and [[faults]] (with member)"));
  }
  const toml::value& stage_value = root.as_table().at("stage");
  if (!stage_value.is_table()) {
    problems.push_back(reader.problem(
        "stage", &stage_value,
        "stage = " + toml_written(stage_value) + " is " + toml_type_name(stage_value) +
            ", not a table: write [stage] with keys " + train_key_list("stage")));
    throw CaseFileError(reader.file(), std::move(problems));
  }
  TrainTable table(reader, stage_value, "stage", problems);
  table.refuse_unknown("stage", {}, "[stage] has " + train_key_list("stage"));
  // The tooth counts are the stage's: a pair's teeth1/teeth2 would say them twice.
  if (const auto gears = pair.as_table().find("gears");
      gears != pair.as_table().end() && gears->second.is_table()) {
    for (const std::string teeth : {"teeth1", "teeth2"}) {
      if (const auto t = gears->second.as_table().find(teeth);
          t != gears->second.as_table().end()) {
        problems.push_back(reader.problem("gears." + teeth, &t->second,
                                          "gears." + teeth +
                                              " is not read in a stage file: the tooth counts "
                                              "are stage.sun_teeth, planet_teeth, ring_teeth"));
      }
    }
  }
  for (const Field& field : case_schema()) {
    if (field.section != "integrator" || !field.required || field.only_when) continue;
    const auto section = pair.as_table().find("integrator");
    const bool given = section != pair.as_table().end() && section->second.is_table() &&
                       section->second.as_table().count(std::string(field.key)) > 0;
    if (!given) {
      problems.push_back(reader.problem(
          field.name(), section != pair.as_table().end() ? &section->second : nullptr,
          field.name() + " is missing (required: " + expected_of(field) + ")"));
    }
  }
  PlanetaryStage stage;
  const auto count = [&](std::string_view key) {
    return static_cast<int>(table.quantity("stage", key).value_or(0.0));
  };
  stage.teeth = {count("sun_teeth"), count("planet_teeth"), count("ring_teeth")};
  stage.planets = count("planets");
  // Unequal spacing: one angle per planet, the first 0 (planet 1 sets the carrier's axis), each
  // further on than the one before (two planets in one place, or out of order, refused); the
  // assembly condition and the tips' clearance are the geometry's (parse_stage).
  if (const std::optional<std::vector<double>> psi = table.list("stage", "planet_angles")) {
    const toml::value& written = *table.find("planet_angles");
    const auto n = static_cast<std::size_t>(stage.planets);
    const auto refuse = [&](std::size_t i, const std::string& allowed) {
      const std::string field = "stage.planet_angles[" + std::to_string(i) + "]";
      const toml::value& element = written.as_array()[i];
      Problem problem = range_problem(field, toml_written(element), allowed);
      problem.where = reader.where(&element);
      problems.push_back(std::move(problem));
    };
    if (stage.planets >= 1 && psi->size() != n) {
      Problem problem =
          range_problem("stage.planet_angles", std::to_string(psi->size()) + " angles",
                        "one angle per planet: stage.planets = " + std::to_string(n));
      problem.where = reader.where(&written);
      problems.push_back(std::move(problem));
    } else if (!psi->empty() && (*psi)[0] != 0.0) {
      refuse(0, "0 deg: planet 1's angle, from which the others are measured");
    } else {
      for (std::size_t i = 1; i < psi->size(); ++i) {
        if ((*psi)[i] == (*psi)[i - 1]) {
          refuse(i, "an angle other than stage.planet_angles[" + std::to_string(i - 1) +
                        "]'s: two planets in one place");
          break;
        }
        if ((*psi)[i] < (*psi)[i - 1]) {
          refuse(i, "an angle beyond stage.planet_angles[" + std::to_string(i - 1) +
                        "]'s: increasing angles in [0, 360) deg");
          break;
        }
      }
    }
    stage.planet_angles_rad = *psi;
  }
  // The codes of train_schema()'s stage.held: 0 ring, 1 carrier, 2 sun.
  const double held = table.quantity("stage", "held").value_or(0.0);
  stage.held = held == 1.0 ? HeldMember::carrier : held == 2.0 ? HeldMember::sun : HeldMember::ring;
  stage.sun_inertia_kg_m2 = table.quantity("stage", "sun_inertia").value_or(0.0);
  stage.ring_inertia_kg_m2 = table.quantity("stage", "ring_inertia").value_or(0.0);
  stage.carrier_inertia_kg_m2 = table.quantity("stage", "carrier_inertia").value_or(0.0);
  stage.planet_inertia_kg_m2 = table.quantity("stage", "planet_inertia").value_or(0.0);
  stage.planet_mass_kg = table.quantity("stage", "planet_mass");
  // The planar stage: any of its keys asks for it, and then each is required (planet_mass too).
  {
    static constexpr std::array<std::string_view, 7> kPlanar{
        "sun_mass",     "ring_mass",       "carrier_mass",  "sun_support",
        "ring_support", "carrier_support", "planet_bearing"};
    std::array<std::optional<double>, 7> value;
    bool any = false;
    for (std::size_t i = 0; i < kPlanar.size(); ++i) {
      value[i] = table.quantity("stage", kPlanar[i]);
      any = any || table.find(kPlanar[i]) != nullptr;
    }
    static constexpr std::string_view kPlanarText =
        "sun_mass, ring_mass, carrier_mass, sun_support, ring_support, carrier_support, "
        "planet_bearing and planet_mass";
    // The dampers in parallel with the supports: optional with the planar stage, 0 when absent.
    static constexpr std::array<std::pair<std::string_view, double StageSupports::*>, 4> kDampers{
        {{"sun_support_damping", &StageSupports::sun_support_damping_n_s_per_m},
         {"ring_support_damping", &StageSupports::ring_support_damping_n_s_per_m},
         {"carrier_support_damping", &StageSupports::carrier_support_damping_n_s_per_m},
         {"planet_bearing_damping", &StageSupports::planet_bearing_damping_n_s_per_m}}};
    if (any) {
      const auto missing = [&](std::string_view key) {
        const std::string name = "stage." + std::string(key);
        problems.push_back(
            reader.problem(name, nullptr,
                           name + " is missing (required with the planar stage's keys: " +
                               std::string(kPlanarText) + ")"));
      };
      // A key written with a bad value is its own problem already.
      for (std::size_t i = 0; i < kPlanar.size(); ++i) {
        if (table.find(kPlanar[i]) == nullptr) missing(kPlanar[i]);
      }
      if (table.find("planet_mass") == nullptr) missing("planet_mass");
      StageSupports k;
      k.sun_mass_kg = value[0].value_or(0.0);
      k.ring_mass_kg = value[1].value_or(0.0);
      k.carrier_mass_kg = value[2].value_or(0.0);
      k.sun_support_n_per_m = value[3].value_or(0.0);
      k.ring_support_n_per_m = value[4].value_or(0.0);
      k.carrier_support_n_per_m = value[5].value_or(0.0);
      k.planet_bearing_n_per_m = value[6].value_or(0.0);
      for (const auto& [key, field] : kDampers) {
        k.*field = table.quantity("stage", key).value_or(0.0);
      }
      stage.supports = k;
    } else {
      // A damper needs the support it is in parallel with.
      for (const auto& damper : kDampers) {
        if (table.find(damper.first) == nullptr) continue;
        const std::string name = "stage." + std::string(damper.first);
        problems.push_back(reader.problem(name, nullptr,
                                          name + " needs the planar stage's keys (" +
                                              std::string(kPlanarText) +
                                              "): its damper is in parallel with a support"));
      }
    }
  }
  stage.input_speed_rad_per_s = table.quantity("stage", "input_speed").value_or(0.0);
  // [[faults]]: each table's member (faults.member); a sun's or a planet's tooth is read by the
  // pair's [[faults]] rows as the sun meshes' pinion or wheel, a ring's as missing only.
  std::vector<std::optional<StageFault>> faults;
  std::vector<std::size_t> pair_fault_of;  // the stage's fault of each pair fault
  toml::value pair_faults = toml::array{};
  if (const auto found = root.as_table().find("faults"); found != root.as_table().end()) {
    read_stage_faults(reader, found->second, stage, faults, pair_fault_of, pair_faults, problems);
  }
  // The meshes' pair: the file's pair sections with the sun-planet tooth counts (the stage's).
  std::optional<toml::value> read_pair;
  {
    toml::value probe = pair;
    if (!pair_faults.as_array().empty()) probe.as_table()["faults"] = pair_faults;
    toml::value& gears = probe.as_table()["gears"];
    if (!gears.is_table()) gears = toml::table{};
    gears.as_table()["teeth1"] =
        toml::value(static_cast<toml::integer>(stage.teeth.sun > 0 ? stage.teeth.sun : 20));
    gears.as_table()["teeth2"] =
        toml::value(static_cast<toml::integer>(stage.teeth.planet > 0 ? stage.teeth.planet : 20));
    try {
      stage.mesh = read_case(reader, probe, file_name, CaseFileKind::pair);
      stage.mesh.run_keys_absent.clear();
      stage.integrator = stage.mesh.integrator;
      for (std::size_t k = 0; k < stage.mesh.faults.size(); ++k) {
        std::optional<StageFault>& f = faults[pair_fault_of[k]];
        f->tooth = stage.mesh.faults[k].tooth;
        f->state = stage.mesh.faults[k].state;
      }
      stage.mesh.faults.clear();
      probe.as_table().erase("faults");
      read_pair = probe;
    } catch (const CaseFileError& e) {
      for (Problem p : e.problems()) {
        // A pair fault's problems under the stage's fault: faults[k] is faults[i] of the file.
        for (std::size_t k = 0; k < pair_fault_of.size(); ++k) {
          const std::string from = "faults[" + std::to_string(k) + "]";
          if (p.field.rfind(from, 0) != 0) continue;
          const std::string to = "faults[" + std::to_string(pair_fault_of[k]) + "]";
          p.field = to + p.field.substr(from.size());
          for (std::size_t at = p.message.find(from); at != std::string::npos;
               at = p.message.find(from, at + to.size())) {
            p.message.replace(at, from.size(), to);
          }
          break;
        }
        const bool seen = std::any_of(problems.begin(), problems.end(), [&](const Problem& q) {
          return q.field == p.field && q.message == p.message;
        });
        if (!seen) problems.push_back(p);
      }
    }
  }
  // The input member (the sun, or the ring when the sun is held) starts at input_speed: a
  // driver's speed at t = 0 is checked against it.
  const std::string input = stage.held == HeldMember::sun ? "ring_torque" : "sun_torque";
  for (const auto& [key, torque] :
       {std::pair<std::string, Torque*>{"sun_torque", &stage.sun_torque},
        {"ring_torque", &stage.ring_torque},
        {"carrier_torque", &stage.carrier_torque}}) {
    const toml::value* value = table.find(key);
    if (value != nullptr && value->is_table()) {
      if (read_pair) {
        *torque = read_body_torque(reader, *read_pair, *value,
                                   key == input ? table.find("input_speed") : nullptr, "stage",
                                   file_name, problems, "stage." + key, "stage.input_speed");
      }
      continue;
    }
    torque->kind = Torque::Kind::constant;
    torque->constant_n_m = table.quantity("stage", key).value_or(0.0);
  }
  if (!problems.empty()) throw CaseFileError(reader.file(), std::move(problems));
  for (const std::optional<StageFault>& f : faults) stage.faults.push_back(*f);
  return stage;
}

}  // namespace

bool is_stage_text(std::string_view toml_text, std::string_view file_name) {
  const Reader reader{std::string(file_name)};
  return has_stage(parse_toml(reader, toml_text, file_name));
}

bool is_stage_file(const std::filesystem::path& path) {
  return is_stage_text(read_text(path), path.string());
}

PlanetaryStage parse_stage(std::string_view toml_text, std::string_view file_name,
                           const std::vector<std::string>& sets) {
  const Reader reader{std::string(file_name)};
  toml::value root = parse_toml(reader, toml_text, file_name);
  if (!root.is_table()) root = toml::table{};
  for (const std::string& assignment : sets) set_in_file(root, assignment);
  if (!has_stage(root)) {
    throw CaseFileError(reader.file(), {reader.problem("stage", nullptr,
                                                       "[stage] is missing: a stage file has "
                                                       "[stage] with keys " +
                                                           train_key_list("stage"))});
  }
  PlanetaryStage stage = read_stage(reader, root, file_name);
  // What the stage's geometry refuses (a ring that does not close, ...), named by its key,
  // before any work.
  try {
    (void)planetary_train(stage);
  } catch (const InputError& e) {
    // The stage's own keys under [stage]; a mesh's (module, ...) as the library names them.
    const bool own = find_train_field("stage." + e.field()) != nullptr;
    std::vector<Problem> problems = e.problems();
    for (Problem& p : problems) {
      // The geometry's planet_angles[n] counts the planets from 1; the file's array from 0, its
      // element as written (in its unit).
      constexpr std::string_view angle = "planet_angles[";
      if (p.field.rfind(angle, 0) == 0) {
        const auto& section = root.as_table().at("stage").as_table();
        const auto written = section.find("planet_angles");
        const std::size_t n = std::stoul(p.field.substr(angle.size()));
        if (written == section.end() || !written->second.is_array() || n < 1 ||
            n > written->second.as_array().size()) {
          // Equal spacing's angles: the planets' count is what the user wrote.
          p = p.renamed("stage.planets", std::to_string(stage.planets));
          continue;
        }
        const toml::value& element = written->second.as_array()[n - 1];
        Problem named =
            p.renamed("stage.planet_angles[" + std::to_string(n - 1) + "]", toml_written(element));
        named.where = reader.where(&element);
        p = named;
        continue;
      }
      if (!own) continue;
      if (p.message.rfind(p.field, 0) == 0) p.message = "stage." + p.message;
      p.field = "stage." + p.field;
    }
    throw CaseFileError(reader.file(), std::move(problems));
  }
  return stage;
}

PlanetaryStage read_stage_file(const std::filesystem::path& path,
                               const std::vector<std::string>& sets) {
  return parse_stage(read_text(path), path.string(), sets);
}

bool is_train_text(std::string_view toml_text, std::string_view file_name) {
  const Reader reader{std::string(file_name)};
  const toml::value root = parse_toml(reader, toml_text, file_name);
  return has_bodies(root);
}

bool is_train_file(const std::filesystem::path& path) {
  return is_train_text(read_text(path), path.string());
}

GearTrain parse_train(std::string_view toml_text, std::string_view file_name,
                      const std::vector<std::string>& sets) {
  const Reader reader{std::string(file_name)};
  toml::value root = parse_toml(reader, toml_text, file_name);
  if (!root.is_table()) root = toml::table{};
  for (const std::string& assignment : sets) set_in_file(root, assignment);
  if (!has_bodies(root)) {
    // A two-gear case, read as it always is.
    return two_gear_train(read_case(reader, root, file_name, CaseFileKind::run));
  }
  return read_train(reader, root, file_name);
}

GearTrain read_train_file(const std::filesystem::path& path, const std::vector<std::string>& sets) {
  return parse_train(read_text(path), path.string(), sets);
}

}  // namespace gearimpact
