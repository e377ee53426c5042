#!/usr/bin/env bash
# Submits a sharded data set to Slurm: a job array of N shards (dataset.sbatch), at most M running
# at once with --throttle M, and a merge job (merge-dataset.sbatch) that starts only when every
# shard has succeeded (afterok) and is cancelled if one fails (--kill-on-invalid-dep).
#
#   scripts/slurm/submit-dataset.sh --shards N --out OUT [--throttle M] [--gearimpact PATH] \
#     SPEC [dataset options...]
#
# The shards write OUT/records/, the merge OUT/merged/, the jobs' logs go to OUT/logs/. PATH
# defaults to this checkout's build/bin/gearimpact. The jobs run in the folder this is run from.
# Partition, account, time limit and the like come from sbatch's own environment variables
# (SBATCH_PARTITION, SBATCH_ACCOUNT, SBATCH_TIMELIMIT, ...). A shard should hold at least ten
# CPU minutes of records: each array task is its own allocation. A task that fails or is killed
# keeps its finished records; submitting the same command again completes the set. Prints
#   array_job=ID shards=N out=OUT
#   merge_job=ID merged=OUT/merged
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd -P)"

usage() {
  echo "usage: $0 --shards N --out OUT [--throttle M] [--gearimpact PATH] SPEC [dataset options...]" >&2
  exit 2
}

tool=submit-dataset options="--throttle" throttle="" gearimpact="$here/../../build/bin/gearimpact"
source "$here/../shard-options.sh"
shard_options_read "$@"
shift "$shard_options_used"
mkdir -p "$out/logs" "$out/records"
out="$(cd "$out" && pwd -P)"
array="0-$((shards - 1))${throttle:+%$throttle}"

array_job="$(sbatch --parsable --array="$array" --output="$out/logs/shard-%a.out" \
  "$here/dataset.sbatch" --gearimpact "$gearimpact" --shards "$shards" --out "$out" -- "$@")"
array_job="${array_job%%;*}"
if ! merge_job="$(sbatch --parsable --dependency="afterok:$array_job" --kill-on-invalid-dep=yes \
  --output="$out/logs/merge.out" \
  "$here/merge-dataset.sbatch" --gearimpact "$gearimpact" --out "$out")"; then
  echo "submit-dataset: the merge job was not accepted; cancelling array job $array_job" >&2
  scancel "$array_job" || true
  exit 1
fi
merge_job="${merge_job%%;*}"
echo "array_job=$array_job shards=$shards out=$out"
echo "merge_job=$merge_job merged=$out/merged"
