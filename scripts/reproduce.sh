#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and reproduces
# the paper into the folder given (default: results/).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-results}"
scripts/setup.sh
scripts/build.sh
build/bin/gearimpact reproduce --out "$out"
echo "reproduce: results and REPORT.md in $out/"
