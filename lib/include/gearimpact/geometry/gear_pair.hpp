// The gear pair and its involute geometry: docs/model.md, section Geometry.
// All lengths in metres, angles in radians, SI throughout.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "gearimpact/named_values.hpp"

namespace gearimpact {

// The hand of the pinion's helix (the wheel has the other): right, the
// section turning forward about +z as z grows (docs/helical.md).
enum class HelixHand { right, left };
inline constexpr std::array<NamedValue<HelixHand>, 2> kHelixHands{{
    {HelixHand::right, "right", "a right-hand pinion (the wheel left-hand)"},
    {HelixHand::left, "left", "a left-hand pinion (the wheel right-hand)"},
}};

// Two involute spur gears cut by the same basic rack, meshing without
// backlash on the operating centre distance (docs/stiffness-models.md, section 1).
// Pitch radius r_i = module * Z_i / 2, tip radius r_i + (ha + x_i) module;
// unshifted (x1 = x2 = 0, the paper's) the pair sits on its standard centre
// distance.
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
  // The rack's dedendum over the module, ha + c: the root radius is
  // r - (ha + c - x) module. Only the models that start the tooth at the root
  // circle see it.
  double dedendum_coefficient = 1.25;
  double profile_shift1 = 0.0;  // x1: the rack's datum line moved out by x1 module
  double profile_shift2 = 0.0;
  // rho / module of the rack's tip round. Absent: the full round
  // c / (1 - sin a0), c = dedendum - addendum coefficient, or where that is
  // wider than the rack's tip land (pressure angles above about 22 deg) the
  // largest round that fits it.
  std::optional<double> rack_tip_radius_coefficient;
  // Needed by the fillet-foundation term only.
  std::optional<double> bore_diameter1_m;
  std::optional<double> bore_diameter2_m;
  // Gear 2's material. Absent: gear 1's.
  std::optional<double> youngs_modulus2_pa;
  std::optional<double> poisson_ratio2;
  // beta at the reference cylinder; 0 is the spur pair. A helical pair's
  // module, pressure angle, shifts and rack coefficients are normal-section
  // values (geometry/helical.hpp maps them to the transverse section). Only
  // the helical functions take beta > 0: MeshLayout, and so the dynamics,
  // refuse it.
  double helix_angle_rad = 0.0;
  HelixHand helix_hand = HelixHand::right;
  // W = b tan(beta_b), how far a helical tooth pair's contact line reaches
  // along the transverse path from one face end to the other; 0 for a spur
  // pair and for every pair a case describes. Set only on the transverse
  // section the dynamics run a helical pair as (swept_transverse_pair of
  // geometry/helical.hpp): MeshLayout then places each tooth pair by its
  // mid-face contact and keeps it loaded while that lies within W/2 of the
  // path of contact (docs/helical.md, Dynamics).
  double face_advance_m = 0.0;
};

bool operator==(const GearPair& a, const GearPair& b);

// Section 7 of the paper with docs/model.md's defaults for what it leaves unstated.
GearPair paper_gear_pair();

// Throws InputError naming the fields that break a relation between fields:
// the undercut limit on teeth, pointed teeth, interference (a tip beyond the
// mating base-circle tangent point), for both gears at once under the tooth
// count with its fixes, then a contact ratio below 1;
// then what rack generation refuses (rack_gear_pair_geometry of
// rack_generation.hpp), with the field named as in GearPair (profile_shift1,
// bore_diameter2, ...). Each field's own range is the case schema's
// (validate(const GearPair&) of case/schema.hpp checks both).
void validate_geometry(const GearPair& pair);

// Throws InputError naming gears.helix_angle: `what` (a command, the spur
// layout) takes spur pairs only.
[[noreturn]] void throw_helical_not_taken(double helix_angle_rad, std::string_view what);

// Which gear of the pair: 1 the pinion (driver in the paper), 2 the wheel.
enum class Gear { one = 1, two = 2 };

int teeth(const GearPair& pair, Gear gear);
double profile_shift(const GearPair& pair, Gear gear);
double youngs_modulus(const GearPair& pair, Gear gear);
double poisson_ratio(const GearPair& pair, Gear gear);
double pitch_radius(const GearPair& pair, Gear gear);
double tip_radius(const GearPair& pair, Gear gear);
double base_radius(const GearPair& pair, Gear gear);

// inv a = tan a - a.
double involute_function(double angle_rad);
// The a in (0, pi/2) with inv a = target > 0 (to full double precision).
double inverse_involute(double target);

// a_w of two gears cut by one rack meshing without backlash:
// inv a_w = inv a0 + 2 tan a0 (x1 + x2) / (z1 + z2). A zero sum of the shifts
// gives a0 itself, not its round trip through inv. Throws InputError
// (field "profile_shift1 + profile_shift2") when inv a_w would be <= 0.
double operating_pressure_angle(double pressure_angle_rad, int teeth1, int teeth2,
                                double profile_shift1, double profile_shift2);
double operating_pressure_angle(const GearPair& pair);

// (13),(27) theta_b_i = pi/(2 Z_i) + inv a0, plus 2 x_i tan a0 / Z_i for a
// shifted gear: half the tooth angle on the base circle.
double half_tooth_angle(const GearPair& pair, Gear gear);

// lp = (Rb1 + Rb2) tan a_w (a_w = a0 unshifted): distance C1C2 along the line of action.
double line_of_action_length(const GearPair& pair);

// X_pitch = Rb1 tan a_w: the pitch point measured from C1.
double pitch_point_position(const GearPair& pair);

