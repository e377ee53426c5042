#include "gearimpact/dynamics/step_bound.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

namespace {

// The largest resolving step with Ke(X) of one pair given by `ke`.
double largest_step(const SimulationCase& c, const std::function<double(double)>& ke) {
  const GearPair& g = c.gears;
  // (42): the pairs loaded when one sits at u, for u along one base pitch.
  const MeshLayout layout(g, c.model.coast_phase);
  const double t0 = layout.base_pitch_m();
  constexpr int samples = 16;
  double stiffest = 0.0;
  for (int i = 0; i <= samples; ++i) {
    const double u = layout.start_m() + t0 * i / samples;
    const LoadedRange range = layout.loaded(u);
    double total = 0.0;
    for (int k = range.k_first; k < range.k_first + range.count; ++k) {
      total += ke(layout.position_m(u, k));
    }
    stiffest = std::max(stiffest, total);
  }
  const double period = 2.0 * pi / std::sqrt(stiffest * inverse_effective_mass_per_kg(g));
  return period / kStepsPerContactPeriod;
}

}  // namespace

void validate_step(const SimulationCase& c, double largest) {
  const IntegratorSettings& s = c.integrator;
  if (s.step_s > largest) {
    throw InputError("integrator.step", s.step_s,
                     "(0, " + format_number(largest) +
                         "] s: a larger step takes fewer than 20 steps per period of the "
                         "stiffest contact and does not resolve it");
  }
}

double largest_resolving_step_s(const SimulationCase& c) {
  return largest_step(c,
                      [&](double x) { return mesh_stiffness(c.gears, x, c.model.stiffness).ke; });
}

double largest_resolving_step_s(const SimulationCase& c, const StiffnessTable& table) {
  return largest_step(c, [&](double x) { return table.stiffness(x); });
}

}  // namespace gearimpact
