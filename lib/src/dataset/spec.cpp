#include "gearimpact/dataset/spec.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <toml.hpp>

#include "../io/toml_values.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/mat_image.hpp"
#include "gearimpact/io/sha256.hpp"
#include "gearimpact/signals/recorder.hpp"
#include "gearimpact/steady/sweep.hpp"

namespace gearimpact::dataset {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kMostSpecBytes = std::size_t{1} << 20;
// Fewer samples than this make no record a study could use (a spectrum of a few lines).
constexpr double kLeastSamples = 16;
// The recorder's sections are discretised for a piecewise-constant input: their error,
// (2 pi f / fs)^2, is small only below fs / 4 (signals::filter_sections refuses above it).
constexpr double kMostSectionFraction = 0.25;

}  // namespace

const std::vector<RecorderKey>& recorder_keys() {
  static const std::vector<RecorderKey> keys{
      {"oversample", std::nullopt, "", 1.0, 64.0, true, true,
       "the simulation's samples per recorded sample, 1 to 64: the sensor sampled and filtered at "
       "oversample x dataset.sample_rate, then decimated to it by the anti-alias FIR (Kaiser, "
       "100 dB, alias-free below 0.4 x dataset.sample_rate) (default 1: no decimator)",
       [](RecorderSettings& r, double v) { r.oversample = static_cast<int>(v); }},
      {"accelerometer_resonance", Dimension::frequency, "Hz", 0.0, kInf, false, false,
       "an accelerometer's mounted resonance, w^2 / (s^2 + 2 zeta w s + w^2), below a quarter of "
       "the sample rate (default: none)",
       [](RecorderSettings& r, double v) { r.accelerometer_resonance_hz = v; }},
      {"accelerometer_damping", std::nullopt, "", 0.0, 1.0, false, false,
       "the accelerometer's damping ratio, in (0, 1) (default 0.02)",
       [](RecorderSettings& r, double v) { r.accelerometer_damping = v; }},
      {"path_modes", std::nullopt, "", 0.0, 32.0, true, true,
       "modes of a seeded transfer path, 0 to 32 (default 0: none)",
       [](RecorderSettings& r, double v) { r.path_modes = static_cast<int>(v); }},
      {"path_band_low", Dimension::frequency, "Hz", 0.0, kInf, false, false,
       "the path modes' lowest frequency (log-uniform draws; default 1 kHz)",
       [](RecorderSettings& r, double v) { r.path_band_low_hz = v; }},
      {"path_band_high", Dimension::frequency, "Hz", 0.0, kInf, false, false,
       "the path modes' highest frequency, below a quarter of the sample rate (default 8 kHz)",
       [](RecorderSettings& r, double v) { r.path_band_high_hz = v; }},
      {"path_damping_low", std::nullopt, "", 0.0, 1.0, false, false,
       "the path modes' least damping ratio (uniform draws; default 0.01)",
       [](RecorderSettings& r, double v) { r.path_damping_low = v; }},
      {"path_damping_high", std::nullopt, "", 0.0, 1.0, false, false,
       "the path modes' largest damping ratio (default 0.05)",
       [](RecorderSettings& r, double v) { r.path_damping_high = v; }},
      {"noise_snr", std::nullopt, "dB", -100.0, 200.0, true, false,
       "white Gaussian noise at this SNR, dB: sigma = RMS(x - mean) 10^(-SNR/20) (default: none)",
       [](RecorderSettings& r, double v) { r.noise_snr_db = v; }},
      {"adc_range", std::nullopt, "", 0.0, kInf, false, false,
       "an ADC's full scale in the sensor's unit: clip at +-range, counted (default: none)",
       [](RecorderSettings& r, double v) { r.adc_range = v; }},
      {"adc_bits", std::nullopt, "", 0.0, 32.0, true, true,
       "the ADC's resolution, LSB = 2 range / 2^bits, 0: no rounding (default 16)",
       [](RecorderSettings& r, double v) { r.adc_bits = static_cast<int>(v); }},
      {"seed", std::nullopt, "", 0.0, 9.0e15, true, true,
       "mixed into every record's noise and path seeds (default 0)",
       [](RecorderSettings& r, double v) { r.seed = static_cast<std::int64_t>(v); }},
  };
  return keys;
}

const char* record_extension(RecordFormat format) {
  switch (format) {
    case RecordFormat::npz:
      return ".npz";
    case RecordFormat::mat:
      return ".mat";
    case RecordFormat::hdf5:
      break;
  }
  return ".h5";
}

Oversampling oversampling(double sample_rate_hz, const RecorderSettings& recorder,
                          long long settle_samples, long long samples) {
  Oversampling o;
  o.factor = recorder.oversample;
  o.rate_hz = static_cast<double>(o.factor) * sample_rate_hz;
  if (o.factor == 1) {
    o.last_fine = settle_samples + samples - 1;
    return o;
  }
  o.filter = signals::kaiser_low_pass(o.rate_hz, signals::kAliasFreeFraction * sample_rate_hz,
                                      signals::kStopbandFraction * sample_rate_hz,
                                      signals::kAntiAliasAttenuationDb);
  const auto half = static_cast<long long>(o.filter->order / 2);
  o.lead = (half + o.factor - 1) / o.factor;
  o.last_fine = o.factor * (settle_samples + samples - 1) + half;
  return o;
}

const std::vector<ChannelInfo>& truth_channels() {
  static const std::vector<ChannelInfo> channels{
      {"theta1_rad", "rad", "the pinion's angle (unwrapped)"},
      {"theta2_rad", "rad", "the wheel's angle (unwrapped)"},
      {"w1_rad_s", "rad/s", "the pinion's speed"},
      {"w2_rad_s", "rad/s", "the wheel's speed"},
      {"drive_force_N", "N", "the normal force on the drive flanks, summed over the pairs"},
      {"coast_force_N", "N", "the normal force on the coast flanks, summed over the pairs"},
      {"dte_m", "m", "the dynamic transmission error s - B along the drive line"},
  };
  return channels;
}

