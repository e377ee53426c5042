// The rows of [model]: the mesh stiffness, damping, friction and contact models.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

void schema_detail::add_model_rows(std::vector<Field>& rows) {
  Rows r(rows, "model");
  r.number(
      "friction_coefficient", {closed(0.0), closed(1.0), {}}, false,
      "f of (35): Ff = f N against the sliding speed; at most 1: dry steel on steel stays "
      "below about 0.8, lubricated teeth below 0.1, and a larger f is no tooth contact; the f of "
      "friction_law = \"constant\"",
      [](auto& c) -> auto& { return c.model.friction_coefficient; });
  // The friction laws. Case files written before they existed hold the
  // constant law, so the writer leaves the keys out at their defaults.
  r.choice(
       "friction_law", choices_of(kFrictionLaws), false,
       "where f of (35) comes from: friction_coefficient, or the Benedict and Kelley (1961) "
       "coefficient at each pair's load and speeds (docs/model.md, section Contact, damping, "
       "friction)",
       [](auto& c) -> auto& { return c.model.friction_law; })
      .written_at_default = false;
  r.quantity(
       "lubricant_viscosity", Dimension::viscosity, "cP", {open(0.0), {}, {}}, true,
       "nu0, the lubricant's dynamic viscosity at the teeth, in Benedict and Kelley's (1961) "
       "f = 0.0127 C_R log10(3.17e8 (W/F) / (nu0 Vs Ve^2)) (He, Gunda and Singh, J. Sound "
       "Vib. 2007)",
       [](auto& c) -> auto& { return c.model.benedict_kelley.viscosity_pa_s; })
      .only_when = FieldCondition{"friction_law", {"benedict-kelley"}};
  r.quantity(
       "surface_roughness", Dimension::length, "um",
       {closed(0.0), open(1.27e-6),
        "C_R = 50 / (50 - S) of Benedict and Kelley diverges at S = 50 micro-inches"},
       true,
       "S, the mean surface roughness of the flanks, in C_R = 50 / (50 - S) of Benedict "
       "and Kelley (1961)",
       [](auto& c) -> auto& { return c.model.benedict_kelley.roughness_m; })
      .only_when = FieldCondition{"friction_law", {"benedict-kelley"}};
  r.number(
       "friction_coefficient_max", {open(0.0), closed(1.0), {}}, false,
       "f_max: Benedict and Kelley's f is clipped to [0, f_max], since it diverges at the "
       "pitch point (Vs -> 0) and is negative where its log argument falls below 1; "
       "default 0.1, the top of lubricated teeth",
       [](auto& c) -> auto& { return c.model.benedict_kelley.most_coefficient; })
      .only_when = FieldCondition{"friction_law", {"benedict-kelley"}};
  // The table law's two lists, one entry per point, of one length
  // (validate_relations). A lookup is a binary search, so the bound is on
  // the case file's size (its lists together bound the values a case file
  // holds), not on the run's cost: a measured friction curve has tens of points.
  constexpr std::size_t kMostFrictionTableEntries = 1000;
  r.number_list(
       "friction_table_slide_to_roll", {}, kMostFrictionTableEntries, true,
       "the slide-to-roll ratios 2 Vs / Ve of the friction table, strictly increasing (0 at the "
       "pitch point when the gears roll, negative where the pinion's flank slides slower); f "
       "is linear between them and constant beyond the first and the last",
       [](auto& c) -> auto& { return c.model.friction_table.slide_to_roll; })
      .only_when = FieldCondition{"friction_law", {"table"}};
  r.number_list(
       "friction_table_coefficients", {closed(0.0), closed(1.0), {}}, kMostFrictionTableEntries,
       true,
       "f at each of friction_table_slide_to_roll, as many; at most 1, as friction_coefficient",
       [](auto& c) -> auto& { return c.model.friction_table.coefficient; })
      .only_when = FieldCondition{"friction_law", {"table"}};
  r.quantity(
       "friction_smoothing_speed", Dimension::speed, "m/s",
       {closed(0.0), closed(0.1),
        "at most 0.1 m/s: a band a small part of the sliding speeds (tenths of m/s and "
        "more on a flank); a wider one turns the friction into a weak viscous f N Vs / v_s "
        "and removes most of it"},
       false,
       "v_s of Ff = f N tanh(Vs / v_s), which replaces sign(Vs) of (35) and so the "
       "friction-reversal event; 0 keeps the exact switch (the paper's). A fixed step h "
       "needs v_s >= 10 h Rb1 |w1| (|w1| + |w2|): 20 steps across the band 2 v_s",
       [](auto& c) -> auto& { return c.model.friction_smoothing_speed_m_s; })
      .written_at_default = false;
  r.choice(
      "damping_form", choices_of(kDampingForms), false, "form of the damping factor D of (32)",
      [](auto& c) -> auto& { return c.model.damping_form; });
  r.choice(
      "damping_stiffness", choices_of(kDampingStiffnesses), false, "the stiffness K in (32)",
      [](auto& c) -> auto& { return c.model.damping_stiffness; });
  r.number(
      "restitution_coefficient", {closed(0.0), closed(1.0), {}}, false,
      "c of (33) e = 1 - c (Vi / speed unit)^p; at most 1: above it e < 0 at every impact "
      "faster than the speed unit. e is held at 0 (a fully plastic impact) for Vi above "
      "speed unit c^(-1/p), where (33) would give e < 0",
      [](auto& c) -> auto& { return c.model.restitution.coefficient; });
  r.number(
      "restitution_exponent", {open(0.0), closed(1.0), {}}, false,
      "p of (33): above 0 so that e falls as Vi grows; the published laws lie in "
      "(0, 1], from 1/5 (Hertzian viscoelastic contact) to 1 (Hunt and Crossley's "
      "linear e); the paper reads 3/8 or 0.36",
      [](auto& c) -> auto& { return c.model.restitution.exponent; });
  r.quantity(
      "restitution_speed_unit", Dimension::speed, "mm/s", {open(0.0), {}, {}}, false,
      "the unit Vi is measured in for (33): mm/s, the paper's length unit, or 1 in/s, "
      "1 m/s",
      [](auto& c) -> auto& { return c.model.restitution.speed_unit_m_s; });
  r.choice(
      "coast_phase", choices_of(kCoastPhases), false, "where the coast-flank contacts sit",
      [](auto& c) -> auto& { return c.model.coast_phase; });
  r.choice(
      "stiffness_model", choices_of(kStiffnessModels), false,
      "the mesh-stiffness model (docs/stiffness-models.md, section 3); a planetary stage's ring "
      "meshes take ISO 6336-1's table unless potential-energy (docs/planetary.md)",
      [](auto& c) -> auto& { return c.model.stiffness.kind; });
  r.choice(
      "moment_sign", choices_of(kMomentSigns), false,
      "sign of the axial-force moment in the bending stiffness",
      [](auto& c) -> auto& { return c.model.stiffness.moment_sign; });
  r.choice(
       "spall_reading", choices_of(kSpallReadings), false,
       "how a partial-width spall's contact loads the teeth (docs/faults.md)",
       [](auto& c) -> auto& { return c.model.stiffness.spall_reading; })
      .written_at_default = false;
  // Helical pairs (docs/helical.md); spur case files leave both out.
  r.integer(
       "face_slices", {closed(1.0), closed(kMostFaceSlices), {}}, false,
       "N, the slices across a helical pair's face (route A, midpoint rule; route B is the "
       "exact face integral), and the sub-bands (at most 64) of uniform depth of a crack "
       "whose depth varies across a helical face; a spur pair ignores it",
       [](auto& c) -> auto& { return c.model.stiffness.face_slices; })
      .written_at_default = false;
  rows.back().keyed_at_default = false;
  r.choice(
       "helical_hertz", choices_of(kHelicalHertz), false,
       "a helical slice's Hertzian term: projected on the inclined contact line, or face-width "
       "(each slice a plain spur pair); a spur pair ignores it",
       [](auto& c) -> auto& { return c.model.stiffness.helical_hertz; })
      .written_at_default = false;
  rows.back().keyed_at_default = false;
  // stiffness_method names the tau-form with a quadrature rule, or the
  // x-form route; xform_rule the rule of the x-form route (used only then).
  // The tau-form's methods have their rule's code, the x-form one past them.
  constexpr int xform_code = static_cast<int>(kQuadratureRules.size());
  std::vector<ChoiceName> rules;
  std::vector<ChoiceName> methods;
  for (const StiffnessMethod& m : kStiffnessMethods) {
    if (m.route == StiffnessRoute::tau_form) {
      rules.push_back(choice(m.name, m.rule, m.meaning));
      methods.push_back(rules.back());
    } else {
      methods.push_back({m.name, xform_code, m.meaning, true});
    }
  }
  Field& method = r.choice(
      "stiffness_method", methods, false, "how the per-tooth terms are integrated",
      [](auto& c) -> auto& { return c.model.stiffness.route; });
  method.get = [](const SimulationCase& c) {
    const StiffnessModel& k = c.model.stiffness;
    return static_cast<double>(k.route == StiffnessRoute::x_form ? xform_code
                                                                 : static_cast<int>(k.rule));
  };
  method.set = [](SimulationCase& c, double code) {
    StiffnessModel& k = c.model.stiffness;
    if (static_cast<int>(code) == xform_code) {
      k.route = StiffnessRoute::x_form;
    } else {
      k.route = StiffnessRoute::tau_form;
      k.rule = static_cast<QuadratureRule>(static_cast<int>(code));
    }
  };
  Field& xform_rule = r.choice(
      "xform_rule", rules, false,
      "the rule the x-form route integrates with (one of the tau-form rules); used only "
      "with stiffness_method = \"xform\"",
      [](auto& c) -> auto& { return c.model.stiffness.rule; });
  xform_rule.set = [](SimulationCase& c, double code) {
    StiffnessModel& k = c.model.stiffness;
    if (k.route == StiffnessRoute::x_form)
      k.rule = static_cast<QuadratureRule>(static_cast<int>(code));
  };
  r.number(
      "stiffness_tolerance", {closed(1e-14), closed(1e-2), {}}, false,
      "relative tolerance of every quadrature of Ke: 1e-14 is a few ulps of the "
      "compliances, 1e-2 a rough run",
      [](auto& c) -> auto& { return c.model.stiffness.relative_tolerance; });
  for (const TermInfo& t : kTerms) {
    r.on_off(
        t.switch_key, std::string(t.description) + " of (29) in Ke (at least one term stays on)",
        [index = index_of(t.term)](auto& c) -> auto& { return c.model.stiffness.terms.on[index]; });
  }
  // The steady-state model's options. Case files written before they
  // existed hold their defaults, so the writer leaves them out at those.
  r.choice(
       "mesh_stiffness", choices_of(kMeshStiffnessModes), false,
       "the mesh stiffness of the dynamics",
       [](auto& c) -> auto& { return c.model.mesh_stiffness; })
      .written_at_default = false;
  r.quantity(
       "constant_mesh_stiffness", Dimension::stiffness, "N/um", {open(0.0), {}, {}}, true,
       "k, the total mesh stiffness along the line of action",
       [](auto& c) -> auto& { return c.model.constant_mesh_stiffness_n_per_m; })
      .only_when = FieldCondition{"mesh_stiffness", {"constant"}};
  r.choice(
       "mesh_force", choices_of(kMeshForces), false,
       "how the mesh force follows from the time-varying stiffness (docs/model.md, section "
       "Energies)",
       [](auto& c) -> auto& { return c.model.mesh_force; })
      .written_at_default = false;
  r.number(
       "mesh_damping_ratio", {closed(0.0), closed(1.0), {}}, false,
       "zeta of the viscous mesh damper c = 2 zeta sqrt(k_mean m_e) on s', in contact and in "
       "the backlash; 0 leaves it out. At most 1 (critical damping): the RK4 step, set by the "
       "stiffness alone, resolves the damper's time constant only up to a few times critical",
       [](auto& c) -> auto& { return c.model.mesh_damping_ratio; })
      .written_at_default = false;
  r.choice(
       "damping_update", choices_of(kDampingUpdates), false,
       "when the Hertzian damping factor D of (32) is set",
       [](auto& c) -> auto& { return c.model.damping_update; })
      .written_at_default = false;
  Field& reference = r.quantity(
      "damping_reference_speed", Dimension::speed, "m/s", {open(0.0), {}, {}}, false,
      "V_ref: the impact speed of the frozen D (damping_update = \"frozen\", or \"auto\" "
      "with elastic bearings)",
      [](auto& c) -> auto& { return c.model.damping_reference_speed_m_s; });
  reference.only_when = FieldCondition{"damping_update", {"frozen", "auto"}};
  // Left out at its default, so that a case written under "auto" keeps the
  // bytes it had when the row applied under "frozen" only.
  reference.written_at_default = false;
}

}  // namespace gearimpact
