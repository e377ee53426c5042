// A spall (pit) on a flank and a chipped tip in one tooth
// (docs/stiffness-models.md, section "A spall or a chipped tip in one
// tooth"): the faulted tooth's sections A, I, its beam compliances by both
// routes, its Hertzian contact length, and where a full-width chip ends its
// contact. The fillet foundation is unchanged.
//
// Where a fault begins and ends is given by radii of flank points. The section
// through the flank point at radius r (the cut across the centre line at that
// point's height) is the one the fault at r acts on; since the flank's radius
// rises with its height, a band of radii is a band of sections.
#pragma once

#include <optional>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/root_crack.hpp"

namespace gearimpact {

// A spall on one flank: from the flank point at start_radius_m to the one at
// end_radius_m (radius_at_roll_distance converts roll distances), width_m
// (b_s) across the face, depth_m (d_s) into the tooth, normal to its centre
// line. The flank says which contact meets it: a contact on the other flank
// keeps its whole length, the sections lose the pit all the same.
struct Spall {
  CrackFlank flank = CrackFlank::loaded;
  double start_radius_m = 0.0;
  double end_radius_m = 0.0;
  double width_m = 0.0;  // b_s
  double depth_m = 0.0;  // d_s; 0: no material removed, the healthy tooth
};

// A chip: the tooth above the radius radius_m (r_k) is gone over width_m (b_k)
// from one edge of the face, on both flanks. r_k at the tip: the healthy tooth.
struct TipChip {
  double radius_m = 0.0;  // r_k
  double width_m = 0.0;   // b_k
};

// sqrt(Rb^2 + L^2): the radius of the involute point at roll distance L from
// the tangent point of the base circle (for the pinion L is the position s on
// the line of action, for the wheel T1T2 - s).
double radius_at_roll_distance(double base_radius_m, double roll_distance_m);

// A section of half thickness x inside the spall's band: the slices across
// the pit lose d_s of their height 2x on the flank, t = 2x - d_s, and bend
// about their own centroid as the crack layer's slices do (I = Int t^3/12 dz):
//   A = 2 x b - b_s d_s,   I = (2/3) x^3 (b - b_s) + b_s (2x - d_s)^3 / 12.
// (I -= b_s (x^3 - (x - d_s)^3)/3 would remove the pit's moment about the
// healthy centre line; about the slice's centroid the parallel-axis theorem
// takes b_s t d_s^2 / 4 more.)
SectionProperties spalled_section(const Spall& spall, double half_thickness_m, double face_width_m);
// A section above r_k: A = 2 x (b - b_k), I = (2/3) x^3 (b - b_k).
SectionProperties chipped_section(const TipChip& chip, double half_thickness_m,
                                  double face_width_m);

// The length of the Hertzian line contact (L of (4)) of a contact at radius
// contact_radius_m on this tooth: b - b_s while it lies in the spall's band
// on the spall's flank (contact_flank: the flank the contact is on, loaded
// for the drive side when the spall's flank is named for the drive side),
// b - b_k above r_k; else b. A length of 0 (a full-width spall or chip)
// means that the pair carries nothing there: hertz_stiffness(pair, 0) is 0,
// and mesh_stiffness of the pair gives Ke 0 there rather than a compliance 1/0.
double spall_contact_length(const Spall& spall, CrackFlank contact_flank, double contact_radius_m,
                            double face_width_m);
double chip_contact_length(const TipChip& chip, double contact_radius_m, double face_width_m);

// The spall on a tooth: its band as roll distances on that tooth (contact
// positions; for a rack-cut tooth the band lies on the involute).
struct PlacedSpall {
  Spall spall;
  double start_roll_distance_m;
  double end_roll_distance_m;
};
// Throws InputError, naming the field, its value and its limit, for a spall
// that does not fit: a band off the involute from its start (the form radius;
// the base circle for the paper's tooth) to the tip, or not rising; b_s outside
// (0, b]; a negative depth, or d_s >= x at some section of the band (its
// thinner end: x rises to one maximum and falls along the involute).
PlacedSpall place_spall(const Spall& spall, const RackGearGeometry& gear, double face_width_m);
// The paper's tooth of gear `which`, from its base circle.
PlacedSpall place_spall(const Spall& spall, const GearPair& pair, Gear which);

// x, the half thickness of the section through the flank point at radius_m
// of the tooth of gear `which` as the model shapes it: the paper's involute
// tooth from its base circle (yang_lin_1987), the rack-cut involute otherwise.
// The thickness a spall's depth is held against (place_spall); radius_m on
// the involute, between its start and the tip.
double flank_half_thickness(const GearPair& pair, Gear which, StiffnessModelKind kind,
                            double radius_m);

// The chip on a tooth and the radius at which that tooth's contact ends: r_k
// for a full-width chip (b_k = b), the tip otherwise.
struct PlacedChip {
  TipChip chip;
  double contact_end_radius_m;
};
// Throws InputError for r_k outside (root, tip] (the root circle; the base
// circle for the paper's tooth) or b_k outside (0, b].
PlacedChip place_chip(const TipChip& chip, const RackGearGeometry& gear, double face_width_m);
PlacedChip place_chip(const TipChip& chip, const GearPair& pair, Gear which);

// The positions X1 (from C1, as contact_segment) at which the pairs holding
// the chipped tooth of gear `which` touch: the contact segment, ended early
// for a pinion tooth (its contact climbs to its tip) and begun late for a
// wheel tooth (its contact starts at its tip) where the contact meets r_k of
// a full-width chip. Empty when that leaves nothing: the pair never touches.
std::optional<ContactSegment> chipped_contact_segment(const GearPair& pair, Gear which,
                                                      const TipChip& chip);

// tooth_compliances (mesh_models.hpp) of a tooth with a spall or a chip, for
// potential_energy and ross_compatible: bending, shear and axial of the
// faulted beam (the flank split where the band begins and ends, resp. at r_k,
// so that both routes integrate smooth pieces), the foundation as for the
// healthy tooth. A fault that removes nothing gives the healthy tooth to the
// bit. Throws InputError as place_spall / place_chip, and for a contact above
// r_k of a full-width chip (no tooth is there).
ToothCompliances spalled_tooth_compliances(const RackGearGeometry& gear, Gear which,
                                           const ToothContact& contact, double contact_width_m,
                                           const StiffnessModel& model, const Spall& spall);
ToothCompliances chipped_tooth_compliances(const RackGearGeometry& gear, Gear which,
                                           const ToothContact& contact, double contact_width_m,
                                           const StiffnessModel& model, const TipChip& chip);

// The effective-width reading of a partial-width spall (SpallReading::
// effective_width; docs/faults.md, docs/verification.md "The spall in 3-D").
// A load over the length L = b - b_s that a spall leaves at one edge of the
// face is carried by the loaded width and by the unloaded b - L beside it,
// whose share decays with the distance z from the load's edge as
// exp(-z / lambda) (the load spreading along the face through the tooth and
// its body):
//   b_eff = L + lambda (1 - exp(-(b - L) / lambda)),   factor = b / b_eff,
// the factor by which a term computed over the whole face grows. The beam
// (bending, shear, axial) and the foundation spread over their own lengths,
// in proportion to the tooth's root thickness S_f = 2 r_f sin theta_f:
// lambda = kSpallBeamSpread S_f, resp. kSpallFoundationSpread S_f. The two
// constants are fitted (least squares of the relative error of each tooth's
// compliance growth) to the rig pair's 3-D finite elements, `gearimpact
// fe-check examples/rig_17_38.toml --spall-width 3.75e-3,7.5e-3,11.25e-3
// --solid-at 4e-3,8.7219e-3,13.5e-3`, and checked on the paper's pair, which
// the fit did not see (both in verify/data/fe_spall_3d.csv).
inline constexpr double kSpallBeamSpread = 0.35;
inline constexpr double kSpallFoundationSpread = 0.74;
struct SpallWidthFactors {
  double beam = 1.0;        // bending, shear and axial
  double foundation = 1.0;  // the fillet foundation
};
// L in (0, b], S_f > 0; L = b gives 1 and 1. Throws std::invalid_argument
// otherwise.
SpallWidthFactors spall_width_factors(double contact_length_m, double face_width_m,
                                      double root_thickness_m);
// S_f = 2 r_f sin theta_f of a rack-cut gear (rack_generation.hpp).
double root_thickness(const RackGearGeometry& gear);

// tau_form_compliances or x_form_compliances (by model.route) of the paper's
// tooth of gear `which` (yang_lin_1987; the pair's face width and the gear's
// E) loaded contact_x_m from its base-circle tangent point, with a spall or a
// chip: each section's integrand times (2/3) x^3 b / I and 2 x b / A (tau-form),
// resp. I and A in (16)-(19) (x-form), split as above.
Compliances spalled_paper_tooth_compliances(const GearPair& pair, Gear which, double contact_x_m,
                                            const StiffnessModel& model, const Spall& spall);
Compliances chipped_paper_tooth_compliances(const GearPair& pair, Gear which, double contact_x_m,
                                            const StiffnessModel& model, const TipChip& chip);

}  // namespace gearimpact
