// docs/stiffness-models.md section 2: the tooth-beam compliances. Closed forms
// for beams whose integrals are known, then every integral of the real teeth
// (trochoid + involute from the root circle) by the two routes of
// tooth_beam.hpp, which share only the flank's points.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/tooth_beam.hpp"
#include "rack_pairs.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

constexpr StiffnessRoute both_routes[] = {StiffnessRoute::tau_form, StiffnessRoute::x_form};

std::string name_of(StiffnessRoute route) {
  return route == StiffnessRoute::tau_form ? "profile parameter" : "section height";
}

// Steel, 10 mm wide.
constexpr BeamMaterial steel{206.8e9, 206.8e9 / 2.6, 10e-3};

// A rectangular tooth of half thickness h from y = 0 to y = l.
FlankPiece rectangle(double h, double l) {
  return {[h](double y) { return ProfilePoint{h, y, 0.0, 1.0}; }, 0.0, l};
}

// Every quadrature is asked for 1e-12 and meets it by its own estimate;
// integrals known in closed form may differ by that and the rounding of the
// closed form: 1e-11 leaves a factor 10.
constexpr double closed_form_bound = 1e-11;

}  // namespace

TEST_CASE("closed forms: a uniform rectangular tooth") {
  const double h = 1.5e-3;  // half thickness
  const double l = 4.0e-3;  // height, root to load
  const double b = steel.width_m;
  const double area = 2.0 * h * b;
  const double second_moment = 2.0 / 3.0 * h * h * h * b;
  for (StiffnessRoute route : both_routes) {
    CAPTURE(name_of(route));
    // Load straight across (tau = 0) at the tip: a cantilever,
    // bending l^3 / (3 E I), shear 1.2 l / (G A), no axial part.
    const BeamCompliance across =
        tooth_beam_compliance({rectangle(h, l)}, {h, l, 0.0}, steel, route);
    CHECK(relative_difference(across.bending_m_per_n,
                              l * l * l / (3.0 * steel.youngs_modulus_pa * second_moment)) <=
          closed_form_bound);
    CHECK(relative_difference(across.shear_m_per_n, 1.2 * l / (steel.shear_modulus_pa * area)) <=
          closed_form_bound);
    CHECK(across.axial_m_per_n == 0.0);
    // Load along the tooth (tau = pi/2) on its centre line (x_t = 0): a
    // column, axial l / (E A); the bending arm cos(pi/2) (l - y) is rounding.
    const BeamCompliance along =
        tooth_beam_compliance({rectangle(h, l)}, {0.0, l, 0.5 * pi}, steel, route);
    CHECK(relative_difference(along.axial_m_per_n, l / (steel.youngs_modulus_pa * area)) <=
          closed_form_bound);
    CHECK(along.bending_m_per_n <= 1e-30);
  }
}

TEST_CASE("closed forms: a tapered tooth in two pieces, one parametrised downwards") {
  // x(y) = h0 + k y on [0, l], split at l/2: the lower piece with y = 2 p
  // (y' = 2), the upper with p running downwards from the top (y = l - p,
  // y' = -1). Load across at the top, tau = 0. With u = h0 + k y and
  // h1 = h0 + k l:
  //   bending (3 / (2 E b k^3)) [3/2 + h1^2 / (2 h0^2) - 2 h1 / h0 + ln(h1 / h0)]
  //   shear   1.2 ln(h1 / h0) / (2 G b k)
  // and, for tau = pi/2, axial ln(h1 / h0) / (2 E b k).
  const double h0 = 2.0e-3;
  const double k = -0.3;
  const double l = 3.0e-3;
  const double h1 = h0 + k * l;
  const std::vector<FlankPiece> flank{
      {[=](double p) {
         return ProfilePoint{h0 + k * 2.0 * p, 2.0 * p, 2.0 * k, 2.0};
       },
       0.0, 0.25 * l},
      {[=](double p) {
         return ProfilePoint{h0 + k * (l - p), l - p, -k, -1.0};
       },
       0.5 * l, 0.0}};
  const double e = steel.youngs_modulus_pa;
  const double g = steel.shear_modulus_pa;
  const double b = steel.width_m;
  const double log_ratio = std::log(h1 / h0);
  const double bending = 3.0 / (2.0 * e * b * k * k * k) *
                         (1.5 + h1 * h1 / (2.0 * h0 * h0) - 2.0 * h1 / h0 + log_ratio);
  for (StiffnessRoute route : both_routes) {
    CAPTURE(name_of(route));
    const BeamCompliance across = tooth_beam_compliance(flank, {h1, l, 0.0}, steel, route);
    CHECK(relative_difference(across.bending_m_per_n, bending) <= closed_form_bound);
    CHECK(relative_difference(across.shear_m_per_n, 1.2 * log_ratio / (2.0 * g * b * k)) <=
          closed_form_bound);
    const BeamCompliance along = tooth_beam_compliance(flank, {0.0, l, 0.5 * pi}, steel, route);
    CHECK(relative_difference(along.axial_m_per_n, log_ratio / (2.0 * e * b * k)) <=
          closed_form_bound);
  }
}

