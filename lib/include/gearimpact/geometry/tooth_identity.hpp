// Which pinion tooth meets which wheel tooth in each pair of the mesh, and
// after how many mesh periods the mesh repeats once teeth differ
// (docs/faults.md, "Tooth identity").
//
// Teeth are numbered in mesh order, i = 0 ... z1-1 on the pinion and
// j = 0 ... z2-1 on the wheel. On the drive line N1 the pairs sit at
// X = reference + k t0 (MeshLayout); the reference grows with theta1, so pairs
// of lower k enter later: the n-th pair to enter, counted from the pair k = 0
// that holds the reference contact at theta1 = 0, is k = -n, and it is pinion
// tooth n mod z1 against wheel tooth n mod z2.
//
// On the coast line N2 the positions X' = reference' + k t0 fall as theta1
// grows; a pinion tooth that lags tooth 0 by i pitches sits i base pitches
// further along N2, so coast pair k is the coast flank of pinion tooth k.
// With the geometric half-base-pitch phase, coast pair 0 at theta1 = 0 is
// t0/2 past the pitch point, which is tooth 0's coast flank when the tooth
// is centred in the wheel's space (the drive flank at the pitch point, the
// tooth half a pitch thickness behind it). The trailing (coast) flank of
// pinion tooth i faces the wheel tooth between pinion teeth i and i+1, which
// is wheel tooth i+1 (pinion tooth i+1 drives it). The in-phase reading of
// (9) keeps the same numbering.
#pragma once

#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

struct TeethInContact {
  int pinion_tooth = 0;  // 0 ... z1-1
  int wheel_tooth = 0;   // 0 ... z2-1
};

// n mod z in 0 ... z-1 for negative n too.
inline int tooth_number(long long n, int z) {
  const long long r = n % z;
  return static_cast<int>(r < 0 ? r + z : r);
}

// The teeth of pair k on `line` (Region::n1 or Region::n2) of a pinion of z1
// and a wheel of z2 teeth. Inline: the dynamics ask it for every loaded pair
// at every evaluation of the equations of motion.
inline TeethInContact teeth_of_pair(int z1, int z2, Region line, int k) {
  if (line == Region::n2) {
    return {tooth_number(k, z1), tooth_number(static_cast<long long>(k) + 1, z2)};
  }
  const long long n = -static_cast<long long>(k);
  return {tooth_number(n, z1), tooth_number(n, z2)};
}

// The same for the teeth of `pair`.
TeethInContact teeth_of_pair(const GearPair& pair, Region line, int k);

// Where a tooth's drive flank carries, in its own gear's simulated angle: the
// tooth meets the drive line N1 while theta mod 2 pi lies in
// [entry_rad, entry_rad + span_rad) (that interval read modulo 2 pi). For
// pinion tooth i, pair k = -i - m z1 sits at X = X_pitch + Rb1 theta1 + k t0
// (MeshLayout), so with t0 = 2 pi Rb1 / z1 it is loaded while
// theta1 - 2 pi i / z1 lies in [(X_start - X_pitch) / Rb1, (X_end - X_pitch) / Rb1];
// a wheel tooth the same in theta2 with Rb2 where the pair rolls
// (Rb1 theta1 = Rb2 theta2: the deflection, micrometres against the segment,
// is left out). What a figure shades to show a faulted tooth's passage.
struct ToothPassage {
  double entry_rad = 0.0;  // in [0, 2 pi)
  double span_rad = 0.0;   // the contact segment's length / Rb of the gear
};
ToothPassage tooth_passage(const GearPair& pair, Gear gear, int tooth);

// Which gears have teeth that differ from the others.
struct DistinctTeeth {
  bool pinion = false;
  bool wheel = false;
};

// The number of mesh periods after which the mesh repeats: 1 when every tooth
// is alike, z1 when only pinion teeth differ, z2 when only wheel teeth differ,
// lcm(z1, z2) (the hunting period) when both do.
long long true_period_mesh_periods(const GearPair& pair, DistinctTeeth distinct);

}  // namespace gearimpact
