#include "gearimpact/dataset/run.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <future>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "gearimpact/batch/pool.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/hdf5_image.hpp"
#include "gearimpact/io/mat_image.hpp"
#include "gearimpact/io/npz_image.hpp"
#include "gearimpact/io/sha256.hpp"
#include "gearimpact/signals/decimate.hpp"
#include "gearimpact/signals/order_tracking.hpp"
#include "gearimpact/signals/recorder.hpp"
#include "gearimpact_code_version.hpp"


namespace gearimpact::dataset {

namespace fs = std::filesystem;

std::string code_version() {
  return GEARIMPACT_CODE_VERSION;
}

namespace {

constexpr int kFormatVersion = 1;
// A steady record's halves differ in RMS by less than this (docs/datasets.md, settled).
constexpr double kSettledRmsChange = 0.02;

double rms_about_mean(const double* x, std::size_t n) {
  if (n == 0) return 0.0;
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i) mean += x[i];
  mean /= static_cast<double>(n);
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) sum += (x[i] - mean) * (x[i] - mean);
  return std::sqrt(sum / static_cast<double>(n));
}

std::uint64_t mixed_seed(std::uint64_t seed, std::int64_t recorder_seed) {
  return recorder_seed == 0 ? seed
                            : seed ^ signals::splitmix64(static_cast<std::uint64_t>(recorder_seed));
}

std::string record_name(std::size_t id) {
  char name[32];
  std::snprintf(name, sizeof name, "r%07zu", id);
  return name;
}

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

// The label's column name: the key and its SI unit ("faults[0].depth_m",
// "torque1.mean_speed_rad_s").
std::string column_name(const Factor& f) {
  if (f.unit.empty()) return f.key;
  std::string unit;
  for (const char c : f.unit) {
    if (c == '/' || c == '*') {
      unit += '_';
    } else if (c != '^') {
      unit += c;
    }
  }
  return f.key + "_" + unit;
}

std::string number_text(double v) {
  return std::isfinite(v) ? shortest_decimal(v) : "";
}

}  // namespace

