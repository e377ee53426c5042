#include "gearimpact/io/case_file.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <toml.hpp>
#include <utility>
#include <vector>

#include "case_reader.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "toml_values.hpp"

namespace gearimpact {

using namespace case_reader;

CaseFileError::CaseFileError(std::string file, std::string field, const std::string& message)
    : Error(message), file_(std::move(file)), field_(std::move(field)) {
  Problem p;
  p.field = field_;
  p.message = message;
  problems_.push_back(std::move(p));
}

CaseFileError::CaseFileError(std::string file, std::vector<Problem> problems)
    : Error(problems_text(problems)),
      file_(std::move(file)),
      field_(problems.empty() ? std::string() : problems.front().field),
      problems_(std::move(problems)) {}

namespace {

// Case files are a page of text; the cap keeps a wrong path (a log, a core
// file) from being read whole.
constexpr std::uintmax_t kLargestFileBytes = 1u << 20;
// Nesting of arrays and inline tables deeper than this is never a case file;
// the TOML parser recurses on it, so it is refused before parsing.
constexpr int kDeepestNesting = 32;
// The longest line of a case file; with the cap on listed values it bounds the
// parser's work (see TextShape).
constexpr std::size_t kLongestLineBytes = 4096;

// The stem of a path without touching the file system.
std::string stem_of(std::string_view file_name) {
  const std::size_t slash = file_name.find_last_of('/');
  if (slash != std::string_view::npos) file_name.remove_prefix(slash + 1);
  const std::size_t dot = file_name.rfind('.');
  if (dot != std::string_view::npos && dot > 0) file_name = file_name.substr(0, dot);
  return std::string(file_name);
}

// What the parser's cost depends on, from one pass over the text: toml11
// 3.7.1 scans a value's whole line for each value on it (its comments), so a
// long line of many values costs their product, and nesting makes it recurse.
struct TextShape {
  int deepest_nesting = 0;  // of [ and { outside strings and comments; headers count too
  std::size_t longest_line_bytes = 0;
  std::size_t longest_line = 0;      // 1-based
  std::size_t bracketed_values = 0;  // commas inside [ ] and { }: values after the first
};

TextShape shape_of(std::string_view text) {
  TextShape shape;
  int depth = 0;
  char quote = 0;
  bool comment = false;
  std::size_t line = 1;
  std::size_t line_start = 0;
  const auto end_line = [&](std::size_t end) {
    // A CRLF line's CR is part of its end, not of its length.
    if (end > line_start && text[end - 1] == '\r') --end;
    if (end - line_start > shape.longest_line_bytes) {
      shape.longest_line_bytes = end - line_start;
      shape.longest_line = line;
    }
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      end_line(i);
      ++line;
      line_start = i + 1;
      comment = false;
      continue;
    }
    if (comment) continue;
    if (quote != 0) {
      if (c == '\\' && quote == '"') {
        ++i;
      } else if (c == quote) {
        quote = 0;
      }
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#') {
      comment = true;
    } else if (c == '[' || c == '{') {
      shape.deepest_nesting = std::max(shape.deepest_nesting, ++depth);
    } else if (c == ']' || c == '}') {
      depth = std::max(0, depth - 1);
    } else if (c == ',' && depth > 0) {
      ++shape.bracketed_values;
    }
  }
  end_line(text.size());
  return shape;
}

// The most values a case file's arrays can hold: the schema's lists at their
// longest.
std::size_t most_listed_values() {
  std::size_t most = 0;
  for (const Field& field : case_schema()) most += field.most_values;
  return most;
}

// "torque1.amplitudes: at most 1000, ..." for the message of too many values.
std::string names_of_lists() {
  std::string names;
  for (const Field& field : case_schema()) {
    if (field.most_values == 0) continue;
    names += (names.empty() ? "" : ", ") + field.name() + ": " + std::to_string(field.most_values);
  }
  return names;
}

// The offset of the first byte that is not part of well-formed UTF-8 (RFC
// 3629: no overlong forms, no surrogates, nothing above U+10FFFF), or npos.
// TOML documents are UTF-8, and toml11 3.7.1 (Debian 12) reads out of bounds
// when it reports invalid UTF-8 inside a literal string: its error path resets
// a location on one buffer to an iterator into another (found here by
// fuzz/fuzz_case_file; upstream ToruNiina/toml11 issue #199, fixed by pull
// request #208 after 3.7.1). Such text is refused before it reaches the parser.
std::size_t first_invalid_utf8(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    std::size_t length = 0;
    unsigned char low = 0x80;
    unsigned char high = 0xBF;
    if (lead < 0x80) {
      length = 1;
    } else if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3;
      if (lead == 0xE0) low = 0xA0;   // overlong
      if (lead == 0xED) high = 0x9F;  // surrogates
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4;
      if (lead == 0xF0) low = 0x90;   // overlong
      if (lead == 0xF4) high = 0x8F;  // above U+10FFFF
    } else {
      return i;
    }
    if (i + length > text.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      const unsigned char next = byte(i + k);
      if (next < (k == 1 ? low : 0x80) || next > (k == 1 ? high : 0xBF)) return i;
    }
    i += length;
  }
  return std::string_view::npos;
}

