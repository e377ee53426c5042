// The rows of the case's name and of [gears]: the pair's tooth geometry.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

void schema_detail::add_gear_rows(std::vector<Field>& rows) {
  {
    Field name;
    name.key = "name";
    name.kind = FieldKind::text;
    name.help =
        "names the case in outputs; a case file without it takes the file's stem, a library "
        "case may stay unnamed";
    name.get_text = [](const SimulationCase& c) { return c.name; };
    name.set_text = [](SimulationCase& c, const std::string& value) { c.name = value; };
    rows.push_back(std::move(name));
  }
  Rows r(rows, "gears");
  const Range teeth{closed(4.0), closed(kMostTeeth), {}};
  r.integer(
      "teeth1", teeth, true,
      "Z1, teeth of gear 1 (the driver in the paper); at least 2 ha / sin^2(a0), "
      "below which rack generation undercuts the involute",
      [](auto& c) -> auto& { return c.gears.teeth1; });
  r.integer(
      "teeth2", teeth, true, "Z2, teeth of gear 2; the same limits as teeth1",
      [](auto& c) -> auto& { return c.gears.teeth2; });
  r.quantity(
      "module", Dimension::length, "mm",
      {closed(1e-6), closed(1.0), "1 um (a micro gear) to 1 m (a mill's ring gear is 0.05 m)"},
      true, "m: pitch radius r_i = m Z_i / 2", [](auto& c) -> auto& { return c.gears.module_m; });
  r.quantity(
      "pressure_angle", Dimension::angle, "deg", {open(0.0), closed(pi / 4.0), {}}, true,
      "a0 of the generating rack and of the mesh (standard centre distance)",
      [](auto& c) -> auto& { return c.gears.pressure_angle_rad; });
  r.quantity(
      "face_width", Dimension::length, "mm", {open(0.0), {}, {}}, true,
      "L, the face width (\"thickness of gears\" in the paper)",
      [](auto& c) -> auto& { return c.gears.face_width_m; });
  r.number(
      "addendum_coefficient", {open(0.0), {}, {}}, false,
      "addendum / module, both gears; the pair must also keep its teeth unpointed, "
      "be free of interference and have a contact ratio in [1, 3)",
      [](auto& c) -> auto& { return c.gears.addendum_coefficient; });
  r.quantity(
      "youngs_modulus", Dimension::pressure, "GPa", {open(0.0), {}, {}}, true, "E of both gears",
      [](auto& c) -> auto& { return c.gears.youngs_modulus_pa; });
  r.number(
      "poisson_ratio", {open(-1.0), open(0.5), "both ends excluded"}, true,
      "nu of both gears; (-1, 0.5) is the range of a stable isotropic solid",
      [](auto& c) -> auto& { return c.gears.poisson_ratio; });
  r.quantity(
      "density", Dimension::density, "kg/m^3", {open(0.0), {}, {}}, true,
      "rho of both gears (solid discs on the pitch circle give J1, J2)",
      [](auto& c) -> auto& { return c.gears.density_kg_m3; });
  r.quantity(
      "backlash", Dimension::length, "mm", {closed(0.0), {}, {}}, true,
      "B of (31), along the line of action: half the total play 2B, the teeth touching at "
      "s = +B (drive flank, N1) and s = -B (coast flank, N2); s and the DTE columns of a "
      "sweep (dte_mean_m, s_min_m, s_max_m) include it, the deflection is s - B on N1",
      [](auto& c) -> auto& { return c.gears.backlash_m; });
  r.number(
      "dedendum_coefficient", {open(0.0), {}, {}}, false,
      "the rack's dedendum / module, ha + c: the root radius is r - (ha + c - x) m; only the "
      "models that start the tooth at the root circle see it; above the addendum coefficient",
      [](auto& c) -> auto& { return c.gears.dedendum_coefficient; });
  r.number(
      "profile_shift1", {}, false,
      "x1: the rack's datum line moved out by x1 m (the pair then meshes at its operating "
      "pressure angle); limited by a pointed tip and by undercut, both named when met",
      [](auto& c) -> auto& { return c.gears.profile_shift1; });
  r.number(
      "profile_shift2", {}, false, "x2, as profile_shift1 for gear 2",
      [](auto& c) -> auto& { return c.gears.profile_shift2; });
  r.number(
       "rack_tip_radius_coefficient", {closed(0.0), {}, {}}, false,
       "rho / m of the rack's tip round; it must fit the clearance and the rack's tip land",
       [](auto& c) -> auto& { return c.gears.rack_tip_radius_coefficient; })
      .when_absent = "the full round c / (1 - sin a0), or the largest that fits the tip land";
  r.quantity(
       "bore_diameter1", Dimension::length, "mm", {open(0.0), {}, {}}, false,
       "bore of gear 1, below its root diameter; needed by the fillet-foundation term only",
       [](auto& c) -> auto& { return c.gears.bore_diameter1_m; })
      .when_absent = "no bore given (the foundation term then refuses to run)";
  r.quantity(
       "bore_diameter2", Dimension::length, "mm", {open(0.0), {}, {}}, false,
       "bore of gear 2, as bore_diameter1",
       [](auto& c) -> auto& { return c.gears.bore_diameter2_m; })
      .when_absent = "no bore given (the foundation term then refuses to run)";
  r.quantity(
       "youngs_modulus2", Dimension::pressure, "GPa", {open(0.0), {}, {}}, false,
       "E of gear 2 (Hertz for two materials)",
       [](auto& c) -> auto& { return c.gears.youngs_modulus2_pa; })
      .when_absent = "gear 1's";
  r.number(
       "poisson_ratio2", {open(-1.0), open(0.5), "both ends excluded"}, false, "nu of gear 2",
       [](auto& c) -> auto& { return c.gears.poisson_ratio2; })
      .when_absent = "gear 1's";
  // Helical pairs (docs/helical.md). Case files written before them hold
  // spur pairs, so the writer leaves both keys out at their defaults.
  r.quantity(
       "helix_angle", Dimension::angle, "deg", {closed(0.0), closed(pi / 4.0), {}}, false,
       "beta at the reference cylinder; 0 is the spur pair. Above 0, module, pressure_angle, "
       "the shifts and the rack coefficients are normal-section values; mesh-stiffness, "
       "iso6336, ste and report (with faults too), simulate (the torsional and the planar "
        "model, with friction under the constant law; with modifications by its slices, faults "
        "laid across them, on rigid or elastic bearings) and sweep (the torsional and the planar "
        "model), modes (without faults) and trains (with friction under the constant law; with "
        "modifications by its slices, faults laid across them, bodies on bearings too) take a "
        "helical pair",
       [](auto& c) -> auto& { return c.gears.helix_angle_rad; })
      .written_at_default = false;
  rows.back().keyed_at_default = false;
  r.choice(
       "helix_hand", choices_of(kHelixHands), false,
       "the hand of gear 1's helix (gear 2 has the other); the order in which the face's "
       "slices enter the zone of action",
       [](auto& c) -> auto& { return c.gears.helix_hand; })
      .written_at_default = false;
  rows.back().keyed_at_default = false;
}

}  // namespace gearimpact
