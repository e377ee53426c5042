// The schema of a simulation case: one row per case-file key, with its kind,
// the unit it is written in, its allowed range, its help text and the field of
// SimulationCase it reads and writes. The case-file reader and writer, the
// library's validate_fields, the command-line flags (`--set section.key=value`
// among them) and the table in docs/case-files.md (`gearimpact schema`) all
// walk these rows, so a key, its range and its default live in one place.
// Defaults are those of a default-constructed SimulationCase.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

enum class FieldKind {
  quantity,  // a number with a unit of `dimension`: "10 mm"
  number,    // a plain number, no unit
  integer,
  choice,  // one of the names of `choices`
  on_off,  // "on" or "off"
  text,    // a name
  // A list of numbers with a unit of `dimension`: in a case file a TOML array
  // of quantity strings, ["10 N*m", "2 N*m"]; on the command line a comma-
  // separated list, "10 N*m, 2 N*m". Each element must lie in `range`.
  quantity_list,
  // A list of plain numbers (no unit): in a case file a TOML array of
  // numbers, [0.0, 0.05]; on the command line "0, 0.05". Each element must
  // lie in `range`.
  number_list,
};

// quantity_list or number_list.
inline bool is_list(FieldKind kind) {
  return kind == FieldKind::quantity_list || kind == FieldKind::number_list;
}

// One allowed name of a choice and the enumerator it stands for.
struct ChoiceName {
  std::string_view name;
  int code;                  // static_cast<int>(enumerator)
  std::string_view meaning;  // for the docs and for messages
  // false: a value only the library can set (a torque given as a function);
  // it has no text form, is never read and cannot be written.
  bool has_text = true;
};

struct Bound {
  double value;  // SI
  bool closed;
};

// Bounds in SI; absent bounds are infinite. Every value must also be finite.
struct Range {
  std::optional<Bound> lower;
  std::optional<Bound> upper;
  std::string_view note;  // appended to the interval in messages: why these bounds
};

// A key that exists only when another key of its section has one of some
// values: [torque1] value only with kind = "constant", mean with kind =
// "sinusoidal" or "harmonic".
struct FieldCondition {
  std::string_view key;
  std::vector<std::string_view> choices;

  // "kind = \"sinusoidal\" or \"harmonic\"", for messages and the docs.
  std::string text() const;
};

struct Field {
  std::string_view section;  // "" for a top-level key
  std::string_view key;
  FieldKind kind = FieldKind::number;
  Dimension dimension = Dimension::length;  // quantity
  std::string_view unit;                    // quantity: the readable unit files are written in
  Range range;                              // quantity, number, integer
  std::vector<ChoiceName> choices;          // choice, on_off
  bool required = false;                    // in a case file
  // Non-empty: the key may be absent (its value then reads as NaN and is
  // neither written nor checked); says what absence means.
  std::string_view when_absent;
  std::optional<FieldCondition> only_when;
  std::string help;
  // The value as a double: SI for quantities, the number, the integer, the
  // choice's code, 1/0 for on/off. Not for text rows.
  std::function<double(const SimulationCase&)> get;
  std::function<void(SimulationCase&, double)> set;
  // Text rows.
  std::function<std::string(const SimulationCase&)> get_text;
  std::function<void(SimulationCase&, const std::string&)> set_text;
  // List rows, in SI.
  std::function<std::vector<double>(const SimulationCase&)> get_list;
  std::function<void(SimulationCase&, const std::vector<double>&)> set_list;
  // List rows: the most elements a list may hold.
  std::size_t most_values = 0;
  // false: the writer leaves the key out while it holds its default, so that
  // keys added after case files were written do not change those files.
  bool written_at_default = true;
  // false: case_key leaves the key out while it holds its default, so that a
  // key added later keeps the keys (and hashes) of the cases before it.
  bool keyed_at_default = true;

  // "section.key", or "key" at the top level.
  std::string name() const;
};

// Every key, in the order case files are written.
const std::vector<Field>& case_schema();

