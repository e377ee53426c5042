#!/usr/bin/env bash
# Configures and builds into build/ (Release, warnings as errors).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGEARIMPACT_WARNINGS_AS_ERRORS=ON
cmake --build build -j "$(nproc)"
