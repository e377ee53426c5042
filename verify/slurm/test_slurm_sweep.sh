#!/usr/bin/env bash
# A sharded sweep through Slurm, end to end, on a one-node cluster started for the test:
#
#   test_slurm_sweep.sh SCRATCH PROGRAM CASE [sweep options...]
#
# PROGRAM is the program with `sweep CASE ... --shard K/N --out DIR` and `merge DIR... --out DIR`
# (gearimpact, or any program with the same command line). scripts/slurm/submit-sweep.sh submits a
# job array of 3 shards and the merge job that depends on it; the test waits for both and checks
# that every task and the merge succeeded, that the merge ran after the last shard, that the
# shards split the rows between them, and that the merged files are byte-identical to a 1-shard
# sweep and merge run directly. A second submission whose shards all fail must leave its merge
# job cancelled, never run. Every daemon is stopped on exit, whatever happens. Exits 77 (a skip
# for ctest) only when local-cluster.sh reports that a daemon cannot start on this machine.
set -euo pipefail
export LC_ALL=C

readonly status_skip=77
readonly shards=3
# Queueing on an idle one-node cluster takes a few seconds; a minute means something is stuck.
readonly jobs_timeout_s=60

(($# >= 3)) || { echo "usage: $0 SCRATCH PROGRAM CASE [sweep options...]" >&2; exit 2; }
repo="$(cd "$(dirname "$0")/../.." && pwd -P)"
scratch="$1"
shift
program="$1"
shift
rm -rf "$scratch"
mkdir -p "$scratch"
scratch="$(cd "$scratch" && pwd -P)"
# The cluster's folder is short because unix socket paths under it are limited to 107 bytes.
cluster="$(mktemp -d /tmp/gearimpact-slurm.XXXXXX)"

cleanup() {
  local status=$?
  if ! "$repo/scripts/slurm/local-cluster.sh" stop "$cluster" >/dev/null; then
    echo "FAIL: a daemon of the test cluster could not be stopped (see above)" >&2
    status=1
  fi
  cp -r "$cluster/log" "$scratch/cluster-log" 2>/dev/null || true
  rm -rf "$cluster"
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM HUP

checks=0
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
pass() {
  checks=$((checks + 1))
  echo "ok: $*"
}

# Slurm's clients read SBATCH_*, SLURM_* and the like as defaults (a partition, an account): the
# caller's, if it runs inside a Slurm job or sets them, do not apply to this cluster.
while read -r variable; do
  unset "$variable"
done < <(compgen -e | grep -E '^(SBATCH|SLURM|SALLOC|SRUN|SQUEUE|SINFO|SCONTROL)_' || true)

started=$SECONDS
set +e
"$repo/scripts/slurm/local-cluster.sh" start "$cluster"
status=$?
set -e
if ((status == status_skip)); then
  echo "SKIP: the local Slurm cluster cannot start on this machine (reason above; logs in" \
    "$scratch/cluster-log)"
  exit "$status_skip"
fi
((status == 0)) || fail "local-cluster.sh start exited with status $status"
export SLURM_CONF="$cluster/slurm.conf"
echo "cluster up after $((SECONDS - started)) s"

# The reference: the whole sweep as one shard, without Slurm.
mkdir -p "$scratch/reference"
"$program" sweep "$@" --shard 0/1 --out "$scratch/reference/shard-0"
"$program" merge "$scratch/reference/shard-0" --out "$scratch/reference/merged"

cd "$scratch"
submitted="$("$repo/scripts/slurm/submit-sweep.sh" --shards "$shards" --out "$scratch/sharded" \
  --gearimpact "$program" "$@")"
echo "$submitted"
array_job="$(sed -n 's/^array_job=\([0-9]*\) .*/\1/p' <<<"$submitted")"
merge_job="$(sed -n 's/^merge_job=\([0-9]*\) .*/\1/p' <<<"$submitted")"
[[ -n "$array_job" && -n "$merge_job" ]] || fail "submit-sweep.sh printed no job ids"

# Shards that all fail (the program is false(1)): their merge must never run.
submitted="$("$repo/scripts/slurm/submit-sweep.sh" --shards 2 --out "$scratch/failing" \
  --gearimpact false "$@")"
echo "$submitted"
failing_array_job="$(sed -n 's/^array_job=\([0-9]*\) .*/\1/p' <<<"$submitted")"
failing_merge_job="$(sed -n 's/^merge_job=\([0-9]*\) .*/\1/p' <<<"$submitted")"

deadline=$((SECONDS + jobs_timeout_s))
while [[ -n "$(squeue -h -o %i)" ]]; do
  if ((SECONDS > deadline)); then
    squeue >&2
    fail "jobs still queued or running after $jobs_timeout_s s"
  fi
  sleep 0.5
done
echo "all jobs done $((SECONDS - started)) s after the start of the cluster"

# One value of a field per job record (an array job has one record per task).
field() { scontrol -o show job "$1" | grep -o " $2=[^ ]*" | cut -d= -f2- || true; }

states="$(field "$array_job" JobState | sort | uniq -c | tr -s ' ')"
[[ "$states" == " $shards COMPLETED" ]] ||
  fail "array job $array_job: task states '$states', expected $shards COMPLETED"
[[ "$(field "$array_job" ExitCode | sort -u)" == 0:0 ]] || fail "array job $array_job: exit codes"
pass "array job $array_job: $shards tasks COMPLETED, exit code 0"
[[ "$(field "$merge_job" JobState)" == COMPLETED && "$(field "$merge_job" ExitCode)" == 0:0 ]] ||
  fail "merge job $merge_job: $(field "$merge_job" JobState) $(field "$merge_job" ExitCode)"
pass "merge job $merge_job COMPLETED, exit code 0"
# Times are ISO 8601 to the second, so they compare as strings; equal seconds are allowed.
last_shard_end="$(field "$array_job" EndTime | sort | tail -n 1)"
merge_start="$(field "$merge_job" StartTime)"
[[ ! "$merge_start" < "$last_shard_end" ]] ||
  fail "merge job started at $merge_start, before the last shard ended at $last_shard_end"
pass "merge started at $merge_start, not before the last shard ended ($last_shard_end)"

for file in sweep.csv poincare.csv summary.json; do
  for ((k = 0; k < shards; k++)); do
    [[ -s "sharded/shard-$k/$file" ]] || fail "shard $k wrote no $file"
  done
  cmp "reference/merged/$file" "sharded/merged/$file" ||
    fail "merged $file of $shards shards differs from the 1-shard sweep's"
  pass "merged $file of $shards shards is byte-identical to the 1-shard sweep's"
done
for file in sweep.csv poincare.csv; do
  merged_rows=$(($(wc -l <"sharded/merged/$file") - 1))
  shard_rows=0
  for ((k = 0; k < shards; k++)); do
    rows=$(($(wc -l <"sharded/shard-$k/$file") - 1))
    ((rows > 0)) || fail "shard $k has no rows in $file: the sweep was not split"
    shard_rows=$((shard_rows + rows))
  done
  ((shard_rows == merged_rows)) ||
    fail "$file: the shards hold $shard_rows rows, the merge $merged_rows"
  pass "$file: the $merged_rows rows are split over the $shards shards, none twice"
done
for log in shard-0 shard-1 shard-2 merge; do
  [[ -s "sharded/logs/$log.out" ]] || fail "no job log sharded/logs/$log.out"
done
pass "each job wrote its log in sharded/logs"

states="$(field "$failing_array_job" JobState | sort -u)"
[[ "$states" == FAILED ]] || fail "failing array job $failing_array_job: states '$states'"
state="$(field "$failing_merge_job" JobState) $(field "$failing_merge_job" Reason)"
[[ "$state" == "CANCELLED DependencyNeverSatisfied" ]] ||
  fail "merge job $failing_merge_job after failed shards: '$state'"
[[ ! -e failing/merged && ! -e failing/logs/merge.out ]] ||
  fail "the merge after failed shards ran"
pass "merge job $failing_merge_job after failed shards: $state, never ran"

echo "slurm sweep: $checks checks passed in $((SECONDS - started)) s"
