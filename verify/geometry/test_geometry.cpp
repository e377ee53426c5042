// docs/model.md, section Geometry: every function checked against an independent
// formulation (the polar involute, the tip-pressure-angle form of the contact
// ratio, the circular pitch) or a closed form.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_profile.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

// Geometry is a few arithmetic operations and one tan/sqrt per quantity; a
// few ulps of each, times the cancellation in lp - sqrt(...) (about 20 for
// X_start), stay below 1e-13.
constexpr double geometry_tolerance = 1e-13;

GearPair pair_17_43_at_25_deg() {
  GearPair pair = paper_gear_pair();
  pair.teeth1 = 17;
  pair.teeth2 = 43;
  pair.pressure_angle_rad = 25.0 * deg;
  return pair;
}

}  // namespace

TEST_CASE("(13),(27) half tooth angle: the involute at the pitch radius is half a tooth wide") {
  // Standard teeth are pi m / 2 thick on the pitch circle, i.e. pi/(2 Z) each
  // side of the centre line; the polar involute of tooth_profile must give that
  // at r = m Z / 2 from the theta_b of (13).
  for (const GearPair& pair : {paper_gear_pair(), pair_17_43_at_25_deg()}) {
    for (Gear gear : {Gear::one, Gear::two}) {
      const InvoluteTooth tooth{base_radius(pair, gear), half_tooth_angle(pair, gear)};
      const double at_pitch = flank_half_angle(tooth, pitch_radius(pair, gear));
      CHECK(relative_difference(at_pitch, std::numbers::pi / (2.0 * teeth(pair, gear))) <
            geometry_tolerance);
    }
  }
}

TEST_CASE("pitch point and lp: X_pitch = Rb1 tan a0 lies on both pitch circles") {
  for (const GearPair& pair : {paper_gear_pair(), pair_17_43_at_25_deg()}) {
    const double x_pitch = pitch_point_position(pair);
    const double lp = line_of_action_length(pair);
    CHECK(relative_difference(std::hypot(base_radius(pair, Gear::one), x_pitch),
                              pitch_radius(pair, Gear::one)) < geometry_tolerance);
    CHECK(relative_difference(std::hypot(base_radius(pair, Gear::two), lp - x_pitch),
                              pitch_radius(pair, Gear::two)) < geometry_tolerance);
    // C1C2 is the common tangent of the base circles: lp^2 + (Rb1 + Rb2)^2 = a^2.
    const double centre_distance = pitch_radius(pair, Gear::one) + pitch_radius(pair, Gear::two);
    const double rb_sum = base_radius(pair, Gear::one) + base_radius(pair, Gear::two);
    CHECK(relative_difference(std::hypot(lp, rb_sum), centre_distance) < geometry_tolerance);
  }
}

TEST_CASE("contact segment ends are where each tip circle meets the line of action") {
  for (const GearPair& pair : {paper_gear_pair(), pair_17_43_at_25_deg()}) {
    const ContactSegment segment = contact_segment(pair);
    const double lp = line_of_action_length(pair);
    CHECK(relative_difference(std::hypot(base_radius(pair, Gear::one), segment.end_m),
                              tip_radius(pair, Gear::one)) < geometry_tolerance);
    CHECK(relative_difference(std::hypot(base_radius(pair, Gear::two), lp - segment.start_m),
                              tip_radius(pair, Gear::two)) < geometry_tolerance);
  }
}

TEST_CASE("(41) base pitch equals the circular pitch of either base circle") {
  for (const GearPair& pair : {paper_gear_pair(), pair_17_43_at_25_deg()}) {
    for (Gear gear : {Gear::one, Gear::two}) {
      CHECK(relative_difference(base_pitch(pair), 2.0 * std::numbers::pi * base_radius(pair, gear) /
                                                      teeth(pair, gear)) < geometry_tolerance);
    }
  }
}

