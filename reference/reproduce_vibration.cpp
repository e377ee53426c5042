// Vibration of a healthy and a cracked pinion: the test-rig-like pair of examples/rig_17_38.toml
// on elastic bearings (docs/vibration.md), its modes, the pinion bearing's signal with a root
// crack of growing depth in pinion tooth 0 (spectrum, time-synchronous average, condition
// indicators of docs/signals.md), and the pair at low load with a torque ripple, where the
// breathing backlash lets the teeth separate.
#include <algorithm>
#include <cmath>
#include <future>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planar_state.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/modes_files.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/modes/modes.hpp"
#include "gearimpact/signals/indicators.hpp"
#include "gearimpact/signals/resample.hpp"
#include "gearimpact/signals/spectrum.hpp"
#include "gearimpact/signals/tsa.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

namespace {

constexpr double kDegree = pi / 180.0;
// The sampling is locked to the mesh: 32 samples a mesh period (f_s = 32 x 680 = 21760 Hz, the
// mesh's 15th harmonic below the Nyquist frequency), from the integrator's dense output at t =
// n / f_s. Every tooth then meets the samples at the same phase, so that what the interpolation
// onto the angle grid of the TSA errs is the same for each tooth and stays in the mesh
// harmonics, out of the difference signal (at 20 kHz, 29.4 samples a mesh period, the healthy
// pair's difference signal was that error, with FM4 = 8).
constexpr int kSamplesPerMeshPeriod = 32;
// The start (the gears at rest on their bearings, the teeth apart) strikes the teeth and rings
// the bearing modes; their damping ratio is 500 / (2 sqrt(1.9e8 m)), about 0.03 to 0.05, so the
// slowest (1897 Hz) decays as exp(-t / 2.8 ms): after 50 ms it is down by exp(-18).
constexpr double kSettleS = 0.05;  // two revolutions
// 38 pinion revolutions are 17 wheel revolutions, the pair's whole period (17 and 38 have no
// common factor): the signal's wheel-periodic part (the healthy pair's, 2 f_wheel - f_pinion
// = 4.2 Hz, modulates its mesh harmonics) then falls out of the pinion's TSA exactly, and every
// wheel order is a bin of the spectrum.
constexpr int kRevolutions = 38;
// Samples kept before the analysed window for the cubic interpolation onto the angle grid.
constexpr std::size_t kLead = 2;
const std::vector<double> kDepths{0.0, 0.25, 0.5, 0.75};
constexpr double kCrackAngleRad = 45.0 * kDegree;
// The low-load pair: a once-per-revolution ripple of the input torque (a coupling's
// misalignment) of a fixed amplitude, at the rig's load and at a tenth of it.
constexpr double kRippleNm = 3.0;
constexpr double kLowLoadFraction = 0.1;
constexpr int kLowLoadRevolutions = 8;

// The example's pair under the drive and the reading these records were made
// with, so that the section's numbers stay as recorded: constant torques,
// T2 set by hand so that T1 w1 + T2 w2 equals the mean power friction (f =
// 0.04) takes at 40 Hz and 10 N*m (17.592 W; w1 held within 1e-5 over 1 s),
// and D set at each impact, the paper's. The example itself now holds its
// speed with a controller and freezes D (docs/vibration.md, "Drive and load").
SimulationCase rig_case() {
  SimulationCase c = parse_case(rig_17_38_toml(), "examples/rig_17_38.toml");
  c.torque1 = Torque{};
  c.torque1.kind = Torque::Kind::constant;
  c.torque1.constant_n_m = 10.0;
  c.torque2 = Torque{};
  c.torque2.kind = Torque::Kind::constant;
  c.torque2.constant_n_m = -22.196478760533587;
  c.model.damping_update = DampingUpdate::each_impact;
  return c;
}

ToothFault crack_on_pinion_tooth_0(double depth_m) {
  ToothFault fault;
  fault.gear = Gear::one;
  fault.tooth = 0;
  fault.state.kind = ToothKind::root_crack;
  fault.state.crack.depth_m = depth_m;
  fault.state.crack.angle_rad = kCrackAngleRad;
  return fault;
}

// A run's samples after the settling time.
struct Record {
  std::vector<double> t_s;
  std::vector<double> theta1_rad;
  // The accelerometer on the pinion's bearing, across the centre line (y).
  std::vector<double> sensor_m_per_s2;
  std::vector<double> dte_m;  // s_d - B
  std::vector<double> coast_force_n;
  int impacts_drive = 0;
  int impacts_coast = 0;
};

// The accelerometer's anti-alias filter: the run is sampled kOversampling times faster and the
// record low-passed (an ideal filter by the DFT of the whole record) below the final Nyquist
// frequency before every kOversampling-th sample is kept. The centre's acceleration steps where
// a pair enters or leaves and where friction reverses, so it holds content far above f_s / 2;
// sampled directly it folds back, and as friction lets the speed differ from 40 Hz by 1e-4 the
// folded part slips through the samples and beats the mesh harmonics (by a factor of 10 over
// about 10 revolutions; friction off, the speed exact, nothing beats). The filter treats the
// record as periodic: the ends' mismatch rings into the record's first and last revolution.
// The filtered record therefore starts a revolution before the settling time and ends 1.5
// revolutions after the analysed window, and only what lies from the settling time on is
// kept: the ringing stays outside but for its 1/n tail. (Without the lead the first
// revolution's negative peaks fell from -440 to -250 m/s^2 over it, the filter's, not the
// pair's: the unfiltered record's RMS is steady from 25 ms on.)
constexpr std::size_t kOversampling = 4;
constexpr double kFilterLeadS = 0.025;  // a revolution at the rig's 40 Hz

Record run_record(SimulationCase c, double sample_rate_hz, double end_s) {
  c.integrator.end_time_s = end_s;
  c.bearings.sensor_gear = 1;
  c.bearings.sensor_angle_rad = 0.5 * pi;
  Record fine;
  RunControl control;
  control.keep_series = false;
  control.keep_samples = false;
  control.sample_rate_hz = sample_rate_hz * kOversampling;
  // The recorded numbers rest on point samples, low-passed below.
  control.sample = SampleKind::point;
  control.on_planar_sample = [&fine, sample_rate_hz](const PlanarSample& sample) {
    if (sample.t_s < kSettleS - kFilterLeadS - 0.5 / sample_rate_hz) return;
    fine.t_s.push_back(sample.t_s);
    fine.theta1_rad.push_back(sample.state.theta1_rad);
    fine.sensor_m_per_s2.push_back(sample.sensor_acceleration_m_per_s2);
    fine.dte_m.push_back(sample.dte_m);
    fine.coast_force_n.push_back(sample.coast_force_n);
  };
  const SimulationResult result = simulate(c, control);
  const std::size_t n = fine.sensor_m_per_s2.size();
  // Below the final Nyquist frequency: the bins k >= n / (2 kOversampling).
  const double fine_rate = sample_rate_hz * kOversampling;
  const std::vector<double> filtered = signals::low_pass(
      fine.sensor_m_per_s2, fine_rate,
      fine_rate * static_cast<double>(n / (2 * kOversampling)) / static_cast<double>(n));
  // Every kOversampling-th sample from the first at the settling time (half a final sample
  // early, as the samples' times are rounded).
  const auto kept = static_cast<std::size_t>(
      std::lower_bound(fine.t_s.begin(), fine.t_s.end(), kSettleS - 0.5 / sample_rate_hz) -
      fine.t_s.begin());
  Record r;
  for (std::size_t i = kept; i < n; i += kOversampling) {
    r.t_s.push_back(fine.t_s[i]);
    r.theta1_rad.push_back(fine.theta1_rad[i]);
    r.sensor_m_per_s2.push_back(filtered[i]);
    r.dte_m.push_back(fine.dte_m[i]);
    r.coast_force_n.push_back(fine.coast_force_n[i]);
  }
  for (const ImpactRecord& impact : result.impacts) {
    if (impact.start_s < kSettleS) continue;
    (impact.line == Region::n1 ? r.impacts_drive : r.impacts_coast) += 1;
  }
  return r;
}

struct Analysed {
  double depth = 0.0;  // q / h_c
  Record record;
  double t0_s = 0.0;             // the window's start
  std::vector<double> waveform;  // kRevolutions revolutions at the nominal speed
  signals::Spectrum spectrum;
  signals::OrderAnalysis orders;
  signals::Indicators indicators;
};

std::string optional_number(const std::optional<double>& v, int digits) {
  return v ? number(*v, digits) : std::string("-");
}
std::string optional_data(const std::optional<double>& v) {
  return v ? format_data_number(*v) : std::string("nan");
}

}  // namespace