RecordData make_record(const Plan& plan, const Record& record, const StiffnessTable* table) {
  const DatasetSpec& spec = plan.spec;
  const Condition& condition = plan.conditions.at(record.condition);
  SimulationCase c = condition.simulation_case;
  if (c.tacho.pulses_per_revolution > 0) {
    c.tacho.seed = static_cast<std::uint32_t>(record.seed & 0xffffffffu);
  }
  if (spec.random_start) {
    // Stream 3 of the record's seed (1 and 2 are the noise's and the path's).
    signals::RandomStream start(record.seed, 3);
    const double turn = start.uniform() * 2.0 * pi / c.gears.teeth1;
    c.initial.theta1_rad += turn;
    c.initial.theta2_rad +=
        turn * base_radius(c.gears, Gear::one) / base_radius(c.gears, Gear::two);
  }
  const double fs = spec.sample_rate_hz;
  const auto n0 = static_cast<long long>(std::llround(spec.settle_s * fs));
  const auto n = static_cast<long long>(plan.samples_per_record);
  // With oversampling M the simulation samples at M fs (fine index i at i / (M fs)); the
  // record's sample j is fine sample M (n0 + j).
  const Oversampling over = oversampling(fs, condition.recorder, n0, n);
  const long long m = over.factor;
  RecordData data;
  data.truth.assign(truth_channels().size(), {});
  for (auto& channel : data.truth) channel.reserve(static_cast<std::size_t>(n));
  data.contact.reserve(static_cast<std::size_t>(n));
  // The sensor from fine sample 1 on, the settle time included, so that the recorder's filters
  // have settled too when the record starts (and the decimator's span before it is filled).
  std::vector<double> sensor;
  sensor.reserve(static_cast<std::size_t>(over.last_fine));
  const auto keep = [&](double t, double a, const std::array<double, 7>& truth) {
    const long long index = std::llround(t * over.rate_hz);
    if (index < 1 || index > over.last_fine) return;
    sensor.push_back(a);
    if (index < m * n0 || index >= m * (n0 + n) || index % m != 0) return;
    for (std::size_t k = 0; k < truth.size(); ++k) data.truth[k].push_back(truth[k]);
    data.contact.push_back(
        static_cast<std::int8_t>((truth[4] > 0.0 ? 1 : 0) | (truth[5] > 0.0 ? 2 : 0)));
  };
  RunControl control;
  control.sample_rate_hz = over.rate_hz;
  control.keep_series = false;
  control.keep_samples = false;
  const bool planar = c.bearings.kind == BearingKind::elastic;
  if (planar) {
    data.sensor_units = "m/s2";
    data.sensor_quantity = "acceleration of gear " + std::to_string(c.bearings.sensor_gear) +
                           "'s centre along the sensor's direction ([bearings] sensor_gear, "
                           "sensor_angle)";
    control.on_planar_sample = [&](const PlanarSample& s) {
      keep(s.t_s, s.sensor_acceleration_m_per_s2,
           {s.state.theta1_rad, s.state.theta2_rad, s.state.w1_rad_per_s, s.state.w2_rad_per_s,
            s.drive_force_n, s.coast_force_n, s.dte_m});
    };
  } else {
    data.sensor_units = "rad/s2";
    data.sensor_quantity = "the wheel's angular acceleration (torsional model: no bearings)";
    control.on_sample = [&](const SampleRow& s) {
      keep(s.t_s, s.acceleration2_rad_per_s2,
           {s.theta1_rad, s.theta2_rad, s.w1_rad_per_s, s.w2_rad_per_s, s.normal_force_n1_n,
            s.normal_force_n2_n, s.dte_m});
    };
  }
  const SimulationResult result = table ? simulate(c, *table, control) : simulate(c, control);
  if (static_cast<long long>(sensor.size()) != over.last_fine ||
      static_cast<long long>(data.contact.size()) != n) {
    throw SimulationError("record " + std::to_string(record.id) + ": " +
                          std::to_string(data.contact.size()) + " samples instead of " +
                          std::to_string(n));
  }
  data.labels.speed_drift_max_rel = result.summary.speed_drift_max_rel.value_or(std::nan(""));
  data.labels.theta1_start_rad = c.initial.theta1_rad;

  // The recorder chain on the whole sampled run: path, accelerometer; then the record is cut.
  const RecorderSettings& r = condition.recorder;
  const std::uint64_t noise_seed = mixed_seed(record.seed, r.seed);
  std::vector<signals::SecondOrderSection> path;
  if (r.path_modes > 0) {
    const std::uint64_t path_seed = r.path_per_record ? noise_seed : mixed_seed(spec.seed, r.seed);
    path = signals::draw_path(path_seed, r.path_modes, r.path_band_low_hz, r.path_band_high_hz,
                              r.path_damping_low, r.path_damping_high);
  }
  std::optional<signals::SecondOrderSection> accelerometer;
  if (r.accelerometer_resonance_hz) {
    accelerometer = signals::accelerometer(*r.accelerometer_resonance_hz, r.accelerometer_damping);
  }
  sensor = signals::path_then_accelerometer(sensor, over.rate_hz, path, accelerometer,
                                            "recorder.path_band_high",
                                            "recorder.accelerometer_resonance");
  if (m == 1) {
    data.sensor.assign(sensor.end() - n, sensor.end());
  } else {
    // The decimator's input: fine samples M (n0 - lead) to the last, so that its outputs fall
    // on the fine samples M (n0 + j), j = 0 ... n - 1, each the filter centred on its instant.
    signals::UniformRecord fine;
    fine.rate_hz = over.rate_hz;
    fine.start_s = -static_cast<double>(over.lead) / fs;
    fine.values.assign(sensor.begin() + (m * (n0 - over.lead) - 1), sensor.end());
    data.sensor = signals::anti_alias_resample(fine, fs).values;
    if (static_cast<long long>(data.sensor.size()) != n) {
      throw SimulationError("record " + std::to_string(record.id) + ": the decimator gave " +
                            std::to_string(data.sensor.size()) + " samples instead of " +
                            std::to_string(n));
    }
  }
  const std::size_t half = data.sensor.size() / 2;
  const double first = rms_about_mean(data.sensor.data(), half);
  const double second = rms_about_mean(data.sensor.data() + half, data.sensor.size() - half);
  const double larger = std::max(first, second);
  data.labels.settled = larger == 0.0 || std::abs(first - second) <= kSettledRmsChange * larger;
  data.labels.realised_snr_db = std::nan("");
  if (r.noise_snr_db) {
    data.labels.realised_snr_db =
        signals::add_noise(data.sensor, *r.noise_snr_db, noise_seed, r.noise_exact).realised_snr_db;
  }
  if (r.adc_range)
    data.labels.clipped = signals::adc(data.sensor, *r.adc_range, r.adc_bits).clipped;

  data.time_s.resize(static_cast<std::size_t>(n));
  for (long long j = 0; j < n; ++j) {
    data.time_s[static_cast<std::size_t>(j)] = static_cast<double>(j) / fs;
  }
  if (c.tacho.pulses_per_revolution > 0) {
    const std::vector<double> emitted =
        signals::tacho_jitter(result.tacho_times_s, c.tacho.jitter_s, c.tacho.seed);
    const double start = static_cast<double>(n0) / fs;
    const double end = static_cast<double>(n0 + n) / fs;
    for (std::size_t k = 0; k < result.tacho_times_s.size(); ++k) {
      const double t = result.tacho_times_s[k];
      if (t < start || t >= end) continue;
      data.tacho_times_s.push_back(t - start);
      data.tacho_emitted_times_s.push_back(emitted[k] - start);
    }
  }
  data.case_toml = write_case_file(c, CaseUnits::si);
  return data;
}

