// The text of values: parsing a key's value with its unit, the allowed range and
// default as messages and docs write them, setting a key from text.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "gearimpact/case/units.hpp"
#include "gearimpact/error.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

namespace {

// A name is written into output file names: at most this many characters.
constexpr std::size_t kLongestName = 100;

bool is_name_character(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.';
}

}  // namespace

std::string schema_detail::bound_text(double value) {
  std::array<char, 64> buffer{};
  const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                          std::chars_format::scientific);
  const std::string scientific(buffer.data(), error == std::errc{} ? end : buffer.data());
  const std::size_t e = scientific.find('e');
  if (e != std::string::npos && scientific.find('.') == std::string::npos) {
    const int exponent = std::stoi(scientific.substr(e + 1));
    if (exponent <= -2 || exponent >= 2) {
      return scientific.substr(0, e) + "e" + std::to_string(exponent);
    }
  }
  return shortest_decimal(value);
}

const ChoiceName* schema_detail::choice_of(const Field& field, double code) {
  for (const ChoiceName& c : field.choices) {
    if (c.code == code) return &c;
  }
  return nullptr;
}

std::string schema_detail::si_text(const Field& field, double value) {
  switch (field.kind) {
    case FieldKind::quantity:
    case FieldKind::quantity_list:
      return shortest_decimal(value) + " " + std::string(units_of(field.dimension).front().symbol);
    case FieldKind::choice:
    case FieldKind::on_off:
      if (const ChoiceName* c = choice_of(field, value)) return "\"" + std::string(c->name) + "\"";
      return "code " + shortest_decimal(value);
    default:
      return shortest_decimal(value);
  }
}

