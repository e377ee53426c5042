// The fields of a simulation case and their allowed ranges.
#pragma once

#include "gearimpact/dynamics/simulation_case.hpp"

namespace gearimpact {

// Throws InputError naming the first field outside its range: every check
// but the step's upper bound, which needs the mesh stiffness (the dynamics
// checks it, largest_resolving_step_s).
void validate_fields(const SimulationCase& c);

}  // namespace gearimpact
