// The largest fixed step that resolves the contact, and the check of a case's
// step against it.
#pragma once

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// 1/20 of the period of the stiffest contact, sqrt(K (Rb1^2/J1 + Rb2^2/J2))
// with K the largest sum of Ke over the loaded pairs (sampled along one base
// pitch), Ke by adaptive quadrature.
double largest_resolving_step_s(const SimulationCase& c);
// The same from a table built for c: Ke to round-off, without the quadrature.
double largest_resolving_step_s(const SimulationCase& c, const StiffnessTable& table);

// Throws InputError unless step <= largest_step_s (the schema holds the
// step's other bounds and the most steps of a run).
void validate_step(const SimulationCase& c, double largest_step_s);

}  // namespace gearimpact
