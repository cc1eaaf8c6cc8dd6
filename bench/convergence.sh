#!/usr/bin/env bash
# The accuracy chart (docs/performance.md, "Accuracy"): the default indentation test over node
# spacing (uniform, and graded to a quarter at the sharp edges), voxel size (grid level sets),
# time-step factor and loading rate, each case's P_max, K and W against the finest affordable
# reference (0.15 mm uniform nodes, 30 mm/s, factor 0.5), drawn as error against wall time (1 thread
# per case) with the Pareto front.
# Usage: bench/convergence.sh [OUT_DIR]   (default out/convergence; about 5 min on 2 cores;
#        re-running skips finished cases). Draws docs/convergence.png and prints the table.
# CONTACT_EVALUATION=one-way charts the node spacing (uniform, graded, the reference) under one-way
# contact evaluation (docs/physics.md) into out/convergence_one_way and docs/convergence_one_way.png;
# CONTACT_AREA=blended likewise with blended contact areas (out/convergence_blended,
# docs/convergence_blended.png).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
evaluation=${CONTACT_EVALUATION:-two-way}
area=${CONTACT_AREA:-nearest}
suffix=$([ "$evaluation" = two-way ] || echo "_${evaluation//-/_}")$([ "$area" = nearest ] || echo "_$area")
out=${1:-"$here/out/convergence$suffix"}
tessera="$here/build/tools/tessera"
slab="$here/out/default_slab"
[ -x "$tessera" ] || "$here/scripts/setup.sh"
[ -f "$slab/bundle.h5" ] || "$tessera" tile --block "$here/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm \
  --grid 7x7 --pitch 10 --fix perimeter --voxel 0.25 --spacing 0.6 -o "$slab"
mkdir -p "$out"

# The default scene with its bundle made absolute, and the same with grid level sets everywhere.
solver=$([ "$evaluation" = two-way ] || echo "contact_evaluation = \"$evaluation\"")
solver+=$([ "$area" = nearest ] || printf '\ncontact_area = "%s"' "$area")
sed "s#^bundle = .*#bundle = \"$slab\"#" "$here/assets/scenes/default.toml" > "$out/base.toml"
{ cat "$out/base.toml"; printf '\n[solver]\nexact_convex_level_sets = false\nexact_mesh_level_sets = false\n%s\n' "$solver"; } \
  > "$out/grid.toml"
[ -z "$solver" ] || printf '\n[solver]\n%s\n' "$solver" >> "$out/base.toml"

sweep() { "$tessera" sweep "$out/$1.toml" -o "$out/$2" --jobs 2 --threads 1 "${@:3}"; }
spacings=0.3e-3,0.45e-3,0.6e-3,0.9e-3,1.2e-3
sweep base spacing --set resolution.node_spacing=$spacings --set resolution.edge_spacing_fraction=1.0    # uniform nodes
sweep base graded --set resolution.node_spacing=$spacings --set resolution.edge_spacing_fraction=0.25   # graded (default)
# The reference: 0.15 mm uniform nodes (14 700 per block), on both cores.
"$tessera" sweep "$out/base.toml" -o "$out/fine" --jobs 1 --threads 2 --set resolution.node_spacing=0.15e-3 \
  --set resolution.edge_spacing_fraction=1.0
if [ -n "$suffix" ]; then
  /usr/bin/python3 "$here/bench/plot_convergence.py" "$out" "$here/docs/convergence$suffix.png"
  exit 0
fi
sweep base speed --set indenter.speed=0.006,0.015,0.06,0.12
sweep base factor --set solver.time_step_factor=0.25,1.0
sweep grid voxel --set resolution.voxel=0.125e-3,0.25e-3,0.5e-3
sweep base combined --set resolution.node_spacing=0.9e-3,1.2e-3 --set indenter.speed=0.06,0.12 --set solver.time_step_factor=1.0 \
  --set resolution.edge_spacing_fraction=1.0
sweep base coarse --set resolution.node_spacing=1.2e-3 --set indenter.speed=0.12 --set resolution.edge_spacing_fraction=1.0  # "fast"
/usr/bin/python3 "$here/bench/plot_convergence.py" "$out" "$here/docs/convergence.png"