TEST_CASE("contact ratio: the paper's pair and the tip-pressure-angle formula") {
  const GearPair paper = paper_gear_pair();
  // docs/model.md, Geometry: "contact ratio (X_end - X_start) / t0 (1.69 here)",
  // given to two decimals.
  CHECK(std::abs(contact_ratio(paper) - 1.69) < 0.005);
  // Textbook form: eps = [Z1 (tan a_a1 - tan a0) + Z2 (tan a_a2 - tan a0)] / (2 pi),
  // with a_ai the pressure angle at the tip, an independent expression.
  for (const GearPair& pair : {paper, pair_17_43_at_25_deg()}) {
    double sum = 0.0;
    for (Gear gear : {Gear::one, Gear::two}) {
      const double tip_angle = std::acos(base_radius(pair, gear) / tip_radius(pair, gear));
      sum += teeth(pair, gear) * (std::tan(tip_angle) - std::tan(pair.pressure_angle_rad));
    }
    CHECK(relative_difference(contact_ratio(pair), sum / (2.0 * std::numbers::pi)) <
          geometry_tolerance);
  }
}

TEST_CASE("(9),(12): theta1 = 0 puts a drive contact at the pitch point, phi1 = a0 - pi/(2 Z1)") {
  const GearPair pair = paper_gear_pair();
  const double phi1 = contact_angle(pair, Gear::one, pitch_point_position(pair));
  CHECK(relative_difference(phi1, pair.pressure_angle_rad -
                                      std::numbers::pi / (2.0 * pair.teeth1)) < geometry_tolerance);
  const LoadedPairs on_n1 = loaded_pairs(pair, Region::n1, 0.0);
  bool pitch_point_loaded = false;
  for (std::size_t i = 0; i < on_n1.count; ++i) {
    pitch_point_loaded |= std::abs(on_n1.position_m[i] - pitch_point_position(pair)) < 1e-15;
  }
  CHECK(pitch_point_loaded);
  // (12) inverted.
  CHECK(relative_difference(contact_position_from_phi1(pair, phi1), pitch_point_position(pair)) <
        geometry_tolerance);
}

TEST_CASE("(12),(25),(26) contact angles equal the polar involute's a_r - psi(r)") {
  // The polar form finds phi as the angle between the load line and the
  // normal to the centre line at the contact point, without (12).
  for (const GearPair& pair : {paper_gear_pair(), pair_17_43_at_25_deg()}) {
    const ContactSegment segment = contact_segment(pair);
    const double lp = line_of_action_length(pair);
    for (int i = 0; i <= 20; ++i) {
      const double x1 = segment.start_m + (segment.end_m - segment.start_m) * i / 20.0;
      const PolarContact c1 =
          polar_contact({base_radius(pair, Gear::one), half_tooth_angle(pair, Gear::one)}, x1);
      const PolarContact c2 =
          polar_contact({base_radius(pair, Gear::two), half_tooth_angle(pair, Gear::two)}, lp - x1);
      // Absolute in radians: phi1 passes through zero near X_start.
      CHECK(std::abs(c1.phi_rad - contact_angle(pair, Gear::one, x1)) < 1e-14);
      CHECK(std::abs(c2.phi_rad - contact_angle(pair, Gear::two, x1)) < 1e-14);
    }
  }
}

