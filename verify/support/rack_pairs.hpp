// Rack-generated gear pairs the stiffness-model suites share, and a check
// that an input is refused with one InputError naming its field.
#pragma once

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/rack_generation.hpp"

namespace gearimpact::verify {

inline constexpr double degree = 3.141592653589793238462643383279502884 / 180.0;

// The paper's pair (z 20/80, m 2 mm, 20 deg, b 10 mm, E 206.8 GPa, nu 0.3,
// standard teeth, full round) with the bores of the ROSS peer run (20 mm and
// 60 mm), as in the header of paper_data/peer-values/ross-pair-a.csv.
inline RackGearPair ross_pair_a() {
  RackGearPair p;
  p.gear1.teeth = 20;
  p.gear2.teeth = 80;
  p.gear1.bore_diameter_m = 20e-3;
  p.gear2.bore_diameter_m = 60e-3;
  return p;
}

struct NamedRackPair {
  std::string name;
  RackGearPair pair;
};

// Pairs with different teeth, modules, widths, pressure angles, shifts and
// rack tip radii; bores put h_f = r_f / r_int near 3, inside the foundation
// fit's range.
inline std::vector<NamedRackPair> varied_rack_pairs() {
  std::vector<NamedRackPair> pairs{{"paper 20/80, ROSS bores", ross_pair_a()}};
  const auto bore_for = [](const RackGear& g) {
    const double rp = 0.5 * g.teeth * g.module_m;
    const double rf =
        rp - (g.addendum_coefficient + g.clearance_coefficient - g.profile_shift_coefficient) *
                 g.module_m;
    return 2.0 * rf / 3.0;
  };
  RackGearPair p;
  p.gear1.teeth = 17;
  p.gear2.teeth = 43;
  p.gear1.module_m = p.gear2.module_m = 3e-3;
  p.gear1.face_width_m = p.gear2.face_width_m = 20e-3;
  p.gear1.profile_shift_coefficient = 0.4;
  p.gear2.profile_shift_coefficient = -0.1;
  pairs.push_back({"17/43, m 3 mm, b 20 mm, x +0.4/-0.1", p});
  p = RackGearPair{};
  p.gear1.teeth = 30;
  p.gear2.teeth = 30;
  p.gear1.module_m = p.gear2.module_m = 4e-3;
  p.gear1.face_width_m = 30e-3;
  p.gear2.face_width_m = 35e-3;
  pairs.push_back({"30/30, m 4 mm, b 30/35 mm", p});
  p = RackGearPair{};
  p.gear1.teeth = 25;
  p.gear2.teeth = 61;
  p.gear1.module_m = p.gear2.module_m = 1.5e-3;
  p.gear1.pressure_angle_rad = p.gear2.pressure_angle_rad = 25.0 * degree;
  p.gear1.face_width_m = p.gear2.face_width_m = 12e-3;
  p.gear1.profile_shift_coefficient = 0.2;
  p.gear2.profile_shift_coefficient = 0.1;
  p.gear1.rack_tip_radius_coefficient = p.gear2.rack_tip_radius_coefficient = 0.2;
  pairs.push_back({"25/61, m 1.5 mm, 25 deg, b 12 mm, x +0.2/+0.1, rho* 0.2", p});
  for (std::size_t i = 1; i < pairs.size(); ++i) {
    pairs[i].pair.gear1.bore_diameter_m = bore_for(pairs[i].pair.gear1);
    pairs[i].pair.gear2.bore_diameter_m = bore_for(pairs[i].pair.gear2);
  }
  return pairs;
}

// `action` must throw one InputError whose field is `field` and whose
// message contains `fragment` (the allowed range, with its number).
template <class Action>
void check_refused(Action action, const std::string& field, const std::string& fragment) {
  try {
    action();
    FAIL("accepted, expected an InputError for " << field);
  } catch (const InputError& e) {
    const std::string message = e.what();
    CAPTURE(message);
    CHECK(e.field() == field);
    CHECK(message.find(fragment) != std::string::npos);
  }
}

}  // namespace gearimpact::verify
