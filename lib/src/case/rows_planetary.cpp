// The rows of a planetary file's [planetary] section (planetary_schema): the
// linear stage of Lin & Parker (1999) (docs/planetary.md), plain Fields
// without a slot of SimulationCase, as train_schema's.
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

namespace {

constexpr std::string_view kSection = "planetary";

std::vector<Field> make_planetary_schema() {
  std::vector<Field> rows;
  const auto row = [&rows](std::string_view key, FieldKind kind, bool required,
                           std::string help) -> Field& {
    rows.push_back(slotless_field(kSection, key, kind, required, std::move(help)));
    return rows.back();
  };
  const auto quantity = [&row](std::string_view key, Dimension dimension, std::string_view unit,
                               Range range, std::string help) -> Field& {
    Field& f = row(key, FieldKind::quantity, true, std::move(help));
    f.dimension = dimension;
    f.unit = unit;
    f.range = range;
    return f;
  };
  // Up to 32 planets: stages carry 3 to 12; more is a typing slip, and the
  // model's size grows as 3 (N + 3).
  constexpr double kMostPlanets = 32.0;
  Field& planets = row("planets", FieldKind::integer, true, "N, the number of (identical) planets");
  planets.range = {closed(1.0), closed(kMostPlanets), {}};
  Field& angles = row("planet_angles", FieldKind::quantity_list, false,
                      "psi_n, each planet's angle counter-clockwise from the carrier axis: the "
                      "first 0, increasing, one per planet");
  planet_angles_field(angles, static_cast<std::size_t>(kMostPlanets));
  // Masses > 0 (M must be positive definite); stiffnesses >= 0 (a member may
  // be free); the pressure angles inside (0, 90) deg, where the mesh lines
  // have both components.
  const Range positive{open(0.0), {}, {}};
  const Range non_negative{closed(0.0), {}, {}};
  const Range pressure{open(0.0), open(0.5 * pi), {}};
  struct Member {
    std::string_view mass, rotational, support, torsional, name;
  };
  const Member members[] = {
      {"sun_mass", "sun_inertia_over_r2", "sun_support", "sun_torsional_support", "sun"},
      {"ring_mass", "ring_inertia_over_r2", "ring_support", "ring_torsional_support", "ring"},
      {"carrier_mass", "carrier_inertia_over_r2", "carrier_support", "carrier_torsional_support",
       "carrier"}};
  for (const Member& m : members) {
    const std::string name(m.name);
    const std::string radius =
        name == "carrier" ? "R_c, the planets' centre circle radius" : "r, its base radius";
    quantity(m.mass, Dimension::mass, "kg", positive, "m, the " + name + "'s mass");
    quantity(m.rotational, Dimension::mass, "kg", positive,
             "I / r^2, the " + name + "'s moment of inertia over the square of " + radius);
    quantity(m.support, Dimension::stiffness, "N/m", non_negative,
             "the " + name + "'s support stiffness on x and on y");
    quantity(m.torsional, Dimension::stiffness, "N/m", non_negative,
             "k_theta / r^2, the " + name + "'s torsional support stiffness over the square of " +
                 radius + " (0: free to turn)");
  }
  quantity("planet_mass", Dimension::mass, "kg", positive, "m_p, each planet's mass");
  quantity("planet_inertia_over_r2", Dimension::mass, "kg", positive,
           "I_p / r_p^2, each planet's moment of inertia over the square of its base radius");
  quantity("planet_bearing", Dimension::stiffness, "N/m", non_negative,
           "k_p, each planet bearing's stiffness, radial and tangential");
  quantity("sun_mesh_stiffness", Dimension::stiffness, "N/m", non_negative,
           "k_sp, each sun-planet mesh's stiffness along its line of action");
  quantity("ring_mesh_stiffness", Dimension::stiffness, "N/m", non_negative,
           "k_rp, each ring-planet mesh's stiffness along its line of action");
  quantity("sun_pressure_angle", Dimension::angle, "deg", pressure,
           "alpha_s, the sun-planet mesh's working pressure angle");
  quantity("ring_pressure_angle", Dimension::angle, "deg", pressure,
           "alpha_r, the ring-planet mesh's working pressure angle");
  return rows;
}

}  // namespace

const std::vector<Field>& planetary_schema() {
  static const std::vector<Field> rows = make_planetary_schema();
  return rows;
}

const Field* find_planetary_field(std::string_view key) {
  for (const Field& field : planetary_schema()) {
    if (field.key == key) return &field;
  }
  return nullptr;
}

}  // namespace gearimpact