std::string key_list(std::string_view section) {
  std::string names;
  for (const Field& field : case_schema()) {
    if (field.section == section) names += (names.empty() ? "" : ", ") + std::string(field.key);
  }
  return names;
}

// A pair file needs the required keys of its own sections only.
bool required_in(const Field& field, CaseFileKind kind) {
  return field.required &&
         (kind == CaseFileKind::run || field.section.empty() || is_pair_section(field.section));
}

// A file whose every section is a pair section is a pair file.
CaseFileKind kind_of(const toml::value& root) {
  if (!root.is_table()) return CaseFileKind::run;
  for (const auto& [key, value] : root.as_table()) {
    const Field* field = find_field(key);
    const bool top_level_key = field != nullptr && field->section.empty();
    // Faulted teeth belong to the pair: a pair file may list them.
    if (!top_level_key && !is_pair_section(key) && key != "faults") return CaseFileKind::run;
  }
  return CaseFileKind::pair;
}

// "; did you mean \"table\"?" for a misspelt choice within two edits, or nothing.
std::string nearest_choice(const Field& field, const toml::value& value) {
  if (!value.is_string()) return {};
  const std::string& text = value.as_string().str;
  std::size_t best = 3;
  std::string_view nearest;
  for (const ChoiceName& c : field.choices) {
    if (!c.has_text) continue;
    const std::size_t d = edit_distance(text, c.name);
    if (d < best) {
      best = d;
      nearest = c.name;
    }
  }
  return nearest.empty() ? std::string() : "; did you mean \"" + std::string(nearest) + "\"?";
}

// " (did you mean model.friction_coefficient?)", or nothing.
std::string suggestion(const std::string& written) {
  const std::optional<std::string> nearest = nearest_key(written);
  return nearest ? " (did you mean " + *nearest + "?)" : std::string();
}

// The tables of a parsed file, each checked against the schema's keys of its
// section: unknown sections and keys are refused (typos do not pass silently),
// each with the nearest key of the schema, all of them at once.
class Document {
 public:
  Document(const Reader& reader, const toml::value& root, CaseFileKind kind,
           std::vector<Problem>& problems)
      : reader_(reader), root_(root), kind_(kind), problems_(problems) {
    const std::vector<std::string_view> sections = schema_sections();
    std::string list;
    for (std::string_view section : sections) {
      list += (list.empty() ? "" : ", ") + ("[" + std::string(section) + "]");
    }
    std::vector<std::string> unknown;
    for (const auto& [key, value] : root.as_table()) {
      const Field* field = find_field(key);
      const bool top_level_key = field != nullptr && field->section.empty();
      // [[faults]] is read apart (read_faults), by fault_schema().
      if (!top_level_key && key != "faults" &&
          std::find(sections.begin(), sections.end(), key) == sections.end()) {
        unknown.push_back(key);
      }
    }
    std::sort(unknown.begin(), unknown.end());
    for (const std::string& key : unknown) {
      problems_.push_back(reader.problem(key, &root.as_table().at(key),
                                         "unknown key or section \"" + key + "\"" +
                                             suggestion(key) + "; a case file has " + key_list("") +
                                             " and the sections " + list));
    }
    for (std::string_view section : sections) open(section);
  }

  // The value of the row's key in the file, or nullptr.
  const toml::value* find(const Field& field) const {
    const toml::value* table = field.section.empty() ? &root_ : section(field.section);
    if (table == nullptr || !table->is_table()) return nullptr;
    const auto& entries = table->as_table();
    const auto found = entries.find(std::string(field.key));
    return found == entries.end() ? nullptr : &found->second;
  }

  // The [section] table, or nullptr when the file has none.
  const toml::value* section(std::string_view name) const {
    const auto& top = root_.as_table();
    const auto found = top.find(std::string(name));
    return found == top.end() ? nullptr : &found->second;
  }

