#!/usr/bin/env python3
"""Writes hex_slab.json: a hexagonal TIS slab of 19 blocks (a centre and two rings) of the hexagonal
block in ../blocks/hex_r5_h3.18_5deg.obj (inradius 5 mm, thickness 3.18 mm, faces at +-5 deg; made
with `tessera block hex --size 5 --thickness 3.18 --angle 5 --unit mm -o hex_r5_h3.18_5deg.obj`).

All blocks share one orientation: face k of a block is face k+3 of its neighbour across it.
Neighbouring centres are 2r = 10 mm apart along the face normals (0, 60, ..., 300 deg).
The outer ring (12 blocks) is fixed; 7 are free. Across the free region, three blocks span
L = 30 mm with M = 4 interfaces.

Usage: python3 make_hex_slab.py > hex_slab.json
"""
import json
import math

R = 5.0  # inradius, mm
pitch = 2 * R
directions = [(math.cos(math.radians(60 * k)), math.sin(math.radians(60 * k))) for k in range(6)]


def hex_distance(q, r):
    return max(abs(q), abs(r), abs(q + r))


bodies = []
for q in range(-2, 3):
    for r in range(-2, 3):
        ring = hex_distance(q, r)
        if ring > 2:
            continue
        # axial coordinates along the 0-degree and 60-degree neighbour directions
        x = pitch * (q * directions[0][0] + r * directions[1][0])
        y = pitch * (q * directions[0][1] + r * directions[1][1])
        bodies.append({"name": f"q{q}r{r}".replace("-", "m"), "shape": "hex", "position": [x, y, 0.0],
                       "quaternion": [1.0, 0.0, 0.0, 0.0], "fixed": ring == 2})

layout = {
    "format": "tessera-layout",
    "version": 1,
    "unit": "mm",
    "shapes": {"hex": {"mesh": "../blocks/hex_r5_h3.18_5deg.obj"}},
    "bodies": bodies,
    "span": {"length": 3 * pitch, "interfaces": 4},
}
print(json.dumps(layout, indent=2))