// The rows of one [[faults]] table (a faulted tooth, docs/faults.md), each
// reading and writing the first element of SimulationCase::faults. Not part of
// case_schema(): a case has any number of these tables.
const std::vector<Field>& fault_schema();
// The rows of a gear train's [[bodies]], [[meshes]] and [[shafts]] tables
// (docs/case-files.md, A gear train): name, unit, default, range and help of
// each key. Their values are a GearTrain's, not a SimulationCase's: the
// case-file reader puts each into the body, mesh or shaft of the table it
// reads, so get() gives NaN (an optional row is absent, its when_absent the
// default) and set() is never called. Not part of case_schema(); a mesh's
// pair keys are the rows of case_schema() under meshes.NAME.
const std::vector<Field>& train_schema();
// The row of "section.key" of train_schema() ("bodies.inertia"), or nullptr.
const Field* find_train_field(std::string_view section_dot_key);
// A train's or a stage's value in SI, built in code or read, against its row
// of train_schema() (`section_dot_key`: "bodies.inertia", "stage.sun_mass"):
// check_value, refused as `name` ("bodies.idler.inertia"), so that the range
// lives in the row alone. std::logic_error for a key without a row.
void check_train_value(std::string_view section_dot_key, double value, std::string_view name);
// The rows of a planetary file's [planetary] section (docs/planetary.md): the
// linear stage's PlanetaryParameters, SI as every row. As train_schema's, not
// a SimulationCase's: get() gives NaN and set() is never called; the
// planetary file's reader (io/planetary_file.hpp) reads them. Not part of
// case_schema().
const std::vector<Field>& planetary_schema();
// The row of `key` (without "planetary.") of planetary_schema(), or nullptr.
const Field* find_planetary_field(std::string_view key);

// Whether a fault row applies to the fault of `one_fault` (its first): its
// condition holds, and so does the condition of the row it depends on.
bool fault_row_applies(const Field& field, const SimulationCase& one_fault);

// The row of "section.key", or nullptr.
const Field* find_field(std::string_view section_dot_key);

// The number of single-character insertions, deletions, substitutions and
// swaps of neighbours that turn `a` into `b` (optimal string alignment).
std::size_t edit_distance(std::string_view a, std::string_view b);

// The key of the schema nearest to `written` ("section.key", or a bare key),
// for a did-you-mean: the fewest edits of the whole name, or of the key alone
// in another section (a key put under the wrong section); nothing when even
// the nearest needs more than a third of the name's characters changed.
std::optional<std::string> nearest_key(std::string_view written);

// The sections in the order of case_schema(), without the top level.
std::vector<std::string_view> schema_sections();

// True when the row's condition (if any) holds for `c`.
bool applies(const Field& field, const SimulationCase& c);
// True when an optional row (when_absent) has no value in `c`.
bool absent(const Field& field, const SimulationCase& c);

// What the row allows, for messages and the docs: "a time > 0 s", "[0, inf)",
// "an integer in [4, 100000]", "one of \"rk4\", \"adaptive\"".
std::string allowed_text(const Field& field);

// The row's value in `c` as a case file writes it: "2 mm", "0.04", "\"rk4\"".
std::string value_text(const Field& field, const SimulationCase& c, bool readable_unit = true);

// The value of the row in a default-constructed SimulationCase, as above, or
// "required" for a key a case file must give.
std::string default_text(const Field& field);

// Throws InputError(name, written, allowed_text(field)) unless `value` (as
// get() returns it) is finite and in the row's range or one of its choices.
void check_value(const Field& field, double value, std::string_view name, std::string_view written);
// The same for a text row.
void check_text(const Field& field, const std::string& value, std::string_view name);

// Reads `value_text` as the command line writes it: a quantity as a plain
// number in SI or with a unit ("0.02", "20 ms"), a number, an integer, a
// choice's name, on/off. Checks it against the row and returns it as get()
// would. Errors are InputError naming `name` (the flag as typed, or
// section.key).
double parse_value(const Field& field, std::string_view value_text, std::string_view name);

