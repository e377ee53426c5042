// `sweep`: the steady state of a case along one parameter (and optionally over a second), in
// both directions, lines in parallel, shardable (batch/steady_sweep.hpp); `merge`: shards into one
// output (io/sweep_files.hpp). This file reads the options, prints the progress and draws the
// figures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "case_flags.hpp"
#include "commands.hpp"
#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/io/sweep_files.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/iso_resonance.hpp"
#include "gearimpact/steady/sweep.hpp"
#include "gnuplot.hpp"
#include "iso_plot.hpp"
#include "program.hpp"
#include "shard_flag.hpp"

namespace gearimpact::cli {

namespace {

struct SweepCommandOptions {
  std::string case_source;
  std::string vary, from, to;
  int points = 0;
  std::string direction = "both";
  std::string vary2, from2, to2;
  int points2 = 1;
  std::string out = "sweep-out";
  std::string shard;
  CLI::Option* shard_flag = nullptr;  // to tell --shard "" from no --shard
  unsigned threads = 0;
  bool plots = true;
  bool overwrite = false;
  double max_points = kMostSweepPoints;
  SteadySettings settings;
  CaseOptions keys;
};

// A value of a numeric key as the user wrote it: with a unit as in case files, or a plain number
// (SI for a quantity), checked against the key's range.
double sweep_value(const std::string& key, const std::string& text, const std::string& flag) {
  const Field& field = sweep_field(key, flag);
  const double value = gearimpact::parse_value(field, text, flag + " (" + key + ")");
  if (const auto warning = plain_speed_warning(field, text, flag + " (" + key + ")")) {
    std::cerr << "gearimpact: warning: " << *warning << '\n';
  }
  return value;
}

bool is_paper_case(const std::string& source) {
  return source == "1" || source == "2" || source == "3";
}

SimulationCase read_case(const std::string& source) {
  if (is_paper_case(source)) return paper_case(std::stoi(source));
  return read_case_file(source);
}

// The unit the user wrote a value in: the symbol of the key's dimension that ends `text` after
// a number ("1000 rpm", "0.05mm"); empty for a plain number or a key without units.
std::string unit_written(const std::string& key, const std::string& text) {
  const Field& field = sweep_field(key, key);
  if (field.kind != FieldKind::quantity) return "";
  std::string t = text;
  while (!t.empty() && t.back() == ' ') t.pop_back();
  std::string best;
  for (const Unit& u : units_of(field.dimension)) {
    const std::string symbol(u.symbol);
    if (symbol.size() <= best.size() || t.size() <= symbol.size() ||
        t.compare(t.size() - symbol.size(), symbol.size(), symbol) != 0) {
      continue;
    }
    const char before = t[t.size() - symbol.size() - 1];
    if (before == ' ' || before == '.' || (before >= '0' && before <= '9')) best = symbol;
  }
  return best;
}

// The spec of the options, on `base` with the case options applied.
SteadySweepSpec sweep_spec(SweepCommandOptions& o, SimulationCase base) {
  o.keys.apply(base);
  SteadySweepSpec spec;
  spec.base = std::move(base);
  spec.vary = o.vary;
  sweep_field(o.vary, "--vary");
  spec.from_si = sweep_value(o.vary, o.from, "--from");
  spec.to_si = sweep_value(o.vary, o.to, "--to");
  spec.unit = unit_written(o.vary, o.from);
  if (spec.unit.empty()) spec.unit = unit_written(o.vary, o.to);
  // Plain numbers: the unit the case file gives the key in, if any.
  if (spec.unit.empty() && !is_paper_case(o.case_source)) {
    spec.unit = unit_written(o.vary, case_file_text(o.case_source, o.vary));
  }
  spec.points = o.points;
  if (!o.vary2.empty()) {
    spec.vary2 = o.vary2;
    sweep_field(o.vary2, "--vary2");
    spec.from2_si = sweep_value(o.vary2, o.from2, "--from2");
    spec.to2_si = sweep_value(o.vary2, o.to2, "--to2");
    spec.unit2 = unit_written(o.vary2, o.from2);
    if (spec.unit2.empty()) spec.unit2 = unit_written(o.vary2, o.to2);
    if (spec.unit2.empty() && !is_paper_case(o.case_source)) {
      spec.unit2 = unit_written(o.vary2, case_file_text(o.case_source, o.vary2));
    }
    spec.points2 = o.points2;
  }
  spec.directions.clear();
  if (o.direction != "down") spec.directions.push_back(SweepDirection::up);
  if (o.direction != "up") spec.directions.push_back(SweepDirection::down);
  const ShardFlag shard =
      parse_shard_flag(o.shard, o.shard_flag != nullptr && o.shard_flag->count() > 0);
  spec.shard = {shard.k, shard.n};
  spec.settings = o.settings;
  spec.threads = o.threads;
  if (!(o.max_points >= 1.0 && o.max_points <= 9e18)) {
    throw InputError("--max-points", shortest_decimal(o.max_points),
                     "a count in [1, 9e18]: the most points of the whole sweep");
  }
  spec.max_points = o.max_points;
  return spec;
}

// run_steady_sweep with its arguments' errors under the flags that set them.
SteadySweep run_naming_flags(const SteadySweepSpec& spec,
                             const std::function<void(const SweepPointResult&)>& on_point) {
  try {
    return run_steady_sweep(spec, on_point);
  } catch (const InputError& e) {
    if (e.field() == "max_points") {
      throw InputError("--points", e.value(), e.allowed() + " (--max-points lifts the bound)");
    }
    for (const char* argument :
         {"vary", "from", "to", "points", "vary2", "from2", "to2", "points2", "shard", "directions",
          "steps_per_contact_period", "max_periods", "tolerance"}) {
      if (e.field() == argument) {
        std::string flag = "--" + e.field();
        std::replace(flag.begin(), flag.end(), '_', '-');
        throw InputError(flag, e.value(), e.allowed());
      }
    }
    throw;
  }
}

// How many different values `xs` holds: gnuplot refuses a plot with no point ("x range is
// invalid"), and a plot of one value says nothing.
std::size_t distinct(std::vector<double> xs) {
  std::sort(xs.begin(), xs.end());
  return static_cast<std::size_t>(std::unique(xs.begin(), xs.end()) - xs.begin());
}

// True when the figure has two values or more to draw; else says on stderr why it is skipped, so
// that a valid run (one point, one shard of a few lines) never fails in its plots.
bool worth_plotting(const char* figure, std::size_t values) {
  if (values >= 2) return true;
  std::cerr << "gearimpact: note: no " << figure
            << " plot: " << (values == 0 ? "nothing" : "a single value") << " to draw\n";
  return false;
}

// How a figure shows a swept key: its label and the SI value of one unit. A quantity in the unit
// the user swept in, else a length in um and any other quantity in its SI unit, named.
struct ShownUnit {
  std::string label;
  double si_per_unit = 1.0;
  std::string symbol;  // empty for a key without units
};

ShownUnit shown_unit(const std::string& key, const std::string& unit) {
  const Field& field = sweep_field(key, key);
  std::string name = literal_key(key);
  if (key == "initial.w1") name = "pinion speed w_1";
  if (key == "initial.w2") name = "gear speed w_2";
  if (field.kind != FieldKind::quantity) return {name, 1.0, ""};
  std::string symbol = unit;
  if (symbol.empty()) {
    symbol = field.dimension == Dimension::length
                 ? "um"
                 : std::string(units_of(field.dimension).front().symbol);
  }
  for (const Unit& u : units_of(field.dimension)) {
    if (u.symbol == symbol) {
      return {name + " (" + symbol + ")", u.factor * std::pow(10.0, u.decimal_exponent), symbol};
    }
  }
  const std::string si(units_of(field.dimension).front().symbol);
  return {name + " (" + si + ")", 1.0, si};
}

constexpr double kMicrometresPerMetre = 1e6;

// The background colour of a regime and its name in the key.
struct RegimeShade {
  Regime regime;
  const char* colour;
};
constexpr RegimeShade kRegimeShades[] = {{Regime::no_impact, "#cfe3f7"},
                                         {Regime::single_sided, "#fde0b6"},
                                         {Regime::double_sided, "#f7c4c4"},
                                         {Regime::no_contact, "#dddddd"}};

const char* shade_of(Regime regime) {
  for (const RegimeShade& s : kRegimeShades) {
    if (s.regime == regime) return s.colour;
  }
  return "#ffffff";
}

// What the shading of a figure of one line shows, after its title.
constexpr const char* kShadingNote =
    "\\nshaded: regime (where up and down differ: up in the lower half, down in the upper)";

// The regimes of line 0 shaded behind a figure, each point's from half-way to its neighbours:
// the whole height where up and down agree, the lower half up and the upper half down where
// they differ (hysteresis). Adds the key's entries of the regimes shown to `f`.
void shade_regimes(Figure& f, const std::vector<SweepPointResult>& rows, double si_per_unit) {
  std::map<int, std::map<SweepDirection, Regime>> at;  // index -> direction -> regime
  std::map<int, double> value;
  for (const SweepPointResult& r : rows) {
    if (r.line != 0) continue;
    value[r.index] = r.value_si / si_per_unit;
    if (r.point.converged) at[r.index][r.direction] = r.point.regime;
  }
  if (value.size() < 2) return;
  std::vector<std::pair<int, double>> points(value.begin(), value.end());
  std::set<Regime> shown;
  int object = 1;
  const auto rect = [&](double x0, double x1, double y0, double y1, Regime regime) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "set object %d rect from %.17g, graph %g to %.17g, graph %g behind fc rgb '%s' "
                  "fs solid 1.0 noborder",
                  object++, x0, y0, x1, y1, shade_of(regime));
    f.setup.emplace_back(text);
    shown.insert(regime);
  };
  // Each point's cell as the regimes of the lower and the upper half; equal neighbours are
  // drawn as one box (boxes side by side show seams).
  struct Cell {
    double x0, x1;
    Regime lower, upper;
  };
  std::vector<Cell> cells;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto found = at.find(points[i].first);
    if (found == at.end()) continue;
    const double x = points[i].second;
    const double x0 = i == 0 ? x : 0.5 * (points[i - 1].second + x);
    const double x1 = i + 1 == points.size() ? x : 0.5 * (x + points[i + 1].second);
    const auto& by_direction = found->second;
    const auto up = by_direction.find(SweepDirection::up);
    const auto down = by_direction.find(SweepDirection::down);
    Cell cell{x0, x1, by_direction.begin()->second, by_direction.begin()->second};
    if (up != by_direction.end() && down != by_direction.end()) {
      cell.lower = up->second;
      cell.upper = down->second;
    }
    if (!cells.empty() && cells.back().x1 == x0 && cells.back().lower == cell.lower &&
        cells.back().upper == cell.upper) {
      cells.back().x1 = x1;
    } else {
      cells.push_back(cell);
    }
  }
  for (const Cell& c : cells) {
    if (c.lower == c.upper) {
      rect(c.x0, c.x1, 0.0, 1.0, c.lower);
    } else {
      rect(c.x0, c.x1, 0.0, 0.5, c.lower);
      rect(c.x0, c.x1, 0.5, 1.0, c.upper);
    }
  }
  for (const RegimeShade& s : kRegimeShades) {
    if (shown.count(s.regime) == 0) continue;
    f.series.push_back("NaN with boxes fs solid 1.0 noborder fc rgb '" + std::string(s.colour) +
                       "' title '" + to_string(s.regime) + "'");
  }
}