namespace {

// "(0, 45]" with both bounds, "> 0" with one; empty without.
template <typename Format>
std::string interval(const Range& range, Format format, bool infinite_bounds) {
  const auto& lower = range.lower;
  const auto& upper = range.upper;
  if (!lower && !upper) return {};
  if ((lower && upper) || infinite_bounds) {
    std::string text = lower ? (lower->closed ? "[" : "(") + format(lower->value) : "(-inf";
    text += ", ";
    text += upper ? format(upper->value) + (upper->closed ? "]" : ")") : "inf)";
    return text;
  }
  if (lower) return (lower->closed ? ">= " : "> ") + format(lower->value);
  return (upper->closed ? "<= " : "< ") + format(upper->value);
}

std::string choice_names(const Field& field) {
  std::string list;
  for (const ChoiceName& c : field.choices) {
    if (!c.has_text) continue;
    if (!list.empty()) list += ", ";
    list += "\"" + std::string(c.name) + "\"";
  }
  return list;
}

bool in_range(const Range& range, double value) {
  if (!std::isfinite(value)) return false;
  if (range.lower &&
      (range.lower->closed ? value < range.lower->value : value <= range.lower->value)) {
    return false;
  }
  if (range.upper &&
      (range.upper->closed ? value > range.upper->value : value >= range.upper->value)) {
    return false;
  }
  return true;
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

// A whole-text decimal number, or nothing.
std::optional<double> plain_number(std::string_view text) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

const Field& field_or_throw(std::string_view key, std::string_view name) {
  if (const Field* field = find_field(key)) return *field;
  const std::optional<std::string> nearest = nearest_key(key);
  throw InputError(std::string(name.empty() ? "section.key" : name), std::string(key),
                   "a key of the case schema, as section.key (`gearimpact schema` lists them)",
                   nearest ? "did you mean " + *nearest + "?" : std::string());
}

}  // namespace

std::string allowed_text(const Field& field) {
  std::string text;
  switch (field.kind) {
    case FieldKind::quantity:
    case FieldKind::quantity_list: {
      const std::string si(units_of(field.dimension).front().symbol);
      if (field.kind == FieldKind::quantity_list) {
        text = "a list of at most " + std::to_string(field.most_values) + " values, each ";
      }
      const std::string bounds = interval(
          field.range, [](double x) { return shortest_decimal(x); }, false);
      text += std::string(describe(field.dimension));
      if (bounds.empty()) {
        text += ", any finite value";
        break;
      }
      text += (field.range.lower && field.range.upper ? " in " : " ") + bounds + " " + si;
      // The same bounds in the unit files are written in, where that differs
      // and says more than 0.
      const bool telling = (field.range.lower && field.range.lower->value != 0.0) ||
                           (field.range.upper && field.range.upper->value != 0.0);
      if (field.unit != si && telling) {
        bool exact = true;
        const std::string suffix = " " + std::string(field.unit);
        const std::string readable = interval(
            field.range,
            [&](double x) {
              std::string q = format_quantity(x, field.dimension, field.unit);
              if (q.size() < suffix.size() ||
                  q.compare(q.size() - suffix.size(), suffix.size(), suffix) != 0) {
                exact = false;
                return q;
              }
              return q.substr(0, q.size() - suffix.size());
            },
            false);
        if (exact) text += ", i.e. " + readable + suffix;
      }
      break;
    }
    case FieldKind::number: {
      const std::string bounds = interval(field.range, bound_text, true);
      text = bounds.empty() ? "any finite number" : bounds;
      break;
    }
    case FieldKind::number_list: {
      const std::string bounds = interval(field.range, bound_text, true);
      text = "a list of at most " + std::to_string(field.most_values) + " plain numbers, each " +
             (bounds.empty() ? "finite" : "in " + bounds);
      break;
    }
    case FieldKind::integer:
      text = "an integer in " +
             interval(
                 field.range, [](double x) { return std::to_string(static_cast<long long>(x)); },
                 true);
      break;
    case FieldKind::choice:
    case FieldKind::on_off:
      text = "one of " + choice_names(field);
      break;
    case FieldKind::text:
      text = "at most " + std::to_string(kLongestName) +
             " letters, digits, '_', '-', '.' (it names output files)";
      break;
  }
  if (!field.range.note.empty()) text += ", " + std::string(field.range.note);
  return text;
}

std::string value_text(const Field& field, const SimulationCase& c, bool readable_unit) {
  if (field.kind == FieldKind::text) return "\"" + field.get_text(c) + "\"";
  if (field.kind == FieldKind::quantity_list) {
    const std::string_view unit =
        readable_unit ? field.unit : units_of(field.dimension).front().symbol;
    std::string text = "[";
    for (double value : field.get_list(c)) {
      if (text.size() > 1) text += ", ";
      text += "\"" + format_quantity(value, field.dimension, unit) + "\"";
    }
    return text + "]";
  }
  if (field.kind == FieldKind::number_list) {
    std::string text = "[";
    for (double value : field.get_list(c)) {
      if (text.size() > 1) text += ", ";
      // TOML needs a point or an exponent to read a float back as one.
      std::string number = shortest_decimal(value);
      if (number.find_first_of(".e") == std::string::npos) number += ".0";
      text += number;
    }
    return text + "]";
  }
  const double value = field.get(c);
  switch (field.kind) {
    case FieldKind::quantity: {
      const std::string_view unit =
          readable_unit ? field.unit : units_of(field.dimension).front().symbol;
      return "\"" + format_quantity(value, field.dimension, unit) + "\"";
    }
    case FieldKind::number: {
      // TOML needs a point or an exponent to read a float back as one.
      std::string text = shortest_decimal(value);
      if (std::isfinite(value) && text.find_first_of(".e") == std::string::npos) text += ".0";
      return text;
    }
    case FieldKind::integer:
      return std::to_string(static_cast<long long>(value));
    default: {
      const ChoiceName* chosen = choice_of(field, value);
      if (chosen == nullptr || !chosen->has_text) {
        throw InputError(
            field.name(), chosen != nullptr ? std::string(chosen->name) : si_text(field, value),
            "one of " + choice_names(field) + " in a case file" +
                (chosen != nullptr ? " (" + std::string(chosen->meaning) + ")" : std::string()));
      }
      return "\"" + std::string(chosen->name) + "\"";
    }
  }
}

std::string default_text(const Field& field) {
  if (field.required) return "required";
  // A text row: the case's name takes the file's stem; another says its own absence.
  if (field.kind == FieldKind::text) {
    return field.when_absent.empty() ? "the file's stem"
                                     : "absent: " + std::string(field.when_absent);
  }
  // A [[faults]] row reads the case's first fault: a default one.
  SimulationCase defaults;
  if (field.section == "faults") defaults.faults.resize(1);
  if (absent(field, defaults)) return "absent: " + std::string(field.when_absent);
  return value_text(field, defaults);
}

void check_value(const Field& field, double value, std::string_view name,
                 std::string_view written) {
  bool ok = false;
  switch (field.kind) {
    case FieldKind::quantity:
    case FieldKind::number:
      ok = in_range(field.range, value);
      break;
    case FieldKind::integer:
      ok = in_range(field.range, value) && value == std::floor(value);
      break;
    case FieldKind::choice:
    case FieldKind::on_off:
      ok = choice_of(field, value) != nullptr;
      break;
    case FieldKind::text:
    case FieldKind::quantity_list:
    case FieldKind::number_list:
      break;
  }
  if (!ok) throw InputError(std::string(name), std::string(written), allowed_text(field));
}

void check_text(const Field& field, const std::string& value, std::string_view name) {
  if (value.size() > kLongestName || !std::all_of(value.begin(), value.end(), is_name_character)) {
    throw InputError(std::string(name), "\"" + value + "\"", allowed_text(field));
  }
}

std::optional<std::string> plain_speed_warning(const Field& field, std::string_view value_text,
                                               std::string_view name) {
  if (field.kind != FieldKind::quantity || field.dimension != Dimension::angular_velocity) {
    return std::nullopt;
  }
  const std::optional<double> value = plain_number(value_text);
  if (!value || *value == 0.0 || !std::isfinite(*value)) return std::nullopt;
  const std::string written(trim(value_text));
  const UnitList units = units_of(Dimension::angular_velocity);
  const auto rpm =
      std::find_if(units.begin(), units.end(), [](const Unit& u) { return u.symbol == "rpm"; });
  // A speed near the largest double has no finite value in rpm: said without it.
  const double in_rpm = *value / rpm->factor;
  char rpm_text[48] = "";
  if (std::isfinite(in_rpm)) std::snprintf(rpm_text, sizeof rpm_text, " (%.6g rpm)", in_rpm);
  return std::string(name) + " = " + written + " is read as " + written + " rad/s" + rpm_text +
         "; write \"" + written + " rad/s\" or \"" + written + " rpm\" to say which";
}

double parse_value(const Field& field, std::string_view value_text, std::string_view name) {
  const std::string written(value_text);
  double value = 0.0;
  switch (field.kind) {
    case FieldKind::quantity:
      if (const std::optional<double> si = plain_number(value_text)) {
        value = *si;
      } else {
        value = parse_quantity(value_text, field.dimension, name);
      }
      break;
    case FieldKind::number:
    case FieldKind::integer: {
      const std::optional<double> number = plain_number(value_text);
      if (!number) {
        throw InputError(std::string(name), written,
                         "a plain number (no unit) in " + allowed_text(field));
      }
      value = *number;
      break;
    }
    case FieldKind::choice:
    case FieldKind::on_off: {
      const auto chosen = std::find_if(
          field.choices.begin(), field.choices.end(),
          [&](const ChoiceName& c) { return c.has_text && c.name == trim(value_text); });
      if (chosen == field.choices.end()) {
        throw InputError(std::string(name), written, allowed_text(field));
      }
      value = chosen->code;
      break;
    }
    case FieldKind::text:
      throw InputError(std::string(name), written, "a name: set it with set_field");
    case FieldKind::quantity_list:
    case FieldKind::number_list:
      throw InputError(std::string(name), written, "a list: read it with parse_list");
  }
  // A plain number of a quantity is in SI; where files write another unit
  // (an angle in deg), a refused one that the range takes in that unit was
  // most likely meant in it: the message says how to write it.
  if (field.kind == FieldKind::quantity && plain_number(value_text) &&
      !in_range(field.range, value)) {
    const UnitList units = units_of(field.dimension);
    const auto readable = std::find_if(units.begin(), units.end(),
                                       [&](const Unit& u) { return u.symbol == field.unit; });
    if (readable != units.begin() && readable != units.end() &&
        in_range(field.range, value * readable->factor)) {
      throw InputError(std::string(name), written,
                       allowed_text(field) + "; a plain number is read in " +
                           std::string(units.front().symbol) + ": \"" +
                           std::string(trim(value_text)) + " " + std::string(field.unit) +
                           "\" gives it in " + std::string(field.unit));
    }
  }
  check_value(field, value, name, written);
  return value;
}

void check_list(const Field& field, const std::vector<double>& values, std::string_view name) {
  if (values.size() > field.most_values) {
    throw InputError(std::string(name), std::to_string(values.size()) + " values",
                     allowed_text(field));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!in_range(field.range, values[i])) {
      throw InputError(std::string(name) + "[" + std::to_string(i) + "]", si_text(field, values[i]),
                       allowed_text(field));
    }
  }
}

