// `gearimpact report` on a helical pair file (docs/helical.md, "Report"): the helical geometry
// table, the contact lines in the zone of action, the mesh stiffness of the slices over a mesh
// period beside ISO 6336-1's c_gamma_alpha b, and with [modifications] the slice model's loaded
// STE and the load across the face.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/helical_faults.hpp"
#include "gearimpact/stiffness/helical_ste.hpp"
#include "geometry_table.hpp"
#include "gnuplot.hpp"
#include "mesh_stiffness_figure.hpp"
#include "program.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

namespace {

// ISO's unit of stiffness per face width, N/(mm um), in N/m^2.
constexpr double kNPerMmUm = 1e9;
// ISO 6336-1's reference line load, 100 N/mm at the reference circle: the load without --torque.
constexpr double kIsoReferenceLineLoad = 100e3;

std::string geometry_section(const GearPair& pair, const HelicalGeometry& g, double torque,
                             const std::string& origin, const std::filesystem::path& dir) {
  GeometryTable r{.angles_in_degrees = true};
  r.both("teeth z", pair.teeth1, pair.teeth2, "1");
  r.both("profile_shift x (normal section)", pair.profile_shift1, pair.profile_shift2, "1");
  r.both("pitch_radius r", g.pitch_radius1_m, g.pitch_radius2_m, "m");
  r.both("base_radius r_b", g.base_radius1_m, g.base_radius2_m, "m");
  r.both("tip_radius r_a", g.tip_radius1_m, g.tip_radius2_m, "m");
  r.both("virtual_teeth zn", g.virtual_teeth1, g.virtual_teeth2, "1");
  r.pair("helix_angle beta", g.helix_angle_rad, "rad");
  r.pair("base_helix_angle beta_b", g.base_helix_angle_rad, "rad");
  r.pair("normal_module m_n", g.normal_module_m, "m");
  r.pair("transverse_module m_t", g.transverse_module_m, "m");
  r.pair("normal_pressure_angle alpha_n", g.normal_pressure_angle_rad, "rad");
  r.pair("transverse_pressure_angle alpha_t", g.transverse_pressure_angle_rad, "rad");
  r.pair("working_pressure_angle alpha_wt", g.working_pressure_angle_rad, "rad");
  r.pair("centre_distance a_w", g.centre_distance_m, "m");
  r.pair("transverse_base_pitch p_bt", g.transverse_base_pitch_m, "m");
  r.pair("normal_base_pitch p_bn", g.normal_base_pitch_m, "m");
  r.pair("path_of_contact g_alpha", g.path_of_contact_m, "m");
  r.pair("transverse_contact_ratio eps_alpha", g.transverse_contact_ratio, "1");
  r.pair("overlap_ratio eps_beta", g.overlap_ratio, "1");
  r.pair("total_contact_ratio eps_gamma", g.total_contact_ratio, "1");
  r.pair("face_width b", g.face_width_m, "m");
  r.pair("contact_line_across_face b/cos(beta_b)", g.contact_line_length_m, "m");
  const HelicalForces f = helical_forces(g, torque);
  r.pair("transverse_force F_bt", f.transverse_n, "N");
  r.pair("tangential_force F_t", f.tangential_n, "N");
  r.pair("radial_force F_r", f.radial_n, "N");
  r.pair("axial_force F_a", f.axial_n, "N");
  r.pair("normal_force F_bn", f.normal_n, "N");
  write_file_atomically((dir / "geometry.csv").string(), r.csv);
  return "Normal-section inputs (module, pressure angle, shifts); the transverse section is the "
         "spur pair of m_t, alpha_t (docs/helical.md). Forces at T_1 = " +
         number(torque, 6) + " N m (" + origin + "). `geometry.csv` holds the same in SI.\n\n" +
         r.md;
}

// The contact lines in the zone of action at theta1 = 0 and a quarter, a half and three quarters
// of a mesh period later: each line X = X_k + sigma (y - b/2) tan(beta_b), clipped to the zone
// [X_SAP, X_EAP] x [0, b]; X from the pinion's base-circle tangent point, mm.
std::string contact_lines_section(const GearPair& pair, const HelicalGeometry& g,
                                  const HelicalMesh& mesh, const FaceStiffness& face,
                                  const std::filesystem::path& dir) {
  const double b = pair.face_width_m;
  const double tan_bb = std::tan(g.base_helix_angle_rad);
  const int sigma = hand_sign(pair.helix_hand);
  const double start = face.start_m();
  const double end = face.end_m();
  std::string csv = "phase,pair,x_mm,y_mm\n";
  const double phases[] = {0.0, 0.25, 0.5, 0.75};
  for (int i = 0; i < 4; ++i) {
    const double theta = phases[i] * mesh.mesh_period_rad();
    bool any = false;
    for (int k = -8; k <= 8; ++k) {
      const double xk = mesh.mid_face_position_m(Region::n1, theta, k);
      // y where the line crosses X_SAP and X_EAP, within [0, b].
      const double y_at_start = 0.5 * b + sigma * (start - xk) / tan_bb;
      const double y_at_end = 0.5 * b + sigma * (end - xk) / tan_bb;
      const double low = std::max(0.0, std::min(y_at_start, y_at_end));
      const double high = std::min(b, std::max(y_at_start, y_at_end));
      if (!(high > low)) continue;
      any = true;
      for (const double y : {low, high}) {
        const double x = xk + sigma * (y - 0.5 * b) * tan_bb;
        csv += format_data_number(phases[i]) + "," + std::to_string(k) + "," +
               format_data_number(x * 1e3) + "," + format_data_number(y * 1e3) + "\n";
      }
      csv += "\n";
    }
    if (any) csv += "\n";
  }
  write_file_atomically((dir / "contact_lines.csv").string(), csv);
  const std::string x0 = format_data_number(start * 1e3);
  const std::string x1 = format_data_number(end * 1e3);
  const std::string y1 = format_data_number(b * 1e3);
  const double margin = 0.05 * (end - start) * 1e3;
  render(dir, {"contact_lines",
               "Contact lines in the zone of action (plane of action), " +
                   std::string(sigma > 0 ? "right" : "left") + "-hand pinion",
               "X along the transverse line of action from the pinion's base tangent point, mm",
               "y across the face, mm",
               // The file holds a data set per phase: no header row read from each of them.
               {"set key outside right top vertical", "set key noautotitle",
                "set object 1 rect from " + x0 + ",0 to " + x1 + "," + y1 +
                    " fs empty border lc rgb 'black' lw 1",
                "set xrange [" + format_data_number(start * 1e3 - margin) + ":" +
                    format_data_number(end * 1e3 + margin) + "]",
                "set yrange [-1:" + format_data_number(b * 1e3 + 1.0) + "]",
                "set arrow 1 from " +
                    format_data_number(mesh.mid_face_position_m(Region::n1, 0.0, 0) * 1e3) +
                    ",graph 0 to " +
                    format_data_number(mesh.mid_face_position_m(Region::n1, 0.0, 0) * 1e3) +
                    ",graph 1 nohead dt 3 lc rgb 'gray40'"},
               {"'contact_lines.csv' index 0 using 3:4 with lines lw 3 lc rgb '#1f77b4' title "
                "'{/Symbol q}_1 = 0'",
                "'contact_lines.csv' index 1 using 3:4 with lines lw 1 lc rgb '#ff7f0e' title "
                "'+ 1/4 mesh period'",
                "'contact_lines.csv' index 2 using 3:4 with lines lw 1 lc rgb '#2ca02c' title "
                "'+ 1/2'",
                "'contact_lines.csv' index 3 using 3:4 with lines lw 1 lc rgb '#d62728' title "
                "'+ 3/4'"}});
  return "The zone of action in the plane of action is g_alpha = " +
         number((end - start) * 1e3, 6) +
         " mm along the transverse line of action by b = " + number(b * 1e3, 6) +
         " mm across the face; the contact lines are straight, inclined at beta_b = " +
         number(g.base_helix_angle_rad * 180.0 / pi, 6) +
         " deg to the axis, p_bt = " + number(g.transverse_base_pitch_m * 1e3, 6) +
         " mm apart along X (`contact_lines.png`, data `contact_lines.csv`, one data set per "
         "phase; the dotted line is the pitch point).\n";
}

std::string stiffness_section(const GearPair& pair, const StiffnessModel& model,
                              const HelicalMeshStiffnessCurve& curve,
                              const std::filesystem::path& dir) {
  write_file_atomically((dir / "helical_mesh_stiffness.csv").string(),
                        helical_mesh_stiffness_csv(curve));
  const double b = pair.face_width_m;
  const double per_b = 1.0 / b / kNPerMmUm;
  const double iso = curve.iso_mesh_stiffness_n_per_m * per_b;
  const std::string scale = format_data_number(per_b);
  render(dir, {"helical_mesh_stiffness",
               "Mesh stiffness over a mesh period, " + to_string(model.kind) +
                   " slices, b = " + number(b * 1e3, 4) + " mm",
               "fraction of the mesh period",
               "mesh stiffness per face width, N/(mm {/Symbol m}m)",
               {"set key outside right top vertical", "set xrange [0:1]", "set yrange [0:*]",
                "set y2label 'summed contact-line length, mm'", "set y2tics", "set y2range [0:*]"},
               {"'helical_mesh_stiffness.csv' using 1:($4 * " + scale +
                    ") with lines lw 2 lc rgb '#1f77b4' title 'face integral (route B)'",
                "'helical_mesh_stiffness.csv' using 1:($3 * " + scale +
                    ") with steps lw 1 lc rgb "
                    "'#ff7f0e' title " +
                    gnuplot_string(std::to_string(curve.face_slices) + " slices (route A)"),
                number(iso, 6) + " with lines dt 3 lw 2 lc rgb 'dark-red' title 'ISO 6336-1 "
                                 "c_{/Symbol g}{/Symbol a}'",
                "'helical_mesh_stiffness.csv' using 1:($5 * 1e3) axes x1y2 with lines dt 2 lw 1 lc "
                "rgb 'gray40' title 'contact-line length (right axis)'"}});
  const auto mm_um = [&](double n_per_m) { return number(n_per_m * per_b, 5); };
  const double percent = 100.0 * (curve.mean_n_per_m / curve.iso_mesh_stiffness_n_per_m - 1.0);
  return "Model " + to_string(model.kind) + ", " + std::to_string(curve.face_slices) +
         " slices, Hertz " +
         (model.helical_hertz == HelicalHertz::projected ? "projected" : "face-width") +
         " (docs/helical.md). Per mm of face width, N/(mm um): the face integral from " +
         mm_um(curve.min_face_n_per_m) + " to " + mm_um(curve.max_face_n_per_m) +
         ", the slices from " + mm_um(curve.min_slices_n_per_m) + " to " +
         mm_um(curve.max_slices_n_per_m) + ", the exact mean " + mm_um(curve.mean_n_per_m) +
         " (both routes, every N); ISO 6336-1's "
         "c_gamma_alpha (its helical c' with cos(beta) and zn) " +
         number(iso, 5) + " (mean " + (percent >= 0.0 ? "+" : "") + number(percent, 3) +
         " % against it; ISO is an empirical fit, a band, not an identity" +
         (model.kind == StiffnessModelKind::yang_lin_1987
              ? std::string(", and yang-lin-1987's tooth, from the base circle without fillet "
                            "foundation, is far stiffer than ISO's fit, docs/stiffness-models.md")
              : std::string()) +
         "). The summed "
         "contact-line length has the mean b eps_alpha / cos(beta_b) = " +
         number(curve.mean_contact_line_length_m * 1e3, 6) +
         " mm (`helical_mesh_stiffness.png`, data `helical_mesh_stiffness.csv`).\n";
}

// The faulted pair's mesh stiffness over the true period against the healthy one, by the
// tables a run reads (helical_true_period_mesh_stiffness): `mesh_stiffness.csv` and the figure
// of a faulted spur pair's report, each faulted tooth's stretch of contact shaded.
std::string faults_section(const SimulationCase& c, int samples, const std::filesystem::path& dir) {
  const TruePeriodMeshStiffness tvms = helical_true_period_mesh_stiffness(
      c.gears, c.model.stiffness, c.faults, static_cast<std::size_t>(samples));
  write_file_atomically((dir / "mesh_stiffness.csv").string(),
                        true_period_mesh_stiffness_csv(tvms));
  Figure f = mesh_stiffness_figure(tvms, c.faults, c.name);
  f.x_label = "pinion angle {/Symbol q}_1 from pair 0's mid-face contact at the pitch point, deg";
  render(dir, f);
  std::string teeth;
  for (const ToothFault& fault : c.faults) {
    teeth += std::string(teeth.empty() ? "" : ", ") +
             (fault.gear == Gear::one ? "pinion tooth " : "wheel tooth ") +
             std::to_string(fault.tooth) + " " + to_string(fault.state.kind);
  }
  return "The faulted teeth (" + teeth +
         ") cover bands of the face (docs/helical.md, Faults); each pair reads the table of its "
         "teeth that a run reads. Over the true period (" +
         tvms.period_kind + ", " + std::to_string(tvms.mesh_periods) +
         " mesh periods) the mesh stiffness runs from " + number(tvms.min_n_per_m / 1e8, 5) +
         " to " + number(tvms.max_n_per_m / 1e8, 5) + " x 10^8 N/m, mean " +
         number(tvms.mean_n_per_m / 1e8, 6) + " x 10^8 N/m against the healthy pair's " +
         number(tvms.healthy_mean_n_per_m / 1e8, 6) +
         " x 10^8 N/m (`mesh_stiffness.png`, data `mesh_stiffness.csv`, columns as "
         "`gearimpact mesh-stiffness`).\n";
}

std::string ste_section(const HelicalSteFiles& files, double torque, const std::string& origin,
                        bool faulted) {
  const HelicalStaticTransmissionError& m = files.modified;
  const HelicalStaticTransmissionError& u = files.unmodified;
  const auto um = [](double metres) { return number(metres * 1e6, 4); };
  const auto range = [&](const HelicalStaticTransmissionError& s) {
    double least = s.points.front().ste_m;
    double most = least;
    for (const HelicalStePoint& p : s.points) {
      least = std::min(least, p.ste_m);
      most = std::max(most, p.ste_m);
    }
    return um(least) + " to " + um(most) + " um (mean " + um(s.ste_mean_m) + ")";
  };
  return "At T_1 = " + number(torque, 6) + " N m (" + origin + "), " +
         std::to_string(m.face_slices) +
         " slices, the slice model's loaded STE (docs/helical.md, \"Loaded STE and the load "
         "across the face\"): " +
         (faulted ? "with the faults " : "with the modifications ") + range(m) +
         ", K_Hbeta = " + number(m.face_load_factor, 4) +
         " from the mean load across the face (at most " + number(m.largest_face_load_factor, 4) +
         " at one angle), its centre " +
         number((m.mean_load_centre_m - 0.5 * m.face_width_m) * 1e3, 4) + " mm from mid-face; " +
         (faulted ? "the healthy pair " : "without them ") + range(u) + ", K_Hbeta " +
         number(u.face_load_factor, 4) +
         ". Files `ste.csv`, `ste_unmodified.csv`, `ste_face_load.csv`, `ste_summary.json`; "
         "figures `ste.png`, `ste_face_load.png`.\n";
}

}  // namespace

