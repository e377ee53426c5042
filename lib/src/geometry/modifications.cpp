#include "gearimpact/geometry/modifications.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/iso1328.hpp"

namespace gearimpact {

namespace {

bool all_zero(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return v == 0.0; });
}

bool all_equal(const std::vector<double>& values) {
  return std::all_of(values.begin(), values.end(), [&](double v) { return v == values.front(); });
}

bool differ(const GearModifications& g) {
  return g.iso1328_class > 0 || !all_equal(g.pitch_m) || !all_equal(g.thickness_m) ||
         !all_equal(g.profile_slope_m);
}

// The roll distance on `gear`'s base circle of a point at `diameter`.
double roll_of_diameter(const GearPair& pair, Gear gear, double diameter_m) {
  const double rb = base_radius(pair, gear);
  const double r = 0.5 * diameter_m;
  return std::sqrt(std::max(0.0, (r - rb) * (r + rb)));
}

// The roll distances of the start of the active profile and of the tip.
struct RollRange {
  double sap;
  double tip;
};
RollRange active_roll(const GearPair& pair, Gear gear) {
  const ContactSegment segment = contact_segment(pair);
  if (gear == Gear::one) return {segment.start_m, segment.end_m};
  const double lp = line_of_action_length(pair);
  return {lp - segment.end_m, lp - segment.start_m};
}

double diameter_of_roll(const GearPair& pair, Gear gear, double roll_m) {
  const double rb = base_radius(pair, gear);
  return 2.0 * std::sqrt(rb * rb + roll_m * roll_m);
}

// C u^p for u in [0, 1].
double relief_curve(double amount_m, ReliefShape shape, double u) {
  return shape == ReliefShape::parabolic ? amount_m * u * u : amount_m * u;
}

// d(C u^p)/du.
double relief_curve_slope(double amount_m, ReliefShape shape, double u) {
  return shape == ReliefShape::parabolic ? 2.0 * amount_m * u : amount_m;
}

// The case-file key of the first lead modification or misalignment set, for a message.
std::string first_lead_key(const Modifications& m) {
  for (const Gear gear : {Gear::one, Gear::two}) {
    const LeadModifications& l = (gear == Gear::one ? m.gear1 : m.gear2).lead;
    const std::string n = gear == Gear::one ? "1" : "2";
    if (l.crowning_m != 0.0) return "crowning" + n;
    if (l.end_relief_i_m != 0.0) return "end_relief_i" + n;
    if (l.end_relief_ii_m != 0.0) return "end_relief_ii" + n;
    if (l.helix_slope_m != 0.0) return "helix_slope_deviation" + n;
  }
  return m.misalignment.gamma_x_rad != 0.0 ? "misalignment_x" : "misalignment_y";
}

std::string mm(double metres) {
  return format_number(metres * 1e3) + " mm";
}

// A gear with a tolerance class: no list of the errors it draws, and a gear
// in the scope of ISO 1328-1:2013, whose formulae are not to be extrapolated.
void check_tolerance_class(const GearPair& pair, Gear gear, const GearModifications& g,
                           const std::string& prefix, Problems& problems) {
  const std::string n = gear == Gear::one ? "1" : "2";
  const std::string key = prefix + ".iso1328_class" + n;
  const std::string written = std::to_string(g.iso1328_class);
  std::string lists;
  if (!g.pitch_m.empty()) lists = "pitch_deviations" + n;
  const bool both = !g.pitch_m.empty() && !g.profile_slope_m.empty();
  if (!g.profile_slope_m.empty()) {
    lists += (lists.empty() ? "" : " and ") + std::string("profile_slope_deviations") + n;
  }
  if (!lists.empty()) {
    problems.add(refused_problem(key, written,
                                 "the class draws the pitch and profile slope errors of gear " + n +
                                     ", which " + lists + (both ? " give" : " gives") + " as well",
                                 "a class, or the lists, for the errors of one gear",
                                 "leave out " + lists + ", or iso1328_class" + n));
    return;
  }
  const int z = teeth(pair, gear);
  const double m_mm = pair.module_m * 1e3;
  const double d_mm = m_mm * z;
  if (z < 5 || z > 1000 || d_mm < 5.0 || d_mm > 15000.0 || m_mm < 0.5 || m_mm > 70.0) {
    problems.add(refused_problem(
        key, written,
        "gear " + n + " (z = " + std::to_string(z) + ", d = " + format_number(d_mm) +
            " mm, m = " + format_number(m_mm) +
            " mm) lies outside the scope of ISO 1328-1:2013, whose formulae are not to be "
            "extrapolated",
        "a class only for a gear with 5 <= z <= 1000, 5 mm <= d = m z <= 15000 mm and "
        "0.5 mm <= m <= 70 mm",
        "give the errors as lists instead"));
  }
}

}  // namespace

