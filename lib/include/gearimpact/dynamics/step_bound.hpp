// The largest fixed step that resolves the contact, and the check of a case's
// step against it.
#pragma once

#include "gearimpact/dynamics/simulation_case.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// Fewer steps per contact period than this do not resolve the contact.
inline constexpr double kStepsPerContactPeriod = 20.0;
// A run of more steps than this is a mistake (days of computing), not a case.
inline constexpr long long kMostSteps = 2'000'000'000LL;

// 1/20 of the period of the stiffest contact, sqrt(K (Rb1^2/J1 + Rb2^2/J2))
// with K the largest sum of Ke over the loaded pairs (sampled along one base
// pitch), Ke by adaptive quadrature.
double largest_resolving_step_s(const SimulationCase& c);
// The same from a table built for c: Ke to round-off, without the quadrature.
double largest_resolving_step_s(const SimulationCase& c, const StiffnessTable& table);

// Throws InputError unless 0 < step <= largest_step_s and the run takes at
// most kMostSteps steps.
void validate_step(const SimulationCase& c, double largest_step_s);

}  // namespace gearimpact