// The mesh frequency on the top axis of a speed sweep's figure: z w / (2 pi) in Hz.
void mesh_frequency_axis(Figure& f, const SteadySweepRecord& spec, double si_per_unit,
                         const Ticks& x) {
  if (spec.mesh_teeth <= 0) return;
  const double hz_per_unit = spec.mesh_teeth * si_per_unit / (2.0 * pi);
  const std::string k = format_number(hz_per_unit);
  f.setup.push_back("set link x2 via x*" + k + " inverse x/" + k);
  f.setup.emplace_back("set xtics nomirror");
  for (const std::string& c :
       tick_commands("x2", nice_ticks(x.from * hz_per_unit, x.to * hz_per_unit), false)) {
    f.setup.push_back(c);
  }
  f.setup.push_back(std::string("set x2label \"mesh frequency z_") +
                    (spec.vary == "initial.w1" ? "1 w_1" : "2 w_2") + " / 2{/Symbol p} (Hz)\"");
}

// The extremes of `values`.
std::pair<double, double> extremes(const std::vector<double>& values) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return {*low, *high};
}

void add(Figure& f, const std::vector<std::string>& commands) {
  f.setup.insert(f.setup.end(), commands.begin(), commands.end());
}

// dynamic_factor_vs_iso_n.csv from the rows (the swept value is w1) and its figure.
void render_iso_plot(const std::filesystem::path& dir, const IsoScale& iso,
                     const std::vector<SweepPointResult>& rows) {
  std::string data =
      "line,direction,index,w1_rad_s,iso_resonance_ratio,iso_resonance_ratio_iso_stiffness,"
      "dynamic_factor,dynamic_factor_quasi_static\n";
  double n_max = 0.0;
  std::vector<double> ns, dfs;
  for (const SweepPointResult& r : rows) {
    const double n = iso_resonance_ratio(r.value_si, iso.resonance_speed_rad_per_s);
    n_max = std::max(n_max, n);
    const std::optional<double>& df = r.point.dynamic_factor;
    if (df) {
      ns.push_back(n);
      dfs.push_back(*df);
    }
    data += std::to_string(r.line) + "," + to_string(r.direction) + "," + std::to_string(r.index) +
            "," + format_data_number(r.value_si) + "," + format_data_number(n) + "," +
            format_data_number(
                iso_resonance_ratio(r.value_si, iso.resonance_speed_iso_stiffness_rad_per_s)) +
            "," + (df ? format_data_number(*df) : "") + "," +
            (df ? format_data_number(*df / iso.quasi_static_force_ratio) : "") + "\n";
  }
  write_file_atomically((dir / "dynamic_factor_vs_iso_n.csv").string(), data);
  const double band_end = std::max(2.0, 1.1 * n_max);
  write_iso_kv_band(dir / "iso_kv_band.csv", iso, band_end);
  Figure f = dynamic_factor_vs_iso_n("dynamic_factor_vs_iso_n", iso, "dynamic_factor_vs_iso_n.csv",
                                     2, 5, 7, "iso_kv_band.csv", true);
  // The ticks of the swept range, readable at any width; the dynamic factor from 0 up.
  const auto [n_low, n_high] = extremes(ns);
  const Ticks x = nice_ticks(n_low, n_high);
  add(f, tick_commands("x", x));
  const double to_iso_n =
      iso.resonance_speed_rad_per_s / iso.resonance_speed_iso_stiffness_rad_per_s;
  add(f, tick_commands("x2", nice_ticks(x.from * to_iso_n, x.to * to_iso_n), false));
  // The y range holds the simulated factors and ISO's K_v over the N shown (up to 1 + C_v4 at
  // the main resonance), as the band draws it.
  const double highest = std::max(*std::max_element(dfs.begin(), dfs.end()),
                                  highest_iso_kv(iso, band_end, x.from, x.to));
  Ticks y = nice_ticks(0.0, highest, 8, 0.05);
  y.from = 0.0;
  add(f, tick_commands("y", y));
  render(dir, f);
}