  // The value of "faults[i].key" in the file, or nullptr.
  const toml::value* fault_value(const std::string& name) const {
    const std::size_t close = name.find("].");
    const toml::value* list = section("faults");
    if (name.rfind("faults[", 0) != 0 || close == std::string::npos || list == nullptr ||
        !list->is_array()) {
      return nullptr;
    }
    const std::size_t i = std::stoul(name.substr(7, close - 7));
    if (i >= list->as_array().size() || !list->as_array()[i].is_table()) return nullptr;
    const auto& entries = list->as_array()[i].as_table();
    const auto found = entries.find(name.substr(close + 2));
    return found == entries.end() ? &list->as_array()[i] : &found->second;
  }

  // True when the section is missing or not a table: its keys are not
  // reported one by one.
  bool broken(std::string_view section) const {
    return std::find(broken_.begin(), broken_.end(), section) != broken_.end();
  }

 private:
  void open(std::string_view name) {
    const std::string section_name(name);
    const toml::value* table = section(name);
    if (table == nullptr) {
      const bool required =
          std::any_of(case_schema().begin(), case_schema().end(), [&](const Field& f) {
            return required_in(f, kind_) && f.section == name && !f.only_when;
          });
      if (required) {
        broken_.push_back(section_name);
        problems_.push_back(reader_.problem(
            section_name, nullptr,
            "section [" + section_name + "] is missing (required; keys " + key_list(name) + ")"));
      }
      return;
    }
    if (!table->is_table()) {
      broken_.push_back(section_name);
      problems_.push_back(reader_.problem(section_name, table,
                                          section_name + " = " + toml_written(*table) + " is " +
                                              toml_type_name(*table) + ", not a section: write [" +
                                              section_name + "] with keys " + key_list(name)));
      return;
    }
    std::vector<std::string> unknown;
    for (const auto& [key, value] : table->as_table()) {
      const Field* field = find_field(section_name + "." + key);
      if (field == nullptr || field->section != name) unknown.push_back(key);
    }
    std::sort(unknown.begin(), unknown.end());
    for (const std::string& key : unknown) {
      const std::string full = section_name + "." + key;
      problems_.push_back(reader_.problem(full, &table->as_table().at(key),
                                          "unknown key " + full + suggestion(full) +
                                              "; the keys of [" + section_name + "] are " +
                                              key_list(name)));
    }
  }

  const Reader& reader_;
  const toml::value& root_;
  CaseFileKind kind_;
  std::vector<Problem>& problems_;
  std::vector<std::string> broken_;
};

}  // namespace

// What a missing required key needs, for the message.
std::string case_reader::expected_of(const Field& field) {
  switch (field.kind) {
    case FieldKind::quantity:
      return allowed_text(field) + ", as a string with one of the units " +
             allowed_units(field.dimension);
    case FieldKind::number:
      return "a number in " + allowed_text(field);
    default:
      return allowed_text(field);
  }
}

namespace {

// The choice the row's condition depends on, e.g. [torque1] kind.
const ChoiceName& selected(const Field& field, const SimulationCase& c) {
  for (const Field& selector : case_schema()) {
    if (selector.section == field.section && selector.key == field.only_when->key) {
      for (const ChoiceName& choice : selector.choices) {
        if (choice.code == selector.get(c)) return choice;
      }
    }
  }
  throw std::logic_error("a schema condition without its choice row");
}

}  // namespace

// The SI values of a list row, from a TOML array of quantity strings; each
// element checked against the row, errors naming section.key[i].
std::vector<double> case_reader::read_list(const Reader& reader, const Field& field,
                                           const toml::value& value) {
  const std::string name = field.name();
  const bool numbers = field.kind == FieldKind::number_list;
  const std::string expected =
      numbers ? "an array of numbers, " + allowed_text(field) + ", e.g. [0.0, 0.05]"
              : "an array of strings, " + allowed_text(field) + " with one of the units " +
                    allowed_units(field.dimension) + ", e.g. [\"10 " + std::string(field.unit) +
                    "\", \"2 " + std::string(field.unit) + "\"]";
  if (!value.is_array()) {
    reader.out_of_range(name, &value, toml_written(value),
                        toml_type_name(value) + "; expected " + expected);
  }
  if (value.as_array().size() > field.most_values) {
    reader.out_of_range(name, &value, std::to_string(value.as_array().size()) + " values",
                        allowed_text(field));
  }
  std::vector<double> values;
  for (const toml::value& element : value.as_array()) {
    const std::string element_name = name + "[" + std::to_string(values.size()) + "]";
    if (numbers) {
      if (!element.is_floating() && !element.is_integer()) {
        reader.out_of_range(element_name, &element, toml_written(element),
                            toml_type_name(element) + "; expected " + expected);
      }
      values.push_back(element.is_floating() ? element.as_floating()
                                             : static_cast<double>(element.as_integer()));
      try {
        check_list(field, {values.back()}, element_name);
      } catch (const InputError& e) {
        reader.out_of_range(element_name, &element, toml_written(element), e.allowed());
      }
      continue;
    }
    if (!element.is_string()) {
      reader.out_of_range(element_name, &element, toml_written(element),
                          toml_type_name(element) + "; expected " + expected);
    }
    try {
      values.push_back(parse_quantity(element.as_string().str, field.dimension, element_name));
      check_list(field, {values.back()}, element_name);
    } catch (const InputError& e) {
      reader.fail(&element,
                  InputError({e.problems().front().renamed(element_name, toml_written(element))}));
    }
  }
  return values;
}

