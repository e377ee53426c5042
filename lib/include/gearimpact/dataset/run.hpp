// Making a data set's records (docs/datasets.md): one record is the case simulated with its
// sensor sampled, the settle time discarded, through the recorder chain, with the truth per
// sample; each is written as one HDF5 file, atomically, and skipped when found complete, so that
// a set run whole, in shards or resumed after a kill gives the same bytes. The merge checks
// every record and writes the labels table and the card.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/dataset/spec.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact::dataset {

// The records of shard k of n: those whose id % n == k.
struct Shard {
  int k = 0;
  int n = 1;
};

// What a record's labels hold beyond its factors.
struct RecordLabels {
  double realised_snr_db = 0.0;  // NaN without noise
  long long clipped = 0;
  bool settled = true;
  double speed_drift_max_rel = 0.0;  // NaN before a whole revolution
  double theta1_start_rad = 0.0;     // the pinion's angle at t = 0 (dataset.start_angle)
};

// One record's arrays and labels.
struct RecordData {
  std::vector<double> time_s;  // from the record's start (after the settle time)
  std::vector<double> sensor;
  std::string sensor_units;
  std::string sensor_quantity;
  // Per sample, in truth_channels() order.
  std::vector<std::vector<double>> truth;
  // Per sample: 1 when the drive flanks carry, plus 2 when the coast flanks carry.
  std::vector<std::int8_t> contact;
  std::vector<double> tacho_times_s;          // true edges within the record; empty: no tacho
  std::vector<double> tacho_emitted_times_s;  // with the seeded jitter
  RecordLabels labels;
  std::string case_toml;  // the record's case, SI, as a case file
};

// Simulates and records one record of the plan; `table`, when given, is the stiffness table of
// its condition's gear pair and model (RunPool::table_for), built once for many records.
RecordData make_record(const Plan& plan, const Record& record,
                       const StiffnessTable* table = nullptr);

// The record's HDF5 file, as bytes (the layout of docs/datasets.md).
std::string record_file(const Plan& plan, const Record& record, const RecordData& data);

// The code version written into every record: the project's version and `git describe` at
// configure time.
std::string code_version();

struct Progress {
  std::size_t done = 0;     // this run's records made
  std::size_t skipped = 0;  // found complete
  std::size_t total = 0;    // the shard's records
  double signal_s = 0.0;    // seconds of signal made
  double cpu_s = 0.0;
  double elapsed_s = 0.0;
  double remaining_s = 0.0;  // estimate
};

// Makes the shard's records into out/records/ (out must exist): each record's r<id>.h5, then its
// r<id>.json (labels, the file's sha256, the spec's sha256), both atomic; a record whose pair is
// complete and verifies is skipped. out/spec.toml holds the spec; a folder of another spec is
// refused. Records run on `threads` workers (0: one per core), which change no byte;
// `progress` is called, on the calling thread, as each record is written, in id order.
Progress run_shard(const Plan& plan, const std::string& out, Shard shard, unsigned threads = 1,
                   const std::function<void(const Progress&)>& progress = {});

// The labels table of the records (docs/datasets.md, labels.csv).
std::string labels_csv(const Plan& plan, const std::vector<std::string>& record_json);

// Checks the folders' records (every id of the plan present once, the same spec sha256, each
// file's sha256) and writes `out` as one set: spec.toml, labels.csv, DATASET_CARD.md and
// records/ (hard links where the file system allows, else copies). Throws InputError naming the
// first missing, doubled or foreign record.
void merge(const std::vector<std::string>& folders, const std::string& out, bool overwrite);

}  // namespace gearimpact::dataset
