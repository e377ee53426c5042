// The mesh stiffness of one tooth pair by the potential energy method: both
// teeth by the model's route, the Hertzian contact, and their series sum (29).
// MODEL.md, section Stiffness. Compliances in m/N, stiffnesses in N/m.
#pragma once

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_profile.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/terms.hpp"

namespace gearimpact {

InvoluteTooth tooth_of(const GearPair& pair, Gear gear);

// (4) Kh = pi E L / (4 (1 - nu^2)).
double hertz_stiffness(const GearPair& pair);

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

  // 1/compliance of a term: of the tooth of `gear` for a per-tooth term, of
  // the pair for a per-pair one (Kh).
  double stiffness(Term term, Gear gear = Gear::one) const;
};
MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model = {});

}  // namespace gearimpact
