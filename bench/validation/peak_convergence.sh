#!/usr/bin/env bash
# The 3 x 3 square slab to its peak (docs/validation.md, "To the peak, square3"): Tessera's runs under
# the three stiffness rules, and the FE quarter model (run_case.py --mirror) at contact penalties
# C = 10, 50, 200 and 1000 x E / element size in 40 increments to 1.2 h (and C = 200 in 80 and 160), then
# the tables of P_max and of the secant stiffness against the overlap, and the figure
# (peak_convergence.py).
# Usage: bench/validation/peak_convergence.sh [OUT]     (default OUT: out/validation_peak)
# Env:   TESSERA (build/tools/tessera). About 11 minutes on 2 cores.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-"$here/out/validation_peak"}
tessera=${TESSERA:-"$here/build/tools/tessera"}
python=/usr/bin/python3
mkdir -p "$out"
"$tessera" tile --block "$here/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 3x3 --pitch 10 \
  -o "$out/bundle" --replace > "$out/tile.log" 2>&1
for rule in span bars sections; do
  sed -e "s/^friction = .*/friction = 0.23\nstiffness_rule = \"$rule\"/" "$here/assets/scenes/default.toml" > "$out/scene_$rule.toml"
  rm -rf "$out/tessera_$rule"
  "$tessera" run "$out/scene_$rule.toml" --bundle "$out/bundle" -o "$out/tessera_$rule" --no-plot > "$out/tessera_$rule.log"
done
for run in 10:40 50:40 200:40 200:80 200:160 1000:40; do
  penalty=${run%:*} increments=${run#*:}
  echo "== FE: penalty $penalty, $increments increments" >&2
  "$python" "$here/bench/validation/run_case.py" "$out/bundle" -o "$out/fe_c${penalty}_i$increments" --mirror \
    --deflection 1.2 --increments "$increments" --penalty "$penalty" --stick 1
done
"$python" "$here/bench/validation/peak_convergence.py" "$out"
