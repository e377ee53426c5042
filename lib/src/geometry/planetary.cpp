#include "gearimpact/geometry/planetary.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

namespace {

// x - floor(x), with x within rounding of an integer taken as that integer:
// Z psi / 2 pi of an assembled planet is an integer that psi's rounding
// would otherwise turn into 0.999...
double frac(double x) {
  const double nearest = std::round(x);
  if (std::fabs(x - nearest) <= 1e-10 * std::max(1.0, std::fabs(x))) return 0.0;
  return x - std::floor(x);
}

void require_toothing(const PlanetaryTeeth& teeth, const PlanetaryToothing& toothing) {
  if (teeth.sun < 1) throw InputError("sun_teeth", std::to_string(teeth.sun), "an integer >= 1");
  if (teeth.planet < 1) {
    throw InputError("planet_teeth", std::to_string(teeth.planet), "an integer >= 1");
  }
  if (teeth.ring <= teeth.planet) {
    throw InputError("ring_teeth", std::to_string(teeth.ring),
                     "an integer > planet_teeth = " + std::to_string(teeth.planet));
  }
  if (!std::isfinite(toothing.module_m) || toothing.module_m <= 0.0) {
    throw InputError("module", toothing.module_m, "a finite value > 0 in m");
  }
  if (!std::isfinite(toothing.pressure_angle_rad) || toothing.pressure_angle_rad <= 0.0 ||
      toothing.pressure_angle_rad >= 0.5 * pi) {
    throw InputError("pressure_angle", toothing.pressure_angle_rad, "an angle in (0, pi/2) rad");
  }
  if (!std::isfinite(toothing.addendum_coefficient) || toothing.addendum_coefficient <= 0.0) {
    throw InputError("addendum_coefficient", toothing.addendum_coefficient, "a finite value > 0");
  }
}

double base_radius_of(int z, const PlanetaryToothing& toothing) {
  return 0.5 * toothing.module_m * z * std::cos(toothing.pressure_angle_rad);
}

// The tip clearance of neighbouring planets dpsi apart: 2 R_c sin(dpsi / 2) > d_a,p.
bool tips_clear(double carrier_radius_m, double dpsi, double planet_tip_diameter_m) {
  return 2.0 * carrier_radius_m * std::sin(0.5 * dpsi) > planet_tip_diameter_m;
}

// k 360 / zsr deg to 17 significant digits, which read back to the same double.
std::string nearest_degrees(double k, int zsr) {
  std::ostringstream out;
  out << std::setprecision(17) << k * 360.0 / zsr;
  return out.str();
}

}  // namespace

InternalMesh internal_mesh(const PlanetaryTeeth& teeth, const PlanetaryToothing& toothing,
                           double centre_distance_m) {
  require_toothing(teeth, toothing);
  if (!std::isfinite(centre_distance_m) || centre_distance_m <= 0.0) {
    throw InputError("centre_distance", centre_distance_m, "a finite value > 0 in m");
  }
  InternalMesh g;
  const double m = toothing.module_m;
  g.ring_base_radius_m = base_radius_of(teeth.ring, toothing);
  g.planet_base_radius_m = base_radius_of(teeth.planet, toothing);
  g.ring_tip_radius_m = 0.5 * m * teeth.ring - toothing.addendum_coefficient * m;
  g.planet_tip_radius_m = 0.5 * m * teeth.planet + toothing.addendum_coefficient * m;
  if (g.ring_tip_radius_m <= g.ring_base_radius_m) {
    throw InputError("ring_teeth", std::to_string(teeth.ring),
                     "a ring whose tip circle (r - h_a m) lies outside its base circle "
                     "(full-depth 20 deg teeth need ring_teeth >= 34)");
  }
  const double cos_w = (g.ring_base_radius_m - g.planet_base_radius_m) / centre_distance_m;
  if (!(cos_w > 0.0 && cos_w < 1.0)) {
    throw InputError("centre_distance", centre_distance_m,
                     "a centre distance > Rb_ring - Rb_planet (the ring mesh's tie "
                     "a_w cos(alpha_r) = Rb_r - Rb_p)");
  }
  g.working_pressure_angle_rad = std::acos(cos_w);
  // T_b T_a = (Rb_a - Rb_b) tan a_w' = a_w sin a_w', both tangent points on
  // one side of the pitch point; a contact at rho_b from T_b is at
  // rho_b + a_w sin a_w' from T_a.
  const double t_b_t_a = centre_distance_m * std::sin(g.working_pressure_angle_rad);
  g.segment_start_m = std::sqrt(g.ring_tip_radius_m * g.ring_tip_radius_m -
                                g.ring_base_radius_m * g.ring_base_radius_m) -
                      t_b_t_a;
  g.segment_end_m = std::sqrt(g.planet_tip_radius_m * g.planet_tip_radius_m -
                              g.planet_base_radius_m * g.planet_base_radius_m);
  g.pitch_point_m = g.planet_base_radius_m * std::tan(g.working_pressure_angle_rad);
  g.base_pitch_m = 2.0 * pi * g.planet_base_radius_m / teeth.planet;
  if (g.segment_start_m < 0.0) {
    throw InputError("ring_teeth", std::to_string(teeth.ring),
                     "a ring-planet mesh whose active segment starts outside the planet's "
                     "tangent point T_b (else involute interference: the ring's tip cuts "
                     "the planet's base circle)");
  }
  g.contact_ratio = (g.segment_end_m - g.segment_start_m) / g.base_pitch_m;
  if (!(g.contact_ratio >= 1.0)) {
    throw InputError("ring_teeth", std::to_string(teeth.ring),
                     "a ring-planet mesh with contact ratio >= 1 (it is " +
                         std::to_string(g.contact_ratio) + ")");
  }
  return g;
}

