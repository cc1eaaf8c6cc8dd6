#!/usr/bin/python3
"""Render an exported assembly (tessera export BUNDLE -o DIR) to a PNG.

Reads DIR/blocks.vtu with VTK's XML reader and draws the placed blocks with matplotlib: fixed blocks
grey, free blocks orange, shaded by face orientation.

Usage: /usr/bin/python3 tools/plot/render_assembly.py DIR -o slab.png [--title TEXT]
Needs Debian's python3-vtk9 and python3-matplotlib.
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from blocks import block_colours, load_blocks  # noqa: E402
from figure_file import save_figure  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directory", help="export directory holding blocks.vtu")
    parser.add_argument("-o", "--output", required=True, help="PNG file to write")
    parser.add_argument("--title", default="", help="figure title")
    args = parser.parse_args()

    triangles, fixed = load_blocks(f"{args.directory}/blocks.vtu")
    colours = block_colours(triangles, fixed, [0.4, -0.5, 0.8])
    points = triangles.reshape(-1, 3)

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
    save_figure(figure, args.output)
    print(f"{args.output}: {len(fixed)} triangles rendered ({int(fixed.sum())} on fixed blocks)")


if __name__ == "__main__":
    main()