namespace {

// (Y dsigma sqrt(pi))^m with dsigma in MPa: dK = that^(1/m) sqrt(a) in MPa sqrt(m).
double paris_scale(const Trajectory& t) {
  return std::pow(t.geometry_factor * t.stress_range_pa * 1e-6 * std::sqrt(pi), t.paris_m);
}

}  // namespace

double paris_depth_m(const Trajectory& t, double cycles) {
  const double k = t.paris_c * paris_scale(t);
  if (t.paris_m == 2.0) return t.initial_m * std::exp(k * cycles);
  const double e = 1.0 - t.paris_m / 2.0;
  return std::pow(std::pow(t.initial_m, e) + e * k * cycles, 1.0 / e);
}

double paris_cycles(const Trajectory& t, double depth_m) {
  const double k = t.paris_c * paris_scale(t);
  if (t.paris_m == 2.0) return std::log(depth_m / t.initial_m) / k;
  const double e = 1.0 - t.paris_m / 2.0;
  return (std::pow(depth_m, e) - std::pow(t.initial_m, e)) / (e * k);
}

std::uint64_t record_seed(std::uint64_t set_seed, std::size_t condition, int replicate) {
  using signals::splitmix64;
  return splitmix64(splitmix64(splitmix64(set_seed) ^ static_cast<std::uint64_t>(condition)) ^
                    static_cast<std::uint64_t>(replicate));
}

namespace {

// ---- reading the spec's TOML ----

// A value's text as --set takes it: a string as written, a number in SI.
std::string as_text(const toml::value& v, const std::string& name, const std::string& allowed) {
  if (v.is_string()) return v.as_string().str;
  if (v.is_integer()) return std::to_string(v.as_integer());
  if (v.is_floating()) return shortest_decimal(v.as_floating());
  throw InputError(name, toml_written(v), allowed);
}

// A quantity ("20 kHz", or a plain number in SI).
double quantity(const toml::value& v, Dimension dimension, const std::string& name) {
  if (v.is_integer()) return static_cast<double>(v.as_integer());
  if (v.is_floating()) return v.as_floating();
  if (v.is_string()) return parse_plain_or_quantity(v.as_string().str, dimension, name);
  throw InputError(name, toml_written(v),
                   "a quantity: a plain number in SI or a string with a unit of " +
                       std::string(describe(dimension)));
}

double number(const toml::value& v, const std::string& name, const std::string& allowed) {
  if (v.is_integer()) return static_cast<double>(v.as_integer());
  if (v.is_floating()) return v.as_floating();
  throw InputError(name, toml_written(v), allowed);
}

long long whole(const toml::value& v, const std::string& name, long long lower, long long upper) {
  const std::string allowed =
      "an integer in [" + std::to_string(lower) + ", " + std::to_string(upper) + "]";
  if (!v.is_integer() || v.as_integer() < lower || v.as_integer() > upper) {
    throw InputError(name, toml_written(v), allowed);
  }
  return v.as_integer();
}

std::string text(const toml::value& v, const std::string& name, const std::string& allowed) {
  if (!v.is_string()) throw InputError(name, toml_written(v), allowed);
  return v.as_string().str;
}

// Refuses keys of `table` outside `known`, naming them as section.key.
void only_keys(const toml::value& table, const std::string& section,
               const std::vector<std::string>& known) {
  for (const auto& [key, value] : table.as_table()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InputError(section.empty() ? key : section + "." + key, toml_written(value),
                       "a key of " +
                           (section.empty() ? std::string("the spec") : "[" + section + "]") +
                           ": " + list);
    }
  }
}

const toml::value* lookup(const toml::value& table, const std::string& key) {
  const auto& t = table.as_table();
  const auto it = t.find(key);
  return it == t.end() ? nullptr : &it->second;
}

const toml::value& table_at(const toml::value& root, const std::string& key, bool required) {
  static const toml::value empty = toml::table{};
  const toml::value* v = lookup(root, key);
  if (v == nullptr) {
    if (required) throw InputError(key, "missing", "a [" + key + "] table");
    return empty;
  }
  if (!v->is_table()) throw InputError(key, toml_written(*v), "a [" + key + "] table");
  return *v;
}

// ---- addressing a key as --set does ----

// "faults[2].depth" as (2, "depth"); nothing for another key.
std::optional<std::pair<std::size_t, std::string>> fault_address(const std::string& key) {
  if (key.rfind("faults[", 0) != 0) return std::nullopt;
  const std::size_t close = key.find("].");
  if (close == std::string::npos || close <= 7) return std::nullopt;
  const std::string digits = key.substr(7, close - 7);
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) ||
      digits.size() > 6) {
    return std::nullopt;
  }
  return std::make_pair(static_cast<std::size_t>(std::stoul(digits)), key.substr(close + 2));
}

const RecorderKey* recorder_key(const std::string& key) {
  if (key.rfind("recorder.", 0) != 0) return nullptr;
  const std::string name = key.substr(9);
  for (const RecorderKey& k : recorder_keys()) {
    if (k.key == name) return &k;
  }
  return nullptr;
}

std::string recorder_allowed(const RecorderKey& k) {
  const std::string upper = std::isinf(k.upper) ? std::string("inf") : shortest_decimal(k.upper);
  std::string range = (k.integer ? "an integer in " : "a value in ") +
                      std::string(k.closed ? "[" : "(") + shortest_decimal(k.lower) + ", " + upper +
                      (k.closed ? "]" : ")");
  if (!k.unit.empty()) range += " " + std::string(k.unit);
  if (k.dimension) range += " (or with a unit)";
  return range + ": " + std::string(k.help);
}

double recorder_value(const RecorderKey& k, const std::string& written, const std::string& name) {
  double v = 0.0;
  if (k.dimension) {
    v = parse_plain_or_quantity(written, *k.dimension, name);
  } else {
    std::string t = written;
    // "30 dB": a plain row's unit may be said, and is not converted.
    const std::string unit(k.unit);
    if (!unit.empty() && t.size() > unit.size() &&
        t.compare(t.size() - unit.size(), unit.size(), unit) == 0) {
      t = t.substr(0, t.size() - unit.size());
    }
    char* end = nullptr;
    v = std::strtod(t.c_str(), &end);
    while (end != nullptr && *end == ' ') ++end;
    if (t.empty() || end == nullptr || *end != '\0') {
      throw InputError(name, written, recorder_allowed(k));
    }
  }
  const bool bad = !std::isfinite(v) ||
                   (k.closed ? v < k.lower || v > k.upper : v <= k.lower || v >= k.upper) ||
                   (k.integer && v != std::floor(v));
  if (bad) throw InputError(name, written, recorder_allowed(k));
  return v;
}

