// The state of single teeth (docs/faults.md): healthy, a root crack, a spall,
// a chipped tip, missing;
// the list of faulted teeth of a case; and the check that a fault fits its
// tooth. A new kind of fault is one more ToothKind, its parameters in
// ToothState, and one branch where the compliance of a pair reads the state
// (mesh_stiffness.cpp) and where equal states are told apart (operator==).
#pragma once

#include <string>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"

namespace gearimpact {

enum class ToothKind {
  healthy,
  root_crack,  // ToothState::crack
  missing,     // the pair that holds the tooth carries nothing
  spall,       // ToothState::spall
  tip_chip,    // ToothState::chip
};

// "healthy", "root-crack", "missing", "spall", "tip-chip": the names case
// files use.
std::string to_string(ToothKind kind);

struct ToothState {
  ToothKind kind = ToothKind::healthy;
  RootCrack crack;  // read only when kind == root_crack
  Spall spall;      // read only when kind == spall
  TipChip chip;     // read only when kind == tip_chip
  // Where a spall's or a chip's band across the face starts on a helical
  // tooth, y from the face end at smaller z (docs/helical.md, Faults): the
  // fault covers [face_start, face_start + width). A spur pair's sections
  // and contact line do not depend on it, which keeps it 0 there.
  double face_start_m = 0.0;
};

// Two states load a tooth alike: the same kind and, for a crack, a spall or a
// chip, the same fault (every field, a crack's start radius absent in both or
// equal).
bool operator==(const ToothState& a, const ToothState& b);
inline bool operator!=(const ToothState& a, const ToothState& b) {
  return !(a == b);
}

// One faulted tooth: gear 1 (pinion) or 2 (wheel), its number in mesh order
// (0 ... z-1, geometry/tooth_identity.hpp) and its state.
struct ToothFault {
  Gear gear = Gear::one;
  int tooth = 0;
  ToothState state;
};
bool operator==(const ToothFault& a, const ToothFault& b);

// The distinct states of one gear's teeth (gear `gear` of z teeth), healthy
// first, and in `tooth_class` each tooth's index among them.
std::vector<ToothState> tooth_classes(const std::vector<ToothFault>& faults, Gear gear, int z,
                                      std::vector<int>& tooth_class);

// Throws InputError unless every fault fits: the tooth number in 0 ... z-1 of
// its gear, one fault per tooth, a crack that place_crack (or, for
// yang-lin-1987, the paper's tooth) accepts, a spall or a chip that
// place_spall / place_chip accepts on the model's tooth (a width up to the
// face width: across the whole face the pair has no contact over the fault's
// extent, MeshTables). Names "faults[i].tooth"
// and the library's fault names; the case-file reader checks the same before,
// under the keys a file writes.
void check_tooth_faults(const GearPair& pair, const StiffnessModel& model,
                        const std::vector<ToothFault>& faults);

// Where a root crack of a tooth of `gear` starts and how deep it may reach, as check_tooth_faults
// holds it (docs/faults.md): the start radius r_s (the crack's own, else the model's default: the
// base circle for yang-lin-1987, ISO's 30-degree tangent point otherwise), the half thickness h_c
// of the section there, and the largest depth, q sin nu < h_c (the crack may not pass the tooth's
// centre line): q < h_c / sin nu at the crack's angle nu. Throws as check_tooth_faults for a crack
// that does not fit its tooth but for its depth.
struct CrackReach {
  double start_radius_m = 0.0;
  double start_half_thickness_m = 0.0;  // h_c
  double largest_depth_m = 0.0;         // h_c / sin nu, not reached
};
CrackReach crack_reach(const GearPair& pair, const StiffnessModel& model, Gear gear,
                       const RootCrack& crack);

// The state of tooth `tooth` of `gear`: the fault's, or healthy.
ToothState tooth_state(const std::vector<ToothFault>& faults, Gear gear, int tooth);

}  // namespace gearimpact
