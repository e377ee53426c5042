#!/usr/bin/env bash
# Configures and builds into build/ (Release, warnings as errors), through ccache when the machine
# has it (scripts/setup.sh installs it): the Python package's check (package_pip_venv) builds the
# same sources again through pip, and takes its objects from the cache. CCACHE_BASEDIR makes the
# cached commands name the sources relative to the build tree, the same in the check's copy.
set -euo pipefail
cd "$(dirname "$0")/.."
cache=()
if command -v ccache >/dev/null; then
  cache=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DGEARIMPACT_WARNINGS_AS_ERRORS=ON "${cache[@]}"
cmake --build build -j "$(nproc)"