// The value of a non-text row as get() returns it; checked against the row.
double case_reader::read_value(const Reader& reader, const Field& field, const toml::value& value) {
  const std::string name = field.name();
  double x = 0.0;
  switch (field.kind) {
    case FieldKind::quantity:
      if (!value.is_string()) {
        const std::string why = value.is_integer() || value.is_floating()
                                    ? "a number without a unit; expected "
                                    : toml_type_name(value) + "; expected ";
        reader.out_of_range(name, &value, toml_written(value), why + expected_of(field));
      }
      try {
        x = parse_quantity(value.as_string().str, field.dimension, name);
      } catch (const InputError& e) {
        reader.fail(&value, e);
      }
      break;
    case FieldKind::number:
      if (value.is_floating()) {
        x = value.as_floating();
      } else if (value.is_integer()) {
        x = static_cast<double>(value.as_integer());
      } else {
        reader.out_of_range(name, &value, toml_written(value),
                            toml_type_name(value) + "; expected a plain number (no unit) in " +
                                allowed_text(field));
      }
      break;
    case FieldKind::integer:
      if (!value.is_integer()) {
        reader.out_of_range(name, &value, toml_written(value),
                            toml_type_name(value) + "; expected " + allowed_text(field));
      }
      x = static_cast<double>(value.as_integer());
      break;
    case FieldKind::choice:
    case FieldKind::on_off: {
      const auto chosen =
          std::find_if(field.choices.begin(), field.choices.end(), [&](const ChoiceName& c) {
            return c.has_text && value.is_string() && value.as_string().str == c.name;
          });
      if (chosen == field.choices.end()) {
        reader.out_of_range(name, &value, toml_written(value),
                            allowed_text(field) + nearest_choice(field, value));
      }
      x = chosen->code;
      break;
    }
    case FieldKind::text:
    case FieldKind::quantity_list:
    case FieldKind::number_list:
      throw std::logic_error("read_value on a text or list row");
  }
  try {
    check_value(field, x, name, toml_written(value));
  } catch (const InputError& e) {
    reader.fail(&value, e);
  }
  return x;
}

