#include "gearimpact/signals/planet_pass.hpp"

#include <cmath>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact::signals {

void check_planet_pass_half_width(double half_width_rad, const char* name) {
  if (!std::isfinite(half_width_rad) || half_width_rad <= 0.0 ||
      half_width_rad > kPlanetPassHalfWidthMaxRad) {
    throw InputError(name, half_width_rad, "an angle in (0, pi] rad");
  }
}

double default_planet_pass_half_width(int planets) {
  if (planets < 1) throw InputError("planets", planets, "an integer >= 1");
  return 2.0 * pi / planets;
}

double wrap_to_pi(double x_rad) {
  // (-pi, pi]: -pi itself goes to pi.
  const double w = x_rad - 2.0 * pi * std::ceil((x_rad - pi) / (2.0 * pi));
  return w;
}

double planet_pass_window(double phi_rad, double half_width_rad) {
  const double phi = wrap_to_pi(phi_rad);
  if (std::fabs(phi) >= half_width_rad) return 0.0;
  return 0.5 * (1.0 + std::cos(pi * phi / half_width_rad));
}

std::vector<double> ring_sensor_signal(const std::vector<std::vector<double>>& forces,
                                       const std::vector<double>& carrier_angle_rad,
                                       const std::vector<double>& planet_angles_rad,
                                       const RingSensor& sensor) {
  const std::size_t planets = planet_angles_rad.size();
  if (planets < 1) throw InputError("planet_angles", "none", "one angle per planet");
  if (forces.size() != planets) {
    throw InputError("forces", std::to_string(forces.size()) + " series",
                     "one per planet, " + std::to_string(planets));
  }
  for (std::size_t n = 0; n < planets; ++n) {
    if (forces[n].size() != carrier_angle_rad.size()) {
      throw InputError("forces[" + std::to_string(n) + "]",
                       std::to_string(forces[n].size()) + " samples",
                       "the carrier angle's " + std::to_string(carrier_angle_rad.size()));
    }
    if (!std::isfinite(planet_angles_rad[n])) {
      throw InputError("planet_angles[" + std::to_string(n) + "]", planet_angles_rad[n],
                       "a finite angle in rad");
    }
    for (double f : forces[n]) {
      if (!std::isfinite(f)) throw InputError("forces[" + std::to_string(n) + "]", f, "finite");
    }
  }
  for (double a : carrier_angle_rad) {
    if (!std::isfinite(a)) throw InputError("carrier_angle", a, "a finite angle in rad");
  }
  if (!std::isfinite(sensor.sensor_angle_rad)) {
    throw InputError("sensor_angle", sensor.sensor_angle_rad, "a finite angle in rad");
  }
  if (sensor.half_width_rad) check_planet_pass_half_width(*sensor.half_width_rad);
  const double d =
      sensor.half_width_rad.value_or(default_planet_pass_half_width(static_cast<int>(planets)));
  std::vector<double> y(carrier_angle_rad.size(), 0.0);
  for (std::size_t i = 0; i < y.size(); ++i) {
    double sum = 0.0;
    for (std::size_t n = 0; n < planets; ++n) {
      const double phi = carrier_angle_rad[i] + planet_angles_rad[n] - sensor.sensor_angle_rad;
      sum += planet_pass_window(phi, d) * forces[n][i];
    }
    y[i] = sum;
  }
  return y;
}

}  // namespace gearimpact::signals
