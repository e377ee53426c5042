#include "gearimpact/io/sweep_files.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/results.hpp"

namespace gearimpact {

namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kSweepHeader =
    "line,direction,index,value_si,regime,period,converged,dte_mean_m,dte_amplitude_m,dte_rms_m,"
    "s_min_m,s_max_m,dte_contact_mean_m,dte_contact_min_m,dte_contact_max_m,dynamic_factor,"
    "impacts_drive_per_period,impacts_coast_per_period,w1_mean_rad_s,w2_mean_rad_s,pinion_rpm,"
    "mesh_frequency_hz\n";
constexpr const char* kPoincareHeader = "line,direction,index,value_si,s_m,ds_m_s\n";
constexpr std::size_t kSweepColumns = 22;
constexpr const char* kSweepFile = "a summary.json written by gearimpact sweep";

std::string optional_number(const std::optional<double>& v) {
  return v ? format_data_number(*v) : "";
}

// The key and swept value that begin a row of both files.
std::string key_fields(const SweepPointResult& r) {
  return std::to_string(r.line) + "," + to_string(r.direction) + "," + std::to_string(r.index) +
         "," + format_data_number(r.value_si);
}

const Field& damping_update_field() {
  return *find_field("model.damping_update");
}

std::string damping_update_name(DampingUpdate update) {
  for (const ChoiceName& choice : damping_update_field().choices) {
    if (choice.code == static_cast<int>(update)) return std::string(choice.name);
  }
  return "";
}

std::string directions_text(const std::vector<SweepDirection>& directions) {
  std::string text;
  for (std::size_t i = 0; i < directions.size(); ++i) {
    text += (i ? "," : "") + to_string(directions[i]);
  }
  return text;
}

Json spec_json(const SteadySweepRecord& s) {
  Json j;
  j["case"] = s.case_name;
  j["case_key_fnv1a64"] = s.case_key_hash;
  j["vary"] = s.vary;
  j["from_si"] = s.from_si;
  j["to_si"] = s.to_si;
  j["points"] = s.points;
  j["vary2"] = s.vary2;
  j["from2_si"] = s.from2_si ? Json(*s.from2_si) : Json(nullptr);
  j["to2_si"] = s.to2_si ? Json(*s.to2_si) : Json(nullptr);
  j["lines"] = s.lines;
  j["directions"] = directions_text(s.directions);
  j["backlash_m"] = s.backlash_m;
  j["unit"] = s.unit;
  j["unit2"] = s.unit2;
  j["mesh_teeth"] = s.mesh_teeth;
  if (s.iso) {
    j["iso_resonance_speed_rad_s"] = s.iso->resonance_speed_rad_per_s;
    j["iso_resonance_speed_iso_stiffness_rad_s"] = s.iso->resonance_speed_iso_stiffness_rad_per_s;
    j["iso_contact_ratio"] = s.iso->contact_ratio;
    j["iso_line_load_n_m"] = s.iso->line_load_n_per_m;
    j["quasi_static_force_ratio"] = s.iso->quasi_static_force_ratio;
  }
  j["tolerance"] = s.tolerance;
  j["steps_per_contact_period"] = s.steps_per_contact_period;
  j["max_periods"] = s.max_periods;
  j["damping_update"] = damping_update_name(s.damping_update);
  j["poincare_period_kind"] = s.poincare_period_kind;
  j["poincare_period_s"] = s.poincare_period_s;
  j["poincare_period_mesh_periods"] = s.poincare_mesh_periods;
  return j;
}

SweepDirection direction_named(const std::string& name, const std::string& where) {
  if (name == to_string(SweepDirection::up)) return SweepDirection::up;
  if (name == to_string(SweepDirection::down)) return SweepDirection::down;
  throw InputError("merge", where + ": direction " + name, "up or down");
}

// The record of a spec block; throws InputError naming `file` when a key is missing or of
// another type.
SteadySweepRecord spec_record(const Json& j, const std::string& file) {
  try {
    SteadySweepRecord s;
    s.case_name = j.at("case").get<std::string>();
    s.case_key_hash = j.at("case_key_fnv1a64").get<std::string>();
    s.vary = j.at("vary").get<std::string>();
    s.from_si = j.at("from_si").get<double>();
    s.to_si = j.at("to_si").get<double>();
    s.points = j.at("points").get<int>();
    s.vary2 = j.at("vary2").get<std::string>();
    if (!s.vary2.empty()) {
      s.from2_si = j.at("from2_si").get<double>();
      s.to2_si = j.at("to2_si").get<double>();
    }
    s.lines = j.at("lines").get<int>();
    if (s.points < 1 || s.lines < 1) {
      throw InputError(
          "merge",
          file + ": points " + std::to_string(s.points) + ", lines " + std::to_string(s.lines),
          "a spec of at least one point and one line");
    }
    std::stringstream list(j.at("directions").get<std::string>());
    for (std::string d; std::getline(list, d, ',');) {
      s.directions.push_back(direction_named(d, file));
    }
    s.backlash_m = j.at("backlash_m").get<double>();
    s.unit = j.at("unit").get<std::string>();
    s.unit2 = j.at("unit2").get<std::string>();
    s.mesh_teeth = j.at("mesh_teeth").get<int>();
    if (j.contains("iso_resonance_speed_rad_s")) {
      IsoScale iso;
      iso.resonance_speed_rad_per_s = j.at("iso_resonance_speed_rad_s").get<double>();
      iso.resonance_speed_iso_stiffness_rad_per_s =
          j.at("iso_resonance_speed_iso_stiffness_rad_s").get<double>();
      iso.contact_ratio = j.at("iso_contact_ratio").get<double>();
      iso.line_load_n_per_m = j.at("iso_line_load_n_m").get<double>();
      iso.quasi_static_force_ratio = j.at("quasi_static_force_ratio").get<double>();
      s.iso = iso;
    }
    s.tolerance = j.at("tolerance").get<double>();
    s.steps_per_contact_period = j.at("steps_per_contact_period").get<double>();
    s.max_periods = j.at("max_periods").get<int>();
    const std::string update = j.at("damping_update").get<std::string>();
    const double code = parse_value(damping_update_field(), update, file + ": damping_update");
    s.damping_update = static_cast<DampingUpdate>(static_cast<int>(code));
    s.poincare_period_kind = j.at("poincare_period_kind").get<std::string>();
    s.poincare_period_s = j.at("poincare_period_s").get<std::array<double, 2>>();
    s.poincare_mesh_periods = j.at("poincare_period_mesh_periods").get<std::array<long long, 2>>();
    return s;
  } catch (const Json::exception& e) {
    throw InputError("merge", file + ": " + e.what(), kSweepFile);
  }
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("merge", path.string(), "a readable file written by gearimpact sweep");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t begin = 0;
  while (true) {
    const std::size_t comma = line.find(',', begin);
    fields.push_back(line.substr(begin, comma - begin));
    if (comma == std::string::npos) return fields;
    begin = comma + 1;
  }
}

// A number as the files write it (format_data_number): finite, read back to the same double,
// nothing before or after it.
double number_field(const std::string& text, const std::string& where) {
  std::size_t used = 0;
  double value = 0.0;
  const bool starts_well =
      !text.empty() && (std::isdigit(static_cast<unsigned char>(text.front())) != 0 ||
                        text.front() == '-' || text.front() == '.');
  if (starts_well) {
    try {
      value = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
  }
  if (!starts_well || used != text.size() || !std::isfinite(value)) {
    throw InputError("merge", where + ": " + text, "a finite number written by gearimpact sweep");
  }
  return value;
}

std::optional<double> optional_field(const std::string& text, const std::string& where) {
  if (text.empty()) return std::nullopt;
  return number_field(text, where);
}

// A whole number in [0, below): a key field of a row, or a period.
int integer_field(const std::string& text, const std::string& where, int below) {
  const bool digits =
      !text.empty() && text.size() <= 10 &&
      std::all_of(text.begin(), text.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
  const long long value = digits ? std::stoll(text) : -1;
  if (value < 0 || value >= below) {
    throw InputError(
        "merge", where + ": " + text,
        "an integer in [0, " + std::to_string(below) + ") written by gearimpact sweep");
  }
  return static_cast<int>(value);
}

Regime regime_named(const std::string& name, const std::string& where) {
  for (Regime r :
       {Regime::no_impact, Regime::single_sided, Regime::double_sided, Regime::no_contact}) {
    if (to_string(r) == name) return r;
  }
  throw InputError("merge", where + ": regime " + name, "NI, SS, DS or NC");
}

using Key = std::tuple<int, int, int>;

Key key_of(const SweepPointResult& r) {
  return {r.line, r.direction == SweepDirection::up ? 0 : 1, r.index};
}

std::string key_text(int line, const std::string& direction, int index) {
  return "(line " + std::to_string(line) + ", direction " + direction + ", index " +
         std::to_string(index) + ")";
}

// The lines of a file after its header, each with its place ("FILE:LINE") for messages. Throws
// InputError naming the file and line when the header is not `header`, a line ends in CR (a
// file passed through a Windows tool), or the last line has no end (a file cut short).
std::vector<std::pair<std::string, std::string>> data_lines(const std::string& text,
                                                            const std::string& name,
                                                            const char* header) {
  std::vector<std::pair<std::string, std::string>> lines;
  std::size_t begin = 0;
  for (std::size_t number = 1; begin < text.size(); ++number) {
    const std::size_t end = text.find('\n', begin);
    const std::string where = name + ":" + std::to_string(number);
    if (end == std::string::npos) {
      throw InputError("merge", where + ": " + text.substr(begin),
                       "a line ended by a newline: the file is cut short");
    }
    std::string line = text.substr(begin, end - begin);
    if (!line.empty() && line.back() == '\r') {
      throw InputError("merge", where,
                       "a line ended by LF alone, as gearimpact writes it (not CRLF)");
    }
    if (number == 1) {
      if (line + "\n" != header) throw InputError("merge", where + ": " + line, header);
    } else {
      lines.emplace_back(where, std::move(line));
    }
    begin = end + 1;
  }
  if (begin == 0) throw InputError("merge", name + ": empty", header);
  return lines;
}

// The key fields of a row of either file, checked against the spec: a line and index of its
// grids, one of its directions, and the value of the grid at that index (to within the rounding
// of the grid's arithmetic).
SweepPointResult row_key(const std::vector<std::string>& f, const SteadySweepRecord& spec,
                         const std::string& where) {
  SweepPointResult r;
  r.line = integer_field(f[0], where, spec.lines);
  r.direction = direction_named(f[1], where);
  if (std::find(spec.directions.begin(), spec.directions.end(), r.direction) ==
      spec.directions.end()) {
    throw InputError("merge", where + ": direction " + f[1],
                     "a direction of its spec (" + directions_text(spec.directions) + ")");
  }
  r.index = integer_field(f[2], where, spec.points);
  r.value_si = number_field(f[3], where);
  const double low = std::min(spec.from_si, spec.to_si);
  const double high = std::max(spec.from_si, spec.to_si);
  const double slack = 1e-9 * std::max(std::abs(low), std::abs(high));
  if (r.value_si < low - slack || r.value_si > high + slack) {
    throw InputError(
        "merge", where + ": value " + f[3],
        "a value of its spec's grid [" + format_number(low) + ", " + format_number(high) + "]");
  }
  // The value at its index of the grid the sweep ran (sweep_grid), to within the same slack.
  const double on_grid = spec.points == 1 ? spec.from_si
                         : r.index + 1 == spec.points
                             ? spec.to_si
                             : spec.from_si + (spec.to_si - spec.from_si) *
                                                  static_cast<double>(r.index) / (spec.points - 1);
  if (std::abs(r.value_si - on_grid) > slack) {
    throw InputError("merge", where + ": value " + f[3],
                     "the value of its spec's grid at index " + std::to_string(r.index) + ", " +
                         format_number(on_grid));
  }
  return r;
}

struct PoincareRow {
  Key key;
  std::string where;
  std::string line;
  PoincareSample sample;
};

// The first key of the spec blocks that differs, for the merge's message.
std::string first_difference(const Json& a, const Json& b) {
  for (const auto& [key, value] : a.items()) {
    if (!b.contains(key) || b.at(key) != value) return key;
  }
  for (const auto& [key, value] : b.items()) {
    if (!a.contains(key)) return key;
  }
  return "";
}

}  // namespace

std::string sweep_csv(const std::vector<SweepPointResult>& rows) {
  std::string csv = kSweepHeader;
  for (const SweepPointResult& r : rows) {
    const SteadyPoint& p = r.point;
    csv += key_fields(r) + "," + (p.converged ? to_string(p.regime) : "") + "," + period_label(p) +
           "," + (p.converged ? "true" : "false") + "," + optional_number(p.dte_mean_m) + "," +
           optional_number(p.dte_amplitude_m) + "," + optional_number(p.dte_rms_m) + "," +
           optional_number(p.s_min_m) + "," + optional_number(p.s_max_m) + "," +
           optional_number(p.dte_contact_mean_m) + "," + optional_number(p.dte_contact_min_m) +
           "," + optional_number(p.dte_contact_max_m) + "," + optional_number(p.dynamic_factor) +
           "," + optional_number(p.impacts_drive_per_period) + "," +
           optional_number(p.impacts_coast_per_period) + "," + optional_number(p.w1_mean_rad_s) +
           "," + optional_number(p.w2_mean_rad_s) + "," + optional_number(p.pinion_rpm) + "," +
           optional_number(p.mesh_frequency_hz) + "\n";
  }
  return csv;
}

std::string poincare_csv(const std::vector<SweepPointResult>& rows) {
  std::string csv = kPoincareHeader;
  for (const SweepPointResult& r : rows) {
    const std::string key = key_fields(r);
    for (const PoincareSample& s : r.point.poincare) {
      csv += key + "," + format_data_number(s.s_m) + "," + format_data_number(s.s_rate_m_s) + "\n";
    }
  }
  return csv;
}

std::string sweep_summary_json(const SteadySweep& sweep) {
  Json j;
  j["spec"] = spec_json(sweep.spec);
  if (sweep.shard) {
    j["shard"] = std::to_string(sweep.shard->k) + "/" + std::to_string(sweep.shard->n);
  }
  std::size_t converged = 0;
  std::map<std::string, std::size_t> regimes;
  for (const SweepPointResult& r : sweep.rows) {
    if (!r.point.converged) continue;
    ++converged;
    ++regimes[to_string(r.point.regime)];
  }
  j["points_written"] = sweep.rows.size();
  j["points_converged"] = converged;
  j["regimes"] = Json::object();
  for (const auto& [name, n] : regimes) j["regimes"][name] = n;
  j["jumps"] = Json::array();
  for (const SweepJump& jump : sweep_jumps(sweep.rows)) {
    Json one;
    one["line"] = jump.line;
    one["direction"] = to_string(jump.direction);
    one["from_si"] = jump.from_si;
    one["to_si"] = jump.to_si;
    one["amplitude_before_m"] = jump.amplitude_before_m;
    one["amplitude_after_m"] = jump.amplitude_after_m;
    one["regime_before"] = to_string(jump.regime_before);
    one["regime_after"] = to_string(jump.regime_after);
    j["jumps"].push_back(one);
  }
  j["contact_loss"] = Json::array();
  for (const ContactChange& change : contact_changes(sweep.rows)) {
    Json one;
    one["line"] = change.line;
    one["direction"] = to_string(change.direction);
    one["change"] = change.lost ? "lost" : "regained";
    one["from_si"] = change.from_si;
    one["to_si"] = change.to_si;
    one["regime_before"] = to_string(change.regime_before);
    one["regime_after"] = to_string(change.regime_after);
    j["contact_loss"].push_back(one);
  }
  j["warnings"] = sweep.warnings;
  return j.dump(2) + "\n";
}

void write_sweep_folder(const std::filesystem::path& dir, const SteadySweep& sweep) {
  std::filesystem::create_directories(dir);
  write_file_atomically((dir / "sweep.csv").string(), sweep_csv(sweep.rows));
  write_file_atomically((dir / "poincare.csv").string(), poincare_csv(sweep.rows));
  write_file_atomically((dir / "summary.json").string(), sweep_summary_json(sweep));
}

namespace {

std::vector<PoincareRow> read_poincare_rows(const std::filesystem::path& file,
                                            const SteadySweepRecord& spec) {
  std::vector<PoincareRow> rows;
  for (const auto& [where, line] : data_lines(read_text(file), file.string(), kPoincareHeader)) {
    const std::vector<std::string> f = split(line);
    if (f.size() != 6) throw InputError("merge", where + ": " + line, "a row of 6 fields");
    const SweepPointResult r = row_key(f, spec, where);
    rows.push_back(
        {key_of(r), where, line, {number_field(f[4], where), number_field(f[5], where)}});
  }
  return rows;
}

}  // namespace

std::vector<SweepPointResult> parse_sweep_csv(const std::string& text, const std::string& file,
                                              const SteadySweepRecord& spec) {
  std::vector<SweepPointResult> rows;
  for (const auto& [where, line] : data_lines(text, file, kSweepHeader)) {
    const std::vector<std::string> f = split(line);
    if (f.size() != kSweepColumns) {
      throw InputError("merge", where + ": " + line,
                       "a row of " + std::to_string(kSweepColumns) + " fields");
    }
    SweepPointResult r = row_key(f, spec, where);
    SteadyPoint& p = r.point;
    if (f[6] != "true" && f[6] != "false") {
      throw InputError("merge", where + ": converged " + f[6], "true or false");
    }
    p.converged = f[6] == "true";
    if (!f[4].empty()) p.regime = regime_named(f[4], where);
    if (f[5] == "aperiodic") {
      p.verdict = PeriodicityVerdict::aperiodic;
    } else if (!f[5].empty()) {
      p.verdict = PeriodicityVerdict::periodic;
      p.period = integer_field(f[5], where, std::numeric_limits<int>::max());
    }
    p.dte_mean_m = optional_field(f[7], where);
    p.dte_amplitude_m = optional_field(f[8], where);
    p.dte_rms_m = optional_field(f[9], where);
    p.s_min_m = optional_field(f[10], where);
    p.s_max_m = optional_field(f[11], where);
    p.dte_contact_mean_m = optional_field(f[12], where);
    p.dte_contact_min_m = optional_field(f[13], where);
    p.dte_contact_max_m = optional_field(f[14], where);
    p.dynamic_factor = optional_field(f[15], where);
    p.impacts_drive_per_period = optional_field(f[16], where);
    p.impacts_coast_per_period = optional_field(f[17], where);
    p.w1_mean_rad_s = optional_field(f[18], where);
    p.w2_mean_rad_s = optional_field(f[19], where);
    p.pinion_rpm = optional_field(f[20], where);
    p.mesh_frequency_hz = optional_field(f[21], where);
    // The last two fields follow from w1_mean (pinion_rpm = 60 w1 / (2 pi), mesh_frequency_hz =
    // z1 |w1| / (2 pi)): both present with it, and their ratio the whole number z1 / 60 (to
    // 1e-12 relative, far above the rounding of the 17 digits written); a row cut short fails.
    if (p.w1_mean_rad_s) {
      const bool whole = p.pinion_rpm && p.mesh_frequency_hz && *p.pinion_rpm != 0.0 && [&] {
        const double z1 = *p.mesh_frequency_hz * 60.0 / std::abs(*p.pinion_rpm);
        return z1 >= 1.0 && std::abs(z1 - std::round(z1)) <= 1e-12 * z1;
      }();
      if (!whole) {
        throw InputError("merge", where + ": " + line,
                         "a whole row: pinion_rpm and mesh_frequency_hz written with w1_mean_rad_s "
                         "and mesh_frequency_hz = z1 |pinion_rpm| / 60 (the row is cut short)");
      }
    }
    rows.push_back(std::move(r));
  }
  return rows;
}

SteadySweep merge_sweep_folders(const std::vector<std::filesystem::path>& dirs) {
  if (dirs.empty()) throw InputError("merge", "no folder", "one or more sweep output folders");
  std::optional<Json> spec;
  SteadySweepRecord record;
  std::map<Key, SweepPointResult> rows;
  std::vector<std::string> warnings;
  for (const std::filesystem::path& dir : dirs) {
    const std::string input = dir.string();
    const std::filesystem::path summary_file = dir / "summary.json";
    Json summary;
    try {
      summary = Json::parse(read_text(summary_file));
    } catch (const Json::exception& e) {
      throw InputError("merge", summary_file.string() + ": " + e.what(), kSweepFile);
    }
    if (!summary.is_object() || !summary.contains("spec") || !summary["spec"].is_object()) {
      throw InputError("merge", summary_file.string(), "a summary.json with its spec");
    }
    if (!spec) {
      spec = summary["spec"];
      record = spec_record(*spec, summary_file.string());
      // The warnings are of the base case and the spec, which every shard shares.
      if (summary.contains("warnings") && summary["warnings"].is_array()) {
        for (const Json& w : summary["warnings"]) {
          if (w.is_string()) warnings.push_back(w.get<std::string>());
        }
      }
    }
    if (summary["spec"] != *spec) {
      throw InputError("merge", input,
                       "a shard of the same sweep as " + dirs.front().string() + " (its spec's \"" +
                           first_difference(*spec, summary["spec"]) + "\" differs)");
    }
    std::set<Key> here;
    const std::filesystem::path sweep_file = dir / "sweep.csv";
    for (SweepPointResult& r :
         parse_sweep_csv(read_text(sweep_file), sweep_file.string(), record)) {
      const Key key = key_of(r);
      if (rows.count(key) > 0) {
        throw InputError("merge",
                         "row " + key_text(r.line, to_string(r.direction), r.index) + " in " +
                             input + " and an earlier folder",
                         "each (line, direction, index) in one shard only");
      }
      here.insert(key);
      rows.emplace(key, std::move(r));
    }
    for (PoincareRow& p : read_poincare_rows(dir / "poincare.csv", record)) {
      if (here.count(p.key) == 0) {
        throw InputError("merge", p.where + ": " + p.line, "a sample of a point of its sweep.csv");
      }
      rows[p.key].point.poincare.push_back(p.sample);
    }
  }
  SteadySweep merged;
  merged.spec = record;
  merged.warnings = warnings;
  for (int l = 0; l < merged.spec.lines; ++l) {
    for (SweepDirection d : merged.spec.directions) {
      for (int i = 0; i < merged.spec.points; ++i) {
        if (rows.count({l, d == SweepDirection::up ? 0 : 1, i}) == 0) {
          throw InputError("merge", "no row " + key_text(l, to_string(d), i),
                           "every (line, direction, index) of the sweep: a shard is missing");
        }
      }
    }
  }
  for (auto& [key, r] : rows) merged.rows.push_back(std::move(r));
  return merged;
}

}  // namespace gearimpact
