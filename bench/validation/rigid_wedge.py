#!/usr/bin/env python3
"""The frictionless rigid wedge, in closed form: what Tessera's model carries on a slab whose one
free block is wedged between fixed ones (a 3 x 3 tiled slab), and the contact area Tessera finds.

The loaded block moves down by delta_b as a rigid body. Each face of it whose outward normal points
down (angle theta from the vertical: |n_z| = sin theta) is pressed into its fixed neighbour's by
d = delta_b sin theta over the faces' overlap A(delta_b) (the two polygons, the block's moved down,
clipped in their plane: fe_model.overlap_area), with a traction k_n d normal to it; frictionless,
the vertical load is

    P(delta_b) = sum over those faces of k_n A(delta_b) delta_b sin^2 theta

Usage: rigid_wedge.py BUNDLE [--youngs-modulus PA] [--tessera RUN]
k_n = E M / L, Tessera's span rule, from the bundle's span (E default 4.2e9 Pa). Prints the closed
form's peak and the load at a few delta_b; with --tessera, for each snapshot of a Tessera run of
that bundle (results.h5), the contact area of the loaded block's wedging pairs against their exact
overlap, and the missing area per unit of the penetration d. Exit 2 for a bundle without a span or
whose central free block is wedged by no fixed block.
"""
import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fe_model as fe  # noqa: E402
from run_case import central_free_block, factor  # noqa: E402


def wedging_faces(blocks):
    """(loaded block, its face, neighbour, the neighbour's face) for each face of the loaded block
    that points down and touches a fixed block."""
    faces = [fe.planar_faces(b) for b in blocks]
    loaded = central_free_block(blocks)
    found = []
    for a, i, b, j in fe.shared_faces(blocks, faces, 1e-6 * fe.slab_size(blocks)):
        if loaded not in (a, b):
            continue
        if a != loaded:
            a, i, b, j = b, j, a, i
        if faces[a][i].normal[2] < 0 and blocks[b].fixed:
            found.append((faces[a][i], b, faces[b][j]))
    return loaded, found


def overlap(blocks, loaded, face, neighbour, other, sink: float) -> float:
    """The faces' overlap (mm^2) with the loaded block moved down by sink (mm)."""
    moved = blocks[loaded].vertices[face.loop] - np.array([0.0, 0.0, sink])
    return fe.overlap_area(moved, blocks[neighbour].vertices[other.loop], face.normal)


def load(blocks, loaded, wedges, k_n: float, sink: float) -> float:
    return sum(k_n * overlap(blocks, loaded, f, b, g, sink) * sink * f.normal[2] ** 2 for f, b, g in wedges)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bundle")
    parser.add_argument("--youngs-modulus", type=factor, default=4.2e9, help="Pa (default 4.2e9)")
    parser.add_argument("--tessera", help="a Tessera run of the bundle (its results.h5): its contact areas")
    args = parser.parse_args()
    try:
        interfaces, length = fe.span(args.bundle)
    except ValueError as e:
        print(f"rigid_wedge: {e}", file=sys.stderr)
        return 2
    k_n = args.youngs_modulus / 1e6 * interfaces / length  # MPa/mm
    blocks = fe.read_bundle(args.bundle)
    loaded, wedges = wedging_faces(blocks)
    if not wedges:
        print(f"rigid_wedge: {args.bundle}: the central free block has no face pointing down onto a fixed block",
              file=sys.stderr)
        return 2
    h = float(np.ptp(blocks[loaded].vertices[:, 2]))
    sinks = np.linspace(0.0, h, 641)
    loads = [load(blocks, loaded, wedges, k_n, s) for s in sinks]
    peak = int(np.argmax(loads))
    print(f"k_n = {k_n:.6g} MPa/mm; {len(wedges)} wedging faces, theta {np.degrees(np.arcsin(abs(wedges[0][0].normal[2]))):.2f} deg: "
          f"P_max = {loads[peak]:.1f} N at delta_b = {sinks[peak]:.3f} mm")
    print("delta_b (mm), P (N): " + ", ".join(f"{s:.2f} {p:.1f}" for s, p in zip(sinks[::64], loads[::64])))
    if args.tessera:
        import h5py
        with h5py.File(Path(args.tessera) / "results.h5", "r") as f:
            names = [n.decode() for n in f["snapshots/body_names"][()]]
            offsets, pairs = f["snapshots/force_offset"][()], f["snapshots/force_pair"][()]
            areas, positions = f["snapshots/force_area"][()], f["snapshots/position"][()]
        me = names.index(blocks[loaded].name)
        for s in range(1, len(offsets) - 1):
            sink = -(positions[s, me, 2] - positions[0, me, 2]) * fe.MM_PER_M
            for face, b, other in wedges:
                rows = [r for r in range(offsets[s], offsets[s + 1])
                        if set(pairs[r]) == {me, names.index(blocks[b].name)}]
                exact = overlap(blocks, loaded, face, b, other, sink)
                if not rows or exact <= 0:
                    continue
                found = areas[rows[0]] * fe.MM_PER_M ** 2
                d = sink * abs(face.normal[2])
                print(f"delta_b {sink:.3f} mm, {blocks[b].name}: Tessera's area {found:.2f} mm^2, overlap "
                      f"{exact:.2f} ({found / exact - 1:+.1%}); d {d:.4f} mm, missing / d {(exact - found) / d:.1f} mm")
    return 0


if __name__ == "__main__":
    sys.exit(main())
