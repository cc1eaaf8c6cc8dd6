#!/usr/bin/env python3
"""How far CalculiX's contact can be trusted while faces slide (docs/validation.md, "To the peak").

A 4 x 4 x 4 mm prism stands on a 20 x 20 x 4 mm block (x from -12 to 8 mm) whose bottom is
clamped; frictionless penalty contact between them. The prism's top is pressed down by 0.01 mm
while it slides 14 mm along x, from x = -8..-4 mm to 6..10 mm: at the end half of it overhangs the
block's edge, as a wedged block's face slides past its neighbour's edge before the slab's peak.
Frictionless and elastic, the end state does not depend on the path, so the normal force at the
end must be that of the prism pressed in place at its end position, whatever the increments: any
difference is the contact formulation's error over a slide.

Usage: sliding_press.py OUT [--increments N ...] [--large-displacements] [--contact surface|mortar]
Prints one line per run: increments, the end's normal force against the pressed-in-place one.
"""
import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fe_model as fe  # noqa: E402

SIDE, HEIGHT, PRESS, SLIDE, START = 4.0, 4.0, 0.01, 14.0, -8.0  # mm


def normal_force(work: Path, start: float, slide: float, model: fe.Model) -> float:
    """The prism's normal force (N) at the step's end: standing from x = start, pressed by PRESS
    while slid by `slide`."""
    work.mkdir(parents=True, exist_ok=True)
    blocks = [fe.box("block", [-12, -10, 0], [8, 10, HEIGHT]),
              fe.box("prism", [start, -SIDE / 2, HEIGHT], [start + SIDE, SIDE / 2, 2 * HEIGHT])]
    mesh = fe.mesh_blocks(blocks, model.element_size)
    held = [fe.Constraint("BOTTOM", mesh.nodes_at(0, 2, 0), 1, 3)]
    top = mesh.nodes_at(1, 2, 2 * HEIGHT)
    pressed = [fe.Constraint("TOPZ", top, 3, 3, -PRESS), fe.Constraint("TOPX", top, 1, 1, slide),
               fe.Constraint("TOPY", top, 2, 2, 0.0)]
    fe.write_input(work / "press.inp", mesh, model, held, pressed)
    stopped = fe.run_ccx(work / "press.inp")
    totals = fe.totals(fe.read_dat(work / "press.dat")) if (work / "press.dat").exists() else []
    if stopped or not totals or totals[-1][0] < model.increments * (1 - 1e-4):
        raise SystemExit(f"sliding_press: ccx stopped in {work}: {stopped}")
    return -float(totals[-1][1][2])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--increments", type=int, nargs="+", default=[10, 40])
    parser.add_argument("--large-displacements", action="store_true")
    parser.add_argument("--contact", choices=list(fe.CONTACT_TYPES), default="surface")
    args = parser.parse_args()
    out = Path(args.out)

    def model(increments):
        return fe.Model(friction=0.0, element_size=1.0, increments=increments, penalty_factor=200,
                        large_displacements=args.large_displacements, contact=args.contact)
    in_place = normal_force(out / "in_place", START + SLIDE, 0.0, model(2))
    geometry = "large" if args.large_displacements else "small"
    print(f"pressed in place, half over the edge: {in_place:.4g} N ({args.contact} contact, {geometry} displacements)")
    for n in args.increments:
        slid = normal_force(out / f"slid_{n}", START, SLIDE, model(n))
        print(f"slid {SLIDE:g} mm in {n} increments: {slid:.4g} N ({slid / in_place - 1:+.1%})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
