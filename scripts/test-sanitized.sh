#!/usr/bin/env bash
# Builds into build-asan with AddressSanitizer and UndefinedBehaviorSanitizer
# (GEARIMPACT_SANITIZE, GCC, benchmarks off) and runs the whole ctest suite
# under them. Any sanitizer report fails its test.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${JOBS:-$(nproc)}"
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGEARIMPACT_SANITIZE=ON \
  -DGEARIMPACT_BUILD_BENCHMARKS=OFF -DGEARIMPACT_WARNINGS_AS_ERRORS=ON
cmake --build build-asan -j "$jobs"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
ctest --test-dir build-asan --output-on-failure -j "$jobs"
