#include "gearimpact/geometry/tooth_outline.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

ToothOutline tooth_outline(const RackGearGeometry& gear, const char* bore_key, int fillet_segments,
                           int involute_segments, const std::vector<double>& vertices_tau_rad) {
  if (!gear.bore_diameter_m) {
    throw InputError(bore_key, "absent",
                     "a bore diameter inside the root circle: the model's rim ends at the bore");
  }
  if (fillet_segments < 2 || involute_segments < 2) {
    throw InputError("outline segments", std::min(fillet_segments, involute_segments),
                     "at least 2 segments on the fillet and on the involute");
  }
  for (const double tau : vertices_tau_rad) {
    if (!(tau >= gear.form_tau_rad && tau <= gear.tip_tau_rad)) {
      throw InputError("contact tau", tau,
                       "[" + format_number(gear.form_tau_rad) + ", " +
                           format_number(gear.tip_tau_rad) + "] rad: the involute");
    }
  }
  ToothOutline outline;
  outline.root_radius_m = gear.root_radius_m;
  outline.tip_radius_m = gear.tip_radius_m;
  outline.bore_radius_m = 0.5 * *gear.bore_diameter_m;
  outline.root_half_angle_rad = gear.root_half_angle_rad;
  // The trochoid up to (not including) its last point, the form point, where
  // the involute begins with a common tangent.
  const double gamma_root = 0.5 * pi;
  const double gamma_form = gear.pressure_angle_rad;
  for (int i = 0; i < fillet_segments; ++i) {
    const double gamma = gamma_root + (gamma_form - gamma_root) * i / fillet_segments;
    const ProfilePoint p = trochoid_point(gear, gamma);
    outline.flank.push_back({p.x_m, p.y_m});
  }
  // The involute's even steps and the asked vertices, in rising tau; a step
  // that lands on an asked vertex (or within a quarter step) gives way
  // to it, so that no segment is degenerate.
  const double step = (gear.tip_tau_rad - gear.form_tau_rad) / involute_segments;
  std::vector<double> taus;
  for (int i = 0; i <= involute_segments; ++i) {
    const double tau = gear.form_tau_rad + step * i;
    const bool near_vertex =
        std::any_of(vertices_tau_rad.begin(), vertices_tau_rad.end(),
                    [&](double v) { return std::fabs(v - tau) < 0.25 * step; });
    if (!near_vertex) taus.push_back(tau);
  }
  taus.insert(taus.end(), vertices_tau_rad.begin(), vertices_tau_rad.end());
  std::sort(taus.begin(), taus.end());
  taus.erase(std::unique(taus.begin(), taus.end()), taus.end());
  const std::size_t involute_start = outline.flank.size();
  for (const double tau : taus) {
    const ProfilePoint p = involute_point(gear, tau);
    outline.flank.push_back({p.x_m, p.y_m});
  }
  for (const double v : vertices_tau_rad) {
    const auto at = std::lower_bound(taus.begin(), taus.end(), v);
    outline.vertex_index.push_back(involute_start + static_cast<std::size_t>(at - taus.begin()));
  }
  return outline;
}

}  // namespace gearimpact
