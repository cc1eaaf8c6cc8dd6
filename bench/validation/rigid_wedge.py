#!/usr/bin/env python3
"""The frictionless rigid wedge, in closed form: what Tessera's model carries on a slab whose one
free block is wedged between fixed ones (a 3 x 3 tiled slab), and the contact area Tessera finds.

The loaded block moves down by delta_b as a rigid body. Each face of it whose outward normal points
down (angle theta from the vertical: |n_z| = sin theta) is pressed into its fixed neighbour's by
d = delta_b sin theta over the faces' overlap A(delta_b) (the two polygons, the block's moved down,
clipped in their plane: fe_model.overlap_area), with a traction k_n d normal to it; frictionless,
the vertical load is

    P(delta_b) = sum over those faces of k_n A(delta_b) delta_b sin^2 theta

The same with A the area a level-set contact finds (nearest_face_area: exact level sets, no nodes)
is what Tessera's formulation carries; it differs from A by strips along the overlap's edges.

Usage: rigid_wedge.py BUNDLE [--youngs-modulus PA] [--tessera RUN]
k_n = E M / L, Tessera's span rule, from the bundle's span (E default 4.2e9 Pa). Prints the closed
form's peak and the load at a few delta_b, both with the exact overlap and with the nearest-face
area; with --tessera, for each snapshot of a Tessera run of that bundle (results.h5), the contact
area of the loaded block's wedging pairs against their exact overlap and the nearest-face area,
and the missing area per unit of the penetration d. Exit 2 for a bundle without a span or whose
central free block is wedged by no fixed block.
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


def nearest_face_area(blocks, loaded, face, neighbour, other, sink: float, samples: int = 400) -> float:
    """The pair's contact area as a level-set contact evaluated both ways with half areas finds it
    with exact level sets and a continuous surface (no nodes): each face's points inside the other
    block (on a grid of `samples` cells across the face's longer side), each weighted by
    max(0, -n . n_nearest), n_nearest the normal of the other block's plane nearest to the point
    (a convex block's signed distance inside is max_j (n_j . x - o_j), its gradient the normal of
    the plane that attains it); half of the sum over the two faces (mm^2).
    A point within d of the other block's next face takes that face's normal, across its own: the
    strips along the overlap's edges that carry nothing."""
    shift = np.array([0.0, 0.0, -sink])
    planes = {k: fe.planar_faces(blocks[k]) for k in (loaded, neighbour)}

    def side(points, own_normal, body, moved):  # the weights' sum over the points inside body (moved)
        normals = np.array([f.normal for f in planes[body]])
        distance = points @ normals.T - (np.array([f.offset for f in planes[body]]) + normals @ moved)
        inside = distance.max(axis=1) < 0
        nearest = normals[distance.argmax(axis=1)]
        return np.maximum(0.0, -(nearest @ own_normal))[inside].sum()

    total = 0.0
    for body, f, other_body, moved_self, moved_other in ((loaded, face, neighbour, shift, np.zeros(3)),
                                                         (neighbour, other, loaded, np.zeros(3), shift)):
        corners = blocks[body].vertices[f.loop] + moved_self
        u = corners[1] - corners[0]
        u /= np.linalg.norm(u)
        w = np.cross(f.normal, u)
        local = np.c_[(corners - corners[0]) @ u, (corners - corners[0]) @ w]
        low, high = local.min(axis=0), local.max(axis=0)
        step = (high - low).max() / samples
        a, b = np.meshgrid(np.arange(low[0] + step / 2, high[0], step), np.arange(low[1] + step / 2, high[1], step))
        grid = np.c_[a.ravel(), b.ravel()]
        inside_face = np.ones(len(grid), bool)  # the convex face: left of each edge (either orientation)
        sign = np.sign(fe.polygon_area(list(local)))
        for k in range(len(local)):
            e = local[k] - local[k - 1]
            inside_face &= sign * (e[0] * (grid[:, 1] - local[k - 1][1]) - e[1] * (grid[:, 0] - local[k - 1][0])) >= 0
        points = corners[0] + np.outer(grid[inside_face, 0], u) + np.outer(grid[inside_face, 1], w)
        total += side(points, f.normal, other_body, moved_other) * step ** 2
    return 0.5 * total


def load(blocks, loaded, wedges, k_n: float, sink: float, area=overlap) -> float:
    return sum(k_n * area(blocks, loaded, f, b, g, sink) * sink * f.normal[2] ** 2 for f, b, g in wedges)


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
    sinks = np.linspace(0.0, h, 321)
    theta = np.degrees(np.arcsin(abs(wedges[0][0].normal[2])))
    print(f"k_n = {k_n:.6g} MPa/mm; {len(wedges)} wedging faces, theta {theta:.2f} deg")
    for name, area in (("the exact overlap", overlap), ("the nearest-face area", nearest_face_area)):
        loads = [load(blocks, loaded, wedges, k_n, s, area) for s in sinks]
        peak = int(np.argmax(loads))
        print(f"with {name}: P_max = {loads[peak]:.1f} N at delta_b = {sinks[peak]:.3f} mm; delta_b (mm), P (N): "
              + ", ".join(f"{s:.2f} {p:.1f}" for s, p in zip(sinks[::32], loads[::32])))
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
                nearest = nearest_face_area(blocks, loaded, face, b, other, sink)
                print(f"delta_b {sink:.3f} mm, {blocks[b].name}: Tessera's area {found:.2f} mm^2, overlap "
                      f"{exact:.2f} ({found / exact - 1:+.1%}); d {d:.4f} mm, missing / d {(exact - found) / d:.1f} mm; "
                      f"nearest-face area {nearest:.2f} ({nearest / exact - 1:+.1%})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
