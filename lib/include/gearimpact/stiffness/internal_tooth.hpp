// The ring's (internal gear's) tooth by the potential-energy method, and a
// ring-planet pair's stiffness by it (docs/planetary.md, "The ring mesh by
// potential energy"): the planet's tooth as the rack-cut tooth of
// mesh_models.hpp, the ring's as the beam of tooth_beam.hpp over its involute
// from the root circle, Hertz (4), in series (29). SI units, angles in rad.
#pragma once

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/planetary.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/tooth_beam.hpp"

namespace gearimpact {

// An unshifted ring tooth of a basic rack (a0, h_a, h_f): its tip inside the
// pitch circle, its root outside, its flank the involute of its base circle
// from the tip circle out to the root circle (no fillet: the tooth is clamped
// at the root circle on a rigid rim).
struct RingTooth {
  int teeth = 0;
  double pitch_radius_m = 0.0;  // r = z m / 2
  double base_radius_m = 0.0;   // r cos a0
  double tip_radius_m = 0.0;    // r - h_a m
  double root_radius_m = 0.0;   // r + h_f m
  // The tooth's half angle at its base circle, pi/(2 z) - inv a0: on the
  // pitch circle the tooth and the space are each half a pitch wide, and the
  // half angle at radius R is this plus inv(acos(r_b / R)), growing outward.
  double half_angle_base_rad = 0.0;
};

// Throws InputError naming `teeth` when the tip circle lies inside the base
// circle (the involute would not reach the tip) or the tooth's half angle at
// the tip is not positive.
RingTooth ring_tooth(int teeth, double module_m, double pressure_angle_rad,
                     double addendum_coefficient, double dedendum_coefficient);

// A point of the ring's flank at involute parameter u = tan(alpha), alpha the
// pressure angle at radius R = r_b sqrt(1 + u^2), in the tooth frame mirrored
// so that the height runs from the root toward the tip as an external tooth's
// does: x = R sin(beta), y = -R cos(beta), beta = half_angle_base + u - atan u.
ProfilePoint ring_flank_point(const RingTooth& tooth, double u);

// The ring tooth loaded at `roll_distance_m` from its base circle's tangent
// point along the line of action (R = sqrt(r_b^2 + roll^2)), in the frame of
// ring_flank_point: the load line makes tau = alpha + beta with the x axis
// (docs/planetary.md derives it), and the beam of tooth_beam.hpp runs from the
// root circle to the contact. InputError for a contact off [tip, root].
BeamCompliance ring_tooth_compliance(const RingTooth& tooth, double roll_distance_m,
                                     const BeamMaterial& material, StiffnessRoute route,
                                     double relative_tolerance);

// The ring-planet pair of `ring_planet` (gears.teeth1 the ring, teeth2 the
// planet; unshifted) on the line of `mesh` (lengths from the planet's tangent
// point T_b): tooth1 the planet's rack-cut tooth by `model` (potential_energy:
// bending, shear, axial and, with its bore bore_diameter2, the fillet
// foundation), tooth2 the ring's by ring_tooth_compliance (no foundation
// term: its rim is rigid), Hertz (4) over the face width, (29) over the terms
// the model switches on.
MeshStiffness internal_mesh_stiffness(const GearPair& ring_planet, const InternalMesh& mesh,
                                      double x_m, const StiffnessModel& model);

// The same pair with the planet's tooth cracked at its root (root_crack.hpp,
// cracked_tooth_compliances), `crack` as the planet's sun mesh sees it: the
// ring holds the planet tooth's other flank, so the crack's flank is the
// other one here (loaded <-> unloaded). The ring's tooth and Hertz are the
// healthy pair's.
MeshStiffness internal_mesh_stiffness(const GearPair& ring_planet, const InternalMesh& mesh,
                                      double x_m, const StiffnessModel& model,
                                      const RootCrack& planet_crack);

// Throws InputError naming rack_tip_radius_coefficient (the value the planet
// is cut with) when the ring's tip meets the planet below its form circle,
// on the fillet the rack's tip round cuts, where the planet's tooth of
// mesh_models.hpp has no involute to load.
void check_planet_form_circle(const GearPair& ring_planet, const InternalMesh& mesh);

// internal_mesh_stiffness's Ke and its terms as a table over the segment
// [mesh.segment_start_m, mesh.segment_end_m].
StiffnessTable internal_potential_energy_table(const GearPair& ring_planet,
                                               const InternalMesh& mesh,
                                               const StiffnessModel& model,
                                               StiffnessTableOptions options = {});

// The mean mesh stiffness over a mesh period of the pairs of `table` (a
// per-pair table over the whole segment, its pairs one base pitch apart):
// (1/p_b) times the integral of Ke over the segment, which sums each pair's
// share of one period. Gauss-Legendre's 4 points on each piece integrate the
// table's polynomials of order up to 7 exactly.
double internal_mean_mesh_stiffness(const StiffnessTable& table, double base_pitch_m);

// The planet's rack-cut tooth as the planet of a twin planet-planet pair (both
// gears the planet's, gear 2's bore on both) so that rack_gear_geometry reads
// the planet's own keys.
GearPair planet_twin(const GearPair& ring_planet);

}  // namespace gearimpact
