#!/usr/bin/python3
"""Render an exported assembly (tessera export BUNDLE -o DIR) to a PNG.

Reads DIR/blocks.vtu with VTK's XML reader and draws the placed blocks with matplotlib: fixed blocks
grey, free blocks orange, shaded by face orientation.

Usage: /usr/bin/python3 tools/plot/render_assembly.py DIR -o slab.png [--title TEXT]
Needs Debian's python3-vtk9 and python3-matplotlib.
"""
import argparse
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader  # noqa: E402


def read_blocks(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid.GetNumberOfCells() == 0:
        sys.exit(f"{path}: no cells; export a bundle with bodies (tessera tile ...)")
    points = vtk_to_numpy(grid.GetPoints().GetData())
    cells = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 3)
    fixed = vtk_to_numpy(grid.GetCellData().GetArray("fixed"))
    return points, cells, fixed


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directory", help="export directory holding blocks.vtu")
    parser.add_argument("-o", "--output", required=True, help="PNG file to write")
    parser.add_argument("--title", default="", help="figure title")
    args = parser.parse_args()

    points, cells, fixed = read_blocks(f"{args.directory}/blocks.vtu")
    points = points * 1e3  # m -> mm
    triangles = points[cells]
    normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    light = np.array([0.4, -0.5, 0.8])
    light /= np.linalg.norm(light)
    shade = 0.45 + 0.55 * np.clip(normals @ light, 0, 1)
    base = np.where(fixed[:, None] == 1, np.array([0.62, 0.64, 0.68]), np.array([0.95, 0.55, 0.15]))
    colours = np.clip(base * shade[:, None], 0, 1)

    figure = plt.figure(figsize=(8, 6), dpi=120)
    axes = figure.add_subplot(projection="3d")
    axes.add_collection3d(Poly3DCollection(triangles, facecolors=colours, edgecolors=(0, 0, 0, 0.12), linewidths=0.3))
    low, high = points.min(axis=0), points.max(axis=0)
    centre, half = (low + high) / 2, (high - low).max() / 2
    flat = 0.3  # the vertical axis is drawn at true scale over a shorter range
    axes.set_xlim(centre[0] - half, centre[0] + half)
    axes.set_ylim(centre[1] - half, centre[1] + half)
    axes.set_zlim(centre[2] - flat * half, centre[2] + flat * half)
    axes.set_box_aspect((1, 1, flat))
    axes.view_init(elev=35, azim=-60)
    axes.set_xlabel("x [mm]")
    axes.set_ylabel("y [mm]")
    axes.set_zlabel("z [mm]")
    if args.title:
        axes.set_title(args.title)
    figure.tight_layout()
    figure.savefig(args.output)
    print(f"{args.output}: {len(fixed)} triangles rendered ({int(fixed.sum())} on fixed blocks)")


if __name__ == "__main__":
    main()
