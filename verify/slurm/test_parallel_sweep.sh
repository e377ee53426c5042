#!/usr/bin/env bash
# A sharded sweep through GNU parallel (scripts/parallel-sweep.sh), end to end:
#
#   test_parallel_sweep.sh SCRATCH PROGRAM CASE [sweep options...]
#
# PROGRAM is the program with `sweep CASE ... --shard K/N --out DIR` and `merge DIR... --out DIR`
# (gearimpact, or any program with the same command line). Checks that 3 shards on 2 job slots
# merge into files byte-identical to a 1-shard sweep and merge run directly, that each shard ran
# once with exit status 0 (parallel's job log), and that shards that fail make the script fail
# without merging.
set -euo pipefail
export LC_ALL=C

readonly shards=3

(($# >= 3)) || { echo "usage: $0 SCRATCH PROGRAM CASE [sweep options...]" >&2; exit 2; }
repo="$(cd "$(dirname "$0")/../.." && pwd -P)"
scratch="$1"
shift
program="$1"
shift
rm -rf "$scratch"
mkdir -p "$scratch"
cd "$scratch"

checks=0
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
pass() {
  checks=$((checks + 1))
  echo "ok: $*"
}

mkdir -p reference
"$program" sweep "$@" --shard 0/1 --out reference/shard-0
"$program" merge reference/shard-0 --out reference/merged

"$repo/scripts/parallel-sweep.sh" --shards "$shards" --jobs 2 --out sharded \
  --gearimpact "$program" "$@"
for file in sweep.csv poincare.csv summary.json; do
  cmp "reference/merged/$file" "sharded/merged/$file" ||
    fail "merged $file of $shards shards differs from the 1-shard sweep's"
  pass "merged $file of $shards shards is byte-identical to the 1-shard sweep's"
done
# parallel's job log: a header, then one line per job with its exit status in column 7 and the
# command, which ends in --out .../shard-K, in column 9.
shards_run="$(awk -F'\t' 'NR > 1 && $7 == 0 { sub(/.*shard-/, "", $9); print $9 }' \
  sharded/logs/parallel.log | sort -n | tr '\n' ' ')"
[[ "$shards_run" == "0 1 2 " ]] || fail "shards that ran with status 0: '$shards_run'"
pass "the job log shows shards 0 1 2 each run once with status 0"

if "$repo/scripts/parallel-sweep.sh" --shards 2 --out failing --gearimpact false "$@"; then
  fail "parallel-sweep.sh succeeded although every shard failed"
fi
[[ ! -e failing/merged ]] || fail "parallel-sweep.sh merged failed shards"
pass "failing shards: parallel-sweep.sh exits non-zero and merges nothing"

echo "parallel sweep: $checks checks passed"
