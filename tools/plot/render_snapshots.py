#!/usr/bin/python3
"""Render a strip of snapshots of a tessera run: the slab at evenly spaced deflections, seen from
below and from the side (like the snapshot figures of Feldfogel et al.).

Usage: /usr/bin/python3 tools/plot/render_snapshots.py RUNDIR [--frames 6]   (writes RUNDIR/snapshots.png)
Reads RUNDIR/paraview/slab.pvd and its blocks_NNNN.vtu with VTK; draws with matplotlib.
"""
import argparse
import xml.etree.ElementTree as ET

try:
    import matplotlib
except ImportError:
    raise SystemExit("needs Debian's python3-matplotlib (scripts/setup.sh installs it)")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from blocks import block_colours, load_blocks as load  # noqa: E402
from figure_file import save_figure  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def draw(axes, triangles, fixed, elevation, azimuth, limits, stretch=1.0):
    view = [np.cos(np.radians(elevation)) * np.cos(np.radians(azimuth)),
            np.cos(np.radians(elevation)) * np.sin(np.radians(azimuth)), np.sin(np.radians(elevation))]
    axes.add_collection3d(Poly3DCollection(triangles, facecolors=block_colours(triangles, fixed, view), linewidths=0))
    (x0, x1), (y0, y1), (z0, z1) = limits
    axes.set_xlim(x0, x1)
    axes.set_ylim(y0, y1)
    axes.set_zlim(z0, z1)
    axes.set_box_aspect((x1 - x0, y1 - y0, stretch * (z1 - z0)))
    axes.view_init(elev=elevation, azim=azimuth)
    axes.set_axis_off()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", help="output directory of tessera run")
    parser.add_argument("--frames", type=int, default=6)
    args = parser.parse_args()
    root = ET.parse(f"{args.run}/paraview/slab.pvd").getroot()
    frames = [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet") if d.get("file").startswith("blocks_")]
    last = frames[-1][0]
    wanted = [last * k / (args.frames - 1) for k in range(args.frames)]
    chosen = [min(frames, key=lambda f: abs(f[0] - w)) for w in wanted]

    first, _ = load(f"{args.run}/paraview/{chosen[0][1]}")
    low, high = first.reshape(-1, 3).min(axis=0), first.reshape(-1, 3).max(axis=0)
    depth = max(last, high[2] - low[2]) + 1.0
    limits = ((low[0], high[0]), (low[1], high[1]), (high[2] - depth - 1.0, high[2] + 1.0))

    figure = plt.figure(figsize=(2.6 * len(chosen), 5.2), dpi=110)
    for column, (delta, name) in enumerate(chosen):
        triangles, fixed = load(f"{args.run}/paraview/{name}")
        below = figure.add_subplot(2, len(chosen), column + 1, projection="3d")
        draw(below, triangles, fixed, -90, -90, limits)
        below.set_title(f"δ = {delta:.2f} mm", fontsize=9)
        side = figure.add_subplot(2, len(chosen), len(chosen) + column + 1, projection="3d")
        draw(side, triangles, fixed, 0, -90, limits, stretch=3.0)
    figure.text(0.01, 0.72, "from below", rotation=90, fontsize=9)
    figure.text(0.01, 0.25, "from the side (z x 3)", rotation=90, fontsize=9)
    figure.tight_layout()
    save_figure(figure, f"{args.run}/snapshots.png")


if __name__ == "__main__":
    main()