ReportSection reproduce_vibration(const ReproduceContext& context) {
  const SimulationCase rig = rig_case();
  const GearPair& pair = rig.gears;
  const double w1 = rig.initial.w1_rad_per_s;
  const double revolution_s = 2.0 * pi / w1;
  const double f_shaft = 1.0 / revolution_s;
  const double f_mesh = pair.teeth1 * f_shaft;
  const double sample_rate_hz = kSamplesPerMeshPeriod * f_mesh;
  // The TSA at the samples a revolution the record has.
  const auto tsa_samples = static_cast<std::size_t>(kSamplesPerMeshPeriod * pair.teeth1);

  // 1. The modes at the mean mesh stiffness.
  const Modes modes = natural_modes(rig);
  write_file_atomically((context.out / "vibration_modes.csv").string(), modes_csv(modes));
  std::string modes_table =
      "| mode | f (Hz) | mesh | pinion bearing | wheel bearing |\n|---|---|---|---|---|\n";
  for (std::size_t k = 0; k < modes.modes.size(); ++k) {
    const NaturalMode& m = modes.modes[k];
    if (m.rigid) continue;
    // A share below 1e-12 is the eigensolver's rounding of a mode that leaves
    // that spring unstrained (a bearing mode across the line of action).
    const auto share = [&m](SpringPart part) {
      const double value = m.energy_share[static_cast<std::size_t>(part)];
      return (value < 1e-12 ? std::string("0") : number(100.0 * value, 3)) + " %";
    };
    modes_table += "| " + std::to_string(k + 1) + " | " + number(m.frequency_hz, 5) + " | " +
                   share(SpringPart::mesh) + " | " + share(SpringPart::bearing1) + " | " +
                   share(SpringPart::bearing2) + " |\n";
  }

  // 2. Healthy and cracked: the runs side by side on the pool.
  const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
  const double h_c = place_crack(crack_on_pinion_tooth_0(0.0).state.crack, geometry.gear1,
                                 rig.model.stiffness.kind, pair.face_width_m)
                         .start_half_thickness_m;
  const double record_end_s = kSettleS + (kRevolutions + 1.5) * revolution_s;
  std::vector<std::future<Record>> running;
  for (double depth : kDepths) {
    SimulationCase c = rig;
    if (depth > 0.0) c.faults = {crack_on_pinion_tooth_0(depth * h_c)};
    running.push_back(context.pool->run(
        [c, sample_rate_hz, record_end_s] { return run_record(c, sample_rate_hz, record_end_s); }));
  }
  // The low-load pair: T1 = mean + ripple sin(w1 t); the load torque T2 scales with the mean,
  // as the rig's T2 does (it balances T1 and the friction power, which is proportional to the
  // normal force).
  const auto ripple_case = [&rig, w1](double fraction) {
    SimulationCase c = rig;
    const double mean = fraction * rig.torque1.constant_n_m;
    c.torque1 = Torque{};
    c.torque1.kind = Torque::Kind::sinusoidal;
    c.torque1.mean_n_m = mean;
    c.torque1.amplitude_n_m = kRippleNm;
    c.torque1.angular_frequency_rad_per_s = w1;
    c.torque2.constant_n_m = fraction * rig.torque2.constant_n_m;
    return c;
  };
  const double low_end_s = kSettleS + kLowLoadRevolutions * revolution_s;
  std::vector<std::future<Record>> low_running;
  for (double fraction : {1.0, kLowLoadFraction}) {
    const SimulationCase c = ripple_case(fraction);
    low_running.push_back(context.pool->run(
        [c, sample_rate_hz, low_end_s] { return run_record(c, sample_rate_hz, low_end_s); }));
  }

  const signals::OrderSets sets{static_cast<std::size_t>(pair.teeth1), 1, 1};
  const auto waveform_samples =
      static_cast<std::size_t>(std::lround(kRevolutions * sample_rate_hz * revolution_s));
  std::vector<Analysed> analysed;
  for (std::size_t k = 0; k < kDepths.size(); ++k) {
    Analysed a;
    a.depth = kDepths[k];
    a.record = running[k].get();
    // The analysed window starts where the pinion angle first reaches a multiple of 2 pi (within
    // the first revolution after settling) and holds kRevolutions revolutions at the nominal
    // speed: the spectrum's record, and the revolutions the TSA averages (its resampling starts
    // at that multiple of 2 pi); kLead samples before it and a mesh period after it are kept for
    // the TSA's interpolation.
    const double start = 2.0 * pi * std::ceil(a.record.theta1_rad.front() / (2.0 * pi));
    const auto first = static_cast<std::size_t>(
        std::lower_bound(a.record.theta1_rad.begin(), a.record.theta1_rad.end(), start) -
        a.record.theta1_rad.begin());
    const std::size_t from = first - std::min<std::size_t>(first, kLead);
    const auto begin = static_cast<std::ptrdiff_t>(first);
    const auto end = begin + static_cast<std::ptrdiff_t>(waveform_samples);
    // The window's mean (a slow drift of the centre, which an accelerometer does not pass) is
    // removed.
    const double mean = std::accumulate(a.record.sensor_m_per_s2.begin() + begin,
                                        a.record.sensor_m_per_s2.begin() + end, 0.0) /
                        static_cast<double>(waveform_samples);
    for (double& v : a.record.sensor_m_per_s2) v -= mean;
    a.t0_s = a.record.t_s[first];
    a.waveform.assign(a.record.sensor_m_per_s2.begin() + begin,
                      a.record.sensor_m_per_s2.begin() + end);
    a.spectrum = signals::amplitude_spectrum(a.waveform, sample_rate_hz, signals::Window::hann);
    const auto tsa_end = end + kSamplesPerMeshPeriod;
    const std::vector<double> angle(a.record.theta1_rad.begin() + static_cast<std::ptrdiff_t>(from),
                                    a.record.theta1_rad.begin() + tsa_end);
    const std::vector<double> sensor(
        a.record.sensor_m_per_s2.begin() + static_cast<std::ptrdiff_t>(from),
        a.record.sensor_m_per_s2.begin() + tsa_end);
    a.orders = signals::analyse_orders(angle, sensor, tsa_samples, signals::Window::hann, sets,
                                       "theta1", "sensor");
    a.indicators = signals::gear_indicators(a.waveform, *a.orders.parts, sets);
    analysed.push_back(std::move(a));
  }
  const std::vector<std::string> labels{"healthy", "q/h_c = 0.25", "q/h_c = 0.5", "q/h_c = 0.75"};

  // The waveform, the spectrum and the TSA, one column per depth.
  std::string wave_csv = "t_s";
  std::string spectrum_csv = "frequency_hz";
  std::string tsa_csv = "pinion_angle_deg";
  for (const Analysed& a : analysed) {
    const std::string q = "q" + number(100.0 * a.depth, 3);
    wave_csv += ",sensor_" + q + "_m_s2";
    spectrum_csv += ",amplitude_" + q + "_m_s2";
    tsa_csv += ",tsa_" + q + "_m_s2,difference_" + q + "_m_s2";
  }
  wave_csv += "\n";
  spectrum_csv += "\n";
  tsa_csv += "\n";
  for (std::size_t i = 0; i < waveform_samples; ++i) {
    wave_csv += format_data_number(static_cast<double>(i) / sample_rate_hz);
    for (const Analysed& a : analysed) {
      wave_csv += ',';
      wave_csv += format_data_number(a.waveform[i]);
    }
    wave_csv += "\n";
  }
  for (std::size_t i = 0; i < analysed.front().spectrum.frequency.size(); ++i) {
    spectrum_csv += format_data_number(analysed.front().spectrum.frequency[i]);
    for (const Analysed& a : analysed) {
      spectrum_csv += ',';
      spectrum_csv += format_data_number(a.spectrum.amplitude[i]);
    }
    spectrum_csv += "\n";
  }
  for (std::size_t j = 0; j < tsa_samples; ++j) {
    tsa_csv +=
        format_data_number(360.0 * static_cast<double>(j) / static_cast<double>(tsa_samples));
    for (const Analysed& a : analysed) {
      tsa_csv += ',';
      tsa_csv += format_data_number(a.orders.tsa[j]);
      tsa_csv += ',';
      tsa_csv += format_data_number(a.orders.parts->difference[j]);
    }
    tsa_csv += "\n";
  }
  write_file_atomically((context.out / "vibration_waveform.csv").string(), wave_csv);
  write_file_atomically((context.out / "vibration_spectrum.csv").string(), spectrum_csv);
  write_file_atomically((context.out / "vibration_tsa.csv").string(), tsa_csv);

  // The indicators against crack depth, with the mesh order's amplitude read two ways: from
  // the TSA (order 17 of the angle-domain average) and from the time spectrum at f_m (a bin:
  // the record is a whole number of revolutions).
  const auto mesh_bin =
      static_cast<std::size_t>(std::lround(f_mesh / analysed.front().spectrum.resolution));
  std::string ind_csv =
      "q_over_hc,depth_m,rms_m_s2,kurtosis,fm0,fm4,na4,nb4,m6a,m8a,energy_ratio,sideband_level,"
      "tsa_mesh_order_amplitude_m_s2,spectrum_mesh_amplitude_m_s2,impacts\n";
  std::string ind_table =
      "| q/h_c | RMS (m/s^2) | kurtosis | FM0 | FM4 | NA4 | NB4 | M6A | M8A | energy ratio | "
      "sideband level |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Analysed& a : analysed) {
    const signals::Indicators& x = a.indicators;
    ind_csv += format_data_number(a.depth) + "," + format_data_number(a.depth * h_c) + "," +
               format_data_number(x.rms) + "," + optional_data(x.kurtosis) + "," +
               optional_data(x.fm0) + "," + optional_data(x.fm4) + "," + optional_data(x.na4) +
               "," + optional_data(x.nb4) + "," + optional_data(x.m6a) + "," +
               optional_data(x.m8a) + "," + optional_data(x.energy_ratio) + "," +
               optional_data(x.sideband_level) + "," +
               format_data_number(a.orders.parts->order_amplitude[sets.teeth]) + "," +
               format_data_number(a.spectrum.amplitude[mesh_bin]) + "," +
               std::to_string(a.record.impacts_drive + a.record.impacts_coast) + "\n";
    ind_table += "| " + number(a.depth, 3) + " | " + number(x.rms, 4) + " | " +
                 optional_number(x.kurtosis, 4) + " | " + optional_number(x.fm0, 4) + " | " +
                 optional_number(x.fm4, 4) + " | " + optional_number(x.na4, 4) + " | " +
                 optional_number(x.nb4, 4) + " | " + optional_number(x.m6a, 4) + " | " +
                 optional_number(x.m8a, 4) + " | " + optional_number(x.energy_ratio, 4) + " | " +
                 optional_number(x.sideband_level, 4) + " |\n";
  }
  write_file_atomically((context.out / "vibration_indicators.csv").string(), ind_csv);

  // Figures: the waveform over two revolutions, the spectrum to 7.5 f_m (past the largest
  // harmonic, the 6th) with the mesh harmonics and their +-1 shaft-order sidebands marked, the
  // TSA with tooth 0's passage shaded.
  const auto column = [](const std::string& file, int x, int y, const std::string& title,
                         const std::string& style, const std::string& scale = "") {
    return gnuplot_string(file) + " using " + std::to_string(x) + ":($" + std::to_string(y) +
           scale + ") with lines " + style + " title " + gnuplot_string(title);
  };
  render(context.out,
         {"vibration_waveform",
          "Pinion bearing acceleration across the centre line (y), two revolutions after settling",
          "t after the settling time (" + number(1e3 * kSettleS, 3) + " ms), ms",
          "acceleration a_{y1}, m/s^2",
          {"set key below", "set grid", "set xrange [0:" + number(2e3 * revolution_s, 6) + "]"},
          {"'vibration_waveform.csv' using ($1 * 1e3):5 with lines lw 1.2 lc rgb '#d62728' title "
           "'root crack q/h_c = 0.75'",
           "'vibration_waveform.csv' using ($1 * 1e3):2 with lines lw 1 lc rgb 'black' title "
           "'healthy'"}});
  const double spectrum_end_hz = 7.5 * f_mesh;
  std::vector<std::string> spectrum_setup{"set key below", "set grid", "set logscale y",
                                          "set format y '10^{%L}'",
                                          "set xrange [0:" + number(spectrum_end_hz, 6) + "]"};
  for (int h = 1; f_mesh * h < spectrum_end_hz; ++h) {
    const double f = f_mesh * h;
    spectrum_setup.push_back("set arrow from " + number(f, 6) + ", graph 0 to " + number(f, 6) +
                             ", graph 1 nohead dt 2 lc rgb 'gray60'");
    spectrum_setup.push_back("set label '" + std::to_string(h) + " f_m' at " + number(f, 6) +
                             ", graph 0.96 center font ',9'");
    for (int side : {-1, 1}) {
      spectrum_setup.push_back("set label '" + std::string(side < 0 ? "-" : "+") + "' at " +
                               number(f + side * f_shaft, 6) +
                               ", graph 0.9 center font ',9' tc rgb '#1f77b4'");
    }
  }
  render(context.out, {"vibration_spectrum",
                       "Spectrum of the pinion bearing acceleration (Hann, " +
                           std::to_string(kRevolutions) + " revolutions): mesh harmonics f_m = " +
                           number(f_mesh, 4) + " Hz, sidebands +-" + number(f_shaft, 3) + " Hz",
                       "f, Hz",
                       "amplitude, m/s^2",
                       spectrum_setup,
                       {column("vibration_spectrum.csv", 1, 5, "root crack q/h_c = 0.75",
                               "lw 1.2 lc rgb '#d62728'"),
                        column("vibration_spectrum.csv", 1, 2, "healthy", "lw 1 lc rgb 'black'")}});
  // Tooth 0's passage in the pinion angle of the TSA (theta1 mod 2 pi).
  const ToothPassage passage = tooth_passage(pair, Gear::one, 0);
  const double enter_deg = passage.entry_rad / kDegree;
  const double passage_deg = passage.span_rad / kDegree;
  std::vector<std::string> tsa_setup{"set key below", "set grid", "set xrange [0:360]",
                                     "set xtics 30"};
  for (double from : {enter_deg, enter_deg - 360.0}) {
    tsa_setup.push_back("set object rect from " + number(from, 6) + ", graph 0 to " +
                        number(from + passage_deg, 6) +
                        ", graph 1 fc rgb '#ffd9b3' fs solid 1.0 noborder behind");
  }
  // The TSA of the healthy and the deepest crack, and the difference signals of all (the TSA
  // without its shaft orders, mesh harmonics and their sidebands), where the crack shows.
  render(context.out,
         {"vibration_tsa",
          "TSA of the pinion bearing acceleration over " + std::to_string(kRevolutions) +
              " pinion revolutions (shaded: cracked tooth 0 in contact)",
          "pinion angle {/Symbol q}_1 mod 360, deg",
          "TSA, m/s^2",
          tsa_setup,
          {column("vibration_tsa.csv", 1, 8, "root crack q/h_c = 0.75", "lw 1.5 lc rgb '#d62728'"),
           column("vibration_tsa.csv", 1, 2, "healthy", "lw 1 lc rgb 'black'")}});
  std::vector<std::string> difference_series;
  const std::vector<std::string> styles{"lw 1.5 lc rgb 'black'", "lw 1 lc rgb '#2ca02c'",
                                        "lw 1 lc rgb '#1f77b4'", "lw 1.5 lc rgb '#d62728'"};
  for (std::size_t k = analysed.size(); k-- > 0;) {
    difference_series.push_back(
        column("vibration_tsa.csv", 1, static_cast<int>(2 * k + 3), labels[k], styles[k]));
  }
  render(context.out, {"vibration_tsa_difference",
                       "Difference signal of the TSA (shaded: cracked tooth 0 in contact)",
                       "pinion angle {/Symbol q}_1 mod 360, deg", "difference signal, m/s^2",
                       tsa_setup, difference_series});

  // 3. Low load with the ripple.
  const Record full = low_running[0].get();
  const Record low = low_running[1].get();
  std::string low_csv = "revolutions,dte_full_load_m,dte_low_load_m,coast_force_low_load_n\n";
  for (std::size_t i = 0; i < low.t_s.size(); ++i) {
    low_csv += format_data_number((low.t_s[i] - kSettleS) / revolution_s) + "," +
               format_data_number(full.dte_m[i]) + "," + format_data_number(low.dte_m[i]) + "," +
               format_data_number(low.coast_force_n[i]) + "\n";
  }
  write_file_atomically((context.out / "vibration_low_load.csv").string(), low_csv);
  render(context.out,
         {"vibration_low_load",
          "DTE with a " + number(kRippleNm, 3) + " N m once-per-revolution ripple of T_1",
          "pinion revolutions after settling",
          "DTE = s_d - B, {/Symbol m}m (0: drive flanks touch)",
          // The key inside, above the curves (the x label and a key below it met), and the coast
          // line's label below the line, where no curve runs.
          {"set key top right opaque", "set grid",
           "set xrange [0:" + std::to_string(kLowLoadRevolutions) + "]",
           "set arrow from graph 0, first 0 to graph 1, first 0 nohead lc rgb 'black'",
           // Where the coast flanks touch with the centres at rest; the centres' motion moves it
           // (the breathing backlash).
           "set arrow from graph 0, first " + number(-2e6 * pair.backlash_m, 6) +
               " to graph 1, first " + number(-2e6 * pair.backlash_m, 6) +
               " nohead dt 2 lc rgb 'gray40'",
           "set label 'coast flanks touch (centres at rest)' at graph 0.02, first " +
               number(-2e6 * pair.backlash_m - 8.0, 6)},
          {"'vibration_low_load.csv' using 1:($2 * 1e6) with lines lw 1.2 lc rgb 'black' title "
           "'T_1 = " +
               number(rig.torque1.constant_n_m, 3) + " N m mean'",
           "'vibration_low_load.csv' using 1:($3 * 1e6) with lines lw 1.2 lc rgb '#d62728' "
           "title 'T_1 = " +
               number(kLowLoadFraction * rig.torque1.constant_n_m, 3) + " N m mean'"}});

  ReportSection section;
  section.title = "Vibration of a healthy and a cracked pinion (an extension)";
  std::string text =
      "The test-rig-like pair of `examples/rig_17_38.toml` (compiled into the program): 17/38 "
      "teeth, module 3 mm, 15 mm face, x1 = -x2 = 0.1, the potential-energy stiffness model, "
      "the planar model on bearings of 1.9e8 N/m and 500 N s/m each way, friction f = 0.04, "
      "w1 = " +
      number(w1, 5) + " rad/s (" + number(f_shaft, 4) + " Hz, f_m = " + number(f_mesh, 4) +
      " Hz), T1 = " + number(rig.torque1.constant_n_m, 3) +
      " N m and T2 = " + number(rig.torque2.constant_n_m, 6) +
      " N m, which balances T1 and the mean friction power (17.59 W) so that the train holds its "
      "speed (the file says how).\n\nModes at the mean mesh stiffness (`gearimpact modes`; data "
      "`vibration_modes.csv`), with each mode's share of the strain energy:\n\n" +
      modes_table +
      "\nThe acceleration of the pinion's centre across the centre line (y: the accelerometer "
      "on its bearing, [bearings] sensor_gear = 1, sensor_angle = 90 deg), sampled at " +
      number(sample_rate_hz, 5) + " Hz, " + std::to_string(kSamplesPerMeshPeriod) +
      " samples a mesh period (locked to the mesh, so that each tooth meets the samples at the "
      "same phase), from the integrator's dense output (step 1 us), the window's mean removed, "
      "from " +
      number(kSettleS, 3) +
      " s on, after the start's transient has decayed; a root crack at nu = 45 deg in pinion "
      "tooth 0 of depth q/h_c = 0.25, 0.5, 0.75 (h_c = " +
      number(h_c * 1e3, 5) +
      " mm, placed as in the faults section). Waveform `vibration_waveform.png`, spectrum of " +
      std::to_string(kRevolutions) +
      " revolutions with the Hann window `vibration_spectrum.png` (mesh harmonics and the "
      "+-1 shaft-order sidebands marked), TSA on the simulated pinion angle over the same " +
      "revolutions at " + std::to_string(tsa_samples) +
      " samples a revolution `vibration_tsa.png` and its difference signal "
      "`vibration_tsa_difference.png` (tooth 0's passage shaded); data "
      "`vibration_waveform.csv`, `vibration_spectrum.csv`, `vibration_tsa.csv`. Indicators "
      "(docs/signals.md; RMS and kurtosis of the record, the others of the TSA with one "
      "sideband a side; `vibration_indicators.csv`):\n\n" +
      ind_table;
  const Analysed& healthy = analysed.front();
  // Which indicators rise with every step of depth, which do not: the table in words.
  const std::vector<std::pair<std::string, std::optional<double> signals::Indicators::*>> named{
      {"kurtosis", &signals::Indicators::kurtosis},
      {"FM0", &signals::Indicators::fm0},
      {"FM4", &signals::Indicators::fm4},
      {"NA4", &signals::Indicators::na4},
      {"NB4", &signals::Indicators::nb4},
      {"M6A", &signals::Indicators::m6a},
      {"M8A", &signals::Indicators::m8a},
      {"energy ratio", &signals::Indicators::energy_ratio},
      {"sideband level", &signals::Indicators::sideband_level}};
  std::string rising;
  std::string other;
  for (const auto& entry : named) {
    bool up = true;
    for (std::size_t k = 1; k < analysed.size(); ++k) {
      const std::optional<double>& before = analysed[k - 1].indicators.*(entry.second);
      const std::optional<double>& now = analysed[k].indicators.*(entry.second);
      up = up && before && now && *now > *before;
    }
    std::string& list = up ? rising : other;
    list += (list.empty() ? "" : ", ") + entry.first;
  }
  int struck = 0;
  for (const Analysed& a : analysed) struck += a.record.impacts_drive + a.record.impacts_coast;
  text +=
      "\nRising with every step of crack depth: " + (rising.empty() ? "none" : rising) +
      "; not: " + (other.empty() ? "none" : other) + ". " + std::to_string(struck) +
      " impacts after settling in the four runs. The accelerometer's signal passes an anti-alias "
      "filter: sampled " +
      std::to_string(kOversampling) +
      " times faster, low-passed below the final Nyquist frequency by the DFT, decimated; the "
      "centre's acceleration steps where pairs enter and leave and where friction reverses, "
      "and without the filter its content above f_s / 2 folds back and beats the mesh "
      "harmonics as the speed departs from 40 Hz (what folds back from above the 4 times faster "
      "rate remains, about 1 m/s^2 a bin, and makes the weak first harmonic's line in time "
      "unreliable). The largest mesh harmonic of the healthy pair, the 6th (" +
      number(6.0 * f_mesh, 4) + " Hz, between the bearing modes at 3644 and 4473 Hz): " +
      number(healthy.orders.parts->order_amplitude[6 * sets.teeth], 6) + " m/s^2 from the TSA, " +
      number(healthy.spectrum.amplitude[6 * mesh_bin], 6) + " m/s^2 from the Hann spectrum.\n";
  text +=
      "\nLow load (`vibration_low_load.png`, data `vibration_low_load.csv`): the input "
      "torque carries a once-per-revolution ripple of " +
      number(kRippleNm, 3) + " N m, T1 = T_m + " + number(kRippleNm, 3) +
      " sin(w1 t), with T2 scaled with T_m. The dynamics are linear in the load as long as "
      "the teeth stay in contact, so a constant torque alone never separates them at any "
      "load; the ripple is an excitation of fixed size against a load that falls. After " +
      number(kSettleS, 3) + " s, over " + std::to_string(kLowLoadRevolutions) +
      " revolutions: at T_m = " + number(rig.torque1.constant_n_m, 3) + " N m " +
      std::to_string(full.impacts_drive) + " drive-side and " + std::to_string(full.impacts_coast) +
      " coast-side impacts; at T_m = " + number(kLowLoadFraction * rig.torque1.constant_n_m, 3) +
      " N m " + std::to_string(low.impacts_drive) + " drive-side and " +
      std::to_string(low.impacts_coast) +
      " coast-side impacts: the teeth leave the drive flanks, cross the backlash and strike "
      "the coast flanks (the band's lower edge moves with the centres: the breathing "
      "backlash).\n";
  section.text = text;
  return section;
}

}  // namespace gearimpact::cli
