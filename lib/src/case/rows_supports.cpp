// The rows of [bearings] and [shafts]: how the gears are held and driven through shafts.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gearimpact/constants.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

namespace {

// The rows of one gear's bearing in [bearings] (their names end in the
// gear's number), each only with kind = "elastic".
template <typename BearingSlot>
void add_bearing(std::vector<Field>& rows, int gear, BearingSlot of) {
  Rows r(rows, "bearings");
  const std::string n = gear == 1 ? "1" : "2";
  const Range stiffness = bearing_stiffness_range();
  const Range damping = bearing_damping_range();
  const FieldCondition elastic{"kind", {"elastic"}};
  // A row's key is a string_view: the names live in static storage.
  static const std::array<std::array<const char*, 5>, 2> names{{
      {"stiffness_x1", "stiffness_y1", "damping_x1", "damping_y1", "mass1"},
      {"stiffness_x2", "stiffness_y2", "damping_x2", "damping_y2", "mass2"},
  }};
  const auto& name = names[static_cast<std::size_t>(gear - 1)];
  r.quantity(
       name[0], Dimension::stiffness, "N/um", stiffness, true,
       "k_x of gear " + n + "'s bearing, along the centre line O1 -> O2",
       [of](auto& c) -> auto& { return of(c).stiffness_x_n_per_m; })
      .only_when = elastic;
  Field& ky = r.quantity(
      name[1], Dimension::stiffness, "N/um", stiffness, false,
      "k_y of gear " + n + "'s bearing, across the centre line", [of](auto& c) -> auto& {
        return of(c).stiffness_y_n_per_m;
      });
  ky.only_when = elastic;
  ky.when_absent = gear == 1 ? "stiffness_x1 (isotropic)" : "stiffness_x2 (isotropic)";
  r.quantity(
       name[2], Dimension::damping, "N*s/m", damping, false,
       "c_x of gear " + n +
           "'s bearing; 0: none (simulate uses it; the modes are those of the undamped "
           "system)",
       [of](auto& c) -> auto& { return of(c).damping_x_n_s_per_m; })
      .only_when = elastic;
  Field& cy = r.quantity(
      name[3], Dimension::damping, "N*s/m", damping, false,
      "c_y of gear " + n + "'s bearing", [of](auto& c) -> auto& {
        return of(c).damping_y_n_s_per_m;
      });
  cy.only_when = elastic;
  cy.when_absent = gear == 1 ? "damping_x1 (isotropic)" : "damping_x2 (isotropic)";
  Field& mass = r.quantity(
      name[4], Dimension::mass, "kg", bearing_mass_range(), false,
      "m, the mass of gear " + n + " with what moves with its centre", [of](auto& c) -> auto& {
        return of(c).mass_kg;
      });
  mass.only_when = elastic;
  mass.when_absent = "the disc whose J the torsional model uses, rho pi r^2 L";
}

}  // namespace

void schema_detail::add_support_rows(std::vector<Field>& rows) {
  {
    // The planar model's keys (docs/vibration.md). Every row is left out of
    // a case file at its default, so that files written before they existed
    // keep their bytes.
    Rows r(rows, "bearings");
    r.choice(
         "kind", choices_of(kBearingKinds), false, "how the gears' centres are held",
         [](auto& c) -> auto& { return c.bearings.kind; })
        .written_at_default = false;
    add_bearing(
        rows, 1, [](auto& c) -> auto& { return c.bearings.gear1; });
    add_bearing(
        rows, 2, [](auto& c) -> auto& { return c.bearings.gear2; });
    const FieldCondition elastic{"kind", {"elastic"}};
    Field& gear = r.integer(
        "sensor_gear", {closed(1.0), closed(2.0), "1: the pinion, 2: the wheel"}, false,
        "the gear on whose bearing the accelerometer of the samples sits "
        "(sensor_acceleration_m_per_s2 of the planar samples, simulate --sample-rate)",
        [](auto& c) -> auto& { return c.bearings.sensor_gear; });
    gear.only_when = elastic;
    gear.written_at_default = false;
    // A full turn either way: an angle as a user measures it, clockwise or not.
    Field& angle = r.quantity(
        "sensor_angle", Dimension::angle, "deg", {closed(-2.0 * pi), closed(2.0 * pi), {}}, false,
        "the accelerometer's direction, from x (O1 -> O2) towards y; 90 deg: across the centre "
        "line",
        [](auto& c) -> auto& { return c.bearings.sensor_angle_rad; });
    angle.only_when = elastic;
    angle.written_at_default = false;
  }
  {
    Rows r(rows, "shafts");
    r.choice(
         "kind", choices_of(kShaftKinds), false,
         "whether the torques act on the gears or on a motor and a load behind torsional shafts",
         [](auto& c) -> auto& { return c.shafts.kind; })
        .written_at_default = false;
    // A watch's wheel to a mill's drive; a shaft from nearly free to stiffer than any (the
    // modes lost their order past it), a damper past any shaft's.
    const Range inertia{closed(1e-12), closed(1e6), {}};
    const Range stiffness{closed(1e-3), closed(1e12), {}};
    const Range damping{closed(0.0), closed(1e6), {}};
    const FieldCondition elastic{"kind", {"elastic"}};
    r.quantity(
         "motor_inertia", Dimension::moment_of_inertia, "kg*m^2", inertia, true,
         "J_m, the motor's moment of inertia on the pinion's shaft",
         [](auto& c) -> auto& { return c.shafts.motor_inertia_kg_m2; })
        .only_when = elastic;
    r.quantity(
         "motor_stiffness", Dimension::torsional_stiffness, "N*m/rad", stiffness, true,
         "k_t of the pinion's shaft, between the motor and the pinion",
         [](auto& c) -> auto& { return c.shafts.motor_stiffness_n_m_per_rad; })
        .only_when = elastic;
    r.quantity(
         "motor_damping", Dimension::rotational_damping, "N*m*s/rad", damping, false,
         "c_t of the pinion's shaft; 0: none (simulate uses it; the modes are undamped)",
         [](auto& c) -> auto& { return c.shafts.motor_damping_n_m_s_per_rad; })
        .only_when = elastic;
    r.quantity(
         "load_inertia", Dimension::moment_of_inertia, "kg*m^2", inertia, true,
         "J_L, the load's moment of inertia on the wheel's shaft",
         [](auto& c) -> auto& { return c.shafts.load_inertia_kg_m2; })
        .only_when = elastic;
    r.quantity(
         "load_stiffness", Dimension::torsional_stiffness, "N*m/rad", stiffness, true,
         "k_t of the wheel's shaft, between the wheel and the load",
         [](auto& c) -> auto& { return c.shafts.load_stiffness_n_m_per_rad; })
        .only_when = elastic;
    r.quantity(
         "load_damping", Dimension::rotational_damping, "N*m*s/rad", damping, false,
         "c_t of the wheel's shaft; 0: none (simulate uses it; the modes are undamped)",
         [](auto& c) -> auto& { return c.shafts.load_damping_n_m_s_per_rad; })
        .only_when = elastic;
  }
}

}  // namespace gearimpact
