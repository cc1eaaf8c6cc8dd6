#!/usr/bin/env python3
"""One FE reference run: a Tessera bundle meshed, pressed and solved by CalculiX (fe_model.py).

Usage: run_case.py BUNDLE -o DIR [--youngs-modulus PA] [--poisson NU] [--friction MU]
                   [--element-size F] [--deflection F] [--punch-radius F] [--increments N]
                   [--penalty F] [--stick F] [--threads N] [--mirror] [--block-stiffness F]
                   [--span-contact]
Lengths F are fractions of the loaded block's thickness h (its z-extent), as Tessera's own
protocol lengths are. Writes DIR/curve.csv (per converged increment: delta_mm, the patch's downward
displacement; load_N, the force on it; block_displacement_mm, the mean downward displacement of
the loaded block's nodes, Tessera's delta_b), DIR/summary.json (the model, counts, time) and
DIR/slab.inp with CalculiX's own files beside it. A step that stops early (past a limit load, ccx
cannot find a balance) keeps its converged increments; summary.json says where and why. Exit 1
when ccx solves no increment (its log named). --mirror models the half or quarter of a slab on the
positive side of its mirror planes x = x_c and y = y_c through the loaded block's centre (blocks
across them cut, their nodes there held normal to the plane) and reports the whole slab's load;
exit 2 for a slab with neither plane. --block-stiffness and --span-contact (the contact slope
Tessera's k_n; exit 2 for a bundle without a span) give Tessera's own model, but CalculiX does not
solve it: where the faces hold the compliance, the force it prints at the k-th of n increments is
F_n / (n - k + 1) (docs/validation.md); getfem_case.py solves it.
"""
import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fe_model as fe  # noqa: E402


def central_free_block(blocks) -> int:
    """The free block nearest the blocks' mean centroid in plan, as Tessera's default target."""
    centres = np.array([b.vertices.mean(axis=0)[:2] for b in blocks])
    mean = centres.mean(axis=0)
    free = [k for k, b in enumerate(blocks) if not b.fixed]
    return min(free, key=lambda k: np.linalg.norm(centres[k] - mean))


def positive(text: str) -> int:
    """An argument that counts something: an integer of at least 1."""
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError(f"{value}: at least 1")
    return value


def factor(text: str) -> float:
    """An argument that scales a modulus: a number above 0."""
    value = float(text)
    if not value > 0:
        raise argparse.ArgumentTypeError(f"{value}: above 0")
    return value


def add_slab_arguments(parser: argparse.ArgumentParser) -> None:
    """The bundle, the output folder, the material and the loading, as every FE run here takes them."""
    parser.add_argument("bundle")
    parser.add_argument("-o", "--out", required=True)
    parser.add_argument("--youngs-modulus", type=float, default=4.2e9, help="Pa (default 4.2e9)")
    parser.add_argument("--poisson", type=float, default=0.2)
    parser.add_argument("--friction", type=float, default=0.23)
    parser.add_argument("--element-size", type=float, default=0.3, help="fraction of h (default 0.3)")
    parser.add_argument("--deflection", type=float, default=0.8, help="fraction of h (default 0.8)")
    parser.add_argument("--punch-radius", type=float, default=0.3, help="fraction of h (default 0.3)")
    parser.add_argument("--increments", type=positive, default=40)
    parser.add_argument("--mirror", action="store_true",
                        help="model the slab's part x >= x_c and/or y >= y_c (x_c, y_c: the loaded block's "
                             "centre) for each of these planes the slab is its own mirror image about, with "
                             "symmetry conditions there (a slab with neither: refused); the load is "
                             "2 or 4 x the part's")
    parser.add_argument("--block-stiffness", type=factor, default=1.0,
                        help="the blocks' Young's modulus x this (default 1; 1000: rigid blocks)")
    parser.add_argument("--span-contact", action="store_true",
                        help="faces as compliant as Tessera's: k_n = E M / L (Tessera's span rule, from the "
                             "bundle's span) times the penetration; k_t = k_n in getfem_case.py, --stick x k_n "
                             "in run_case.py; a bundle without a span: exit 2")


def refuse(program: str, message: str) -> None:
    """A refusal: the program's name and the reason on stderr, and exit 2."""
    print(f"{program}: {message}", file=sys.stderr)
    raise SystemExit(2)


def face_stiffness(args, program: str) -> float | None:
    """The faces' k_n (MPa/mm) that --span-contact asks for (E the case's, not the blocks'), or None.
    A bundle without a span: the reason on stderr, after the program's name, and exit 2."""
    if not args.span_contact:
        return None
    try:
        interfaces, length = fe.span(args.bundle)
    except ValueError as e:
        refuse(program, str(e))
    return args.youngs_modulus / 1e6 * interfaces / length


