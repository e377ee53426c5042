// How a mesh stiffness is computed: the named model (the paper's or one of
// docs/stiffness-models.md section 3), which terms of (29) enter, by which route
// (the tau-form (20)-(24) or the x-form (16)-(19)), with which quadrature rule,
// and the sign of the axial moment. docs/model.md, section Stiffness.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "gearimpact/named_values.hpp"
#include "gearimpact/numerics/quadrature.hpp"
#include "gearimpact/stiffness/terms.hpp"

namespace gearimpact {

// Two formulations of the same energies: the tau-form integrates (20)-(24)
// over the involute parameter; the x-form integrates (16)-(19) over the tooth
// centre line with every section built from the polar involute (no formula
// shared with the tau-form).
enum class StiffnessRoute { tau_form, x_form };

// The named models (docs/stiffness-models.md section 3).
//  yang_lin_1987: the paper's: Hertz, bending, axial; the involute tooth from
//    the base circle, by the route and rule above.
//  potential_energy: Hertz, bending, shear, axial, fillet foundation; the
//    rack-cut tooth from the root circle (mesh_models.hpp).
//  ross_compatible: potential_energy with ROSS's theta_f and u_f.
// For the last two the route picks the beam integration of tooth_beam.hpp
// (tau_form: over each piece's parameter, Boost Gauss-Kronrod; x_form: over
// the section height, GSL QAG); rule and moment sign do not apply.
enum class StiffnessModelKind { yang_lin_1987, potential_energy, ross_compatible };

// The names of case files' stiffness_model and of --model.
inline constexpr std::array<NamedValue<StiffnessModelKind>, 3> kStiffnessModels{{
    {StiffnessModelKind::yang_lin_1987, "yang-lin-1987",
     "the paper's: involute from the base circle, Hertz, bending, axial"},
    {StiffnessModelKind::potential_energy, "potential-energy",
     "trochoid + involute from the root circle, Hertz, bending, shear, axial, fillet foundation "
     "(needs both bores)"},
    {StiffnessModelKind::ross_compatible, "ross-compatible",
     "potential-energy with the ROSS gear element's two conventions"},
}};

// By kStiffnessModels; parse throws InputError naming `field` with the names.
StiffnessModelKind parse_stiffness_model(std::string_view name, std::string_view field);
std::string to_string(StiffnessModelKind kind);

// Whether the model has the term at all (yang_lin_1987: hertz, bending,
// axial; the others every term). A term enters Ke when the model provides it
// and its switch is on.
bool provides(StiffnessModelKind kind, Term term);

// The sign of the axial-force moment in M = Fb (l - x) -/+ Fa h. `physical` is
// the printed (14): the axial component, offset h towards the loaded flank,
// unbends the tooth. `flipped` adds it instead, as a possible slip in the
// authors' program (see the reproduction report).
enum class AxialMomentSign { physical, flipped };
inline constexpr std::array<NamedValue<AxialMomentSign>, 2> kMomentSigns{{
    {AxialMomentSign::physical, "physical", "M = Fb (l - x) - Fa h as printed"},
    {AxialMomentSign::flipped, "flipped", "M = Fb (l - x) + Fa h (not physical)"},
}};
// By kMomentSigns; parse throws InputError naming `field` with the names.
AxialMomentSign parse_moment_sign(std::string_view name, std::string_view field);
std::string to_string(AxialMomentSign sign);

// How a partial-width spall's contact (the length b - b_s it leaves) loads the
// teeth (docs/faults.md, "A pair's compliance"; docs/verification.md, "The
// spall in 3-D"). hertz_only: Hertz (4) over b - b_s, the beam and the
// foundation over the whole face. effective_width: the rack-cut models'
// bending, shear, axial and foundation terms of both teeth over the width the
// load spreads to (spall_width_factors, surface_faults.hpp). by_model, the
// default: effective_width for the rack-cut models, which the 3-D finite
// elements checked on three pairs, and hertz_only for yang_lin_1987, whose
// tooth from the base circle has no root thickness or foundation to spread by.
enum class SpallReading { by_model, hertz_only, effective_width };
inline constexpr std::array<NamedValue<SpallReading>, 3> kSpallReadings{{
    {SpallReading::by_model, "by-model",
     "effective-width with potential-energy and ross-compatible, hertz-only with yang-lin-1987"},
    {SpallReading::hertz_only, "hertz-only",
     "Hertz over b - b_s, the beam and foundation over the whole face"},
    {SpallReading::effective_width, "effective-width",
     "also each tooth's beam and foundation over the width the load spreads to (the 3-D "
     "finite elements' reading; potential-energy and ross-compatible)"},
}};
SpallReading parse_spall_reading(std::string_view name, std::string_view field);
std::string to_string(SpallReading reading);

// How a helical pair's slice sees the inclined contact line in its Hertzian
// term (docs/helical.md, section The slice model).
enum class HelicalHertz { projected, face_width };
inline constexpr std::array<NamedValue<HelicalHertz>, 2> kHelicalHertz{{
    {HelicalHertz::projected, "projected",
     "c_H cos(beta_b): the slice's contact line is db / cos(beta_b) long and its approach the "
     "transverse one times cos(beta_b)"},
    {HelicalHertz::face_width, "face-width", "c_H: each slice a plain spur pair of its width"},
}};
// The most slices across a helical pair's face (model.face_slices).
inline constexpr int kMostFaceSlices = 4096;

struct StiffnessModel {
  StiffnessModelKind kind = StiffnessModelKind::yang_lin_1987;
  StiffnessRoute route = StiffnessRoute::tau_form;
  QuadratureRule rule = QuadratureRule::gsl_qag;
  AxialMomentSign moment_sign = AxialMomentSign::physical;
  // Requested of every rule. 1e-12 is within reach of all of them at every
  // contact position (tanh-sinh's level-difference estimate stalls near
  // 1e-13 on these integrands although its result is better).
  double relative_tolerance = 1e-12;
  TermSet terms;
  SpallReading spall_reading = SpallReading::by_model;
  // A helical pair's slices across the face (route A, midpoint rule) and
  // their Hertzian term; a spur pair ignores both.
  int face_slices = 32;
  HelicalHertz helical_hertz = HelicalHertz::projected;
};
bool operator==(const StiffnessModel& a, const StiffnessModel& b);

// Throws InputError unless at least one term the model provides is on,
// naming the switch of the first (hertz_term, or section.hertz_term for a
// non-empty `section`). The ranges of the other
// fields are the case schema's (validate(const StiffnessModel&) of
// case/schema.hpp checks both).
void validate_terms(const StiffnessModel& model, std::string_view section = {});
// Throws InputError naming spall_reading (section.spall_reading for a
// non-empty `section`) for effective_width with yang_lin_1987: the reading's
// spread is the rack-cut tooth's (its root thickness, its foundation), which
// the paper's tooth from the base circle does not have.
void check_spall_reading(const StiffnessModel& model, std::string_view section = {});
// The reading a model applies: by_model resolved by its kind (above), the others as given.
SpallReading applied_spall_reading(const StiffnessModel& model);

// A method of --method and of case files' stiffness_method: a route, and
// for the tau-form the rule it integrates with.
struct StiffnessMethod {
  StiffnessRoute route;
  QuadratureRule rule;  // of the tau-form; the x-form keeps the model's (xform_rule)
  std::string_view name;
  std::string_view meaning;
};
// The tau-form with each rule, named as the rule (kQuadratureRules, in the
// order of QuadratureRule), then the x-form route.
inline constexpr std::array<StiffnessMethod, 5> kStiffnessMethods{{
    {StiffnessRoute::tau_form, QuadratureRule::gsl_qag, kQuadratureRules[0].name,
     "GSL QAG on the tau-form"},
    {StiffnessRoute::tau_form, QuadratureRule::gsl_cquad, kQuadratureRules[1].name,
     "GSL CQUAD on the tau-form"},
    {StiffnessRoute::tau_form, QuadratureRule::boost_gauss_kronrod, kQuadratureRules[2].name,
     "Boost Gauss-Kronrod on the tau-form"},
    {StiffnessRoute::tau_form, QuadratureRule::boost_tanh_sinh, kQuadratureRules[3].name,
     "Boost tanh-sinh on the tau-form"},
    {StiffnessRoute::x_form, QuadratureRule::gsl_qag, "xform", "the x-form route (16)-(19)"},
}};

static_assert(kQuadratureRules[0].value == QuadratureRule::gsl_qag &&
                  kQuadratureRules[1].value == QuadratureRule::gsl_cquad &&
                  kQuadratureRules[2].value == QuadratureRule::boost_gauss_kronrod &&
                  kQuadratureRules[3].value == QuadratureRule::boost_tanh_sinh,
              "kStiffnessMethods names the tau-form's methods by kQuadratureRules' order");

// The model with the method named `name` of kStiffnessMethods (the x-form
// keeps the model's rule). Throws InputError naming `field` with the names.
StiffnessModel with_method(StiffnessModel model, std::string_view name, std::string_view field);
// The term of kTerms whose id is `id` (hertz, bending, axial, ...); throws
// InputError naming `field` and the ids otherwise.
Term term_named(std::string_view id, std::string_view field = "term");

// The name in kStiffnessMethods of the model's route and rule.
std::string method_name(const StiffnessModel& model);

}  // namespace gearimpact
