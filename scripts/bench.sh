#!/usr/bin/env bash
# Builds Release and runs every benchmark once, writing
#   benchmarks/results/bench.json  (Google Benchmark's JSON, all repetitions)
#   benchmarks/results/bench.md    (the machine, the command, the table, the targets)
# Usage: scripts/bench.sh [--binary PATH] [--min-time SECONDS] [--repetitions N]
#                         [--filter REGEX] [--accuracy-positions N]
# --binary skips the build (the CMake target `bench` passes its own program).
# Ratios are only meaningful between rows of one run: the machine is shared.
set -euo pipefail
cd "$(dirname "$0")/.."
binary=""
min_time=0.5
repetitions=3
filter="."
accuracy_positions=10000
while (($#)); do
  case "$1" in
    --binary) binary="$2"; shift 2 ;;
    --min-time) min_time="$2"; shift 2 ;;
    --repetitions) repetitions="$2"; shift 2 ;;
    --filter) filter="$2"; shift 2 ;;
    --accuracy-positions) accuracy_positions="$2"; shift 2 ;;
    *) echo "bench.sh: unknown argument $1 (see the usage at the top of the script)" >&2; exit 2 ;;
  esac
done

if [ -z "$binary" ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGEARIMPACT_WARNINGS_AS_ERRORS=ON \
    -DGEARIMPACT_BUILD_BENCHMARKS=ON > /dev/null
  cmake --build build -j "$(nproc)" --target gearimpact_bench
  binary=build/bin/gearimpact_bench
fi
build_dir="$(cd "$(dirname "$binary")/.." && pwd)"
build_type="$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$build_dir/CMakeCache.txt" 2>/dev/null || true)"
compiler="$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build_dir/CMakeCache.txt" 2>/dev/null || true)"
if [ "$build_type" != "Release" ]; then
  echo "bench.sh: warning: $binary is a '$build_type' build, timings are not representative" >&2
fi

out_dir=benchmarks/results
mkdir -p "$out_dir"
command=("$binary" "--benchmark_min_time=$min_time" "--benchmark_repetitions=$repetitions"
  "--benchmark_report_aggregates_only=true" "--benchmark_filter=$filter"
  "--accuracy-positions=$accuracy_positions"
  "--benchmark_out=$out_dir/bench.json" "--benchmark_out_format=json"
  "--markdown=$out_dir/table.md.tmp")
"${command[@]}"

{
  echo "# Benchmark run"
  echo
  # The results folder itself does not make the source tree dirty.
  commit="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  if [ -n "$(git status --porcelain -- . ':!benchmarks/results' 2>/dev/null)" ]; then commit="$commit-dirty"; fi
  echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC'), commit $commit"
  echo "- machine: $(nproc) cores, $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)," \
    "shared with other work while measured"
  echo "- compiler: ${compiler:-unknown} ($("${compiler:-c++}" --version 2>/dev/null | head -1)), build type ${build_type:-unknown}"
  echo "- command: \`scripts/bench.sh --min-time $min_time --repetitions $repetitions" \
    "--filter '$filter' --accuracy-positions $accuracy_positions\`" \
    "(median of $repetitions repetitions of at least $min_time s each)"
  echo
  cat "$out_dir/table.md.tmp"
} > "$out_dir/bench.md"
rm -f "$out_dir/table.md.tmp"
echo "bench.sh: wrote $out_dir/bench.json and $out_dir/bench.md"