// The title of a line's series: `direction` alone for one line, with the line's value of the
// second key for several.
std::string line_title(const SteadySweepRecord& spec, int line, const char* direction) {
  if (spec.lines < 2) return direction;
  const ShownUnit unit2 = shown_unit(spec.vary2, spec.unit2);
  const double from2 = spec.from2_si.value_or(0.0);
  const double to2 = spec.to2_si.value_or(0.0);
  const double value = line + 1 == spec.lines
                           ? to2
                           : from2 + (to2 - from2) * line / static_cast<double>(spec.lines - 1);
  char number[64];
  std::snprintf(number, sizeof number, "%.6g", value / unit2.si_per_unit);
  return literal_key(spec.vary2) + " = " + number +
         (unit2.symbol.empty() ? "" : " " + unit2.symbol) + ", " + direction;
}

// The plots of a sweep folder: amplitude up and down, the bifurcation diagram, the regime map.
void render_plots(const std::filesystem::path& dir, const SteadySweep& sweep) {
  const SteadySweepRecord& spec = sweep.spec;
  const ShownUnit unit = shown_unit(spec.vary, spec.unit);
  const std::string x_of = "($4 / " + format_number(unit.si_per_unit) + ")";
  std::vector<double> amplitude_x, amplitude_y, poincare_x, poincare_y, iso_x, map_x, map_lines;
  for (const SweepPointResult& r : sweep.rows) {
    const double x = r.value_si / unit.si_per_unit;
    if (r.point.dte_amplitude_m) {
      amplitude_x.push_back(x);
      amplitude_y.push_back(*r.point.dte_amplitude_m * kMicrometresPerMetre);
    }
    for (const PoincareSample& p : r.point.poincare) {
      poincare_x.push_back(x);
      poincare_y.push_back(p.s_m * kMicrometresPerMetre);
    }
    if (r.point.dynamic_factor) iso_x.push_back(r.value_si);
    if (r.direction == SweepDirection::up) {
      map_x.push_back(x);
      map_lines.push_back(r.line);
    }
  }
  const std::vector<SweepJump> jumps = sweep_jumps(sweep.rows);
  const bool one_line = spec.lines < 2;
  const char* styles[2] = {"pt 7 ps 0.7 lw 1.5 lc rgb '#1f4e9c'",
                           "pt 6 ps 1.0 lw 1.5 dt 2 lc rgb '#b2182b'"};
  if (worth_plotting("amplitude", distinct(amplitude_x))) {
    Figure amplitude;
    amplitude.name = "amplitude";
    amplitude.title = "Steady DTE amplitude, swept up and down";
    if (one_line) amplitude.title += kShadingNote;
    amplitude.x_label = unit.label;
    amplitude.y_label = "DTE amplitude, half peak-to-peak of s ({/Symbol m}m)";
    amplitude.setup = {"set key outside right top"};
    const auto [x_low, x_high] = extremes(amplitude_x);
    const auto [y_low, y_high] = extremes(amplitude_y);
    const Ticks x = nice_ticks(x_low, x_high, 8, 0.02);
    add(amplitude, tick_commands("x", x));
    add(amplitude, tick_commands("y", nice_ticks(y_low, y_high, 8, 0.05)));
    mesh_frequency_axis(amplitude, spec, unit.si_per_unit, x);
    for (const SweepJump& j : jumps) {
      char arrow[256];
      std::snprintf(
          arrow, sizeof arrow,
          "set arrow from %.17g, %.17g to %.17g, %.17g head filled lw 2 lc rgb '%s' front",
          j.from_si / unit.si_per_unit, j.amplitude_before_m * kMicrometresPerMetre,
          j.to_si / unit.si_per_unit, j.amplitude_after_m * kMicrometresPerMetre,
          j.direction == SweepDirection::up ? "#1f4e9c" : "#b2182b");
      amplitude.setup.emplace_back(arrow);
    }
    for (int line = 0; line < spec.lines; ++line) {
      for (int d = 0; d < 2; ++d) {
        const char* direction = d == 0 ? "up" : "down";
        amplitude.series.push_back(
            "'sweep.csv' using (($1 == " + std::to_string(line) + " && strcol(2) eq \"" +
            direction + "\") ? " + x_of + " : NaN):($9 * 1e6) with linespoints " +
            (one_line ? std::string(styles[d])
                      : "lc " + std::to_string(line + 1) + (d == 0 ? " pt 7" : " pt 6 dt 2")) +
            " title " + gnuplot_string(line_title(spec, line, direction)));
      }
    }
    if (!jumps.empty()) {
      amplitude.series.push_back("NaN with vectors head filled lw 2 lc rgb 'black' title 'jump'");
    }
    if (one_line) shade_regimes(amplitude, sweep.rows, unit.si_per_unit);
    render(dir, amplitude);
  }
  if (worth_plotting("bifurcation", distinct(poincare_x))) {
    Figure bifurcation;
    bifurcation.name = "bifurcation";
    bifurcation.title = "Bifurcation diagram: s at the excitation phase";
    if (one_line) bifurcation.title += kShadingNote;
    bifurcation.x_label = unit.label;
    bifurcation.y_label = "s at the excitation phase ({/Symbol m}m)";
    bifurcation.setup = {"set key outside right top"};
    const auto [x_low, x_high] = extremes(poincare_x);
    const auto [y_low, y_high] = extremes(poincare_y);
    const Ticks x = nice_ticks(x_low, x_high, 8, 0.02);
    add(bifurcation, tick_commands("x", x));
    add(bifurcation, tick_commands("y", nice_ticks(y_low, y_high, 8, 0.05)));
    mesh_frequency_axis(bifurcation, spec, unit.si_per_unit, x);
    // A jump: a dotted line half-way between the points it falls between.
    for (const SweepJump& j : jumps) {
      if (j.line != 0) continue;
      char arrow[200];
      std::snprintf(arrow, sizeof arrow,
                    "set arrow from %.17g, graph 0 to %.17g, graph 1 nohead dt 3 lw 1.5 lc rgb "
                    "'%s' front",
                    0.5 * (j.from_si + j.to_si) / unit.si_per_unit,
                    0.5 * (j.from_si + j.to_si) / unit.si_per_unit,
                    j.direction == SweepDirection::up ? "#1f4e9c" : "#b2182b");
      bifurcation.setup.emplace_back(arrow);
    }
    bifurcation.series = {
        "'poincare.csv' using (strcol(2) eq \"up\" ? " + x_of +
            " : NaN):($5 * 1e6) with points pt 7 ps 0.5 lc rgb '#1f4e9c' title 'up'",
        "'poincare.csv' using (strcol(2) eq \"down\" ? " + x_of +
            " : NaN):($5 * 1e6) with points pt 6 ps 0.8 lc rgb '#b2182b' title 'down'"};
    if (!jumps.empty()) {
      bifurcation.series.push_back("NaN with lines dt 3 lw 1.5 lc rgb 'black' title 'jump'");
    }
    if (one_line) shade_regimes(bifurcation, sweep.rows, unit.si_per_unit);
    render(dir, bifurcation);
  }
  if (spec.iso && worth_plotting("dynamic_factor_vs_iso_n", distinct(iso_x))) {
    render_iso_plot(dir, *spec.iso, sweep.rows);
  }
  if (spec.vary2.empty() || spec.lines < 2) return;
  // The map needs up rows spread over two values of each key.
  if (!worth_plotting("regime-map", std::min(distinct(map_x), distinct(map_lines)))) return;
  const ShownUnit unit2 = shown_unit(spec.vary2, spec.unit2);
  const double from2 = spec.from2_si.value_or(0.0) / unit2.si_per_unit;
  const double to2 = spec.to2_si.value_or(0.0) / unit2.si_per_unit;
  const std::string step2 = format_number((to2 - from2) / (spec.lines - 1));
  Figure map;
  map.name = "regime-map";
  map.title = "Regimes, swept up";
  map.x_label = unit.label;
  map.y_label = unit2.label;
  map.setup = {"set key outside right top", "unset grid"};
  const auto [x_low, x_high] = extremes(map_x);
  // Each point's cell reaches half-way to its neighbours, so that the ends sit half a step out.
  const double dx = (x_high - x_low) / std::max(1, spec.points - 1);
  const double dy = (to2 - from2) / (spec.lines - 1);
  add(map, tick_commands("x", nice_ticks(x_low - 0.5 * dx, x_high + 0.5 * dx)));
  add(map, tick_commands("y", nice_ticks(from2 - 0.5 * dy, to2 + 0.5 * dy)));
  mesh_frequency_axis(map, spec, unit.si_per_unit, nice_ticks(x_low - 0.5 * dx, x_high + 0.5 * dx));
  std::set<Regime> present;
  bool unconverged = false;
  for (const SweepPointResult& r : sweep.rows) {
    if (r.direction != SweepDirection::up) continue;
    if (r.point.converged) {
      present.insert(r.point.regime);
    } else {
      unconverged = true;
    }
  }
  for (const RegimeShade& shade : kRegimeShades) {
    if (present.count(shade.regime) == 0) continue;
    map.series.push_back("'sweep.csv' using (strcol(2) eq \"up\" && strcol(5) eq \"" +
                         to_string(shade.regime) + "\" ? " + x_of + " : NaN):(" +
                         format_number(from2) + " + $1 * " + step2 + "):(" +
                         format_number(0.5 * dx) + "):(" + format_number(0.5 * dy) +
                         ") with boxxyerror fs solid 1.0 noborder fc rgb '" + shade.colour +
                         "' title '" + to_string(shade.regime) + "'");
  }
  if (unconverged) {
    map.series.push_back("'sweep.csv' using (strcol(2) eq \"up\" && strcol(7) eq \"false\" ? " +
                         x_of + " : NaN):(" + format_number(from2) + " + $1 * " + step2 +
                         ") with points pt 2 ps 1.2 lc rgb 'black' title 'not converged'");
  }
  render(dir, map);
}

