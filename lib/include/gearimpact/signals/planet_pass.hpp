// The ring-housing sensor of a planetary stage (docs/planetary.md, "The
// ring-housing sensor"): a sensor fixed on the ring's housing at angle phi_0
// sees each planet's ring-mesh force through a planet-pass window,
//
//   y(t) = sum_n w(phi_n(t) - phi_0) (F_d,rn(t) - F_c,rn(t)),
//   w(phi) = (1 + cos(pi phi / D)) / 2 for |phi| < D, else 0,
//
// phi_n = theta_c + psi_n planet n's angle in the fixed frame, the difference
// wrapped to (-pi, pi]. With the default D = 2 pi / N the windows of N equally
// spaced planets sum to 1 at every carrier angle, so a constant force reads
// constant. The input is what a stage's run gives: a force series per planet
// and the carrier's angle series on one time grid. A housing transfer
// function (force to acceleration) is not applied.
#pragma once

#include <optional>
#include <vector>

#include "gearimpact/constants.hpp"

namespace gearimpact::signals {

// The half-width D: (0, pi] rad, the one place its range is kept; 2 pi / N by
// default. Throws InputError naming `name` outside the range.
inline constexpr double kPlanetPassHalfWidthMaxRad = pi;
void check_planet_pass_half_width(double half_width_rad, const char* name = "half_width");
double default_planet_pass_half_width(int planets);

// x wrapped to (-pi, pi].
double wrap_to_pi(double x_rad);

// w(phi) of the window of half-width D (phi wrapped first).
double planet_pass_window(double phi_rad, double half_width_rad);

struct RingSensor {
  double sensor_angle_rad = 0.0;         // phi_0, counter-clockwise from the fixed x axis
  std::optional<double> half_width_rad;  // D; absent: the default 2 pi / N
};

// y at each sample: forces[n][i] is planet n's F_d,rn - F_c,rn (N) at sample i,
// carrier_angle_rad[i] theta_c, planet_angles_rad[n] psi_n (counter-clockwise
// from the carrier axis). Throws InputError unless there is a planet, every
// force series has the carrier's length, every value is finite and D is in range.
std::vector<double> ring_sensor_signal(const std::vector<std::vector<double>>& forces,
                                       const std::vector<double>& carrier_angle_rad,
                                       const std::vector<double>& planet_angles_rad,
                                       const RingSensor& sensor = {});

}  // namespace gearimpact::signals
