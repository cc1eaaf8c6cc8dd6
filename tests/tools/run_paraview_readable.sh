#!/usr/bin/env bash
# CTest: the ParaView time series of `tessera run` loads in VTK's own readers, every frame with
# all blocks, and curve.png is drawn. Usage: run_paraview_readable.sh TESSERA PYTHON SOURCE_DIR
set -euo pipefail
tessera=$1 python=$2 source=$3
if ! "$python" -c 'import vtkmodules.vtkIOXML' 2>/dev/null; then
  echo "skipped: $python cannot import vtkmodules (install python3-vtk9, or ParaView's Python)"; exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$tessera" tile --block "$source/assets/blocks/planar_a10_h3.18_5deg.obj" --unit mm --grid 3x3 --pitch 10 \
  --spacing 1.0 -o "$work/slab" > /dev/null
printf 'bundle = "slab"\n[indenter]\nspeed = 0.05\n[protocol]\ndelta_max = 0.3e-3\n[damping]\nlocal = 0.3\n[output]\nsnapshot_every = 0.1e-3\n' > "$work/scene.toml"
"$tessera" run "$work/scene.toml" -o "$work/out" > /dev/null 2>&1
"$python" - "$work/out" <<'PY'
import sys, xml.etree.ElementTree as ET
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
out = sys.argv[1]
files = [d.get("file") for d in ET.parse(f"{out}/paraview/slab.pvd").getroot().iter("DataSet")]
blocks = [f for f in files if f.startswith("blocks_")]
forces = [f for f in files if f.startswith("forces_")]
assert len(blocks) >= 3 and len(forces) == len(blocks), files
def load(name):
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(f"{out}/paraview/{name}")
    r.Update()
    return r.GetOutput()
for name in blocks:
    grid = load(name)
    assert grid.GetNumberOfCells() == 9 * 12, (name, grid.GetNumberOfCells())
    assert grid.GetCellData().GetArray("body_id") is not None
links = 0
for name in forces:
    grid = load(name)
    assert grid.GetPointData().GetArray("force").GetNumberOfComponents() == 3
    assert grid.GetPointData().GetArray("magnitude") is not None
    links = max(links, grid.GetNumberOfPoints())
assert links >= 3, links  # the loaded block against its neighbours and the indenter
print(f"ok: {len(blocks)} frames of 9 blocks, up to {links} force-chain links")
PY
test -s "$work/out/curve.png"
