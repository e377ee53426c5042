// `gearimpact report CASE --out DIR`: what applies to one user's pair, in one folder, as
// `reproduce` does for the paper's: the geometry, the three stiffness models against ISO 6336-1,
// the terms at the pitch point, load sharing, and (for a run file) a short time history, with
// REPORT.md stating every warning with its numbers.
#include <cctype>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/stiffness/comparison.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"
#include "geometry_table.hpp"
#include "mesh_stiffness_figure.hpp"
#include "program.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

namespace {

// ISO's unit of stiffness per face width, N/(mm um), in N/m^2; and N/um in N/m.
constexpr double kNPerMmUm = 1e9;
constexpr double kNPerUm = 1e6;
// The most rows the time history keeps: a figure's worth, a CSV of about a megabyte.
constexpr double kMostHistoryRows = 20000.0;

// ISO 6336-1's line load at the reference circle above which its N_S and c' take no low-load
// correction, 100 N/mm in N/m: the load a modified pair file without a torque is shown at.
constexpr double kIsoReferenceLineLoad = 100e3;

struct ReportOptions {
  std::string case_file;
  std::string out;
  bool overwrite = false;
  int samples = 400;
  std::string torque;  // empty: the case's mean torque, else ISO's reference line load
};

// The load that a modified or faulted pair's STE and load sharing are computed at: T1 > 0 on the
// drive flanks, and where it comes from, in words.
struct ReportLoad {
  double torque1_n_m = 0.0;
  std::string origin;
};

// Writes the report's files into `dir` and prints a line per part on stderr.
class Progress {
 public:
  void done(const std::string& part) const {
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    std::cerr << "report: " << part << " ... " << number(s, 3) << " s\n";
  }