// The options of `sweep` after CASE.
void add_sweep_options(CLI::App* sweep, SweepCommandOptions& o) {
  sweep
      ->add_option("--vary", o.vary,
                   "the key to sweep, section.key: any quantity, number or integer key of the "
                   "case schema (`gearimpact schema`), or an element of a list key, section.key[i]")
      ->required();
  sweep->add_option("--from", o.from, "first value, with its unit as in case files")->required();
  sweep->add_option("--to", o.to, "last value")->required();
  sweep
      ->add_option("--points", o.points,
                   "number of values (>= 1); points x points2 x directions at most --max-points")
      ->required();
  sweep->add_option("--direction", o.direction, "up, down or both")
      ->check(CLI::IsMember({"up", "down", "both"}));
  CLI::Option* vary2 = sweep->add_option("--vary2", o.vary2, "a second key: one line per value");
  // Without --vary2 they would do nothing.
  sweep->add_option("--from2", o.from2, "first value of the second key")->needs(vary2);
  sweep->add_option("--to2", o.to2, "last value of the second key")->needs(vary2);
  sweep->add_option("--points2", o.points2, "number of values of the second key")->needs(vary2);
  sweep->add_option("--max-points", o.max_points,
                    "the most points (points x points2 x directions) the sweep may run, so that a "
                    "slip of --points does not start a run of days (default " +
                        shortest_decimal(kMostSweepPoints) + ")");
  sweep->add_option("--out", o.out,
                    "output folder: new or empty (else --overwrite), in a folder that exists; "
                    "written beside it and renamed into place when complete");
  sweep->add_flag("--overwrite", o.overwrite, "replace a non-empty --out folder whole");
  o.shard_flag =
      sweep->add_option("--shard", o.shard,
                        "K/N: the lines u with u % N == K (default: SLURM_ARRAY_TASK_ID - "
                        "SLURM_ARRAY_TASK_MIN of SLURM_ARRAY_TASK_COUNT, else all)");
  o.keys.add_flags(sweep, kSweep);
  o.keys.add_set(sweep,
                 "KEY=VALUE for any key of the case schema, before the sweep, in order, after "
                 "the flags that set keys (repeatable); a numeric key as a swept value: a "
                 "speed moves the other speed, a mean torque the other mean torque (balance)",
                 SetNumbers::as_swept_value);
  sweep->add_option("--tolerance", o.settings.tolerance,
                    "samples repeat within this fraction of B and B w_n, in (0, " +
                        shortest_decimal(kMostTolerance) + "]");
  sweep->add_option("--steps-per-contact-period", o.settings.steps_per_contact_period,
                    "RK4 steps per period of the stiffest contact, in [" +
                        shortest_decimal(kLeastStepsPerContactPeriod) + ", " +
                        shortest_decimal(kMostStepsPerContactPeriod) + "]");
  sweep->add_option("--max-periods", o.settings.max_periods,
                    "excitation periods a point may run before it is not converged, in [1, " +
                        std::to_string(kMostMaxPeriods) + "]");
  sweep
      ->add_option("--threads", o.threads,
                   "worker threads, in [0, " + std::to_string(kMostThreads) + "] (0: one per core)")
      ->check(CLI::Range(0u, static_cast<unsigned>(kMostThreads)));
  sweep->add_flag("!--no-plots", o.plots, "skip the gnuplot figures");
}

