#!/bin/sh
# pip_venv.sh SOURCE_DIR WORK_DIR PYTHON CLI [BUILD_SUBDIR CONFIGURE_ARG...]: the README's
# Python install, on a copy of the source tree (the build writes into it): a virtual environment
# over the system's packages, `pip install --no-build-isolation .` with no package index, then
# what the install lays out and three of the Python suites against the installed package. With
# the optional arguments (a build
# through ccache, verify/package/CMakeLists.txt), the package's CMake tree is BUILD_SUBDIR of the
# copy and is configured with that build's compiler and flags (the CONFIGURE_ARGs), so that its
# objects come from the cache.
set -eu
source=$1 work=$2 python=$3 cli=$4
rm -rf "$work" && mkdir -p "$work/src"
for entry in CMakeLists.txt cmake lib reference python paper_data examples README.md pyproject.toml \
    setup.py setup.cfg; do
  cp -R "$source/$entry" "$work/src/"
done
"$python" -m venv --system-site-packages "$work/venv"
if [ $# -ge 5 ]; then
  # The cache rewrites paths inside CCACHE_BASEDIR relative to the compiler's folder, so that the
  # copy's sources, seen from BUILD_SUBDIR of the copy, read as the build's sources from its tree.
  GEARIMPACT_BUILD_DIR=$5
  shift 5
  GEARIMPACT_CMAKE_ARGS=
  for arg in "$@"; do
    GEARIMPACT_CMAKE_ARGS="$GEARIMPACT_CMAKE_ARGS '$arg'"
  done
  CCACHE_BASEDIR=${CCACHE_BASEDIR:-$source}
  export GEARIMPACT_BUILD_DIR GEARIMPACT_CMAKE_ARGS CCACHE_BASEDIR
else
  # -O0: this checks the install route, not the optimiser or the numbers: the same sources at -O3
  # are the build tree's Python suites (python_*), and -O0 compiles in about 60 % of -O1's time.
  GEARIMPACT_CMAKE_ARGS=${GEARIMPACT_CMAKE_ARGS:-"'-DCMAKE_CXX_FLAGS_RELEASE=-O0 -DNDEBUG'"}
  export GEARIMPACT_CMAKE_ARGS
fi
CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-2} PIP_NO_INDEX=1 \
  "$work/venv/bin/pip" install --no-build-isolation "$work/src"
cd "$work"
# What the install lays out: the module imported from the environment, the program and the
# paper's data it carries, the program run, a case read from that data and a short run in-process.
env -u PYTHONPATH "$work/venv/bin/python" -c "
import gearimpact, subprocess, sys
assert gearimpact.__file__.startswith('$work/venv/'), gearimpact.__file__
program = gearimpact.program_path()
assert str(program).startswith('$work/venv/'), program
usage = subprocess.run([str(program), '--help'], check=True, capture_output=True, text=True).stdout
assert 'gear impact dynamics' in usage, usage
case = gearimpact.read_case(gearimpact.paper_data_dir() / 'case1.toml')
run = gearimpact.simulate(gearimpact.paper_data_dir() / 'case1.toml', end_time='1 ms')
print('installed:', gearimpact.__file__, gearimpact.__version__, program)
"
# The suites that need no heavy run (the others, at -O0, would take minutes and test the same
# sources again): the native module's types and errors, a pair on its own, the speed units.
env -u PYTHONPATH PYTHONDONTWRITEBYTECODE=1 GEARIMPACT_CLI="$cli" GEARIMPACT_SOURCE_DIR="$source" \
  "$work/venv/bin/python" -m pytest -q -p no:cacheprovider "$source/verify/python/test_native.py" \
  "$source/verify/python/test_gear_pair_alone.py" "$source/verify/python/test_speed_units.py"