namespace {

// The record's layout (docs/datasets.md), into an HDF5 or an NPZ image: the same paths, arrays
// and attributes.
template <class Image>
std::string fill_record(Image& h5, const Plan& plan, const Record& record, const RecordData& data) {
  const DatasetSpec& spec = plan.spec;
  const Condition& condition = plan.conditions.at(record.condition);
  h5.attribute("/", "format", std::string("gearimpact-record"));
  h5.attribute("/", "format_version", std::int64_t{kFormatVersion});
  h5.attribute("/", "dataset", spec.name);
  h5.attribute("/", "record_id", static_cast<std::int64_t>(record.id));
  h5.attribute("/", "condition", static_cast<std::int64_t>(record.condition));
  h5.attribute("/", "replicate", static_cast<std::int64_t>(record.replicate));
  h5.attribute("/", "split", condition.split);
  h5.attribute("/", "seed", std::to_string(record.seed));
  h5.attribute("/", "sample_rate_hz", spec.sample_rate_hz);
  h5.attribute("/", "settle_s", spec.settle_s);
  h5.attribute("/", "duration_s", spec.duration_s);
  h5.attribute("/", "n_samples", static_cast<std::int64_t>(data.time_s.size()));
  h5.attribute("/", "spec_sha256", spec.spec_sha256);
  h5.attribute("/", "code_version", code_version());
  h5.dataset("/time", data.time_s, "s");
  h5.group("/signals");
  h5.dataset("/signals/sensor", data.sensor, data.sensor_units);
  h5.attribute("/signals/sensor", "quantity", data.sensor_quantity);
  const RecorderSettings& r = condition.recorder;
  const Oversampling over =
      oversampling(spec.sample_rate_hz, r, std::llround(spec.settle_s * spec.sample_rate_hz),
                   static_cast<long long>(plan.samples_per_record));
  if (!over.filter) {
    h5.attribute("/signals/sensor", "sample",
                 std::string("interval-average: the mean over the interval ending at each sample "
                             "(transfer sinc(f T) with a delay of T/2)"));
  } else {
    const signals::KaiserLowPass& f = *over.filter;
    h5.attribute("/signals/sensor", "sample",
                 std::string("interval-average at simulation_rate_hz (the mean over the interval "
                             "ending at each fine sample), the recorder's filters at that rate, "
                             "then the anti-alias decimator: a linear-phase FIR by Kaiser's "
                             "window (no delay) centred on each recorded instant"));
    h5.attribute("/signals/sensor", "oversample", std::int64_t{over.factor});
    h5.attribute("/signals/sensor", "simulation_rate_hz", over.rate_hz);
    h5.attribute("/signals/sensor", "decimator_passband_edge_hz", f.pass_hz);
    h5.attribute("/signals/sensor", "decimator_stopband_edge_hz", f.stop_hz);
    h5.attribute("/signals/sensor", "decimator_attenuation_db", f.attenuation_db);
    h5.attribute("/signals/sensor", "decimator_taps", static_cast<std::int64_t>(f.order + 1));
    h5.attribute("/signals/sensor", "decimator_kaiser_beta", f.beta);
    h5.attribute("/signals/sensor", "alias_free_band_hz", f.pass_hz);
  }
  h5.attribute("/signals/sensor", "path_modes", std::int64_t{r.path_modes});
  h5.attribute("/signals/sensor", "accelerometer_resonance_hz",
               r.accelerometer_resonance_hz.value_or(std::nan("")));
  h5.attribute("/signals/sensor", "noise_snr_db", r.noise_snr_db.value_or(std::nan("")));
  h5.attribute("/signals/sensor", "adc_range", r.adc_range.value_or(std::nan("")));
  h5.group("/truth");
  for (std::size_t k = 0; k < truth_channels().size(); ++k) {
    const ChannelInfo& info = truth_channels()[k];
    const std::string path = "/truth/" + std::string(info.name);
    h5.dataset(path, data.truth[k], std::string(info.units));
    h5.attribute(path, "quantity", std::string(info.help));
  }
  h5.dataset("/truth/contact", data.contact, "1");
  h5.attribute("/truth/contact", "quantity",
               std::string("flags: 1 the drive flanks carry, 2 the coast flanks carry"));
  if (condition.simulation_case.tacho.pulses_per_revolution > 0) {
    h5.group("/tacho");
    h5.dataset("/tacho/true_times_s", data.tacho_times_s, "s");
    h5.dataset("/tacho/emitted_times_s", data.tacho_emitted_times_s, "s");
    h5.attribute("/tacho", "pulses_per_revolution",
                 std::int64_t{condition.simulation_case.tacho.pulses_per_revolution});
    h5.attribute("/tacho", "shaft",
                 std::string(name_of(kTachoShafts, condition.simulation_case.tacho.shaft)));
  }
  h5.group("/labels");
  for (std::size_t i = 0; i < spec.factors.size(); ++i) {
    const std::string name = column_name(spec.factors[i]);
    if (spec.factors[i].numeric) {
      h5.attribute("/labels", name, condition.values[i]);
    } else {
      h5.attribute("/labels", name, condition.texts[i]);
    }
  }
  if (spec.trajectory) {
    h5.attribute("/labels", "trajectory", static_cast<std::int64_t>(condition.trajectory));
    h5.attribute("/labels", "trajectory_step", std::int64_t{condition.trajectory_step});
    h5.attribute("/labels", "cycles", condition.cycles);
    h5.attribute("/labels", "cycles_to_failure", condition.cycles_to_failure);
    h5.attribute("/labels", "rul_cycles", condition.cycles_to_failure - condition.cycles);
  }
  h5.attribute("/labels", "realised_snr_db", data.labels.realised_snr_db);
  h5.attribute("/labels", "clipped", static_cast<std::int64_t>(data.labels.clipped));
  h5.attribute("/labels", "settled", std::int64_t{data.labels.settled ? 1 : 0});
  h5.attribute("/labels", "speed_drift_max_rel", data.labels.speed_drift_max_rel);
  h5.attribute("/labels", "theta1_start_rad", data.labels.theta1_start_rad);
  h5.group("/provenance");
  h5.text("/provenance/case_toml", data.case_toml);
  h5.text("/provenance/spec_toml", spec.spec_text);
  h5.attribute("/provenance", "code_version", code_version());
  h5.attribute("/provenance", "seed", std::to_string(record.seed));
  return h5.bytes();
}

}  // namespace

