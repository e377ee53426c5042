#!/usr/bin/env bash
# Submits a sharded parameter sweep to Slurm: a job array of N shards (sweep.sbatch) and a merge
# job (merge.sbatch) that starts only when every shard has succeeded (afterok) and is cancelled
# if one fails (--kill-on-invalid-dep), so that no merge of a partial sweep is ever attempted.
#
#   scripts/slurm/submit-sweep.sh --shards N --out OUT [--gearimpact PATH] CASE [sweep options...]
#
# Shard K (0-based) writes OUT/shard-K/, the merge OUT/merged/, the jobs' logs go to OUT/logs/.
# PATH defaults to this checkout's build/bin/gearimpact. The jobs run in the folder this is run
# from, so relative paths in CASE and the sweep options mean the same to them. Partition, account,
# time limit and the like come from sbatch's own environment variables (SBATCH_PARTITION,
# SBATCH_ACCOUNT, SBATCH_TIMELIMIT, ...), which apply to both jobs. Prints
#   array_job=ID shards=N out=OUT
#   merge_job=ID merged=OUT/merged
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd -P)"

usage() {
  echo "usage: $0 --shards N --out OUT [--gearimpact PATH] CASE [sweep options...]" >&2
  exit 2
}

tool=submit-sweep options="" gearimpact="$here/../../build/bin/gearimpact"
source "$here/../shard-options.sh"
shard_options_read "$@"
shift "$shard_options_used"
mkdir -p "$out/logs"
out="$(cd "$out" && pwd -P)"

array_job="$(sbatch --parsable --array="0-$((shards - 1))" --output="$out/logs/shard-%a.out" \
  "$here/sweep.sbatch" --gearimpact "$gearimpact" --shards "$shards" --out "$out" -- "$@")"
array_job="${array_job%%;*}"
if ! merge_job="$(sbatch --parsable --dependency="afterok:$array_job" --kill-on-invalid-dep=yes \
  --output="$out/logs/merge.out" \
  "$here/merge.sbatch" --gearimpact "$gearimpact" --shards "$shards" --out "$out")"; then
  echo "submit-sweep: the merge job was not accepted; cancelling array job $array_job" >&2
  scancel "$array_job" || true
  exit 1
fi
merge_job="${merge_job%%;*}"
echo "array_job=$array_job shards=$shards out=$out"
echo "merge_job=$merge_job merged=$out/merged"
