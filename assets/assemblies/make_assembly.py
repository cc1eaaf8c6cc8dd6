#!/usr/bin/env python3
"""Writes a small TIS assembly the way interlocking-design tools export one, to try
`tessera assemble` on (docs/tiling.md, "Assemblies"): a 5 x 5 slab of the default planar block
scaled 6x (60 mm blocks, 19.08 mm thick), placed in world coordinates, in metres with 6 decimals,
y up; the 9 inner blocks as the objects of parts.obj, the 16-block outer ring as one multi-piece
mesh, frame.obj. Standard library only.

Usage: make_assembly.py OUTDIR
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
BLOCK = os.path.join(HERE, "..", "blocks", "planar_a10_h3.18_5deg.obj")  # mm
SCALE = 6.0e-3      # mm -> m, and 6x larger
PITCH = 10.0 * SCALE  # m
N = 5


def read_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if p and p[0] == "v":
                vertices.append(tuple(float(x) for x in p[1:4]))
            elif p and p[0] == "f":
                faces.append(tuple(int(x.split("/")[0]) for x in p[1:4]))
    return vertices, faces


def placed(vertices, row, col):
    """Block (row, col) of the square grid, every other one turned 90 degrees, z up, metres."""
    turn = (row + col) % 2 == 1
    cx, cy = (col - (N - 1) / 2) * PITCH, (row - (N - 1) / 2) * PITCH
    out = []
    for x, y, z in vertices:
        x, y, z = x * SCALE, y * SCALE, z * SCALE
        if turn:
            x, y = -y, x
        out.append((x + cx, y + cy, z))
    return out


def y_up(v):
    """z-up world -> the file's y-up frame (the inverse of tessera's --up y)."""
    x, y, z = v
    return (x, z, -y)


def write(path, blocks, faces, objects):
    with open(path, "w") as f:
        f.write("# exported assembly: metres, y up\n")
        base = 0
        for name, vertices in blocks:
            if objects:
                f.write("o %s\n" % name)
            for v in vertices:
                f.write("v %.6f %.6f %.6f\n" % y_up(v))
            for a, b, c in faces:
                f.write("f %d %d %d\n" % (a + base, b + base, c + base))
            base += len(vertices)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    vertices, faces = read_obj(BLOCK)
    inner, ring = [], []
    for row in range(N):
        for col in range(N):
            block = ("block_r%dc%d" % (row, col), placed(vertices, row, col))
            (ring if row in (0, N - 1) or col in (0, N - 1) else inner).append(block)
    write(os.path.join(out, "parts.obj"), inner, faces, True)
    write(os.path.join(out, "frame.obj"), ring, faces, False)
    print("wrote %s/parts.obj (%d blocks) and %s/frame.obj (%d blocks as one mesh): metres, y up"
          % (out, len(inner), out, len(ring)))


if __name__ == "__main__":
    main()
