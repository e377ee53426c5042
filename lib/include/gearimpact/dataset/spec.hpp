// A data set's spec (docs/datasets.md): a base case, factors over its keys and the recorder's,
// a design over the factors, held-out conditions and replicates; and its plan, the records it
// makes, each case validated by the schema before any record is made.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/signals/decimate.hpp"

namespace gearimpact::dataset {

// What the recorder does to the sampled sensor (signals/recorder.hpp), in the order it does it:
// a transfer path of seeded modes, an accelerometer resonance, noise at an SNR, an ADC.
struct RecorderSettings {
  // M: the sensor is sampled and filtered at M x the set's sample rate, then brought to it by
  // the anti-alias decimator (signals::anti_alias_resample); 1: no decimator.
  int oversample = 1;
  std::optional<double> accelerometer_resonance_hz;
  double accelerometer_damping = 0.02;
  int path_modes = 0;
  double path_band_low_hz = 1000.0;
  double path_band_high_hz = 8000.0;
  double path_damping_low = 0.01;
  double path_damping_high = 0.05;
  // false: one path for the whole set (one machine), drawn from the set's seed; true: a path
  // per record, from the record's seed (augmentation).
  bool path_per_record = false;
  std::optional<double> noise_snr_db;
  bool noise_exact = false;
  std::optional<double> adc_range;  // in the sensor's unit
  int adc_bits = 16;
  // Mixed into every record's noise and path seeds: a factor over it gives other draws.
  std::int64_t seed = 0;
};

// One key of [recorder]: its name as a factor addresses it ("recorder.noise_snr"), its unit,
// range and help, and how it sets RecorderSettings. The one home of these ranges.
struct RecorderKey {
  std::string_view key;
  std::optional<Dimension> dimension;  // none: a plain number (dB for noise_snr)
  std::string_view unit;               // SI unit as labels name it ("Hz", "dB", "")
  double lower;
  double upper;
  bool closed;  // [lower, upper], else (lower, upper)
  bool integer;
  std::string_view help;
  void (*set)(RecorderSettings&, double);
};
const std::vector<RecorderKey>& recorder_keys();

// What a record's oversampling takes (docs/datasets.md, "The anti-alias decimator"): the
// simulation's rate M fs, the decimator's filter (kaiser_low_pass(M fs, 0.4 fs, 0.5 fs, 100 dB),
// the one anti_alias_resample designs), and the fine samples the record needs: from index 1 (the
// recorder's filters settle over the settle time) to the last output's instant plus half the
// filter's span, the decimator's input starting `lead` output samples before the record.
struct Oversampling {
  int factor = 1;  // M
  double rate_hz = 0.0;
  std::optional<signals::KaiserLowPass> filter;  // none for M = 1
  long long lead = 0;                            // ceil(half span / M), in output samples
  long long last_fine = 0;                       // the last fine sample's index (t = i / (M fs))
};
// For a record of `samples` after `settle_samples` at sample_rate_hz.
Oversampling oversampling(double sample_rate_hz, const RecorderSettings& recorder,
                          long long settle_samples, long long samples);

// A factor: a key of the case schema as --set addresses it (faults[i].key included) or of
// [recorder], over levels (texts as a case file or --set writes them) or a range [low, high]
// in SI (`points` values on a grid, or stratified/random draws).
struct Factor {
  std::string key;
  std::vector<std::string> levels;
  std::optional<std::pair<double, double>> range;
  int points = 0;       // a range on a grid
  std::string unit;     // the SI unit of its values ("m", "rad/s"; "" for a number or a name)
  bool numeric = true;  // false: a choice or a name, labelled as its text
};

enum class DesignKind { grid, latin_hypercube, random };

// A held-out region: the conditions whose factor `key` has one of `levels` or lies in `range`
// (SI, closed) go to split `split` (default "test"); the others to the spec's default split.
struct HeldOut {
  std::string key;
  std::vector<std::string> levels;
  std::optional<std::pair<double, double>> range;
  std::string split = "test";
};

// A degradation trajectory (run to failure): a crack's depth grown by Paris' law,
// da/dN = C dK^m with dK = Y dsigma sqrt(pi a) (C in m/cycle with dK in MPa sqrt(m); N counts
// revolutions of the faulted gear), sampled at `snapshots` steps from `initial` to `final`, evenly
// in N or in a. Each snapshot is a steady record in which the crack does not grow. Every condition
// of the design runs the whole trajectory, which stays in one split.
struct Trajectory {
  std::string key;  // faults[i].depth
  double initial_m = 0.0;
  double final_m = 0.0;
  double paris_c = 0.0;
  double paris_m = 0.0;
  double geometry_factor = 1.0;
  double stress_range_pa = 0.0;
  int snapshots = 2;
  bool even_in_depth = false;  // false: evenly in cycles
};

// Paris' law in closed form: the depth after n cycles from a0, and the cycles from a0 to a.
// a(N) = [a0^(1-m/2) + (1-m/2) C (Y dsigma sqrt(pi))^m N]^(1/(1-m/2)) for m != 2, a0 exp(C (Y
// dsigma)^2 pi N) for m = 2 (dsigma in MPa, a in m).
double paris_depth_m(const Trajectory& t, double cycles);
double paris_cycles(const Trajectory& t, double depth_m);

// A record's file: HDF5 (".h5", the default), a NumPy archive (".npz", the same arrays as .npy
// members and the attributes as JSON) or a MATLAB v5 MAT-file (".mat", through libmatio).
enum class RecordFormat { hdf5, npz, mat };

// The record file's extension: ".h5", ".npz" or ".mat".
const char* record_extension(RecordFormat format);

struct DatasetSpec {
  std::string name;
  std::uint64_t seed = 0;
  double duration_s = 0.0;
  double settle_s = 0.0;
  int replicates = 1;
  double sample_rate_hz = 0.0;
  // true ("random", the default): each record starts the pair turned by a seeded angle,
  // theta1 + d with d ~ U[0, 2 pi / z1) and theta2 + d Rb1 / Rb2 (the deflection unchanged), so
  // that replicates differ in their mesh phase, not in their noise alone; false ("case"): the
  // base case's angles.
  bool random_start = true;
  RecordFormat format = RecordFormat::hdf5;
  std::filesystem::path base_case_path;
  std::string base_case_text;
  SimulationCase base;
  RecorderSettings recorder;
  std::vector<Factor> factors;
  DesignKind design = DesignKind::grid;
  int design_points = 0;  // latin-hypercube, random
  std::uint64_t design_seed = 0;
  std::string default_split = "train";
  std::vector<HeldOut> heldout;
  std::optional<Trajectory> trajectory;
  std::string spec_text;
  // sha256 of the spec's text and the base case's: shards of one set share it.
  std::string spec_sha256;
};

// Reads a spec file (TOML, at most 1 MiB); the base case is read relative to its folder. Throws
// InputError naming the key as written ("factors[1].key", "dataset.duration") and what it allows.
DatasetSpec read_spec(const std::filesystem::path& path);
DatasetSpec parse_spec(std::string_view text, const std::filesystem::path& folder,
                       std::string_view file_name);
// The same with the base case's text given (a merge reads it from the set, not from its path).
DatasetSpec parse_spec_with_base(std::string_view text, const std::filesystem::path& folder,
                                 std::string_view file_name,
                                 const std::optional<std::string>& base_case_text);

// One condition: a value of each factor, as text for the case (a level, or a number in SI) and
// as the label's value (SI; NaN for a non-numeric factor, whose label is its text).
struct Condition {
  std::vector<std::string> texts;
  std::vector<double> values;
  std::string split;
  SimulationCase simulation_case;  // the base case with the factors set, validated
  RecorderSettings recorder;
  // With a trajectory: the design's condition it grows from, the snapshot, its cycles and the
  // cycles from its start to its final depth; values and texts end with the depth.
  std::size_t trajectory = 0;
  int trajectory_step = 0;
  double cycles = 0.0;
  double cycles_to_failure = 0.0;
};

struct Record {
  std::size_t id = 0;  // 0-based, the position in the set
  std::size_t condition = 0;
  int replicate = 0;
  std::uint64_t seed = 0;
};

// The bounds a set must keep, each refused before any work with its estimate.
struct Bounds {
  double max_records = 1e6;
  double max_samples = 1e11;  // over every record and channel
  double max_bytes = 200e9;
};

struct Plan {
  DatasetSpec spec;
  std::vector<Condition> conditions;
  std::vector<Record> records;
  std::size_t samples_per_record = 0;
  double bytes_per_record = 0.0;  // an estimate of one record's file
};

// The record's seed: a SplitMix64 hash of (set seed, condition, replicate), so that it depends
// on nothing else (not the shard, the order or a resume).
std::uint64_t record_seed(std::uint64_t set_seed, std::size_t condition, int replicate);

// The design's conditions, every case validated (its refusal names the condition and the key),
// the records (conditions x replicates, condition-major) and the bounds checked. Throws
// InputError before any record is made.
Plan make_plan(const DatasetSpec& spec, const Bounds& bounds = {});

// The channels every record has besides the sensor: the truth per sample.
struct ChannelInfo {
  std::string_view name;
  std::string_view units;
  std::string_view help;
};
const std::vector<ChannelInfo>& truth_channels();

}  // namespace gearimpact::dataset
