// A planetary file (docs/planetary.md): [planetary] read by the rows of
// planetary_schema() into PlanetaryParameters, with the case reader's checks
// and problems (case_reader.hpp).
#include "gearimpact/io/planetary_file.hpp"

#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <toml.hpp>
#include <utility>
#include <vector>

#include "case_reader.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/case_file.hpp"
#include "toml_values.hpp"

namespace gearimpact {

using namespace case_reader;

namespace {

constexpr std::string_view kSection = "planetary";

std::string planetary_key_list() {
  std::string names;
  for (const Field& field : planetary_schema()) {
    names += (names.empty() ? "" : ", ") + std::string(field.key);
  }
  return names;
}

// The row nearest an unknown key, for a did-you-mean: at most a third of its
// characters changed.
std::string nearest_planetary_key(const std::string& key) {
  const Field* best = nullptr;
  std::size_t fewest = key.size() / 3 + 1;
  for (const Field& field : planetary_schema()) {
    const std::size_t edits = edit_distance(key, field.key);
    if (edits < fewest) {
      fewest = edits;
      best = &field;
    }
  }
  return best == nullptr ? std::string()
                         : "did you mean planetary." + std::string(best->key) + "? ";
}

class PlanetaryReader {
 public:
  PlanetaryReader(const Reader& reader, const toml::value& table, std::vector<Problem>& problems)
      : reader_(reader), table_(table), problems_(problems) {}

  const toml::value* find(std::string_view key) const {
    const auto& entries = table_.as_table();
    const auto found = entries.find(std::string(key));
    return found == entries.end() ? nullptr : &found->second;
  }

  // A quantity or integer row's value in SI, or nothing (absent: a problem
  // when required; refused: a problem).
  std::optional<double> value(std::string_view key) {
    const Field& row = *find_planetary_field(key);
    const toml::value* value = find(key);
    if (value == nullptr) {
      if (row.required) missing(row);
      return std::nullopt;
    }
    try {
      return read_value(reader_, row, *value);
    } catch (const CaseFileError& e) {
      problems_.insert(problems_.end(), e.problems().begin(), e.problems().end());
      return std::nullopt;
    }
  }

  std::optional<std::vector<double>> list(std::string_view key) {
    const Field& row = *find_planetary_field(key);
    const toml::value* value = find(key);
    if (value == nullptr) return std::nullopt;
    try {
      return read_list(reader_, row, *value);
    } catch (const CaseFileError& e) {
      problems_.insert(problems_.end(), e.problems().begin(), e.problems().end());
      return std::nullopt;
    }
  }

  void missing(const Field& row) {
    const std::string field = row.name();
    problems_.push_back(reader_.problem(
        field, &table_, field + " is missing (required: " + expected_of(row) + ")"));
  }

  void refuse_unknown() {
    for (const auto& [key, value] : table_.as_table()) {
      if (find_planetary_field(key) != nullptr) continue;
      const std::string field = std::string(kSection) + "." + key;
      problems_.push_back(reader_.problem(field, &value,
                                          "unknown key " + field + "; " +
                                              nearest_planetary_key(key) + "[planetary] has " +
                                              planetary_key_list()));
    }
  }

