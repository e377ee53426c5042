#include "gearimpact/case/schema.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/named_values.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

namespace {

// The rows in the order a case file writes them: the case key (case_key) hashes them in it.
std::vector<Field> make_schema() {
  std::vector<Field> rows;
  add_gear_rows(rows);
  add_torque_rows(rows);
  add_initial_rows(rows);
  add_model_rows(rows);
  add_run_rows(rows);
  add_modification_rows(rows);
  add_support_rows(rows);
  return rows;
}

}  // namespace

std::string FieldCondition::text() const {
  std::string list;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (i > 0) list += i + 1 == choices.size() ? " or " : ", ";
    list += "\"" + std::string(choices[i]) + "\"";
  }
  return std::string(key) + " = " + list;
}

std::string Field::name() const {
  if (section.empty()) return std::string(key);
  return std::string(section) + "." + std::string(key);
}

const std::vector<Field>& case_schema() {
  static const std::vector<Field> rows = make_schema();
  return rows;
}

const Field* find_field(std::string_view section_dot_key) {
  const std::size_t dot = section_dot_key.find('.');
  const std::string_view section =
      dot == std::string_view::npos ? std::string_view() : section_dot_key.substr(0, dot);
  const std::string_view key =
      dot == std::string_view::npos ? section_dot_key : section_dot_key.substr(dot + 1);
  for (const Field& field : case_schema()) {
    if (field.section == section && field.key == key) return &field;
  }
  return nullptr;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Rows of the dynamic programme: the previous two and the current.
  std::vector<std::size_t> before(b.size() + 1);
  std::vector<std::size_t> previous(b.size() + 1);
  std::vector<std::size_t> current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::optional<std::string> nearest_key(std::string_view written) {
  const std::size_t dot = written.find('.');
  const std::string_view bare = dot == std::string_view::npos ? written : written.substr(dot + 1);
  std::optional<std::string> best;
  std::size_t fewest = std::numeric_limits<std::size_t>::max();
  for (const Field& field : case_schema()) {
    const std::string name = field.name();
    // A key under the wrong section costs one edit more than its own typos.
    const std::size_t d =
        std::min(edit_distance(written, name), edit_distance(bare, field.key) + 1);
    if (d < fewest) {
      fewest = d;
      best = name;
    }
  }
  if (!best || fewest == 0 || 3 * fewest > std::max<std::size_t>(written.size(), 3)) return {};
  return best;
}

std::vector<std::string_view> schema_sections() {
  std::vector<std::string_view> sections;
  for (const Field& field : case_schema()) {
    if (!field.section.empty() &&
        std::find(sections.begin(), sections.end(), field.section) == sections.end()) {
      sections.push_back(field.section);
    }
  }
  return sections;
}

bool absent(const Field& field, const SimulationCase& c) {
  return !field.when_absent.empty() && field.kind != FieldKind::text && std::isnan(field.get(c));
}

bool applies(const Field& field, const SimulationCase& c) {
  if (!field.only_when) return true;
  for (const Field& selector : case_schema()) {
    if (selector.section == field.section && selector.key == field.only_when->key) {
      const ChoiceName* chosen = choice_of(selector, selector.get(c));
      const auto& choices = field.only_when->choices;
      return chosen != nullptr &&
             std::find(choices.begin(), choices.end(), chosen->name) != choices.end();
    }
  }
  return false;
}

std::string case_key(const SimulationCase& c) {
  if (c.torque1.kind == Torque::Kind::user || c.torque2.kind == Torque::Kind::user) return {};
  std::string key;
  const SimulationCase defaults;
  for (const Field& field : case_schema()) {
    if (field.section.empty() && field.key == "name") continue;
    if (!applies(field, c) || absent(field, c)) continue;
    if (!field.keyed_at_default && field.get(c) == field.get(defaults)) continue;
    key += field.name() + "=" + value_text(field, c, false) + "\n";
  }
  for (std::size_t i = 0; i < c.faults.size(); ++i) {
    SimulationCase one;
    one.faults = {c.faults[i]};
    for (const Field& field : fault_schema()) {
      if (!fault_row_applies(field, one) || absent(field, one)) continue;
      key += "faults[" + std::to_string(i) + "]." + std::string(field.key) + "=" +
             value_text(field, one, false) + "\n";
    }
  }
  return key;
}

std::string schema_markdown() {
  const auto cell = [](std::string text) {
    std::string escaped;
    for (char ch : text) {
      if (ch == '|') escaped += '\\';
      escaped += ch;
    }
    return escaped;
  };
  std::string table = "| key | unit | default | allowed | meaning |\n|---|---|---|---|---|\n";
  std::vector<const Field*> rows;
  for (const Field& field : case_schema()) rows.push_back(&field);
  for (const Field& field : fault_schema()) rows.push_back(&field);
  for (const Field& field : train_schema()) rows.push_back(&field);
  for (const Field& field : planetary_schema()) rows.push_back(&field);
  for (const Field* row : rows) {
    const Field& field = *row;
    std::string help(field.help);
    if (field.kind == FieldKind::choice) {
      for (const ChoiceName& c : field.choices) {
        if (c.has_text) help += "; \"" + std::string(c.name) + "\": " + std::string(c.meaning);
      }
    }
    if (field.only_when) help += " (only with " + field.only_when->text() + ")";
    const bool has_unit =
        field.kind == FieldKind::quantity || field.kind == FieldKind::quantity_list;
    const std::string unit = has_unit ? std::string(field.unit) : std::string("-");
    table += "| `" + field.name() + "` | " + cell(unit) + " | " + cell(default_text(field)) +
             " | " + cell(allowed_text(field)) + " | " + cell(help) + " |\n";
  }
  return table;
}

}  // namespace gearimpact