WorkingAngles working_angles(const PlanetaryTeeth& teeth, const PlanetaryToothing& toothing,
                             double carrier_radius_m) {
  require_toothing(teeth, toothing);
  if (!std::isfinite(carrier_radius_m) || carrier_radius_m <= 0.0) {
    throw InputError("carrier_radius", carrier_radius_m, "a finite value > 0 in m");
  }
  WorkingAngles w;
  w.carrier_radius_m = carrier_radius_m;
  w.sun_base_radius_m = base_radius_of(teeth.sun, toothing);
  w.planet_base_radius_m = base_radius_of(teeth.planet, toothing);
  w.ring_base_radius_m = base_radius_of(teeth.ring, toothing);
  const double cos_s = (w.sun_base_radius_m + w.planet_base_radius_m) / carrier_radius_m;
  const double cos_r = (w.ring_base_radius_m - w.planet_base_radius_m) / carrier_radius_m;
  if (!(cos_s > 0.0 && cos_s < 1.0)) {
    throw InputError("carrier_radius", carrier_radius_m,
                     "a radius > Rb_s + Rb_p (the sun mesh's tie R_c cos(alpha_s) = Rb_s + Rb_p)");
  }
  if (!(cos_r > 0.0 && cos_r < 1.0)) {
    throw InputError("carrier_radius", carrier_radius_m,
                     "a radius > Rb_r - Rb_p (the ring mesh's tie R_c cos(alpha_r) = Rb_r - Rb_p)");
  }
  w.sun_rad = std::acos(cos_s);
  w.ring_rad = std::acos(cos_r);
  return w;
}

double standard_carrier_radius(const PlanetaryTeeth& teeth, const PlanetaryToothing& toothing) {
  require_toothing(teeth, toothing);
  if (teeth.ring != teeth.sun + 2 * teeth.planet) {
    throw InputError(
        "ring_teeth", std::to_string(teeth.ring),
        "sun_teeth + 2 planet_teeth = " + std::to_string(teeth.sun + 2 * teeth.planet) +
            " (unshifted sun and ring meshes at one centre distance)");
  }
  return 0.5 * toothing.module_m * (teeth.sun + teeth.planet);
}

std::vector<double> equal_planet_angles(const PlanetaryTeeth& teeth,
                                        const PlanetaryToothing& toothing, int planets) {
  require_toothing(teeth, toothing);
  if (planets < 1) throw InputError("planets", std::to_string(planets), "an integer >= 1");
  if ((teeth.sun + teeth.ring) % planets != 0) {
    throw InputError(
        "planets", std::to_string(planets),
        "a divisor of sun_teeth + ring_teeth = " + std::to_string(teeth.sun + teeth.ring) +
            " (equal spacing's assembly condition)");
  }
  std::vector<double> angles;
  for (int n = 0; n < planets; ++n) angles.push_back(2.0 * pi * n / planets);
  return checked_planet_angles(teeth, toothing, angles);
}