 private:
  std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

double mean_torque(const Torque& t) {
  return t.kind == Torque::Kind::constant ? t.constant_n_m : t.mean_n_m;
}

// T1's mean: a speed controller or a motor holds the load, so in the mean
// T1 = -T2 Rb1 / Rb2.
double mean_torque1(const SimulationCase& c) {
  if (c.torque1.kind == Torque::Kind::speed_controlled ||
      c.torque1.kind == Torque::Kind::induction_motor) {
    return -mean_torque(c.torque2) * base_radius(c.gears, Gear::one) /
           base_radius(c.gears, Gear::two);
  }
  return mean_torque(c.torque1);
}

// The geometry section and geometry.csv (lengths in mm), with the bounds a designer places
// modifications and faults within and a run's step is held to.
std::string geometry_section(const SimulationCase& c, bool run, const std::filesystem::path& dir) {
  const GearPair& pair = c.gears;
  const RackGearPairGeometry g = rack_gear_pair_geometry(pair);
  const ContactSegment segment = contact_segment(pair);
  const double t0 = base_pitch(pair);
  const double mm = 1e3;
  std::string text;
  text += "Contact ratio eps_alpha = " + number(contact_ratio(pair), 6) +
          "; operating pressure angle " + number(g.operating_pressure_angle_rad * 180.0 / pi, 6) +
          " deg; centre distance " + number(g.centre_distance_m * mm, 6) + " mm; base pitch t0 " +
          number(t0 * mm, 6) + " mm.\n\n";
  text +=
      "Path of contact on the line of action, from the pinion's base-circle tangent point: X1 "
      "from " +
      number(segment.start_m * mm, 6) + " to " + number(segment.end_m * mm, 6) + " mm (length " +
      number((segment.end_m - segment.start_m) * mm, 6) + " mm; pitch point at " +
      number(pitch_point_position(pair) * mm, 6) + " mm); two pairs carry the load over " +
      number(
          100.0 * 2.0 * (segment.end_m - segment.start_m - t0) / (segment.end_m - segment.start_m),
          4) +
      " % of it, " + number(100.0 * (contact_ratio(pair) - 1.0), 4) + " % of the mesh period.\n\n";
  GeometryTable lines;
  const RackGearGeometry& a = g.gear1;
  const RackGearGeometry& b = g.gear2;
  lines.both("teeth", a.teeth, b.teeth, "1");
  lines.both("profile_shift", a.profile_shift_coefficient, b.profile_shift_coefficient, "1");
  lines.both("pitch_radius", a.pitch_radius_m, b.pitch_radius_m, "m");
  lines.both("base_radius", a.base_radius_m, b.base_radius_m, "m");
  lines.both("tip_radius", a.tip_radius_m, b.tip_radius_m, "m");
  lines.both("root_radius", a.root_radius_m, b.root_radius_m, "m");
  lines.both("form_radius", a.form_radius_m, b.form_radius_m, "m");
  // Where the active profile starts on each gear: the mate's tip acting on the line of action.
  const double sap1 = std::hypot(a.base_radius_m, g.start_of_active_profile_m);
  const double sap2 =
      std::hypot(b.base_radius_m, g.line_of_action_length_m - g.end_of_active_profile_m);
  lines.both("start_of_active_profile_radius", sap1, sap2, "m");
  lines.both("active_profile_above_form_circle", sap1 - a.form_radius_m, sap2 - b.form_radius_m,
             "m");
  // Rack generation undercuts the involute below z = 2 (ha - x) / sin^2 a0.
  const double sin_a0 = std::sin(pair.pressure_angle_rad);
  const auto least_teeth = [&](const RackGearGeometry& r) {
    return 2.0 * (r.addendum_coefficient - r.profile_shift_coefficient) / (sin_a0 * sin_a0);
  };
  const auto least_shift = [&](const RackGearGeometry& r) {
    return r.addendum_coefficient - 0.5 * r.teeth * sin_a0 * sin_a0;
  };
  lines.both("undercut_limit_teeth", least_teeth(a), least_teeth(b), "1");
  lines.both("undercut_margin_shift", a.profile_shift_coefficient - least_shift(a),
             b.profile_shift_coefficient - least_shift(b), "1");
  lines.both("root_half_angle_theta_f", a.root_half_angle_rad, b.root_half_angle_rad, "rad");
  // Where one pair carries the whole load, and so where a tip relief starts.
  const ActiveProfile profile1 = active_profile(pair, Gear::one);
  const ActiveProfile profile2 = active_profile(pair, Gear::two);
  lines.both("lpstc_diameter", profile1.lowest_single_contact_diameter_m,
             profile2.lowest_single_contact_diameter_m, "m");
  lines.both("hpstc_diameter", profile1.highest_single_contact_diameter_m,
             profile2.highest_single_contact_diameter_m, "m");
  // A root crack at the model's default start: the section's half thickness there bounds its
  // depth, q sin(nu) < h_c.
  RootCrack at_default;
  at_default.angle_rad = pi / 4.0;
  try {
    const CrackReach crack1 = crack_reach(pair, c.model.stiffness, Gear::one, at_default);
    const CrackReach crack2 = crack_reach(pair, c.model.stiffness, Gear::two, at_default);
    lines.both("crack_start_radius_r_s", crack1.start_radius_m, crack2.start_radius_m, "m");
    lines.both("crack_start_half_thickness_h_c", crack1.start_half_thickness_m,
               crack2.start_half_thickness_m, "m");
  } catch (const InputError&) {
    // A tooth whose model places no crack (its default start off the flank): no rows.
  }
  lines.pair_csv_only("contact_ratio", contact_ratio(pair), "1");
  lines.pair_csv_only("operating_pressure_angle", g.operating_pressure_angle_rad, "rad");
  lines.pair_csv_only("centre_distance", g.centre_distance_m, "m");
  lines.pair_csv_only("contact_segment_start_x1", segment.start_m, "m");
  lines.pair_csv_only("contact_segment_end_x1", segment.end_m, "m");
  const StepBounds bounds = step_bounds(c);
  lines.pair_csv_only("contact_period", bounds.contact_period_s, "s");
  lines.pair_csv_only("largest_step_rk4", bounds.rk4_step_s, "s");
  lines.pair_csv_only("largest_step_dopri5", bounds.dopri5_step_s, "s");
  if (run && bounds.mesh_period_s > 0.0) {
    lines.pair_csv_only("largest_step_mesh_period", bounds.mesh_step_s, "s");
  }
  write_file_atomically((dir / "geometry.csv").string(), lines.csv);
  text += lines.md;
  text +=
      "\n(`geometry.csv`, SI units. `active_profile_above_form_circle`: the margin by which "
      "the contact stays on the involute, > 0 on a sound pair. `undercut_margin_shift`: x "
      "minus the least shift free of undercut, ha - z sin^2(a0) / 2. `lpstc_diameter`, "
      "`hpstc_diameter`: the lowest and highest points of single tooth contact, a base pitch "
      "from each end of the path of contact; a long tip relief starts at the HPSTC, and a relief "
      "starts within [d_SAP, d_a) (`modifications.tip_relief_start1`, ...). "
      "`crack_start_radius_r_s`, `crack_start_half_thickness_h_c`: where a root crack starts by "
      "default for the model (" +
      to_string(c.model.stiffness.kind) +
      ") and the half thickness there; a crack's depth q is bounded by q sin(nu) < h_c.)\n\n";
  for (std::size_t i = 0; i < c.faults.size(); ++i) {
    const ToothFault& f = c.faults[i];
    if (f.state.kind != ToothKind::root_crack) continue;
    const CrackReach reach = crack_reach(pair, c.model.stiffness, f.gear, f.state.crack);
    text += "Root crack faults[" + std::to_string(i) + "] (" +
            (f.gear == Gear::one ? "pinion" : "wheel") + " tooth " + std::to_string(f.tooth) +
            "): r_s = " + number(reach.start_radius_m * mm, 6) +
            " mm, h_c = " + number(reach.start_half_thickness_m * mm, 6) +
            " mm; its deepest q = " + number(largest_crack_depth(f.state.crack) * mm, 6) +
            " mm of at most h_c / sin(nu) = " + number(reach.largest_depth_m * mm, 6) + " mm.\n\n";
  }
  text += "Step bound of a run: the stiffest contact's period 2 pi sqrt(m_e / K) is " +
          number(bounds.contact_period_s * 1e6, 5) +
          " us, so integrator.step <= " + number(bounds.rk4_step_s * 1e6, 5) +
          " us with rk4 (the adaptive method's first step), " +
          number(bounds.dopri5_step_s * 1e6, 5) + " us with dopri5";
  if (run && bounds.mesh_period_s > 0.0) {
    text += "; at the case's pinion speed, " + number(kStepsPerMeshPeriod, 3) +
            " steps a mesh period: <= " + number(bounds.mesh_step_s * 1e6, 5) + " us";
  }
  text += " (`contact_period`, `largest_step_*` in `geometry.csv`).\n";
  return text;
}

// The models compared: all three when both bores are given (the foundation term needs them).
StiffnessComparison models_of(const GearPair& pair, std::size_t samples, std::string& note) {
  if (pair.bore_diameter1_m && pair.bore_diameter2_m) {
    return compare_stiffness_models(pair, samples);
  }
  note =
      "Only yang-lin-1987: potential-energy and ross-compatible need both bores for their "
      "fillet-foundation term (gears.bore_diameter1, gears.bore_diameter2).\n\n";
  StiffnessComparison c{};
  StiffnessModel model;
  c.models.push_back({model.kind, time_varying_mesh_stiffness(pair, model, samples),
                      mesh_stiffness(pair, pitch_point_position(pair), model)});
  c.iso = iso6336_method_b(iso6336_pair(pair, 0.0));
  c.iso_single_n_per_m = c.iso.single_stiffness_n_per_m2 * pair.face_width_m;
  c.iso_mesh_n_per_m = c.iso.mesh_stiffness_n_per_m2 * pair.face_width_m;
  return c;
}

std::string term_cell(const MeshStiffness& k, Term term, StiffnessModelKind kind) {
  if (!provides(kind, term)) return "-";
  return number(1.0 / k.pair.of(term) / kNPerUm, 4);
}

std::string stiffness_section(const GearPair& pair, const StiffnessComparison& comparison,
                              const std::filesystem::path& dir,
                              std::vector<std::string>& warnings) {
  const double b_mm = pair.face_width_m * 1e3;
  std::vector<std::string> series;
  for (const ModelComparison& m : comparison.models) {
    const std::string stem = "stiffness_tvms_" + to_string(m.kind);
    std::string csv = "fraction,theta1_deg,pairs,ke_n_per_um,ke_per_face_width_n_per_mm_um\n";
    for (const MeshStiffnessSample& s : m.tvms.samples) {
      csv += format_number(s.fraction) + "," + format_number(s.theta1_rad * 180.0 / pi) + "," +
             std::to_string(s.pairs) + "," + format_number(s.stiffness_n_per_m / kNPerUm) + "," +
             format_number(s.stiffness_n_per_m / pair.face_width_m / kNPerMmUm) + "\n";
    }
    write_file_atomically((dir / (stem + ".csv")).string(), csv);
    series.push_back(gnuplot_string(stem + ".csv") + " using 1:5 with lines lw 2 title " +
                     gnuplot_string(to_string(m.kind)));
    if (!m.tvms.foundation_extrapolations.empty()) {
      warnings.push_back(to_string(m.kind) + ": " +
                         foundation_extrapolation_warning(m.tvms.foundation_extrapolations) + ".");
    }
  }
  const double c_prime = comparison.iso.single_stiffness_n_per_m2 / kNPerMmUm;
  const double c_gamma = comparison.iso.mesh_stiffness_n_per_m2 / kNPerMmUm;
  series.push_back(number(c_prime, 6) +
                   " with lines dt 2 lw 2 lc rgb 'black' title \"ISO 6336-1 c'\"");
  series.push_back(
      number(c_gamma, 6) +
      " with lines dt 3 lw 2 lc rgb 'dark-red' title 'ISO 6336-1 c_{/Symbol g}{/Symbol a}'");
  render(dir,
         {"stiffness_tvms",
          "Mesh stiffness over one mesh period against ISO 6336-1 (b = " + number(b_mm, 4) + " mm)",
          "fraction of the mesh period",
          "mesh stiffness per face width, N/(mm {/Symbol m}m)",
          {"set key outside right top vertical", "set xrange [0:1]", "set yrange [0:*]"},
          series});
  std::string text =
      "yang-lin-1987 is the paper's tooth, an involute beam from the base circle without fillet "
      "or gear body, and so much stiffer than the rack-cut teeth of the other two "
      "(docs/stiffness-models.md). Mesh stiffness of each model (all its terms on) over one mesh "
      "period, per mm of face "
      "width as ISO 6336-1 states c' and c_gamma_alpha (`stiffness_tvms.png`, `.svg`; data "
      "`stiffness_tvms_<model>.csv`). ISO is an empirical fit with a scatter of its own: a "
      "band, not an identity. ISO 6336-1 method B (spur, C_M 0.8, C_R 1, no low-load "
      "correction): c' = " +
      number(c_prime, 5) +
      " N/(mm um) (c' b = " + number(comparison.iso_single_n_per_m / kNPerUm, 5) +
      " N/um), c_gamma_alpha = " + number(c_gamma, 5) +
      " N/(mm um) (c_gamma_alpha b = " + number(comparison.iso_mesh_n_per_m / kNPerUm, 5) +
      " N/um).\n\n";
  text += "| model | min | max | mean | min vs c' | mean vs c_gamma_alpha |\n";
  text += "|---|---|---|---|---|---|\n";
  const auto percent = [](double value, double reference) {
    const double p = 100.0 * (value / reference - 1.0);
    return (p >= 0.0 ? "+" : "") + number(p, 3) + " %";
  };
  for (const ModelComparison& m : comparison.models) {
    const double per_b = 1.0 / pair.face_width_m / kNPerMmUm;
    text += "| " + to_string(m.kind) + " | " + number(m.tvms.min_n_per_m * per_b, 4) + " | " +
            number(m.tvms.max_n_per_m * per_b, 4) + " | " + number(m.tvms.mean_n_per_m * per_b, 4) +
            " | " + percent(m.tvms.min_n_per_m, comparison.iso_single_n_per_m) + " | " +
            percent(m.tvms.mean_n_per_m, comparison.iso_mesh_n_per_m) + " |\n";
  }
  text += "\n(N/(mm um) per mm of face width.)\n\n### Terms at the pitch point\n\n";
  text +=
      "One pair in contact at the pitch point, stiffness of each term, N/um (both teeth in "
      "series; \"-\": not in the model):\n\n";
  text += "| model | hertz | bending | axial | shear | foundation | pair |\n";
  text += "|---|---|---|---|---|---|---|\n";
  for (const ModelComparison& m : comparison.models) {
    const MeshStiffness& k = m.at_pitch_point;
    text += "| " + to_string(m.kind) + " | " + term_cell(k, Term::hertz, m.kind) + " | " +
            term_cell(k, Term::bending, m.kind) + " | " + term_cell(k, Term::axial, m.kind) +
            " | " + term_cell(k, Term::shear, m.kind) + " | " +
            term_cell(k, Term::foundation, m.kind) + " | " + number(k.ke / kNPerUm, 4) + " |\n";
  }
  return text;
}

// With `modified` (the shares of the case's pair with its modifications and faults, from its
// loaded STE), load_sharing.csv gains the column share_modified and the figure its curve.
std::string load_sharing_section(const GearPair& pair, const StiffnessModel& model, int points,
                                 const std::filesystem::path& dir,
                                 const std::vector<LoadShareSample>* modified = nullptr,
                                 const std::string& modified_title = "",
                                 TeethInContact teeth = {}) {
  const std::vector<LoadShareSample> shares = load_sharing(pair, model, points);
  const ContactSegment segment = contact_segment(pair);
  std::string csv =
      std::string("x1_mm,path_fraction,pairs,share") + (modified ? ",share_modified" : "") + "\n";
  double least = 1.0;
  for (std::size_t i = 0; i < shares.size(); ++i) {
    const LoadShareSample& s = shares[i];
    csv += format_number(s.x1_m * 1e3) + "," +
           format_number((s.x1_m - segment.start_m) / (segment.end_m - segment.start_m)) + "," +
           std::to_string(s.pairs) + "," + format_number(s.share);
    if (modified) csv += "," + format_number((*modified)[i].share);
    csv += "\n";
    least = std::min(least, s.share);
  }
  write_file_atomically((dir / "load_sharing.csv").string(), csv);
  Figure figure{
      "load_sharing",
      "Load sharing: one tooth pair's share of the mesh force along its path (" +
          to_string(model.kind) + ")",
      "position on the path of contact X_1, mm (pitch point dashed)",
      "share of the mesh force",
      {"set key off", "set yrange [0:1.05]",
       "set arrow from " + number(pitch_point_position(pair) * 1e3, 8) + ", graph 0 to " +
           number(pitch_point_position(pair) * 1e3, 8) + ", graph 1 nohead dt 2 lc rgb 'gray30'"},
      {"'load_sharing.csv' using 1:4 with lines lw 2"}};
  std::string text =
      "One tooth pair's share of the mesh force as it crosses the path of contact, the "
      "loaded pairs deflecting alike, k(X1) / sum of k over the pairs in contact (model " +
      to_string(model.kind) +
      " of the case file; `load_sharing.png`, data "
      "`load_sharing.csv`). Its least share, at the path's ends, is " +
      number(least, 4) + ".\n";
  if (modified) {
    figure.setup[0] = "set key outside bottom center horizontal";
    figure.series = {
        "'load_sharing.csv' using 1:4 with lines lw 2 lc rgb 'gray50' title 'healthy, unmodified'",
        "'load_sharing.csv' using 1:5 with lines lw 2 lc rgb '#1f77b4' title '" + modified_title +
            "'"};
    double least_modified = 1.0;
    double most_modified = 0.0;
    for (const LoadShareSample& m : *modified) {
      least_modified = std::min(least_modified, m.share);
      most_modified = std::max(most_modified, m.share);
    }
    text +=
        "\nColumn `share_modified` (blue in the figure): the share of the pair of pinion tooth " +
        std::to_string(teeth.pinion_tooth) + " and wheel tooth " +
        std::to_string(teeth.wheel_tooth) +
        " (the first faulted tooth's, else teeth 0) with the case's modifications and faults at "
        "the load of the "
        "section \"Static transmission error\", from that STE's balance sum k max(0, delta - "
        "e) = F at each position (0 where its gap keeps it out of contact): from " +
        number(least_modified, 4) + " to " + number(most_modified, 4) +
        ", against the unmodified column's " + number(least, 4) + " to 1.\n";
  }
  render(dir, figure);
  return text;
}

// The modifications of the case in words, one item each; empty for none.
std::vector<std::string> modification_items(const Modifications& m) {
  std::vector<std::string> items;
  const auto um = [](double metres) { return number(metres * 1e6, 4) + " um"; };
  const auto shape = [](ReliefShape s) {
    return std::string(s == ReliefShape::linear ? "linear" : "parabolic");
  };
  const auto largest = [](const std::vector<double>& values) {
    double most = 0.0;
    for (const double v : values) most = std::max(most, std::fabs(v));
    return most;
  };
  for (const Gear gear : {Gear::one, Gear::two}) {
    const GearModifications& g = gear == Gear::one ? m.gear1 : m.gear2;
    const std::string who = gear == Gear::one ? "pinion" : "wheel";
    if (g.tip.amount_m > 0.0) {
      items.push_back(who + " tip relief " + um(g.tip.amount_m) + " at the tip, " +
                      shape(g.tip.shape) + ", from d_Ca = " + number(g.tip.diameter_m * 1e3, 6) +
                      " mm");
    }
    if (g.root.amount_m > 0.0) {
      items.push_back(who + " root relief " + um(g.root.amount_m) +
                      " at the start of the active profile, " + shape(g.root.shape) +
                      ", to d_Cf = " + number(g.root.diameter_m * 1e3, 6) + " mm");
    }
    if (largest(g.pitch_m) > 0.0) {
      items.push_back(who + " pitch errors, largest |f| " + um(largest(g.pitch_m)));
    }
    if (largest(g.thickness_m) > 0.0) {
      items.push_back(who + " thickness errors, largest |f| " + um(largest(g.thickness_m)));
    }
    if (largest(g.profile_slope_m) > 0.0) {
      items.push_back(who + " profile slope errors, largest |f_Ha| " +
                      um(largest(g.profile_slope_m)));
    }
    if (g.iso1328_class > 0) {
      items.push_back(who + " errors drawn from ISO 1328-1 flank tolerance class " +
                      std::to_string(g.iso1328_class) + " (error_seed " +
                      std::to_string(m.error_seed) + ")");
    }
  }
  return items;
}

// The STE of the case's pair with its modifications and faults beside the healthy unmodified
// pair (the files and figures of `gearimpact ste`), and what it says.
std::string ste_section(const SimulationCase& c, const ReportLoad& load, int samples,
                        const std::filesystem::path& dir) {
  SteTexts texts;
  try {
    texts = ste_texts(c, load.torque1_n_m, samples);
  } catch (const InputError& e) {
    if (e.field() == "points") throw InputError("--samples", e.value(), e.allowed());
    if (e.field() == "torque") throw InputError("--torque", e.value(), e.allowed());
    throw;
  }
  write_file_atomically((dir / "ste.csv").string(), texts.csv);
  write_file_atomically((dir / "ste_unmodified.csv").string(), texts.unmodified_csv);
  write_file_atomically((dir / "ste_pairs.csv").string(), texts.pairs_csv);
  write_file_atomically((dir / "ste_unmodified_pairs.csv").string(), texts.unmodified_pairs_csv);
  write_file_atomically((dir / "ste_summary.json").string(), texts.summary_json);
  render(dir, ste_figure(c, texts));
  render(dir, ste_sharing_figure(c, texts));
  const StaticTransmissionError& ste = texts.modified;
  // The least and largest STE over the carried angles.
  const auto extremes = [](const StaticTransmissionError& e) {
    double least = INFINITY;
    double most = -INFINITY;
    for (const StePoint& p : e.points) {
      if (!p.carried) continue;
      least = std::min(least, p.ste_m);
      most = std::max(most, p.ste_m);
    }
    return std::pair<double, double>{least, most};
  };
  const auto row = [&](const std::string& name, const StaticTransmissionError& e, double ratio) {
    const auto [least, most] = extremes(e);
    return "| " + name + " | " + number(least * 1e6, 5) + " | " + number(most * 1e6, 5) + " | " +
           number(e.ste_peak_to_peak_m * 1e6, 5) + " | " + number(e.ste_mean_m * 1e6, 5) + " | " +
           number(ratio, 5) + " |\n";
  };
  std::string text =
      "The loaded static transmission error of the case's pair with its modifications and "
      "faults, beside the healthy pair without modifications (`gearimpact ste` at T1 = " +
      number(load.torque1_n_m, 6) + " N m, F = " + number(ste.force_n, 6) +
      " N on the drive "
      "flanks, " +
      load.origin + "; " + std::to_string(samples) + " angles per mesh period over " +
      std::to_string(ste.mesh_periods) +
      " mesh periods). Figures `ste.png` and `ste_load_sharing.png`, data `ste.csv`, "
      "`ste_unmodified.csv`, `ste_pairs.csv`, `ste_unmodified_pairs.csv` and `ste_summary.json` "
      "(as `gearimpact ste` writes them).\n\n";
  text +=
      "| | STE min (um) | STE max (um) | peak-to-peak (um) | mean (um) | quasi-static peak / F |\n";
  text += "|---|---|---|---|---|---|\n";
  text += row("this pair", ste, texts.quasi_static_force_ratio);
  text += row("healthy, unmodified", texts.unmodified, texts.unmodified_quasi_static_force_ratio);
  text += "\n";
  text +=
      "The quasi-static peak is the largest mesh force of a slow run over F: where a pair enters "
      "touching (or crosses a fault's edge) the loaded pairs keep their deflection for an "
      "instant, and the force jumps; a relief that holds the entering pair off removes the jump "
      "(docs/faults.md, \"Static transmission error\"). A sweep of this case divides its dynamic "
      "factor by it.\n";
  return text;
}

std::string time_history_section(const SimulationCase& run, const std::filesystem::path& dir) {
  SimulationCase c = run;
  const double steps = c.integrator.end_time_s / c.integrator.step_s;
  c.integrator.output_every =
      std::max(c.integrator.output_every, static_cast<int>(std::ceil(steps / kMostHistoryRows)));
  // A long run says what it is doing before it starts.
  std::cerr << "report: time history, " << number(steps, 3) << " steps of "
            << number(c.integrator.step_s * 1e6, 3) << " us ...\n";
  const SimulationResult r = simulate(c);
  // DTE relative to the contact: s - B on the drive flanks (T1 >= 0), s + B on the coast ones.
  const double side = mean_torque1(c) >= 0.0 ? 1.0 : -1.0;
  const double contact = side * c.gears.backlash_m;
  std::string csv = "t_ms,dte_um,s_um,pairs,normal_force_n\n";
  double least = INFINITY;
  double most = -INFINITY;
  double force_max = 0.0;
  for (const SeriesRow& row : r.series) {
    const double dte = row.s_m - contact;
    csv += format_number(row.t_s * 1e3) + "," + format_number(dte * 1e6) + "," +
           format_number(row.s_m * 1e6) + "," + std::to_string(row.pairs) + "," +
           format_number(row.normal_force_n) + "\n";
    least = std::min(least, dte);
    most = std::max(most, dte);
    force_max = std::max(force_max, row.normal_force_n);
  }
  write_file_atomically((dir / "time_history.csv").string(), csv);
  render(dir, {"time_history_dte",
               "Dynamic transmission error against time (s " + std::string(side > 0 ? "-" : "+") +
                   " B, " + number(c.integrator.end_time_s * 1e3, 4) +
                   " ms from the case's "
                   "initial state)",
               "time t, ms",
               "DTE, {/Symbol m}m (0: the teeth just touch)",
               {"set key off"},
               {"'time_history.csv' using 1:2 with lines lw 1.5"}});
  const double rb1 = base_radius(c.gears, Gear::one);
  const double static_load = std::fabs(mean_torque1(c)) / rb1;
  std::string text = "The case run as its file says (" + number(c.integrator.end_time_s * 1e3, 4) +
                     " ms, every " + std::to_string(c.integrator.output_every) +
                     "th step kept; `time_history_dte.png`, data `time_history.csv`): DTE = s " +
                     (side > 0 ? "-" : "+") + " B from " + number(least * 1e6, 5) + " to " +
                     number(most * 1e6, 5) + " um, " + std::to_string(r.summary.impacts_n1) +
                     " impacts on the drive flanks and " + std::to_string(r.summary.impacts_n2) +
                     " on the coast flanks, largest mesh force " + number(force_max, 5) + " N";
  if (static_load > 0.0) {
    text += " (" + number(force_max / static_load, 4) +
            " times the static load |T1| / Rb1 = " + number(static_load, 5) + " N)";
  }
  return text + ".\n";
}

// The faulted pair's mesh stiffness over its true period against the same pairs all healthy
// (mesh_stiffness.csv, the figure of `mesh-stiffness --figure`), `samples` per mesh period.
std::string faulted_stiffness_section(const SimulationCase& c, int samples,
                                      const std::filesystem::path& dir) {
  MeshStiffnessTexts texts;
  try {
    texts = mesh_stiffness_texts(c.gears, c.model.stiffness, samples, c.faults);
  } catch (const InputError& e) {
    // The true period's bound on the samples, under the option that sets them.
    if (e.field() != "samples") throw;
    throw InputError("--samples", e.value(), e.allowed());
  }
  write_file_atomically((dir / "mesh_stiffness.csv").string(), texts.csv);
  render(dir, mesh_stiffness_figure(texts.tvms, c.faults, c.name));
  const TruePeriodMeshStiffness& t = texts.tvms;
  const double healthy_min =
      time_varying_mesh_stiffness(c.gears, c.model.stiffness, static_cast<std::size_t>(samples))
          .min_n_per_m;
  return "The mesh stiffness of the case's model (" + to_string(c.model.stiffness.kind) +
         ") with its [[faults]] over the true period (" + t.period_kind + ", " +
         std::to_string(t.mesh_periods) +
         " mesh periods) from pinion tooth 0 entering against wheel tooth 0, against the same "
         "pairs all healthy; the stretches where a faulted tooth is in contact are shaded "
         "(`mesh_stiffness.png`, data `mesh_stiffness.csv`).\n\n"
         "| | min (N/um) | mean (N/um) |\n|---|---|---|\n| with the faults | " +
         number(t.min_n_per_m / kNPerUm, 5) + " | " + number(t.mean_n_per_m / kNPerUm, 6) +
         " |\n| healthy | " + number(healthy_min / kNPerUm, 5) + " | " +
         number(t.healthy_mean_n_per_m / kNPerUm, 6) + " |\n\nThe mean is " +
         number(100.0 * (1.0 - t.mean_n_per_m / t.healthy_mean_n_per_m), 4) +
         " % below the healthy mean, the minimum " +
         number(100.0 * (1.0 - t.min_n_per_m / healthy_min), 4) + " % below the healthy minimum.\n";
}

// The load of a modified or faulted pair's STE: --torque, else the run's mean pinion torque
// (its size: the STE loads the drive flanks), else ISO's reference line load.
ReportLoad report_load(const ReportOptions& o, const SimulationCase& c, bool run) {
  if (!o.torque.empty()) {
    const double t = parse_quantity(o.torque, Dimension::torque, "--torque");
    if (!(t > 0.0)) {
      throw InputError("--torque", o.torque,
                       "a pinion torque > 0 (" + allowed_units(Dimension::torque) +
                           "): it loads the drive flanks");
    }
    return {t, "the --torque given"};
  }
  if (run && c.torque1.kind != Torque::Kind::prescribed_speed) {
    const double t = std::fabs(mean_torque(c.torque1));
    if (t > 0.0) {
      return {t, std::string("the size of the case's mean pinion torque") +
                     (mean_torque(c.torque1) < 0.0 ? ", on the drive flanks" : "")};
    }
  }
  const double t = kIsoReferenceLineLoad * c.gears.face_width_m * pitch_radius(c.gears, Gear::one);
  return {t,
          "ISO 6336-1's reference line load F_t / b = 100 N/mm at the reference circle: the "
          "case gives no mean torque (--torque sets one)"};
}

void write_report(const ReportOptions& o) {
  require_output_folder(o.out, o.overwrite, {o.case_file});
  const PairOrRunCase read = read_pair_or_run_file(o.case_file);
  const SimulationCase& c = read.simulation_case;
  const bool run = read.kind == CaseFileKind::run;
  // A helical pair's sections are its own (its geometry, contact lines, slices).
  if (c.gears.helix_angle_rad != 0.0) {
    write_helical_report(c, o.case_file, o.out, o.overwrite, o.samples, o.torque);
    return;
  }
  // A modified or faulted pair: its STE and load sharing beside the unmodified, at one load.
  const bool changed = !is_unmodified(c.modifications) || !c.faults.empty();
  if (!changed && !o.torque.empty()) {
    throw InputError("--torque", o.torque,
                     "only for a pair with [modifications] or [[faults]], whose load sharing "
                     "depends on the load; this pair has neither");
  }
  ReportLoad load;
  if (changed) {
    load = report_load(o, c, run);
    StaticTransmissionErrorOptions options;
    options.points_per_mesh_period = o.samples;
    // The faults' true period, as `ste` finds it, bounds the samples before any work.
    options.faulted = faulted_teeth(c);
    try {
      validate_static_transmission_error(c.gears, c.modifications, load.torque1_n_m, options);
    } catch (const InputError& e) {
      throw InputError(e.field() == "points" ? "--samples" : "--torque", e.value(), e.allowed());
    }
  }
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  const Progress progress;
  std::vector<std::string> warnings;
  std::string faulted;
  if (!c.faults.empty()) {
    warnings.push_back("the case has " + std::to_string(c.faults.size()) +
                       " faulted teeth ([[faults]]): the geometry and stiffness sections are "
                       "the healthy pair's, the load sharing and static transmission error "
                       "sections show the faulted pair beside the healthy one" +
                       (run ? std::string("; the time history runs with the faults") : "") +
                       "; the section \"Mesh stiffness with the faults\" gives the faulted "
                       "stiffness over the true period");
    faulted = faulted_stiffness_section(c, o.samples, dir);
    progress.done("mesh stiffness with the faults");
  }

  const std::string geometry = geometry_section(c, run, dir);
  progress.done("geometry");
  std::string note;
  const StiffnessComparison comparison =
      models_of(c.gears, static_cast<std::size_t>(o.samples), note);
  std::string stiffness = note + stiffness_section(c.gears, comparison, dir, warnings);
  // A kinematic driver's mean torque is not known before the run; a mean torque of 0 (a free
  // impact, Table 1's cases 1 and 3) has no line load for ISO's low-load factor.
  const bool driven = run && c.torque1.kind == Torque::Kind::prescribed_speed;
  const double line_load =
      run && !driven
          ? std::fabs(mean_torque1(c)) / (pitch_radius(c.gears, Gear::one) * c.gears.face_width_m)
          : 0.0;
  if (line_load > 0.0) {
    // ISO's line load at the reference circle, K_A = 1: below 100 N/mm c' takes the low-load
    // factor (iso6336 --load).
    Iso6336Pair loaded = iso6336_pair(c.gears, 0.0);
    loaded.specific_load_n_per_m = line_load;
    stiffness += "\nAt the case's mean pinion torque F_t / b = " + number(line_load * 1e-3, 4) +
                 " N/mm (K_A = 1): ISO's low-load factor (F_t K_A / b / 100 N/mm)^0.25 below 100 "
                 "N/mm is " +
                 number(iso6336_method_b(loaded).low_load_factor, 4) + ".\n";
  }
  progress.done("stiffness models and ISO 6336-1");
  std::string sharing;
  std::string ste;
  const std::vector<std::string> modifications = modification_items(c.modifications);
  if (changed) {
    const auto healthy = std::make_shared<const StiffnessTable>(c.gears, c.model.stiffness);
    const MeshTables tables(c.gears, c.model.stiffness, c.faults, healthy);
    // The pair of the first faulted tooth (pair -i holds tooth i of either gear), else pair 0.
    const int k = c.faults.empty() ? 0 : -c.faults.front().tooth;
    const std::vector<LoadShareSample> shares =
        loaded_load_sharing(c.gears, c.modifications, load.torque1_n_m, tables,
                            contact_positions(c.gears, o.samples), k);
    const TeethInContact teeth = teeth_of_pair(c.gears, Region::n1, k);
    std::string title = modifications.empty() ? "faulted" : "modified";
    if (!modifications.empty() && !c.faults.empty()) title = "faulted, modified";
    sharing = load_sharing_section(c.gears, c.model.stiffness, o.samples, dir, &shares,
                                   title + ", teeth " + std::to_string(teeth.pinion_tooth) + "/" +
                                       std::to_string(teeth.wheel_tooth) +
                                       ", T_1 = " + number(load.torque1_n_m, 4) + " N m",
                                   teeth);
    progress.done("load sharing");
    ste = ste_section(c, load, o.samples, dir);
    progress.done("static transmission error");
  } else {
    sharing = load_sharing_section(c.gears, c.model.stiffness, o.samples, dir);
    progress.done("load sharing");
  }
  std::string history =
      "The case file is a pair file ([gears] and [model] only): no torques or speeds, no time "
      "history.\n";
  if (run) {
    for (const std::string& w : run_warnings(c)) {
      std::string sentence = w;
      sentence.front() =
          static_cast<char>(std::toupper(static_cast<unsigned char>(sentence.front())));
      warnings.push_back(sentence + ".");
    }
    history = time_history_section(c, dir);
    progress.done("time history");
  }

  std::string md = "# gearimpact report: " + c.name + "\n\n";
  md += "Case file `" + o.case_file + "` (" + (run ? "a run file" : "a pair file") +
        "): " + std::to_string(c.gears.teeth1) + "/" + std::to_string(c.gears.teeth2) +
        " teeth, m " + number(c.gears.module_m * 1e3, 6) + " mm, b " +
        number(c.gears.face_width_m * 1e3, 6) + " mm, x " + number(c.gears.profile_shift1, 4) +
        "/" + number(c.gears.profile_shift2, 4) + ", a0 " +
        number(c.gears.pressure_angle_rad * 180.0 / pi, 6) + " deg.\n\n";
  if (!modifications.empty()) {
    md += "Modifications ([modifications]):\n\n";
    for (const std::string& item : modifications) md += "- " + item + "\n";
    md +=
        "\nThe sections \"Load sharing\" and \"Static transmission error\" show the pair "
        "with them beside the pair without.\n\n";
  }
  md += "## Warnings\n\n";
  if (warnings.empty()) md += "None.\n";
  for (const std::string& w : warnings) md += "- " + w + "\n";
  md += "\n## Geometry\n\n" + geometry + "\n## Mesh stiffness and ISO 6336-1\n\n" + stiffness +
        "\n## Load sharing\n\n" + sharing;
  if (!ste.empty()) md += "\n## Static transmission error\n\n" + ste;
  if (!faulted.empty()) md += "\n## Mesh stiffness with the faults\n\n" + faulted;
  md += "\n## Time history\n\n" + history;
  write_file_atomically((dir / "REPORT.md").string(), md);
  folder.commit();
  for (const std::string& w : warnings) std::cerr << "gearimpact: warning: " << w << "\n";
  std::cerr << "report: wrote " << (std::filesystem::path(o.out) / "REPORT.md").string() << "\n";
}

}  // namespace

void register_report_commands(CLI::App& app) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* report = app.add_subcommand(
      "report",
      "Everything that applies to your pair in one folder: geometry, the stiffness models against "
      "ISO 6336-1, terms at the pitch point, load sharing, a time history for a run file, and "
      "REPORT.md with every warning");
  report
      ->add_option("case", o->case_file, "case file: a pair file ([gears], [model]) or a run file")
      ->required();
  report
      ->add_option("--out", o->out,
                   "output folder: new or empty (else --overwrite), in a folder that exists")
      ->required();
  report->add_flag("--overwrite", o->overwrite, "replace a non-empty --out folder whole");
  report->add_option("--torque", o->torque,
                     "for a pair with [modifications] or [[faults]]: the pinion torque T1 > 0 "
                     "with its unit (\"100 N*m\") its STE and load sharing are computed at; "
                     "default the run file's mean torque, else ISO's 100 N/mm line load");
  report
      ->add_option("--samples", o->samples,
                   "samples over the mesh period and the path, 2 to 100000")
      ->check(CLI::Range(2, 100000));
  report->callback([o] { write_report(*o); });
}

}  // namespace gearimpact::cli
