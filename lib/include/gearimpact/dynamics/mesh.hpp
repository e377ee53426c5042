// The mesh as one spring between the gears along the line of action: the
// effective mass of the relative mode, the mean mesh stiffness of
// docs/steady-state.md section 2, and the viscous mesh damper they set.
#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// 1/m_e = Rb1^2/J1 + Rb2^2/J2, where m_e is the mass of s = Rb1 theta1 - Rb2 theta2.
double inverse_effective_mass_per_kg(double base_radius1_m, double inertia1_kg_m2,
                                     double base_radius2_m, double inertia2_kg_m2);
// m_e = 1 / (Rb1^2/J1 + Rb2^2/J2).
double effective_mass_kg(double base_radius1_m, double inertia1_kg_m2, double base_radius2_m,
                         double inertia2_kg_m2);
// The same for the pair's discs (moment_of_inertia).
double inverse_effective_mass_per_kg(const GearPair& pair);
double effective_mass_kg(const GearPair& pair);

// Ke and dKe/dX of one pair at X from its table, continued along the tangent
// beyond [start, end] (the contact segment, or with part >= 0 that part of a
// table cut at a fault's edges): stage states of a step that ends on a pair's
// entry, exit or a fault's edge reach a hair beyond it, and the right-hand
// side stays smooth there. part < 0: the table's own piece at X. Inline:
// both systems read it for every loaded pair at every stage.
inline StiffnessAndDerivative pair_stiffness_continued(const StiffnessTable& table, int part,
                                                       double x_m, double start_m, double end_m) {
  const double xc = std::clamp(x_m, start_m, end_m);
  StiffnessAndDerivative k = part >= 0 ? table.stiffness_and_derivative_in_part(xc, part)
                                       : table.stiffness_and_derivative(xc);
  k.stiffness_n_per_m += k.derivative_n_per_m2 * (x_m - xc);
  return k;
}

// docs/steady-state.md section 1: the optional linear viscous mesh damper
// c = 2 zeta sqrt(k m_e), in N s/m. Throws InputError unless zeta >= 0 and
// k, m_e > 0, all finite.
double viscous_mesh_damping_n_s_per_m(double damping_ratio, double mesh_stiffness_n_per_m,
                                      double effective_mass_kg);

// c of the case's viscous mesh damper, 0 without one (model.mesh_damping_ratio
// 0): c = 2 zeta sqrt(k m_e) with m_e of the discs and k the mean mesh
// stiffness, over the true period when the teeth differ (`teeth` with faults,
// else nullptr). The torsional and the planar system both take theirs here.
double case_mesh_damping_n_s_per_m(const SimulationCase& c, const StiffnessTable& table,
                                   const MeshTables* teeth);
// The same with the m_e of the mesh's two bodies as they turn in a train
// (effective_mass_kg of their base radii and inertias), not of the pair's discs.
double case_mesh_damping_n_s_per_m(const SimulationCase& c, const StiffnessTable& table,
                                   const MeshTables* teeth, double mass_kg);

// With modifications (docs/faults.md) a pair touches by its own penetration
// dl - e_k(X), whose rate is dl' - de_k/dX dX/dt, dX/dt the line's sign times
// Rb1 w1. The gap's branch is that of its zone: how many of `kinks_m`
// (ToothGaps::kinks_m, ascending) lie at or below X.
int gap_zone(const std::vector<double>& kinks_m, double x_m);
struct PairPenetration {
  double delta_m;    // dl - e_k(X)
  double rate_m_s;   // its rate
  double gap_slope;  // de_k/dX, m/m
};
// Pair k on `line` at X with the line's penetration dl and its rate: the gap of
// the zone `zone` between two kinks (or the segment's ends [start, end]),
// continued along its tangent beyond them, as Ke is, so that a stage state of
// a step that ends on a kink keeps the zone's own gap. The slope is taken at
// least a millionth of the zone inside it, where it is the zone's whatever the
// rounding of the kink's position (exactly, for the linear reliefs whose kinks
// these are).
PairPenetration pair_penetration_with_gap(const ToothGaps& gaps, const std::vector<double>& kinks_m,
                                          int zone, Region line, int k, double x_m, double dl_m,
                                          double dl_rate_m_s, double x_rate_m_s, double start_m,
                                          double end_m);
