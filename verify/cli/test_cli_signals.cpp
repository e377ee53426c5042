// `gearimpact signals` end to end: a CSV of a signal periodic in an unevenly
// advancing angle, whose order spectrum and FM0 are known in closed form, the
// outputs it writes, and every refusal of a flag before any work.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "relative.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

using gearimpact::verify::relative_difference;
using gearimpact::verify::run_command;
using gearimpact::verify::Scratch;
using std::numbers::pi;

namespace {

const std::string kCli = GEARIMPACT_CLI;

// theta(t) = W t + e sin(v t) (advancing: W > e v), sampled every 20 us for
// 1 s: W = 2 pi 5 rad/s gives 5 revolutions of 10000 rows.
// x = 1 + cos(20 theta) + 0.25 cos(40 theta): a 20-tooth gear's mesh
// harmonics and nothing else. f = cos(zu) + 0.25 cos(2zu) has extremes
// 1.25 at zu = 0 and -0.75 at zu = pi, so FM0 = 2 / (1 + 0.25) = 1.6;
// with 640 samples a revolution (a multiple of 2 z = 40) both are samples.
void write_signal(const std::filesystem::path& path) {
  std::ofstream out(path);
  out << "t_s,theta_rad,x\n";
  const double w = 2.0 * pi * 5.0;
  for (int i = 0; i <= 50000; ++i) {
    const double t = 2e-5 * i;
    const double theta = w * t + 0.3 * std::sin(2.0 * pi * 3.0 * t);
    char line[160];
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", t, theta,
                  1.0 + std::cos(20.0 * theta) + 0.25 * std::cos(40.0 * theta));
    out << line;
  }
}

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The amplitude of the row whose order is `order` in order_spectrum.csv.
double amplitude_at(const std::string& csv, double order) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  double best = -1.0;
  double best_distance = 1e300;
  while (std::getline(in, line)) {
    const auto comma = line.find(',');
    const double o = std::stod(line.substr(0, comma));
    if (std::abs(o - order) < best_distance) {
      best_distance = std::abs(o - order);
      best = std::stod(line.substr(comma + 1));
    }
  }
  return best;
}

}  // namespace

