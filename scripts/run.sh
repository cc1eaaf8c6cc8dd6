#!/usr/bin/env bash
# Set-up + main job: installs what is missing, builds, and builds the bundled default slab of the
# paper (7 x 7 planar-faced TIS blocks, 10 x 10 x 3.18 mm, faces at 5 deg, pitch 10 mm, outer ring
# fixed) at the paper's resolution (0.25 mm voxels, 0.6 mm nodes) into out/default_slab, exports it
# for ParaView and prints what the bundle holds.
# Usage: scripts/run.sh [OUTDIR]      (default OUTDIR: out/default_slab)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-"$here/out/default_slab"}
"$here/scripts/setup.sh"
tessera="${BUILD_DIR:-$here/build}/tools/tessera"
"$tessera" tile --block "$here/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 7x7 --pitch 10 \
  --fix perimeter --voxel 0.25 --spacing 0.6 -o "$out"
"$tessera" export "$out" -o "$out/view"
"$tessera" inspect "$out"
echo "results: $out (bundle.h5, one .vdb per shape); open $out/view/assembly.pvd in ParaView"
