// The rows of [modifications] (reliefs and tooth errors) and of each [[faults]] table.
#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

namespace {

// The keys of one gear's modifications in [modifications] (their names end in
// the gear's number). Every row is left out of a case file at its default, so
// that files written before these keys existed keep their bytes.
template <typename GearSlot>
void add_modifications(std::vector<Field>& rows, int gear, GearSlot of) {
  Rows r(rows, "modifications");
  const bool one = gear == 1;
  const std::string n = one ? "1" : "2";
  // A relief or an error is micrometres; a millimetre is a typing slip.
  const Range amount{closed(0.0), closed(1e-3), "at most 1 mm: reliefs are micrometres"};
  const Range deviation{closed(-1e-3), closed(1e-3), "within 1 mm: tooth errors are micrometres"};
  const Range diameter{closed(0.0), {}, {}};
  r.quantity(
       one ? "tip_relief1" : "tip_relief2", Dimension::length, "um", amount, false,
       "C_a, the tip relief of gear " + n +
           ": material removed at the tip of both flanks of every tooth, along the line of "
           "action; 0: none",
       [of](auto& c) -> auto& { return of(c).tip.amount_m; })
      .written_at_default = false;
  r.quantity(
       one ? "tip_relief_start1" : "tip_relief_start2", Dimension::length, "mm", diameter, false,
       "d_Ca, the diameter where the tip relief of gear " + n + " starts; with tip_relief" + n +
           " > 0 it lies in the active profile, [d_SAP, d_a) (check-case names the limits)",
       [of](auto& c) -> auto& { return of(c).tip.diameter_m; })
      .written_at_default = false;
  r.choice(
       one ? "tip_relief_shape1" : "tip_relief_shape2", choices_of(kReliefShapes), false,
       "the shape of the tip relief of gear " + n +
           " over its roll length: C_a u^p, u from 0 at d_Ca to 1 at the tip",
       [of](auto& c) -> auto& { return of(c).tip.shape; })
      .written_at_default = false;
  r.quantity(
       one ? "root_relief1" : "root_relief2", Dimension::length, "um", amount, false,
       "C_f, the root relief of gear " + n +
           ": material removed at the start of its active profile (where the mating tip "
           "meets it), both flanks; 0: none",
       [of](auto& c) -> auto& { return of(c).root.amount_m; })
      .written_at_default = false;
  r.quantity(
       one ? "root_relief_end1" : "root_relief_end2", Dimension::length, "mm", diameter, false,
       "d_Cf, the diameter where the root relief of gear " + n + " ends; with root_relief" + n +
           " > 0 it lies in (d_SAP, d_a], at most d_Ca",
       [of](auto& c) -> auto& { return of(c).root.diameter_m; })
      .written_at_default = false;
  r.choice(
       one ? "root_relief_shape1" : "root_relief_shape2", choices_of(kReliefShapes), false,
       "the shape of the root relief of gear " + n + ": C_f u^p, u from 0 at d_Cf to 1 at d_SAP",
       [of](auto& c) -> auto& { return of(c).root.shape; })
      .written_at_default = false;
  // One value per tooth. A case file's lists together bound the TOML parser's work, so the
  // lists of one tooth each stop at 1000 teeth, more than a gear measured tooth by tooth has.
  constexpr std::size_t most = 1000;
  r.quantity_list(
       one ? "pitch_deviations1" : "pitch_deviations2", Dimension::length, "um", deviation, most,
       false,
       "f_p of each tooth of gear " + n +
           ", tooth 0 first (none, or one per tooth): a positive f makes the tooth "
           "meet later on the drive flanks (gap +f) and earlier on the coast flanks "
           "(gap -f)",
       [of](auto& c) -> auto& { return of(c).pitch_m; })
      .written_at_default = false;
  r.quantity_list(
       one ? "thickness_deviations1" : "thickness_deviations2", Dimension::length, "um", deviation,
       most, false,
       "material removed from each flank of each tooth of gear " + n +
           " (the tooth 2 f thinner along the base tangent; negative: thicker), "
           "tooth 0 first",
       [of](auto& c) -> auto& { return of(c).thickness_m; })
      .written_at_default = false;
  r.quantity_list(
       one ? "profile_slope_deviations1" : "profile_slope_deviations2", Dimension::length, "um",
       deviation, most, false,
       "f_Ha of each tooth of gear " + n +
           ", tooth 0 first: a gap rising linearly along the active profile from "
           "-f_Ha/2 at d_SAP to +f_Ha/2 at the tip (0 at the middle of its roll length)",
       [of](auto& c) -> auto& { return of(c).profile_slope_m; })
      .written_at_default = false;
  r.integer(
       one ? "iso1328_class1" : "iso1328_class2",
       {closed(0.0), closed(11.0), "0: none; ISO 1328-1:2013 has the classes 1 to 11"}, false,
       "A, the flank tolerance class of gear " + n +
           " (ISO 1328-1:2013, 1 the finest): draws its pitch and profile slope deviations "
           "within the class's f_pT and f_HalphaT with error_seed, in place of their lists "
           "(docs/faults.md, \"Errors drawn from a tolerance class\"); 0: none",
       [of](auto& c) -> auto& { return of(c).iso1328_class; })
      .written_at_default = false;
  // The lead modifications (helical pairs): neither written nor keyed at their defaults, so
  // that every file without them keeps its bytes and its case key.
  const auto lead = [&rows](Field& field) {
    field.written_at_default = false;
    field.keyed_at_default = false;
    (void)rows;
  };
  lead(r.quantity(
      one ? "crowning1" : "crowning2", Dimension::length, "um", amount, false,
      "C_beta, the crowning of gear " + n +
          " (helical pairs): C_beta (2u)^2 across the face, u = y/b - 1/2, on both flanks of "
          "every tooth, along the transverse line of action; 0: none",
      [of](auto& c) -> auto& { return of(c).lead.crowning_m; }));
  lead(r.quantity(
      one ? "end_relief_i1" : "end_relief_i2", Dimension::length, "um", amount, false,
      "C_I, the end relief of gear " + n +
          " at the face end y = 0 (helical pairs): C_I ((l_I - y) / l_I)^p for y < l_I, both "
          "flanks; 0: none",
      [of](auto& c) -> auto& { return of(c).lead.end_relief_i_m; }));
  lead(r.quantity(
      one ? "end_relief_i_length1" : "end_relief_i_length2", Dimension::length, "mm", diameter,
      false,
      "l_I, the length across the face of the end relief end_relief_i" + n +
          "; with it > 0 in (0, b]",
      [of](auto& c) -> auto& { return of(c).lead.end_relief_i_length_m; }));
  lead(r.quantity(
      one ? "end_relief_ii1" : "end_relief_ii2", Dimension::length, "um", amount, false,
      "C_II, the end relief of gear " + n +
          " at the face end y = b (helical pairs): C_II ((y - b + l_II) / l_II)^p for "
          "y > b - l_II, both flanks; 0: none",
      [of](auto& c) -> auto& { return of(c).lead.end_relief_ii_m; }));
  lead(r.quantity(
      one ? "end_relief_ii_length1" : "end_relief_ii_length2", Dimension::length, "mm", diameter,
      false,
      "l_II, the length across the face of the end relief end_relief_ii" + n +
          "; with it > 0 in (0, b - l_I]",
      [of](auto& c) -> auto& { return of(c).lead.end_relief_ii_length_m; }));
  lead(r.choice(
      one ? "end_relief_shape1" : "end_relief_shape2", choices_of(kReliefShapes), false,
      "the shape p of both end reliefs of gear " + n + " across the face", [of](auto& c) -> auto& {
        return of(c).lead.end_relief_shape;
      }));
  lead(r.quantity(
      one ? "helix_slope_deviation1" : "helix_slope_deviation2", Dimension::length, "um", deviation,
      false,
      "f_Hbeta of every tooth of gear " + n +
          " (helical pairs), a wrong helix angle: a gap f_Hbeta u on the drive flanks (N1) and "
          "-f_Hbeta u on the coast flanks (N2), u = y/b - 1/2, along the transverse line of "
          "action (convert ISO 1328's sign and evaluation range first); 0: none",
      [of](auto& c) -> auto& { return of(c).lead.helix_slope_m; }));
}

// The rows of one [[faults]] table. Their slots read the first fault of a
// case: the reader and the writer pass each fault in a case of its own.
std::vector<Field> make_fault_schema() {
  std::vector<Field> rows;
  Rows r(rows, "faults");
  const auto fault = [](auto& c) -> auto& {
    return c.faults.front();
  };
  r.choice(
      "gear",
      {choice("pinion", Gear::one, "gear 1, the driving pinion"),
       choice("wheel", Gear::two, "gear 2")},
      true,
      "the gear the faulted tooth belongs to", [fault](auto& c) -> auto& { return fault(c).gear; });
  r.integer(
      "tooth", {closed(0.0), closed(kMostTeeth - 1.0), "and below the gear's number of teeth"},
      true,
      "the tooth's number in mesh order, 0 ... z-1 (docs/faults.md, Tooth identity); "
      "one fault per tooth",
      [fault](auto& c) -> auto& { return fault(c).tooth; });
  r.choice(
      "kind",
      {choice("root-crack", ToothKind::root_crack,
              "a crack from the root (Tian 2004; Chen & Shao 2011 across the face)"),
       choice("missing", ToothKind::missing, "the tooth is gone: its pair carries nothing"),
       choice("spall", ToothKind::spall,
              "a pit on one flank over part of the active profile and of the face"),
       choice("tip-chip", ToothKind::tip_chip,
              "the tooth above a radius gone over part of the face, from one edge")},
      true, "the tooth's fault", [fault](auto& c) -> auto& { return fault(c).state.kind; });
  const auto crack = [fault](auto& c) -> auto& {
    return fault(c).state.crack;
  };
  r.quantity(
       "depth", Dimension::length, "mm", {closed(0.0), {}, {}}, true,
       "q of a uniform crack, q0 (at the start edge) of the width profiles; q sin nu < h_c, "
       "the half thickness where the crack starts",
       [crack](auto& c) -> auto& { return crack(c).depth_m; })
      .only_when = FieldCondition{"kind", {"root-crack"}};
  r.quantity(
       "angle", Dimension::angle, "deg", {open(0.0), closed(0.5 * pi), {}}, true,
       "nu, between the crack and the tooth centre line",
       [crack](auto& c) -> auto& { return crack(c).angle_rad; })
      .only_when = FieldCondition{"kind", {"root-crack"}};
  r.choice(
       "profile",
       {choice("uniform", CrackProfile::uniform, "q across the whole face"),
        choice("partial-width", CrackProfile::partial_width,
               "q0 sqrt((W_c - z) / W_c) up to width W_c"),
        choice("full-width", CrackProfile::full_width,
               "sqrt((q2^2 - q0^2) z / b + q0^2), q2 the end_depth")},
       false,
       "how the depth runs across the face", [crack](auto& c) -> auto& { return crack(c).profile; })
      .only_when = FieldCondition{"kind", {"root-crack"}};
  r.quantity(
       "end_depth", Dimension::length, "mm", {closed(0.0), {}, {}}, true,
       "q2, the depth at the far edge of the face",
       [crack](auto& c) -> auto& { return crack(c).end_depth_m; })
      .only_when = FieldCondition{"profile", {"full-width"}};
  r.quantity(
       "width", Dimension::length, "mm", {open(0.0), {}, "and at most the face width"}, true,
       "W_c, how far across the face the crack runs",
       [crack](auto& c) -> auto& { return crack(c).width_m; })
      .only_when = FieldCondition{"profile", {"partial-width"}};
  Field& start = r.quantity(
      "start_radius", Dimension::length, "mm", {open(0.0), {}, {}}, false,
      "r_s, where the crack starts on the flank; potential-energy and ross-compatible only",
      [crack](auto& c) -> auto& { return crack(c).start_radius_m; });
  start.only_when = FieldCondition{"kind", {"root-crack"}};
  start.when_absent =
      "the fillet point whose tangent makes 30 deg with the centre line (potential-energy, "
      "ross-compatible); the base circle (yang-lin-1987)";
  // A spall and a chip (surface_faults.hpp). depth, width and start_radius
  // share their keys with the crack's rows: one row of a key applies to a
  // fault, by its kind (fault_row_applies).
  const auto spall = [fault](auto& c) -> auto& {
    return fault(c).state.spall;
  };
  r.quantity(
       "depth", Dimension::length, "mm", {closed(0.0), {}, {}}, true,
       "d_s, how deep the pit reaches into the tooth, normal to its centre line; below the "
       "half thickness of the tooth at the thinner end of the spall",
       [spall](auto& c) -> auto& { return spall(c).depth_m; })
      .only_when = FieldCondition{"kind", {"spall"}};
  r.quantity(
       "width", Dimension::length, "mm", {open(0.0), {}, "and at most the face width"}, true,
       "b_s of a spall, b_k of a chip: how far across the face it runs, up to the face width "
       "(docs/faults.md: across the whole face its pair has no contact over the spall's band, "
       "or above the chip's radius)",
       [fault](auto& c) -> auto& {
         return fault(c).state.kind == ToothKind::tip_chip ? fault(c).state.chip.width_m
                                                           : fault(c).state.spall.width_m;
       })
      .only_when = FieldCondition{"kind", {"spall", "tip-chip"}};
  // Left out of written files and case keys at 0, so that every file without
  // it keeps its bytes and its key.
  Field& face_start = r.quantity(
      "face_start", Dimension::length, "mm", {closed(0.0), {}, "and face_start + width <= b"},
      false,
      "helical pairs: where the spall's or the chip's band across the face begins, from the "
      "face end at smaller z (y = 0); it covers [face_start, face_start + width) "
      "(docs/helical.md, Faults); 0 on a spur pair, whose teeth do not depend on it",
      [fault](auto& c) -> auto& { return fault(c).state.face_start_m; });
  face_start.only_when = FieldCondition{"kind", {"spall", "tip-chip"}};
  face_start.written_at_default = false;
  face_start.keyed_at_default = false;
  r.quantity(
       "start_radius", Dimension::length, "mm", {open(0.0), {}, "and on the active profile"}, true,
       "where the spall begins: the radius of its lower edge on the flank, on the active "
       "profile (from where the mating tip meets the flank to below the tip)",
       [spall](auto& c) -> auto& { return spall(c).start_radius_m; })
      .only_when = FieldCondition{"kind", {"spall"}};
  r.quantity(
       "end_radius", Dimension::length, "mm", {open(0.0), {}, "above start_radius, up to the tip"},
       true, "where the spall ends: the radius of its upper edge on the flank",
       [spall](auto& c) -> auto& { return spall(c).end_radius_m; })
      .only_when = FieldCondition{"kind", {"spall"}};
  r.choice(
       "flank",
       {choice("drive", CrackFlank::loaded,
               "the flank that carries the load when the pinion drives (line of action N1)"),
        choice("coast", CrackFlank::unloaded, "the other flank (line of action N2)")},
       false,
       "the flank the pit is on: a contact on the other flank keeps its whole length, the "
       "sections lose the pit all the same",
       [spall](auto& c) -> auto& { return spall(c).flank; })
      .only_when = FieldCondition{"kind", {"spall"}};
  r.quantity(
       "radius", Dimension::length, "mm", {open(0.0), {}, "above the root, up to the tip"}, true,
       "r_k: the tooth above this radius is gone over the chip's width, on both flanks",
       [fault](auto& c) -> auto& { return fault(c).state.chip.radius_m; })
      .only_when = FieldCondition{"kind", {"tip-chip"}};
  return rows;
}

}  // namespace

