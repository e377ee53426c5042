// The machinery the case schema's rows are written with (Rows, bind, the
// choices of an enumeration) and the rows of each section, which make_schema
// (schema.cpp) adds in the order a case file writes them. Private to lib/src/case.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/named_values.hpp"

namespace gearimpact::schema_detail {

// Tooth counts beyond this are not gears but typing slips; the geometry
// needs at least 4 (the teeth rows), the undercut limit more (validate_geometry).
constexpr double kMostTeeth = 100000.0;

constexpr Bound open(double value) {
  return {value, false};
}
constexpr Bound closed(double value) {
  return {value, true};
}

// One significant digit as 1e-14 or 2e9, the rest as the shortest decimal.
std::string bound_text(double value);

// The choice of `field` whose code is `code`, or null.
const ChoiceName* choice_of(const Field& field, double code);

// The value in SI as a library user set it, for messages.
std::string si_text(const Field& field, double value);

// get/set of a field of SimulationCase reached by `slot`, a generic lambda
// returning a reference to it (const or not), whatever its type: double, int,
// bool (on/off) or an enumeration (a choice's code).
template <typename Slot>
void bind(Field& field, Slot slot) {
  field.get = [slot](const SimulationCase& c) {
    using T = std::decay_t<decltype(slot(c))>;
    if constexpr (std::is_same_v<T, std::optional<double>>) {
      return slot(c).value_or(std::numeric_limits<double>::quiet_NaN());
    } else if constexpr (std::is_enum_v<T>) {
      return static_cast<double>(static_cast<int>(slot(c)));
    } else if constexpr (std::is_same_v<T, bool>) {
      return slot(c) ? 1.0 : 0.0;
    } else {
      return static_cast<double>(slot(c));
    }
  };
  field.set = [slot](SimulationCase& c, double value) {
    using T = std::decay_t<decltype(slot(c))>;
    if constexpr (std::is_same_v<T, std::optional<double>>) {
      slot(c) = value;
    } else if constexpr (std::is_enum_v<T>) {
      slot(c) = static_cast<T>(static_cast<int>(value));
    } else if constexpr (std::is_same_v<T, bool>) {
      slot(c) = value != 0.0;
    } else if constexpr (std::is_integral_v<T>) {
      slot(c) = static_cast<T>(value);
    } else {
      slot(c) = value;
    }
  };
}

// A row of a file's section that SimulationCase has no slot for (a train's
// bodies, meshes and shafts; a planetary stage's members): its own reader
// reads it, so a get or set through the case is a programming error.
inline Field slotless_field(std::string_view section, std::string_view key, FieldKind kind,
                            bool required, std::string help) {
  Field f;
  f.section = section;
  f.key = key;
  f.kind = kind;
  f.required = required;
  f.help = std::move(help);
  f.get = [](const SimulationCase&) { return std::numeric_limits<double>::quiet_NaN(); };
  f.set = [section](SimulationCase&, double) {
    throw std::logic_error("a row of [" + std::string(section) + "] has no slot in SimulationCase");
  };
  return f;
}

// The ranges of an elastic bearing's values: the two-gear [bearings] rows'
// (stiffness_x1, ..., mass1) and a train body's bearings (bodies.bearings.*).
// Stiffer than any rolling or journal bearing (1e8 to 1e10 N/m) by five
// orders and more. The eigenproblem's rounding grows as eps k / m: at 1e16
// it is still below 1e-8 of a mesh mode's w^2 (the paper's pair meets the
// torsional limit to 2e-8 there); stiffer only loses digits, and
// kind = "rigid" is that limit exactly.
// Softer than 1e-3 N/m is no bearing (the centres then move freely to rounding, and the
// modes call near-zero modes elastic). A damper past 1e6 N*s/m is past any bearing or
// squeeze-film damper (1e2 to 1e5) and made a run's state NaN mid-run.
inline Range bearing_stiffness_range() {
  return {closed(1e-3), closed(1e16), "softer is no bearing; stiffer is kind = \"rigid\""};
}
inline Range bearing_damping_range() {
  return {closed(0.0), closed(1e6), "more is past any bearing or squeeze-film damper"};
}
inline Range bearing_mass_range() {
  return {closed(1e-4), closed(1e6), "a tenth of a gram (a watch's gear) to a thousand tonnes"};
}

// A planetary stage's planet angles psi_n (a planetary file's and a stage
// file's key): degrees in [0, 360), at most `most` of them, equally spaced
// when absent.
inline void planet_angles_field(Field& angles, std::size_t most) {
  angles.dimension = Dimension::angle;
  angles.unit = "deg";
  angles.range = {closed(0.0), open(2.0 * pi), {}};
  angles.most_values = most;
  angles.when_absent = "equally spaced, 360 (n - 1) / N deg";
}

template <typename E>
ChoiceName choice(std::string_view name, E value, std::string_view meaning, bool has_text = true) {
  return {name, static_cast<int>(value), meaning, has_text};
}

// The choices of a row from the table of its enumeration.
template <typename E, std::size_t N>
std::vector<ChoiceName> choices_of(const std::array<NamedValue<E>, N>& table) {
  std::vector<ChoiceName> choices;
  for (const NamedValue<E>& entry : table) {
    choices.push_back(choice(entry.name, entry.value, entry.meaning));
  }
  return choices;
}

// The rows of one section, added in the order they are written.
class Rows {
 public:
  explicit Rows(std::vector<Field>& rows, std::string_view section)
      : rows_(rows), section_(section) {}

