// `gearimpact signals IN.csv --column NAME --out DIR`: the spectrum of one
// column of a CSV file the program wrote, and with the shaft's angle its order
// spectrum, time-synchronous average and condition indicators
// (docs/signals.md).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/io/signal_files.hpp"
#include "gearimpact/signals/decimate.hpp"
#include "gearimpact/signals/indicators.hpp"
#include "gearimpact/signals/order_tracking.hpp"
#include "gearimpact/signals/recorder.hpp"
#include "gearimpact/signals/resample.hpp"
#include "gearimpact/signals/spectrum.hpp"
#include "gearimpact/signals/tsa.hpp"
#include "gnuplot.hpp"

namespace gearimpact::cli {
namespace {

struct SignalsOptions {
  std::string input;
  std::string column;
  std::string time_column = "t_s";
  std::string from;
  std::string angle_column;
  // Computed order tracking: the angle estimated from a tacho's edge times
  // (simulate --tacho-out's t_emitted_s) instead of a simulated angle.
  std::string tacho_times;
  std::string pulses_per_revolution = "1";
  std::string sample_rate;
  std::string window = "hann";
  std::string samples_per_revolution = "auto";
  std::string band;
  std::string nb4_half_width = "auto";
  std::string teeth;
  std::string shaft_orders = "1";
  std::string sidebands = "1";
  std::string case_file;
  std::string mark_tooth;
  std::string out;
  bool overwrite = false;
  bool plots = true;
  // The recorder (signals/recorder.hpp).
  std::string accelerometer;  // "F_HZ:ZETA"
  std::string path_modes;
  std::string path_band = "1000:8000";
  std::string path_damping = "0.01:0.05";
  std::string noise_snr;
  bool noise_exact = false;
  std::string seed = "0";
  std::string range;
  std::string bits = "16";
};

// "A:B" as two numbers, naming `flag`.
std::pair<double, double> number_pair(const std::string& text, const std::string& flag,
                                      const std::string& allowed) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw InputError(flag, text, allowed);
  char* end = nullptr;
  const std::string a = text.substr(0, colon);
  const std::string b = text.substr(colon + 1);
  const double x = std::strtod(a.c_str(), &end);
  if (a.empty() || end != a.c_str() + a.size() || !std::isfinite(x)) {
    throw InputError(flag, text, allowed);
  }
  const double y = std::strtod(b.c_str(), &end);
  if (b.empty() || end != b.c_str() + b.size() || !std::isfinite(y)) {
    throw InputError(flag, text, allowed);
  }
  return {x, y};
}

// --mark-tooth "pinion:N" or "wheel:N" with --case-file: where that tooth's
// drive flank carries, in its gear's angle (tooth_passage), to shade on the TSA.
ToothPassage marked_passage(const SignalsOptions& o) {
  const std::string allowed =
      "\"pinion:N\" or \"wheel:N\", N a tooth number from 0 (mesh order, as [[faults]] tooth)";
  const auto colon = o.mark_tooth.find(':');
  const std::string gear_name = o.mark_tooth.substr(0, colon);
  if (colon == std::string::npos || (gear_name != "pinion" && gear_name != "wheel")) {
    throw InputError("--mark-tooth", o.mark_tooth, allowed);
  }
  const std::string digits = o.mark_tooth.substr(colon + 1);
  int tooth = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), tooth);
  if (digits.empty() || error != std::errc{} || end != digits.data() + digits.size()) {
    throw InputError("--mark-tooth", o.mark_tooth, allowed);
  }
  if (o.case_file.empty()) {
    throw InputError("--mark-tooth", o.mark_tooth,
                     "with --case-file, the pair or run file of the record's run");
  }
  if (o.angle_column.empty()) {
    throw InputError("--mark-tooth", o.mark_tooth,
                     "with --angle-column, the marked gear's simulated angle (theta1_rad or "
                     "theta2_rad): the TSA it shades");
  }
  const GearPair pair = read_pair_or_run_file(o.case_file).simulation_case.gears;
  const Gear gear = gear_name == "pinion" ? Gear::one : Gear::two;
  try {
    return tooth_passage(pair, gear, tooth);
  } catch (const InputError& e) {
    throw InputError("--mark-tooth", o.mark_tooth, e.problems().front().allowed);
  }
}

// The library's names of the settings, as the flags that set them.
InputError as_flags(const InputError& e) {
  static const std::vector<std::pair<std::string, std::string>> flags{
      {"sample rate", "--sample-rate"},
      {"output rate", "--sample-rate"},
      {"samples per revolution", "--samples-per-revolution"},
      {"teeth", "--teeth"},
      {"sidebands", "--sidebands"},
      {"nb4 half width", "--nb4-half-width"},
      {"band", "--band"},
      {"shaft orders", "--shaft-orders"}};
  std::vector<Problem> problems;
  for (const Problem& p : e.problems()) {
    std::string field = p.field;
    for (const auto& [name, flag] : flags) {
      if (field == name) field = flag;
    }
    problems.push_back(p.renamed(field, p.value));
  }
  return InputError(problems);
}

template <typename Check>
void naming_flags(Check check) {
  try {
    check();
  } catch (const InputError& e) {
    throw as_flags(e);
  }
}