struct KeyInfo {
  std::string unit;
  bool numeric = true;
  bool integer = false;
  std::optional<Dimension> dimension;
};

// What a factor's key is, checked against the base case: an unknown key, a list key, a fault
// the case does not have, or a key the case does not read are refused naming `name`.
KeyInfo key_info(const SimulationCase& base, const std::string& key, const std::string& name) {
  if (key.rfind("recorder.", 0) == 0) {
    const RecorderKey* k = recorder_key(key);
    if (k == nullptr) {
      std::string list;
      for (const RecorderKey& r : recorder_keys()) {
        list += (list.empty() ? "" : ", ") + std::string("recorder.") + std::string(r.key);
      }
      throw InputError(std::vector<Problem>{
          refused_problem(name, key, "no such key", "a key of [recorder]: " + list)});
    }
    return {std::string(k->unit), true, k->integer, k->dimension};
  }
  const Field* field = nullptr;
  if (const auto fault = fault_address(key)) {
    if (fault->first >= base.faults.size()) {
      throw InputError(name, key,
                       "a fault of the base case: it has " + std::to_string(base.faults.size()) +
                           " [[faults]] table(s), faults[0] ... (add the fault to the base case, "
                           "its size then a factor)");
    }
    SimulationCase one;
    one.faults = {base.faults[fault->first]};
    std::string keys;
    for (const Field& row : fault_schema()) {
      if (keys.find(std::string(row.key)) == std::string::npos) {
        keys += (keys.empty() ? "" : ", ") + std::string(row.key);
      }
      if (row.key == fault->second && fault_row_applies(row, one)) field = &row;
    }
    if (field == nullptr) {
      throw InputError(std::vector<Problem>{
          refused_problem(name, key, "no such key for this fault's kind",
                          "a key of faults[" + std::to_string(fault->first) +
                              "] that its kind reads; the keys of [[faults]]: " + keys)});
    }
  } else {
    field = find_field(key);
    if (field == nullptr) {
      const std::optional<std::string> nearest = nearest_key(key);
      throw InputError(std::vector<Problem>{refused_problem(
          name, key, "no such key",
          "a key of the case schema as --set names it (`gearimpact schema`), faults[i].key, or "
          "recorder.key",
          nearest ? "did you mean " + *nearest + "?" : std::string())});
    }
    if (!applies(*field, base)) {
      throw InputError(name, key,
                       "a key the base case reads: " + field->name() + " is used only with " +
                           std::string(field->section) + "." + field->only_when->text());
    }
  }
  if (is_list(field->kind)) {
    throw InputError(name, key, "a key of one value: a list key cannot be a factor");
  }
  KeyInfo info;
  info.numeric = field->kind == FieldKind::quantity || field->kind == FieldKind::number ||
                 field->kind == FieldKind::integer;
  info.integer = field->kind == FieldKind::integer;
  if (field->kind == FieldKind::quantity) {
    info.dimension = field->dimension;
    info.unit = std::string(units_of(field->dimension).front().symbol);
  }
  return info;
}

// Sets `key` of the condition from `written`, checked by its row; errors name `name`. Returns
// its value in SI (NaN for a choice or a name).
double set_key(SimulationCase& c, RecorderSettings& r, const std::string& key,
               const std::string& written, const std::string& name) {
  if (const RecorderKey* k = recorder_key(key)) {
    const double v = recorder_value(*k, written, name);
    k->set(r, v);
    return v;
  }
  if (const auto fault = fault_address(key)) {
    SimulationCase one;
    one.faults = {c.faults.at(fault->first)};
    for (const Field& row : fault_schema()) {
      if (row.key != fault->second || !fault_row_applies(row, one)) continue;
      const double v = parse_value(row, written, name);
      row.set(one, v);
      c.faults[fault->first] = one.faults.front();
      const bool numeric = row.kind == FieldKind::quantity || row.kind == FieldKind::number ||
                           row.kind == FieldKind::integer;
      return numeric ? v : std::nan("");
    }
    throw InputError(name, written, "a key this fault's kind reads");
  }
  const Field& field = *find_field(key);
  const bool numeric = field.kind == FieldKind::quantity || field.kind == FieldKind::number ||
                       field.kind == FieldKind::integer;
  if (!numeric) {
    set_field(c, key, written, name);
    return std::nan("");
  }
  // As sweep sets a swept value: a speed sets the pair rolling at it, a torque's mean moves the
  // other's so that they balance.
  const SimulationCase before = c;
  apply_sweep_value(c, before, key, parse_value(field, written, name));
  // A speed controller holds the speed a record is labelled with: its reference follows the
  // pinion's initial speed, and a reference sets the initial speeds.
  if (c.torque1.kind == Torque::Kind::speed_controlled) {
    if (key == "initial.w1" || key == "initial.w2") {
      set_sweep_value(c, "torque1.mean_speed", c.initial.w1_rad_per_s);
    } else if (key == "torque1.mean_speed") {
      const SimulationCase rolling = c;
      apply_sweep_value(c, rolling, "initial.w1", c.torque1.mean_speed_rad_per_s);
    }
  }
  return field.get(c);
}

std::pair<double, double> range_of(const toml::value& v, const KeyInfo& info,
                                   const std::string& name) {
  if (!v.is_array() || v.as_array().size() != 2) {
    throw InputError(name, toml_written(v), "[LOW, HIGH]: two values, LOW < HIGH");
  }
  const auto one = [&](const toml::value& e, const std::string& n) {
    if (info.dimension) return quantity(e, *info.dimension, n);
    if (e.is_string()) {
      std::string t = e.as_string().str;
      if (t.size() > 2 && t.compare(t.size() - 2, 2, "dB") == 0) t = t.substr(0, t.size() - 2);
      char* end = nullptr;
      const double x = std::strtod(t.c_str(), &end);
      while (end != nullptr && *end == ' ') ++end;
      if (t.empty() || *end != '\0') throw InputError(n, toml_written(e), "a number");
      return x;
    }
    return number(e, n, "a number");
  };
  const double low = one(v.as_array()[0], name + "[0]");
  const double high = one(v.as_array()[1], name + "[1]");
  if (!(low < high) || !std::isfinite(low) || !std::isfinite(high)) {
    throw InputError(name, toml_written(v.as_array()[0]) + ", " + toml_written(v.as_array()[1]),
                     "[LOW, HIGH]: two finite values, LOW < HIGH");
  }
  return {low, high};
}

}  // namespace

