// The mesh stiffness of one tooth pair by the potential energy method: both
// teeth by the named model (the paper's routes, or mesh_models.hpp for the
// models beyond it), the Hertzian contact, and their series sum (29).
// docs/model.md, section Stiffness; docs/stiffness-models.md. Compliances in m/N,
// stiffnesses in N/m.
#pragma once

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_profile.hpp"
#include "gearimpact/stiffness/fillet_foundation.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/terms.hpp"

namespace gearimpact {

struct ToothState;      // tooth_state.hpp
enum class CrackFlank;  // root_crack.hpp

InvoluteTooth tooth_of(const GearPair& pair, Gear gear);

// (4) Kh = pi E L / (4 (1 - nu^2)) for gears of one material; for two,
// (pi L / 2) / [(1 - nu1^2)/E1 + (1 - nu2^2)/E2] (hertz_stiffness_two_materials).
double hertz_stiffness(const GearPair& pair);
// The same over a contact length L in [0, b] in place of the face width b (a
// tooth with a spall or a chip, surface_faults.hpp): 0 for L = 0, where the
// pair carries nothing. hertz_stiffness(pair) is this with L = b, to the bit.
double hertz_stiffness(const GearPair& pair, double contact_length_m);

// The per-tooth terms of one tooth loaded at distance `contact_x_m` from the
// tangent point of its own base circle along the line of action (X1 for gear
// 1, lp - X1 for gear 2), by the model's route. The contact must lie above the
// base circle: X > 0.
Compliances tooth_compliance(const InvoluteTooth& tooth, double contact_x_m,
                             double youngs_modulus_pa, double face_width_m,
                             const StiffnessModel& model = {});

// Every compliance of one pair in contact at X1 (from C1), and Ke by (29) over
// the terms the model switches on (the others are reported all the same).
struct MeshStiffness {
  Compliances tooth1;    // per-tooth terms of the gear-1 tooth
  Compliances tooth2;    // of the gear-2 tooth
  Compliances pair;      // every term: per-tooth ones summed over both teeth
  Compliances included;  // the terms switched on, the others 0: what (29) sums
  double ke;             // (29)
  // The fillet-foundation fit was used outside its range for either tooth
  // (fillet_foundation.hpp): the foundation term is an extrapolation.
  bool foundation_extrapolated = false;

  // 1/compliance of a term: of the tooth of `gear` for a per-tooth term, of
  // the pair for a per-pair one (Kh).
  double stiffness(Term term, Gear gear = Gear::one) const;
};
// yang_lin_1987: the paper's route for X1 in (0, lp). potential_energy and
// ross_compatible: pair_stiffness of mesh_models.hpp at s = X1 (both measured
// from the base-circle tangent point of gear 1) for X1 on the contact segment;
// their foundation term needs both bores (InputError naming bore_diameter1 or
// bore_diameter2 otherwise).
MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model = {});

// The same pair with the pinion tooth in state `tooth1` and the wheel tooth in
// `tooth2` (docs/faults.md), in contact on the drive flanks (line N1): Hertz
// and each tooth's terms as above, a cracked tooth's by root_crack.hpp
// (cracked_paper_tooth_compliances for yang_lin_1987,
// cracked_tooth_compliances for the rack-cut models), a spalled or chipped
// tooth's by surface_faults.hpp (spalled_ / chipped_paper_tooth_compliances,
// spalled_ / chipped_tooth_compliances). Hertz (4) runs over the contact
// length the faults leave: the smaller of the two teeth's
// spall_contact_length / chip_contact_length (the faults are taken to face
// each other across the face). Two healthy teeth give
// mesh_stiffness(pair, x1_m, model) bit for bit. Where a spall or a chip
// across the whole face leaves no contact length (inside the spall's band on
// its flank, above the chip's r_k) the pair has no contact: Ke and every term
// 0. A missing tooth has no compliance: std::logic_error (the pair carries
// nothing, see MeshTables).
MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model,
                             const ToothState& tooth1, const ToothState& tooth2);
// The same with the contact on the flanks `contact_flank`: loaded, the drive
// flanks (N1); unloaded, the coast flanks (N2). Only a spall tells them apart:
// a contact on the flank without the pit keeps its whole length.
MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model,
                             const ToothState& tooth1, const ToothState& tooth2,
                             CrackFlank contact_flank);

// One tooth's per-tooth terms and whether its foundation fit was
// extrapolated.
struct ToothTerms {
  Compliances terms;
  bool foundation_extrapolated = false;
};
// The tooth of `gear` in `state` (not missing) of a pair in contact at X1, as
// mesh_stiffness(pair, X1, model, tooth1, tooth2) computes each tooth of a
// pair with a faulted tooth (a healthy tooth too: pair_stiffness tooth by
// tooth for the rack-cut models). InputError for X1 off its range.
ToothTerms faulted_pair_tooth_terms(const GearPair& pair, Gear gear, double x1_m,
                                    const StiffnessModel& model, const ToothState& state);
// The Hertzian contact length the two teeth's states leave to a contact at X1
// on `contact_flank`: the face width, less a spall's or a chip's share; 0
// where a fault across the whole face leaves no contact (the pair carries
// nothing there, and its teeth's terms are not asked for).
double pair_contact_length_m(const GearPair& pair, double x1_m, const ToothState& tooth1,
                             const ToothState& tooth2, CrackFlank contact_flank);
// That mesh_stiffness from its two teeth's terms: Hertz over the contact
// length the states leave on `contact_flank`, and (29). With the terms of
// faulted_pair_tooth_terms it is that mesh_stiffness to the bit.
MeshStiffness mesh_stiffness_of_teeth(const GearPair& pair, double x1_m,
                                      const StiffnessModel& model, const ToothState& tooth1,
                                      const ToothState& tooth2, CrackFlank contact_flank,
                                      const ToothTerms& terms1, const ToothTerms& terms2);

// The gears whose foundation fit the model uses outside its range, pinion first: empty for a
// model without the foundation term (yang_lin_1987) or with it off. InputError naming
// bore_diameter1 or bore_diameter2 when the term is on and a bore is missing.
std::vector<FoundationExtrapolation> foundation_extrapolations(const GearPair& pair,
                                                               const StiffnessModel& model);

}  // namespace gearimpact
