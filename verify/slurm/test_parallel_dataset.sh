#!/usr/bin/env bash
# A sharded data set through GNU parallel (scripts/parallel-dataset.sh), end to end:
#
#   test_parallel_dataset.sh SCRATCH PROGRAM SPEC
#
# Checks that 3 shards on 2 job slots merge into records and a labels table byte-identical to the
# set made whole, that each shard ran once with status 0 (parallel's job log), and that shards
# that fail make the script fail without merging.
set -euo pipefail
export LC_ALL=C

(($# == 3)) || { echo "usage: $0 SCRATCH PROGRAM SPEC" >&2; exit 2; }
repo="$(cd "$(dirname "$0")/../.." && pwd -P)"
scratch="$1" program="$2" spec="$3"
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

"$program" dataset "$spec" --out whole --quiet >/dev/null
"$program" dataset merge whole --out whole-merged >/dev/null

"$repo/scripts/parallel-dataset.sh" --shards 3 --jobs 2 --out sharded --gearimpact "$program" \
  "$spec" --quiet >/dev/null
for file in whole-merged/*; do
  cmp "$file" "sharded/merged/$(basename "$file")" ||
    fail "$(basename "$file") of 3 shards differs from the whole set's"
done
pass "every file of the merged 3-shard set is byte-identical to the whole set's"
shards_run="$(awk -F'\t' 'NR > 1 && $7 == 0 { sub(/.*--shard /, "", $9); sub(/\/.*/, "", $9); print $9 }' \
  sharded/logs/parallel.log | sort -n | tr '\n' ' ')"
[[ "$shards_run" == "0 1 2 " ]] || fail "shards that ran with status 0: '$shards_run'"
pass "the job log shows shards 0 1 2 each run once with status 0"

if "$repo/scripts/parallel-dataset.sh" --shards 2 --out failing --gearimpact false "$spec" \
  2>/dev/null; then
  fail "parallel-dataset.sh succeeded although every shard failed"
fi
[[ ! -e failing/merged ]] || fail "parallel-dataset.sh merged failed shards"
pass "failing shards: parallel-dataset.sh exits non-zero and merges nothing"

echo "parallel dataset: $checks checks passed"