  template <typename Slot>
  Field& quantity(std::string_view key, Dimension dimension, std::string_view unit, Range range,
                  bool required, const std::string& help, Slot slot) {
    Field& f = add(key, FieldKind::quantity, required, help, slot);
    f.dimension = dimension;
    f.unit = unit;
    f.range = range;
    return f;
  }
  template <typename Slot>
  Field& number(std::string_view key, Range range, bool required, const std::string& help,
                Slot slot) {
    Field& f = add(key, FieldKind::number, required, help, slot);
    f.range = range;
    return f;
  }
  template <typename Slot>
  Field& integer(std::string_view key, Range range, bool required, const std::string& help,
                 Slot slot) {
    // The row's range must fit its slot's type: a value past it would wrap when set (a tooth
    // of 2^31 read as -2^31), so every integer row is bounded on both sides.
    using T = std::decay_t<decltype(slot(std::declval<SimulationCase&>()))>;
    if (!range.lower || !range.upper ||
        range.lower->value < static_cast<double>(std::numeric_limits<T>::lowest()) ||
        range.upper->value > static_cast<double>(std::numeric_limits<T>::max())) {
      throw std::logic_error("the integer row " + std::string(key) +
                             " has a range its slot's type cannot hold");
    }
    Field& f = add(key, FieldKind::integer, required, help, slot);
    f.range = range;
    return f;
  }
  template <typename Slot>
  Field& choice(std::string_view key, std::vector<ChoiceName> choices, bool required,
                const std::string& help, Slot slot) {
    Field& f = add(key, FieldKind::choice, required, help, slot);
    f.choices = std::move(choices);
    return f;
  }
  // A list of quantities, each in `range`; `slot` returns the std::vector<double>.
  template <typename Slot>
  Field& quantity_list(std::string_view key, Dimension dimension, std::string_view unit,
                       Range range, std::size_t most_values, bool required, const std::string& help,
                       Slot slot) {
    Field f;
    f.section = section_;
    f.key = key;
    f.kind = FieldKind::quantity_list;
    f.required = required;
    f.help = help;
    f.dimension = dimension;
    f.unit = unit;
    f.range = range;
    f.most_values = most_values;
    f.get_list = [slot](const SimulationCase& c) { return slot(c); };
    f.set_list = [slot](SimulationCase& c, const std::vector<double>& values) { slot(c) = values; };
    rows_.push_back(std::move(f));
    return rows_.back();
  }
  // A list of plain numbers, each in `range`; `slot` returns the std::vector<double>.
  template <typename Slot>
  Field& number_list(std::string_view key, Range range, std::size_t most_values, bool required,
                     const std::string& help, Slot slot) {
    Field& f = quantity_list(key, Dimension::length, "", range, most_values, required, help, slot);
    f.kind = FieldKind::number_list;
    return f;
  }
  template <typename Slot>
  Field& on_off(std::string_view key, const std::string& help, Slot slot) {
    Field& f = add(key, FieldKind::on_off, false, help, slot);
    f.choices = {{"on", 1, "included", true}, {"off", 0, "left out", true}};
    return f;
  }

 private:
  template <typename Slot>
  Field& add(std::string_view key, FieldKind kind, bool required, const std::string& help,
             Slot slot) {
    Field f;
    f.section = section_;
    f.key = key;
    f.kind = kind;
    f.required = required;
    f.help = help;
    bind(f, slot);
    rows_.push_back(std::move(f));
    return rows_.back();
  }

  std::vector<Field>& rows_;
  std::string_view section_;
};

// The rows of each section (rows_*.cpp), appended to `rows` in the order they are written.
// name and [gears]
void add_gear_rows(std::vector<Field>& rows);
// [torque1] and [torque2]
void add_torque_rows(std::vector<Field>& rows);
// [initial]
void add_initial_rows(std::vector<Field>& rows);
// [model]
void add_model_rows(std::vector<Field>& rows);
// [integrator], [drive] and [tacho]
void add_run_rows(std::vector<Field>& rows);
// [modifications]
void add_modification_rows(std::vector<Field>& rows);
// [bearings] and [shafts]
void add_support_rows(std::vector<Field>& rows);

}  // namespace gearimpact::schema_detail