bool operator==(const LeadModifications& a, const LeadModifications& b) {
  return a.crowning_m == b.crowning_m && a.end_relief_i_m == b.end_relief_i_m &&
         a.end_relief_i_length_m == b.end_relief_i_length_m &&
         a.end_relief_ii_m == b.end_relief_ii_m &&
         a.end_relief_ii_length_m == b.end_relief_ii_length_m &&
         a.end_relief_shape == b.end_relief_shape && a.helix_slope_m == b.helix_slope_m;
}
bool operator==(const Misalignment& a, const Misalignment& b) {
  return a.gamma_x_rad == b.gamma_x_rad && a.gamma_y_rad == b.gamma_y_rad;
}
bool operator==(const Relief& a, const Relief& b) {
  return a.amount_m == b.amount_m && a.diameter_m == b.diameter_m && a.shape == b.shape;
}
bool operator==(const GearModifications& a, const GearModifications& b) {
  return a.tip == b.tip && a.root == b.root && a.pitch_m == b.pitch_m &&
         a.thickness_m == b.thickness_m && a.profile_slope_m == b.profile_slope_m &&
         a.iso1328_class == b.iso1328_class && a.lead == b.lead;
}
bool operator==(const Modifications& a, const Modifications& b) {
  return a.gear1 == b.gear1 && a.gear2 == b.gear2 && a.error_seed == b.error_seed &&
         a.misalignment == b.misalignment;
}

bool has_lead_gaps(const Modifications& m) {
  for (const GearModifications* g : {&m.gear1, &m.gear2}) {
    const LeadModifications& l = g->lead;
    if (l.crowning_m != 0.0 || l.end_relief_i_m != 0.0 || l.end_relief_ii_m != 0.0 ||
        l.helix_slope_m != 0.0) {
      return true;
    }
  }
  return m.misalignment.gamma_x_rad != 0.0 || m.misalignment.gamma_y_rad != 0.0;
}

double lead_gap_m(const Modifications& m, Region line, double b, double alpha_wt, double y) {
  const double u = y / b - 0.5;
  double gap = 0.0;
  for (const GearModifications* g : {&m.gear1, &m.gear2}) {
    const LeadModifications& l = g->lead;
    gap += l.crowning_m * (4.0 * u * u);
    if (l.end_relief_i_m > 0.0 && y < l.end_relief_i_length_m) {
      gap += relief_curve(l.end_relief_i_m, l.end_relief_shape,
                          (l.end_relief_i_length_m - y) / l.end_relief_i_length_m);
    }
    if (l.end_relief_ii_m > 0.0 && y > b - l.end_relief_ii_length_m) {
      gap += relief_curve(l.end_relief_ii_m, l.end_relief_shape,
                          (y - b + l.end_relief_ii_length_m) / l.end_relief_ii_length_m);
    }
    gap += (line == Region::n1 ? 1.0 : -1.0) * l.helix_slope_m * u;
  }
  const double across = std::sin(alpha_wt) * m.misalignment.gamma_x_rad;
  const double along = std::cos(alpha_wt) * m.misalignment.gamma_y_rad;
  gap += b * u * (line == Region::n1 ? across + along : across - along);
  return gap;
}

bool is_unmodified(const Modifications& m) {
  if (has_lead_gaps(m)) return false;
  for (const GearModifications* g : {&m.gear1, &m.gear2}) {
    if (g->tip.amount_m != 0.0 || g->root.amount_m != 0.0 || g->iso1328_class > 0 ||
        !all_zero(g->pitch_m) || !all_zero(g->thickness_m) || !all_zero(g->profile_slope_m)) {
      return false;
    }
  }
  return true;
}

DistinctTeeth distinct_teeth(const Modifications& m) {
  return {differ(m.gear1), differ(m.gear2)};
}