DatasetSpec parse_spec(std::string_view spec_text, const std::filesystem::path& folder,
                       std::string_view file_name) {
  return parse_spec_with_base(spec_text, folder, file_name, std::nullopt);
}

DatasetSpec parse_spec_with_base(std::string_view spec_text, const std::filesystem::path& folder,
                                 std::string_view file_name,
                                 const std::optional<std::string>& base_case_text) {
  DatasetSpec spec;
  spec.spec_text = std::string(spec_text);
  toml::value root;
  try {
    std::istringstream stream{std::string(spec_text)};
    root = toml::parse(stream, std::string(file_name));
  } catch (const std::exception& e) {
    std::string first = e.what();
    first = first.substr(0, first.find('\n'));
    throw InputError(std::string(file_name), "(not TOML)", "a TOML file: " + first);
  }
  only_keys(root, "", {"dataset", "base", "recorder", "factors", "design", "split", "trajectory"});

  // [dataset]
  const toml::value& d = table_at(root, "dataset", true);
  only_keys(
      d, "dataset",
      {"name", "seed", "duration", "settle", "replicates", "sample_rate", "start_angle", "format"});
  if (const toml::value* v = lookup(d, "format")) {
    const std::string allowed =
        std::string(
            "\"hdf5\" (one HDF5 file per record, the default), \"npz\" (one NumPy "
            "archive of .npy members per record)") +
        (mat_files_available() ? " or \"mat\" (one MATLAB v5 MAT-file per record)"
                               : "; \"mat\" (MATLAB v5) needs a build with libmatio "
                                 "(Debian: libmatio-dev)");
    const std::string f = text(*v, "dataset.format", allowed);
    if (f == "hdf5") {
      spec.format = RecordFormat::hdf5;
    } else if (f == "npz") {
      spec.format = RecordFormat::npz;
    } else if (f == "mat" && mat_files_available()) {
      spec.format = RecordFormat::mat;
    } else {
      throw InputError("dataset.format", toml_written(*v), allowed);
    }
  }
  if (const toml::value* v = lookup(d, "start_angle")) {
    const std::string a = text(*v, "dataset.start_angle", "\"random\" or \"case\"");
    if (a != "random" && a != "case") {
      throw InputError("dataset.start_angle", toml_written(*v),
                       "\"random\" (a seeded mesh phase per record, the default) or \"case\" "
                       "(the base case's angles)");
    }
    spec.random_start = a == "random";
  }
  const auto required = [&](const toml::value& t, const std::string& section,
                            const std::string& key) -> const toml::value& {
    const toml::value* v = lookup(t, key);
    if (v == nullptr) throw InputError(section + "." + key, "missing", "required");
    return *v;
  };
  spec.name = lookup(d, "name") ? text(*lookup(d, "name"), "dataset.name", "a name") : "dataset";
  if (const toml::value* s = lookup(d, "seed")) {
    spec.seed = static_cast<std::uint64_t>(
        whole(*s, "dataset.seed", 0, std::numeric_limits<long long>::max()));
  }
  spec.duration_s =
      quantity(required(d, "dataset", "duration"), Dimension::time, "dataset.duration");
  spec.settle_s = quantity(required(d, "dataset", "settle"), Dimension::time, "dataset.settle");
  spec.sample_rate_hz =
      quantity(required(d, "dataset", "sample_rate"), Dimension::frequency, "dataset.sample_rate");
  if (!(spec.sample_rate_hz > 0.0) || !std::isfinite(spec.sample_rate_hz)) {
    throw InputError("dataset.sample_rate", toml_written(*lookup(d, "sample_rate")),
                     "a frequency > 0 Hz");
  }
  if (!(spec.duration_s * spec.sample_rate_hz >= kLeastSamples) ||
      !std::isfinite(spec.duration_s)) {
    throw InputError("dataset.duration", toml_written(*lookup(d, "duration")),
                     "a time of at least 16 samples (16 / sample_rate = " +
                         shortest_decimal(kLeastSamples / spec.sample_rate_hz) + " s)");
  }
  if (!(spec.settle_s * spec.sample_rate_hz >= 1.0) || !std::isfinite(spec.settle_s)) {
    throw InputError("dataset.settle", toml_written(*lookup(d, "settle")),
                     "a time of at least one sample interval (" +
                         shortest_decimal(1.0 / spec.sample_rate_hz) +
                         " s): the start's transient is discarded");
  }
  if (const toml::value* r = lookup(d, "replicates")) {
    spec.replicates = static_cast<int>(whole(*r, "dataset.replicates", 1, 1000000));
  }

  // [base]
  const toml::value& b = table_at(root, "base", true);
  only_keys(b, "base", {"case"});
  const std::string case_name =
      text(required(b, "base", "case"), "base.case", "a case file's path");
  spec.base_case_path = folder / case_name;
  if (base_case_text) {
    spec.base_case_text = *base_case_text;
  } else {
    std::ifstream in(spec.base_case_path, std::ios::binary);
    if (!in) {
      throw InputError("base.case", "\"" + case_name + "\"",
                       "a readable case file (relative to the spec's folder: " +
                           spec.base_case_path.string() + ")");
    }
    std::ostringstream all;
    all << in.rdbuf();
    spec.base_case_text = all.str();
  }
  try {
    spec.base = parse_case(spec.base_case_text, spec.base_case_path.string());
  } catch (const CaseFileError& e) {
    throw InputError(std::vector<Problem>{refused_problem(
        "base.case", "\"" + case_name + "\"", std::string("not a valid case: ") + e.what(),
        "a case file this program reads (gearimpact check-case)")});
  }

  // [recorder]
  const toml::value& r = table_at(root, "recorder", false);
  {
    std::vector<std::string> known{"noise_exact", "path"};
    for (const RecorderKey& k : recorder_keys()) known.emplace_back(k.key);
    only_keys(r, "recorder", known);
    for (const RecorderKey& k : recorder_keys()) {
      const toml::value* v = lookup(r, std::string(k.key));
      if (v == nullptr) continue;
      const std::string name = "recorder." + std::string(k.key);
      k.set(spec.recorder, recorder_value(k, as_text(*v, name, recorder_allowed(k)), name));
    }
    if (const toml::value* v = lookup(r, "noise_exact")) {
      if (!v->is_boolean())
        throw InputError("recorder.noise_exact", toml_written(*v), "true or false");
      spec.recorder.noise_exact = v->as_boolean();
    }
    if (const toml::value* v = lookup(r, "path")) {
      const std::string p = text(*v, "recorder.path", "\"fixed\" or \"per-record\"");
      if (p != "fixed" && p != "per-record") {
        throw InputError("recorder.path", toml_written(*v),
                         "\"fixed\" (one path for the set) or \"per-record\"");
      }
      spec.recorder.path_per_record = p == "per-record";
    }
  }

  // [[factors]]
  if (const toml::value* fs = lookup(root, "factors")) {
    if (!fs->is_array()) throw InputError("factors", toml_written(*fs), "[[factors]] tables");
    for (std::size_t i = 0; i < fs->as_array().size(); ++i) {
      const toml::value& f = fs->as_array()[i];
      const std::string at = "factors[" + std::to_string(i) + "]";
      if (!f.is_table()) throw InputError(at, toml_written(f), "a [[factors]] table");
      only_keys(f, at, {"key", "levels", "range", "points"});
      Factor factor;
      factor.key = text(required(f, at, "key"), at + ".key", "a key as --set names it");
      for (const Factor& other : spec.factors) {
        if (other.key == factor.key) {
          throw InputError(at + ".key", factor.key, "a key of one factor only");
        }
      }
      const KeyInfo info = key_info(spec.base, factor.key, at + ".key");
      factor.unit = info.unit;
      factor.numeric = info.numeric;
      const toml::value* levels = lookup(f, "levels");
      const toml::value* range = lookup(f, "range");
      if ((levels == nullptr) == (range == nullptr)) {
        throw InputError(at, factor.key, "levels = [...] or range = [LOW, HIGH], one of them");
      }
      if (levels != nullptr) {
        if (!levels->is_array() || levels->as_array().empty()) {
          throw InputError(at + ".levels", toml_written(*levels), "a non-empty array of values");
        }
        for (std::size_t j = 0; j < levels->as_array().size(); ++j) {
          factor.levels.push_back(as_text(levels->as_array()[j],
                                          at + ".levels[" + std::to_string(j) + "]",
                                          "a value as a case file writes it"));
        }
        if (lookup(f, "points") != nullptr) {
          throw InputError(at + ".points", toml_written(*lookup(f, "points")), "only with range");
        }
      } else {
        if (!info.numeric) {
          throw InputError(at + ".range", toml_written(*range),
                           "levels = [...]: " + factor.key + " is a choice or a name");
        }
        factor.range = range_of(*range, info, at + ".range");
        if (const toml::value* p = lookup(f, "points")) {
          factor.points = static_cast<int>(whole(*p, at + ".points", 2, 1000000));
        }
      }
      spec.factors.push_back(factor);
    }
    int speeds = 0;
    for (const Factor& f : spec.factors) {
      speeds += f.key == "initial.w1" || f.key == "initial.w2" || f.key == "torque1.mean_speed";
    }
    if (speeds > 1 && spec.base.torque1.kind == Torque::Kind::speed_controlled) {
      throw InputError("factors", "initial.w1, initial.w2, torque1.mean_speed",
                       "one of them as a factor: under a speed controller each sets the others "
                       "(the pair rolls at the controller's reference)");
    }
  }

  // [design]
  const toml::value& g = table_at(root, "design", false);
  only_keys(g, "design", {"kind", "points", "seed"});
  if (const toml::value* k = lookup(g, "kind")) {
    const std::string kind = text(*k, "design.kind", "\"grid\", \"latin-hypercube\" or \"random\"");
    if (kind == "grid") {
      spec.design = DesignKind::grid;
    } else if (kind == "latin-hypercube") {
      spec.design = DesignKind::latin_hypercube;
    } else if (kind == "random") {
      spec.design = DesignKind::random;
    } else {
      throw InputError("design.kind", toml_written(*k),
                       "\"grid\", \"latin-hypercube\" or \"random\"");
    }
  }
  spec.design_seed = spec.seed;
  if (const toml::value* s = lookup(g, "seed")) {
    spec.design_seed = static_cast<std::uint64_t>(
        whole(*s, "design.seed", 0, std::numeric_limits<long long>::max()));
  }
  if (spec.design == DesignKind::grid) {
    if (lookup(g, "points") != nullptr) {
      throw InputError("design.points", toml_written(*lookup(g, "points")),
                       "only with kind = \"latin-hypercube\" or \"random\" (a grid's size is "
                       "its factors' levels and points)");
    }
    for (std::size_t i = 0; i < spec.factors.size(); ++i) {
      if (spec.factors[i].range && spec.factors[i].points == 0) {
        throw InputError("factors[" + std::to_string(i) + "].points", "missing",
                         "an integer >= 2 with range on a grid (design.kind = \"grid\")");
      }
    }
  } else {
    if (lookup(g, "points") == nullptr) {
      throw InputError("design.points", "missing",
                       "the number of conditions the design draws, an integer >= 1");
    }
    spec.design_points =
        static_cast<int>(whole(*lookup(g, "points"), "design.points", 1, 100000000));
    for (std::size_t i = 0; i < spec.factors.size(); ++i) {
      if (spec.factors[i].points != 0) {
        throw InputError("factors[" + std::to_string(i) + "].points",
                         std::to_string(spec.factors[i].points),
                         "only on a grid: a drawn design takes design.points");
      }
    }
  }

  // [split]
  const toml::value& s = table_at(root, "split", false);
  only_keys(s, "split", {"default", "heldout"});
  if (const toml::value* v = lookup(s, "default")) {
    spec.default_split = text(*v, "split.default", "a split's name (default \"train\")");
  }
  if (const toml::value* hs = lookup(s, "heldout")) {
    if (!hs->is_array())
      throw InputError("split.heldout", toml_written(*hs), "[[split.heldout]] tables");
    for (std::size_t i = 0; i < hs->as_array().size(); ++i) {
      const toml::value& h = hs->as_array()[i];
      const std::string at = "split.heldout[" + std::to_string(i) + "]";
      if (!h.is_table()) throw InputError(at, toml_written(h), "a [[split.heldout]] table");
      only_keys(h, at, {"key", "levels", "range", "split"});
      HeldOut held;
      held.key = text(required(h, at, "key"), at + ".key", "a factor's key");
      const auto factor = std::find_if(spec.factors.begin(), spec.factors.end(),
                                       [&](const Factor& f) { return f.key == held.key; });
      if (factor == spec.factors.end()) {
        std::string keys;
        for (const Factor& f : spec.factors) keys += (keys.empty() ? "" : ", ") + f.key;
        throw InputError(at + ".key", held.key, "a factor's key: " + keys);
      }
      const KeyInfo info = key_info(spec.base, held.key, at + ".key");
      const toml::value* levels = lookup(h, "levels");
      const toml::value* range = lookup(h, "range");
      if ((levels == nullptr) == (range == nullptr)) {
        throw InputError(at, held.key, "levels = [...] or range = [LOW, HIGH], one of them");
      }
      if (levels != nullptr) {
        if (!levels->is_array() || levels->as_array().empty()) {
          throw InputError(at + ".levels", toml_written(*levels), "a non-empty array of values");
        }
        for (std::size_t j = 0; j < levels->as_array().size(); ++j) {
          held.levels.push_back(as_text(levels->as_array()[j],
                                        at + ".levels[" + std::to_string(j) + "]",
                                        "a value as a case file writes it"));
        }
      } else {
        if (!info.numeric)
          throw InputError(at + ".range", toml_written(*range), "levels of a choice");
        held.range = range_of(*range, info, at + ".range");
      }
      if (const toml::value* v = lookup(h, "split")) {
        held.split = text(*v, at + ".split", "a split's name (default \"test\")");
      }
      spec.heldout.push_back(held);
    }
  }
  // [trajectory]
  if (const toml::value* tv = lookup(root, "trajectory")) {
    if (!tv->is_table()) throw InputError("trajectory", toml_written(*tv), "a [trajectory] table");
    only_keys(*tv, "trajectory",
              {"key", "initial", "final", "paris_c", "paris_m", "geometry_factor", "stress_range",
               "snapshots", "spacing"});
    Trajectory t;
    t.key = text(required(*tv, "trajectory", "key"), "trajectory.key", "faults[i].depth");
    const auto fault = fault_address(t.key);
    if (!fault || fault->second != "depth") {
      throw InputError("trajectory.key", t.key,
                       "faults[i].depth: the depth of a root crack of the base case");
    }
    key_info(spec.base, t.key, "trajectory.key");
    for (const Factor& f : spec.factors) {
      if (f.key == t.key) {
        throw InputError("trajectory.key", t.key, "a key that is not also a factor");
      }
    }
    for (const HeldOut& h : spec.heldout) {
      if (h.key == t.key) throw InputError("split.heldout key", h.key, "not the trajectory's key");
    }
    t.initial_m =
        quantity(required(*tv, "trajectory", "initial"), Dimension::length, "trajectory.initial");
    t.final_m =
        quantity(required(*tv, "trajectory", "final"), Dimension::length, "trajectory.final");
    if (!(t.initial_m > 0.0) || !(t.final_m > t.initial_m) || !std::isfinite(t.final_m)) {
      throw InputError("trajectory.final", shortest_decimal(t.final_m) + " m",
                       "a depth above trajectory.initial (" + shortest_decimal(t.initial_m) +
                           " m), which is > 0");
    }
    const auto positive = [&](const char* key, double lower_open) {
      const double v = number(required(*tv, "trajectory", key), std::string("trajectory.") + key,
                              "a number > " + shortest_decimal(lower_open));
      if (!(v > lower_open) || !std::isfinite(v)) {
        throw InputError(std::string("trajectory.") + key, shortest_decimal(v),
                         "a finite number > " + shortest_decimal(lower_open));
      }
      return v;
    };
    t.paris_c = positive("paris_c", 0.0);
    t.paris_m = positive("paris_m", 0.0);
    if (lookup(*tv, "geometry_factor") != nullptr)
      t.geometry_factor = positive("geometry_factor", 0.0);
    t.stress_range_pa = quantity(required(*tv, "trajectory", "stress_range"), Dimension::pressure,
                                 "trajectory.stress_range");
    if (!(t.stress_range_pa > 0.0) || !std::isfinite(t.stress_range_pa)) {
      throw InputError("trajectory.stress_range", shortest_decimal(t.stress_range_pa) + " Pa",
                       "a stress range > 0");
    }
    t.snapshots = static_cast<int>(
        whole(required(*tv, "trajectory", "snapshots"), "trajectory.snapshots", 2, 100000));
    if (const toml::value* v = lookup(*tv, "spacing")) {
      const std::string sp = text(*v, "trajectory.spacing", "\"cycles\" or \"depth\"");
      if (sp != "cycles" && sp != "depth") {
        throw InputError("trajectory.spacing", toml_written(*v),
                         "\"cycles\" (snapshots evenly in N) or \"depth\" (evenly in a)");
      }
      t.even_in_depth = sp == "depth";
    }
    spec.trajectory = t;
  }
  spec.spec_sha256 = sha256_hex(spec.spec_text + std::string(1, '\0') + spec.base_case_text);
  return spec;
}