void run_sweep(SweepCommandOptions& o) {
  const std::vector<std::string> inputs = is_paper_case(o.case_source)
                                              ? std::vector<std::string>{}
                                              : std::vector<std::string>{o.case_source};
  require_output_folder(o.out, o.overwrite, inputs);
  const SteadySweepSpec spec = sweep_spec(o, read_case(o.case_source));
  AtomicFolder folder(o.out, o.overwrite, inputs);
  std::mutex progress_mutex;
  std::size_t done = 0;
  const std::size_t total = shard_point_count(spec);
  // The swept value in the unit the user gave it in, SI beside it.
  const ShownUnit shown = shown_unit(spec.vary, spec.unit);
  const auto value_text = [&](double si) {
    if (shown.symbol.empty()) return format_number(si);
    // Ten digits: the conversion's last-digit rounding (12000.000000000002 rpm) is not the user's.
    char in_unit[32];
    std::snprintf(in_unit, sizeof in_unit, "%.10g", si / shown.si_per_unit);
    std::string text = in_unit;
    text += " " + shown.symbol;
    const std::string si_symbol(
        units_of(sweep_field(spec.vary, spec.vary).dimension).front().symbol);
    if (shown.symbol != si_symbol) text += " (" + format_number(si) + " " + si_symbol + ")";
    return text;
  };
  const SteadySweep sweep = run_naming_flags(spec, [&](const SweepPointResult& r) {
    const std::lock_guard lock(progress_mutex);
    ++done;
    std::cerr << "sweep: " << done << "/" << total << "  line " << r.line << " "
              << to_string(r.direction) << " " << spec.vary << " = " << value_text(r.value_si)
              << ": "
              << (r.point.converged
                      ? to_string(r.point.regime) + " period " + std::to_string(r.point.period)
                      : std::string("not converged"))
              << " after " << r.point.periods_run << " periods"
              << (r.failure.empty() ? "" : " (" + r.failure + ")") << '\n';
  });
  for (const std::string& warning : sweep.warnings) {
    std::cerr << "gearimpact: warning: " << warning << '\n';
  }
  write_sweep_folder(folder.temporary(), sweep);
  if (o.plots) render_plots(folder.temporary(), sweep);
  folder.commit();
}

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string out;
  bool plots = true;
  bool overwrite = false;
};