std::string record_file(const Plan& plan, const Record& record, const RecordData& data) {
  if (plan.spec.format == RecordFormat::npz) {
    NpzImage npz;
    return fill_record(npz, plan, record, data);
  }
  if (plan.spec.format == RecordFormat::mat) {
    MatImage mat;
    return fill_record(mat, plan, record, data);
  }
  Hdf5Image h5;
  return fill_record(h5, plan, record, data);
}

namespace {

// The record's sidecar: what labels.csv needs, and what proves the record complete.
std::string sidecar(const Plan& plan, const Record& record, const RecordData& data,
                    const std::string& file_sha256) {
  const Condition& condition = plan.conditions.at(record.condition);
  nlohmann::ordered_json j;
  j["record_id"] = record.id;
  j["condition"] = record.condition;
  j["replicate"] = record.replicate;
  j["split"] = condition.split;
  j["seed"] = std::to_string(record.seed);
  j["spec_sha256"] = plan.spec.spec_sha256;
  j["file_sha256"] = file_sha256;
  j["realised_snr_db"] = number_text(data.labels.realised_snr_db);
  j["clipped"] = data.labels.clipped;
  j["settled"] = data.labels.settled;
  j["speed_drift_max_rel"] = number_text(data.labels.speed_drift_max_rel);
  j["theta1_start_rad"] = number_text(data.labels.theta1_start_rad);
  return j.dump(1) + "\n";
}

struct Sidecar {
  bool valid = false;
  nlohmann::json json;
};

// The sidecar of record `id` in `folder` when it, and the file whose digest it holds, are
// complete and of this spec.
Sidecar complete_record(const fs::path& folder, std::size_t id, const std::string& spec_sha256,
                        const char* extension) {
  Sidecar s;
  const std::string text = read_all(folder / (record_name(id) + ".json"));
  if (text.empty()) return s;
  try {
    s.json = nlohmann::json::parse(text);
  } catch (const std::exception&) {
    return s;
  }
  if (!s.json.is_object() || s.json.value("spec_sha256", "") != spec_sha256 ||
      s.json.value("record_id", std::size_t{0} - 1) != id) {
    return s;
  }
  const std::string bytes = read_all(folder / (record_name(id) + extension));
  s.valid = !bytes.empty() && sha256_hex(bytes) == s.json.value("file_sha256", "");
  return s;
}

double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// Throws InputError naming `out` when it holds another spec's set.
void require_same_spec(const Plan& plan, const fs::path& out) {
  const std::string previous = read_all(out / "spec.sha256");
  if (!previous.empty() && previous != plan.spec.spec_sha256 + "\n") {
    throw InputError("out", out.string(),
                     "a new folder, or one of this spec's set (it holds the set of spec sha256 " +
                         previous.substr(0, previous.size() - 1) + "; this spec's is " +
                         plan.spec.spec_sha256 + ")");
  }
}

void write_spec_files(const Plan& plan, const fs::path& out) {
  require_same_spec(plan, out);
  if (read_all(out / "spec.sha256").empty()) {
    write_file_atomically((out / "spec.toml").string(), plan.spec.spec_text);
    write_file_atomically((out / "base_case.toml").string(), plan.spec.base_case_text);
    write_file_atomically((out / "spec.sha256").string(), plan.spec.spec_sha256 + "\n");
  }
}

}  // namespace

