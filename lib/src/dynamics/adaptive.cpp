// The torsional run by the adaptive integrator (adaptive_loop.hpp).
#include "adaptive_loop.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "rk4.hpp"
#include "run.hpp"

namespace gearimpact {

SimulationResult run_adaptive(const SimulationCase& c, const StiffnessTable& table,
                              const RunControl& control) {
  Run run(c, table, control);
  // A helical pair's section (face_advance_m > 0) places its pairs over the
  // widened segment, where only its table has their stiffness.
  const double first_step = c.gears.face_advance_m > 0.0 ? largest_resolving_step_s(c, table)
                                                         : largest_resolving_step_s(c);
  const double t = run_adaptive_loop(run, c, first_step);
  return run.finish(t, "adaptive");
}

}  // namespace gearimpact