Modifications with_drawn_errors(const GearPair& pair, const Modifications& m) {
  Modifications drawn = m;
  for (const Gear gear : {Gear::one, Gear::two}) {
    GearModifications& g = gear == Gear::one ? drawn.gear1 : drawn.gear2;
    if (g.iso1328_class == 0) continue;
    DrawnToothErrors errors = draw_tooth_errors(pair, gear, g.iso1328_class, m.error_seed);
    g.pitch_m = std::move(errors.pitch_m);
    g.profile_slope_m = std::move(errors.profile_slope_m);
  }
  return drawn;
}

double least_gap_bound_m(const GearPair& pair, const Modifications& modifications, Region line) {
  const Modifications m = with_drawn_errors(pair, modifications);
  double bound = 0.0;
  for (const GearModifications* g : {&m.gear1, &m.gear2}) {
    const std::size_t n =
        std::max({g->pitch_m.size(), g->thickness_m.size(), g->profile_slope_m.size()});
    double least = 0.0;
    for (std::size_t t = 0; t < n; ++t) {
      double e = 0.0;
      if (!g->pitch_m.empty()) e += line == Region::n1 ? g->pitch_m[t] : -g->pitch_m[t];
      if (!g->thickness_m.empty()) e += g->thickness_m[t];
      if (!g->profile_slope_m.empty()) e -= 0.5 * std::fabs(g->profile_slope_m[t]);
      least = t == 0 ? e : std::min(least, e);
    }
    bound += least;
  }
  return bound;
}

ActiveProfile active_profile(const GearPair& pair, Gear gear) {
  const RollRange roll = active_roll(pair, gear);
  const double t0 = base_pitch(pair);
  return {diameter_of_roll(pair, gear, roll.sap), 2.0 * tip_radius(pair, gear),
          diameter_of_roll(pair, gear, roll.tip - t0), diameter_of_roll(pair, gear, roll.sap + t0)};
}