Progress run_shard(const Plan& plan, const std::string& out, Shard shard, unsigned threads,
                   const std::function<void(const Progress&)>& progress) {
  if (shard.n < 1 || shard.k < 0 || shard.k >= shard.n) {
    throw InputError("shard", std::to_string(shard.k) + "/" + std::to_string(shard.n),
                     "K/N with 0 <= K < N");
  }
  const fs::path folder(out);
  const char* extension = record_extension(plan.spec.format);
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    throw InputError("out", out, "an existing folder (the shards of a set share it)");
  }
  require_same_spec(plan, folder);
  Progress p;
  std::vector<const Record*> mine;
  for (const Record& r : plan.records) {
    if (static_cast<int>(r.id % static_cast<std::size_t>(shard.n)) != shard.k) continue;
    if (complete_record(folder, r.id, plan.spec.spec_sha256, extension).valid) {
      ++p.skipped;
    } else {
      mine.push_back(&r);
    }
  }
  p.total = mine.size() + p.skipped;
  // The disk must hold what is left with a margin (the estimate is rough), before any work.
  const double needed = 1.2 * plan.bytes_per_record * static_cast<double>(mine.size());
  const fs::space_info space = fs::space(folder, error);
  if (!error && static_cast<double>(space.available) < needed) {
    throw InputError(std::vector<Problem>{refused_problem(
        "out", out,
        "its file system has " + shortest_decimal(static_cast<double>(space.available)) +
            " bytes free, below 1.2 times the shard's estimate (" + shortest_decimal(needed / 1.2) +
            " bytes)",
        "a folder on a file system with room for the records")});
  }
  write_spec_files(plan, folder);
  const double cpu0 = cpu_seconds();
  const auto wall0 = std::chrono::steady_clock::now();
  // Records on the pool's workers, each stiffness table built once per gear pair and model; a
  // record depends on nothing but its plan and id, so the threads change no byte. After a
  // failure the records not yet begun are skipped, not made.
  // Declared before the pool, whose destructor waits for the tasks that read it.
  std::atomic<bool> failed{false};
  RunPool pool(threads);
  std::vector<std::future<void>> made;
  made.reserve(mine.size());
  for (const Record* r : mine) {
    made.push_back(pool.run([&plan, &pool, &folder, &failed, extension, r] {
      if (failed.load()) return;
      try {
        const auto table = pool.table_for(plan.conditions.at(r->condition).simulation_case);
        const RecordData data = make_record(plan, *r, table.get());
        const std::string bytes = record_file(plan, *r, data);
        const std::string name = record_name(r->id);
        write_file_atomically((folder / (name + extension)).string(), bytes);
        // The sidecar last: its presence, with the file's digest, marks the record complete.
        write_file_atomically((folder / (name + ".json")).string(),
                              sidecar(plan, *r, data, sha256_hex(bytes)));
      } catch (...) {
        failed.store(true);
        throw;
      }
    }));
  }
  for (std::future<void>& f : made) {
    f.get();
    ++p.done;
    p.signal_s += plan.spec.duration_s;
    p.cpu_s = cpu_seconds() - cpu0;
    p.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const std::size_t left = p.total - p.done - p.skipped;
    p.remaining_s =
        p.done == 0 ? 0.0 : p.elapsed_s / static_cast<double>(p.done) * static_cast<double>(left);
    if (progress) progress(p);
  }
  p.cpu_s = cpu_seconds() - cpu0;
  p.elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return p;
}

std::string labels_csv(const Plan& plan, const std::vector<std::string>& record_json) {
  const char* extension = record_extension(plan.spec.format);
  std::string csv = "record_id,file,split,condition,replicate,seed";
  for (const Factor& f : plan.spec.factors) csv += "," + column_name(f);
  const bool trajectory = plan.spec.trajectory.has_value();
  if (trajectory) csv += ",trajectory,trajectory_step,cycles,cycles_to_failure,rul_cycles";
  csv += ",realised_snr_db,clipped,settled,speed_drift_max_rel,theta1_start_rad,file_sha256\n";
  for (std::size_t id = 0; id < plan.records.size(); ++id) {
    const nlohmann::json j = nlohmann::json::parse(record_json.at(id));
    const Record& r = plan.records[id];
    const Condition& c = plan.conditions[r.condition];
    csv += std::to_string(id) + "," + record_name(id) + extension + "," + c.split + "," +
           std::to_string(r.condition) + "," + std::to_string(r.replicate) + "," +
           std::to_string(r.seed);
    for (std::size_t i = 0; i < plan.spec.factors.size(); ++i) {
      csv += ",";
      csv += plan.spec.factors[i].numeric ? shortest_decimal(c.values[i]) : c.texts[i];
    }
    if (trajectory) {
      csv += "," + std::to_string(c.trajectory) + "," + std::to_string(c.trajectory_step) + "," +
             shortest_decimal(c.cycles) + "," + shortest_decimal(c.cycles_to_failure) + "," +
             shortest_decimal(c.cycles_to_failure - c.cycles);
    }
    csv += "," + j.at("realised_snr_db").get<std::string>() + "," +
           std::to_string(j.at("clipped").get<long long>()) + "," +
           (j.at("settled").get<bool>() ? "1" : "0") + "," +
           j.at("speed_drift_max_rel").get<std::string>() + "," +
           j.at("theta1_start_rad").get<std::string>() + "," +
           j.at("file_sha256").get<std::string>() + "\n";
  }
  return csv;
}