std::size_t whole_number(const std::string& text, const std::string& flag) {
  std::size_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size()) {
    throw InputError(flag, text, "a whole number (see gearimpact signals --help)");
  }
  return value;
}

double number(const std::string& text, const std::string& flag) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) {
    throw InputError(flag, text, "a number (see gearimpact signals --help)");
  }
  return value;
}

// Four digits: a number a figure's legend states.
std::string four_digits(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

void add(Figure& f, const std::vector<std::string>& commands) {
  f.setup.insert(f.setup.end(), commands.begin(), commands.end());
}

// Dashed verticals at the mesh harmonics h * mesh (h >= 1) up to `highest`,
// each labelled; `unit` follows the multiple ("f_m", "z").
void mark_mesh_harmonics(Figure& f, double mesh, double highest, const std::string& name) {
  for (int h = 1; h * mesh <= highest && h <= 20; ++h) {
    char at[64];
    std::snprintf(at, sizeof at, "%.10g", h * mesh);
    f.setup.push_back(std::string("set arrow from ") + at + ", graph 0 to " + at +
                      ", graph 1 nohead dt 2 lc rgb 'grey40'");
    const std::string label = (h == 1 ? "" : std::to_string(h) + " ") + name;
    f.setup.push_back("set label " + gnuplot_string(label) + " at " + at +
                      ", graph 0.97 center front tc rgb 'grey20'");
  }
}

// Short red ticks at the top at the sidebands h * mesh +- j * shaft (j = 1..
// sidebands) of each marked harmonic, where a fault's once-per-revolution
// modulation puts its energy; a key entry says what they are.
void mark_sidebands(Figure& f, double mesh, double shaft, std::size_t sidebands, double highest,
                    const std::string& label) {
  for (int h = 1; h * mesh <= highest && h <= 20; ++h) {
    for (std::size_t j = 1; j <= sidebands; ++j) {
      for (const double sign : {-1.0, 1.0}) {
        const double at = h * mesh + sign * static_cast<double>(j) * shaft;
        if (at <= 0.0 || at > highest) continue;
        char x[64];
        std::snprintf(x, sizeof x, "%.10g", at);
        f.setup.push_back(std::string("set arrow from ") + x + ", graph 0.86 to " + x +
                          ", graph 0.93 nohead lw 1.5 lc rgb '#c0392b'");
      }
    }
  }
  // Below the plot: the harmonics' labels along the top stay free.
  f.setup.emplace_back("set key below horizontal samplen 2");
  f.series.push_back("NaN with lines lw 1.5 lc rgb '#c0392b' title " + gnuplot_string(label));
}

// A column's physical quantity and unit from its name's unit suffix (the program's columns
// carry one: sensor_acceleration_m_per_s2, w2_dot_rad_s2, drive_force_N, dte_m); the bare name
// when it has none. `quantity` false gives the unit alone ("" without one).
struct Physical {
  std::string quantity;
  std::string unit;
};
Physical physical(const std::string& column) {
  static const std::vector<std::pair<std::string, Physical>> suffixes{
      {"_m_per_s2", {"acceleration", "m/s^2"}},
      {"_m_s2", {"acceleration", "m/s^2"}},
      {"_rad_per_s2", {"angular acceleration", "rad/s^2"}},
      {"_rad_s2", {"angular acceleration", "rad/s^2"}},
      {"_m_s", {"velocity", "m/s"}},
      {"_rad_s", {"angular speed", "rad/s"}},
      {"_rad", {"angle", "rad"}},
      {"_N", {"force", "N"}},
      {"_m", {"displacement", "m"}},
  };
  for (const auto& [suffix, p] : suffixes) {
    if (column.size() > suffix.size() &&
        column.compare(column.size() - suffix.size(), suffix.size(), suffix) == 0) {
      return p;
    }
  }
  return {column, ""};
}
std::string axis_label(const std::string& column) {
  const Physical p = physical(column);
  return p.unit.empty() ? literal_key(column) : p.quantity + " (" + p.unit + ")";
}

void spectrum_figure(const std::filesystem::path& dir, const std::string& name,
                     const std::string& title, const std::string& x_label, double top, double mesh,
                     const std::string& mesh_name, const std::string& column, double shaft = 0.0,
                     std::size_t sidebands = 0) {
  Figure f;
  f.name = name;
  f.title = title;
  f.x_label = x_label;
  const std::string unit = physical(column).unit;
  f.y_label = "amplitude (" + (unit.empty() ? std::string() : unit + ", ") + "log scale)";
  f.setup = {"set logscale y", "set format y '10^{%L}'", "set key off"};
  add(f, tick_commands("x", nice_ticks(0.0, top)));
  if (mesh > 0.0) mark_mesh_harmonics(f, mesh, top, mesh_name);
  f.series = {gnuplot_string(name + ".csv") +
              " using 1:($2 > 0 ? $2 : NaN) with lines lw 1.2 lc rgb '#1f4e99' notitle"};
  if (mesh > 0.0 && shaft > 0.0 && sidebands > 0) {
    const std::string orders = sidebands == 1 ? "1" : "1.." + std::to_string(sidebands);
    const bool one = sidebands == 1;
    mark_sidebands(
        f, mesh, shaft, sidebands, top,
        "sidebands " + mesh_name + " +- " + orders +
            (name == "order_spectrum" ? (one ? " order" : " orders")
                                      : (one ? " shaft frequency" : " shaft frequencies")));
  }
  render(dir, f);
}

// The record as it was analysed (the uniform grid), at most its last
// kWaveformSamples samples so that the figure stays legible: waveform.csv.
constexpr std::size_t kWaveformSamples = 16384;

std::size_t waveform_start(const std::vector<double>& uniform) {
  return uniform.size() > kWaveformSamples ? uniform.size() - kWaveformSamples : 0;
}

void write_waveform(const std::filesystem::path& dir, const std::string& column,
                    const std::vector<double>& uniform, double start_s, double rate_hz) {
  std::string csv = "t_s," + column + "\n";
  for (std::size_t i = waveform_start(uniform); i < uniform.size(); ++i) {
    csv += format_data_number(start_s + static_cast<double>(i) / rate_hz) + "," +
           format_data_number(uniform[i]) + "\n";
  }
  write_file_atomically((dir / "waveform.csv").string(), csv);
}

// The figure's span: the last kWaveformRevolutions revolutions of a record with a shaft (its
// mesh periods then stand apart instead of filling the plot as a band), else the last
// kWaveformFigureSamples samples; waveform.csv keeps more.
constexpr double kWaveformRevolutions = 2.0;
constexpr std::size_t kWaveformFigureSamples = 2048;

void waveform_figure(const std::filesystem::path& dir, const std::string& column,
                     const std::vector<double>& uniform, double start_s, double rate_hz,
                     double shaft_hz) {
  const std::size_t written = uniform.size() - waveform_start(uniform);
  const std::size_t shown = std::min(
      written, shaft_hz > 0.0
                   ? static_cast<std::size_t>(std::ceil(kWaveformRevolutions * rate_hz / shaft_hz))
                   : kWaveformFigureSamples);
  const double from = start_s + static_cast<double>(uniform.size() - shown) / rate_hz;
  Figure f;
  f.name = "waveform";
  f.title = "Waveform of " + literal_key(column) +
            (shaft_hz > 0.0 && shown < written ? ", last 2 revolutions"
             : shown < uniform.size()          ? ", last " + std::to_string(shown) + " samples"
                                               : std::string());
  f.x_label = "time (s)";
  f.y_label = axis_label(column);
  char range[96];
  std::snprintf(range, sizeof range, "set xrange [%.15g:%.15g]", from,
                start_s + static_cast<double>(uniform.size() - 1) / rate_hz);
  f.setup = {"set key off", range};
  f.series = {"'waveform.csv' using 1:2 with lines lw 1 lc rgb '#1f4e99'"};
  render(dir, f);
}

// The TSA less its mean (which would otherwise set the scale), with the
// difference and residual signals, which have none.
void tsa_figure(const std::filesystem::path& dir, const std::string& column,
                const std::vector<double>& tsa, bool with_parts,
                const std::optional<ToothPassage>& marked, const std::string& marked_name) {
  double mean = 0.0;
  for (double v : tsa) mean += v / static_cast<double>(tsa.size());
  char shift[40];
  std::snprintf(shift, sizeof shift, "%.17g", mean);
  Figure f;
  f.name = "tsa";
  f.title = "TSA of " + literal_key(column) + ", one revolution";
  f.x_label = "shaft angle (deg)";
  f.y_label = axis_label(column);
  // The key below the plot, in one row: the curves keep the figure's width.
  f.setup = {"set key below horizontal samplen 2"};
  add(f, tick_commands("x", Ticks{0.0, 360.0, 45.0, 0}));
  if (marked) {
    // The passage may wrap past 360 deg: its part there is drawn from 0.
    const double from = marked->entry_rad * 180.0 / pi;
    const double span = marked->span_rad * 180.0 / pi;
    for (const double start : {from, from - 360.0}) {
      char rect[160];
      std::snprintf(rect, sizeof rect,
                    "set object rect from %.10g, graph 0 to %.10g, graph 1 fc rgb '#ffd9b3' "
                    "fs solid 1.0 noborder behind",
                    start, start + span);
      f.setup.emplace_back(rect);
    }
    // A key entry, not the title: a long title is cut at the figure's edge.
    f.series.push_back("NaN with boxes fs solid 1.0 lc rgb '#ffd9b3' title '" + marked_name +
                       " in contact'");
  }
  f.series.push_back("'tsa.csv' using ($1*180/pi):($2-(" + std::string(shift) +
                     ")) with lines lw 1.5 lc rgb '#1f4e99' title 'TSA less its mean (" +
                     four_digits(mean) + ")'");
  if (with_parts) {
    f.series.push_back(
        "'tsa.csv' using ($1*180/pi):5 with lines lw 1.2 lc rgb '#c0392b' title 'difference'");
    f.series.push_back(
        "'tsa.csv' using ($1*180/pi):4 with lines lw 1 dt 2 lc rgb '#27ae60' title 'residual'");
  }
  render(dir, f);
}

// The fastest whole revolution's mean speed, Hz: over each revolution of the angle from its
// first multiple of 2 pi, one turn over the time between the crossings (linear between samples).
double fastest_revolution_hz(const std::vector<double>& time, const std::vector<double>& angle) {
  const double turn = 2.0 * pi;
  double next = std::ceil(angle.front() / turn) * turn;
  double last_crossing = std::numeric_limits<double>::quiet_NaN();
  double fastest = 0.0;
  for (std::size_t i = 1; i < angle.size(); ++i) {
    while (angle[i] >= next && angle[i - 1] < next) {
      const double t =
          time[i - 1] + (time[i] - time[i - 1]) * (next - angle[i - 1]) / (angle[i] - angle[i - 1]);
      if (std::isfinite(last_crossing) && t > last_crossing) {
        fastest = std::max(fastest, 1.0 / (t - last_crossing));
      }
      last_crossing = t;
      next += turn;
    }
  }
  if (!(fastest > 0.0)) {
    // Less than one whole revolution: the mean speed (resample_on_angle refuses it later).
    fastest = (angle.back() - angle.front()) / (turn * (time.back() - time.front()));
  }
  return fastest;
}

void run_signals(SignalsOptions o) {
  // Every flag first, before the file is read.
  std::optional<double> rate;
  if (!o.sample_rate.empty()) {
    rate = parse_plain_or_quantity(o.sample_rate, Dimension::frequency, "--sample-rate");
    naming_flags([&] { signals::check_sample_rate(*rate); });
  }
  const signals::Window window = signals::parse_window(o.window, "--window");
  // The record's start, in s or with a unit: what comes before (a run's
  // start ringing its modes) is left out.
  double from = -std::numeric_limits<double>::infinity();
  if (!o.from.empty()) {
    char* end = nullptr;
    const double plain = std::strtod(o.from.c_str(), &end);
    from = end == o.from.c_str() + o.from.size() &&
                   o.from.find_first_not_of("0123456789+-.eE") == std::string::npos
               ? plain
               : parse_quantity(o.from, Dimension::time, "--from");
    if (!(std::isfinite(from) && from >= 0.0)) {
      throw InputError("--from", o.from, "a time >= 0 s (a plain number in s or with a unit)");
    }
  }
  const bool tracked = !o.tacho_times.empty();
  if (tracked && !o.angle_column.empty()) {
    throw InputError(std::vector<Problem>{refused_problem(
        "--tacho-times", o.tacho_times, "contradicts --angle-column: the angle is one or the other",
        "--tacho-times or --angle-column")});
  }
  if (tracked) o.angle_column = "tacho angle";
  const bool has_angle = !o.angle_column.empty();
  if (!has_angle && !o.teeth.empty()) {
    throw InputError(std::vector<Problem>{
        refused_problem("--teeth", o.teeth, "needs --angle-column (the angle of the gear's shaft)",
                        "a tooth count with --angle-column")});
  }
  std::size_t per_revolution = 0;
  std::optional<signals::OrderSets> sets;
  if (has_angle) {
    // auto (0): the indicators' grid, from the record's band.
    if (o.samples_per_revolution != "auto") {
      per_revolution = whole_number(o.samples_per_revolution, "--samples-per-revolution");
      naming_flags([&] { signals::check_samples_per_revolution(per_revolution); });
    }
    if (!o.teeth.empty()) {
      sets = signals::OrderSets{whole_number(o.teeth, "--teeth"),
                                whole_number(o.shaft_orders, "--shaft-orders"),
                                whole_number(o.sidebands, "--sidebands")};
      if (o.nb4_half_width != "auto") {
        sets->nb4_half_width = whole_number(o.nb4_half_width, "--nb4-half-width");
        if (sets->nb4_half_width == 0) {
          throw InputError("--nb4-half-width", o.nb4_half_width,
                           "2 to (teeth - 1) / 2, or auto (the default, (teeth - 1) / 2)");
        }
      }
      // With P auto, the largest grid stands in until the record's band gives P.
      naming_flags([&] {
        signals::check_order_sets(*sets,
                                  per_revolution != 0 ? per_revolution : std::size_t{1} << 24);
      });
    }
  }
  std::optional<double> band_hz;
  if (!o.band.empty()) {
    if (!has_angle) {
      throw InputError(std::vector<Problem>{
          refused_problem("--band", o.band, "needs --angle-column (it bounds the TSA's orders)",
                          "--band HZ with --angle-column")});
    }
    band_hz = number(o.band, "--band");
    if (!(*band_hz > 0.0 && std::isfinite(*band_hz))) {
      throw InputError("--band", o.band, "a finite frequency > 0 Hz");
    }
  }
  // The recorder's settings, checked before the file is read (the frequencies against the
  // record's rate once it is known).
  const auto seed = static_cast<unsigned long long>(whole_number(o.seed, "--seed"));
  std::optional<signals::SecondOrderSection> accelerometer;
  if (!o.accelerometer.empty()) {
    const auto [f, zeta] = number_pair(o.accelerometer, "--accelerometer",
                                       "RESONANCE_HZ:DAMPING_RATIO, e.g. 30000:0.02");
    if (!(f > 0.0 && zeta > 0.0 && zeta < 1.0)) {
      throw InputError("--accelerometer", o.accelerometer,
                       "a resonance > 0 Hz and a damping ratio in (0, 1), e.g. 30000:0.02");
    }
    accelerometer = signals::accelerometer(f, zeta);
  }
  std::vector<signals::SecondOrderSection> path;
  if (!o.path_modes.empty()) {
    const std::size_t modes = whole_number(o.path_modes, "--path-modes");
    const auto band = number_pair(o.path_band, "--path-band", "LOW_HZ:HIGH_HZ, 0 < LOW <= HIGH");
    const auto damping =
        number_pair(o.path_damping, "--path-damping", "LOW:HIGH, 0 < LOW <= HIGH < 1");
    try {
      path = signals::draw_path(seed, static_cast<int>(std::min<std::size_t>(modes, 1000)),
                                band.first, band.second, damping.first, damping.second);
    } catch (const InputError& e) {
      const std::string field = e.problems().front().field;
      const std::string flag = field == "path modes"  ? "--path-modes"
                               : field == "path band" ? "--path-band"
                                                      : "--path-damping";
      throw InputError(flag,
                       field == "path modes"  ? o.path_modes
                       : field == "path band" ? o.path_band
                                              : o.path_damping,
                       e.problems().front().allowed);
    }
  }
  std::optional<double> noise_snr;
  if (!o.noise_snr.empty()) {
    noise_snr = number(o.noise_snr, "--noise-snr");
    if (!std::isfinite(*noise_snr)) {
      throw InputError("--noise-snr", o.noise_snr, "a finite signal-to-noise ratio in dB");
    }
  }
  std::optional<double> adc_range;
  const std::size_t bits = whole_number(o.bits, "--bits");
  if (bits > 32) throw InputError("--bits", o.bits, "an integer in [0, 32] (0: no rounding)");
  if (!o.range.empty()) {
    adc_range = number(o.range, "--range");
    if (!(*adc_range > 0.0 && std::isfinite(*adc_range))) {
      throw InputError("--range", o.range, "a finite full scale > 0, in the column's unit");
    }
  }
  std::optional<ToothPassage> marked;
  if (!o.mark_tooth.empty()) marked = marked_passage(o);
  if (o.mark_tooth.empty() && !o.case_file.empty()) {
    throw InputError("--case-file", o.case_file, "only with --mark-tooth, which reads it");
  }
  require_output_folder(o.out, o.overwrite, {o.input});

  std::vector<std::string> names{o.time_column, o.column};
  std::vector<std::string> flags{"--time-column", "--column"};
  if (has_angle && !tracked) {
    names.push_back(o.angle_column);
    flags.emplace_back("--angle-column");
  }
  std::vector<std::vector<double>> columns = read_csv_columns(o.input, names, flags);
  if (tracked) {
    // The rows between the first and the last edge, where the angle is
    // estimated, and the angle on them (signals::angle_from_pulses).
    const std::size_t ppr = whole_number(o.pulses_per_revolution, "--pulses-per-revolution");
    const std::vector<double> pulses =
        read_csv_columns(o.tacho_times, {"t_emitted_s"}, {"--tacho-times"}).front();
    if (pulses.size() < 3) {
      throw InputError("--tacho-times", o.tacho_times,
                       "a file of at least 3 edge times (column t_emitted_s)");
    }
    std::vector<std::vector<double>> kept(2);
    for (std::size_t i = 0; i < columns[0].size(); ++i) {
      if (columns[0][i] < pulses.front() || columns[0][i] > pulses.back()) continue;
      kept[0].push_back(columns[0][i]);
      kept[1].push_back(columns[1][i]);
    }
    naming_flags([&] {
      kept.push_back(signals::angle_from_pulses(pulses, ppr, kept[0], o.tacho_times.c_str()));
    });
    columns = std::move(kept);
  }
  // The rows from --from on (the time column ascends, as a run writes it).
  const auto first = static_cast<std::ptrdiff_t>(
      std::lower_bound(columns[0].begin(), columns[0].end(), from) - columns[0].begin());
  for (std::vector<double>& column : columns) column.erase(column.begin(), column.begin() + first);
  const std::vector<double>& time = columns[0];
  const std::vector<double>& signal = columns[1];
  if (time.size() < 4) {
    throw InputError(o.input,
                     std::to_string(time.size()) + " rows" +
                         (o.from.empty() ? std::string() : " from --from = " + o.from),
                     "at least 4 rows");
  }
  const double span = time.back() - time.front();
  // The record's own rate, 1 / its median spacing (a run's event rows add a
  // few shorter steps); without --sample-rate the grid is the record's.
  std::vector<double> spacing(time.size() - 1);
  for (std::size_t i = 1; i < time.size(); ++i) spacing[i - 1] = time[i] - time[i - 1];
  const auto widest = std::max_element(spacing.begin(), spacing.end());
  const std::size_t gap_row = static_cast<std::size_t>(widest - spacing.begin());
  const double gap = *widest;
  std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
  const double median = spacing[spacing.size() / 2];
  const double record_rate = 1.0 / median;
  // A gap in the record (rows lost, two records joined) would be bridged by the interpolation
  // as if the signal were smooth there: refused where it is both 100 times the median spacing
  // and 1 % of the record (an adaptive run's free flights are long steps, not gaps).
  if (gap > 100.0 * median && gap > 0.01 * span) {
    char text[160];
    std::snprintf(text, sizeof text, "a gap of %.4g s (%.3g %% of the record) after t = %.10g s",
                  gap, 100.0 * gap / span, time[gap_row]);
    throw InputError(std::vector<Problem>{
        refused_problem("--time-column", o.time_column, text,
                        "a record without gaps: at most 100 times its median spacing (" +
                            four_digits(median) + " s) or 1 % of the record between rows")});
  }
  // A coarser grid would fold what lies above its Nyquist frequency onto the
  // spectrum (a simulated acceleration steps where pairs enter and leave):
  // as a recorder's anti-alias filter does, the record on its own uniform grid
  // is low-passed below that frequency first, and the angle taken on the same
  // grid for the order analysis.
  const bool coarser = rate && *rate < record_rate * (1.0 - 1e-9);
  // The grids' sizes, before any is made: each is held a few times over.
  naming_flags([&] {
    signals::uniform_sample_count(time.front(), time.back(), rate ? *rate : record_rate);
    if (coarser) signals::uniform_sample_count(time.front(), time.back(), record_rate);
  });
  // The accelerometer and the path act on the record at its own rate (each sample held over
  // the interval ending at it, as an interval average is); a record whose spacing is not
  // uniform is taken on its own uniform grid first.
  std::vector<double> recorded = signal;
  std::vector<double> recorded_time = time;
  std::vector<double> uniform_angle;
  std::vector<signals::SecondOrderSection> sections = path;
  if (accelerometer) sections.push_back(*accelerometer);
  if (!sections.empty()) {
    const double most = *std::max_element(spacing.begin(), spacing.end());
    if (most > 1.000001 / record_rate) {
      naming_flags([&] {
        recorded_time = signals::uniform_times(time.front(), time.back(), record_rate);
        recorded = signals::resample_uniform(time, signal, record_rate, o.time_column.c_str(),
                                             o.column.c_str());
        if (has_angle) {
          uniform_angle = signals::resample_uniform(time, columns[2], record_rate,
                                                    o.time_column.c_str(), o.angle_column.c_str());
        }
      });
    }
    recorded = signals::path_then_accelerometer(recorded, record_rate, path, accelerometer,
                                                "--path-band", "--accelerometer");
  }
  const std::vector<double>& record_time = recorded_time;
  const std::vector<double>& record_angle =
      uniform_angle.empty() && has_angle ? columns[2] : uniform_angle;
  std::vector<double> filtered_time;
  std::vector<double> filtered_signal;
  std::vector<double> filtered_angle;
  if (coarser) {
    // The record on its own uniform grid through the anti-alias decimator, which gives the
    // coarser grid's instants half its span inside the record's ends; the angle, smooth, at the
    // same instants by the cubic.
    naming_flags([&] {
      signals::UniformRecord uniform_record;
      uniform_record.start_s = record_time.front();
      uniform_record.rate_hz = record_rate;
      uniform_record.values = signals::resample_uniform(record_time, recorded, record_rate,
                                                        o.time_column.c_str(), o.column.c_str());
      const signals::UniformRecord decimated = signals::anti_alias_resample(uniform_record, *rate);
      filtered_signal = decimated.values;
      filtered_time.resize(filtered_signal.size());
      for (std::size_t n = 0; n < filtered_time.size(); ++n) {
        filtered_time[n] = decimated.start_s + static_cast<double>(n) / *rate;
      }
      if (has_angle) {
        filtered_angle.resize(filtered_time.size());
        for (std::size_t n = 0; n < filtered_time.size(); ++n) {
          filtered_angle[n] =
              signals::interpolate_cubic(record_time, record_angle, filtered_time[n]);
        }
      }
    });
  }
  const std::vector<double>& analysed_time = coarser ? filtered_time : record_time;
  std::vector<double> analysed_signal = coarser ? filtered_signal : recorded;
  // Noise, then the ADC, on the band-limited record.
  std::optional<signals::NoiseResult> noise;
  if (noise_snr) noise = signals::add_noise(analysed_signal, *noise_snr, seed, o.noise_exact);
  std::optional<signals::AdcResult> converted;
  if (adc_range) converted = signals::adc(analysed_signal, *adc_range, static_cast<int>(bits));
  SignalsRun run;
  run.input = o.input;
  run.column = o.column;
  run.time_column = o.time_column;
  run.start_s = time.front();
  run.end_s = time.back();
  run.sample_rate_hz = rate ? *rate : record_rate;
  run.record_rate_hz = record_rate;
  if (coarser) {
    run.anti_alias = signals::kaiser_low_pass(record_rate, signals::kAliasFreeFraction * *rate,
                                              signals::kStopbandFraction * *rate,
                                              signals::kAntiAliasAttenuationDb);
  }
  run.accelerometer = accelerometer;
  run.path = path;
  run.noise_snr_db = noise_snr;
  run.noise_exact = o.noise_exact;
  run.noise = noise;
  run.adc_range = adc_range;
  run.adc_bits = static_cast<int>(bits);
  run.adc = converted;
  run.seed = seed;
  if (converted && converted->clipped > 0) {
    std::cerr << "warning: " << converted->clipped << " samples clipped at --range " << o.range
              << "\n";
  }
  run.window = std::string(signals::to_string(window));
  std::vector<double> uniform;
  naming_flags([&] {
    uniform = signals::resample_uniform(analysed_time, analysed_signal, run.sample_rate_hz,
                                        o.time_column.c_str(), o.column.c_str());
  });
  run.samples = uniform.size();
  const signals::Spectrum spectrum =
      signals::amplitude_spectrum(uniform, run.sample_rate_hz, window);

  AtomicFolder folder(o.out, o.overwrite, {o.input});
  const std::filesystem::path dir = folder.temporary();
  write_file_atomically((dir / "spectrum.csv").string(), spectrum_csv(spectrum, "frequency_hz"));
  write_waveform(dir, o.column, uniform, analysed_time.front(), run.sample_rate_hz);
  signals::Indicators indicators;
  std::vector<double> tsa_values;
  double mesh_hz = 0.0;
  if (has_angle) {
    const std::vector<double>& angle = coarser ? filtered_angle : record_angle;
    run.angle_column = o.angle_column;
    run.sets = sets;
    // The band's highest order: --band, or kBandFraction of the analysed rate when that is not
    // the record's own (below it the library counts the record's samples a revolution), over
    // the fastest whole revolution's speed.
    std::optional<std::size_t> max_order;
    if (band_hz || coarser) {
      const double band = band_hz ? *band_hz : signals::kBandFraction * run.sample_rate_hz;
      max_order =
          static_cast<std::size_t>(std::floor(band / fastest_revolution_hz(analysed_time, angle)));
    }
    signals::OrderAnalysis a;
    naming_flags([&] {
      a = signals::analyse_orders(angle, analysed_signal, per_revolution, window, sets,
                                  o.angle_column.c_str(), o.column.c_str(), max_order);
    });
    run.samples_per_revolution = a.samples_per_revolution;
    run.max_order = a.max_order;
    run.band_hz = band_hz;
    run.indicator_grid = a.indicator_grid;
    if (a.indicator_parts) {
      run.nb4_harmonic = a.indicator_parts->nb4_harmonic;
      run.nb4_half_width = a.indicator_parts->nb4_half_width;
    }
    run.angle_grid = a.grid;
    run.revolutions = a.revolutions;
    // Over the analysed instants: the decimator's record starts and ends inside the input's.
    run.shaft_frequency_hz = (angle.back() - angle.front()) /
                             (2.0 * pi * (analysed_time.back() - analysed_time.front()));
    write_file_atomically((dir / "order_spectrum.csv").string(), spectrum_csv(a.orders, "order"));
    write_file_atomically((dir / "tsa.csv").string(),
                          tsa_csv(a.tsa, a.parts ? &*a.parts : nullptr));
    tsa_values = a.tsa;
    if (sets) {
      indicators = signals::gear_indicators(uniform, *a.indicator_parts, *sets);
      mesh_hz = run.shaft_frequency_hz * static_cast<double>(sets->teeth);
    } else {
      indicators = signals::record_indicators(uniform);
    }
  } else {
    indicators = signals::record_indicators(uniform);
  }
  const std::string json = indicators_json(run, indicators);
  write_file_atomically((dir / "indicators.json").string(), json);
  if (o.plots) {
    // The spectrum up to the band free of aliases when the record was decimated, else up to
    // the Nyquist frequency.
    const double nyquist = run.anti_alias ? run.anti_alias->pass_hz : run.sample_rate_hz / 2.0;
    const std::size_t sidebands = sets ? sets->sidebands : 0;
    waveform_figure(dir, o.column, uniform, analysed_time.front(), run.sample_rate_hz,
                    run.shaft_frequency_hz);
    spectrum_figure(
        dir, "spectrum",
        "Amplitude spectrum of " + literal_key(o.column) + " (" + run.window + " window)",
        "frequency (Hz)", nyquist, mesh_hz, "f_m", o.column, run.shaft_frequency_hz, sidebands);
    if (has_angle) {
      const double half = static_cast<double>(run.angle_grid) / 2.0;
      const double z = sets ? static_cast<double>(sets->teeth) : 0.0;
      spectrum_figure(
          dir, "order_spectrum",
          "Order spectrum of " + literal_key(o.column) + " on " + literal_key(o.angle_column),
          "order (cycles per revolution)", sets ? std::min(half, 3.5 * z) : half, z, "z", o.column,
          1.0, sidebands);
      tsa_figure(dir, o.column, tsa_values, sets.has_value(), marked,
                 o.mark_tooth.substr(0, o.mark_tooth.find(':')) + " tooth " +
                     o.mark_tooth.substr(o.mark_tooth.find(':') + 1));
    }
  }
  folder.commit();
  std::cout << json;
}

}  // namespace