void validate_modifications(const GearPair& helical_or_spur, const Modifications& m,
                            const std::string& prefix) {
  // A helical pair's profile modifications act in its transverse section.
  const GearPair pair = transverse_pair(helical_or_spur);
  Problems problems;
  for (const Gear gear : {Gear::one, Gear::two}) {
    const LeadModifications& l = (gear == Gear::one ? m.gear1 : m.gear2).lead;
    const std::string n = gear == Gear::one ? "1" : "2";
    const double b = pair.face_width_m;
    for (const auto& [amount, length, key] :
         {std::tuple{l.end_relief_i_m, l.end_relief_i_length_m, "end_relief_i_length"},
          std::tuple{l.end_relief_ii_m, l.end_relief_ii_length_m, "end_relief_ii_length"}}) {
      if (amount > 0.0 && !(length > 0.0 && length <= b)) {
        problems.add(range_problem(
            prefix + "." + key + n, mm(length),
            "a length in (0, b] = (0, " + mm(b) + "] with the end relief's amount > 0"));
      }
    }
    if (l.end_relief_i_m > 0.0 && l.end_relief_ii_m > 0.0 &&
        l.end_relief_i_length_m + l.end_relief_ii_length_m > b) {
      problems.add(range_problem(prefix + ".end_relief_ii_length" + n, mm(l.end_relief_ii_length_m),
                                 "at most b - end_relief_i_length" + n + " = " +
                                     mm(b - l.end_relief_i_length_m) +
                                     ": the two end reliefs of one face do not overlap"));
    }
  }
  if (helical_or_spur.helix_angle_rad == 0.0 && has_lead_gaps(m)) {
    problems.add(refused_problem(
        prefix + "." + first_lead_key(m), "set on a spur pair",
        "gaps across the face are taken by the slice model of a helical pair only",
        "no crowning, end relief, helix slope deviation or misalignment on a spur pair",
        "gears.helix_angle > 0, or remove the [modifications] lead keys"));
  }
  for (const Gear gear : {Gear::one, Gear::two}) {
    const GearModifications& g = gear == Gear::one ? m.gear1 : m.gear2;
    const std::string n = gear == Gear::one ? "1" : "2";
    const ActiveProfile active = active_profile(pair, gear);
    const std::string profile =
        "the active profile of gear " + n + ", from d_SAP = " + mm(active.start_diameter_m) +
        " (where the mating tip meets it) " + "to the tip d_a = " + mm(active.tip_diameter_m);
    const bool tip = g.tip.amount_m > 0.0;
    const bool root = g.root.amount_m > 0.0;
    if (tip && !(g.tip.diameter_m >= active.start_diameter_m &&
                 g.tip.diameter_m < active.tip_diameter_m)) {
      problems.add(range_problem(prefix + ".tip_relief_start" + n, mm(g.tip.diameter_m),
                                 "a diameter in [" + mm(active.start_diameter_m) + ", " +
                                     mm(active.tip_diameter_m) + "): " + profile));
    }
    if (root && !(g.root.diameter_m > active.start_diameter_m &&
                  g.root.diameter_m <= active.tip_diameter_m)) {
      problems.add(range_problem(prefix + ".root_relief_end" + n, mm(g.root.diameter_m),
                                 "a diameter in (" + mm(active.start_diameter_m) + ", " +
                                     mm(active.tip_diameter_m) + "]: " + profile));
    }
    if (tip && root && g.root.diameter_m > g.tip.diameter_m) {
      problems.add(range_problem(prefix + ".root_relief_end" + n, mm(g.root.diameter_m),
                                 "at most tip_relief_start" + n + " = " + mm(g.tip.diameter_m) +
                                     ": the root and tip relief of one flank do not overlap"));
    }
    const auto per_tooth = [&](const std::vector<double>& list, const char* key) {
      const auto z = static_cast<std::size_t>(teeth(pair, gear));
      if (!list.empty() && list.size() != z) {
        problems.add(range_problem(prefix + "." + key + n, std::to_string(list.size()) + " values",
                                   "none, or one per tooth of gear " + n + " (teeth" + n + " = " +
                                       std::to_string(z) + "), tooth 0 first"));
      }
    };
    per_tooth(g.pitch_m, "pitch_deviations");
    per_tooth(g.thickness_m, "thickness_deviations");
    per_tooth(g.profile_slope_m, "profile_slope_deviations");
    if (g.iso1328_class > 0) check_tolerance_class(pair, gear, g, prefix, problems);
  }
  if (m.error_seed != 0 && m.gear1.iso1328_class == 0 && m.gear2.iso1328_class == 0) {
    problems.add(refused_problem(
        prefix + ".error_seed", std::to_string(m.error_seed),
        "it seeds the errors a tolerance class draws, and neither gear "
        "has one",
        "0 without iso1328_class1 or iso1328_class2",
        "iso1328_class1 (or iso1328_class2) = 6 to draw the errors, or no error_seed"));
  }
  problems.throw_if_any();
}

ToothGaps::ToothGaps(const GearPair& pair, const Modifications& m)
    : pair_(pair), m_(with_drawn_errors(pair, m)), lp_(line_of_action_length(pair)) {
  const ContactSegment segment = contact_segment(pair);
  start_ = segment.start_m;
  end_ = segment.end_m;
  for (const Gear gear : {Gear::one, Gear::two}) {
    const GearModifications& g = gear == Gear::one ? m.gear1 : m.gear2;
    const auto i = static_cast<std::size_t>(gear == Gear::one ? 0 : 1);
    tip_start_roll_[i] = roll_of_diameter(pair, gear, g.tip.diameter_m);
    root_end_roll_[i] = roll_of_diameter(pair, gear, g.root.diameter_m);
  }
}

double ToothGaps::relief_m(Gear gear, double x_m) const {
  const GearModifications& g = gear == Gear::one ? m_.gear1 : m_.gear2;
  const auto i = static_cast<std::size_t>(gear == Gear::one ? 0 : 1);
  // The gear's own roll distance and the ends of its active profile.
  const double s = gear == Gear::one ? x_m : lp_ - x_m;
  const double sap = gear == Gear::one ? start_ : lp_ - end_;
  const double tip = gear == Gear::one ? end_ : lp_ - start_;
  double e = 0.0;
  if (g.tip.amount_m > 0.0 && s > tip_start_roll_[i]) {
    const double u = std::min(1.0, (s - tip_start_roll_[i]) / (tip - tip_start_roll_[i]));
    e += relief_curve(g.tip.amount_m, g.tip.shape, u);
  }
  if (g.root.amount_m > 0.0 && s < root_end_roll_[i]) {
    const double u = std::min(1.0, (root_end_roll_[i] - s) / (root_end_roll_[i] - sap));
    e += relief_curve(g.root.amount_m, g.root.shape, u);
  }
  return e;
}

