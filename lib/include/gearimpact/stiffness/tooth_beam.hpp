// The tooth as a beam on its centre line, loaded at a flank point along the
// normal there: bending, shear and axial compliances by the potential-energy
// method (docs/stiffness-models.md, section 2), over any flank made of smooth
// parametric pieces. Two independent routes compute every integral.
#pragma once

#include <functional>
#include <vector>

#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/model.hpp"

namespace gearimpact {

// One smooth piece of the flank (x half thickness, y height along the centre
// line), with y strictly increasing from parameter_root to parameter_top
// (either may be the larger number: the trochoid's gamma falls as y rises).
struct FlankPiece {
  std::function<ProfilePoint(double)> point;
  double parameter_root;
  double parameter_top;
};

// The contact point (x_t, y_t) and the angle tau between the load line (the
// flank normal) and the x axis: the load has the component F cos tau across
// the tooth and F sin tau along it, towards the root.
struct BeamLoad {
  double x_m;
  double y_m;
  double tau_rad;
};

struct BeamMaterial {
  double youngs_modulus_pa;
  double shear_modulus_pa;
  double width_m;
};

// The two routes of StiffnessRoute (model.hpp), for a flank of pieces:
// tau_form: each piece integrated over its own parameter, dy = y'(p) dp, with
//   Boost's adaptive Gauss-Kronrod (61 points).
// x_form: each piece integrated over the height y, the section at y found by
//   solving y(p) = y (TOMS 748), with GSL QAG (61-point Gauss-Kronrod,
//   globally adaptive: x(y) near the root circle behaves like a square root
//   of a point just below it, which needs many subintervals).
// They share the flank's points and nothing else (not y'(p), not the rule,
// not the library).

struct BeamCompliance {
  double bending_m_per_n;
  double shear_m_per_n;
  double axial_m_per_n;
};

// Section at height y: A = 2 x b, I = (2/3) x^3 b. Over the flank, from its
// root to the load (Tian 2004; docs/stiffness-models.md section 2):
//   1/kb = Int [cos tau (y_t - y) - x_t sin tau]^2 / (E I) dy   (the physical sign
//          of the axial force's moment: it unbends the tooth)
//   1/ks = Int 1.2 cos^2 tau / (G A) dy
//   1/ka = Int sin^2 tau / (E A) dy
// Each quadrature is asked for `relative_tolerance` (the range of the case
// schema's stiffness_tolerance) and throws QuadratureError if it misses it.
BeamCompliance tooth_beam_compliance(const std::vector<FlankPiece>& flank, const BeamLoad& load,
                                     const BeamMaterial& material, StiffnessRoute route,
                                     double relative_tolerance = 1e-12);

// A section's area A and second moment I.
struct BeamSection {
  double area_m2;
  double second_moment_m4;
};
// The section at height y of half thickness x, for a tooth whose sections are
// not 2 x b and (2/3) x^3 b (a cracked tooth, root_crack.hpp).
using BeamSections = std::function<BeamSection(double half_thickness_m, double height_m)>;

// As above with the sections `sections` gives in place of A = 2 x b and
// I = (2/3) x^3 b; the flank's pieces must be smooth in them.
BeamCompliance tooth_beam_compliance(const std::vector<FlankPiece>& flank, const BeamLoad& load,
                                     const BeamMaterial& material, StiffnessRoute route,
                                     double relative_tolerance, const BeamSections& sections);

// What `sections` change: the integrals over `flank` of each density with
// them less the density with A = 2 x b and I = (2/3) x^3 b, so that a tooth
// whose sections differ on part of its flank is the intact tooth plus this
// over that part. The flank may be empty (no change). Throws as above.
BeamCompliance tooth_beam_compliance_change(const std::vector<FlankPiece>& flank,
                                            const BeamLoad& load, const BeamMaterial& material,
                                            StiffnessRoute route, double relative_tolerance,
                                            const BeamSections& sections);

}  // namespace gearimpact
