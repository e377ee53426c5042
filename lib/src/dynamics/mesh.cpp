#include "gearimpact/dynamics/mesh.hpp"

#include <cmath>

#include "gearimpact/numerics/quadrature.hpp"

namespace gearimpact {

double effective_mass_kg(const GearPair& pair) {
  const double rb1 = base_radius(pair, Gear::one);
  const double rb2 = base_radius(pair, Gear::two);
  return 1.0 / (rb1 * rb1 / moment_of_inertia(pair, Gear::one) +
                rb2 * rb2 / moment_of_inertia(pair, Gear::two));
}

double mean_mesh_stiffness_n_m(const SimulationCase& c, const StiffnessTable& table) {
  if (c.model.mesh_stiffness == MeshStiffnessMode::constant) {
    return c.model.constant_mesh_stiffness_n_m;
  }
  const ContactSegment segment = contact_segment(c.gears);
  // Ke is smooth on the segment (its table is a piecewise Chebyshev fit): the
  // adaptive rule meets 1e-12 relative.
  QuadratureTolerance tolerance;
  tolerance.relative = 1e-12;
  const QuadratureResult integral = integrate_gsl_qag([&](double x) { return table.stiffness(x); },
                                                      segment.start_m, segment.end_m, tolerance);
  return integral.value / base_pitch(c.gears);
}

double natural_frequency_rad_s(const SimulationCase& c, const StiffnessTable& table) {
  return std::sqrt(mean_mesh_stiffness_n_m(c, table) / effective_mass_kg(c.gears));
}

}  // namespace gearimpact
