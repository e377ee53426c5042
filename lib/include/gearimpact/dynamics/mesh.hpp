// The mesh as one spring between the gears along the line of action: the
// effective mass of the relative mode and the mean mesh stiffness of
// STEADY-STATE.md section 2, which set the viscous mesh damper
// (viscous_mesh_damping_n_s_per_m, steady/closed_forms.hpp).
#pragma once

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// m_e = 1 / (Rb1^2/J1 + Rb2^2/J2), the mass of s = Rb1 theta1 - Rb2 theta2.
double effective_mass_kg(const GearPair& pair);

// The mesh stiffness averaged over one base pitch: k of MeshStiffnessMode::constant,
// else (1/t0) Int Ke(X) dX over the contact segment, since over one pitch each
// position of the segment is passed by exactly one loaded pair (42). Throws
// QuadratureError when the integral misses its tolerance.
double mean_mesh_stiffness_n_m(const SimulationCase& c, const StiffnessTable& table);

// w_n = sqrt(k_mean / m_e), the natural frequency of the relative mode with
// the mean mesh stiffness (STEADY-STATE.md section 2). Throws as
// mean_mesh_stiffness_n_m.
double natural_frequency_rad_s(const SimulationCase& c, const StiffnessTable& table);

}  // namespace gearimpact
