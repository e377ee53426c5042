// The mesh-stiffness models beyond the 1987 paper (docs/stiffness-models.md,
// section 3) for gears cut by a rack: every per-tooth compliance of one pair
// at a position on the line of action, and the pair's stiffness.
#pragma once

#include <vector>

#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/fillet_foundation.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/tooth_beam.hpp"

namespace gearimpact {

// The models are StiffnessModelKind::potential_energy and ross_compatible
// (model.hpp):
//  potential_energy: Hertz, bending, shear, axial, fillet foundation; the
//    tooth from the root circle (trochoid, then involute); theta_f where the
//    trochoid meets the root circle, u_f where the load line crosses the
//    centre line.
//  ross_compatible: potential_energy with the two conventions of ROSS
//    (petrobras/ross at 631a249a, ross/multi_rotor/gear_element.py):
//    theta_f = [pi/2 + 2 tan a0 (ha - rho*) + 2 rho* / cos a0] / z and
//    u_f = y_t - r_f.
// Of a StiffnessModel they read the kind, the terms, the route (the beam
// integration of tooth_beam.hpp) and the tolerance of every quadrature.

// Kh = (pi b / 2) / [(1 - nu1^2) / E1 + (1 - nu2^2) / E2] (docs/stiffness-models.md
// section 2): two elastic cylinders in line contact over the width b, which is
// the paper's (4) pi E b / (4 (1 - nu^2)) for equal materials.
double hertz_stiffness_two_materials(double width_m, double youngs_modulus1_pa,
                                     double poisson_ratio1, double youngs_modulus2_pa,
                                     double poisson_ratio2);

// theta_f of the model: where the trochoid meets the root circle (b1 / r_p)
// for potential_energy, ROSS's formula for ross_compatible.
double foundation_root_half_angle(const RackGearGeometry& gear, StiffnessModelKind kind);

// u_f of the model for a contact at (x_t, y_t) with load angle tau:
// y_t - x_t tan tau - r_f (potential_energy), y_t - r_f (ross_compatible).
double foundation_load_height(const RackGearGeometry& gear, const ToothContact& contact,
                              StiffnessModelKind kind);

// The tooth of `gear` from its root circle to the contact: the trochoid
// (gamma from pi/2 to a0) and the involute (tau from its form point to the
// contact's tau).
std::vector<FlankPiece> flank_to_contact(const RackGearGeometry& gear, double contact_tau_rad);

// The gears whose foundation fit is used outside its range (fillet_foundation.hpp), pinion first;
// empty when the model's foundation term is off. The fit's inputs h_f and theta_f are the gears'
// own, the same at every contact position. Throws InputError as tooth_compliances for a missing
// bore.
std::vector<FoundationExtrapolation> foundation_extrapolations(const RackGearPairGeometry& pair,
                                                               const StiffnessModel& model);

// Compliances of one tooth, m/N.
struct ToothCompliances {
  double bending_m_per_n = 0.0;
  double shear_m_per_n = 0.0;
  double axial_m_per_n = 0.0;
  double foundation_m_per_n = 0.0;
  // The foundation fit was used outside its range (sainsot_coefficients).
  bool foundation_extrapolated = false;
  double total_m_per_n() const {
    return bending_m_per_n + shear_m_per_n + axial_m_per_n + foundation_m_per_n;
  }
};

// One tooth of `gear` (gear `which` of its pair) loaded at `contact`,
// over the contact width, with the terms the model switches on. Throws
// InputError when the foundation term is on and the gear has no bore, or
// when no tooth term is on.
ToothCompliances tooth_compliances(const RackGearGeometry& gear, Gear which,
                                   const ToothContact& contact, double contact_width_m,
                                   const StiffnessModel& model);

// Every term of one pair at s (m from T1) and the pair's stiffness,
// 1/k = 1/Kh + sum over both teeth of (1/kb + 1/ks + 1/ka + 1/kf).
struct PairStiffness {
  ToothCompliances gear1;
  ToothCompliances gear2;
  double hertz_m_per_n = 0.0;
  double stiffness_n_per_m = 0.0;
};
PairStiffness pair_stiffness(const RackGearPairGeometry& pair, const StiffnessModel& model,
                             double s_m);

// Throws InputError unless the model is potential_energy or ross_compatible
// and at least one of its terms is on (validate_terms); with the foundation
// term on, both gears need a bore (bore_diameter1, bore_diameter2).
void validate(const StiffnessModel& model, const RackGearPairGeometry& pair);

}  // namespace gearimpact