namespace {

// A problem of a check across keys, at the line of the key it names and with
// that key's value as the file wrote it.
Problem at_key(const Reader& reader, const Document& document, const SimulationCase& c,
               const Problem& problem) {
  const Field* field = find_field(problem.field);
  const toml::value* at = field != nullptr ? document.find(*field) : nullptr;
  std::string value = problem.value;
  if (field == nullptr && (at = document.fault_value(problem.field)) != nullptr) {
    // The value as the file wrote it, unless the key is absent (then `at` is its table).
    Problem p = at->is_table() ? problem : problem.renamed(problem.field, toml_written(*at));
    p.where = reader.where(at);
    return p;
  }
  if (at != nullptr) {
    value = toml_written(*at);
  } else if (field != nullptr) {
    value = value_text(*field, c) + " (the default)";
  }
  if (at == nullptr) {
    const std::size_t dot = problem.field.find('.');
    if (dot != std::string::npos) {
      at = document.section(std::string_view(problem.field).substr(0, dot));
    }
  }
  Problem p = problem.renamed(problem.field, value);
  p.where = reader.where(at);
  return p;
}

// Reads one row's key into `result`; throws CaseFileError for its problems.
void read_row(const Reader& reader, const Document& document, const Field& field, CaseFileKind kind,
              SimulationCase& result) {
  const std::string name = field.name();
  const toml::value* value = document.find(field);
  if (!applies(field, result)) {
    if (value != nullptr) {
      const ChoiceName& choice = selected(field, result);
      reader.fail(name, value,
                  name + " = " + toml_written(*value) + " is not used by " +
                      std::string(field.only_when->key) + " = \"" + std::string(choice.name) +
                      "\" (" + std::string(choice.meaning) + ")");
    }
    return;
  }
  if (value == nullptr) {
    if (required_in(field, kind)) {
      reader.fail(name, document.section(field.section),
                  name + " is missing (required: " + expected_of(field) + ")");
    }
    if (field.kind == FieldKind::text) {
      try {
        check_text(field, field.get_text(result), name);
      } catch (const InputError& e) {
        reader.out_of_range(name, nullptr, e.value(), e.allowed());
      }
    }
    return;
  }
  if (field.kind == FieldKind::text) {
    if (!value->is_string()) {
      reader.out_of_range(name, value, toml_written(*value),
                          toml_type_name(*value) + "; expected a string of " + allowed_text(field));
    }
    try {
      check_text(field, value->as_string().str, name);
    } catch (const InputError& e) {
      reader.fail(value, e);
    }
    field.set_text(result, value->as_string().str);
    return;
  }
  if (is_list(field.kind)) {
    field.set_list(result, read_list(reader, field, *value));
    return;
  }
  field.set(result, read_value(reader, field, *value));
}

std::string fault_key_list() {
  std::vector<std::string_view> keys;
  for (const Field& field : fault_schema()) {
    if (std::find(keys.begin(), keys.end(), field.key) == keys.end()) keys.push_back(field.key);
  }
  std::string names;
  for (std::string_view key : keys) names += (names.empty() ? "" : ", ") + std::string(key);
  return names;
}

// Whether a row of [[faults]] with this key applies to the fault: several
// kinds share a key (depth, width, start_radius), each by its own row.
bool fault_key_applies(std::string_view key, const SimulationCase& one_fault) {
  return std::any_of(fault_schema().begin(), fault_schema().end(), [&](const Field& f) {
    return f.key == key && fault_row_applies(f, one_fault);
  });
}

// The conditions under which some row with this key is read, choices of one
// selector together: kind = "root-crack" or "spall", or profile = ...
std::string fault_key_conditions(std::string_view key) {
  std::vector<std::pair<std::string_view, std::vector<std::string_view>>> conditions;
  for (const Field& f : fault_schema()) {
    if (f.key != key || !f.only_when) continue;
    auto found = std::find_if(conditions.begin(), conditions.end(),
                              [&](const auto& c) { return c.first == f.only_when->key; });
    if (found == conditions.end()) {
      conditions.emplace_back(f.only_when->key, std::vector<std::string_view>{});
      found = conditions.end() - 1;
    }
    for (std::string_view choice : f.only_when->choices) {
      if (std::find(found->second.begin(), found->second.end(), choice) == found->second.end()) {
        found->second.push_back(choice);
      }
    }
  }
  std::string text;
  for (const auto& [selector, choices] : conditions) {
    if (!text.empty()) text += ", or ";
    text += FieldCondition{selector, choices}.text();
  }
  return text;
}

// The [[faults]] tables into result.faults, each read by the rows of
// fault_schema() in a case of its own and named faults[i].key. A table with a
// problem is left out of the case, and "faults" is then among `failed`, so that
// no check across keys reads a shifted list.
void read_faults(const Reader& reader, const toml::value& root, SimulationCase& result,
                 std::vector<std::string>& failed, std::vector<Problem>& problems) {
  const auto& top = root.as_table();
  const auto found = top.find("faults");
  if (found == top.end()) return;
  const toml::value& list = found->second;
  if (!list.is_array()) {
    failed.emplace_back("faults");
    problems.push_back(reader.problem(
        "faults", &list,
        "faults = " + toml_written(list) + " is " + toml_type_name(list) +
            ", not an array of tables: write one [[faults]] table per faulted tooth, with keys " +
            fault_key_list()));
    return;
  }
  for (std::size_t i = 0; i < list.as_array().size(); ++i) {
    const toml::value& table = list.as_array()[i];
    const std::string section = "faults[" + std::to_string(i) + "]";
    if (!table.is_table()) {
      failed.push_back(section);
      problems.push_back(reader.problem(section, &table,
                                        section + " = " + toml_written(table) + " is " +
                                            toml_type_name(table) + ", not a [[faults]] table"));
      continue;
    }
    const std::size_t before = problems.size();
    for (const auto& entry : table.as_table()) {
      const std::string& key = entry.first;
      const toml::value& value = entry.second;
      const bool known = std::any_of(fault_schema().begin(), fault_schema().end(),
                                     [&](const Field& f) { return f.key == key; });
      if (!known) {
        problems.push_back(reader.problem(section + "." + key, &value,
                                          "unknown key " + section + "." + key +
                                              "; the keys of [[faults]] are " + fault_key_list()));
      }
    }
    SimulationCase one;
    one.faults.resize(1);
    for (const Field& row : fault_schema()) {
      Field named = row;
      named.section = section;
      const std::string name = named.name();
      const auto entry = table.as_table().find(std::string(row.key));
      const toml::value* value = entry == table.as_table().end() ? nullptr : &entry->second;
      if (!fault_row_applies(row, one)) {
        // Reported once, by the key's first row, unless another row reads it.
        const bool first_of_key =
            &*std::find_if(fault_schema().begin(), fault_schema().end(),
                           [&](const Field& f) { return f.key == row.key; }) == &row;
        if (value != nullptr && first_of_key && !fault_key_applies(row.key, one)) {
          problems.push_back(reader.problem(
              name, value,
              name + " = " + toml_written(*value) + " is read only with " +
                  fault_key_conditions(row.key) + "; this fault is of another kind"));
        }
        continue;
      }
      if (value == nullptr) {
        if (row.required) {
          problems.push_back(reader.problem(
              name, &table, name + " is missing (required: " + expected_of(named) + ")"));
          // The rows after a missing choice depend on it.
          if (row.kind == FieldKind::choice) break;
        }
        continue;
      }
      try {
        row.set(one, read_value(reader, named, *value));
      } catch (const CaseFileError& e) {
        problems.insert(problems.end(), e.problems().begin(), e.problems().end());
        // The rows after a refused choice depend on it.
        if (row.kind == FieldKind::choice) break;
      }
    }
    if (problems.size() == before) {
      result.faults.push_back(one.faults.front());
    } else {
      failed.push_back(section);
    }
  }
}

}  // namespace