TEST_CASE("(42) pairs a base pitch apart; two pairs for a fraction eps - 1 of each pitch") {
  for (const GearPair& pair : {paper_gear_pair(), pair_17_43_at_25_deg()}) {
    const ContactSegment segment = contact_segment(pair);
    const double t0 = base_pitch(pair);
    const double eps = contact_ratio(pair);
    // One base pitch of gear-1 rotation, sampled finely: the share of two-pair
    // positions must be eps - 1, up to the sampling resolution.
    const int samples = 100000;
    const double rotation_per_pitch = t0 / base_radius(pair, Gear::one);
    int two = 0;
    for (int i = 0; i < samples; ++i) {
      const double theta1 = rotation_per_pitch * (i + 0.5) / samples;
      for (Region line : {Region::n1, Region::n2}) {
        const LoadedPairs loaded = loaded_pairs(pair, line, theta1);
        REQUIRE(loaded.count >= 1);
        REQUIRE(loaded.count <= 2);
        for (std::size_t k = 0; k < loaded.count; ++k) {
          CHECK(loaded.position_m[k] >= segment.start_m);
          CHECK(loaded.position_m[k] <= segment.end_m);
          if (k > 0) {
            CHECK(std::abs(loaded.position_m[k] - loaded.position_m[k - 1] - t0) < 1e-15);
          }
        }
        if (line == Region::n1 && loaded.count == 2) ++two;
      }
    }
    CHECK(std::abs(static_cast<double>(two) / samples - (eps - 1.0)) < 2.0 / samples);
  }
}

TEST_CASE(
    "coast line N2: half a base pitch from the drive contacts by default, in phase as option") {
  const GearPair pair = paper_gear_pair();
  const double t0 = base_pitch(pair);
  const double theta1 = 0.004;  // any rotation
  const double rolled = base_radius(pair, Gear::one) * theta1;
  // A standard tooth is half a circular pitch thick on the pitch circle, so
  // its coast flank crosses the pitch point a half angular pitch, pi/Z1, of
  // rotation after the drive flank: Rb1 pi / Z1 = t0 / 2 along the line.
  const double half_pitch_roll = base_radius(pair, Gear::one) * std::numbers::pi / pair.teeth1;
  CHECK(relative_difference(half_pitch_roll, t0 / 2.0) < geometry_tolerance);
  for (CoastPhase phase : {CoastPhase::half_base_pitch, CoastPhase::in_phase}) {
    const double offset = phase == CoastPhase::half_base_pitch ? half_pitch_roll : 0.0;
    const LoadedPairs loaded = loaded_pairs(pair, Region::n2, theta1, phase);
    for (std::size_t k = 0; k < loaded.count; ++k) {
      const double pitches =
          (loaded.position_m[k] - pitch_point_position(pair) + rolled - offset) / t0;
      CHECK(std::abs(pitches - std::round(pitches)) < 1e-12);
    }
  }
}

TEST_CASE("inertia of a solid disc on the pitch radius") {
  const GearPair pair = paper_gear_pair();
  // rho pi r^4 L / 2 with r = 20 mm: 7800 * pi * (0.02)^4 * 0.01 / 2.
  CHECK(relative_difference(moment_of_inertia(pair, Gear::one),
                            7800.0 * std::numbers::pi * 1.6e-7 * 0.01 / 2.0) < 1e-15);
  CHECK(relative_difference(moment_of_inertia(pair, Gear::two) / moment_of_inertia(pair, Gear::one),
                            256.0) < 1e-14);
}