def slab_part(bundle: str, mirror: bool, program: str):
    """The blocks modelled (with --mirror, fe_model.mirror_part's), the loaded block's index among
    them, its thickness h (z-extent, mm) and centre, and the mirror axes. A slab with no mirror
    plane when mirror is asked for: the reason on stderr, after the program's name, and exit 2."""
    blocks = fe.read_bundle(bundle)
    loaded = central_free_block(blocks)
    h = float(np.ptp(blocks[loaded].vertices[:, 2]))
    centre = blocks[loaded].vertices.mean(axis=0)
    axes = []
    if mirror:
        name = blocks[loaded].name
        try:
            blocks, axes = fe.mirror_part(blocks, centre)
        except ValueError as e:
            refuse(program, str(e))
        loaded = next(k for k, b in enumerate(blocks) if b.name == name)
    return blocks, loaded, h, centre, axes


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_slab_arguments(parser)
    parser.add_argument("--penalty", type=float, default=50.0,
                        help="contact slope K = PENALTY x E / element size (default 50)")
    parser.add_argument("--stick", type=float, default=0.1,
                        help="friction's stick slope = STICK x the contact slope (default 0.1)")
    parser.add_argument("--contact", choices=list(fe.CONTACT_TYPES), default="surface",
                        help="CalculiX's contact pairs: surface to surface (penalty, default) or mortar")
    parser.add_argument("--large-displacements", action="store_true",
                        help="NLGEOM: equilibrium on the deformed geometry (default: small displacements)")
    parser.add_argument("--threads", type=int, default=2)
    args = parser.parse_args()

    out = Path(args.out)
    blocks, loaded, h, centre, axes = slab_part(args.bundle, args.mirror, "run_case")
    share = 2 ** len(axes)  # the whole slab's load per the model's
    slope = face_stiffness(args, "run_case") or 0.0  # (0: --penalty's)
    out.mkdir(parents=True, exist_ok=True)  # (after the refusals: none leaves an empty folder)
    model = fe.Model(youngs_modulus=args.youngs_modulus / 1e6, poisson=args.poisson, friction=args.friction,
                     increments=args.increments, element_size=args.element_size * h, penalty_factor=args.penalty,
                     stick_factor=args.stick, contact=args.contact, block_stiffness=args.block_stiffness,
                     large_displacements=args.large_displacements, slope=slope)
    start = time.time()
    mesh = fe.mesh_blocks(blocks, model.element_size)
    held, pressed = fe.slab_supports(mesh, loaded, args.punch_radius * h, args.deflection * h, centre)
    held += fe.symmetry_constraints(mesh, centre, axes)
    inp = out / "slab.inp"
    fe.write_input(inp, mesh, model, held, pressed,
                   watch=mesh.node_ids(loaded, np.ones(len(mesh.meshes[loaded].nodes), bool)))
    meshed = time.time() - start
    stopped = fe.run_ccx(inp, args.threads)
    printed = fe.read_dat(out / "slab.dat") if (out / "slab.dat").exists() else []
    totals = fe.totals(printed)
    if not totals:
        print(f"run_case: ccx solved no increment ({out / 'slab.log'}): {stopped}", file=sys.stderr)
        return 1
    mean = fe.mean_displacements(printed, fe.symmetry_weights(mesh, centre, axes))
    curve = [(0.0, 0.0, 0.0)] + [(t / model.increments * args.deflection * h, -share * force[2], -mean[t][2])
                                 for t, force in totals]
    (out / "curve.csv").write_text("delta_mm,load_N,block_displacement_mm\n" +
                                   "".join(f"{d:.9g},{p:.9g},{b:.9g}\n" for d, p, b in curve))
    summary = {
        "bundle": str(Path(args.bundle).resolve()), "loaded_block": blocks[loaded].name, "thickness_mm": h,
        "youngs_modulus_MPa": model.youngs_modulus, "block_stiffness": model.block_stiffness,
        "poisson": model.poisson, "friction": model.friction,
        "element_size_mm": model.element_size, "contact_slope_MPa_per_mm": model.contact_slope(),
        "stick_slope_MPa_per_mm": model.stick_factor * model.contact_slope(),
        "contact": args.contact, "large_displacements": model.large_displacements,
        "punch_radius_mm": args.punch_radius * h, "deflection_mm": args.deflection * h,
        "nodes": int(sum(len(m.nodes) for m in mesh.meshes)),
        "elements": int(sum(len(m.tets) for m in mesh.meshes)), "contact_pairs": len(mesh.pairs),
        "patch_nodes": len(pressed[0].nodes), "increments": len(totals), "mirror_planes": ["xy"[a] for a in axes],
        # ccx may end a step on a sliver of an increment (rounding) that fails: the step counts as
        # completed where its converged increments reached its end.
        "completed": not stopped or totals[-1][0] >= model.increments * (1 - 1e-4), "stopped": stopped,
        "mesh_seconds": meshed, "total_seconds": time.time() - start,
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(f"run_case: {blocks[loaded].name} pressed {args.deflection * h:.3g} mm: "
          f"{summary['nodes']} nodes, {len(mesh.pairs)} contact pairs, {len(totals)} increments, "
          f"load {curve[-1][1]:.4g} N, {summary['total_seconds']:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
