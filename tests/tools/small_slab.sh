# Sourced by the shell tests: a temporary folder $work (removed on exit) holding $work/slab, a
# 3 x 3 slab of the default block at 1 mm uniform nodes. Needs $tessera and $source set.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$tessera" tile --block "$source/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 3x3 --pitch 10 \
  --spacing 1.0 --edge-spacing 1 -o "$work/slab" > /dev/null
