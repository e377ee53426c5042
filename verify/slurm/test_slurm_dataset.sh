#!/usr/bin/env bash
# A sharded data set through Slurm, end to end, on a one-node cluster started for the test:
#
#   test_slurm_dataset.sh SCRATCH PROGRAM SPEC
#
# scripts/slurm/submit-dataset.sh submits a job array of 3 shards (at most 2 at once) and the merge
# job that depends on it; the test waits for both and checks that every task and the merge
# succeeded, and that the merged set is byte-identical to the set made whole without Slurm. A
# second submission whose shards all fail must leave its merge job cancelled, never run. Every
# daemon is stopped on exit. Exits 77 (a skip for ctest) only when local-cluster.sh reports that a
# daemon cannot start on this machine.
set -euo pipefail
export LC_ALL=C

readonly status_skip=77
readonly shards=3
# Queueing on an idle one-node cluster takes a few seconds; a minute means something is stuck.
readonly jobs_timeout_s=60

(($# == 3)) || { echo "usage: $0 SCRATCH PROGRAM SPEC" >&2; exit 2; }
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

cd "$scratch"
"$program" dataset "$@" --out whole --quiet >/dev/null
"$program" dataset merge whole --out whole-merged >/dev/null

submitted="$("$repo/scripts/slurm/submit-dataset.sh" --shards "$shards" --throttle 2 \
  --out "$scratch/sharded" --gearimpact "$program" "$@" --quiet)"
echo "$submitted"
array_job="$(sed -n 's/^array_job=\([0-9]*\) .*/\1/p' <<<"$submitted")"
merge_job="$(sed -n 's/^merge_job=\([0-9]*\) .*/\1/p' <<<"$submitted")"
[[ -n "$array_job" && -n "$merge_job" ]] || fail "submit-dataset.sh printed no job ids"
submitted="$("$repo/scripts/slurm/submit-dataset.sh" --shards 2 --out "$scratch/failing" \
  --gearimpact false "$@")"
failing_merge_job="$(sed -n 's/^merge_job=\([0-9]*\) .*/\1/p' <<<"$submitted")"

deadline=$((SECONDS + jobs_timeout_s))
while [[ -n "$(squeue -h -o %i)" ]]; do
  if ((SECONDS > deadline)); then
    squeue >&2
    fail "jobs still queued or running after $jobs_timeout_s s"
  fi
  sleep 0.5
done

field() { scontrol -o show job "$1" | grep -o " $2=[^ ]*" | cut -d= -f2- || true; }
states="$(field "$array_job" JobState | sort | uniq -c | tr -s ' ')"
[[ "$states" == " $shards COMPLETED" ]] ||
  fail "array job $array_job: task states '$states', expected $shards COMPLETED"
pass "array job $array_job: $shards tasks COMPLETED"
[[ "$(field "$merge_job" JobState)" == COMPLETED ]] || fail "merge job $merge_job did not complete"
pass "merge job $merge_job COMPLETED"
for file in whole-merged/*; do
  cmp "$file" "sharded/merged/$(basename "$file")" ||
    fail "$(basename "$file") of $shards Slurm shards differs from the whole set's"
done
pass "every file of the merged Slurm set is byte-identical to the whole set's"
state="$(field "$failing_merge_job" JobState) $(field "$failing_merge_job" Reason)"
[[ "$state" == "CANCELLED DependencyNeverSatisfied" ]] ||
  fail "merge job $failing_merge_job after failed shards: '$state'"
[[ ! -e failing/merged ]] || fail "the merge after failed shards ran"
pass "merge job $failing_merge_job after failed shards: $state, never ran"

echo "slurm dataset: $checks checks passed in $((SECONDS - started)) s"
