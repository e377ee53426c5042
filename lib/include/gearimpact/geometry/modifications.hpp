// Profile modifications and tooth errors as a gap per pair of teeth
// (docs/faults.md, "Modifications and errors").
//
// Every pair k on a line of action has a gap e_k(X): the sum of its two teeth's
// deviations at the contact, measured along the line of action, positive where
// material is removed (the pair touches later). X is the contact position from
// C1 on N1 (from C1' on N2), as MeshLayout places the pairs: the pinion's roll
// distance is X, the wheel's is lp - X. The pinion's tip is at X_end =
// sqrt(ra1^2 - Rb1^2), the wheel's at X_start = lp - sqrt(ra2^2 - Rb2^2)
// (contact_segment), on either line.
//
// Tip and root relief act on both flanks of every tooth of their gear; the
// errors of one tooth are given per tooth, numbered as teeth_of_pair numbers
// them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/named_values.hpp"

namespace gearimpact {

// The shape of a relief: linear (p = 1) or parabolic (p = 2) in the roll
// distance, C ((s - s_r) / (s_a - s_r))^p.
enum class ReliefShape { linear = 1, parabolic = 2 };
inline constexpr std::array<NamedValue<ReliefShape>, 2> kReliefShapes{{
    {ReliefShape::linear, "linear", "C (u)^1, u the fraction of the relieved roll length"},
    {ReliefShape::parabolic, "parabolic", "C (u)^2, tangent to the unmodified involute"},
}};

// One relief of one gear. A tip relief removes `amount` at the tip circle,
// falling to 0 at the diameter `diameter_m` (d_Ca, its start); a root relief
// removes `amount` at the start of the active profile (the mating tip's
// contact), falling to 0 at `diameter_m` (d_Cf, its end). amount 0: none,
// and diameter_m is not read.
struct Relief {
  double amount_m = 0.0;
  double diameter_m = 0.0;
  ReliefShape shape = ReliefShape::linear;
};

// The modifications and errors of one gear. Each error list is empty (no
// error on any tooth) or holds one value per tooth, tooth 0 first, in m along
// the line of action:
// - pitch: the tooth's position deviation f; a positive f makes it meet later
//   on N1 and earlier on N2 (gap +f on the drive flank, -f on the coast flank);
// - thickness: material removed from each of its two flanks (the tooth is 2 f
//   thinner along the base tangent), gap +f on both flanks;
// - profile_slope: f_Ha, a gap rising linearly along the active profile from
//   -f_Ha/2 at its start to +f_Ha/2 at the tip, 0 at the middle of its roll
//   length (both flanks alike): a positive f_Ha leaves the tip thinner.
// A flank tolerance class of ISO 1328-1:2013 (iso1328_class > 0) draws the
// pitch and profile slope errors instead (draw_tooth_errors of iso1328.hpp,
// with the pair's error_seed); their lists are then empty.
// The lead modifications of one gear (helical pairs, docs/helical.md, "Lead
// modifications and misalignment"): gaps across the face, along the transverse
// line of action as the profile gaps are, the same on every tooth, y the
// position across the face from the face end at smaller z (y = 0) to y = b
// and u = y / b - 1/2.
// - crowning: C_beta (2u)^2 on both flanks;
// - end relief at each face end: C_I ((l_I - y) / l_I)^p for y < l_I and
//   C_II ((y - b + l_II) / l_II)^p for y > b - l_II, both flanks, p of `shape`;
// - helix slope: f_Hbeta u on the drive flank (line N1) and -f_Hbeta u on the
//   coast flank (N2), a wrong helix angle (the tooth's section turned by an
//   angle growing across the face, as a pitch deviation growing with u).
struct LeadModifications {
  double crowning_m = 0.0;
  double end_relief_i_m = 0.0;  // C_I at y = 0
  double end_relief_i_length_m = 0.0;
  double end_relief_ii_m = 0.0;  // C_II at y = b
  double end_relief_ii_length_m = 0.0;
  ReliefShape end_relief_shape = ReliefShape::linear;
  double helix_slope_m = 0.0;  // f_Hbeta
};

struct GearModifications {
  Relief tip;
  Relief root;
  LeadModifications lead;
  std::vector<double> pitch_m;
  std::vector<double> thickness_m;
  std::vector<double> profile_slope_m;
  int iso1328_class = 0;  // 0: no class
};

// The wheel axis tilted against the pinion's (helical pairs): gamma_x in the
// plane of the axes (the wheel's transverse section centre moves along +x, away
// from the pinion, as y grows) and gamma_y across it (along +y, the way the
// pinion's pitch point moves), small angles in rad. The frame of
// docs/vibration.md: O1 the origin, e_x towards O2, the pinion turning about +z.
struct Misalignment {
  double gamma_x_rad = 0.0;
  double gamma_y_rad = 0.0;
};

struct Modifications {
  GearModifications gear1;
  GearModifications gear2;
  std::uint32_t error_seed = 0;  // read only with a tolerance class
  Misalignment misalignment;
};

bool operator==(const LeadModifications& a, const LeadModifications& b);
bool operator==(const Misalignment& a, const Misalignment& b);
bool operator==(const Relief& a, const Relief& b);
bool operator==(const GearModifications& a, const GearModifications& b);
bool operator==(const Modifications& a, const Modifications& b);

// True when every relief amount is 0, every error list is empty or all 0, no
// gear has a tolerance class and no lead modification or misalignment is set:
// the gaps are 0 everywhere.
bool is_unmodified(const Modifications& m);

// True when a lead modification (crowning, end relief, helix slope) of either
// gear or a misalignment is set: gaps that vary across the face, which only
// the slice model of a helical pair takes.
bool has_lead_gaps(const Modifications& m);

// The gap across the face at y (m from the face end at smaller z) on `line`
// (Region::n1, the drive flanks, or Region::n2) of a pair of face width b and
// transverse working pressure angle alpha_wt: both gears' lead modifications
// and the misalignment's mismatch, along the transverse line of action,
//   N1: b u (gamma_x sin(alpha_wt) + gamma_y cos(alpha_wt)) = F_beta u,
//   N2: b u (gamma_x sin(alpha_wt) - gamma_y cos(alpha_wt)),
// u = y / b - 1/2 (the wheel moved along n1 = (sin, cos)(alpha_wt) opens the
// drive flanks, along n2 = (sin, -cos)(alpha_wt) the coast flanks).
double lead_gap_m(const Modifications& m, Region line, double face_width_m,
                  double working_pressure_angle_rad, double y_m);

// Which gears have teeth that differ from each other (an error list whose
// values are not all equal, or errors drawn from a tolerance class), for
// true_period_mesh_periods.
DistinctTeeth distinct_teeth(const Modifications& m);

// `m` with the errors of each gear that has a tolerance class drawn into its
// pitch and profile slope lists (draw_tooth_errors); unchanged without one.
Modifications with_drawn_errors(const GearPair& pair, const Modifications& m);

// A bound below every pair's gap on `line` (Region::n1 or Region::n2): each
// gear's least tooth deviation there (pitch with the line's sign, thickness,
// and the profile slope at its lower end, -|f_Ha|/2, the drawn errors of a
// tolerance class among them), reliefs adding nothing below 0. 0 without
// errors.
double least_gap_bound_m(const GearPair& pair, const Modifications& m, Region line);

// The active profile of one gear as radii: from the contact with the mating
// tip (the start of the active profile, SAP) to its own tip.
struct ActiveProfile {
  double start_diameter_m;
  double tip_diameter_m;
  // The lowest and the highest point of single tooth contact (LPSTC, HPSTC): in roll on the own
  // base circle t0 below the tip's roll (the pair ahead leaves) and t0 above the start's (the pair
  // behind enters), d = 2 sqrt(Rb^2 + roll^2). Between them one pair carries the whole load; a
  // long tip relief starts at the HPSTC, a short one above it.
  double lowest_single_contact_diameter_m;
  double highest_single_contact_diameter_m;
};
ActiveProfile active_profile(const GearPair& pair, Gear gear);

// The checks across fields: each relief with an amount > 0 has its diameter
// in the active profile (a tip relief's start in [d_SAP, d_a), a root
// relief's end in (d_SAP, d_a]), and the tip and root relief of one gear do
// not overlap; each error list is empty or has one value per tooth; a gear
// with a tolerance class has no pitch or profile slope list and lies in the
// scope of ISO 1328-1:2013 (5 <= z <= 1000, 5 mm <= d <= 15000 mm,
// 0.5 mm <= m <= 70 mm), and an error_seed other than 0 has a class to
// seed. Throws
// InputError naming the field as `prefix` + "." + the case-file key
// ("modifications.tip_relief_start1"), with the limit in its allowed text.
void validate_modifications(const GearPair& pair, const Modifications& m,
                            const std::string& prefix = "modifications");

// The gaps of a validated pair and its modifications, with the roll lengths
// precomputed and the errors of a tolerance class drawn.
class ToothGaps {
 public:
  ToothGaps(const GearPair& pair, const Modifications& m);