void schema_detail::add_modification_rows(std::vector<Field>& rows) {
  add_modifications(
      rows, 1, [](auto& c) -> auto& { return c.modifications.gear1; });
  add_modifications(
      rows, 2, [](auto& c) -> auto& { return c.modifications.gear2; });
  Rows(rows, "modifications")
      .integer(
          "error_seed", {closed(0.0), closed(4294967295.0), "a 32-bit unsigned integer"}, false,
          "the seed of the tooth errors iso1328_class1 and iso1328_class2 draw: the same seed, "
          "the same teeth, bit for bit",
          [](auto& c) -> auto& { return c.modifications.error_seed; })
      .written_at_default = false;
  // A misalignment is milliradians; a degree is a slip of the unit.
  const Range tilt{closed(-pi / 180.0), closed(pi / 180.0),
                   "within 1 deg: misalignments are milliradians"};
  for (const auto& [key, help, slot] :
       {std::tuple{"misalignment_x",
                   "gamma_x, the wheel axis tilted against the pinion's in the plane of the axes "
                   "(helical pairs): the wheel's section centre moves away from the pinion as y "
                   "grows; gaps b u gamma_x sin(alpha_wt) on both flanks",
                   &Misalignment::gamma_x_rad},
        std::tuple{"misalignment_y",
                   "gamma_y, the wheel axis tilted across the plane of the axes (helical "
                   "pairs): the wheel's section centre moves along +y as y grows; gaps "
                   "+b u gamma_y cos(alpha_wt) on the drive flanks, - on the coast flanks",
                   &Misalignment::gamma_y_rad}}) {
    Field& field =
        Rows(rows, "modifications")
            .quantity(
                key, Dimension::angle, "deg", tilt, false, help, [slot = slot](auto& c) -> auto& {
                  return c.modifications.misalignment.*slot;
                });
    field.written_at_default = false;
    field.keyed_at_default = false;
  }
}

const std::vector<Field>& fault_schema() {
  static const std::vector<Field> rows = make_fault_schema();
  return rows;
}

bool fault_row_applies(const Field& field, const SimulationCase& one_fault) {
  if (!field.only_when) return true;
  for (const Field& selector : fault_schema()) {
    if (selector.key != field.only_when->key) continue;
    if (!fault_row_applies(selector, one_fault)) return false;
    const double code = selector.get(one_fault);
    for (const ChoiceName& c : selector.choices) {
      if (c.code != code) continue;
      const auto& choices = field.only_when->choices;
      return std::find(choices.begin(), choices.end(), c.name) != choices.end();
    }
  }
  return false;
}

}  // namespace gearimpact
