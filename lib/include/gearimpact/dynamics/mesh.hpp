// The mesh as one spring between the gears along the line of action: the
// effective mass of the relative mode, the mean mesh stiffness of
// docs/steady-state.md section 2, and the viscous mesh damper they set.
#pragma once

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
// side stays smooth there. part < 0: the table's own piece at X.
StiffnessAndDerivative pair_stiffness_continued(const StiffnessTable& table, int part, double x_m,
                                                double start_m, double end_m);

// docs/steady-state.md section 1: the optional linear viscous mesh damper
// c = 2 zeta sqrt(k m_e), in N s/m. Throws InputError unless zeta >= 0 and
// k, m_e > 0, all finite.
double viscous_mesh_damping_n_s_per_m(double damping_ratio, double mesh_stiffness_n_per_m,
                                      double effective_mass_kg);

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