namespace {

// `text` without one pair of enclosing `open` and `close` characters (after trimming), or as it
// is when it has none.
std::string_view unwrapped(std::string_view text, char open, char close) {
  const std::string_view t = trim(text);
  if (t.size() >= 2 && t.front() == open && t.back() == close) return t.substr(1, t.size() - 2);
  return t;
}

// For a plain number of a quantity list refused in SI that the range takes in the unit files
// write (an angle in deg): how to write it in that unit; else empty.
std::string unit_hint(const Field& field, std::string_view item) {
  const std::optional<double> number = plain_number(item);
  if (field.kind != FieldKind::quantity_list || !number) return {};
  const UnitList units = units_of(field.dimension);
  const auto readable = std::find_if(units.begin(), units.end(),
                                     [&](const Unit& u) { return u.symbol == field.unit; });
  if (readable == units.begin() || readable == units.end() ||
      !in_range(field.range, *number * readable->factor)) {
    return {};
  }
  return "; a plain number is read in " + std::string(units.front().symbol) + ": \"" +
         std::string(item) + " " + std::string(field.unit) + "\" gives it in " +
         std::string(field.unit);
}

}  // namespace

std::vector<double> parse_list(const Field& field, std::string_view value_text,
                               std::string_view name) {
  std::vector<double> values;
  // As a case file writes the list, ["0 deg", "120 deg"], or bare, 0 deg, 120 deg.
  const std::string_view list = unwrapped(value_text, '[', ']');
  if (trim(list).empty()) return values;
  std::string_view rest = list;
  for (;;) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = trim(unwrapped(rest.substr(0, comma), '"', '"'));
    const std::string item_name = std::string(name) + "[" + std::to_string(values.size()) + "]";
    double value = 0.0;
    if (const std::optional<double> si = plain_number(item)) {
      value = *si;
    } else if (field.kind == FieldKind::number_list) {
      throw InputError(item_name, std::string(item),
                       "a plain number (no unit): " + allowed_text(field));
    } else {
      value = parse_quantity(item, field.dimension, item_name);
    }
    if (!in_range(field.range, value)) {
      throw InputError(item_name, std::string(item), allowed_text(field) + unit_hint(field, item));
    }
    values.push_back(value);
    if (values.size() > field.most_values) {
      throw InputError(std::string(name),
                       "more than " + std::to_string(field.most_values) + " values",
                       allowed_text(field));
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return values;
}

void set_field(SimulationCase& c, std::string_view section_dot_key, std::string_view value_text,
               std::string_view name_in_messages) {
  const Field& field = field_or_throw(section_dot_key, name_in_messages);
  const std::string name = name_in_messages.empty() ? field.name() : std::string(name_in_messages);
  if (field.kind == FieldKind::text) {
    const std::string value(trim(value_text));
    check_text(field, value, name);
    field.set_text(c, value);
    return;
  }
  if (!applies(field, c)) {
    throw InputError(name, std::string(value_text),
                     "nothing: " + field.name() + " is used only with " +
                         std::string(field.section) + "." + field.only_when->text() +
                         " (set that first)");
  }
  if (is_list(field.kind)) {
    field.set_list(c, parse_list(field, value_text, name));
    return;
  }
  field.set(c, parse_value(field, value_text, name));
}

double get_numeric_field(const SimulationCase& c, std::string_view section_dot_key) {
  const Field& field = field_or_throw(section_dot_key, {});
  if (field.kind != FieldKind::quantity && field.kind != FieldKind::number &&
      field.kind != FieldKind::integer) {
    const char* what = field.kind == FieldKind::text ? "name"
                       : is_list(field.kind)         ? "list"
                                                     : "choice";
    throw InputError(field.name(), "(a " + std::string(what) + ")",
                     "a quantity, number or integer key for get_numeric_field");
  }
  return field.get(c);
}

}  // namespace gearimpact