DatasetSpec read_spec(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("SPEC", path.string(), "a readable spec file (TOML)");
  std::string content(kMostSpecBytes + 1, '\0');
  in.read(content.data(), static_cast<std::streamsize>(content.size()));
  content.resize(static_cast<std::size_t>(in.gcount()));
  if (content.size() > kMostSpecBytes) {
    throw InputError("SPEC", path.string(), "a spec file of at most 1 MiB");
  }
  return parse_spec(content, path.parent_path(), path.string());
}

namespace {

// The value of design draw u in [0, 1) of a factor: a level, or a value of its range.
std::string drawn(const Factor& f, double u, bool integer) {
  if (!f.levels.empty()) {
    const auto j = std::min(f.levels.size() - 1,
                            static_cast<std::size_t>(u * static_cast<double>(f.levels.size())));
    return f.levels[j];
  }
  double v = f.range->first + u * (f.range->second - f.range->first);
  if (integer) v = std::round(v);
  return shortest_decimal(v);
}

// The grid's values of one factor: its levels, or `points` values evenly over its range.
std::vector<std::string> grid_values(const Factor& f, bool integer) {
  if (!f.levels.empty()) return f.levels;
  std::vector<std::string> values;
  for (int j = 0; j < f.points; ++j) {
    double v = f.range->first +
               (f.range->second - f.range->first) * static_cast<double>(j) / (f.points - 1);
    if (j == f.points - 1) v = f.range->second;
    if (integer) v = std::round(v);
    values.push_back(shortest_decimal(v));
  }
  return values;
}

bool held_out(const HeldOut& h, const std::string& written, double value,
              const SimulationCase& base, std::size_t i) {
  if (h.range) return value >= h.range->first && value <= h.range->second;
  for (std::size_t j = 0; j < h.levels.size(); ++j) {
    if (h.levels[j] == written) return true;
    if (std::isnan(value)) continue;
    // The same value written otherwise ("1800 rpm" against 188.49...).
    SimulationCase c = base;
    RecorderSettings r;
    const double level =
        set_key(c, r, h.key, h.levels[j],
                "split.heldout[" + std::to_string(i) + "].levels[" + std::to_string(j) + "]");
    if (level == value) return true;
  }
  return false;
}

}  // namespace