TEST_CASE("signals: order spectrum, TSA and FM0 of mesh harmonics in an uneven angle") {
  Scratch scratch("signals");
  const auto csv = scratch.dir / "signal.csv";
  write_signal(csv);
  const auto out = scratch.dir / "out";
  const auto r = run_command(kCli + " signals " + csv.string() +
                             " --column x --angle-column theta_rad --teeth 20"
                             " --samples-per-revolution 640 --no-plots --out " +
                             out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  for (const char* name : {"spectrum.csv", "order_spectrum.csv", "tsa.csv", "indicators.json"}) {
    CHECK(std::filesystem::exists(out / name));
  }
  // The error left is the cubic interpolation's on a grid of about 2000
  // rows a radian: 4 h^4 max|x''''| / 24 with h = 5e-4 rad and
  // max|x''''| = 20^4 + 0.25 40^4 = 8e5, below 1e-7; the amplitudes and
  // FM0 (a ratio of sums of a few such values) to 1e-6 relative.
  const std::string orders = read(out / "order_spectrum.csv");
  CHECK(relative_difference(amplitude_at(orders, 20.0), 1.0) < 1e-6);
  CHECK(relative_difference(amplitude_at(orders, 40.0), 0.25) < 1e-6);
  CHECK(amplitude_at(orders, 7.0) < 1e-6);
  const auto json = nlohmann::json::parse(read(out / "indicators.json"));
  CHECK(json["revolutions"] == 5);
  CHECK(json["samples_per_revolution"] == 640);
  CHECK(relative_difference(json["gear"]["fm0"].get<double>(), 1.6) < 1e-6);
  CHECK(relative_difference(json["shaft_frequency_hz"].get<double>(),
                            (2.0 * pi * 5.0 + 0.3 * std::sin(2.0 * pi * 3.0)) / (2.0 * pi)) <
        1e-12);
  // The TSA file: one revolution of 640 angles, its columns named.
  const std::string tsa = read(out / "tsa.csv");
  CHECK(tsa.rfind("angle_rad,tsa,regular,residual,difference,mesh_band,mesh_band_envelope\n", 0) ==
        0);
  CHECK(std::count(tsa.begin(), tsa.end(), '\n') == 641);
}

// Occurrences of `what` in `text`.
std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST_CASE("signals: the waveform is the record's end, the sidebands are marked where they lie") {
  Scratch scratch("signals-figures");
  const auto csv = scratch.dir / "signal.csv";
  write_signal(csv);
  const auto out = scratch.dir / "out";
  const auto r = run_command(kCli + " signals " + csv.string() +
                             " --column x --angle-column theta_rad --teeth 20 --sidebands 2"
                             " --samples-per-revolution 640 --out " +
                             out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  for (const char* name : {"waveform.csv", "waveform.png", "spectrum.png", "order_spectrum.png"}) {
    CHECK(std::filesystem::exists(out / name));
  }
  // At the record's own rate the grid is the record's times, where the cubic returns each
  // sample itself: the last of the 16384 rows kept is the signal at t = 1 s in closed form.
  // The rate is 1 / the median spacing, 2e-5 s computed as a difference of the times (about
  // 1e-12 relative), so the grid's last time is 1 s within 1e-10 and the value, whose slope is
  // below 2e3 per s, within 1e-8.
  const std::string waveform = read(out / "waveform.csv");
  CHECK(std::count(waveform.begin(), waveform.end(), '\n') == 16384 + 1);
  const std::string last = waveform.substr(waveform.rfind('\n', waveform.size() - 2) + 1);
  const double theta = 2.0 * pi * 5.0 + 0.3 * std::sin(2.0 * pi * 3.0);
  CHECK(relative_difference(std::stod(last.substr(0, last.find(','))), 1.0) < 1e-10);
  CHECK(relative_difference(std::stod(last.substr(last.find(',') + 1)),
                            1.0 + std::cos(20.0 * theta) + 0.25 * std::cos(40.0 * theta)) < 1e-8);
  // Sidebands h f_m +- 1, 2 f_s of each harmonic drawn: the spectrum spans the record's band (to
  // its Nyquist frequency, 25 kHz) and marks its first 20 harmonics (f_m = 100 Hz), the order
  // spectrum 3 up to order 70 (3.5 z), 4 ticks each.
  CHECK(count_of(read(out / "spectrum.gp"), "graph 0.86") == 20 * 4);
  CHECK(count_of(read(out / "order_spectrum.gp"), "graph 0.86") == 3 * 4);
  CHECK(read(out / "order_spectrum.gp").find("set arrow from 38, graph 0.86") != std::string::npos);
  // The waveform's figure spans at most the last two revolutions and what waveform.csv holds:
  // here two revolutions at 5 Hz are 20000 rows at 50 kHz, so the 16384 rows written.
  const std::string figure = read(out / "waveform.gp");
  const auto range = figure.find("set xrange [");
  REQUIRE(range != std::string::npos);
  const double from = std::stod(figure.substr(range + 12));
  CHECK(std::abs((1.0 - from) - (16384 - 1) * 2e-5) < 1e-9);  // from the first row shown
  CHECK(figure.find("last 16384 samples") != std::string::npos);
  // A column without a unit suffix is labelled by its name; the TSA's key goes below the plot
  // and its title stays short enough for the figure's width.
  CHECK(figure.find("set ylabel 'x'") != std::string::npos);
  const std::string tsa = read(out / "tsa.gp");
  CHECK(tsa.find("set key below") != std::string::npos);
  CHECK(tsa.find("set title 'TSA of x, one revolution'") != std::string::npos);
}

TEST_CASE("signals labels a column with a unit suffix by its quantity and unit") {
  Scratch scratch("signals-labels");
  const auto csv = scratch.dir / "signal.csv";
  {
    std::ofstream out(csv);
    out << "t_s,sensor_acceleration_m_per_s2\n";
    for (int i = 0; i < 1000; ++i) out << i * 1e-4 << "," << std::sin(0.05 * i) << "\n";
  }
  const auto out = scratch.dir / "out";
  const auto r = run_command(kCli + " signals " + csv.string() +
                             " --column sensor_acceleration_m_per_s2 --out " + out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(read(out / "waveform.gp").find("set ylabel 'acceleration (m/s^2)'") != std::string::npos);
  CHECK(read(out / "spectrum.gp").find("set ylabel 'amplitude (m/s^2, log scale)'") !=
        std::string::npos);
}

TEST_CASE("signals shades a marked tooth's passage on the TSA, where tooth_passage puts it") {
  Scratch scratch("signals-mark");
  const auto csv = scratch.dir / "signal.csv";
  write_signal(csv);
  const auto out = scratch.dir / "out";
  const std::string case1 = std::string(GEARIMPACT_PAPER_DATA_DIR) + "/case1.toml";
  const auto r = run_command(kCli + " signals " + csv.string() +
                             " --column x --angle-column theta_rad --teeth 20 --case-file " +
                             case1 + " --mark-tooth pinion:7 --out " + out.string());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const gearimpact::ToothPassage p =
      gearimpact::tooth_passage(gearimpact::paper_gear_pair(), gearimpact::Gear::one, 7);
  const std::string script = read(out / "tsa.gp");
  const std::string rect = "set object rect from ";
  const auto at = script.find(rect);
  REQUIRE(at != std::string::npos);
  const double from_deg = std::stod(script.substr(at + rect.size()));
  // Printed with ten digits.
  CHECK(std::abs(from_deg - p.entry_rad * 180.0 / pi) < 1e-7);
  CHECK(script.find("pinion tooth 7 in contact") != std::string::npos);
}

TEST_CASE("signals at a rate below the record's decimates it through the anti-alias filter") {
  // 4258 samples at 8 kHz of sin(2 pi 300 t) + 0.5 sin(2 pi 3300 t), from 0.25 s on (2258
  // samples), kept at 2 kHz (Nyquist 1 kHz): 3300 Hz would fold to |3300 - 2 2000| = 700 Hz. The
  // decimator at the ratio 4 has 259 taps and gives only the instants whose span lies inside the
  // record: from ceil(129 / 4) = 33 outputs in, 500 samples (0.25 s: whole periods of 300 Hz and
  // of the folded 700 Hz, so each falls on a bin of the rectangular window). Its passband ripple
  // and stopband are 1e-5 (100 dB) within Kaiser's 1 dB: the bar is 2e-5 of the tone. Without
  // the filter the 2 kHz grid's samples hold the 3300 Hz tone, which reads 0.5 at 700 Hz.
  Scratch scratch("signals-alias");
  const auto csv = scratch.dir / "tones.csv";
  {
    std::ofstream out(csv);
    out << "t_s,x\n";
    for (int i = 0; i < 4258; ++i) {
      const double t = i / 8000.0;
      char line[96];
      std::snprintf(line, sizeof line, "%.17g,%.17g\n", t,
                    std::sin(2.0 * pi * 300.0 * t) + 0.5 * std::sin(2.0 * pi * 3300.0 * t));
      out << line;
    }
  }
  const auto run = [&](const std::string& flags, const std::string& folder) {
    const auto r =
        run_command(kCli + " signals " + csv.string() + " --column x --window " + "rectangular " +
                    flags + " --no-plots --out " + (scratch.dir / folder).string());
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out);
  };
  const nlohmann::json kept = run("--from '0.25 s' --sample-rate 2000", "kept");
  CHECK(kept["record_start_s"].get<double>() == 0.25);
  // 1 / the spacing 1/8000 as the CSV's 17 digits give it.
  CHECK(relative_difference(kept["record_rate_hz"].get<double>(), 8000.0) < 1e-12);
  CHECK(kept["anti_alias"]["stopband_edge_hz"].get<double>() == 1000.0);
  CHECK(kept["anti_alias"]["taps"].get<int>() == 259);
  CHECK(kept["alias_free_band_hz"].get<double>() == 800.0);
  CHECK(kept["samples"].get<int>() == 500);
  const std::string spectrum = read(scratch.dir / "kept" / "spectrum.csv");
  CHECK(std::abs(amplitude_at(spectrum, 300.0) - 1.0) < 2e-5);
  CHECK(amplitude_at(spectrum, 700.0) < 2e-5);
  // At the record's own rate nothing is filtered and 3300 Hz reads 0.5 (to
  // 1e-9: measured 6e-11, the cubic's error at the record's own instants
  // given to 17 digits), from 2018 / 8000 s: 2240 samples, whole periods of both tones.
  const nlohmann::json own = run("--from '0.25225 s'", "own");
  CHECK(own["anti_alias"].is_null());
  const std::string full = read(scratch.dir / "own" / "spectrum.csv");
  CHECK(std::abs(amplitude_at(full, 3300.0) - 0.5) < 1e-9);
}

TEST_CASE("signals refuses a bad flag before any work, naming it and its range") {
  Scratch scratch("signals-flags");
  const std::string case1 = std::string(GEARIMPACT_PAPER_DATA_DIR) + "/case1.toml";
  const auto csv = scratch.dir / "signal.csv";
  write_signal(csv);
  const std::string head = kCli + " signals " + csv.string() + " ";
  const std::string out = " --out " + (scratch.dir / "out").string();
  const struct {
    std::string flags;
    std::string message;
  } cases[] = {
      {"--column y", "--column = y: no such column in"},
      {"--column x --time-column s", "--time-column = s: no such column in"},
      {"--column x --window hamming",
       "--window = hamming is outside the allowed range: rectangular or hann"},
      {"--column x --sample-rate -5",
       "--sample-rate = -5 is outside the allowed range: a finite value > 0"},
      {"--column x --from '-1 s'", "--from = -1 s is outside the allowed range: a time >= 0 s"},
      {"--column x --from 2", "rows from --from = 2 is outside the allowed range: at least 4"},
      {"--column x --teeth 20", "--teeth = 20: needs --angle-column"},
      {"--column x --angle-column theta_rad --teeth 300 --samples-per-revolution 512",
       "--teeth = 300 is outside the allowed range: 3 to 254"},
      {"--column x --angle-column theta_rad --teeth 20 --nb4-half-width 1",
       "--nb4-half-width = 1 is outside the allowed range: 2 to 9 for 20 teeth"},
      {"--column x --angle-column theta_rad --teeth 20 --nb4-half-width 0",
       "--nb4-half-width = 0 is outside the allowed range: 2 to (teeth - 1) / 2, or auto"},
      {"--column x --band 100", "--band = 100: needs --angle-column"},
      {"--column x --angle-column theta_rad --teeth 20 --band 50",
       "--band = orders up to 10 is outside the allowed range: a band up to at least order 21"},
      {"--column x --angle-column theta_rad --teeth 20 --sidebands 10",
       "--sidebands = 10 is outside the allowed range: 0 to 9"},
      {"--column x --angle-column theta_rad --teeth 20 --shaft-orders 19",
       "--shaft-orders = 19 is outside the allowed range: 0 to 18"},
      {"--column x --angle-column theta_rad --samples-per-revolution 8",
       "--samples-per-revolution = 8 is outside the allowed range: 16 to 16777216"},
      {"--column x --angle-column theta_rad --teeth two",
       "--teeth = two is outside the allowed range: a whole number"},
      {"--column x --angle-column x", "x (sample 2)"},  // not increasing
      {"--column x --angle-column theta_rad --mark-tooth pinion:3",
       "--mark-tooth = pinion:3 is outside the allowed range: with --case-file"},
      {"--column x --angle-column theta_rad --mark-tooth gear:3 --case-file " + case1,
       "--mark-tooth = gear:3 is outside the allowed range: \"pinion:N\" or \"wheel:N\""},
      {"--column x --angle-column theta_rad --mark-tooth pinion:20 --case-file " + case1,
       "--mark-tooth = pinion:20 is outside the allowed range: a tooth number in [0, 19]"},
      {"--column x --mark-tooth wheel:3 --case-file " + case1,
       "--mark-tooth = wheel:3 is outside the allowed range: with --angle-column"},
      {"--column x --case-file " + case1, "--case-file = " + case1},
      {"--column x --accelerometer 30000", "--accelerometer = 30000 is outside the allowed range"},
      {"--column x --accelerometer 30000:1.5",
       "--accelerometer = 30000:1.5 is outside the allowed range: a resonance > 0 Hz and a "
       "damping ratio in (0, 1)"},
      {"--column x --accelerometer 20000:0.05",
       "--accelerometer = 20000 Hz is outside the allowed range: a frequency in (0, 12500) Hz"},
      {"--column x --path-modes 0",
       "--path-modes = 0 is outside the allowed range: an integer in [1, 16]"},
      {"--column x --path-modes 2 --path-band 9000:8000",
       "--path-band = 9000:8000 is outside the allowed range: 0 < low <= high"},
      {"--column x --noise-snr inf", "--noise-snr = inf is outside the allowed range: a finite"},
      {"--column x --range 0", "--range = 0 is outside the allowed range: a finite full scale > 0"},
      {"--column x --range 1 --bits 40",
       "--bits = 40 is outside the allowed range: an integer in [0, 32]"},
      {"--column x --seed -1", "--seed = -1 is outside the allowed range: a whole number"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.flags);
    const auto r = run_command(head + c.flags + out);
    CHECK(r.exit_code == 1);
    CHECK(r.err.find(c.message) != std::string::npos);
    CHECK(r.err.find('\n') == r.err.size() - 1);  // one line
    CHECK_FALSE(std::filesystem::exists(scratch.dir / "out"));
  }
}

TEST_CASE(
    "signals' recorder: the noise's realised SNR, seeded, and the ADC's clip count recorded") {
  Scratch scratch("signals-recorder");
  const auto csv = scratch.dir / "signal.csv";
  write_signal(csv);
  const auto run = [&](const std::string& flags, const std::string& name) {
    const auto out = scratch.dir / name;
    const auto r = run_command(kCli + " signals " + csv.string() + " --column x --no-plots " +
                               flags + " --out " + out.string());
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(read(out / "indicators.json"));
  };
  const auto clean = run("", "clean");
  const auto a = run("--noise-snr 20 --seed 4", "a");
  const auto b = run("--noise-snr 20 --seed 4", "b");
  const auto c = run("--noise-snr 20 --seed 5", "c");
  const auto exact = run("--noise-snr 20 --seed 4 --noise-exact", "exact");
  CHECK(clean["recorder"]["noise_snr_db"].is_null());
  // 50001 samples: the realised SNR scatters by (10 / ln 10) sqrt(2 / N) = 0.027 dB.
  const double deviation = 10.0 / std::log(10.0) * std::sqrt(2.0 / 50001.0);
  CHECK(std::abs(a["recorder"]["realised_snr_db"].get<double>() - 20.0) <= 5.0 * deviation);
  CHECK(a["recorder"]["realised_snr_db"] == b["recorder"]["realised_snr_db"]);
  CHECK(a["record"]["rms"] == b["record"]["rms"]);
  CHECK(a["recorder"]["realised_snr_db"] != c["recorder"]["realised_snr_db"]);
  CHECK(std::abs(exact["recorder"]["realised_snr_db"].get<double>() - 20.0) <= 1e-12);
  CHECK(exact["recorder"]["noise_mode"] == "exact");
  // x = 1 + cos(20 theta) + 0.25 cos(40 theta) reaches 2.25: a range of 2 clips its peaks.
  const auto clipped = run("--range 2 --bits 0", "clipped");
  CHECK(clipped["recorder"]["clipped"].get<long long>() > 0);
  // The record's peak is the range's, to the cubic resampling's overshoot at a clip's corner.
  CHECK(clipped["record"]["peak"].get<double>() <= 2.0 * 1.001);
  CHECK(clean["record"]["peak"].get<double>() > 2.2);
  CHECK(run("--range 3 --bits 0", "unclipped")["recorder"]["clipped"] == 0);
}
