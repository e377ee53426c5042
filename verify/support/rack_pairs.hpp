// Rack-generated gear pairs the stiffness-model suites share, and a check
// that an input is refused with one InputError naming its field.
#pragma once

#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact::verify {

inline constexpr double degree = 3.141592653589793238462643383279502884 / 180.0;

// The paper's pair (z 20/80, m 2 mm, 20 deg, b 10 mm, E 206.8 GPa, nu 0.3,
// standard teeth, full round) with the bores of the ROSS peer run (20 mm and
// 60 mm), as in the header of paper_data/peer-values/ross-pair-a.csv.
inline GearPair ross_pair_a() {
  GearPair p;
  p.teeth1 = 20;
  p.teeth2 = 80;
  p.bore_diameter1_m = 20e-3;
  p.bore_diameter2_m = 60e-3;
  return p;
}

struct NamedRackPair {
  std::string name;
  GearPair pair;
};

// Pairs with different teeth, modules, widths, pressure angles, shifts and
// rack tip radii; bores put h_f = r_f / r_int near 3, inside the foundation
// fit's range.
inline std::vector<NamedRackPair> varied_rack_pairs() {
  std::vector<NamedRackPair> pairs{{"paper 20/80, ROSS bores", ross_pair_a()}};
  const auto bore_for = [](const GearPair& pair, Gear gear) {
    const double rp = 0.5 * teeth(pair, gear) * pair.module_m;
    const double rf = rp - (pair.dedendum_coefficient - profile_shift(pair, gear)) * pair.module_m;
    return 2.0 * rf / 3.0;
  };
  GearPair p;
  p.teeth1 = 17;
  p.teeth2 = 43;
  p.module_m = 3e-3;
  p.face_width_m = 20e-3;
  p.profile_shift1 = 0.4;
  p.profile_shift2 = -0.1;
  pairs.push_back({"17/43, m 3 mm, b 20 mm, x +0.4/-0.1", p});
  p = GearPair{};
  p.teeth1 = 30;
  p.teeth2 = 30;
  p.module_m = 4e-3;
  // The pair's one face width is the width in contact: of gears 30 mm and
  // 35 mm wide, 30 mm.
  p.face_width_m = 30e-3;
  pairs.push_back({"30/30, m 4 mm, b 30 mm", p});
  p = GearPair{};
  p.teeth1 = 25;
  p.teeth2 = 61;
  p.module_m = 1.5e-3;
  p.pressure_angle_rad = 25.0 * degree;
  p.face_width_m = 12e-3;
  p.profile_shift1 = 0.2;
  p.profile_shift2 = 0.1;
  p.rack_tip_radius_coefficient = 0.2;
  pairs.push_back({"25/61, m 1.5 mm, 25 deg, b 12 mm, x +0.2/+0.1, rho* 0.2", p});
  for (std::size_t i = 1; i < pairs.size(); ++i) {
    GearPair& pair = pairs[i].pair;
    pair.bore_diameter1_m = bore_for(pair, Gear::one);
    pair.bore_diameter2_m = bore_for(pair, Gear::two);
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