Plan make_plan(const DatasetSpec& spec, const Bounds& bounds) {
  Plan plan;
  plan.spec = spec;
  const std::size_t nf = spec.factors.size();
  std::vector<bool> integer(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    integer[i] =
        key_info(spec.base, spec.factors[i].key, "factors[" + std::to_string(i) + "].key").integer;
  }
  // The design's texts per condition: a level as written, or a range's value in SI.
  std::vector<std::vector<std::string>> texts;
  double conditions = 1.0;
  if (spec.design == DesignKind::grid) {
    for (std::size_t i = 0; i < nf; ++i) {
      conditions *= static_cast<double>(grid_values(spec.factors[i], integer[i]).size());
    }
  } else {
    conditions = spec.design_points;
  }
  if (spec.trajectory) conditions *= spec.trajectory->snapshots;
  const double records = conditions * spec.replicates;
  const std::size_t n0 =
      static_cast<std::size_t>(std::llround(spec.settle_s * spec.sample_rate_hz));
  const auto samples =
      static_cast<std::size_t>(std::llround(spec.duration_s * spec.sample_rate_hz));
  plan.samples_per_record = samples;
  // f8 time, sensor and truth channels, the int8 contact flags, and about 16 kB of metadata and
  // case text.
  const double channels = 2.0 + static_cast<double>(truth_channels().size());
  plan.bytes_per_record = static_cast<double>(samples) * (8.0 * channels + 1.0) + 16384.0;
  const auto refuse = [](const std::string& what, double estimate, double bound,
                         const std::string& flag) {
    throw InputError(std::vector<Problem>{
        refused_problem(what, shortest_decimal(estimate),
                        "the set's estimate is above the bound " + shortest_decimal(bound),
                        "at most " + shortest_decimal(bound) + " (" + flag + " lifts the bound)")});
  };
  if (records > bounds.max_records) refuse("records", records, bounds.max_records, "max_records");
  // A ZIP without its 64-bit extension holds at most 4 GiB.
  if (spec.format == RecordFormat::npz && plan.bytes_per_record >= 4.0e9) {
    throw InputError("dataset.format", "\"npz\"",
                     "records below 4 GiB (a ZIP without its 64-bit extension): one record is "
                     "about " +
                         shortest_decimal(plan.bytes_per_record) +
                         " bytes; \"hdf5\", or a shorter dataset.duration");
  }
  const double total_samples = records * static_cast<double>(samples) * channels;
  if (total_samples > bounds.max_samples) {
    refuse("samples", total_samples, bounds.max_samples, "max_samples");
  }
  const double bytes = records * plan.bytes_per_record;
  if (bytes > bounds.max_bytes) refuse("bytes", bytes, bounds.max_bytes, "max_bytes");

  const std::size_t snapshots =
      spec.trajectory ? static_cast<std::size_t>(spec.trajectory->snapshots) : 1;
  std::size_t count = static_cast<std::size_t>(conditions) / snapshots;
  texts.assign(count, std::vector<std::string>(nf));
  if (spec.design == DesignKind::grid) {
    std::size_t stride = 1;
    // The last factor varies fastest.
    for (std::size_t i = nf; i-- > 0;) {
      const std::vector<std::string> values = grid_values(spec.factors[i], integer[i]);
      for (std::size_t c = 0; c < count; ++c) texts[c][i] = values[(c / stride) % values.size()];
      stride *= values.size();
    }
  } else {
    for (std::size_t i = 0; i < nf; ++i) {
      signals::RandomStream stream(spec.design_seed, 1000 + i);
      std::vector<std::size_t> strata(count);
      std::iota(strata.begin(), strata.end(), std::size_t{0});
      if (spec.design == DesignKind::latin_hypercube) {
        // Fisher-Yates on our own uniforms: each stratum [j/n, (j+1)/n) once per factor.
        for (std::size_t j = count; j-- > 1;) {
          const auto k =
              std::min(j, static_cast<std::size_t>(stream.uniform() * static_cast<double>(j + 1)));
          std::swap(strata[j], strata[k]);
        }
      }
      for (std::size_t c = 0; c < count; ++c) {
        const double u =
            spec.design == DesignKind::latin_hypercube
                ? (static_cast<double>(strata[c]) + stream.uniform()) / static_cast<double>(count)
                : stream.uniform();
        texts[c][i] = drawn(spec.factors[i], u, integer[i]);
      }
    }
  }

  // A trajectory: each design condition becomes its snapshots, the depth a factor of the plan.
  std::vector<Condition> grown(count);
  if (spec.trajectory) {
    const Trajectory& t = *spec.trajectory;
    Factor depth;
    depth.key = t.key;
    depth.unit = "m";
    plan.spec.factors.push_back(depth);
    const double last = static_cast<double>(snapshots - 1);
    const double to_failure = paris_cycles(t, t.final_m);
    std::vector<std::vector<std::string>> expanded;
    grown.clear();
    for (std::size_t c = 0; c < count; ++c) {
      for (std::size_t k = 0; k < snapshots; ++k) {
        const double f = static_cast<double>(k) / last;
        double a = 0.0;
        double n = 0.0;
        if (t.even_in_depth) {
          a = k + 1 == snapshots ? t.final_m : t.initial_m + f * (t.final_m - t.initial_m);
          n = k == 0 ? 0.0 : k + 1 == snapshots ? to_failure : paris_cycles(t, a);
        } else {
          n = k + 1 == snapshots ? to_failure : f * to_failure;
          a = k == 0 ? t.initial_m : k + 1 == snapshots ? t.final_m : paris_depth_m(t, n);
        }
        expanded.push_back(texts[c]);
        expanded.back().push_back(shortest_decimal(a));
        Condition g;
        g.trajectory = c;
        g.trajectory_step = static_cast<int>(k);
        g.cycles = n;
        g.cycles_to_failure = to_failure;
        grown.push_back(g);
      }
    }
    texts = std::move(expanded);
    count = texts.size();
  }
  const std::vector<Factor>& factors = plan.spec.factors;
  // Every condition's case, validated before any record.
  for (std::size_t c = 0; c < count; ++c) {
    Condition condition = grown[c];
    condition.texts = texts[c];
    condition.simulation_case = spec.base;
    condition.recorder = spec.recorder;
    const std::string where = "condition " + std::to_string(c);
    for (std::size_t i = 0; i < factors.size(); ++i) {
      const std::string name =
          i < nf ? "factors[" + std::to_string(i) + "] " + factors[i].key : "trajectory.key";
      condition.values.push_back(set_key(condition.simulation_case, condition.recorder,
                                         factors[i].key, texts[c][i], name));
    }
    SimulationCase& sc = condition.simulation_case;
    const Oversampling over =
        oversampling(spec.sample_rate_hz, condition.recorder, static_cast<long long>(n0),
                     static_cast<long long>(samples));
    if (over.factor > 1 && static_cast<long long>(n0) <= over.lead) {
      throw InputError(
          "dataset.settle", shortest_decimal(spec.settle_s) + " s",
          "at least " + shortest_decimal(static_cast<double>(over.lead + 1) / spec.sample_rate_hz) +
              " s with recorder.oversample = " + std::to_string(over.factor) + " (" + where +
              "): the anti-alias filter's half span before the record's first "
              "sample, plus one sample");
    }
    // The run covers the last fine sample, and half a sample more.
    sc.integrator.end_time_s = (static_cast<double>(over.last_fine) + 1.5) / over.rate_hz;
    try {
      sc = parse_case(write_case_file(sc, CaseUnits::si), "");
      refuse_planar_simulation(sc);
      validate_gaps(sc);
      RunControl control;
      control.sample_rate_hz = over.rate_hz;
      validate_sampling(sc, control);
    } catch (const CaseFileError& e) {
      // Named by the condition's factor values as the spec writes them, then the key.
      std::string values;
      for (std::size_t i = 0; i < factors.size(); ++i) {
        values += (i ? ", " : "") + factors[i].key + " = " + texts[c][i];
      }
      std::vector<Problem> problems;
      for (const Problem& p : e.problems()) {
        Problem named = p.renamed(where + " (" + values + "): " + p.field, p.value);
        named.where.clear();
        problems.push_back(named);
      }
      throw InputError(problems);
    }
    const RecorderSettings& r = condition.recorder;
    // The sections run at the simulation's rate, M x dataset.sample_rate.
    const double most = kMostSectionFraction * over.rate_hz;
    const std::string rate_name =
        over.factor == 1 ? "dataset.sample_rate" : "dataset.sample_rate x recorder.oversample";
    if (r.accelerometer_resonance_hz && *r.accelerometer_resonance_hz >= most) {
      throw InputError("recorder.accelerometer_resonance",
                       shortest_decimal(*r.accelerometer_resonance_hz) + " Hz",
                       "below a quarter of " + rate_name + " (" + shortest_decimal(most) + " Hz)");
    }
    if (r.path_modes > 0 &&
        (r.path_band_high_hz >= most || !(r.path_band_low_hz < r.path_band_high_hz) ||
         !(r.path_damping_low < r.path_damping_high))) {
      throw InputError("recorder.path_band_high", shortest_decimal(r.path_band_high_hz) + " Hz",
                       "above recorder.path_band_low, below a quarter of " + rate_name + " (" +
                           shortest_decimal(most) +
                           " Hz); path_damping_low below path_damping_high");
    }
    condition.split = spec.default_split;
    for (std::size_t h = 0; h < spec.heldout.size(); ++h) {
      const HeldOut& held = spec.heldout[h];
      const auto i = static_cast<std::size_t>(
          std::find_if(spec.factors.begin(), spec.factors.end(),
                       [&](const Factor& f) { return f.key == held.key; }) -
          spec.factors.begin());
      if (held_out(held, texts[c][i], condition.values[i], spec.base, h)) {
        condition.split = held.split;
        break;
      }
    }
    plan.conditions.push_back(std::move(condition));
  }
  for (std::size_t c = 0; c < count; ++c) {
    for (int k = 0; k < spec.replicates; ++k) {
      plan.records.push_back({plan.records.size(), c, k, record_seed(spec.seed, c, k)});
    }
  }
  return plan;
}

}  // namespace gearimpact::dataset
