// Tooth faults and modifications on the paper's pair (docs/faults.md): the mesh stiffness over a
// pinion revolution with a root crack of growing depth, a partial-width crack, a spall and a
// missing tooth; the stiffness loss against crack depth; and the loaded static transmission error
// with and without a parabolic tip relief near its optimum.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

namespace {

constexpr double kDegree = pi / 180.0;
// Samples per mesh period of each true-period curve: the curves are smooth between the entries
// and exits of pairs, whose angles the extremes and the exact mean take from the pieces' ends.
constexpr std::size_t kSamplesPerMeshPeriod = 50;
// The crack depths of the figure, and of the loss table (q / h_c).
const std::vector<double> kFigureDepths{0.0, 0.25, 0.5, 0.75};
const std::vector<double> kTableDepths{0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0};
constexpr double kCrackAngleRad = 45.0 * kDegree;

GearPair faults_pair() {
  GearPair pair = paper_gear_pair();
  pair.bore_diameter1_m = 20e-3;
  pair.bore_diameter2_m = 60e-3;
  return pair;
}

StiffnessModel faults_model() {
  StiffnessModel model;
  model.kind = StiffnessModelKind::potential_energy;
  return model;
}

ToothFault on_pinion_tooth_0(const ToothState& state) {
  ToothFault fault;
  fault.gear = Gear::one;
  fault.tooth = 0;
  fault.state = state;
  return fault;
}

ToothFault uniform_crack(double depth_m) {
  ToothState state;
  state.kind = ToothKind::root_crack;
  state.crack.depth_m = depth_m;
  state.crack.angle_rad = kCrackAngleRad;
  return on_pinion_tooth_0(state);
}

// One faulted tooth's mesh stiffness over the pinion revolution.
struct Curve {
  std::string column;  // CSV column and key
  std::string title;   // the figure's key
  TruePeriodMeshStiffness tvms;
};

Curve curve_of(const GearPair& pair, const StiffnessModel& model, const ToothFault& fault,
               const std::string& column, const std::string& title) {
  return {column, title, true_period_mesh_stiffness(pair, model, {fault}, kSamplesPerMeshPeriod)};
}

std::string percent(double loss) {
  return number(100.0 * loss, 4) + " %";
}

// The parabolic tip relief of both gears, amount C_a, from the highest point of single tooth
// contact of each (the long relief: the single-pair zone stays unmodified).
Modifications tip_relief(const GearPair& pair, double amount_m) {
  const ContactSegment segment = contact_segment(pair);
  const RackGearPairGeometry g = rack_gear_pair_geometry(pair);
  const double t0 = base_pitch(pair);
  Modifications m;
  m.gear1.tip.amount_m = amount_m;
  m.gear1.tip.shape = ReliefShape::parabolic;
  m.gear1.tip.diameter_m = 2.0 * std::hypot(base_radius(pair, Gear::one), segment.start_m + t0);
  m.gear2.tip.amount_m = amount_m;
  m.gear2.tip.shape = ReliefShape::parabolic;
  m.gear2.tip.diameter_m = 2.0 * std::hypot(base_radius(pair, Gear::two),
                                            g.line_of_action_length_m - (segment.end_m - t0));
  return m;
}

}  // namespace

