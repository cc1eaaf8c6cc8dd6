#!/usr/bin/env bash
# Mirrored loads (docs/geometry.md, "Symmetries"): a 9 x 5 slab of the default block loaded at
# (12, 3), (-12, 3) and (12, -3) mm at every preset; prints P_max, K, W and the failure label of
# each run (mirror images must agree within 0.1 %).
# Usage: bench/mirrored_loads.sh [OUT_DIR]   (default out/mirrored_loads; about 5 min on 2 cores)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-"$here/out/mirrored_loads"}
tessera="$here/build/tools/tessera"
[ -x "$tessera" ] || "$here/scripts/setup.sh"
mkdir -p "$out"
[ -f "$out/slab/bundle.h5" ] || "$tessera" tile --block "$here/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 9x5 \
  --pitch 10 --fix perimeter -o "$out/slab" --replace > "$out/tile.log"
for preset in fast default fine paper; do
  for point in "0.012, 0.003" "-0.012, 0.003" "0.012, -0.003"; do
    name="${preset}_${point//[ ,]/_}"
    sed -e "s#^bundle = .*#bundle = \"$out/slab\"#" -e "s#^\[indenter\]#[indenter]\npoint = [$point]#" \
      "$here/assets/scenes/default.toml" > "$out/$name.toml"
    rm -rf "$out/run_$name"  # this script's own run: again from scratch
    "$tessera" run "$out/$name.toml" --preset "$preset" -o "$out/run_$name" --threads 2 --no-plot > "$out/$name.log"
  done
done
/usr/bin/python3 - "$out" <<'PY'
import glob, json, os, sys
print("| preset | load point (mm) | P_max N | K N/mm | W mJ | failure |")
print("|---|---|---|---|---|---|")
for path in sorted(glob.glob(os.path.join(sys.argv[1], "run_*", "summary.json"))):
    r = json.load(open(path))["response"]
    preset, x, _, y = os.path.basename(os.path.dirname(path))[4:].split("_", 3)
    print("| %s | (%g, %g) | %.3f | %.3f | %.3f | %s |" % (preset, float(x) * 1e3, float(y.strip("_")) * 1e3, r["peak_load_N"],
                                                          r["stiffness_N_per_mm"], r["loading_energy_mJ"], r["failure_mode"]))
PY