// A plain number given for a speed (a quantity row of an angular velocity) is
// read in rad/s, as every plain quantity is read in SI, while people count a
// speed in rpm: the warning for `value_text` given as `name` ("initial.w1 =
// 1500 is read as 1500 rad/s (14323.9 rpm); write \"1500 rad/s\" or \"1500
// rpm\" to say which"), or nothing for text with a unit, another row, or 0
// (the same in every unit).
std::optional<std::string> plain_speed_warning(const Field& field, std::string_view value_text,
                                               std::string_view name);

// Sets one key of `c` from text, by its row; errors name `section_dot_key`,
// or `name_in_messages` when given (the flag a user typed).
void set_field(SimulationCase& c, std::string_view section_dot_key, std::string_view value_text,
               std::string_view name_in_messages = {});

// Reads a comma-separated list for a list row (each element as parse_value
// reads a quantity, or a plain number) and checks each element; errors name
// `name`[i].
std::vector<double> parse_list(const Field& field, std::string_view value_text,
                               std::string_view name);
// Throws InputError naming `name` if the list is longer than the row allows,
// and `name`[i] unless every element is finite and in the row's range.
void check_list(const Field& field, const std::vector<double>& values, std::string_view name);

// The value of a quantity, number or integer key, in SI. Throws InputError for
// an unknown key or one that is not numeric.
double get_numeric_field(const SimulationCase& c, std::string_view section_dot_key);

// A gear pair of the library: the [gears] rows' ranges, then the relations
// between them (validate_geometry of gear_pair.hpp). InputError names the
// field as GearPair does (module, teeth2, bore_diameter1, ...).
void validate(const GearPair& pair);

// A stiffness model of the library: the [model] rows that describe it
// (stiffness_model, moment_sign, stiffness_method, xform_rule,
// stiffness_tolerance, the term switches), then at least one term on
// (validate_terms of stiffness/model.hpp). InputError names the key.
void validate(const StiffnessModel& model);

// The integrator's settings of a library caller: the [integrator] rows' ranges that apply to
// its kind, then at most kMostSteps steps over the end time. InputError names the key as
// integrator.KEY.
void validate(const IntegratorSettings& integrator);

// The problems of validate_relations added to `problems`, each check left out
// when a key it reads is in `failed` (rows already refused): a pair whose
// module is refused has no contact ratio worth reporting.
void relation_problems(const SimulationCase& c, const std::vector<std::string>& failed,
                       Problems& problems);

// The checks that involve more than one key: the gear pair as a whole
// (validate_geometry, its errors under gears.* names), at least one term of
// (29) (validate_terms, under model.*), a callable user torque, a harmonic torque's lists of one
// length, at most kMostSteps steps. InputError names the key as section.key.
void validate_relations(const SimulationCase& c);

// Throws one InputError naming every key of c.run_keys_absent (a gear pair
// alone, without the torques or the end time a run needs), each with what it
// takes; nothing for a case a run can use. Every run checks it first. A
// helical pair is refused naming gears.helix_angle before that, for the runs
// that take spur pairs only; simulate() (check_run, validate), the steady state
// and the steady sweeps take it (validate_absent_run_keys, then
// refuse_helical_run of dynamics/simulate.hpp).
void validate_run_keys(const SimulationCase& c);
// validate_run_keys without the helical refusal.
void validate_absent_run_keys(const SimulationCase& c);

// Throws one InputError naming (as section.key) every field outside its
// range, with the relations among the fields that passed (relation_problems):
// every check but the step's upper bound, which needs the mesh stiffness (the
// dynamics checks it, largest_resolving_step_s).
void validate_fields(const SimulationCase& c);

// Every input of `c` but its name, one "section.key=value" line per row that
// applies and has a value, values in SI as value_text writes them (exact:
// they read back to the same doubles). Two cases with equal keys run alike;
// a row added to the schema enters the key without a change elsewhere.
// Empty for a case with no text form (a torque given as a function).
std::string case_key(const SimulationCase& c);

// The schema as a Markdown table: key, unit, default, allowed range, help; the rows of
// case_schema(), fault_schema(), train_schema() and planetary_schema().
std::string schema_markdown();

}  // namespace gearimpact