namespace {

std::string card(const Plan& plan, const std::vector<std::string>& record_json) {
  const DatasetSpec& s = plan.spec;
  const std::size_t n = plan.records.size();
  std::string size_category = n < 1000     ? "n<1K"
                              : n < 10000  ? "1K<n<10K"
                              : n < 100000 ? "10K<n<100K"
                                           : "100K<n<1M";
  std::string t = "---\npretty_name: " + s.name + "\nlicense: unspecified\nsize_categories:\n- " +
                  size_category + "\nannotations_creators:\n- machine-generated\n---\n\n";
  t += "# " + s.name + "\n\n";
  t += "A simulated data set of gearimpact " + code_version() + ": " + std::to_string(n) +
       " records of " + shortest_decimal(s.duration_s) + " s at " +
       shortest_decimal(s.sample_rate_hz) + " Hz (" + std::to_string(plan.samples_per_record) +
       " samples each) after " + shortest_decimal(s.settle_s) +
       " s of settling, discarded. Spec sha256 " + s.spec_sha256 + ".\n\n";
  t += "## Generation\n\n";
  t +=
      "Base case `" + s.base_case_path.filename().string() +
      "` (in this folder as `base_case.toml`; each record "
      "holds its own case in `/provenance/case_toml`): " +
      std::string(plan.conditions.front().simulation_case.bearings.kind == BearingKind::elastic
                      ? "planar model on elastic bearings; the sensor is the acceleration of the "
                        "sensor gear's centre along its direction, m/s2"
                      : "torsional model; the sensor is the wheel's angular acceleration, rad/s2") +
      ", sampled as interval averages (transfer sinc(f T)). Drive as the case gives it. "
      "Recorder chain: ";
  const RecorderSettings& r = s.recorder;
  t += r.path_modes > 0 ? std::to_string(r.path_modes) + "-mode transfer path (" +
                              (r.path_per_record ? "per record" : "one for the set") + "), "
                        : "no transfer path, ";
  t += r.accelerometer_resonance_hz
           ? "accelerometer resonance " + shortest_decimal(*r.accelerometer_resonance_hz) + " Hz, "
           : "no accelerometer resonance, ";
  t +=
      r.noise_snr_db ? "noise at " + shortest_decimal(*r.noise_snr_db) + " dB SNR, " : "no noise, ";
  t += r.adc_range ? "ADC +-" + shortest_decimal(*r.adc_range) + ", " + std::to_string(r.adc_bits) +
                         " bits."
                   : "no ADC.";
  t += " (Base-case values of the recorder; a factor may change them per condition.)\n\n";
  t += "## Factors and design\n\n";
  t += std::string("Design: ") +
       (s.design == DesignKind::grid              ? "full grid"
        : s.design == DesignKind::latin_hypercube ? "Latin hypercube"
                                                  : "seeded random") +
       ", " + std::to_string(plan.conditions.size()) + " conditions x " +
       std::to_string(s.replicates) +
       " replicates (replicates differ by their seed: start "
       "angle, noise, path per record, tacho jitter). Set seed " +
       std::to_string(s.seed) + ".\n\n";
  t += "| factor | label column | values |\n|---|---|---|\n";
  for (std::size_t i = 0; i < s.factors.size(); ++i) {
    const Factor& f = s.factors[i];
    std::map<std::string, int> counts;
    double lo = INFINITY, hi = -INFINITY;
    for (const Condition& c : plan.conditions) {
      counts[c.texts[i]] += s.replicates;
      if (f.numeric) {
        lo = std::min(lo, c.values[i]);
        hi = std::max(hi, c.values[i]);
      }
    }
    std::string values;
    if (counts.size() <= 12) {
      for (const auto& [v, k] : counts) {
        values += (values.empty() ? "" : ", ") + v + " (" + std::to_string(k) + " records)";
      }
    } else {
      values = std::to_string(counts.size()) + " values in [" + shortest_decimal(lo) + ", " +
               shortest_decimal(hi) + "] " + f.unit;
    }
    t += "| `" + f.key + "` | `" + column_name(f) + "` | " + values + " |\n";
  }
  if (s.trajectory) {
    const Trajectory& tr = *s.trajectory;
    t += "\nDegradation: every condition of the design is a trajectory of " +
         std::to_string(tr.snapshots) + " snapshots of `" + tr.key + "` from " +
         shortest_decimal(tr.initial_m) + " m to " + shortest_decimal(tr.final_m) +
         " m, grown by Paris' law da/dN = C (Y dsigma sqrt(pi a))^m with C = " +
         shortest_decimal(tr.paris_c) +
         " m/cycle (dK in MPa sqrt(m)), m = " + shortest_decimal(tr.paris_m) +
         ", Y = " + shortest_decimal(tr.geometry_factor) +
         ", dsigma = " + shortest_decimal(tr.stress_range_pa * 1e-6) +
         " MPa; N counts revolutions "
         "of the faulted gear, " +
         (tr.even_in_depth ? "snapshots evenly in depth" : "snapshots evenly in N") + ", " +
         shortest_decimal(paris_cycles(tr, tr.final_m)) +
         " cycles to the final depth. "
         "Each snapshot is a steady record in which the crack does not grow. Labels: trajectory, "
         "trajectory_step, cycles, cycles_to_failure, rul_cycles.\n";
  }
  t += "\n## Splits\n\n";
  std::map<std::string, int> splits;
  for (const Record& rec : plan.records) splits[plan.conditions[rec.condition].split] += 1;
  for (const auto& [name, k] : splits) t += "- " + name + ": " + std::to_string(k) + " records\n";
  for (const HeldOut& h : s.heldout) {
    t += "- held out to `" + h.split + "`: `" + h.key + "` " +
         (h.range ? "in [" + shortest_decimal(h.range->first) + ", " +
                        shortest_decimal(h.range->second) + "] (SI)"
                  : "at " +
                        [&] {
                          std::string l;
                          for (const std::string& v : h.levels) l += (l.empty() ? "" : ", ") + v;
                          return l;
                        }()) +
         "\n";
  }
  t += "\nWhole conditions go to one split: no condition's replicates span two.\n\n";
  t += "## Labels and quality\n\n";
  int settled = 0;
  long long clipped = 0;
  double snr_lo = INFINITY, snr_hi = -INFINITY;
  for (const std::string& text : record_json) {
    const nlohmann::json j = nlohmann::json::parse(text);
    settled += j.at("settled").get<bool>() ? 1 : 0;
    clipped += j.at("clipped").get<long long>();
    const std::string snr = j.at("realised_snr_db").get<std::string>();
    if (!snr.empty()) {
      snr_lo = std::min(snr_lo, std::stod(snr));
      snr_hi = std::max(snr_hi, std::stod(snr));
    }
  }
  t += "`labels.csv`: one row per record (record_id, file, split, condition, replicate, seed, each "
       "factor in SI with its unit in the column's name, the trajectory's columns if any, "
       "realised_snr_db, clipped, settled, "
       "speed_drift_max_rel, theta1_start_rad, file_sha256). Settled (halves' RMS within 2 %): " +
       std::to_string(settled) + " of " + std::to_string(n) +
       ". Samples clipped: " + std::to_string(clipped) + ".";
  if (std::isfinite(snr_lo)) {
    t += " Realised SNR " + shortest_decimal(snr_lo) + " to " + shortest_decimal(snr_hi) + " dB.";
  }
  if (s.format == RecordFormat::mat) {
    t +=
        "\n\n## Loading\n\nOne MATLAB v5 MAT-file per record: `time`, `signals.sensor`, "
        "`truth.*`, `tacho.*`, `provenance.case_toml`, and the attributes of each path under "
        "`attributes` (`attributes.root.sample_rate_hz`, `attributes.labels.*`; layout: "
        "docs/datasets.md of gearimpact). MATLAB:\n\n```matlab\n"
        "T = readtable('labels.csv', 'Delimiter', ',', 'VariableNamingRule', 'preserve');\n"
        "r = load(T.file{1});\nx = r.signals.sensor;\nfs = r.attributes.root.sample_rate_hz;\n"
        "```\n\nPython (scipy):\n\n```python\nimport csv, numpy as np, scipy.io\n"
        "rows = list(csv.DictReader(open(\"labels.csv\")))\n"
        "x = np.stack([scipy.io.loadmat(r[\"file\"], simplify_cells=True)[\"signals\"][\"sensor\"] "
        "for r in rows])\n```\n\n";
  } else if (s.format == RecordFormat::npz) {
    t += "\n\n## Loading\n\nOne NumPy archive per record (`numpy.load`: each channel a .npy "
         "member named by its path, `signals/sensor`, `truth/w1_rad_s`, ...; the attributes in "
         "`attributes.json`, the case and spec as .txt; layout: docs/datasets.md of gearimpact). "
         "Python (numpy):\n\n```python\nimport csv, json, numpy as np\n"
         "rows = list(csv.DictReader(open(\"labels.csv\")))\n"
         "x = np.stack([np.load(r[\"file\"])[\"signals/sensor\"] for r in rows])\n"
         "fs = "
         "json.loads(np.load(rows[0][\"file\"])[\"attributes.json\"])[\"/\"][\"sample_rate_hz\"]\n"
         "y = np.array([r[\"split\"] for r in rows])\n```\n\n"
         "MATLAB reads the .npy members after unzip (a .npy reader such as npy-matlab's readNPY), "
         "or make the set as HDF5 (`format = \"hdf5\"`).\n\n";
  } else {
    t += "\n\n## Loading\n\nOne HDF5 file per record (layout: docs/datasets.md of gearimpact). "
         "Python (h5py, numpy):\n\n```python\nimport csv, h5py, numpy as np\n"
         "rows = list(csv.DictReader(open(\"labels.csv\")))\n"
         "x = np.stack([h5py.File(r[\"file\"], \"r\")[\"signals/sensor\"][:] for r in rows])\n"
         "y = np.array([r[\"split\"] for r in rows])\n```\n\n"
         "MATLAB:\n\n```matlab\nT = readtable('labels.csv', 'Delimiter', ',', "
         "'VariableNamingRule', "
         "'preserve');\n"
         "x = h5read(T.file{1}, '/signals/sensor');\n"
         "fs = h5readatt(T.file{1}, '/', 'sample_rate_hz');\n```\n\n";
  }
  t += "## Limitations\n\nSpur gears, lumped bearings, no casing (a transfer path is an "
       "augmentation model, not a casing model); cracks do not grow within a record.\n\n";
  t += "## Citation\n\nYang, D. C. H. and Lin, J. Y. (1987), Hertzian damping, tooth friction and "
       "bending elasticity in gear impact dynamics, ASME J. Mech. Trans. Autom. Des. 109(2), "
       "189-196; and gearimpact (CITATION.cff).\n";
  return t;
}

}  // namespace