std::vector<double> checked_planet_angles(const PlanetaryTeeth& teeth,
                                          const PlanetaryToothing& toothing,
                                          const std::vector<double>& angles_rad) {
  require_toothing(teeth, toothing);
  if (angles_rad.empty()) throw InputError("planet_angles", "[]", "at least one angle");
  const double carrier_radius = 0.5 * toothing.module_m * (teeth.sun + teeth.planet);
  const double tip_diameter =
      toothing.module_m * (teeth.planet + 2.0 * toothing.addendum_coefficient);
  const int zsr = teeth.sun + teeth.ring;
  for (std::size_t n = 0; n < angles_rad.size(); ++n) {
    const double psi = angles_rad[n];
    const std::string field = "planet_angles[" + std::to_string(n + 1) + "]";
    if (!std::isfinite(psi) || psi < 0.0 || psi >= 2.0 * pi || (n == 0 && psi != 0.0) ||
        (n > 0 && psi <= angles_rad[n - 1])) {
      throw InputError(field, psi, "increasing angles in [0, 2 pi) rad, the first 0");
    }
    // (Z_s + Z_r) psi_n / (2 pi) an integer: the sun and ring teeth both fit.
    const double count = zsr * psi / (2.0 * pi);
    if (std::fabs(count - std::round(count)) > 1e-9 * std::max(1.0, std::fabs(count))) {
      throw InputError(field, nearest_degrees(count, zsr) + " deg",
                       "a multiple of 360 deg / (sun_teeth + ring_teeth) = 360 deg / " +
                           std::to_string(zsr) +
                           ", where the sun's and the ring's teeth both fit the planet (the "
                           "assembly condition)",
                       "the nearest such angle, " + nearest_degrees(std::round(count), zsr) +
                           " deg, written to all its digits");
    }
    const double next = n + 1 < angles_rad.size() ? angles_rad[n + 1] : 2.0 * pi;
    if (angles_rad.size() > 1 && !tips_clear(carrier_radius, next - psi, tip_diameter)) {
      throw InputError(field, psi,
                       "planets whose tips clear their neighbour's: 2 R_c sin(dpsi / 2) > "
                       "d_a,p = " +
                           std::to_string(tip_diameter) + " m");
    }
  }
  return angles_rad;
}

StageSpeeds willis_speeds(const PlanetaryTeeth& teeth, HeldMember held, double input_rad_per_s) {
  if (teeth.sun < 1 || teeth.planet < 1 || teeth.ring <= teeth.planet) {
    throw InputError("teeth",
                     std::to_string(teeth.sun) + ", " + std::to_string(teeth.planet) + ", " +
                         std::to_string(teeth.ring),
                     "sun, planet >= 1 and ring > planet");
  }
  const double zs = teeth.sun;
  const double zr = teeth.ring;
  StageSpeeds w;
  // (w_s - w_c) / (w_r - w_c) = -Z_r / Z_s, that is Z_s w_s + Z_r w_r = (Z_s + Z_r) w_c.
  switch (held) {
    case HeldMember::ring:
      w.sun = input_rad_per_s;
      w.carrier = zs / (zs + zr) * w.sun;
      break;
    case HeldMember::carrier:
      w.sun = input_rad_per_s;
      w.ring = -zs / zr * w.sun;
      break;
    case HeldMember::sun:
      w.ring = input_rad_per_s;
      w.carrier = zr / (zs + zr) * w.ring;
      break;
  }
  w.planet = w.carrier - zs / teeth.planet * (w.sun - w.carrier);
  return w;
}

double sun_mesh_phase(int sun_teeth, double psi_rad, bool sun_ahead) {
  const double g = frac(sun_teeth * psi_rad / (2.0 * pi));
  return sun_ahead ? g : frac(-g);
}

double ring_mesh_phase(int ring_teeth, double psi_rad, bool sun_ahead) {
  const double g = frac(-ring_teeth * psi_rad / (2.0 * pi));
  return sun_ahead ? g : frac(-g);
}

double sun_ring_phase(const PlanetaryTeeth& teeth, const PlanetaryToothing& toothing,
                      double sun_angle_rad, double ring_angle_rad, bool sun_ahead) {
  require_toothing(teeth, toothing);
  // (13) for the unshifted planet: theta_bp = pi / (2 Z_p) + inv a0.
  const double theta_bp =
      pi / (2.0 * teeth.planet) + involute_function(toothing.pressure_angle_rad);
  const double g = frac(
      teeth.planet *
      (2.0 * theta_bp - involute_function(sun_angle_rad) - involute_function(ring_angle_rad) - pi) /
      (2.0 * pi));
  return sun_ahead ? g : frac(-g);
}

HarmonicType harmonic_type(int harmonic, int sun_teeth, int planets) {
  if (harmonic < 1) throw InputError("harmonic", std::to_string(harmonic), "an integer >= 1");
  if (planets < 1) throw InputError("planets", std::to_string(planets), "an integer >= 1");
  if (sun_teeth < 1) throw InputError("sun_teeth", std::to_string(sun_teeth), "an integer >= 1");
  const long k = (static_cast<long>(harmonic) * sun_teeth) % planets;
  if (k == 0) return HarmonicType::rotational;
  if (k == 1 || k == planets - 1) return HarmonicType::translational;
  return HarmonicType::planet;
}

}  // namespace gearimpact
