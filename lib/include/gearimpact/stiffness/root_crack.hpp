// A root crack in one tooth (Tian 2004, with Chen & Shao's 2011 depth
// profiles across the face; docs/stiffness-models.md, section "Root crack"):
// the cracked tooth's sections A(y), I(y) and its beam compliances by both
// routes of tooth_beam.hpp. Hertz and the fillet foundation are unchanged.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/geometry/tooth_profile.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/tooth_beam.hpp"

namespace gearimpact {

// How the depth runs across the face, z from the crack's start edge (0 <= z <= b):
//  uniform:       q(z) = q                                   (2-D, Tian)
//  partial_width: q(z) = q0 sqrt((W_c - z) / W_c), z <= W_c; 0 beyond
//  full_width:    q(z) = sqrt((q2^2 - q0^2) z / b + q0^2)
enum class CrackProfile { uniform, partial_width, full_width };

// The flank the crack starts on. The loaded flank by default: the crack opens
// on the tension side. The tooth is symmetric, so in this reading A and I do
// not depend on it; it says which load direction the crack meets.
enum class CrackFlank { loaded, unloaded };

struct RootCrack {
  CrackProfile profile = CrackProfile::uniform;
  double depth_m = 0.0;      // q (uniform) or q0 (partial and full width)
  double end_depth_m = 0.0;  // q2 (full width): the depth at z = b
  double width_m = 0.0;      // W_c (partial width)
  double angle_rad = 0.0;    // nu, between the crack and the tooth centre line
  // r_s; absent: default_crack_start_radius of the model.
  std::optional<double> start_radius_m;
  CrackFlank flank = CrackFlank::loaded;
};

// q(z), m; z in [0, b].
double crack_depth_at(const RootCrack& crack, double z_m, double face_width_m);
// The largest and the smallest q(z) over the face.
double largest_crack_depth(const RootCrack& crack);
double smallest_crack_depth(const RootCrack& crack);

// A(y) = Int_0^b t dz and I(y) = Int_0^b t^3 / 12 dz of a section at or above
// the start, t(y, z) = x + min(x, h_q(z)) + max(0, x - h_c), h_q = h_c - q(z) sin nu.
// With nothing cut (every slice has t = 2x) they are 2 x b and (2/3) x^3 b
// to the bit, as the healthy tooth's.
struct SectionProperties {
  double area_m2;
  double second_moment_m4;
};
SectionProperties healthy_section(double half_thickness_m, double face_width_m);

// Uniform depth in closed form; the partial- and full-width profiles by GSL
// QAG over the depth itself (z = W_c (1 - w^2), resp. z = (v^2 - q0^2) b /
// (q2^2 - q0^2)), where the integrands are polynomials of degree <= 4, so the
// 61-point rule is exact; its error estimate is checked as every quadrature's
// (QuadratureError).
SectionProperties cracked_section(const RootCrack& crack, double half_thickness_m,
                                  double start_half_thickness_m, double face_width_m);

// The same integrals over z for any depth q(z) (piecewise smooth between
// `breaks_m`, strictly inside (0, b)), by GSL QAG in z: an independent route
// for the profiles above, and the check of the width integrals.
SectionProperties cracked_section_over_width(const std::function<double(double)>& depth_m_at_z,
                                             const std::vector<double>& breaks_m, double sin_nu,
                                             double half_thickness_m, double start_half_thickness_m,
                                             double face_width_m);

// r_s when the crack does not give it: yang_lin_1987, the base circle (Tian's
// tooth); potential_energy and ross_compatible, the fillet point whose tangent
// makes 30 deg with the centre line (ISO 6336-3's critical section).
double default_crack_start_radius(const RackGearGeometry& gear, StiffnessModelKind kind);

// The crack placed on a tooth: r_s, h_c = x(r_s) and the crack.
struct PlacedCrack {
  RootCrack crack;
  double start_radius_m;
  double start_half_thickness_m;  // h_c
};
// Throws InputError for a crack that does not fit: a negative depth, a width
// outside (0, b], an angle outside (0, 90] deg, a start off the flank from the
// root circle to the tip, or q sin nu >= h_c (named with the values).
PlacedCrack place_crack(const RootCrack& crack, const RackGearGeometry& gear,
                        StiffnessModelKind kind, double face_width_m);

// tooth_beam_compliance of a cracked tooth: sections below r_s intact, at and
// above it cracked_section; the flank is split at r_s (where the section
// jumps) and where the cut starts or stops growing (where it kinks), so that
// both routes integrate smooth pieces.
BeamCompliance cracked_beam_compliance(const std::vector<FlankPiece>& flank, const BeamLoad& load,
                                       const BeamMaterial& material, const PlacedCrack& crack,
                                       StiffnessRoute route, double relative_tolerance = 1e-12);

// tooth_compliances (mesh_models.hpp) of a tooth with a root crack, for
// potential_energy and ross_compatible: bending, shear and axial of the cracked
// beam, the foundation as for the healthy tooth.
ToothCompliances cracked_tooth_compliances(const RackGearGeometry& gear, Gear which,
                                           const ToothContact& contact, double contact_width_m,
                                           const StiffnessModel& model, const RootCrack& crack);

// tau_form_compliances or x_form_compliances (by model.route) of the
// paper's tooth (yang_lin_1987) with a root crack from its base-circle
// section (Tian's tooth, h_c = Rb sin theta_b): each section's integrand
// times (2/3) x^3 b / I(y), resp. 2 x b / A(y). The start is that section; a
// given r_s is refused. Throws InputError as place_crack.
// The refusals of cracked_paper_tooth_compliances without its integrals:
// InputError for a crack that does not fit the paper's tooth.
void check_paper_crack(const InvoluteTooth& tooth, double face_width_m, const RootCrack& crack);
// h_c of the paper's tooth, whose crack starts at the base-circle section: Rb sin theta_b.
double paper_crack_start_half_thickness(const InvoluteTooth& tooth);

Compliances cracked_paper_tooth_compliances(const InvoluteTooth& tooth, double contact_x_m,
                                            double youngs_modulus_pa, double face_width_m,
                                            const StiffnessModel& model, const RootCrack& crack);

// The change a root crack makes to a tooth's beam terms, prepared once for
// many contact positions: the cracked tooth's integrals less the healthy
// tooth's, integrated over the sections the crack cuts only (those with
// q sin nu > h_c - x at or above the start) and split where the cut starts and
// kinks, found once for the whole flank. The cracked tooth is the healthy one
// plus this change (MeshTables builds its tables so); the functions above
// integrate the cracked tooth whole, the route the change is checked against.

// The paper's tooth (yang_lin_1987): bending and axial, by model.route.
// Throws InputError as check_paper_crack.
class PaperCrackChange {
 public:
  PaperCrackChange(const InvoluteTooth& tooth, double youngs_modulus_pa, double face_width_m,
                   const StiffnessModel& model, const RootCrack& crack);
  // cracked_paper_tooth_compliances less tau_form_compliances (or
  // x_form_compliances) at the same contact; 0 where the crack cuts nothing.
  Compliances at(double contact_x_m) const;
  // The contact positions X (from the tangent point, as `at` takes them)
  // where the contact's own section is one of those where the cut starts or
  // kinks: there the change kinks as a function of X. Ascending; empty when
  // the crack cuts nothing. Some may lie off the contact segment.
  std::vector<double> kinks_m() const;

