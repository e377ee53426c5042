// Tooth faults and modifications on the paper's pair (docs/faults.md): the mesh stiffness over a
// pinion revolution with a root crack of growing depth, a partial-width crack, a spall and a
// missing tooth; the stiffness loss against crack depth; the loaded static transmission error
// with and without a parabolic tip relief near its optimum; and the dynamic response with a
// cracked and with a missing tooth where the healthy pair runs without impacts.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
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

// The dynamic response (docs/faults.md, "The response with a cracked tooth"): the loaded pair of
// the steady-state section (balanced torques, no friction, the viscous mesh damper at zeta =
// 0.05, no Hertzian damping) on this section's pair and model. The equations are linear in the
// deflection and the load, so the load only scales the response: 10 N is one choice of many. Near
// w1 = 1410 rad/s the healthy pair runs in contact close to the edge where contact is lost; a
// cracked tooth's softer passage tips it over.
constexpr double kDynamicsW1 = 1410.0;
constexpr double kDynamicsForceN = 10.0;
constexpr double kDynamicsRevolutions = 4.0;
// DTE samples per mesh period: enough to draw each mesh period's swing.
constexpr double kDynamicsSamplesPerMeshPeriod = 50.0;

struct Response {
  std::string title;
  std::vector<ToothFault> faults;
  SimulationResult result;
};

// Where pinion tooth 0 is in contact on the drive line, in pinion revolutions within [0, 1):
// pair 0 sits at X = X_p + Rb1 theta1 (MeshLayout), inside the contact segment from X_start to
// X_end.
std::pair<double, double> tooth0_contact_revolutions(const GearPair& pair) {
  const ContactSegment segment = contact_segment(pair);
  const double rb1 = base_radius(pair, Gear::one);
  const double x_p = pitch_point_position(pair);
  const double from = (segment.start_m - x_p) / rb1 / (2.0 * pi);
  const double to = (segment.end_m - x_p) / rb1 / (2.0 * pi);
  const double shift = std::floor(from);
  return {from - shift, to - shift};
}

