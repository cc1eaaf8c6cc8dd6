#!/usr/bin/env bash
# Set-up + main job: installs what is missing, builds, and prepares the bundled default block
# (the paper's planar-faced TIS block, 10 x 10 x 3.18 mm, faces at 5 deg) at the paper's
# resolution into out/default, then prints what the bundle holds.
# Usage: scripts/run.sh [OUTDIR]      (default OUTDIR: out/default)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-"$here/out/default"}
"$here/scripts/setup.sh"
tessera="${BUILD_DIR:-$here/build}/tools/tessera"
"$tessera" prep "$here/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --voxel 0.25 --spacing 0.6 \
  --name planar --replace -o "$out"
"$tessera" inspect "$out"
echo "results: $out (bundle.h5, planar.vdb)"