 private:
  Compliances tau_form_change(double contact_x_m) const;
  Compliances x_form_change(double contact_x_m) const;

  InvoluteTooth tooth_;
  double youngs_modulus_pa_;
  double face_width_m_;
  StiffnessModel model_;
  RootCrack crack_;
  double sin_nu_;
  double h_c_;
  // The section angles tau (ascending, in (-pi/2, 0)) where the cut starts
  // (the first: x = h_c - q_max sin nu) and where it kinks (x = h_c and
  // x = h_c - q_min sin nu); from there down to the base circle every section
  // is cut. Empty when the crack cuts nothing.
  std::vector<double> tau_ends_;
};

// A rack-cut tooth (potential_energy, ross_compatible): bending, shear and
// axial, by model.route; the foundation is unchanged. `gear` must outlive the
// object. Throws InputError as place_crack.
class RackCrackChange {
 public:
  RackCrackChange(const RackGearGeometry& gear, double contact_width_m, const StiffnessModel& model,
                  const RootCrack& crack);
  // cracked_beam_compliance less tooth_beam_compliance of the flank up to the
  // contact, as cracked_tooth_compliances and tooth_compliances load it.
  BeamCompliance at(const ToothContact& contact) const;
  // The heights y on the tooth (ToothContact::y_m) where the cut starts or
  // kinks: where the contact meets one, the change kinks. Empty when the
  // crack cuts nothing.
  const std::vector<double>& kink_heights_m() const { return heights_; }

 private:
  const RackGearGeometry* gear_;
  double contact_width_m_;
  StiffnessModel model_;
  PlacedCrack placed_;
  double sin_nu_;
  // r_s and the heights above it where the cut kinks, over the whole flank.
  std::vector<double> heights_;
};

}  // namespace gearimpact
