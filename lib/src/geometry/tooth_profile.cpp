#include "gearimpact/geometry/tooth_profile.hpp"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// Pressure angle of the involute at radius r, from sqrt((r-Rb)(r+Rb)) so that
// it keeps full precision just above the base circle.
double pressure_angle_at(double base_radius, double radius) {
  const double tangent_length = std::sqrt((radius - base_radius) * (radius + base_radius));
  return std::atan2(tangent_length, base_radius);
}

}  // namespace

ContactArm contact_arm(const InvoluteTooth& tooth, double phi_rad) {
  const double rb = tooth.base_radius_m;
  const double roll = tooth.half_tooth_angle_rad + phi_rad;
  // (10)
  const double h = rb * (roll * std::cos(phi_rad) - std::sin(phi_rad));
  // (11)
  const double l =
      rb * (roll * std::sin(phi_rad) + std::cos(phi_rad) - std::cos(tooth.half_tooth_angle_rad));
  return {h, l};
}

double flank_half_angle(const InvoluteTooth& tooth, double radius_m) {
  const double a = pressure_angle_at(tooth.base_radius_m, radius_m);
  return tooth.half_tooth_angle_rad - (std::tan(a) - a);
}

PolarContact polar_contact(const InvoluteTooth& tooth, double x_m) {
  const double rb = tooth.base_radius_m;
  const double radius = std::hypot(rb, x_m);
  const double psi = flank_half_angle(tooth, radius);
  const double a = std::atan2(x_m, rb);
  const ContactArm arm{radius * std::sin(psi),
                       radius * std::cos(psi) - rb * std::cos(tooth.half_tooth_angle_rad)};
  return {arm, a - psi};
}

double section_half_thickness(const InvoluteTooth& tooth, double height_m) {
  const double rb = tooth.base_radius_m;
  const double root_height = rb * std::cos(tooth.half_tooth_angle_rad);
  // Within 1e-10 Rb of the base circle the root cannot be resolved against Rb
  // in double precision; there the section follows its expansion about the
  // base circle, y = Rb sin theta_b + height tan theta_b + O(height^1.5).
  if (height_m < 1e-10 * rb) {
    return rb * std::sin(tooth.half_tooth_angle_rad) +
           std::max(height_m, 0.0) * std::tan(tooth.half_tooth_angle_rad);
  }
  const auto excess_height = [&](double r) {
    return r * std::cos(flank_half_angle(tooth, r)) - root_height - height_m;
  };
  // Since psi < theta_b above the base circle, the height of radius r exceeds
  // (r - Rb) cos theta_b, so r = Rb + 2 height / cos theta_b brackets the
  // root (the factor 2 covers the rounding of Rb + height) unless the tooth is
  // pointed below that height.
  const double upper = rb + 2.0 * height_m / std::cos(tooth.half_tooth_angle_rad);
  if (flank_half_angle(tooth, upper) <= 0.0 && excess_height(upper) < 0.0) {
    throw InputError("section height", height_m, "heights below the pointed tip of the tooth");
  }
  std::uintmax_t iterations = 200;
  const auto bracket =
      boost::math::tools::toms748_solve(excess_height, rb, upper, -height_m, excess_height(upper),
                                        boost::math::tools::eps_tolerance<double>(), iterations);
  const double r = 0.5 * (bracket.first + bracket.second);
  return r * std::sin(flank_half_angle(tooth, r));
}

}  // namespace gearimpact