double ToothGaps::tooth_m(Gear gear, int tooth, Region line, double x_m) const {
  const GearModifications& g = gear == Gear::one ? m_.gear1 : m_.gear2;
  const auto t = static_cast<std::size_t>(tooth);
  double e = relief_m(gear, x_m);
  if (!g.pitch_m.empty()) e += line == Region::n1 ? g.pitch_m[t] : -g.pitch_m[t];
  if (!g.thickness_m.empty()) e += g.thickness_m[t];
  if (!g.profile_slope_m.empty()) {
    const double s = gear == Gear::one ? x_m : lp_ - x_m;
    const double sap = gear == Gear::one ? start_ : lp_ - end_;
    const double tip = gear == Gear::one ? end_ : lp_ - start_;
    e += g.profile_slope_m[t] * ((s - sap) / (tip - sap) - 0.5);
  }
  return e;
}

double ToothGaps::tooth_slope(Gear gear, int tooth, double x_m) const {
  const GearModifications& g = gear == Gear::one ? m_.gear1 : m_.gear2;
  const auto i = static_cast<std::size_t>(gear == Gear::one ? 0 : 1);
  // The wheel's roll distance lp - X falls as X grows.
  const double ds_dx = gear == Gear::one ? 1.0 : -1.0;
  const double s = gear == Gear::one ? x_m : lp_ - x_m;
  const double sap = gear == Gear::one ? start_ : lp_ - end_;
  const double tip = gear == Gear::one ? end_ : lp_ - start_;
  double de_ds = 0.0;
  if (g.tip.amount_m > 0.0 && s >= tip_start_roll_[i]) {
    const double length = tip - tip_start_roll_[i];
    const double u = (s - tip_start_roll_[i]) / length;
    if (u < 1.0) de_ds += relief_curve_slope(g.tip.amount_m, g.tip.shape, u) / length;
  }
  if (g.root.amount_m > 0.0 && s < root_end_roll_[i]) {
    const double length = root_end_roll_[i] - sap;
    const double u = (root_end_roll_[i] - s) / length;
    if (u < 1.0) de_ds -= relief_curve_slope(g.root.amount_m, g.root.shape, u) / length;
  }
  if (!g.profile_slope_m.empty()) {
    de_ds += g.profile_slope_m[static_cast<std::size_t>(tooth)] / (tip - sap);
  }
  return de_ds * ds_dx;
}

ToothGaps::GapAndSlope ToothGaps::gap_and_slope(Region line, int k, double x_m) const {
  const TeethInContact teeth = teeth_of_pair(pair_, line, k);
  return {tooth_m(Gear::one, teeth.pinion_tooth, line, x_m) +
              tooth_m(Gear::two, teeth.wheel_tooth, line, x_m),
          tooth_slope(Gear::one, teeth.pinion_tooth, x_m) +
              tooth_slope(Gear::two, teeth.wheel_tooth, x_m)};
}

std::vector<double> ToothGaps::kinks_m() const {
  std::vector<double> kinks;
  for (const Gear gear : {Gear::one, Gear::two}) {
    const GearModifications& g = gear == Gear::one ? m_.gear1 : m_.gear2;
    const auto i = static_cast<std::size_t>(gear == Gear::one ? 0 : 1);
    // A parabolic relief starts with slope 0: no jump.
    const auto add = [&](const Relief& relief, double roll_m) {
      if (relief.amount_m <= 0.0 || relief.shape != ReliefShape::linear) return;
      const double x = gear == Gear::one ? roll_m : lp_ - roll_m;
      if (x > start_ && x < end_) kinks.push_back(x);
    };
    add(g.tip, tip_start_roll_[i]);
    add(g.root, root_end_roll_[i]);
  }
  std::sort(kinks.begin(), kinks.end());
  return kinks;
}

double ToothGaps::gap_m(Region line, int k, double x_m) const {
  const TeethInContact teeth = teeth_of_pair(pair_, line, k);
  return tooth_m(Gear::one, teeth.pinion_tooth, line, x_m) +
         tooth_m(Gear::two, teeth.wheel_tooth, line, x_m);
}

}  // namespace gearimpact
