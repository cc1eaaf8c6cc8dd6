#!/usr/bin/env bash
# CTest: the default slab exported by tessera loads in VTK's own readers with the right counts,
# and renders to a PNG. Usage: export_readable.sh TESSERA PYTHON SOURCE_DIR
set -euo pipefail
tessera=$1 python=$2 source=$3
if ! "$python" -c 'import vtkmodules.vtkIOXML' 2>/dev/null; then
  echo "skipped: $python cannot import vtkmodules (install python3-vtk9, or ParaView's Python)"; exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$tessera" tile --block "$source/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 7x7 --pitch 10 \
  --fix perimeter -o "$work/slab" > /dev/null
"$tessera" export "$work/slab" -o "$work/view" > /dev/null
nodes=$("$tessera" inspect "$work/slab" --json | "$python" -c \
  'import json,sys; j=json.load(sys.stdin); s=j["shapes"][0]; print(s["nodes"]["count"] * len(j["bodies"]))')
# 49 bodies, 24 fixed, 12 triangles each, every body's nodes
"$python" "$source/tests/tools/check_export.py" "$work/view" 49 24 588 "$nodes"
"$python" "$source/tools/plot/render_assembly.py" "$work/view" -o "$work/slab.png"
"$python" -c 'import sys, matplotlib.image as m; a = m.imread(sys.argv[1]); assert a.shape[0] > 100 and a.shape[1] > 100 and a[..., :3].std() > 0.05, "blank image"; print("ok: png", a.shape)' "$work/slab.png"
