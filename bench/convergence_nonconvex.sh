#!/usr/bin/env bash
# The accuracy chart for blocks that are not convex (docs/performance.md, "Non-convex blocks"): for
# the wave block and the two-way osteomorphic block (`tessera block`), a 7 x 7 slab with its perimeter
# fixed, indented at the centre at 120 mm/s to 2.5 mm (the default test's material and indenter),
# over the level set (exact mesh; the grid at 0.25 and 0.125 mm voxels) and the surface nodes
# (0.6 mm, uniform or graded; 1.2 mm uniform, the fast preset's), each case's P_max, K and W against two references: for the nodes,
# the exact mesh with 0.3 mm graded nodes (on both cores); for the level set, the exact mesh at
# 0.0625 mm voxels with the same 0.6 mm nodes. Every other case runs on one thread, two at a time.
# Usage: bench/convergence_nonconvex.sh [OUT_DIR]   (default out/convergence_nonconvex; about 15 min
#        on 2 cores, and about 20 min more per block for the node references; re-running skips
#        finished cases). Prints the tables (bench/nonconvex_table.py).
# Env:   NODE_REFERENCE=0 leaves the node references out (errors are then against the level-set
#        reference); VOXEL_REFERENCE=0 the level-set references too (errors against the exact mesh
#        at 0.25 mm voxels with graded 0.6 mm nodes, which was within 0.01 % of its 0.0625 mm
#        voxels on the wave block).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-"$here/out/convergence_nonconvex"}
tessera="$here/build/tools/tessera"
[ -x "$tessera" ] || "$here/scripts/setup.sh"
mkdir -p "$out"

# The blocks: 10 mm sides, 3.18 mm thick, as the default block; the osteomorphic block curved on
# all four sides (0.5 mm amplitude), so that it interlocks with every neighbour. Both tile face to
# face at a pitch of 10 mm (the wave block's turned copies and the osteomorphic block's unturned
# copies match to within the mesh).
"$tessera" block wave --size 10 --thickness 3.18 --angle 5 --amplitude 0.2 --unit mm -o "$out/wave.obj" > /dev/null
"$tessera" block osteomorphic --size 10 --thickness 3.18 --amplitude 0.5 --y-amplitude 0.5 --unit mm \
  -o "$out/osteomorphic.obj" > /dev/null
tile() {  # NAME [tile options]
  [ -f "$out/$1/slab/bundle.h5" ] || "$tessera" tile --block "$out/$1.obj" --unit mm --grid 7x7 --pitch 10 \
    --fix perimeter --voxel 0.25 --spacing 0.6 -o "$out/$1/slab" "${@:2}" > /dev/null
}
tile wave
tile osteomorphic --no-alternate

for block in wave osteomorphic; do
  dir="$out/$block"
  { sed -e "s#^bundle = .*#bundle = \"$dir/slab\"#" -e 's#^speed = .*#speed = 0.12#' \
      -e 's#^stop_on_failure = .*#stop_on_failure = false\ndelta_max = 2.5e-3#' "$here/assets/scenes/default.toml"; } > "$dir/exact.toml"
  { cat "$dir/exact.toml"; printf '\n[solver]\nexact_mesh_level_sets = false\n'; } > "$dir/grid.toml"
  sweep() { "$tessera" sweep "$dir/$1.toml" -o "$dir/$2" --jobs 2 --threads 1 "${@:3}"; }
  sweep exact nodes --set resolution.edge_spacing_fraction=0.25,1.0
  sweep exact fast --set resolution.node_spacing=1.2e-3 --set resolution.edge_spacing_fraction=1.0  # the fast preset's nodes
  [ "${VOXEL_REFERENCE:-1}" = 0 ] || sweep exact voxel --set resolution.voxel=0.0625e-3
  sweep grid grid --set resolution.voxel=0.125e-3,0.25e-3
  [ "${NODE_REFERENCE:-1}" = 0 ] || "$tessera" sweep "$dir/exact.toml" -o "$dir/reference" --jobs 1 --threads 2 --set resolution.node_spacing=0.3e-3
done
/usr/bin/python3 "$here/bench/nonconvex_table.py" "$out"
