#!/usr/bin/env python3
"""sliding_press.py's test on GetFEM's large-sliding contact (docs/validation.md, "To the peak
with GetFEM").

The same prism (4 x 4 x 4 mm) on the same block (x from -12 to 8 mm; y from -5 to 5 mm, narrower
than sliding_press.py's, for time: both runs here share it), frictionless, the block's bottom
clamped, the prism's top pressed down by 0.01 mm while it slides 14 mm until half of it overhangs
the block's edge. Elastic and frictionless, the end cannot depend on the path: slid in N increments
the normal force must be the pressed-in-place one. Contact: GetFEM's integral large sliding contact
brick (raytracing, augmented Lagrangian multiplier on the prism's bottom), linear elasticity on
quadratic hexahedra of size 1 mm, E = 4.2 GPa, nu = 0.2.

Usage: getfem_sliding_press.py [--increments N ...]      (default 10; about 2 min an increment)
Prints the pressed-in-place force, then one line per run. Needs Debian's python3-getfem.
"""
import argparse
import time

import numpy as np

E, NU = 4200.0, 0.2  # MPa
SIDE, HEIGHT, PRESS, SLIDE, START, SIZE = 4.0, 4.0, 0.01, 14.0, -8.0, 1.0  # mm
TOP, BOTTOM = 1, 2  # a block's mesh regions: its faces looking up and down


def elastic_block(gf, md, name: str, mesh):
    """The block meshed by `mesh` as the model's displacement variable `name`: quadratic elements,
    linear elasticity of the data lambda and mu, its top and bottom faces the regions TOP and
    BOTTOM. Returns (its finite element method, its integration method)."""
    mesh.set_region(TOP, mesh.outer_faces_with_direction([0.0, 0.0, 1.0], 0.01))
    mesh.set_region(BOTTOM, mesh.outer_faces_with_direction([0.0, 0.0, -1.0], 0.01))
    mfu = gf.MeshFem(mesh, 3)
    mfu.set_classical_fem(2)
    mim = gf.MeshIm(mesh, 5)
    md.add_fem_variable(name, mfu)
    md.add_isotropic_linearized_elasticity_brick(mim, name, "lambda", "mu")
    return mfu, mim


def grid(a: float, b: float) -> np.ndarray:
    return np.linspace(a, b, int(round((b - a) / SIZE)) + 1)


def normal_force(start: float, slide: float, increments: int) -> float:
    """The prism's normal force (N) at the end: standing from x = start, pressed by PRESS while slid
    by `slide`, in `increments` equal steps."""
    import getfem as gf
    gf.util_trace_level(0)
    block = gf.Mesh("cartesian", grid(-12, 8), grid(-5, 5), grid(0, HEIGHT))
    prism = gf.Mesh("cartesian", grid(start, start + SIDE), grid(-SIDE / 2, SIDE / 2), grid(HEIGHT, 2 * HEIGHT))
    md = gf.Model("real")
    md.add_initialized_data("lambda", [E * NU / ((1 + NU) * (1 - 2 * NU))])
    md.add_initialized_data("mu", [E / (2 * (1 + NU))])
    md.add_initialized_data("r", [E / SIZE])  # the augmentation parameter: convergence, not the answer
    md.add_initialized_data("pressed", [0.0, 0.0, 0.0])
    contact = md.add_integral_large_sliding_contact_brick_raytracing("r", 0.5 * SIZE)
    (block_fem, block_im), (prism_fem, prism_im) = elastic_block(gf, md, "block", block), \
        elastic_block(gf, md, "prism", prism)
    md.add_Dirichlet_condition_with_multipliers(block_im, "block", block_fem, BOTTOM)
    md.add_Dirichlet_condition_with_multipliers(prism_im, "prism", prism_fem, TOP, "pressed")
    md.add_filtered_fem_variable("traction", prism_fem, BOTTOM)
    md.add_slave_contact_boundary_to_large_sliding_contact_brick(contact, prism_im, BOTTOM, "prism", "traction")
    md.add_master_contact_boundary_to_large_sliding_contact_brick(contact, block_im, TOP, "block")
    for step in range(1, increments + 1):
        s = step / increments
        md.set_variable("pressed", [slide * s, 0.0, -PRESS * s])
        iterations, converged = md.solve("max_res", 1e-9, "max_iter", 60, "lsearch", "simplest", "lsolver", "mumps")
        if not converged:
            raise SystemExit(f"getfem_sliding_press: no convergence at increment {step} of {increments}")
    return gf.asm_generic(prism_im, 0, "traction(3)", BOTTOM, md)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--increments", type=int, nargs="+", default=[10])
    args = parser.parse_args()
    start = time.time()
    in_place = normal_force(START + SLIDE, 0.0, 2)
    print(f"pressed in place, half over the edge: {in_place:.6g} N ({time.time() - start:.0f} s)", flush=True)
    for n in args.increments:
        start = time.time()
        slid = normal_force(START, SLIDE, n)
        print(f"slid in {n} increments: {slid:.6g} N ({100 * (slid / in_place - 1):+.4f} %, {time.time() - start:.0f} s)", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
