#!/usr/bin/env bash
# The 3 x 3 square slab to its peak (docs/validation.md, "To the peak, square3"): Tessera's runs under
# the three stiffness rules, and the FE quarter model (run_case.py --mirror) to 1.2 h at contact
# penalties C = 10 and 200 x E / element size in 40 increments in small displacements, and in large
# displacements (NLGEOM) at C = 10, 200 and 1000 in 40 increments and at C = 200 in 80, 160 and 320,
# then the tables of P_max and of the secant stiffness against the overlap, and the figure
# (peak_convergence.py).
# Usage: bench/validation/peak_convergence.sh [OUT]     (default OUT: out/validation_peak)
# Env:   TESSERA (build/tools/tessera). About 30 minutes on 2 cores.
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
for run in 10:40 200:40 10:40:large 200:40:large 1000:40:large 200:80:large 200:160:large 200:320:large; do
  IFS=: read -r penalty increments large <<< "$run"
  echo "== FE: penalty $penalty, $increments increments ${large:-small} displacements" >&2
  "$python" "$here/bench/validation/run_case.py" "$out/bundle" -o "$out/fe_c${penalty}_i$increments${large:+_large}" \
    --mirror --deflection 1.2 --increments "$increments" --penalty "$penalty" --stick 1 ${large:+--large-displacements}
done
"$python" "$here/bench/validation/peak_convergence.py" "$out"