  // The deviation of one gear's relief (tip and root) at the contact X on
  // either line, m, material removed positive.
  double relief_m(Gear gear, double x_m) const;
  // The deviation of tooth `tooth` of `gear` at X on `line` (Region::n1 or
  // Region::n2): relief, pitch, thickness and profile slope.
  double tooth_m(Gear gear, int tooth, Region line, double x_m) const;
  // d tooth_m / dX.
  double tooth_slope(Gear gear, int tooth, double x_m) const;
  // e_k(X): the sum of the two teeth of pair k on `line` (teeth_of_pair).
  double gap_m(Region line, int k, double x_m) const;
  // e_k(X) and its slope de_k/dX, which the dynamics needs for the rate of a
  // pair's penetration as its contact moves along the line. The slope is
  // one-sided where a relief begins (its right-hand value; linear reliefs
  // have a kink there) and 0 beyond the tip, where u is held at 1.
  struct GapAndSlope {
    double gap_m;
    double slope;  // de_k/dX, m/m
  };
  GapAndSlope gap_and_slope(Region line, int k, double x_m) const;
  // The contact positions X strictly inside the contact segment where a
  // gap's slope jumps (where a linear relief begins), ascending, on either
  // line: the dynamics locates them as events.
  std::vector<double> kinks_m() const;

 private:
  GearPair pair_;
  Modifications m_;
  double lp_;
  double start_;  // X_start: the wheel's tip, the pinion's SAP
  double end_;    // X_end: the pinion's tip, the wheel's SAP
  // Roll distances on each gear's own base circle: where each relief begins.
  std::array<double, 2> tip_start_roll_{};
  std::array<double, 2> root_end_roll_{};
};

}  // namespace gearimpact
