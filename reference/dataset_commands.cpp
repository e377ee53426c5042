// `gearimpact dataset SPEC --out DIR [--shard K/N]`: a labelled data set's records, sharded and
// resumable; `gearimpact dataset merge DIR... --out OUT`: the checked set with its labels table
// and card (docs/datasets.md). Glue only: the work is dataset/ of the library.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "case_flags.hpp"
#include "commands.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/dataset/run.hpp"
#include "gearimpact/dataset/spec.hpp"
#include "gearimpact/error.hpp"
#include "shard_flag.hpp"

namespace gearimpact::cli {

namespace {

struct DatasetOptions {
  std::string spec;
  std::string out;
  std::string shard;
  CLI::Option* shard_flag = nullptr;
  double max_records = 1e6;
  double max_samples = 1e11;
  double max_bytes = 200e9;
  unsigned threads = 1;
  bool plan_only = false;
  bool quiet = false;
};

struct MergeOptions {
  std::vector<std::string> folders;
  std::string out;
  bool overwrite = false;
};

std::string duration_text(double s) {
  char text[48];
  if (s < 120.0) {
    std::snprintf(text, sizeof text, "%.0f s", s);
  } else if (s < 7200.0) {
    std::snprintf(text, sizeof text, "%.1f min", s / 60.0);
  } else {
    std::snprintf(text, sizeof text, "%.1f h", s / 3600.0);
  }
  return text;
}

void check_bound(double value, const char* flag) {
  if (!(value >= 1.0) || !std::isfinite(value)) {
    throw InputError(flag, shortest_decimal(value), "a number >= 1");
  }
}

void run_dataset(const DatasetOptions& o) {
  check_bound(o.max_records, "--max-records");
  check_bound(o.max_samples, "--max-samples");
  check_bound(o.max_bytes, "--max-bytes");
  const ShardFlag shard =
      parse_shard_flag(o.shard, o.shard_flag != nullptr && o.shard_flag->count() > 0);
  dataset::Bounds bounds;
  bounds.max_records = o.max_records;
  bounds.max_samples = o.max_samples;
  bounds.max_bytes = o.max_bytes;
  dataset::Plan plan;
  try {
    plan = dataset::make_plan(dataset::read_spec(o.spec), bounds);
  } catch (const InputError& e) {
    // The library names its bounds as dataset::Bounds does; the program's are flags.
    std::vector<Problem> problems;
    for (Problem p : e.problems()) {
      for (const auto& [name, flag] :
           {std::pair{"max_records", "--max-records"}, std::pair{"max_samples", "--max-samples"},
            std::pair{"max_bytes", "--max-bytes"}}) {
        const std::string lifts = std::string("(") + name + " lifts the bound)";
        const std::size_t at = p.allowed.find(lifts);
        if (at != std::string::npos) {
          p.allowed.replace(at, lifts.size(), std::string("(") + flag + " lifts the bound)");
          p = refused_problem(p.field, p.value, p.reason, p.allowed, p.fix);
        }
      }
      problems.push_back(p);
    }
    throw InputError(problems);
  }
  const double records = static_cast<double>(plan.records.size());
  std::printf(
      "{\n  \"records\": %zu,\n  \"conditions\": %zu,\n  \"samples_per_record\": %zu,\n"
      "  \"bytes_estimate\": %.0f,\n  \"spec_sha256\": \"%s\",\n  \"code_version\": \"%s\",\n"
      "  \"shard\": \"%d/%d\"\n}\n",
      plan.records.size(), plan.conditions.size(), plan.samples_per_record,
      records * plan.bytes_per_record, plan.spec.spec_sha256.c_str(),
      dataset::code_version().c_str(), shard.k, shard.n);
  if (o.plan_only) return;
  if (o.out.empty()) throw InputError("--out", "none", "the set's folder (made if absent)");
  std::filesystem::create_directories(o.out);
  double last = -1e9;
  const auto progress = [&](const dataset::Progress& p) {
    const bool end = p.done + p.skipped == p.total;
    if (o.quiet || (!end && p.elapsed_s - last < 2.0)) return;
    last = p.elapsed_s;
    std::fprintf(stderr,
                 "dataset: shard %d/%d: %zu/%zu records (%zu found complete), %.3g s of signal per "
                 "CPU s, elapsed %s, about %s left\n",
                 shard.k, shard.n, p.done + p.skipped, p.total, p.skipped,
                 p.cpu_s > 0.0 ? p.signal_s / p.cpu_s : 0.0, duration_text(p.elapsed_s).c_str(),
                 duration_text(p.remaining_s).c_str());
  };
  if (o.threads > kMostThreads) {
    throw InputError("--threads", std::to_string(o.threads),
                     "an integer in [0, " + std::to_string(kMostThreads) + "] (0: all cores)");
  }
  dataset::Progress p;
  try {
    p = dataset::run_shard(plan, o.out, {shard.k, shard.n}, o.threads, progress);
  } catch (const InputError& e) {
    // The library names its arguments; the program, its flags.
    if (e.field() != "out" && e.field() != "shard") throw;
    std::vector<Problem> problems;
    for (const Problem& q : e.problems()) problems.push_back(q.renamed("--" + q.field, q.value));
    throw InputError(problems);
  }
  if (!o.quiet && p.done == 0) {
    std::fprintf(stderr, "dataset: shard %d/%d: all %zu records were complete\n", shard.k, shard.n,
                 p.total);
  }
}

}  // namespace

void register_dataset_commands(CLI::App& app) {
  auto o = std::make_shared<DatasetOptions>();
  CLI::App* cmd = app.add_subcommand(
      "dataset",
      "a labelled data set from a spec (base case, factors, design, splits, recorder): one HDF5 "
      "file per record in DIR, sharded (--shard K/N) and resumable; `dataset merge` checks the "
      "shards and writes labels.csv and DATASET_CARD.md (docs/datasets.md)");
  cmd->add_option("SPEC", o->spec, "the data set's spec (TOML, docs/datasets.md)");
  cmd->add_option("--out", o->out,
                  "the set's folder, shared by its shards (made if absent); a record found "
                  "complete there is kept, so that rerunning the command resumes");
  o->shard_flag = cmd->add_option(
      "--shard", o->shard,
      "K/N: the records whose id % N == K (default: SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN "
      "of SLURM_ARRAY_TASK_COUNT, else all)");
  cmd->add_option("--max-records", o->max_records,
                  "the most records the set may have (default 1e6)");
  cmd->add_option("--max-samples", o->max_samples,
                  "the most samples over every record and channel (default 1e11)");
  cmd->add_option("--max-bytes", o->max_bytes,
                  "the most bytes the records may take, estimated (default 2e11)");
  cmd->add_option("--threads", o->threads,
                  "records made at once in this process, 0 to 1024 (0: one per core; default 1); "
                  "the files are the same bytes for any count");
  cmd->add_flag("--plan", o->plan_only, "print the plan (counts, bytes) and stop");
  cmd->add_flag("--quiet", o->quiet, "no progress lines on stderr");
  cmd->require_subcommand(0, 1);
  auto m = std::make_shared<MergeOptions>();
  CLI::App* merge = cmd->add_subcommand(
      "merge",
      "check a set's shard folders (every record present once, of one spec, its sha256) and "
      "write OUT: the records, labels.csv, DATASET_CARD.md");
  merge->add_option("DIR", m->folders, "the shards' folders (one, when they share it)")->required();
  merge->add_option("--out", m->out, "the merged set's folder: new or empty (else --overwrite)")
      ->required();
  merge->add_flag("--overwrite", m->overwrite, "replace a non-empty --out folder whole");
  merge->callback([m] {
    dataset::merge(m->folders, m->out, m->overwrite);
    std::cout << "dataset merge: " << m->out << "\n";
  });
  cmd->callback([o, cmd] {
    if (cmd->get_subcommands().empty()) {
      if (o->spec.empty()) throw InputError("SPEC", "none", "a spec file (docs/datasets.md)");
      run_dataset(*o);
    }
  });
}

}  // namespace gearimpact::cli