void merge(const std::vector<std::string>& folders, const std::string& out, bool overwrite) {
  if (folders.empty()) throw InputError("DIR", "none", "one or more folders of a set's shards");
  const fs::path first(folders.front());
  const std::string sha = read_all(first / "spec.sha256");
  if (sha.empty()) {
    throw InputError("DIR", folders.front(), "a folder `gearimpact dataset` wrote (spec.sha256)");
  }
  for (const std::string& f : folders) {
    const std::string other = read_all(fs::path(f) / "spec.sha256");
    if (other != sha) {
      throw InputError(
          "DIR", f,
          "a shard of the same spec (spec sha256 " + sha.substr(0, sha.size() - 1) +
              "; this folder's: " +
              (other.empty() ? std::string("none") : other.substr(0, other.size() - 1)) + ")");
    }
  }
  Bounds none;
  none.max_records = none.max_samples = none.max_bytes = INFINITY;
  const Plan plan = make_plan(
      parse_spec_with_base(read_all(first / "spec.toml"), first, (first / "spec.toml").string(),
                           read_all(first / "base_case.toml")),
      none);
  const std::string spec_sha = plan.spec.spec_sha256;
  const char* extension = record_extension(plan.spec.format);
  if (spec_sha + "\n" != sha) {
    throw InputError("DIR", folders.front(),
                     "spec.toml and base_case.toml whose sha256 is spec.sha256's");
  }
  std::vector<std::string> sidecars(plan.records.size());
  std::vector<fs::path> files(plan.records.size());
  std::vector<std::string> missing;
  for (const Record& r : plan.records) {
    std::vector<std::string> holders;
    for (const std::string& f : folders) {
      const fs::path folder(f);
      const bool present = fs::exists(folder / (record_name(r.id) + ".json")) ||
                           fs::exists(folder / (record_name(r.id) + extension));
      if (!present) continue;
      const Sidecar s = complete_record(folder, r.id, spec_sha, extension);
      if (!s.valid) {
        throw InputError("record " + std::to_string(r.id), (folder / record_name(r.id)).string(),
                         "a complete record: its " + std::string(extension) +
                             " and .json of this spec, the file's sha256 "
                             "as the .json holds (rerun the shard to complete it)");
      }
      if (!holders.empty() && fs::equivalent(fs::path(holders.front()), folder)) continue;
      holders.push_back(f);
      sidecars[r.id] = s.json.dump();
      files[r.id] = folder / (record_name(r.id) + extension);
    }
    if (holders.size() > 1) {
      throw InputError("record " + std::to_string(r.id), holders[0] + ", " + holders[1],
                       "one shard folder per record (a record in two folders)");
    }
    if (holders.empty()) missing.push_back(std::to_string(r.id));
  }
  if (!missing.empty()) {
    std::string list;
    for (std::size_t i = 0; i < missing.size() && i < 10; ++i) list += (i ? ", " : "") + missing[i];
    if (missing.size() > 10) list += ", ...";
    throw InputError("records", std::to_string(missing.size()) + " missing",
                     "every record of the set (missing: " + list + "; run their shards)");
  }
  AtomicFolder folder(out, overwrite, folders);
  const fs::path tmp(folder.temporary());
  write_file_atomically((tmp / "spec.toml").string(), plan.spec.spec_text);
  write_file_atomically((tmp / "base_case.toml").string(), plan.spec.base_case_text);
  write_file_atomically((tmp / "spec.sha256").string(), sha);
  write_file_atomically((tmp / "labels.csv").string(), labels_csv(plan, sidecars));
  write_file_atomically((tmp / "DATASET_CARD.md").string(), card(plan, sidecars));
  for (const Record& r : plan.records) {
    const fs::path target = tmp / (record_name(r.id) + extension);
    std::error_code link_error;
    fs::create_hard_link(files[r.id], target, link_error);
    if (link_error) write_file_atomically(target.string(), read_all(files[r.id]));
  }
  folder.commit();
}

}  // namespace gearimpact::dataset