SimulationCase case_reader::read_case(const Reader& reader, const toml::value& root,
                                      std::string_view file_name, CaseFileKind kind) {
  // Every problem of the file is gathered and reported at once; the checks
  // across keys run only on keys that were read without one.
  std::vector<Problem> problems;
  const Document document(reader, root, kind, problems);
  SimulationCase result;
  result.name = stem_of(file_name);
  std::vector<std::string> failed;
  for (const Field& field : case_schema()) {
    if (document.broken(field.section)) {
      failed.push_back(field.name());
      continue;
    }
    // A key that depends on a choice refused above is left out: which keys apply is unknown,
    // and reporting them would only echo that one problem.
    if (field.only_when) {
      const std::string chooser =
          std::string(field.section) + "." + std::string(field.only_when->key);
      if (std::find(failed.begin(), failed.end(), chooser) != failed.end()) {
        failed.push_back(field.name());
        continue;
      }
    }
    try {
      read_row(reader, document, field, kind, result);
    } catch (const CaseFileError& e) {
      failed.push_back(field.name());
      problems.insert(problems.end(), e.problems().begin(), e.problems().end());
    }
  }
  read_faults(reader, root, result, failed, problems);
  // A pair file gives no run: the keys a run would need are named, for a run to refuse.
  if (kind == CaseFileKind::pair) {
    for (const Field& field : case_schema()) {
      // The rows a run always needs; those under a torque's kind follow from the kind.
      if (field.required && !field.only_when && !required_in(field, kind)) {
        result.run_keys_absent.push_back(field.name());
      }
    }
  }
  Problems relations;
  relation_problems(result, failed, relations);
  for (const Problem& p : relations.list()) problems.push_back(at_key(reader, document, result, p));
  // The dynamics refuses a step that cannot resolve the contact or the mesh
  // period, and torques that imply a deflection past the tooth model; the
  // file says so here, at the key's line, before any work starts. These need
  // the mesh stiffness of a valid case. A pair file describes no run.
  if (problems.empty() && kind == CaseFileKind::run) {
    try {
      validate_implied(result);
    } catch (const QuadratureError& e) {
      const Field& tolerance = *find_field("model.stiffness_tolerance");
      problems.push_back(
          reader.problem(tolerance.name(), document.find(tolerance),
                         tolerance.name() + " = " + value_text(tolerance, result) +
                             " with stiffness_method = " + method_name(result.model.stiffness) +
                             ": the mesh stiffness cannot be computed to it (" + e.what() +
                             "); 1e-12 is within reach of every method"));
    } catch (const InputError& e) {
      for (const Problem& p : e.problems()) {
        problems.push_back(at_key(reader, document, result, p));
      }
    }
  }
  if (!problems.empty()) throw CaseFileError(reader.file(), std::move(problems));
  return result;
}