namespace {

std::string error_of(const GearPair& pair) {
  try {
    validate(pair);
  } catch (const InputError& e) {
    return e.field() + " | " + e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("bad gear pairs are refused with the field and its allowed range") {
  CHECK(error_of(paper_gear_pair()) == "no error");
  CHECK(error_of(pair_17_43_at_25_deg()) == "no error");

  GearPair pair = paper_gear_pair();
  pair.poisson_ratio = 0.5;
  CHECK(error_of(pair).find("poisson_ratio | poisson_ratio = 0.5") == 0);
  CHECK(error_of(pair).find("(-1, 0.5)") != std::string::npos);

  pair = paper_gear_pair();
  pair.backlash_m = -1e-5;
  CHECK(error_of(pair).find("backlash |") == 0);
  CHECK(error_of(pair).find(">= 0") != std::string::npos);

  pair = paper_gear_pair();
  pair.youngs_modulus_pa = 0.0;
  CHECK(error_of(pair).find("youngs_modulus |") == 0);

  pair = paper_gear_pair();
  pair.density_kg_m3 = std::nan("");
  CHECK(error_of(pair).find("density |") == 0);

  // 2 ha / sin^2(20 deg) = 17.1: 17 teeth undercut, the limit is named.
  pair = paper_gear_pair();
  pair.teeth1 = 17;
  CHECK(error_of(pair).find("teeth1 |") == 0);
  CHECK(error_of(pair).find("17.097") != std::string::npos);

  // A short addendum: contact ratio below 1.
  pair = paper_gear_pair();
  pair.addendum_coefficient = 0.5;
  CHECK(error_of(pair).find("contact_ratio |") == 0);

  // 12 teeth against 80: the wheel's tip passes C1, the tangent point on
  // base circle 1 (X_start < 0), and the pinion is undercut; the tooth count
  // is blamed, not the addendum.
  pair = paper_gear_pair();
  pair.teeth1 = 12;
  const std::string interference = error_of(pair);
  CAPTURE(interference);
  CHECK(interference.find("teeth1 |") == 0);
  CHECK(interference.find("undercuts") != std::string::npos);
}

TEST_CASE("the fixes of a small pinion: the fewest teeth and the smallest shift, by the relation") {
  // teeth1 = 15 at x1 = 0 (the case of a user who thought it fine): undercut below
  // 2 (ha - x) / sin^2(a0), with X_start < 0 too.
  const double sin2 = std::pow(std::sin(20.0 * std::numbers::pi / 180.0), 2);
  for (const int z : {12, 15, 17}) {
    CAPTURE(z);
    GearPair pair = paper_gear_pair();
    pair.teeth1 = z;
    const std::optional<int> fewest = smallest_teeth_for_shift(pair, Gear::one);
    const std::optional<double> shift = smallest_shift_for_teeth(pair, Gear::one);
    REQUIRE(fewest);
    REQUIRE(shift);
    // The independent route: the undercut limit of the rack at x = 0, ceil(2 / sin^2 a0) = 18,
    // and at z, x = 1 - z sin^2(a0) / 2 rounded up to 0.001 (interference at the root binds
    // later for these pairs).
    CHECK(*fewest == 18);
    CHECK(*shift ==
          doctest::Approx(std::ceil((1.0 - z * sin2 / 2.0) * 1000.0) / 1000.0).epsilon(1e-12));
    // The relation just holds at the fix and just fails either side: one tooth fewer, or
    // 0.001 less shift, and validate names teeth1 again.
    const auto blames_teeth1 = [](const GearPair& p) {
      try {
        validate(p);
      } catch (const InputError& e) {
        return e.field() == "teeth1";
      }
      return false;
    };
    GearPair at = pair;
    at.teeth1 = *fewest;
    CHECK(error_of(at) == "no error");
    at.teeth1 = *fewest - 1;
    CHECK(blames_teeth1(at));
    at = pair;
    at.profile_shift1 = *shift;
    CHECK(!blames_teeth1(at));
    at.profile_shift1 = *shift - 0.001;
    CHECK(blames_teeth1(at));
    // The message names both.
    const std::string message = error_of(pair);
    CHECK(message.find("fix: teeth1 = 18 (the fewest at profile_shift1 = 0), or profile_shift1 = " +
                       format_number(*shift)) != std::string::npos);
  }
}

TEST_CASE("both gears' refusals at once") {
  GearPair pair = paper_gear_pair();
  pair.teeth1 = 12;
  pair.teeth2 = 12;
  try {
    validate_geometry(pair);
    FAIL("no error");
  } catch (const InputError& e) {
    REQUIRE(e.problems().size() == 2);
    CHECK(e.problems()[0].field == "teeth1");
    CHECK(e.problems()[1].field == "teeth2");
    CHECK(std::string(e.what()).find("(1 of 2 problems, one per line)\nteeth2 = 12") !=
          std::string::npos);
  }
}