// The faulted and healthy responses over kDynamicsRevolutions, each continued from the healthy
// pair's state more than a revolution after the static deflection (where the start's transient
// has died out: the healthy run then strikes nothing), written to faults_dynamics.csv (DTE samples)
// and faults_dynamics_impacts.csv (every impact), drawn, and described.
std::string dynamic_response(const ReproduceContext& context, const GearPair& pair,
                             const StiffnessModel& model, const StiffnessTable& table, double h_c,
                             double mean_stiffness_n_per_m) {
  PairLoad load;
  load.static_force_n = kDynamicsForceN;
  load.deflection_stiffness_n_per_m = mean_stiffness_n_per_m;
  SimulationCase healthy = loaded_paper_pair(kDynamicsW1, load);
  healthy.gears = pair;
  healthy.model.stiffness = model;
  const double revolution_s = 2.0 * pi / kDynamicsW1;
  // The warm-up ends half a mesh period before tooth 0 enters, at least a revolution after the
  // start, so that each response meets the fault with a whole passage and the revolution windows
  // below begin at an entry.
  const std::pair<double, double> contact = tooth0_contact_revolutions(pair);
  const double start_revolutions = healthy.initial.theta1_rad / (2.0 * pi);
  const double entry = std::ceil(start_revolutions + 1.0 - contact.first) + contact.first;
  healthy.integrator.end_time_s = (entry - 0.5 / pair.teeth1 - start_revolutions) * revolution_s;
  RunControl quiet;
  quiet.keep_series = false;
  const RunState warm = simulate(healthy, table, quiet).final_state;

  ToothState missing;
  missing.kind = ToothKind::missing;
  std::vector<Response> responses{
      {"healthy", {}, {}},
      {"root crack q/h_c = 0.5", {uniform_crack(0.5 * h_c)}, {}},
      {"root crack q/h_c = 0.75", {uniform_crack(0.75 * h_c)}, {}},
      {"missing tooth", {on_pinion_tooth_0(missing)}, {}},
  };
  RunControl control = quiet;
  control.resume = warm;
  control.sample_rate_hz = kDynamicsSamplesPerMeshPeriod * pair.teeth1 * kDynamicsW1 / (2.0 * pi);
  // The grid from the resumed start on, as recorded (only the deflection is used).
  control.sample = SampleKind::point;
  for (Response& r : responses) {
    SimulationCase c = healthy;
    c.faults = r.faults;
    c.integrator.end_time_s = (kDynamicsRevolutions + 0.5 / pair.teeth1) * revolution_s;
    r.result = simulate(c, table, control);
  }

  // The pinion angle in revolutions from tooth 0's first entry, at the mean speed: theta1(t0) +
  // w1 (t - t0); balanced torques keep the mean speed at w1, and the angle differs from it by the
  // deflection's share, below 1e-5 of a revolution. Revolution k runs from k to k + 1.
  const double t0 = warm.time_s;
  const double theta0 = warm.state.theta1_rad;
  const auto revolutions_at = [&](double t_s) {
    return (theta0 + kDynamicsW1 * (t_s - t0)) / (2.0 * pi) - entry;
  };

  std::string csv = "revolutions_from_tooth0_entry";
  const std::vector<std::string> columns{"healthy", "crack_q50", "crack_q75", "missing"};
  for (const std::string& column : columns) csv += ",dte_" + column + "_m";
  csv += "\n";
  const std::vector<SampleRow>& samples = responses.front().result.samples;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    csv += format_data_number(revolutions_at(samples[i].t_s));
    for (const Response& r : responses) {
      csv += ',';
      csv += format_data_number(r.result.samples[i].dte_m);
    }
    csv += "\n";
  }
  write_file_atomically((context.out / "faults_dynamics.csv").string(), csv);

  std::string impacts_csv =
      "response,revolutions_from_tooth0_entry,revolution,mesh_periods_after_tooth0_entry,"
      "impact_speed_m_s\n";
  std::string table_text =
      "| response | impacts in " + number(kDynamicsRevolutions, 2) +
      " revolutions | per revolution | mesh periods after tooth 0 enters | least DTE (um) |\n"
      "|---|---|---|---|---|\n";
  std::vector<std::vector<int>> per_revolution;
  for (std::size_t k = 0; k < responses.size(); ++k) {
    const std::vector<ImpactRecord> struck = struck_impacts(responses[k].result);
    std::vector<int> counts(static_cast<std::size_t>(kDynamicsRevolutions), 0);
    std::string phases;
    int phases_shown = 0;
    for (const ImpactRecord& impact : struck) {
      const double from_entry = revolutions_at(impact.start_s);
      const double window = std::max(0.0, std::floor(from_entry));
      const double mesh_periods = (from_entry - window) * pair.teeth1;
      impacts_csv += std::to_string(k) + "," + format_data_number(from_entry) + "," +
                     format_data_number(window) + "," + format_data_number(mesh_periods) + "," +
                     format_data_number(impact.impact_speed_m_s) + "\n";
      ++counts[std::min(counts.size() - 1, static_cast<std::size_t>(window))];
      if (window < 1.0 && ++phases_shown <= 4) {
        phases += (phases.empty() ? "" : ", ") + number(mesh_periods, 3);
      } else if (window < 1.0 && phases_shown == 5) {
        phases += ", ...";
      }
    }
    double least = INFINITY;
    for (const SampleRow& row : responses[k].result.samples) least = std::min(least, row.dte_m);
    std::string per;
    for (std::size_t i = 0; i < counts.size(); ++i) {
      per += (i == 0 ? "" : ", ") + std::to_string(counts[i]);
    }
    table_text += "| " + responses[k].title + " | " + std::to_string(struck.size()) + " | " + per +
                  " | " + (phases.empty() ? "-" : phases) + " | " + number(least * 1e6, 3) + " |\n";
    per_revolution.push_back(counts);
  }
  write_file_atomically((context.out / "faults_dynamics_impacts.csv").string(), impacts_csv);

  std::vector<std::string> setup{"set key below", "set grid", "set xtics 0.5",
                                 "set xrange [" + format_data_number(revolutions_at(t0)) + ":" +
                                     format_data_number(kDynamicsRevolutions) + "]"};
  for (double rev = 0.0; rev < kDynamicsRevolutions; rev += 1.0) {
    setup.push_back("set object rect from " + format_data_number(rev) + ", graph 0 to " +
                    format_data_number(rev + contact.second - contact.first) +
                    ", graph 1 fc rgb '#ffd9b3' fs solid 1.0 noborder behind");
  }
  setup.push_back("set arrow from graph 0, first 0 to graph 1, first 0 nohead lc rgb 'black'");
  const auto dte = [](int column, const std::string& title, const std::string& style) {
    return "'faults_dynamics.csv' using 1:($" + std::to_string(column) + " * 1e6) with lines " +
           style + " title " + gnuplot_string(title);
  };
  // Each response's impacts as points on the line DTE = 0.
  const auto impacts = [](int response, const std::string& style) {
    return "'faults_dynamics_impacts.csv' using 2:($1 == " + std::to_string(response) +
           " ? 0 : 1/0) with points pt 7 " + style + " notitle";
  };
  const std::string x_label =
      "pinion revolutions from tooth 0's entry (shaded: tooth 0 in the contact segment; dots: "
      "impacts)";
  const std::string operating = "w1 = " + number(kDynamicsW1, 4) +
                                " rad/s, F = " + number(kDynamicsForceN, 3) + " N, zeta = 0.05";
  render(context.out,
         {"faults_dynamics_crack",
          "DTE with a cracked pinion tooth, " + operating,
          x_label,
          "DTE = s - B, {/Symbol m}m (below 0: contact lost)",
          setup,
          {dte(4, "root crack q/h_c = 0.75", "lw 1.5 lc rgb '#d62728'"),
           dte(3, "root crack q/h_c = 0.5", "lw 1.2 lc rgb '#1f77b4'"),
           dte(2, "healthy", "lw 0.8 lc rgb 'black'"), impacts(2, "ps 1.6 lc rgb '#d62728'"),
           impacts(1, "ps 0.9 lc rgb '#1f77b4'")}});
  render(context.out,
         {"faults_dynamics_missing",
          "DTE with a missing pinion tooth, " + operating,
          x_label,
          "DTE = s - B, {/Symbol m}m (below 0: contact lost)",
          setup,
          {dte(5, "missing tooth", "lw 1.2 lc rgb '#d62728'"),
           dte(2, "healthy", "lw 1.5 lc rgb 'black'"), impacts(3, "ps 0.8 lc rgb '#d62728'")}});

  std::string text =
      "\nDynamic response with one faulted pinion tooth (`faults_dynamics_crack.png`, "
      "`faults_dynamics_missing.png`; DTE samples `faults_dynamics.csv`, " +
      number(kDynamicsSamplesPerMeshPeriod, 3) +
      " per mesh period; every impact `faults_dynamics_impacts.csv`). The loaded pair of the "
      "steady-state section on this section's pair and model: balanced torques T_1 = F Rb1, T_2 "
      "= -F Rb2 with F = " +
      number(kDynamicsForceN, 3) + " N, w1 = " + number(kDynamicsW1, 4) +
      " rad/s, no friction, the viscous mesh damper at zeta = 0.05 and no Hertzian damping. "
      "These equations are linear in the deflection and the load, so another load scales the "
      "DTE and leaves the impacts as they are (`test_faults_dynamics`; docs/faults.md): \"low "
      "load\" is no cause of separation here, the operating point near the edge where contact is "
      "lost is. The healthy pair starts at the static deflection F / k_mean and runs " +
      number(warm.time_s / revolution_s, 3) +
      " pinion revolutions, to half a mesh period before tooth 0 enters, in which the start's "
      "transient dies out; every response below continues from that state for " +
      number(kDynamicsRevolutions, 2) +
      " revolutions, the fault acting from then on. Impacts are counted in revolution windows "
      "from tooth 0's entry into the contact segment; the phases are those of the first "
      "window.\n\n" +
      table_text;
  // Each faulted response in words, from its counts: the same count in every revolution, or not.
  text += "\nThe healthy pair stays in contact (its least DTE is above 0).";
  for (std::size_t k = 1; k < responses.size(); ++k) {
    const std::vector<int>& counts = per_revolution[k];
    const bool steady =
        std::all_of(counts.begin(), counts.end() - 1, [&](int n) { return n == counts.front(); });
    text += " With the " + responses[k].title + ", ";
    if (counts.front() == 0 && steady) {
      text += "no impact.";
    } else if (steady) {
      text += std::to_string(counts.front()) + (counts.front() == 1 ? " impact" : " impacts") +
              " in every revolution, at the same " + (counts.front() == 1 ? "phase" : "phases") +
              " after tooth 0 enters.";
    } else {
      text += "impacts that change from revolution to revolution.";
    }
  }
  text +=
      " A crack's impacts follow the cracked tooth's passage (it carries from its entry to "
      "about " +
      number(contact_ratio(pair), 3) +
      " mesh periods later), as the pair rebounds from the softer mesh, and do not tip the pair "
      "onto impacts every mesh period. The missing tooth's pair lets the gears fly where it would "
      "carry alone, the next pair enters pressed in (the DTE swings by about 0.5 um each way), "
      "and the pair then strikes in every mesh period for the rest of the revolution with a "
      "swing that does not die out. The operating point sits at the edge of separation, chosen "
      "so; a few rad/s away the counts change.\n";
  return text;
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
           style + " title " + gnuplot_string(title);
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
  text += dynamic_response(context, pair, model, table, h_c, reference.healthy_mean_n_per_m);
  section.text = text;
  return section;
}

}  // namespace gearimpact::cli