namespace {

// A list's "[a, b, ...]" over lines of kValuesPerLine values: the reader
// refuses lines longer than kLongestLineBytes, and the longest list must read
// back. The elements are quoted quantities or plain numbers, which hold no ", ".
std::string wrapped_list(const std::string& one_line) {
  constexpr int kValuesPerLine = 8;
  const std::string_view inner = std::string_view(one_line).substr(1, one_line.size() - 2);
  if (static_cast<std::size_t>(std::count(one_line.begin(), one_line.end(), ',')) <
      kValuesPerLine) {
    return one_line;
  }
  std::string text = "[";
  std::size_t start = 0;
  for (int count = 0;; ++count) {
    const std::size_t comma = inner.find(", ", start);
    text += (count % kValuesPerLine == 0 ? "\n  " : " ");
    text += inner.substr(start, comma == std::string_view::npos ? comma : comma - start);
    if (comma == std::string_view::npos) break;
    text += ",";
    start = comma + 2;
  }
  return text + "\n]";
}

// toml11's report, "[error] toml::parse_key: an invalid key appeared.\n
// --> file\n | \n 2 | [gears\n   | ^--- is not a valid key\n Hint: ...", as
// one line: the line number of its first excerpt, its reason and its first
// note ("an invalid key appeared: is not a valid key").
struct TomlError {
  std::size_t line = 0;
  std::string message;
};

TomlError toml_error(const std::string& report) {
  TomlError error;
  std::istringstream lines(report);
  std::string line;
  std::getline(lines, line);
  const std::size_t tag = line.find("] ");
  std::string reason = tag == std::string::npos ? line : line.substr(tag + 2);
  if (reason.rfind("toml::", 0) == 0) {
    const std::size_t colon = reason.find(": ");
    if (colon != std::string::npos) reason = reason.substr(colon + 2);
  }
  while (!reason.empty() && (reason.back() == '.' || reason.back() == ' ')) reason.pop_back();
  std::string note;
  while (std::getline(lines, line)) {
    const std::size_t bar = line.find(" | ");
    if (bar == std::string::npos) continue;
    const std::string left = line.substr(0, bar);
    const std::size_t digit = left.find_first_of("0123456789");
    if (error.line == 0 && digit != std::string::npos &&
        left.find_first_not_of(" 0123456789") == std::string::npos) {
      error.line = std::stoul(left.substr(digit));
    } else if (note.empty() && left.find_first_not_of(' ') == std::string::npos) {
      const std::string right = line.substr(bar + 3);
      const std::size_t text = right.find_first_not_of(" ^~-");
      if (text != std::string::npos && text > 0) note = right.substr(text);
    }
  }
  error.message = note.empty() ? reason : reason + ": " + note;
  if (error.message.empty()) error.message = report.substr(0, report.find('\n'));
  // One line of printable text: a CR-only file would otherwise echo itself.
  constexpr std::size_t kLongestMessage = 200;
  if (error.message.size() > kLongestMessage) error.message.resize(kLongestMessage);
  for (char& c : error.message) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  }
  return error;
}

}  // namespace

// Parses the text to TOML, refusing what no case file can be. Throws CaseFileError.
toml::value case_reader::parse_toml(const Reader& reader, std::string_view toml_text,
                                    std::string_view file_name) {
  if (toml_text.size() > kLargestFileBytes) {
    reader.fail(
        "", nullptr,
        "is " + std::to_string(toml_text.size()) + " bytes; a case file is at most 1 MiB of TOML");
  }
  const TextShape shape = shape_of(toml_text);
  if (shape.deepest_nesting > kDeepestNesting) {
    reader.fail("", nullptr,
                "not a case file: arrays or tables nested deeper than " +
                    std::to_string(kDeepestNesting) + " levels");
  }
  if (shape.longest_line_bytes > kLongestLineBytes) {
    reader.fail_at_line(
        shape.longest_line,
        "the line is " + std::to_string(shape.longest_line_bytes) + " bytes; a line is at most " +
            std::to_string(kLongestLineBytes) +
            " bytes (a long array may go over several lines, a line break after any comma; a "
            "long comment over several comment lines)");
  }
  if (const std::size_t most = most_listed_values(); shape.bracketed_values > most) {
    reader.fail("", nullptr,
                "its arrays and inline tables hold more than " + std::to_string(most) +
                    " values; a case file's lists hold at most that many together (" +
                    names_of_lists() + ")");
  }
  if (const std::size_t bad = first_invalid_utf8(toml_text); bad != std::string_view::npos) {
    const auto line =
        std::count(toml_text.begin(), toml_text.begin() + static_cast<long>(bad), '\n');
    reader.fail("", nullptr,
                "not valid TOML: byte " + std::to_string(bad + 1) + " (line " +
                    std::to_string(line + 1) + ") is not part of well-formed UTF-8");
  }
  toml::value root;
  try {
    std::istringstream stream{std::string(toml_text)};
    root = toml::parse(stream, std::string(file_name));
  } catch (const std::exception& e) {
    const TomlError error = toml_error(e.what());
    if (error.line > 0) reader.fail_at_line(error.line, "not valid TOML: " + error.message);
    reader.fail("", nullptr, "not valid TOML: " + error.message);
  }
  return root;
}