void write_helical_report(const SimulationCase& c, const std::string& case_file,
                          const std::string& out, bool overwrite, int samples,
                          const std::string& torque_text) {
  const bool modified = !is_unmodified(c.modifications);
  const bool faulted = !c.faults.empty();
  if (!modified && !faulted && !torque_text.empty()) {
    throw InputError("--torque", torque_text,
                     "only for a pair with [modifications] or [[faults]], whose STE depends on "
                     "the load; this pair has neither");
  }
  const HelicalGeometry g = helical_geometry(c.gears);
  double torque = kIsoReferenceLineLoad * c.gears.face_width_m * g.pitch_radius1_m;
  std::string origin =
      "ISO 6336-1's reference line load F_t / b = 100 N/mm at the reference "
      "circle (--torque sets one)";
  if (!torque_text.empty()) {
    torque = parse_quantity(torque_text, Dimension::torque, "--torque");
    if (!(torque > 0.0)) {
      throw InputError("--torque", torque_text,
                       "a pinion torque > 0 (" + allowed_units(Dimension::torque) +
                           "): it loads the drive flanks");
    }
    origin = "the --torque given";
  }
  if (modified || faulted) {
    try {
      check_helical_ste(c, torque, samples);
    } catch (const InputError& e) {
      if (e.field() == "points") throw InputError("--samples", e.value(), e.allowed());
      if (e.field() == "torque") throw InputError("--torque", torque_text, e.allowed());
      throw;
    }
  }
  AtomicFolder folder(out, overwrite, {case_file});
  const std::filesystem::path dir = folder.temporary();
  const FaceStiffness face(c.gears, c.model.stiffness, c.model.stiffness.helical_hertz);
  const HelicalMesh mesh(c.gears, face);
  const HelicalMeshStiffnessCurve curve =
      helical_mesh_stiffness(c.gears, c.model.stiffness, samples);
  std::string md = "# gearimpact report: " + c.name + " (helical)\n\n";
  md += "Case file `" + case_file + "` (a pair file): " + std::to_string(c.gears.teeth1) + "/" +
        std::to_string(c.gears.teeth2) + " teeth, m_n " + number(c.gears.module_m * 1e3, 6) +
        " mm, beta " + number(c.gears.helix_angle_rad * 180.0 / pi, 6) + " deg (" +
        (hand_sign(c.gears.helix_hand) > 0 ? "right" : "left") + "-hand pinion), b " +
        number(c.gears.face_width_m * 1e3, 6) + " mm, x " + number(c.gears.profile_shift1, 4) +
        "/" + number(c.gears.profile_shift2, 4) + ", alpha_n " +
        number(c.gears.pressure_angle_rad * 180.0 / pi, 6) + " deg.\n\n";
  md +=
      "## Warnings\n\n- The axial force F_a and the tilting moments are reported, not "
      "modelled: the helical dynamics (simulate, modes, sweeps) are not built yet.\n";
  md += "\n## Geometry\n\n" + geometry_section(c.gears, g, torque, origin, dir);
  md += "\n## Contact lines\n\n" + contact_lines_section(c.gears, g, mesh, face, dir);
  md += "\n## Mesh stiffness and ISO 6336-1\n\n" +
        stiffness_section(c.gears, c.model.stiffness, curve, dir);
  if (faulted) {
    md += "\n## Faults\n\n" + faults_section(c, samples, dir);
  }
  if (modified || faulted) {
    const HelicalSteFiles files =
        write_helical_ste_files(c, torque, samples, dir, true, "ste_summary.json");
    md += "\n## Static transmission error and the load across the face\n\n" +
          ste_section(files, torque, origin, faulted);
  }
  write_file_atomically((dir / "REPORT.md").string(), md);
  folder.commit();
  std::cerr << "report: wrote " << (std::filesystem::path(out) / "REPORT.md").string() << "\n";
}

}  // namespace gearimpact::cli
