#!/usr/bin/env bash
# Makes a data set in shards with GNU parallel on one machine (or several, through parallel's
# --sshlogin and a shared folder), then merges it:
#
#   scripts/parallel-dataset.sh --shards N --out OUT [--jobs J] [--gearimpact PATH] \
#     SPEC [dataset options...]
#
# Shard K (0-based) runs `PATH dataset SPEC [dataset options...] --shard K/N --out OUT/records`,
# at most J at once (default: the number of cores); then `PATH dataset merge OUT/records --out
# OUT/merged`. The first failing shard stops the launch of new ones, the script exits non-zero and
# nothing is merged; finished records stay, and running the script again completes the set.
# parallel's job log is OUT/logs/parallel.log. PATH defaults to this checkout's build/bin/gearimpact.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd -P)"

usage() {
  echo "usage: $0 --shards N --out OUT [--jobs J] [--gearimpact PATH] SPEC [dataset options...]" >&2
  exit 2
}

tool=parallel-dataset options="--jobs" jobs="$(nproc)" gearimpact="$here/../build/bin/gearimpact"
source "$here/shard-options.sh"
shard_options_read "$@"
shift "$shard_options_used"
if ! command -v parallel >/dev/null; then
  echo "parallel-dataset: GNU parallel is not installed (scripts/setup.sh installs it)" >&2
  exit 1
fi
mkdir -p "$out/logs" "$out/records"

# -q quotes every word for the shell parallel runs it in; {} is the shard number.
parallel -q --jobs "$jobs" --halt soon,fail=1 --joblog "$out/logs/parallel.log" \
  "$gearimpact" dataset "$@" --shard "{}/$shards" --out "$out/records" \
  ::: $(seq 0 $((shards - 1)))

"$gearimpact" dataset merge "$out/records" --out "$out/merged"
echo "parallel-dataset: $shards shards merged into $out/merged"
