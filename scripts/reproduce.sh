#!/usr/bin/env bash
# The README's first command: installs what is missing, builds, and reproduces
# the paper into the folder given (default: results/).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-results}"
scripts/setup.sh
scripts/build.sh
mkdir -p "$out"
echo "reproduce: mesh stiffness table -> $out/stiffness.csv"
build/bin/gearimpact stiffness --points 401 > "$out/stiffness.csv"
echo "reproduce: Fig. 8 energy ratios -> $out/fig8_energy_ratios.csv"
build/bin/gearimpact energy-ratios --points 601 > "$out/fig8_energy_ratios.csv"
build/bin/gearimpact energy-ratios --points 601 --flipped-moment > "$out/fig8_energy_ratios_flipped_moment.csv"
echo "reproduce: done, results in $out/"
