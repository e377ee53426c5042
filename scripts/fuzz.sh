#!/usr/bin/env bash
# Fuzzes the case-file reader and the merge's sweep.csv reader with libFuzzer (clang, ASan + UBSan) in
# build-fuzz. Usage: scripts/fuzz.sh [SECONDS] (default 20).
#   SECONDS=0 only builds and registers the ctest run (ctest -R fuzz_).
# New inputs found go to build-fuzz/fuzz/corpus-<target>; crashes to
# build-fuzz/fuzz/crash-*. To keep a finding, minimise it and copy it into
# fuzz/corpus/<target>/ with a name saying what it found.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
jobs="${JOBS:-$(nproc)}"
CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DGEARIMPACT_FUZZ=ON -DGEARIMPACT_BUILD_BENCHMARKS=OFF \
  -DGEARIMPACT_FUZZ_SECONDS="$seconds"
cmake --build build-fuzz -j "$jobs" --target fuzz_case_file fuzz_sweep_rows
if [ "$seconds" != 0 ]; then
  ctest --test-dir build-fuzz --output-on-failure -R '^fuzz_'
fi
