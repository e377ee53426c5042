#!/bin/sh
# pip_venv.sh SOURCE_DIR WORK_DIR PYTHON CLI: the README's Python install, on a
# copy of the source tree (the build writes into it): a virtual environment
# over the system's packages, `pip install --no-build-isolation .` with no
# package index, then the Python suite against the installed package.
set -eu
source=$1 work=$2 python=$3 cli=$4
rm -rf "$work" && mkdir -p "$work/src"
for entry in CMakeLists.txt cmake lib reference python paper_data examples README.md pyproject.toml \
    setup.py setup.cfg; do
  cp -R "$source/$entry" "$work/src/"
done
"$python" -m venv --system-site-packages "$work/venv"
# -O1: this checks the install route, not the optimiser; -O3 compiles about three times as long,
# and the same sources at -O3 are the build tree's python_api suite.
GEARIMPACT_CMAKE_ARGS=${GEARIMPACT_CMAKE_ARGS:-"'-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG'"} \
CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-2} PIP_NO_INDEX=1 \
  "$work/venv/bin/pip" install --no-build-isolation "$work/src"
cd "$work"
env -u PYTHONPATH "$work/venv/bin/python" -c "
import gearimpact, sys
assert gearimpact.__file__.startswith('$work/venv/'), gearimpact.__file__
print('installed:', gearimpact.__file__, gearimpact.__version__)
"
env -u PYTHONPATH PYTHONDONTWRITEBYTECODE=1 GEARIMPACT_CLI="$cli" GEARIMPACT_SOURCE_DIR="$source" \
  "$work/venv/bin/python" -m pytest -q -p no:cacheprovider "$source/verify/python"