void register_signals_commands(CLI::App& app) {
  auto o = std::make_shared<SignalsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "signals",
      "spectrum of a column of a CSV file (a time series of simulate); with --angle-column its "
      "order spectrum and time-synchronous average, with --teeth the condition indicators: "
      "DIR/spectrum.csv, order_spectrum.csv, tsa.csv, indicators.json and figures "
      "(docs/signals.md)");
  cmd->add_option("IN", o->input, "CSV file with a header line (e.g. of gearimpact simulate)")
      ->required();
  cmd->add_option("--column", o->column, "the signal's column (e.g. s_m, normal_force_N)")
      ->required();
  cmd->add_option("--time-column", o->time_column, "the time column, s (default t_s)");
  cmd->add_option("--from", o->from,
                  "the record's start, s or with a unit (e.g. \"50 ms\"): the rows before it are "
                  "left out, such as a run's start ringing its modes (default: the first row)");
  cmd->add_option("--sample-rate", o->sample_rate,
                  "Hz (a plain number, or \"80 kHz\") of the uniform grid the samples are "
                  "interpolated onto (cubic, fourth "
                  "order); default: the record's own rate, 1 / its median spacing; a lower rate "
                  "decimates the record through an anti-alias filter (a linear-phase Kaiser FIR, "
                  "100 dB from the lower rate's Nyquist frequency, alias-free below 0.4 of it; "
                  "the record then starts and ends half the filter's span inside)");
  cmd->add_option("--window", o->window, "rectangular or hann (default hann)");
  cmd->add_option("--angle-column", o->angle_column,
                  "the shaft's angle, rad, strictly increasing (e.g. theta1_rad): order "
                  "spectrum and TSA over its whole revolutions");
  cmd->add_option("--tacho-times", o->tacho_times,
                  "computed order tracking: a CSV of a tacho's edge times (column t_emitted_s, "
                  "as simulate --tacho-out writes), whose angle (a quadratic through each three "
                  "edges) replaces --angle-column; the record is cut to the edges' span");
  cmd->add_option("--pulses-per-revolution", o->pulses_per_revolution,
                  "the tacho's edges a revolution, with --tacho-times (default 1)");
  cmd->add_option("--samples-per-revolution", o->samples_per_revolution,
                  "angle steps a revolution of tsa.csv, 16 to 16777216, above 2 (teeth + "
                  "sidebands) (default auto: the indicators' grid, the smallest power of two >= 8 "
                  "q_max + 1); the indicators do not depend on it");
  cmd->add_option("--band", o->band,
                  "Hz: the record's band; the TSA keeps the orders up to q_max = floor(BAND / "
                  "the fastest revolution's speed) (default 0.4 of the analysed rate)");
  cmd->add_option("--nb4-half-width", o->nb4_half_width,
                  "NB4's band h* z +- W orders about the strongest mesh harmonic h*, W from 2 to "
                  "(z - 1) / 2 (default auto: (z - 1) / 2; over z +- 1 NB4 is 1.5 whatever the "
                  "fault)");
  cmd->add_option("--teeth", o->teeth,
                  "teeth of the gear on that shaft: regular, residual and difference signals, "
                  "FM0 ... sideband level, mesh harmonics marked");
  cmd->add_option("--shaft-orders", o->shaft_orders,
                  "shaft orders 0..k counted regular (default 1)");
  cmd->add_option("--sidebands", o->sidebands,
                  "sidebands +-1..m of each mesh harmonic counted regular (default 1)");
  cmd->add_option("--case-file", o->case_file,
                  "the pair or run file of the record's run (read for --mark-tooth)");
  cmd->add_option("--mark-tooth", o->mark_tooth,
                  "\"pinion:N\" or \"wheel:N\" with --case-file: shade on tsa.png where that "
                  "tooth's drive flank carries (the angle column must be that gear's simulated "
                  "angle)");
  cmd->add_option("--out", o->out,
                  "output folder: new or empty (else --overwrite), written beside it and renamed "
                  "into place when complete")
      ->required();
  cmd->add_option("--accelerometer", o->accelerometer,
                  "RESONANCE_HZ:DAMPING_RATIO: an accelerometer's resonance, w^2 / (s^2 + 2 zeta w "
                  "s + w^2), on the record at its own rate (below a quarter of it)");
  cmd->add_option("--path-modes", o->path_modes,
                  "a transfer path of this many modes, each g (2 zeta w s + w^2) / (s^2 + 2 zeta w "
                  "s + w^2), drawn from --seed");
  cmd->add_option("--path-band", o->path_band,
                  "LOW_HZ:HIGH_HZ: the path modes' frequencies, log-uniform (default 1000:8000)");
  cmd->add_option("--path-damping", o->path_damping,
                  "LOW:HIGH: the path modes' damping ratios, uniform (default 0.01:0.05)");
  cmd->add_option("--noise-snr", o->noise_snr,
                  "dB: white Gaussian noise of sigma = RMS(x - mean) 10^(-SNR/20) after the "
                  "anti-alias filter, drawn from --seed");
  cmd->add_flag("--noise-exact", o->noise_exact,
                "rescale the noise's draw to the stated SNR exactly (default: its expectation)");
  cmd->add_option("--seed", o->seed, "the recorder's seed (default 0), a whole number");
  cmd->add_option("--range", o->range,
                  "an ADC's full scale in the column's unit: clip at +-RANGE (counted, warned)");
  cmd->add_option(
      "--bits", o->bits,
      "the ADC's resolution with --range: LSB = 2 RANGE / 2^BITS (default 16; 0: none)");
  cmd->add_flag("--overwrite", o->overwrite, "replace a non-empty --out folder whole");
  cmd->add_flag("!--no-plots", o->plots, "skip the gnuplot figures");
  cmd->callback([o] { run_signals(*o); });
}

}  // namespace gearimpact::cli