 private:
  const Reader& reader_;
  const toml::value& table_;
  std::vector<Problem>& problems_;
};

bool has_planetary(const toml::value& root) {
  return root.is_table() && root.as_table().count(std::string(kSection)) > 0;
}

}  // namespace

bool is_planetary_text(std::string_view toml_text, std::string_view file_name) {
  const Reader reader{std::string(file_name)};
  return has_planetary(parse_toml(reader, toml_text, file_name));
}

bool is_planetary_file(const std::filesystem::path& path) {
  return is_planetary_text(read_text(path), path.string());
}

PlanetaryCase parse_planetary(std::string_view toml_text, std::string_view file_name) {
  const Reader reader{std::string(file_name)};
  const toml::value root = parse_toml(reader, toml_text, file_name);
  std::vector<Problem> problems;
  PlanetaryCase result;
  result.name = std::filesystem::path(std::string(file_name)).stem().string();
  for (const auto& [key, value] : root.as_table()) {
    if (key == kSection) continue;
    if (key == "name") {
      if (value.is_string() && !value.as_string().str.empty()) {
        result.name = value.as_string().str;
      } else {
        problems.push_back(
            reader.problem("name", &value,
                           "name = " + toml_written(value) + " is not a name: a non-empty string"));
      }
      continue;
    }
    problems.push_back(reader.problem(
        key, &value, "unknown key " + key + "; a planetary file holds name and [planetary] only"));
  }
  const toml::value& table = root.as_table().at(std::string(kSection));
  if (!table.is_table()) {
    reader.fail(std::string(kSection), &table,
                "planetary = " + toml_written(table) + " is " + toml_type_name(table) +
                    ", not a [planetary] section with keys " + planetary_key_list());
  }
  PlanetaryReader section(reader, table, problems);
  section.refuse_unknown();
  PlanetaryParameters& p = result.parameters;
  const auto set = [&section](std::string_view key, double& slot) {
    if (const std::optional<double> v = section.value(key)) slot = *v;
  };
  const std::optional<double> planets = section.value("planets");
  set("sun_mass", p.sun.mass_kg);
  set("sun_inertia_over_r2", p.sun.rotational_mass_kg);
  set("sun_support", p.sun.support_stiffness_n_per_m);
  set("sun_torsional_support", p.sun.torsional_support_n_per_m);
  set("ring_mass", p.ring.mass_kg);
  set("ring_inertia_over_r2", p.ring.rotational_mass_kg);
  set("ring_support", p.ring.support_stiffness_n_per_m);
  set("ring_torsional_support", p.ring.torsional_support_n_per_m);
  set("carrier_mass", p.carrier.mass_kg);
  set("carrier_inertia_over_r2", p.carrier.rotational_mass_kg);
  set("carrier_support", p.carrier.support_stiffness_n_per_m);
  set("carrier_torsional_support", p.carrier.torsional_support_n_per_m);
  set("planet_mass", p.planet_mass_kg);
  set("planet_inertia_over_r2", p.planet_rotational_mass_kg);
  set("planet_bearing", p.planet_bearing_stiffness_n_per_m);
  set("sun_mesh_stiffness", p.sun_mesh_stiffness_n_per_m);
  set("ring_mesh_stiffness", p.ring_mesh_stiffness_n_per_m);
  set("sun_pressure_angle", p.sun_pressure_angle_rad);
  set("ring_pressure_angle", p.ring_pressure_angle_rad);
  const std::optional<std::vector<double>> angles = section.list("planet_angles");
  if (planets) {
    const auto n = static_cast<std::size_t>(*planets);
    if (angles) {
      if (angles->size() != n) {
        const toml::value* at = section.find("planet_angles");
        Problem problem =
            range_problem("planetary.planet_angles", std::to_string(angles->size()) + " angles",
                          "one angle per planet: planetary.planets = " + std::to_string(n));
        problem.where = reader.where(at);
        problems.push_back(std::move(problem));
      } else {
        // psi_1 = 0 sets the carrier axis; the order numbers the planets.
        const toml::value& written = *section.find("planet_angles");
        for (std::size_t i = 0; i < n; ++i) {
          const double psi = (*angles)[i];
          if ((i == 0 && psi != 0.0) || (i > 0 && psi <= (*angles)[i - 1])) {
            const std::string field = "planetary.planet_angles[" + std::to_string(i) + "]";
            const toml::value& element = written.as_array()[i];
            Problem problem = range_problem(field, toml_written(element),
                                            "increasing angles in [0, 360) deg, the first 0");
            problem.where = reader.where(&element);
            problems.push_back(std::move(problem));
            break;
          }
        }
        p.planet_angles_rad = *angles;
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        p.planet_angles_rad.push_back(2.0 * pi * static_cast<double>(i) / static_cast<double>(n));
      }
    }
  }
  if (!problems.empty()) throw CaseFileError(reader.file(), std::move(problems));
  return result;
}

PlanetaryCase read_planetary_file(const std::filesystem::path& path) {
  return parse_planetary(read_text(path), path.string());
}

}  // namespace gearimpact