TEST_CASE("two routes: every beam integral of the real teeth agrees to 1e-10") {
  // Each route meets 1e-12 by its own estimate; they share the flank's
  // points only (route 1 uses y'(p) and Boost, route 2 root-finds sections
  // and uses GSL), so a slip in y'(p), a limit or a piece's orientation
  // separates them by far more than 1e-10.
  constexpr double bound = 1e-10;
  double worst = 0.0;
  std::string worst_where;
  int compared = 0;
  for (const auto& named : verify::varied_rack_pairs()) {
    const RackGearPairGeometry pair = rack_gear_pair_geometry(named.pair);
    for (int i = 0; i <= 16; ++i) {
      const double s = pair.start_of_active_profile_m +
                       (pair.end_of_active_profile_m - pair.start_of_active_profile_m) * i / 16.0;
      const PairContact contact = pair_contact(pair, s);
      for (int gear_index = 0; gear_index < 2; ++gear_index) {
        const RackGearGeometry& gear = gear_index == 0 ? pair.gear1 : pair.gear2;
        const ToothContact& c = gear_index == 0 ? contact.gear1 : contact.gear2;
        const BeamMaterial material{gear.youngs_modulus_pa,
                                    gear.youngs_modulus_pa / (2.0 * (1.0 + gear.poisson_ratio)),
                                    pair.contact_width_m};
        const std::vector<FlankPiece> flank = flank_to_contact(gear, c.tau_rad);
        const BeamCompliance a = tooth_beam_compliance(flank, {c.x_m, c.y_m, c.tau_rad}, material,
                                                       StiffnessRoute::tau_form);
        const BeamCompliance b = tooth_beam_compliance(flank, {c.x_m, c.y_m, c.tau_rad}, material,
                                                       StiffnessRoute::x_form);
        const std::string where =
            named.name + ", gear " + std::to_string(gear_index + 1) + ", s = " + format_number(s);
        CAPTURE(where);
        const double d[3] = {relative_difference(a.bending_m_per_n, b.bending_m_per_n),
                             relative_difference(a.shear_m_per_n, b.shear_m_per_n),
                             relative_difference(a.axial_m_per_n, b.axial_m_per_n)};
        for (double difference : d) {
          CHECK(difference <= bound);
          if (difference > worst) {
            worst = difference;
            worst_where = where;
          }
          ++compared;
        }
      }
    }
  }
  MESSAGE("two routes: " << compared << " integrals, worst relative difference " << worst << " at "
                         << worst_where);
  CHECK(compared == 4 * 17 * 2 * 3);
}

TEST_CASE("the fillet matters: the tooth from the root circle is more compliant than from r_c") {
  // Dropping the trochoid piece leaves the involute from the form radius
  // only: every integrand is positive, so each compliance must fall, and
  // bending most near the root (the fillet carries the largest moment).
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  const PairContact contact =
      pair_contact(pair, 0.5 * (pair.start_of_active_profile_m + pair.end_of_active_profile_m));
  const ToothContact& c = contact.gear1;
  const BeamMaterial material{pair.gear1.youngs_modulus_pa, pair.gear1.youngs_modulus_pa / 2.6,
                              pair.contact_width_m};
  std::vector<FlankPiece> flank = flank_to_contact(pair.gear1, c.tau_rad);
  const BeamCompliance whole =
      tooth_beam_compliance(flank, {c.x_m, c.y_m, c.tau_rad}, material, StiffnessRoute::tau_form);
  flank.erase(flank.begin());
  const BeamCompliance involute_only =
      tooth_beam_compliance(flank, {c.x_m, c.y_m, c.tau_rad}, material, StiffnessRoute::tau_form);
  CHECK(whole.bending_m_per_n > involute_only.bending_m_per_n);
  CHECK(whole.shear_m_per_n > involute_only.shear_m_per_n);
  CHECK(whole.axial_m_per_n > involute_only.axial_m_per_n);
  MESSAGE("paper pinion at mid-path: the fillet adds "
          << 100.0 * (whole.bending_m_per_n / involute_only.bending_m_per_n - 1.0)
          << " % to bending, " << 100.0 * (whole.shear_m_per_n / involute_only.shear_m_per_n - 1.0)
          << " % to shear, " << 100.0 * (whole.axial_m_per_n / involute_only.axial_m_per_n - 1.0)
          << " % to axial");
}