void run_merge(const MergeOptions& o) {
  AtomicFolder folder(o.out, o.overwrite, o.inputs);
  const SteadySweep merged =
      merge_sweep_folders(std::vector<std::filesystem::path>(o.inputs.begin(), o.inputs.end()));
  write_sweep_folder(folder.temporary(), merged);
  if (o.plots) render_plots(folder.temporary(), merged);
  folder.commit();
}

}  // namespace

SteadySweep sweep_with_options(const SimulationCase& c, const std::vector<std::string>& options) {
  CLI::App app{"sweep"};
  SweepCommandOptions o;
  add_sweep_options(&app, o);
  std::vector<std::string> reversed(options.rbegin(), options.rend());
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    throw InputError("options", e.what(), "options of gearimpact sweep after CASE");
  }
  return run_naming_flags(sweep_spec(o, c), {});
}

void register_sweep_commands(CLI::App& app) {
  auto o = std::make_shared<SweepCommandOptions>();
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "steady state along a parameter, up and down, continued from point to point: DIR/sweep.csv, "
      "poincare.csv, summary.json and plots");
  sweep->add_option("CASE", o->case_source, "case file, or 1, 2, 3 for Table 1")->required();
  add_sweep_options(sweep, *o);
  sweep->callback([o] { run_sweep(*o); });

  auto m = std::make_shared<MergeOptions>();
  CLI::App* merge = app.add_subcommand(
      "merge", "merge sweep shards by (line, direction, index); fails naming a missing key");
  merge->add_option("DIR", m->inputs, "shard output folders")->required();
  merge
      ->add_option("--out", m->out,
                   "merged output folder: new or empty (else --overwrite), not a shard's, in a "
                   "folder that exists; written beside it and renamed into place when complete")
      ->required();
  merge->add_flag("--overwrite", m->overwrite, "replace a non-empty --out folder whole");
  merge->add_flag("!--no-plots", m->plots, "skip the gnuplot figures");
  merge->callback([m] { run_merge(*m); });
}

}  // namespace gearimpact::cli
