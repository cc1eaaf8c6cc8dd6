#!/usr/bin/python3
"""Checks `tessera export` output with VTK's own readers (a real reader, not ours).

Usage: check_export.py DIR BODIES FIXED TRIANGLES NODES
Exits non-zero with a message when a file does not load or a count is off.
"""
import sys
import xml.etree.ElementTree as ET

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader


def load(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        sys.exit(f"{path}: VTK could not read it")
    return reader.GetOutput()


def expect(what, actual, expected):
    if actual != expected:
        sys.exit(f"{what}: {actual}, expected {expected}")
    print(f"ok: {what} = {actual}")


def main():
    directory, bodies, fixed, triangles, nodes = sys.argv[1], *map(int, sys.argv[2:6])
    collection = ET.parse(f"{directory}/assembly.pvd").getroot()
    files = [d.get("file") for d in collection.iter("DataSet")]
    expect("files in assembly.pvd", sorted(files), ["blocks.vtu", "nodes.vtu"])

    blocks = load(f"{directory}/blocks.vtu")
    expect("block triangles", blocks.GetNumberOfCells(), triangles)
    body_id = vtk_to_numpy(blocks.GetCellData().GetArray("body_id"))
    fixed_flag = vtk_to_numpy(blocks.GetCellData().GetArray("fixed"))
    expect("bodies in blocks.vtu", len(set(body_id.tolist())), bodies)
    expect("fixed bodies", len(set(body_id[fixed_flag == 1].tolist())), fixed)
    expect("cell types are triangles", set(vtk_to_numpy(blocks.GetCellTypesArray()).tolist()), {5})

    points = load(f"{directory}/nodes.vtu")
    expect("surface nodes", points.GetNumberOfPoints(), nodes)
    expect("node bodies", len(set(vtk_to_numpy(points.GetPointData().GetArray("body_id")).tolist())), bodies)
    normals = vtk_to_numpy(points.GetPointData().GetArray("normal"))
    expect("unit normals", bool(abs((normals ** 2).sum(axis=1) - 1).max() < 1e-9), True)


if __name__ == "__main__":
    main()