std::string case_reader::read_text(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) throw CaseFileError(file, "", file + ": cannot be read: " + error.message());
  if (size > kLargestFileBytes) {
    throw CaseFileError(
        file, "",
        file + ": is " + std::to_string(size) + " bytes; a case file is at most 1 MiB of TOML");
  }
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw CaseFileError(file, "", file + ": cannot be opened");
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

std::string toml_type_name(const toml::value& value) {
  switch (value.type()) {
    case toml::value_t::boolean:
      return "a boolean";
    case toml::value_t::integer:
      return "an integer";
    case toml::value_t::floating:
      return "a float";
    case toml::value_t::string:
      return "a string";
    case toml::value_t::array:
      return "an array";
    case toml::value_t::table:
      return "a table";
    case toml::value_t::empty:
      return "nothing";
    default:
      return "a date or time";
  }
}

std::string toml_written(const toml::value& value) {
  switch (value.type()) {
    case toml::value_t::string:
      return "\"" + value.as_string().str + "\"";
    case toml::value_t::integer:
      return std::to_string(value.as_integer());
    case toml::value_t::floating:
      return shortest_decimal(value.as_floating());
    case toml::value_t::boolean:
      return value.as_boolean() ? "true" : "false";
    case toml::value_t::array: {
      std::string list = "[";
      for (const toml::value& element : value.as_array()) {
        list += (list.size() > 1 ? ", " : "") + toml_written(element);
      }
      return list + "]";
    }
    default:
      return "(" + toml_type_name(value) + ")";
  }
}

bool is_pair_section(std::string_view section) {
  // The bearings and shafts mount the pair: `modes` reads them from a pair file.
  return section == "gears" || section == "model" || section == "modifications" ||
         section == "bearings" || section == "shafts";
}

SimulationCase parse_case(std::string_view toml_text, std::string_view file_name) {
  const Reader reader{std::string(file_name)};
  const toml::value root = parse_toml(reader, toml_text, file_name);
  return read_case(reader, root, file_name, CaseFileKind::run);
}

PairOrRunCase parse_pair_or_run(std::string_view toml_text, std::string_view file_name) {
  const Reader reader{std::string(file_name)};
  const toml::value root = parse_toml(reader, toml_text, file_name);
  const CaseFileKind kind = kind_of(root);
  return {read_case(reader, root, file_name, kind), kind};
}

PairOrRunCase read_pair_or_run_file(const std::filesystem::path& path) {
  return parse_pair_or_run(read_text(path), path.string());
}

SimulationCase read_case_file(const std::filesystem::path& path) {
  return parse_case(read_text(path), path.string());
}

std::string write_case_file(const SimulationCase& c, CaseUnits units) {
  std::string text = "# gearimpact case file (see docs/case-files.md)\n";
  std::string_view section;
  // A gear pair alone is written as a pair file: its torques and integrator are no one's values.
  const bool pair_alone = !c.run_keys_absent.empty();
  for (const Field& field : case_schema()) {
    if (!applies(field, c) || absent(field, c)) continue;
    if (pair_alone && !field.section.empty() && !is_pair_section(field.section)) continue;
    if (!field.written_at_default && value_text(field, c) == value_text(field, SimulationCase{})) {
      continue;
    }
    if (field.section != section) {
      section = field.section;
      text += "\n[" + std::string(section) + "]\n";
    }
    std::string value = value_text(field, c, units == CaseUnits::readable);
    if (is_list(field.kind)) value = wrapped_list(value);
    text += std::string(field.key) + " = " + value + "\n";
  }
  for (const ToothFault& fault : c.faults) {
    SimulationCase one;
    one.faults = {fault};
    text += "\n[[faults]]\n";
    for (const Field& field : fault_schema()) {
      if (!fault_row_applies(field, one) || absent(field, one)) continue;
      text += std::string(field.key) + " = " +
              value_text(field, one, units == CaseUnits::readable) + "\n";
    }
  }
  return text;
}

std::string case_file_text(const std::filesystem::path& path, const std::string& key) {
  const std::size_t dot = key.find('.');
  if (dot == std::string::npos) return "";
  try {
    std::ifstream stream(path, std::ios::binary);
    if (!stream) return "";
    const toml::value root = toml::parse(stream, path.string());
    if (!root.is_table() || !root.contains(key.substr(0, dot))) return "";
    const toml::value& section = root.at(key.substr(0, dot));
    if (!section.is_table() || !section.contains(key.substr(dot + 1))) return "";
    const toml::value& value = section.at(key.substr(dot + 1));
    return value.is_string() ? value.as_string().str : "";
  } catch (const std::exception&) {
    return "";
  }
}

}  // namespace gearimpact
