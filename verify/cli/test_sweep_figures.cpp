// The sweep's figures read at any range: `gearimpact merge` draws them from a sweep folder, here
// one written by the test with figures over a narrow range (amplitudes within 1e-9 m of each
// other, speeds within 1e-6 of each other) and a wide one (six decades), of one line and of two;
// gnuplot renders each to SVG, and the tick labels read from the SVG (the text a reader sees) must
// differ along every axis. The axes name the unit swept in, never "(SI)".
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "run_command.hpp"
#include "scratch.hpp"

using namespace gearimpact::verify;
namespace fs = std::filesystem;

namespace {

std::string number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

void write(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The values of one figure's data: the swept value and each point's figures from `t` in [0, 1]
// along the grid, mapped into [low, high] (linearly, or by decades when `log`).
struct Range {
  double low, high;
  bool log;
  double at(double t) const { return log ? low * std::pow(high / low, t) : low + (high - low) * t; }
};

struct Data {
  Range speed;      // rad/s
  Range amplitude;  // m
  Range s;          // m
  Range factor;
  int lines;
};

// A sweep folder as `gearimpact sweep` writes it: summary.json, sweep.csv and poincare.csv of a
// sweep of initial.w1 given in rpm (and gears.backlash in mm for two lines), regimes NI, SS and
// DS in turn, each direction's amplitude a little apart so that the jumps show.
void write_sweep_folder(const fs::path& dir, const Data& d) {
  fs::create_directories(dir);
  const int points = 5;
  std::string spec =
      "{\"spec\": {\"case\": \"figures\", \"case_key_fnv1a64\": \"0\", \"vary\": "
      "\"initial.w1\", \"from_si\": " +
      number(d.speed.at(0)) + ", \"to_si\": " + number(d.speed.at(1)) +
      ", \"points\": " + std::to_string(points) + ", \"vary2\": \"" +
      (d.lines > 1 ? "gears.backlash" : "") +
      "\", \"from2_si\": " + (d.lines > 1 ? "4e-05" : "null") +
      ", \"to2_si\": " + (d.lines > 1 ? "6e-05" : "null") +
      ", \"lines\": " + std::to_string(d.lines) +
      ", \"directions\": \"up,down\", \"backlash_m\": 5e-05, \"unit\": \"rpm\", "
      "\"unit2\": \"" +
      (d.lines > 1 ? "mm" : "") +
      "\", \"mesh_teeth\": 20, \"iso_resonance_speed_rad_s\": 6341.8, "
      "\"iso_resonance_speed_iso_stiffness_rad_s\": 3199.5, \"iso_contact_ratio\": "
      "1.69, \"iso_line_load_n_m\": 15000.0, \"quasi_static_force_ratio\": 1.3, \"tolerance\": "
      "1e-06, "
      "\"steps_per_contact_period\": 128.0, \"max_periods\": 3000, "
      "\"damping_update\": \"frozen\", \"poincare_period_kind\": \"mesh\", "
      "\"poincare_period_s\": [1e-4, 1e-4], \"poincare_period_mesh_periods\": [1, 1]}, "
      "\"warnings\": []}\n";
  write(dir / "summary.json", spec);
  std::string sweep =
      "line,direction,index,value_si,regime,period,converged,dte_mean_m,dte_amplitude_m,dte_rms_m,"
      "s_min_m,s_max_m,dte_contact_mean_m,dte_contact_min_m,dte_contact_max_m,dynamic_factor,"
      "impacts_drive_per_period,impacts_coast_per_period,w1_mean_rad_s,w2_mean_rad_s,pinion_rpm,"
      "mesh_frequency_hz\n";
  std::string poincare = "line,direction,index,value_si,s_m,ds_m_s\n";
  const char* regimes[] = {"NI", "SS", "DS"};
  for (int line = 0; line < d.lines; ++line) {
    for (const std::string direction : {"up", "down"}) {
      for (int i = 0; i < points; ++i) {
        const double t = static_cast<double>(i) / (points - 1);
        // The down branch a quarter step further along: the two differ, as on either side of a
        // jump.
        const double u = direction == "up" ? t : std::min(1.0, t + 0.25);
        // The swept value on the sweep's own grid (linear, sweep_grid), which merge checks.
        const double w = i + 1 == points ? d.speed.high
                                         : d.speed.low + (d.speed.high - d.speed.low) *
                                                             static_cast<double>(i) / (points - 1);
        const double a = d.amplitude.at(u);
        const double s = d.s.at(u);
        sweep += std::to_string(line) + "," + direction + "," + std::to_string(i) + "," +
                 number(w) + "," + regimes[(i + line) % 3] + ",1,true," + number(s) + "," +
                 number(a) + "," + number(a / 2) + "," + number(s - a) + "," + number(s + a) +
                 ",1e-07,0,2e-07," + number(d.factor.at(u)) + ",0,0," + number(w) + "," +
                 number(w / 4) + "," + number(w * 60 / (2 * M_PI)) + "," +
                 number(20 * w / (2 * M_PI)) + "\n";
        poincare += std::to_string(line) + "," + direction + "," + std::to_string(i) + "," +
                    number(w) + "," + number(s) + ",0\n";
      }
    }
  }
  write(dir / "sweep.csv", sweep);
  write(dir / "poincare.csv", poincare);
}

// A text of a figure: where gnuplot placed it and how it is anchored.
struct Label {
  double x, y;
  std::string anchor;
  std::string text;
};

// Every text of gnuplot's SVG: <g transform="translate(X,Y)" ... text-anchor="A"> then
// <text><tspan ...>TEXT</tspan></text>.
std::vector<Label> labels_of(const std::string& svg) {
  std::vector<Label> labels;
  const std::string open = "<g transform=\"translate(";
  for (std::size_t at = svg.find(open); at != std::string::npos; at = svg.find(open, at + 1)) {
    Label l{};
    if (std::sscanf(svg.c_str() + at + open.size(), "%lf,%lf", &l.x, &l.y) != 2) continue;
    const std::size_t tag_end = svg.find('>', at);
    const std::size_t anchor = svg.find("text-anchor=\"", at);
    if (anchor == std::string::npos || anchor > tag_end) continue;
    l.anchor = svg.substr(anchor + 13, svg.find('"', anchor + 13) - anchor - 13);
    const std::size_t text = svg.find("<text>", tag_end);
    if (text == std::string::npos || text > svg.find("<g ", tag_end)) continue;
    const std::size_t tspan = svg.find('>', svg.find("<tspan", text)) + 1;
    l.text = svg.substr(tspan, svg.find("</tspan>", tspan) - tspan);
    labels.push_back(l);
  }
  return labels;
}

// True when `text` is a number and nothing else (gnuplot may print the minus as U+2212).
bool is_number(const std::string& shown, double& value) {
  std::string text;
  for (std::size_t i = 0; i < shown.size(); ++i) {
    if (shown.compare(i, 3, "\xe2\x88\x92") == 0) {
      text += '-';
      i += 2;
    } else {
      text += shown[i];
    }
  }
  while (!text.empty() && text.front() == ' ') text.erase(0, 1);
  if (text.empty()) return false;
  std::size_t used = 0;
  try {
    value = std::stod(text, &used);
  } catch (...) {
    return false;
  }
  return used == text.size();
}

// The tick labels of each axis: numbers right-aligned at one x (the y axis), left-aligned at one
// x (y2), centred at one y (x at the bottom, x2 at the top).
std::map<std::string, std::vector<std::string>> axes_of(const std::vector<Label>& labels) {
  std::map<std::string, std::vector<std::string>> axes;
  for (const Label& l : labels) {
    double value = 0;
    if (!is_number(l.text, value)) continue;
    const bool vertical = l.anchor == "end" || l.anchor == "start";
    axes[l.anchor + "@" + std::to_string(std::lround(vertical ? l.x : l.y))].push_back(l.text);
  }
  return axes;
}

void check_figure(const fs::path& svg_file, std::size_t least_axes) {
  CAPTURE(svg_file.string());
  REQUIRE(fs::exists(svg_file));
  const std::string svg = read(svg_file);
  const auto axes = axes_of(labels_of(svg));
  std::size_t with_ticks = 0;
  for (const auto& [axis, texts] : axes) {
    CAPTURE(axis);
    std::string shown;
    for (const std::string& t : texts) shown += "[" + t + "] ";
    CAPTURE(shown);
    if (texts.size() >= 2) ++with_ticks;
    // Distinct labels along the axis.
    CHECK(std::set<std::string>(texts.begin(), texts.end()).size() == texts.size());
  }
  CHECK(with_ticks >= least_axes);
  CHECK(svg.find("(SI)") == std::string::npos);
}

}  // namespace

TEST_CASE("every sweep figure has distinct tick labels at a narrow and a wide range") {
  const Data narrow{{1000.0, 1000.001, false},
                    {1e-6, 1e-6 + 8e-10, false},
                    {5e-5, 5e-5 + 8e-10, false},
                    {1.5, 1.5 + 4e-9, false},
                    1};
  const Data wide{
      {10.0, 1e5, true}, {1e-9, 1e-3, true}, {-1e-4, 1e-3, false}, {1.0, 50.0, true}, 1};
  for (const Data& base : {narrow, wide}) {
    for (const int lines : {1, 2}) {
      Data d = base;
      d.lines = lines;
      CAPTURE(lines);
      CAPTURE(d.amplitude.high - d.amplitude.low);
      const Scratch scratch("sweep-figures");
      write_sweep_folder(scratch.dir / "shard", d);
      const CommandResult r =
          run_command(std::string(GEARIMPACT_CLI) + " merge " + (scratch.dir / "shard").string() +
                      " --out " + (scratch.dir / "merged").string());
      CAPTURE(r.err);
      REQUIRE(r.exit_code == 0);
      const fs::path out = scratch.dir / "merged";
      // x, y and the mesh frequency on top for a speed sweep; ISO's N on both x axes.
      check_figure(out / "amplitude.svg", 3);
      check_figure(out / "bifurcation.svg", 3);
      check_figure(out / "dynamic_factor_vs_iso_n.svg", 3);
      if (lines > 1) check_figure(out / "regime-map.svg", 3);
      // The speed in the unit swept in, the lengths in um.
      const std::string amplitude = read(out / "amplitude.svg");
      CHECK(amplitude.find("(rpm)") != std::string::npos);
      CHECK(read(out / "amplitude.gp").find("($9 * 1e6)") != std::string::npos);
    }
  }
}

TEST_CASE("plain numbers are drawn in the unit the case file gives the swept key, else in SI") {
  const Scratch scratch("sweep-figures-unit");
  const std::string sweep_case = std::string(GEARIMPACT_PAPER_DATA_DIR) +
                                 "/../verify/slurm/sharded-sweep.toml";  // w1 = "3000 rad/s"
  std::string text = read(sweep_case);
  const std::string rad_s = "w1 = \"3000 rad/s\"";
  REQUIRE(text.find(rad_s) != std::string::npos);
  write(scratch.dir / "rpm.toml",
        text.replace(text.find(rad_s), rad_s.size(), "w1 = \"1000 rpm\""));
  for (const auto& [file, unit] : {std::pair<std::string, std::string>{sweep_case, "(rad/s)"},
                                   {(scratch.dir / "rpm.toml").string(), "(rpm)"}}) {
    CAPTURE(file);
    const fs::path out = scratch.dir / ("out-" + unit.substr(1, 3));
    const CommandResult r = run_command(
        std::string(GEARIMPACT_CLI) + " sweep " + file +
        " --vary initial.w1 --from 300 --to 400 --points 2 --direction up --out " + out.string());
    CAPTURE(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(read(out / "amplitude.gp").find("set xlabel 'pinion speed w_1 " + unit + "'") !=
          std::string::npos);
  }
}

TEST_CASE("the dynamic factor's figure shows ISO's K_v whole over the N it spans") {
  // w1 from 3000 to 9000 rad/s with w_E1 = 6341.8 rad/s: N from 0.47 to 1.42, across ISO's main
  // resonance, where K_v = 1 + C_v4 = 1.9 (eps_alpha 1.69); the simulated factors stay within
  // 1.0 to 1.2. The y range must reach the band's highest point inside the x range.
  const Data d{
      {3000.0, 9000.0, false}, {1e-6, 2e-6, false}, {5e-5, 6e-5, false}, {1.0, 1.2, false}, 1};
  const Scratch scratch("sweep-figures-kv");
  write_sweep_folder(scratch.dir / "shard", d);
  const CommandResult r =
      run_command(std::string(GEARIMPACT_CLI) + " merge " + (scratch.dir / "shard").string() +
                  " --out " + (scratch.dir / "merged").string());
  REQUIRE_MESSAGE(r.exit_code == 0, r.err);
  const std::string gp = read(scratch.dir / "merged" / "dynamic_factor_vs_iso_n.gp");
  const auto range = [&gp](const std::string& axis) {
    // The last setting is the one drawn ("set yrange [0:*]" comes first).
    const std::string key = "set " + axis + "range [";
    const std::size_t at = gp.rfind(key);
    REQUIRE(at != std::string::npos);
    double low = 0.0;
    double high = 0.0;
    REQUIRE(std::sscanf(gp.c_str() + at + key.size(), "%lf:%lf", &low, &high) == 2);
    return std::pair<double, double>{low, high};
  };
  const auto [x_low, x_high] = range("x");
  const auto [y_low, y_high] = range("y");
  std::istringstream band(read(scratch.dir / "merged" / "iso_kv_band.csv"));
  std::string line;
  std::getline(band, line);
  double highest = 0.0;
  while (std::getline(band, line)) {
    double n = 0.0;
    double kv = 0.0;
    REQUIRE(std::sscanf(line.c_str(), "%lf,%lf", &n, &kv) == 2);
    if (n >= x_low && n <= x_high) highest = std::max(highest, kv);
  }
  CAPTURE(x_low);
  CAPTURE(x_high);
  CHECK(highest == doctest::Approx(1.9).scale(0).epsilon(1e-12));
  CHECK(y_low == 0.0);
  CHECK(y_high >= highest);
}
