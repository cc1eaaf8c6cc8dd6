#!/usr/bin/env bash
# Set-up + main job: installs what is missing, builds, builds the bundled default slab of the paper
# (7 x 7 planar-faced TIS blocks, 10 x 10 x 3.18 mm, faces at 5 deg, pitch 10 mm, outer ring fixed)
# at the paper's resolution (0.25 mm voxels, 0.6 mm nodes) into out/default_slab, and runs the
# indentation test of assets/scenes/default.toml on it into out/default_run (1–1.5 min on 2
# cores; a previous out/default_run is replaced). Prints the response parameters and where the files are.
# Usage: scripts/run.sh [OUTDIR]      (default OUTDIR: out)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-"$here/out"}
"$here/scripts/setup.sh"
tessera="${BUILD_DIR:-$here/build}/tools/tessera"
"$tessera" tile --block "$here/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 7x7 --pitch 10 \
  --fix perimeter --voxel 0.25 --spacing 0.6 --replace -o "$out/default_slab"  # this script's own slab
"$tessera" export "$out/default_slab" -o "$out/default_slab/view"
rm -rf "$out/default_run"  # this script's own previous result: run it again from scratch
"$tessera" run "$here/assets/scenes/default.toml" --bundle "$out/default_slab" -o "$out/default_run"
echo "slab: $out/default_slab (open view/assembly.pvd in ParaView); run: $out/default_run (curve.png, snapshots.png, summary.json)"
