// The torsional run by the adaptive integrator (adaptive_loop.hpp).
#include "adaptive_loop.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "rk4.hpp"
#include "run.hpp"

namespace gearimpact {

SimulationResult run_adaptive(const SimulationCase& c, const StiffnessTable& table,
                              const RunControl& control) {
  Run run(c, table, control);
  const double t = run_adaptive_loop(run, c, largest_resolving_step_s(c));
  return run.finish(t, "adaptive");
}

}  // namespace gearimpact
