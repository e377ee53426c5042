// `sweep`: the steady state of a case along one parameter (and optionally over a second), in
// both directions, lines in parallel, shardable; `merge`: shards into one output. The rows are
// keyed (line, direction, index) and written sorted by key, so the merged output does not depend
// on how the lines were split.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "commands.hpp"
#include "gearimpact/batch/pool.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/iso_resonance.hpp"
#include "gearimpact/steady/sweep.hpp"
#include "gnuplot.hpp"
#include "iso_plot.hpp"

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
  std::vector<std::string> set;
  std::string mesh_stiffness;
  std::string damping_update;
  unsigned threads = 0;
  bool plots = true;
  SteadySettings settings;
};

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string optional_number(const std::optional<double>& v) {
  return v ? number(*v) : "";
}

// A value of a numeric key as the user wrote it: with a unit as in case files, or a plain number
// (SI for a quantity), checked against the key's range.
double sweep_value(const std::string& key, const std::string& text, const std::string& flag) {
  return gearimpact::parse_value(sweep_field(key, flag), text, flag + " (" + key + ")");
}

SimulationCase read_case(const std::string& source) {
  if (source == "1" || source == "2" || source == "3") return paper_case(std::stoi(source));
  return read_case_file(source);
}

struct Shard {
  int k = 0;
  int n = 1;
};

