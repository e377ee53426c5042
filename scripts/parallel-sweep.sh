#!/usr/bin/env bash
# Runs a sharded parameter sweep on one machine (or several, through GNU parallel's --sshlogin)
# with GNU parallel, then merges the shards:
#
#   scripts/parallel-sweep.sh --shards N --out OUT [--jobs J] [--gearimpact PATH] \
#     CASE [sweep options...]
#
# Shard K (0-based) runs `PATH sweep CASE [sweep options...] --shard K/N --out OUT/shard-K`, at most
# J at once (default: the number of cores); then `PATH merge OUT/shard-0 ... --out OUT/merged`.
# The first failing shard stops the launch of new ones, the script exits non-zero and nothing is
# merged. parallel's job log (command, exit status, run time of each shard) is OUT/logs/parallel.log.
# PATH defaults to this checkout's build/bin/gearimpact.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd -P)"

usage() {
  echo "usage: $0 --shards N --out OUT [--jobs J] [--gearimpact PATH] CASE [sweep options...]" >&2
  exit 2
}

tool=parallel-sweep options="--jobs" jobs="$(nproc)" gearimpact="$here/../build/bin/gearimpact"
source "$here/shard-options.sh"
shard_options_read "$@"
shift "$shard_options_used"
if ! command -v parallel >/dev/null; then
  echo "parallel-sweep: GNU parallel is not installed (scripts/setup.sh installs it)" >&2
  exit 1
fi
mkdir -p "$out/logs"

# -q quotes every word of the command for the shell parallel runs it in, so paths and options
# with spaces or shell characters pass unchanged; {} is the shard number.
parallel -q --jobs "$jobs" --halt soon,fail=1 --joblog "$out/logs/parallel.log" \
  "$gearimpact" sweep "$@" --shard "{}/$shards" --out "$out/shard-{}" \
  ::: $(seq 0 $((shards - 1)))

shard_dirs=()
for ((k = 0; k < shards; k++)); do
  shard_dirs+=("$out/shard-$k")
done
"$gearimpact" merge "${shard_dirs[@]}" --out "$out/merged"
echo "parallel-sweep: $shards shards merged into $out/merged"
