// How a mesh stiffness is computed: the named model (the paper's or one of
// STIFFNESS-MODELS.md section 3), which terms of (29) enter, by which route
// (the tau-form (20)-(24) or the x-form (16)-(19)), with which quadrature rule,
// and the sign of the axial moment. MODEL.md, section Stiffness.
#pragma once

#include <string>
#include <string_view>

#include "gearimpact/numerics/quadrature.hpp"
#include "gearimpact/stiffness/terms.hpp"

namespace gearimpact {

// Two formulations of the same energies: the tau-form integrates (20)-(24)
// over the involute parameter; the x-form integrates (16)-(19) over the tooth
// centre line with every section built from the polar involute (no formula
// shared with the tau-form).
enum class StiffnessRoute { tau_form, x_form };

// The named models (STIFFNESS-MODELS.md section 3).
//  yang_lin_1987: the paper's: Hertz, bending, axial; the involute tooth from
//    the base circle, by the route and rule above.
//  potential_energy: Hertz, bending, shear, axial, fillet foundation; the
//    rack-cut tooth from the root circle (mesh_models.hpp).
//  ross_compatible: potential_energy with ROSS's theta_f and u_f.
// For the last two the route picks the beam integration of tooth_beam.hpp
// (tau_form: over each piece's parameter, Boost Gauss-Kronrod; x_form: over
// the section height, GSL QAG); rule and moment sign do not apply.
enum class StiffnessModelKind { yang_lin_1987, potential_energy, ross_compatible };

// "yang-lin-1987", "potential-energy", "ross-compatible"; parse throws
// InputError naming `field` with the three names.
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
};
bool operator==(const StiffnessModel& a, const StiffnessModel& b);

// Throws InputError unless at least one term the model provides is on and the
// tolerance is in [1e-14, 1e-2].
void validate(const StiffnessModel& model);

// The vocabulary of --method and of case files' stiffness_method: gsl,
// gsl-cquad, boost-gk, boost-ts (the tau-form with that rule), or xform (the
// x-form route with the model's rule). Throws InputError naming `field`.
StiffnessModel with_method(StiffnessModel model, std::string_view name, std::string_view field);
// The term of kTerms whose id is `id` (hertz, bending, axial, ...); throws
// InputError naming `field` and the ids otherwise.
Term term_named(std::string_view id, std::string_view field = "term");

// "xform" for the x-form route, else the rule's name.
std::string method_name(const StiffnessModel& model);

}  // namespace gearimpact
