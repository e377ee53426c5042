// The loaded static transmission error (docs/faults.md, "Static transmission
// error"): at each pinion angle, quasi-statically, the drive-side deflection
// delta that carries F = T1 / Rb1 on the pairs in contact,
//
//     sum_k k_k(X_k) max(0, delta - e_k(X_k)) = F,
//
// with e_k the gap of pair k (modifications.hpp). The left side is piecewise
// linear, continuous and increasing in delta (strictly above min_k e_k), so
// delta is unique; it is found exactly by taking the pairs in order of their
// gaps (solve_deflection), and the bracketing root finder of Boost.Math
// (solve_deflection_bracketed) is the independent route the tests compare.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"

namespace gearimpact {

// The stiffness of drive pair k in contact at X (N/m): the healthy table's
// Ke(X) by default, each pair's own table where teeth differ (MeshTables); 0
// for a pair that carries nothing (a missing tooth).
using PairStiffnessFunction = std::function<double(int k, double x_m)>;

// One pair's part in the balance: its stiffness and its gap.
struct PairSpring {
  double stiffness_n_per_m;
  double gap_m;
};

// The delta of sum k_i max(0, delta - e_i) = force for force > 0 and every
// k_i > 0: the pairs sorted by gap, the first m of them carrying the load
// where delta_m = (F + sum k_i e_i) / (sum k_i) does not pass the next gap.
// Throws InputError for an empty list, force <= 0 or a stiffness <= 0.
double solve_deflection(const std::vector<PairSpring>& springs, double force_n);

// sum_i k_i max(0, delta - e_i): the force the pairs carry at the deflection delta.
double carried_force(const std::vector<PairSpring>& springs, double delta_m);

// The same by Boost.Math's TOMS 748 on [e_0, e_0 + 2 F / k_0], pair 0 the
// one of the least gap (the residual is -F at the lower end, >= F at the
// upper), to a bracket of
// `relative_tolerance` of delta's size.
double solve_deflection_bracketed(const std::vector<PairSpring>& springs, double force_n,
                                  double relative_tolerance = 1e-15);

struct StaticTransmissionErrorOptions {
  int points_per_mesh_period = 200;  // 2 to 100000
  // The mesh periods computed: 0 the true period of the teeth; more (a
  // multiple of it) to set an unmodified pair beside a modified one.
  long long mesh_periods = 0;
  // The gears whose teeth differ by their faults (MeshTables::distinct()):
  // with the modifications' distinct_teeth they set the true period.
  DistinctTeeth faulted{};
};

// One pinion angle.
struct StePoint {
  double theta1_rad = 0.0;
  // False where every pair in the segment has a missing tooth: no pair on the
  // line of action carries F (the teeth would turn through the gap until the
  // next pair met off the line of action, which the model has not), so
  // ste_m and the effective stiffness have no value (0 here; empty in CSV).
  bool carried = true;
  double ste_m = 0.0;  // delta: the wheel's lag behind rigid perfect gears, on the line of action
  double kte_m = 0.0;  // min_k e_k: the unloaded (kinematic) transmission error
  double effective_stiffness_n_per_m = 0.0;  // sum of k_k over the loaded pairs
  // Every pair within the contact segment, in ascending X (the newest first).
  std::size_t pairs = 0;
  std::array<int, MeshLayout::capacity> k{};
  std::array<double, MeshLayout::capacity> x_m{};
  std::array<double, MeshLayout::capacity> gap_m{};
  std::array<double, MeshLayout::capacity> stiffness_n_per_m{};
  std::array<double, MeshLayout::capacity> share{};  // F_k / F, 0 for a pair not touching
  std::array<TeethInContact, MeshLayout::capacity> teeth{};
};

struct StaticTransmissionError {
  double torque1_n_m = 0.0;
  double force_n = 0.0;              // |T1| / Rb1
  long long mesh_periods = 1;        // the true period in mesh periods
  double period_rad = 0.0;           // the true period as a pinion angle
  std::vector<StePoint> points;      // theta1 = i period / n, i = 0 ... n-1
  double ste_mean_m = 0.0;           // the mean over the carried points
  double ste_peak_to_peak_m = 0.0;   // max - min over the carried points
  std::size_t uncarried_points = 0;  // points with carried false
};

// Throws InputError naming "torque" for T1 = 0, negative or not finite, and
// "points" outside [2, 100000] or beyond 1e7 angles over the period, and
// "mesh_periods" below 0: the
// checks of static_transmission_error, for a caller to make before building
// its stiffness table.
void validate_static_transmission_error(const GearPair& pair, const Modifications& m,
                                        double torque1_n_m, StaticTransmissionErrorOptions options);

// The STE of a validated pair with its modifications under the pinion torque
// T1 (the load |T1| / Rb1 on the drive flanks), over the true period of the
// teeth (true_period_mesh_periods with distinct_teeth(m) and
// options.faulted). Throws as validate_static_transmission_error, and
// InputError naming "[[faults]]" when no point is carried.
StaticTransmissionError static_transmission_error(const GearPair& pair, const Modifications& m,
                                                  double torque1_n_m,
                                                  const PairStiffnessFunction& stiffness,
                                                  StaticTransmissionErrorOptions options = {});
// The same with the healthy table's Ke(X) for every pair.
StaticTransmissionError static_transmission_error(const GearPair& pair, const Modifications& m,
                                                  double torque1_n_m, const StiffnessTable& table,
                                                  StaticTransmissionErrorOptions options = {});
// The same with each pair's own table (faulted teeth), over the true period
// of the faults and the modifications (options.faulted is set from `tables`).
StaticTransmissionError static_transmission_error(const GearPair& pair, const Modifications& m,
                                                  double torque1_n_m, const MeshTables& tables,
                                                  StaticTransmissionErrorOptions options = {});

// Load sharing with the modifications and faults under the pinion torque T1: at each X1 of
// `positions` (m from C1 on N1, in the contact segment), the balance above at the angle that puts
// pair k (MeshLayout's index on N1: pinion tooth -k mod z1 against wheel tooth -k mod z2,
// teeth_of_pair) at X1, and that pair's share F_k / F of the load T1 / Rb1 (0 where its gap
// keeps it out of contact); `pairs` counts the pairs in the contact segment. Without gaps or faults
// the share is k(X1) / sum k of load_sharing (time_varying_stiffness.hpp). Throws InputError naming
// "torque" as validate_static_transmission_error does, and "positions" for a position outside the
// contact segment.
std::vector<LoadShareSample> loaded_load_sharing(const GearPair& pair, const Modifications& m,
                                                 double torque1_n_m, const MeshTables& tables,
                                                 const std::vector<double>& positions, int k = 0);

// The zero-speed limit of the largest mesh force over the load F = |T1| / Rb1 of the drive
// flanks, from the loaded static transmission error: in a slow run the deflection follows the
// STE delta(theta1), and the mesh force sum k max(0, delta - e) stays F wherever it is continuous
// in theta1. Where it jumps (a pair enters at X_start touching, delta > e_k(X_start); a pair
// crosses a break of its table, a spall's or a chip's edge) the loaded pairs keep the deflection
// delta_- of just before for an instant, so the force is carried_force(the pairs just after,
// delta_-): the largest of these over the true period of the teeth and modifications, over F, and
// at least 1 (where a pair leaves or a gap holds the entering pair off, the force does not rise).
// An event with no pair carrying just before (missing teeth) is an impact, not a quasi-static
// peak, and is left out. For a pair without gaps or faults it is K_after / K_before at the entry
// (quasi_static_force_ratio of steady/iso_resonance.hpp). Throws InputError naming "torque" as
// validate_static_transmission_error does.
double quasi_static_peak_force_ratio(const GearPair& pair, const Modifications& m,
                                     double torque1_n_m, const MeshTables& tables);

}  // namespace gearimpact
