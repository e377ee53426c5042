// The gear pair and its involute geometry: MODEL.md, section Geometry.
// All lengths in metres, angles in radians, SI throughout.
#pragma once

#include <array>
#include <cstddef>

namespace gearimpact {

// Two standard involute spur gears on their standard centre distance. Pitch
// radius r_i = module * Z_i / 2, tip radius r_i + addendum.
struct GearPair {
  int teeth1 = 20;
  int teeth2 = 80;
  double module_m = 2.0e-3;
  double pressure_angle_rad = 0.3490658503988659;  // 20 deg
  double face_width_m = 10.0e-3;
  double addendum_coefficient = 1.0;  // addendum = coefficient * module
  double youngs_modulus_pa = 206.8e9;
  double poisson_ratio = 0.3;
  double density_kg_m3 = 7800.0;
  double backlash_m = 0.05e-3;
};

// Section 7 of the paper with MODEL.md's defaults for what it leaves unstated.
GearPair paper_gear_pair();

// Throws InputError naming the first field outside its range: counts and
// material, the undercut limit on teeth, pointed teeth, interference (a tip
// beyond the mating base-circle tangent point), and a contact ratio below 1.
void validate(const GearPair& pair);

// Which gear of the pair: 1 the pinion (driver in the paper), 2 the wheel.
enum class Gear { one = 1, two = 2 };

int teeth(const GearPair& pair, Gear gear);
double pitch_radius(const GearPair& pair, Gear gear);
double tip_radius(const GearPair& pair, Gear gear);
double base_radius(const GearPair& pair, Gear gear);

// inv a = tan a - a.
double involute_function(double angle_rad);

// (13),(27) theta_b_i = pi/(2 Z_i) + inv a0: half the tooth angle on the base circle.
double half_tooth_angle(const GearPair& pair, Gear gear);

// lp = (Rb1 + Rb2) tan a0: distance C1C2 along the line of action.
double line_of_action_length(const GearPair& pair);

// X_pitch = Rb1 tan a0: the pitch point measured from C1.
double pitch_point_position(const GearPair& pair);

// The contact segment on the line of action, measured from C1:
// X_start = lp - sqrt(ra2^2 - Rb2^2) (tip of gear 2), X_end = sqrt(ra1^2 - Rb1^2).
struct ContactSegment {
  double start_m;
  double end_m;
};
ContactSegment contact_segment(const GearPair& pair);

// (41) t0 = pi m cos a0.
double base_pitch(const GearPair& pair);

// (X_end - X_start) / t0.
double contact_ratio(const GearPair& pair);

// Contact position X1 (from C1) to the contact angle of each gear:
// (12) phi1 = X1/Rb1 - theta_b1; (25),(26) phi2 = (lp - X1)/Rb2 - theta_b2.
double contact_angle(const GearPair& pair, Gear gear, double x1_m);
// Inverse of (12): X1 = Rb1 (phi1 + theta_b1).
double contact_position_from_phi1(const GearPair& pair, double phi1_rad);

// The two lines of action of (1)-(3): N1 (drive flanks, s > B), N2 (coast flanks).
enum class ContactLine { n1, n2 };

// Where the coast-flank contacts sit relative to the drive-flank ones.
enum class CoastPhase {
  half_base_pitch,  // default: X' = X_pitch - Rb1 theta1 + t0/2 + k t0 (geometric)
  in_phase,         // literal reading of (9): X' = X_pitch - Rb1 theta1 + k t0
};

// Positions on `line` of every pair whose contact lies in [X_start, X_end], for
// gear-1 rotation theta1, by (42): on N1, X = X_pitch + Rb1 theta1 + k t0.
// Sorted ascending. A pair exactly on an end point counts as loaded.
struct LoadedPairs {
  static constexpr std::size_t capacity = 4;
  std::array<double, capacity> position_m{};
  std::size_t count = 0;
};
LoadedPairs loaded_pairs(const GearPair& pair, ContactLine line, double theta1_rad,
                         CoastPhase coast_phase = CoastPhase::half_base_pitch);

// Solid discs on the pitch radius: J = rho pi r^4 L / 2.
double moment_of_inertia(const GearPair& pair, Gear gear);

}  // namespace gearimpact