// The teeth of a mesh that differ from pair to pair, built once a run by
// either system: with faults (and a time-varying stiffness) each pair's
// tables (MeshTables, sharing the healthy `table`, which the caller keeps
// alive, without owning it); with modifications each pair's gap and the
// kinks of its slope.
struct MeshTeeth {
  std::shared_ptr<const MeshTables> tables;  // none: every pair reads the healthy table
  std::shared_ptr<const ToothGaps> gaps;     // none: no modifications
  std::vector<double> kinks_m;               // ToothGaps::kinks_m
};
// constant_k: model.constant_mesh_stiffness where the stiffness is constant, else 0.
// `given`: the pairs' tables built by the caller (a helical slice's, MeshTables::slice),
// taken in place of c.faults' where those would be built.
MeshTeeth mesh_teeth(const SimulationCase& c, const StiffnessTable& table, double constant_k,
                     std::shared_ptr<const MeshTables> given = nullptr);

// The event values a loaded pair adds for its table's part and its gap, in
// the torsional and the planar system alike; each appends to g from g[n] on
// and advances n.
// Where the pair's table is cut at a fault's edges: the two ends of its part
// inside the segment, where Ke jumps (held positive at the segment's ends).
inline void append_part_events(const StiffnessTable* table, int part, double x_m, double* g,
                               int& n) {
  if (table == nullptr || table->part_count() <= 1) return;
  g[n++] = part > 0 ? x_m - table->part_start_m(part) : 1.0;
  g[n++] = part + 1 < table->part_count() ? table->part_end_m(part) - x_m : 1.0;
}
// With gaps: the pair's touching by its own penetration dk (it touches or
// lets go), and for a touching pair the kinks of its gap around X (zone), where
// the gap's slope jumps at a linear relief's start: the damping force and the
// gap's work with it. A pair whose gap is open neither slides under load nor
// pushes, and its kinks change nothing: four values held positive. Returns
// whether the pair touches (its friction and push values follow).
inline bool append_gap_events(bool touching, int zone, const std::vector<double>& kinks_m,
                              double x_m, double dk_m, double* g, int& n) {
  g[n++] = touching ? dk_m : -dk_m;
  if (!touching) {
    for (int e = 0; e < 4; ++e) g[n++] = 1.0;
    return false;
  }
  const auto z = static_cast<std::size_t>(zone);
  g[n++] = z > 0 ? x_m - kinks_m[z - 1] : 1.0;
  g[n++] = z < kinks_m.size() ? kinks_m[z] - x_m : 1.0;
  return true;
}

// The least gap e_k(X_k) of the pairs in the contact segment of `line` at
// theta1: the line's contact begins where its penetration passes it.
double least_pair_gap_m(const ToothGaps& gaps, const MeshLayout& layout, Region line,
                        double theta1_rad);

// The mesh stiffness averaged over one base pitch: k of MeshStiffnessMode::constant,
// else (1/t0) Int Ke(X) dX over the contact segment, since over one pitch each
// position of the segment is passed by exactly one loaded pair (42). Throws
// QuadratureError when the integral misses its tolerance.
double mean_mesh_stiffness_n_per_m(const SimulationCase& c, const StiffnessTable& table);

// With teeth that differ, the mean over the true period of N mesh periods
// (MeshTables::true_period_mesh_periods): (1/(N t0)) times the sum over the N
// drive-line pairs of one period of Int Ke(X) dX of each pair's table, 0 for
// a pair with a missing tooth. Every tooth alike: the one-pitch mean above.
double mean_mesh_stiffness_n_per_m(const SimulationCase& c, const MeshTables& tables);

// w_n = sqrt(k_mean / m_e), the natural frequency of the relative mode with
// the mean mesh stiffness (docs/steady-state.md section 2). Throws as
// mean_mesh_stiffness_n_per_m.
double natural_frequency_rad_per_s(const SimulationCase& c, const StiffnessTable& table);

}  // namespace gearimpact
