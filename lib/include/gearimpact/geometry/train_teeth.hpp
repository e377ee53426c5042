// Tooth identity and periods for the meshes of a gear train and of a
// planetary stage (docs/planetary.md, "Tooth identity and periods"), and the
// tooth fault frequencies of a ring-fixed stage. The rule of one pair
// (tooth_identity.hpp) carried to any mesh: teeth are numbered clockwise seen
// from +z, so a gear turning counter-clockwise presents 0, 1, 2, ... to a
// mesh fixed in the frame its angle is measured in; the tooth "at" a mesh is
// the one whose centre line crossed the mesh's line of centres last, and it
// stays there one mesh period.
#pragma once

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/planetary.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"

namespace gearimpact {

// floor(x) as an integer, for the tooth counts.
long long whole_pitches(double x);

// A mesh of a train between bodies a and b, `pair` its gears (gear 1 on a,
// gear 2 on b; dynamics/train.hpp): the teeth of the drive pair that crossed
// the pitch point last when body a has turned theta_a (its forward sense, the
// pair's theta1) from where pair 0 (tooth 0 against tooth 0) holds it: the
// n-th pair, n = floor(z1 theta_a / 2 pi), is tooth n mod z1 against tooth
// n mod z2 (the pair's rule, teeth_of_pair(z1, z2, n1, -n)).
TeethInContact mesh_teeth_at(const GearPair& pair, double theta_a_rad);

// A mesh's pairing repeats after lcm(Z_a, Z_b) mesh periods, the hunting period
// (throws InputError unless both counts are >= 1).
long long hunting_period_mesh_periods(int teeth_a, int teeth_b);

// A planetary stage (geometry/planetary.hpp: its teeth, psi_n counter-clockwise
// from the carrier axis e1): angles relative to the carrier are theta - theta_c,
// counter-clockwise; a member's tooth-0 angle is its tooth 0's centre line, the
// sun's and ring's at the stage centre from e1, a planet's at its own centre
// from its e_zeta (outward). A sun turning counter-clockwise relative to the
// carrier turns each planet and the ring clockwise relative to it (Willis).

// Which teeth are at planet n's two meshes for the members' tooth-0 angles
// relative to the carrier, psi_n the planet's position. The sun mesh lies at
// psi_n from the stage centre and at pi from the planet's e_zeta; the ring
// mesh at psi_n from the stage centre and at 0 from the planet's e_zeta. "Last
// crossed" in the sense the teeth move with the sun turning counter-clockwise
// relative to the carrier: sun tooth j = floor(Z_s (sun - psi_n) / 2 pi), planet
// tooth ceil(Z_p (planet - pi) / 2 pi) at the sun and ceil(Z_p planet / 2 pi) at
// the ring, ring tooth ceil(Z_r (ring - psi_n) / 2 pi), each mod its count. One
// mesh period on, the sun's tooth is the next (+1), the planet's and the ring's
// the previous (-1).
struct StageMeshTeeth {
  int sun = 0;             // the sun tooth at the sun mesh
  int planet_at_sun = 0;   // the planet's tooth at its sun mesh
  int planet_at_ring = 0;  // the planet's tooth at its ring mesh
  int ring = 0;            // the ring tooth at the ring mesh
};
StageMeshTeeth stage_mesh_teeth(const PlanetaryTeeth& teeth, double psi_n_rad, double sun_rad,
                                double planet_rad, double ring_rad);

// A ring-fixed stage with every tooth's state its own repeats after
// lcm(Z_s, Z_p, Z_r) mesh periods: the sun relative to the carrier, each
// planet and the carrier against the ring all make whole turns.
long long stage_period_mesh_periods(const PlanetaryTeeth& teeth);

// The frequencies at which a faulted tooth meets a mesh, ring fixed, for the
// carrier's turns per second f_c and N planets: the mesh frequency
// f_m = Z_r f_c; a sun tooth N f_m / Z_s (it meets every planet each turn
// relative to the carrier); a planet tooth f_m / Z_p in each of its two meshes
// (opposite flanks); a ring tooth N f_c (every planet passes it each carrier
// turn). Throws InputError unless the counts are >= 1 and f_c finite.
struct StageFaultFrequencies {
  double mesh_hz = 0.0;
  double sun_tooth_hz = 0.0;
  double planet_tooth_hz = 0.0;  // per mesh
  double ring_tooth_hz = 0.0;
};
StageFaultFrequencies stage_fault_frequencies(const PlanetaryTeeth& teeth, int planets,
                                              double carrier_hz);

}  // namespace gearimpact