// The contact segment on the line of action, measured from C1:
// X_start = lp - sqrt(ra2^2 - Rb2^2) (tip of gear 2), X_end = sqrt(ra1^2 - Rb1^2).
struct ContactSegment {
  double start_m;
  double end_m;
};
ContactSegment contact_segment(const GearPair& pair);
// The segment over which one tooth pair is in contact: contact_segment, and
// for a swept transverse section (face_advance_m = W) that widened by W/2 at
// both ends, where its contact line still crosses part of the face.
ContactSegment pair_contact_segment(const GearPair& pair);

// `points` (>= 2) evenly spaced positions X1 from X_start to X_end inclusive,
// the last set exactly so that X_end is not lost to rounding: the positions of
// the stiffness and energy tables.
std::vector<double> contact_positions(const GearPair& pair, int points);

// (41) t0 = pi m cos a0.
double base_pitch(const GearPair& pair);

// (X_end - X_start) / t0.
double contact_ratio(const GearPair& pair);

// Contact position X1 (from C1) to the contact angle of each gear:
// (12) phi1 = X1/Rb1 - theta_b1; (25),(26) phi2 = (lp - X1)/Rb2 - theta_b2.
double contact_angle(const GearPair& pair, Gear gear, double x1_m);
// Inverse of (12): X1 = Rb1 (phi1 + theta_b1).
double contact_position_from_phi1(const GearPair& pair, double phi1_rad);

// (31) Which side of the backlash the teeth are on: N1, the line of action of
// the drive flanks (s > B); free flight in the backlash (region (2)); N2, the
// line of action of the coast flanks (s < -B). Written as 1, 0, -1.
enum class Region { n2 = -1, free = 0, n1 = 1 };

// Where the coast-flank contacts sit relative to the drive-flank ones.
enum class CoastPhase {
  half_base_pitch,  // default: X' = X_pitch - Rb1 theta1 + t0/2 + k t0 (geometric)
  in_phase,         // literal reading of (9): X' = X_pitch - Rb1 theta1 + k t0
};
inline constexpr std::array<NamedValue<CoastPhase>, 2> kCoastPhases{{
    {CoastPhase::half_base_pitch, "half-base-pitch",
     "coast-flank contacts t0/2 from the drive ones (geometric)"},
    {CoastPhase::in_phase, "in-phase", "the literal reading of (9)"},
}};

// The pairs of one line of action: which are loaded, k_first to k_first + count - 1.
struct LoadedRange {
  int k_first = 0;
  int count = 0;
};

// (42): the pairs on a line sit at X = reference + k t0 (k integer), the
// reference moving with the rotation theta1; a pair is loaded while its X lies
// in [X_start, X_end] (an end point counts as loaded). For a swept transverse
// section (GearPair::face_advance_m = W > 0) X is the pair's mid-face contact
// and the segment [X_start - W/2, X_end + W/2] (pair_contact_segment). On N1 X is measured from
// C1, on N2 X' from C1' (docs/model.md, Geometry). The one place that places and
// counts the pairs: the simulation, the energy split of Fig. 8 and the step
// bound all ask here.
class MeshLayout {
 public:
  // At most this many pairs on a line (the contact ratio is validated below capacity - 1).
  static constexpr int capacity = 4;

  MeshLayout(const GearPair& pair, CoastPhase coast_phase);
  // A line given by its numbers (an internal mesh's, geometry/planetary.hpp):
  // X_pitch, gear 1's base radius, the base pitch t0 and the contact segment
  // [start, end], all measured from gear 1's tangent point.
  MeshLayout(double pitch_point_m, double base_radius1_m, double base_pitch_m, double start_m,
             double end_m, CoastPhase coast_phase);

  // X of the pair k = 0 on `line` (Region::n1 or Region::n2) at rotation theta1,
  // (9) with (12): X_pitch + Rb1 theta1 on N1, X_pitch - Rb1 theta1 (+ t0/2) on N2.
  double reference_m(Region line, double theta1_rad) const {
    return line == Region::n1 ? x_pitch_ + rb1_ * theta1_rad
                              : x_pitch_ - rb1_ * theta1_rad + coast_offset_;
  }
  // X of pair k.
  double position_m(double reference_m, int k) const { return reference_m + k * t0_; }
  // The loaded pairs when pair 0 is at `reference_m`.
  LoadedRange loaded(double reference_m) const;

  double start_m() const { return start_; }
  double end_m() const { return end_; }
  double base_pitch_m() const { return t0_; }

 private:
  double x_pitch_;
  double rb1_;
  double t0_;
  double start_;
  double end_;
  double coast_offset_;
};

// Positions on `line` of every pair loaded at gear-1 rotation theta1, by (42),
// sorted ascending.
struct LoadedPairs {
  static constexpr std::size_t capacity = MeshLayout::capacity;
  std::array<double, capacity> position_m{};
  std::size_t count = 0;
};
LoadedPairs loaded_pairs(const GearPair& pair, Region line, double theta1_rad,
                         CoastPhase coast_phase = CoastPhase::half_base_pitch);

// Solid discs on the pitch radius: J = rho pi r^4 L / 2.
double moment_of_inertia(const GearPair& pair, Gear gear);
// The same discs' mass, m = rho pi r^2 L (so that J = m r^2 / 2).
double disc_mass(const GearPair& pair, Gear gear);

// The fixes validate_geometry names for a gear whose teeth are undercut,
// pointed or interfere at the root: the fewest teeth at its shift, and the
// smallest shift (rounded up to 0.001) at its tooth count, for which those
// relations hold; nothing when none up to 100000 teeth or a shift of 3 does.
std::optional<int> smallest_teeth_for_shift(const GearPair& pair, Gear gear);
std::optional<double> smallest_shift_for_teeth(const GearPair& pair, Gear gear);

}  // namespace gearimpact
