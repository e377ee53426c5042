#include "gearimpact/geometry/train_teeth.hpp"

#include <cmath>
#include <numeric>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

void require_teeth(const char* name, int teeth) {
  if (teeth < 1) throw InputError(name, teeth, "an integer >= 1");
}

// ceil(x) as an integer.
long long whole_pitches_up(double x) {
  return static_cast<long long>(std::ceil(x));
}

}  // namespace

long long whole_pitches(double x) {
  return static_cast<long long>(std::floor(x));
}

TeethInContact mesh_teeth_at(const GearPair& pair, double theta_a_rad) {
  const long long n = whole_pitches(pair.teeth1 * theta_a_rad / (2.0 * pi));
  return {tooth_number(n, pair.teeth1), tooth_number(n, pair.teeth2)};
}

long long hunting_period_mesh_periods(int teeth_a, int teeth_b) {
  require_teeth("teeth_a", teeth_a);
  require_teeth("teeth_b", teeth_b);
  return std::lcm(static_cast<long long>(teeth_a), static_cast<long long>(teeth_b));
}

StageMeshTeeth stage_mesh_teeth(const PlanetaryTeeth& teeth, double psi_n_rad, double sun_rad,
                                double planet_rad, double ring_rad) {
  require_teeth("sun_teeth", teeth.sun);
  require_teeth("planet_teeth", teeth.planet);
  require_teeth("ring_teeth", teeth.ring);
  const double turn = 2.0 * pi;
  StageMeshTeeth t;
  t.sun = tooth_number(whole_pitches(teeth.sun * (sun_rad - psi_n_rad) / turn), teeth.sun);
  t.planet_at_sun =
      tooth_number(whole_pitches_up(teeth.planet * (planet_rad - pi) / turn), teeth.planet);
  t.planet_at_ring = tooth_number(whole_pitches_up(teeth.planet * planet_rad / turn), teeth.planet);
  t.ring = tooth_number(whole_pitches_up(teeth.ring * (ring_rad - psi_n_rad) / turn), teeth.ring);
  return t;
}

long long stage_period_mesh_periods(const PlanetaryTeeth& teeth) {
  require_teeth("sun_teeth", teeth.sun);
  require_teeth("planet_teeth", teeth.planet);
  require_teeth("ring_teeth", teeth.ring);
  return std::lcm(std::lcm(static_cast<long long>(teeth.sun), static_cast<long long>(teeth.planet)),
                  static_cast<long long>(teeth.ring));
}

StageFaultFrequencies stage_fault_frequencies(const PlanetaryTeeth& teeth, int planets,
                                              double carrier_hz) {
  require_teeth("sun_teeth", teeth.sun);
  require_teeth("planet_teeth", teeth.planet);
  require_teeth("ring_teeth", teeth.ring);
  if (planets < 1) throw InputError("planets", planets, "an integer >= 1");
  if (!std::isfinite(carrier_hz))
    throw InputError("carrier_hz", carrier_hz, "a finite value in Hz");
  StageFaultFrequencies f;
  f.mesh_hz = teeth.ring * carrier_hz;
  f.sun_tooth_hz = planets * f.mesh_hz / teeth.sun;
  f.planet_tooth_hz = f.mesh_hz / teeth.planet;
  f.ring_tooth_hz = planets * carrier_hz;
  return f;
}

}  // namespace gearimpact