ReportSection reproduce_faults(const ReproduceContext& context) {
  const GearPair pair = faults_pair();
  const StiffnessModel model = faults_model();
  const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
  const PlacedCrack placed =
      place_crack(uniform_crack(0.0).state.crack, geometry.gear1, model.kind, pair.face_width_m);
  const double h_c = placed.start_half_thickness_m;

  // 1. The mesh stiffness over a pinion revolution.
  std::vector<Curve> curves;
  for (double depth : kFigureDepths) {
    curves.push_back(curve_of(pair, model, uniform_crack(depth * h_c),
                              "crack_q" + number(100.0 * depth, 3),
                              "root crack q/h_c = " + number(depth, 3)));
  }
  ToothState partial;
  partial.kind = ToothKind::root_crack;
  partial.crack.profile = CrackProfile::partial_width;
  partial.crack.depth_m = 0.5 * h_c;
  partial.crack.width_m = 0.5 * pair.face_width_m;
  partial.crack.angle_rad = kCrackAngleRad;
  curves.push_back(curve_of(pair, model, on_pinion_tooth_0(partial), "crack_half_width",
                            "crack q_0/h_c = 0.5 over half the face (Chen and Shao)"));
  ToothState spall;
  spall.kind = ToothKind::spall;
  spall.spall.start_radius_m = 20e-3;
  spall.spall.end_radius_m = 21e-3;
  spall.spall.width_m = 4e-3;
  spall.spall.depth_m = 0.2e-3;
  curves.push_back(curve_of(pair, model, on_pinion_tooth_0(spall), "spall",
                            "spall 0.2 mm deep, 4 mm wide, r 20 to 21 mm"));
  ToothState missing;
  missing.kind = ToothKind::missing;
  curves.push_back(curve_of(pair, model, on_pinion_tooth_0(missing), "missing", "missing tooth"));

  const TruePeriodMeshStiffness& reference = curves.front().tvms;
  std::string csv = "theta1_deg,healthy_n_per_m";
  for (const Curve& c : curves) csv += "," + c.column + "_n_per_m";
  csv += "\n";
  for (std::size_t i = 0; i < reference.samples.size(); ++i) {
    csv += format_data_number(reference.samples[i].theta1_rad / kDegree) + "," +
           format_data_number(reference.samples[i].healthy_ke_n_per_m);
    for (const Curve& c : curves) {
      csv += ',';
      csv += format_data_number(c.tvms.samples[i].ke_n_per_m);
    }
    csv += '\n';
  }
  write_file_atomically((context.out / "faults_tvms.csv").string(), csv);
  const auto column_plot = [](int column, const std::string& title, const std::string& style) {
    return "'faults_tvms.csv' using 1:($" + std::to_string(column) + " * 1e-8) with lines " +
           style + " title '" + title + "'";
  };
  const std::vector<std::string> setup{"set key below", "set xrange [0:360]", "set xtics 30"};
  std::vector<std::string> crack_series{column_plot(2, "healthy", "lw 2 lc rgb 'gray50'")};
  for (std::size_t k = 1; k < kFigureDepths.size(); ++k) {
    crack_series.push_back(column_plot(static_cast<int>(k) + 3, curves[k].title, "lw 1.5"));
  }
  const std::string x_label = "pinion angle {/Symbol q}_1 from the faulted tooth 0 entering, deg";
  render(context.out, {"faults_tvms_cracks",
                       "Root crack at 45 deg in pinion tooth 0: mesh stiffness over a revolution",
                       x_label, "mesh stiffness, 10^8 N/m", setup, crack_series});
  std::vector<std::string> other_series{column_plot(2, "healthy", "lw 2 lc rgb 'gray50'")};
  for (std::size_t k = kFigureDepths.size(); k < curves.size(); ++k) {
    other_series.push_back(column_plot(static_cast<int>(k) + 3, curves[k].title, "lw 1.5"));
  }
  render(context.out,
         {"faults_tvms_others", "One faulted pinion tooth: mesh stiffness over a revolution",
          x_label, "mesh stiffness, 10^8 N/m", setup, other_series});

  // 2. Mean and minimum stiffness loss against crack depth.
  const double healthy_min =
      time_varying_mesh_stiffness(pair, model, kSamplesPerMeshPeriod).min_n_per_m;
  std::string loss_csv = "q_over_hc,depth_m,mean_n_per_m,min_n_per_m,mean_loss,min_loss\n";
  std::string loss_table =
      "| q/h_c | q (mm) | mean (N/m) | min (N/m) | mean loss | min loss |\n"
      "|---|---|---|---|---|---|\n";
  for (double depth : kTableDepths) {
    const TruePeriodMeshStiffness t =
        true_period_mesh_stiffness(pair, model, {uniform_crack(depth * h_c)}, 2);
    const double mean_loss = 1.0 - t.mean_n_per_m / t.healthy_mean_n_per_m;
    const double min_loss = 1.0 - t.min_n_per_m / healthy_min;
    loss_csv += format_data_number(depth) + "," + format_data_number(depth * h_c) + "," +
                format_data_number(t.mean_n_per_m) + "," + format_data_number(t.min_n_per_m) + "," +
                format_data_number(mean_loss) + "," + format_data_number(min_loss) + "\n";
    loss_table += "| " + number(depth, 3) + " | " + number(depth * h_c * 1e3, 4) + " | " +
                  number(t.mean_n_per_m, 6) + " | " + number(t.min_n_per_m, 6) + " | " +
                  percent(mean_loss) + " | " + percent(min_loss) + " |\n";
  }
  write_file_atomically((context.out / "faults_stiffness_loss.csv").string(), loss_csv);
  render(context.out, {"faults_stiffness_loss",
                       "Stiffness loss against crack depth, one cracked pinion tooth (nu = 45 deg)",
                       "crack depth q / h_c",
                       "loss against the healthy pair, %",
                       {"set key top left", "set xrange [0:1]"},
                       {"'faults_stiffness_loss.csv' using 1:($6 * 100) with "
                        "linespoints lw 2 pt 7 title 'minimum over the revolution'",
                        "'faults_stiffness_loss.csv' using 1:($5 * 100) with "
                        "linespoints lw 2 pt 5 title 'mean over the revolution'"}});

  // 3. Loaded STE with and without the tip relief, at Table 1's torque of case 2.
  const double torque_n_m = paper_case(2).torque1.constant_n_m;
  const StiffnessTable table(pair, model);
  const double step_m = 0.02e-6;
  std::string scan_csv = "relief_amount_m,ste_peak_to_peak_m,ste_mean_m\n";
  double best_amount = 0.0;
  double best_pp = INFINITY;
  double unmodified_pp = 0.0;
  StaticTransmissionErrorOptions scan_options;
  scan_options.points_per_mesh_period = 400;
  for (int i = 0; i <= 30; ++i) {
    const double amount = i * step_m;
    const StaticTransmissionError ste =
        static_transmission_error(pair, tip_relief(pair, amount), torque_n_m, table, scan_options);
    scan_csv += format_data_number(amount) + "," + format_data_number(ste.ste_peak_to_peak_m) +
                "," + format_data_number(ste.ste_mean_m) + "\n";
    if (i == 0) unmodified_pp = ste.ste_peak_to_peak_m;
    if (ste.ste_peak_to_peak_m < best_pp) {
      best_pp = ste.ste_peak_to_peak_m;
      best_amount = amount;
    }
  }
  write_file_atomically((context.out / "faults_ste_relief_scan.csv").string(), scan_csv);
  StaticTransmissionErrorOptions plot_options;
  plot_options.points_per_mesh_period = 400;
  plot_options.mesh_periods = 2;
  const Modifications best = tip_relief(pair, best_amount);
  const StaticTransmissionError plain =
      static_transmission_error(pair, Modifications{}, torque_n_m, table, plot_options);
  const StaticTransmissionError relieved =
      static_transmission_error(pair, best, torque_n_m, table, plot_options);
  std::string ste_csv = "theta1_deg,ste_unmodified_m,ste_relieved_m,kte_relieved_m\n";
  for (std::size_t i = 0; i < plain.points.size(); ++i) {
    ste_csv += format_data_number(plain.points[i].theta1_rad / kDegree) + "," +
               format_data_number(plain.points[i].ste_m) + "," +
               format_data_number(relieved.points[i].ste_m) + "," +
               format_data_number(relieved.points[i].kte_m) + "\n";
  }
  write_file_atomically((context.out / "faults_ste.csv").string(), ste_csv);
  render(context.out, {"faults_ste",
                       "Loaded STE at T_1 = " + number(torque_n_m, 4) +
                           " N m: unmodified and with C_a = " + number(best_amount * 1e6, 3) +
                           " {/Symbol m}m parabolic tip relief",
                       "pinion angle {/Symbol q}_1, deg (two mesh periods)",
                       "STE, {/Symbol m}m",
                       {"set key outside right top vertical"},
                       {"'faults_ste.csv' using 1:($2 * 1e6) with lines lw 2 lc rgb 'gray40' title "
                        "'unmodified'",
                        "'faults_ste.csv' using 1:($3 * 1e6) with lines lw 2 title 'tip relief'",
                        "'faults_ste.csv' using 1:($4 * 1e6) with lines dt 2 title 'relief, "
                        "unloaded (KTE)'"}});

  ReportSection section;
  section.title = "Tooth faults and modifications (an extension)";
  std::string text =
      "The paper's pair under the potential-energy model with bores 20/60 mm (as the stiffness "
      "section), one faulted pinion tooth (tooth 0; docs/faults.md). The crack starts at the "
      "model's fillet point (h_c = " +
      number(h_c * 1e3, 5) +
      " mm there) at nu = 45 deg. Mesh stiffness over the pinion revolution (the true period) "
      "from tooth 0 entering, " +
      std::to_string(kSamplesPerMeshPeriod) +
      " samples per mesh period: `faults_tvms_cracks.png` (uniform crack, q/h_c = 0, 0.25, 0.5, "
      "0.75), `faults_tvms_others.png` (a crack of q_0/h_c = 0.5 over half the face by Chen & "
      "Shao's profile, a spall, a missing tooth), data `faults_tvms.csv`.\n\n";
  text += "| fault | min (N/m) | mean (N/m) | mean loss |\n|---|---|---|---|\n";
  text += "| healthy | " + number(healthy_min, 6) + " | " +
          number(reference.healthy_mean_n_per_m, 6) + " | 0 % |\n";
  for (const Curve& c : curves) {
    text += "| " + c.title + " | " + number(c.tvms.min_n_per_m, 6) + " | " +
            number(c.tvms.mean_n_per_m, 6) + " | " +
            percent(1.0 - c.tvms.mean_n_per_m / c.tvms.healthy_mean_n_per_m) + " |\n";
  }
  text +=
      "\nStiffness loss against crack depth (`faults_stiffness_loss.png`, data "
      "`faults_stiffness_loss.csv`): the mean over the revolution (exact, by quadrature on each "
      "smooth piece) against the healthy mean, and the minimum against the healthy minimum (where "
      "the cracked tooth carries alone). One tooth in " +
      std::to_string(pair.teeth1) +
      " is cracked, so the mean moves far less than the minimum.\n\n" + loss_table;
  text +=
      "\nLoaded static transmission error at Table 1's pinion torque of case 2, T_1 = " +
      number(torque_n_m, 5) +
      " N m, with a parabolic tip relief on both gears from the highest point of single-tooth "
      "contact (`faults_ste.png`, data `faults_ste.csv`). The amount C_a was scanned from 0 to " +
      number(30 * step_m * 1e6, 3) + " um in steps of " + number(step_m * 1e6, 3) +
      " um (`faults_ste_relief_scan.csv`); the criterion is the least peak-to-peak STE over the "
      "mesh period: C_a = " +
      number(best_amount * 1e6, 3) + " um gives " + number(best_pp * 1e6, 4) +
      " um peak to peak against " + number(unmodified_pp * 1e6, 4) + " um unmodified.\n";
  text +=
      "\nPublished crack-loss curves (Ren et al., Machines 10:664, 2022; Nguyen et al., Front. "
      "Mech. Eng. 11:1682102, 2025) are not compared here: neither their pairs' parameters nor "
      "their values were at hand when this section was built, so `paper_data/` holds none.\n";
  section.text = text;
  return section;
}

}  // namespace gearimpact::cli
