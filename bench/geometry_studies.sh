#!/usr/bin/env bash
# The two geometry studies of docs/reproduction.md ("Geometry studies"), on the default scene:
#   face angle: 7 x 7 square slabs generated at theta in {0, 2.5, 5, 7.5, 10, 15, 20} deg
#               (tessera tile --tiling square), at mu = 0.23 and at a saturated mu = 7;
#   wave faces: the wave-faced block (tessera block wave, theta 5 deg, amplitude 0.02 a) against the
#               planar block, mu in {0.23, 0.5, 1, 2, 7}.
# Usage: bench/geometry_studies.sh [OUTDIR]   (default out/geometry_studies). Re-running finishes only
# what is missing. Tables: /usr/bin/python3 bench/geometry_tables.py OUTDIR.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-"$here/out/geometry_studies"}
tessera="${BUILD_DIR:-$here/build}/tools/tessera"
scene="$here/assets/scenes/default.toml"
mkdir -p "$out"
# A scene per bundle, with its absolute path (sweeps copy the scene into their case folders).
scene_for() { sed "s|^bundle = .*|bundle = \"$1\"|" "$scene" > "$2"; }
for angle in 0 2.5 5 7.5 10 15 20; do
  b="$out/angle_$angle/slab"
  [ -f "$b/bundle.h5" ] || "$tessera" tile --tiling square --grid 7x7 --pitch 10 --thickness 3.18 --angle "$angle" --unit mm -o "$b" --replace > "$out/angle_$angle.tile.log"
  scene_for "$b" "$out/angle_$angle/scene.toml"
  "$tessera" sweep "$out/angle_$angle/scene.toml" -o "$out/angle_$angle/mu" --set mu=0.23,7
done
for family in planar wave; do
  mesh="$out/$family.obj"
  [ -f "$mesh" ] || "$tessera" block "$family" --size 10 --thickness 3.18 --angle 5 --unit mm -o "$mesh" > /dev/null
  b="$out/$family/slab"
  [ -f "$b/bundle.h5" ] || "$tessera" tile --block "$mesh" --unit mm --grid 7x7 --pitch 10 -o "$b" --replace > "$out/$family.tile.log"
  scene_for "$b" "$out/$family/scene.toml"
  "$tessera" sweep "$out/$family/scene.toml" -o "$out/$family/mu" --set mu=0.23,0.5,1,2,7
done
