#!/usr/bin/env bash
# Mesh convergence of the FE reference (docs/validation.md, "Mesh convergence"): the 3 x 3 slab
# of the paper's block at element sizes h x SIZES, pressed to DEFLECTION x h in INCREMENTS
# increments, and K fitted as compare.py does (over [0, 0.4 mm] of the block's displacement).
# Usage: bench/validation/mesh_convergence.sh [OUT]     (default OUT: out/validation/mesh)
# Env:   SIZES ("0.6 0.4 0.3 0.2"), DEFLECTION (0.15), INCREMENTS (6), PENALTY (50),
#        TESSERA (build/tools/tessera)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
out=${1:-"$here/out/validation/mesh"}
tessera=${TESSERA:-"$here/build/tools/tessera"}
python=/usr/bin/python3
mkdir -p "$out"
"$tessera" tile --block "$here/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 3x3 --pitch 10 \
  -o "$out/bundle" --replace > "$out/tile.log" 2>&1
echo "| element size (h) | nodes | K on δ_b (N/mm) | K on δ (N/mm) | P at the last increment (N) | time (s) |"
echo "|---|---|---|---|---|---|"
for size in ${SIZES:-0.6 0.4 0.3 0.2}; do
  "$python" "$here/bench/validation/run_case.py" "$out/bundle" -o "$out/size_$size" --element-size "$size" \
    --deflection "${DEFLECTION:-0.15}" --increments "${INCREMENTS:-6}" --penalty "${PENALTY:-50}" > "$out/size_$size.log"
  "$python" - "$out/size_$size" "$size" "$here/bench/validation" <<'EOF'
import json, sys
import numpy as np
folder, size = sys.argv[1], sys.argv[2]
sys.path.insert(0, sys.argv[3])
from compare import slope
c = np.genfromtxt(f"{folder}/curve.csv", delimiter=",", names=True)
s = json.load(open(f"{folder}/summary.json"))
k_b, k = slope(c["block_displacement_mm"], c["load_N"], 0.4), slope(c["delta_mm"], c["load_N"], 0.4)
print(f"| {size} | {s['nodes']} | {k_b:.0f} | {k:.0f} | {c['load_N'][-1]:.1f} | {s['total_seconds']:.0f} |")
EOF
done
