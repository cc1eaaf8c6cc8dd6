#!/usr/bin/env python3
"""The tall3 case of docs/validation.md: the 3 x 3 slab of the paper's block with its loaded block
made twice as tall upwards (the same four face planes, from -h/2 to 3h/2), so that its faces keep
their whole overlap with the neighbours' while it slides down by up to h.

Usage: tall_block.py LAYOUT_IN LAYOUT_OUT   (LAYOUT_IN: `tessera export`'s layout.json of the 3 x 3
slab; writes LAYOUT_OUT and, beside it, tall.obj in metres, and gives the centre body that shape)
"""
import json
import math
import sys
from pathlib import Path

A, H, THETA = 10e-3, 3.18e-3, math.radians(5.0)  # the paper's block, m


def tall_block_obj(path: Path) -> None:
    """The planar block's planes x = +-(a/2 + z tan theta), y = +-(a/2 - z tan theta), z from -h/2 to 3h/2."""
    vertices = []
    for z in (-H / 2, 3 * H / 2):
        hx, hy = A / 2 + z * math.tan(THETA), A / 2 - z * math.tan(THETA)
        vertices += [(x, y, z) for y in (-hy, hy) for x in (-hx, hx)]
    faces = [(1, 3, 4), (1, 4, 2), (5, 6, 8), (5, 8, 7), (1, 2, 6), (1, 6, 5),
             (3, 7, 8), (3, 8, 4), (1, 5, 7), (1, 7, 3), (2, 4, 8), (2, 8, 6)]
    lines = ["# the tall loaded block of bench/validation's tall3 case (m)"]
    lines += [f"v {x:.15g} {y:.15g} {z:.15g}" for x, y, z in vertices]
    lines += [f"f {a} {b} {c}" for a, b, c in faces]
    path.write_text("\n".join(lines) + "\n")


def main() -> int:
    source, target = Path(sys.argv[1]), Path(sys.argv[2])
    layout = json.loads(source.read_text())
    if layout["unit"] != "m":
        raise SystemExit(f"tall_block.py: {source} is not in metres (tessera export writes m)")
    tall_block_obj(target.parent / "tall.obj")
    layout["shapes"]["tall"] = {"mesh": str((target.parent / "tall.obj").resolve())}
    centre = [b for b in layout["bodies"] if not b["fixed"]]
    if len(centre) != 1:
        raise SystemExit(f"tall_block.py: {source} has {len(centre)} free bodies, not the 3 x 3 slab's one")
    centre[0]["shape"] = "tall"
    target.write_text(json.dumps(layout, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
