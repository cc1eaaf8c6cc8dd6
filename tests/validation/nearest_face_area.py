"""rigid_wedge.nearest_face_area (the contact area a level-set contact's nearest-face rule finds,
with exact level sets and no nodes) against its closed form.

Two equal cubes of side s, one on the other, the top one pressed down into the bottom one by d:
each pressed face's points inside the other cube within d of one of its side faces have that side
face as their nearest plane, whose normal is across their own (weight 0); the rest have the
pressed face (weight 1). So the area is (s - 2d)^2 on either side, and its half-sum the same,
while the faces' overlap stays s^2. Shifted sideways by s/2 the overlap is s^2/2 and each side
loses the strips along the other cube's three faces that bound it: (s - 2d)(s/2 - d). A smaller
cube of side a centred on the larger one is asymmetric: its face keeps a^2 (the larger cube's side
faces are farther than d), the larger one's loses its strips along the smaller cube's four side
faces, (a - 2d)^2; the half-sum is (a^2 + (a - 2d)^2) / 2.

Usage: nearest_face_area.py
"""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench" / "validation"))
import fe_model as fe  # noqa: E402
from rigid_wedge import nearest_face_area, overlap  # noqa: E402

CORNERS = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], float)
TRIANGLES = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                      [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])


def cube(name: str, side: float, origin) -> fe.Block:  # the bottom one fixed
    return fe.Block(name, name == "bottom", CORNERS * side + np.asarray(origin, float), TRIANGLES)


def face(block: fe.Block, normal) -> fe.Face:
    return next(f for f in fe.planar_faces(block) if np.allclose(f.normal, normal))


def main() -> int:
    s, a, d = 10.0, 6.0, 0.5
    failures = []
    for top, shift, expected_overlap, expected_area in (
            (s, 0.0, s * s, (s - 2 * d) ** 2),
            (s, s / 2, s * s / 2, (s - 2 * d) * (s / 2 - d)),
            (a, (s - a) / 2, a * a, (a * a + (a - 2 * d) ** 2) / 2)):
        blocks = [cube("top", top, (shift, (s - top) / 2, s)), cube("bottom", s, (0, 0, 0))]
        down, up = face(blocks[0], (0, 0, -1)), face(blocks[1], (0, 0, 1))
        found = nearest_face_area(blocks, 0, down, 1, up, d, samples=2000)
        exact = overlap(blocks, 0, down, 1, up, d)
        print(f"top side {top} mm, shift {shift} mm: overlap {exact:.3f} mm^2 (closed form {expected_overlap:.3f}), "
              f"nearest-face area {found:.3f} mm^2 (closed form {expected_area:.3f})")
        if abs(exact - expected_overlap) > 1e-9 * expected_overlap:
            failures.append(f"overlap {exact} != {expected_overlap}")
        if abs(found - expected_area) > 3e-3 * expected_area:  # the grid's cells: s / 2000
            failures.append(f"nearest-face area {found} != {expected_area} (top side {top}, shift {shift})")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