Shard parse_shard(const std::string& text) {
  std::string spec = text;
  if (spec.empty()) {
    const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
    const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
    if (id == nullptr || count == nullptr) return {};
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    const long k = std::atol(id) - (min != nullptr ? std::atol(min) : 0);
    spec = std::to_string(k) + "/" + count;
  }
  // K/N: two runs of at most 9 digits around one slash.
  const std::size_t slash = spec.find('/');
  const auto digits = [](const std::string& part) {
    return !part.empty() && part.size() <= 9 &&
           std::all_of(part.begin(), part.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
  };
  const std::string k_text = slash == std::string::npos ? spec : spec.substr(0, slash);
  const std::string n_text = slash == std::string::npos ? "" : spec.substr(slash + 1);
  if (!digits(k_text) || !digits(n_text) || std::stoi(n_text) < 1 ||
      std::stoi(k_text) >= std::stoi(n_text)) {
    throw InputError("--shard", spec,
                     "K/N with 0 <= K < N (or SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_COUNT and "
                     "SLURM_ARRAY_TASK_MIN)");
  }
  return {std::stoi(k_text), std::stoi(n_text)};
}

struct Unit {
  int line;
  SweepDirection direction;
};

// The part of summary.json that every shard of one sweep shares; merge checks it and keeps it.
std::string spec_block(const SweepCommandOptions& o, const SimulationCase& c,
                       const std::vector<double>& grid, const std::vector<double>& grid2,
                       const std::vector<SweepDirection>& directions,
                       const std::optional<IsoScale>& iso) {
  std::ostringstream s;
  s << "  \"spec\": {\n"
    << "    \"case\": \"" << c.name << "\",\n"
    << "    \"vary\": \"" << o.vary << "\",\n"
    << "    \"from_si\": " << number(grid.front()) << ",\n"
    << "    \"to_si\": " << number(grid.back()) << ",\n"
    << "    \"points\": " << grid.size() << ",\n"
    << "    \"vary2\": \"" << o.vary2 << "\",\n"
    << "    \"from2_si\": " << (o.vary2.empty() ? "null" : number(grid2.front())) << ",\n"
    << "    \"to2_si\": " << (o.vary2.empty() ? "null" : number(grid2.back())) << ",\n"
    << "    \"lines\": " << grid2.size() << ",\n"
    << "    \"directions\": \"";
  for (std::size_t i = 0; i < directions.size(); ++i) {
    s << (i ? "," : "") << to_string(directions[i]);
  }
  s << "\",\n"
    << "    \"backlash_m\": " << number(c.gears.backlash_m) << ",\n";
  if (iso) {
    s << "    \"iso_resonance_speed_rad_s\": " << number(iso->resonance_speed_rad_s) << ",\n"
      << "    \"iso_resonance_speed_iso_stiffness_rad_s\": "
      << number(iso->resonance_speed_iso_stiffness_rad_s) << ",\n"
      << "    \"iso_contact_ratio\": " << number(iso->contact_ratio) << ",\n"
      << "    \"iso_line_load_n_m\": " << number(iso->line_load_n_m) << ",\n";
  }
  s << "    \"tolerance\": " << number(o.settings.tolerance) << ",\n"
    << "    \"steps_per_contact_period\": " << number(o.settings.steps_per_contact_period) << ",\n"
    << "    \"max_periods\": " << o.settings.max_periods << ",\n"
    << "    \"damping_update\": \""
    << (c.model.damping_update == DampingUpdate::each_impact ? "each-impact"
        : c.model.damping_update == DampingUpdate::frozen    ? "frozen"
                                                             : "off")
    << "\"\n"
    << "  }";
  return s.str();
}

using Key = std::tuple<int, int, int>;  // line, direction (0 up, 1 down), index

struct Row {
  std::string sweep;     // one line of sweep.csv
  std::string poincare;  // its lines of poincare.csv
  std::string regime;
  bool converged = false;
};

const char* kSweepHeader =
    "line,direction,index,value_si,regime,period,converged,dte_mean_m,dte_amplitude_m,dte_rms_m,"
    "s_min_m,s_max_m,dynamic_factor,impacts_drive_per_period,impacts_coast_per_period\n";
const char* kPoincareHeader = "line,direction,index,value_si,s_m,ds_m_s\n";

Row make_row(const SweepPointResult& r) {
  const SteadyPoint& p = r.point;
  const std::string key = std::to_string(r.line) + "," + to_string(r.direction) + "," +
                          std::to_string(r.index) + "," + number(r.value_si);
  Row row;
  row.converged = p.converged;
  row.regime = p.converged ? to_string(p.regime) : "";
  row.sweep = key + "," + row.regime + "," + period_label(p) + "," +
              (p.converged ? "true" : "false") + "," + optional_number(p.dte_mean_m) + "," +
              optional_number(p.dte_amplitude_m) + "," + optional_number(p.dte_rms_m) + "," +
              optional_number(p.s_min_m) + "," + optional_number(p.s_max_m) + "," +
              optional_number(p.dynamic_factor) + "," +
              optional_number(p.impacts_drive_per_period) + "," +
              optional_number(p.impacts_coast_per_period) + "\n";
  for (const PoincareSample& s : p.poincare) {
    row.poincare += key + "," + number(s.s_m) + "," + number(s.s_rate_m_s) + "\n";
  }
  return row;
}

struct Counts {
  std::size_t points = 0, converged = 0;
  std::map<std::string, std::size_t> regimes;
};

void write_outputs(const std::filesystem::path& dir, const std::string& spec,
                   const std::map<Key, Row>& rows, const std::string& extra) {
  std::filesystem::create_directories(dir);
  std::string sweep = kSweepHeader;
  std::string poincare = kPoincareHeader;
  Counts counts;
  for (const auto& [key, row] : rows) {
    sweep += row.sweep;
    poincare += row.poincare;
    ++counts.points;
    if (row.converged) {
      ++counts.converged;
      ++counts.regimes[row.regime];
    }
  }
  write_file_atomically((dir / "sweep.csv").string(), sweep);
  write_file_atomically((dir / "poincare.csv").string(), poincare);
  std::ostringstream json;
  json << "{\n"
       << spec << ",\n"
       << extra << "  \"points_written\": " << counts.points << ",\n"
       << "  \"points_converged\": " << counts.converged << ",\n  \"regimes\": {";
  bool first = true;
  for (const auto& [name, n] : counts.regimes) {
    json << (first ? "" : ", ") << "\"" << name << "\": " << n;
    first = false;
  }
  json << "}\n}\n";
  write_file_atomically((dir / "summary.json").string(), json.str());
}

// The spec fields merge needs, read back from the spec block.
struct SpecCounts {
  int points = 0;
  int lines = 0;
  std::vector<std::string> directions;
  std::string vary2;
  double from2 = 0.0, to2 = 0.0;
  std::optional<IsoScale> iso;  // for a sweep of initial.w1
};

// The value of "name": in the JSON text the sweep writes: a quoted string
// (without the quotes) or a bare token up to the next comma or line end.
std::optional<std::string> json_value(const std::string& json, const std::string& name) {
  const std::string key = "\"" + name + "\": ";
  const std::size_t at = json.find(key);
  if (at == std::string::npos) return std::nullopt;
  std::size_t begin = at + key.size();
  if (begin < json.size() && json[begin] == '"') {
    const std::size_t end = json.find('"', begin + 1);
    if (end == std::string::npos) return std::nullopt;
    return json.substr(begin + 1, end - begin - 1);
  }
  const std::size_t end = json.find_first_of(",\n}", begin);
  return json.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

SpecCounts read_spec_counts(const std::string& spec, const std::string& file) {
  SpecCounts counts;
  const auto field = [&](const char* name) {
    const std::optional<std::string> value = json_value(spec, name);
    if (!value) {
      throw InputError(file, std::string("no ") + name,
                       "a summary.json written by gearimpact sweep");
    }
    return *value;
  };
  counts.points = std::stoi(field("points"));
  counts.lines = std::stoi(field("lines"));
  if (const std::optional<std::string> directions = json_value(spec, "directions")) {
    std::stringstream list(*directions);
    for (std::string d; std::getline(list, d, ',');) counts.directions.push_back(d);
  }
  counts.vary2 = field("vary2");
  if (!counts.vary2.empty()) {
    counts.from2 = std::stod(field("from2_si"));
    counts.to2 = std::stod(field("to2_si"));
  }
  if (json_value(spec, "iso_resonance_speed_rad_s")) {
    IsoScale iso;
    iso.resonance_speed_rad_s = std::stod(field("iso_resonance_speed_rad_s"));
    iso.resonance_speed_iso_stiffness_rad_s =
        std::stod(field("iso_resonance_speed_iso_stiffness_rad_s"));
    iso.contact_ratio = std::stod(field("iso_contact_ratio"));
    iso.line_load_n_m = std::stod(field("iso_line_load_n_m"));
    counts.iso = iso;
  }
  return counts;
}

std::string read_text(const std::filesystem::path& path);

// dynamic_factor_vs_iso_n.csv from sweep.csv (the swept value is w1) and its figure.
void render_iso_plot(const std::filesystem::path& dir, const IsoScale& iso) {
  std::istringstream csv(read_text(dir / "sweep.csv"));
  std::string data =
      "line,direction,index,w1_rad_s,iso_resonance_ratio,iso_resonance_ratio_iso_stiffness,"
      "dynamic_factor\n";
  const auto split = [](const std::string& line) {
    std::vector<std::string> fields;
    std::istringstream in(line);
    for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
    return fields;
  };
  // The columns by their names in kSweepHeader: the swept w1 and the dynamic factor.
  std::string header_line = kSweepHeader;
  header_line.pop_back();  // the newline
  const std::vector<std::string> header = split(header_line);
  const auto column = [&header](const char* name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t w1_column = column("value_si");
  const std::size_t df_column = column("dynamic_factor");
  double n_max = 0.0;
  std::string line;
  std::getline(csv, line);
  while (std::getline(csv, line)) {
    std::vector<std::string> fields = split(line);
    fields.resize(header.size());
    const double w1 = std::stod(fields[w1_column]);
    const double n = iso_resonance_ratio(w1, iso.resonance_speed_rad_s);
    n_max = std::max(n_max, n);
    data += fields[0] + "," + fields[1] + "," + fields[2] + "," + fields[w1_column] + "," +
            number(n) + "," +
            number(iso_resonance_ratio(w1, iso.resonance_speed_iso_stiffness_rad_s)) + "," +
            fields[df_column] + "\n";
  }
  write_file_atomically((dir / "dynamic_factor_vs_iso_n.csv").string(), data);
  write_iso_kv_band(dir / "iso_kv_band.csv", iso, std::max(2.0, 1.1 * n_max));
  render(dir, dynamic_factor_vs_iso_n("dynamic_factor_vs_iso_n", iso, "dynamic_factor_vs_iso_n.csv",
                                      2, 5, 7, "iso_kv_band.csv"));
}

// The plots of a sweep folder: amplitude up and down, the bifurcation diagram, the regime map.
void render_plots(const std::filesystem::path& dir, const SpecCounts& spec,
                  const std::string& vary) {
  const std::string line_count = std::to_string(spec.lines);
  Figure amplitude;
  amplitude.name = "amplitude";
  amplitude.title = "Steady DTE amplitude, sweeps up and down";
  amplitude.x_label = vary + " (SI)";
  amplitude.y_label = "half peak-to-peak of s (m)";
  amplitude.setup = {"set key outside right"};
  for (const char* d : {"up", "down"}) {
    amplitude.series.push_back(std::string("for [l=0:") + std::to_string(spec.lines - 1) +
                               "] 'sweep.csv' using (($1 == l && strcol(2) eq \"" + d +
                               "\") ? $4 : NaN):9 with linespoints title sprintf('line %d " + d +
                               "', l)");
  }
  render(dir, amplitude);
  Figure bifurcation;
  bifurcation.name = "bifurcation";
  bifurcation.title = "Bifurcation diagram: Poincare samples of s";
  bifurcation.x_label = vary + " (SI)";
  bifurcation.y_label = "s at the excitation phase (m)";
  bifurcation.series = {
      "'poincare.csv' using (strcol(2) eq \"up\" ? $4 : NaN):5 with points pt 7 ps 0.4 title 'up'",
      "'poincare.csv' using (strcol(2) eq \"down\" ? $4 : NaN):5 with points pt 6 ps 0.6 title "
      "'down'"};
  render(dir, bifurcation);
  if (spec.iso) render_iso_plot(dir, *spec.iso);
  if (spec.vary2.empty() || spec.lines < 2) return;
  const std::string step2 = number((spec.to2 - spec.from2) / (spec.lines - 1));
  Figure map;
  map.name = "regime-map";
  map.title = "Regimes (up sweeps): NI 0, SS 1, DS 2, NC 3";
  map.x_label = vary + " (SI)";
  map.y_label = spec.vary2 + " (SI)";
  map.setup = {"set cbrange [0:3]", "set palette maxcolors 4",
               "set cbtics ('NI' 0, 'SS' 1, 'DS' 2, 'NC' 3)"};
  map.series = {
      "'sweep.csv' using (strcol(2) eq \"up\" ? $4 : NaN):(" + number(spec.from2) + " + $1 * " +
      step2 +
      "):(strcol(5) eq \"NI\" ? 0 : strcol(5) eq \"SS\" ? 1 : strcol(5) eq \"DS\" ? 2 : 3) "
      "with points pt 5 ps 1.5 palette notitle"};
  render(dir, map);
}

// The case of CASE with --set, --mesh-stiffness and --damping-update applied.
SimulationCase base_case(const SweepCommandOptions& o) {
  SimulationCase base = read_case(o.case_source);
  if (!o.mesh_stiffness.empty()) {
    base.model.mesh_stiffness = o.mesh_stiffness == "constant" ? MeshStiffnessMode::constant
                                                               : MeshStiffnessMode::time_varying;
  }
  if (!o.damping_update.empty()) {
    base.model.damping_update = o.damping_update == "frozen" ? DampingUpdate::frozen
                                : o.damping_update == "off"  ? DampingUpdate::off
                                                             : DampingUpdate::each_impact;
  }
  // After the flags, so that a key used only with their choice (the frozen D's reference speed,
  // the constant stiffness) can be set.
  for (const std::string& assignment : o.set) {
    const std::size_t eq = assignment.find('=');
    if (eq == std::string::npos) throw InputError("--set", assignment, "KEY=VALUE");
    const std::string key = assignment.substr(0, eq);
    const std::string value = assignment.substr(eq + 1);
    const Field* field = find_field(key);
    if (field != nullptr &&
        (field->kind == FieldKind::quantity || field->kind == FieldKind::number ||
         field->kind == FieldKind::integer)) {
      const SimulationCase before = base;
      apply_sweep_value(base, before, key, sweep_value(key, value, "--set"));
    } else {
      set_field(base, key, value, "--set " + key);
    }
  }
  return base;
}

// The lines u = line x direction with u % N == K.
std::vector<Unit> shard_units(std::size_t lines, const std::vector<SweepDirection>& directions,
                              const Shard& shard) {
  std::vector<Unit> units;
  int u = 0;
  for (int line = 0; line < static_cast<int>(lines); ++line) {
    for (SweepDirection d : directions) {
      if (u++ % shard.n == shard.k) units.push_back({line, d});
    }
  }
  return units;
}

void run_sweep(SweepCommandOptions& o) {
  const SimulationCase base = base_case(o);
  sweep_field(o.vary, "--vary");
  const std::vector<double> grid =
      sweep_grid(sweep_value(o.vary, o.from, "--from"), sweep_value(o.vary, o.to, "--to"), o.points,
                 "--from", "--to", "--points");
  std::vector<double> grid2{0.0};
  if (!o.vary2.empty()) {
    sweep_field(o.vary2, "--vary2");
    grid2 =
        sweep_grid(sweep_value(o.vary2, o.from2, "--from2"), sweep_value(o.vary2, o.to2, "--to2"),
                   o.points2, "--from2", "--to2", "--points2");
  }
  std::vector<SweepDirection> directions;
  if (o.direction != "down") directions.push_back(SweepDirection::up);
  if (o.direction != "up") directions.push_back(SweepDirection::down);
  const Shard shard = parse_shard(o.shard);
  // Refuse a case without a steady state before any work, naming the key.
  {
    SimulationCase probe = base;
    if (!o.vary2.empty()) apply_sweep_value(probe, base, o.vary2, grid2.front());
    apply_sweep_value(probe, SimulationCase(probe), o.vary, grid.front());
    validate(probe);
    require_steady_case(probe);
  }
  const std::vector<Unit> units = shard_units(grid2.size(), directions, shard);
  RunPool pool(o.threads);
  // N = w1 / w_E1 of the base case's pair and load (a second key that changes them is not seen).
  std::optional<IsoScale> iso;
  if (o.vary == "initial.w1") iso = iso_scale(base, *pool.table_for(base));
  std::mutex progress_mutex;
  std::size_t done = 0;
  const std::size_t total = units.size() * grid.size();
  std::vector<std::future<std::vector<SweepPointResult>>> futures;
  for (const Unit& unit : units) {
    futures.push_back(pool.run([&, unit] {
      SimulationCase line_case = base;
      if (!o.vary2.empty()) {
        apply_sweep_value(line_case, base, o.vary2, grid2[static_cast<std::size_t>(unit.line)]);
      }
      return sweep_line(
          line_case, [&](const SimulationCase& c) { return pool.table_for(c); }, o.vary, grid,
          unit.direction, unit.line, o.settings,
          [&](const SweepPointResult& r) {
            const std::lock_guard lock(progress_mutex);
            ++done;
            std::cerr << "sweep: " << done << "/" << total << "  line " << r.line << " "
                      << to_string(r.direction) << " " << o.vary << " = " << number(r.value_si)
                      << ": "
                      << (r.point.converged ? to_string(r.point.regime) + " period " +
                                                  std::to_string(r.point.period)
                                            : std::string("not converged"))
                      << " after " << r.point.periods_run << " periods"
                      << (r.failure.empty() ? "" : " (" + r.failure + ")") << '\n';
          });
    }));
  }
  std::map<Key, Row> rows;
  for (auto& f : futures) {
    for (const SweepPointResult& r : f.get()) {
      rows[{r.line, r.direction == SweepDirection::up ? 0 : 1, r.index}] = make_row(r);
    }
  }
  const std::string spec = spec_block(o, base, grid, grid2, directions, iso);
  std::string extra =
      "  \"shard\": \"" + std::to_string(shard.k) + "/" + std::to_string(shard.n) + "\",\n";
  write_outputs(o.out, spec, rows, extra);
  if (o.plots) render_plots(o.out, read_spec_counts(spec, o.out), o.vary);
}

struct MergeOptions {
  std::vector<std::string> inputs;
  std::string out;
  bool plots = true;
};

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("merge", path.string(), "a readable file written by gearimpact sweep");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The rows of one shard folder into `rows`; a key already there is refused.
void read_shard_rows(const std::filesystem::path& dir, const std::string& input,
                     std::map<Key, Row>& rows) {
  std::istringstream csv(read_text(dir / "sweep.csv"));
  std::string line;
  std::getline(csv, line);
  while (std::getline(csv, line)) {
    std::istringstream fields(line);
    std::string l, d, i, value, regime, period, converged;
    std::getline(fields, l, ',');
    std::getline(fields, d, ',');
    std::getline(fields, i, ',');
    std::getline(fields, value, ',');
    std::getline(fields, regime, ',');
    std::getline(fields, period, ',');
    std::getline(fields, converged, ',');
    const Key key{std::stoi(l), d == "up" ? 0 : 1, std::stoi(i)};
    Row& row = rows[key];
    if (!row.sweep.empty()) {
      throw InputError("merge",
                       "row (line " + l + ", direction " + d + ", index " + i + ") in " + input +
                           " and an earlier folder",
                       "each (line, direction, index) in one shard only");
    }
    row.sweep = line + "\n";
    row.regime = regime;
    row.converged = converged == "true";
  }
  std::istringstream poincare(read_text(dir / "poincare.csv"));
  std::getline(poincare, line);
  while (std::getline(poincare, line)) {
    std::istringstream fields(line);
    std::string l, d, i;
    std::getline(fields, l, ',');
    std::getline(fields, d, ',');
    std::getline(fields, i, ',');
    rows[{std::stoi(l), d == "up" ? 0 : 1, std::stoi(i)}].poincare += line + "\n";
  }
}

void run_merge(const MergeOptions& o) {
  std::string spec;
  std::string vary;
  std::map<Key, Row> rows;
  for (const std::string& input : o.inputs) {
    const std::filesystem::path dir(input);
    const std::string summary = read_text(dir / "summary.json");
    const std::size_t start = summary.find("  \"spec\": {");
    const std::size_t end = summary.find("\n  }", start);
    if (start == std::string::npos || end == std::string::npos) {
      throw InputError("merge", (dir / "summary.json").string(), "a summary.json with its spec");
    }
    const std::string this_spec = summary.substr(start, end + 4 - start);
    if (spec.empty()) spec = this_spec;
    if (this_spec != spec) {
      throw InputError("merge", input, "a shard of the same sweep as " + o.inputs.front());
    }
    read_shard_rows(dir, input, rows);
  }
  if (o.inputs.empty()) throw InputError("merge", "no folder", "one or more sweep output folders");
  const SpecCounts counts = read_spec_counts(spec, o.inputs.front());
  for (int l = 0; l < counts.lines; ++l) {
    for (const std::string& d : counts.directions) {
      for (int i = 0; i < counts.points; ++i) {
        const auto found = rows.find({l, d == "up" ? 0 : 1, i});
        if (found == rows.end() || found->second.sweep.empty()) {
          throw InputError("merge",
                           "no row (line " + std::to_string(l) + ", direction " + d + ", index " +
                               std::to_string(i) + ")",
                           "every (line, direction, index) of the sweep: a shard is missing");
        }
      }
    }
  }
  write_outputs(o.out, spec, rows, "");
  if (const std::optional<std::string> value = json_value(spec, "vary")) vary = *value;
  if (o.plots) render_plots(o.out, counts, vary);
}

}  // namespace

void register_sweep_commands(CLI::App& app) {
  auto o = std::make_shared<SweepCommandOptions>();
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "steady state along a parameter, up and down, continued from point to point: DIR/sweep.csv, "
      "poincare.csv, summary.json and plots");
  sweep->add_option("CASE", o->case_source, "case file, or 1, 2, 3 for Table 1")->required();
  sweep
      ->add_option("--vary", o->vary,
                   "the key to sweep, section.key: any quantity, number or integer key of the "
                   "case schema (`gearimpact schema`)")
      ->required();
  sweep->add_option("--from", o->from, "first value, with its unit as in case files")->required();
  sweep->add_option("--to", o->to, "last value")->required();
  sweep->add_option("--points", o->points, "number of values (>= 1)")->required();
  sweep->add_option("--direction", o->direction, "up, down or both")
      ->check(CLI::IsMember({"up", "down", "both"}));
  sweep->add_option("--vary2", o->vary2, "a second key: one line per value");
  sweep->add_option("--from2", o->from2, "first value of the second key");
  sweep->add_option("--to2", o->to2, "last value of the second key");
  sweep->add_option("--points2", o->points2, "number of values of the second key");
  sweep->add_option("--out", o->out, "output folder");
  sweep->add_option("--shard", o->shard,
                    "K/N: the lines u with u % N == K (default: SLURM_ARRAY_TASK_ID - "
                    "SLURM_ARRAY_TASK_MIN of SLURM_ARRAY_TASK_COUNT, else all)");
  sweep->add_option(
      "--set", o->set,
      "KEY=VALUE for any key of the case schema, before the sweep, in order, after "
      "--mesh-stiffness and --damping-update (repeatable); a numeric key as a swept value: a "
      "speed moves the other speed, a mean torque the other mean torque (balance)");
  sweep->add_option("--mesh-stiffness", o->mesh_stiffness, "time-varying or constant")
      ->check(CLI::IsMember({"time-varying", "constant"}));
  sweep->add_option("--damping-update", o->damping_update, "each-impact, frozen or off")
      ->check(CLI::IsMember({"each-impact", "frozen", "off"}));
  sweep->add_option("--tolerance", o->settings.tolerance,
                    "samples repeat within this fraction of B and B w_n");
  sweep->add_option("--steps-per-contact-period", o->settings.steps_per_contact_period,
                    "RK4 steps per period of the stiffest contact");
  sweep->add_option("--max-periods", o->settings.max_periods,
                    "excitation periods a point may run before it is not converged");
  sweep->add_option("--threads", o->threads, "worker threads (0: one per core)");
  sweep->add_flag("!--no-plots", o->plots, "skip the gnuplot figures");
  sweep->callback([o] { run_sweep(*o); });

  auto m = std::make_shared<MergeOptions>();
  CLI::App* merge = app.add_subcommand(
      "merge", "merge sweep shards by (line, direction, index); fails naming a missing key");
  merge->add_option("DIR", m->inputs, "shard output folders")->required();
  merge->add_option("--out", m->out, "merged output folder")->required();
  merge->add_flag("!--no-plots", m->plots, "skip the gnuplot figures");
  merge->callback([m] { run_merge(*m); });
}

}  // namespace gearimpact::cli
