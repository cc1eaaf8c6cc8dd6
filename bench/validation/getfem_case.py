#!/usr/bin/env python3
"""One FE reference run to the peak with GetFEM's large-sliding contact (docs/validation.md, "To the
peak with GetFEM").

CalculiX's contacts overstate a press slid past an edge (sliding_press.py); GetFEM's raytracing
contact with an augmented-Lagrangian multiplier (the integral large sliding contact brick; Y.
Renard & K. Poulios, GetFEM's user documentation, "Large sliding/large deformation contact with
friction bricks") follows it: slid in 10 increments it ends on the pressed-in-place force to six
digits (getfem_sliding_press.py). Here the slab's free blocks are elastic solids (linear
elasticity, quadratic elements on the corners of gmsh's tetrahedra, fe_model.mesh_block); every
side face of a free block is a slave contact boundary with Coulomb friction, against the other free
blocks and the fixed blocks that share a face with one (meshed, clamped on their whole surface:
Tessera's fixed blocks never move, as fe_model clamps every node of them). The loaded block's top
is pressed down on a round patch at its centre, held laterally (as run_case.py); the load is the
vertical resultant of the contact tractions, and friction's slip in an increment is measured from
the last one's displacement. Units: mm, N, MPa.

Usage: getfem_case.py BUNDLE -o DIR [--youngs-modulus PA] [--poisson NU] [--friction MU]
                      [--element-size F] [--deflection F] [--punch-radius F] [--increments N]
Lengths F are fractions of the loaded block's thickness h, as in run_case.py. Writes DIR/curve.csv
(delta_mm, load_N, block_displacement_mm: the loaded block's mean downward displacement, Tessera's
delta_b) and DIR/summary.json. Needs Debian's python3-getfem (scripts/setup.sh) and python3-gmsh.
"""
import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fe_model as fe  # noqa: E402
from run_case import add_slab_arguments, central_free_block  # noqa: E402


def convex_points(nodes, corners):
    """Tetrahedra by their corners as GetFEM's add_convex takes them: dim x 4 x convexes (straight
    simplices: the blocks' faces are planes)."""
    return np.ascontiguousarray(nodes[corners].transpose(2, 1, 0))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_slab_arguments(parser)
    args = parser.parse_args()
    import getfem as gf
    gf.util_trace_level(0)
    gf.util_warning_level(0)

    start = time.time()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    blocks = fe.read_bundle(args.bundle)
    loaded = central_free_block(blocks)
    h = float(np.ptp(blocks[loaded].vertices[:, 2]))
    size, radius, deflection = args.element_size * h, args.punch_radius * h, args.deflection * h
    free = [k for k, b in enumerate(blocks) if not b.fixed]

    import gmsh
    gmsh.initialize(["-nt", "1"])
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        meshes = {k: fe.mesh_block(blocks[k], fe.planar_faces(blocks[k]), size) for k in range(len(blocks))}
    finally:
        gmsh.finalize()

    E = args.youngs_modulus / 1e6
    lam = E * args.poisson / ((1 + args.poisson) * (1 - 2 * args.poisson))
    mu = E / (2 * (1 + args.poisson))
    md = gf.Model("real")
    md.add_initialized_data("lambda", [lam])
    md.add_initialized_data("mu", [mu])
    md.add_initialized_data("r", [E / size])  # the augmentation parameter: convergence, not the answer
    md.add_initialized_data("f", [args.friction])
    md.add_initialized_data("alpha", [1.0])
    contact = md.add_integral_large_sliding_contact_brick_raytracing("r", size, "f", "alpha", 0)
    SURFACE, PATCH = 1, 2
    parts = {}
    for k in free:
        m = gf.Mesh("empty", 3)
        m.add_convex(gf.GeoTrans("GT_PK(3,1)"), convex_points(meshes[k].nodes, meshes[k].tets[:, :4]))
        sides = [f.normal for f in fe.planar_faces(blocks[k]) if abs(f.normal[2]) < 0.9]  # top and bottom touch nothing
        m.set_region(SURFACE, np.hstack([m.outer_faces_with_direction(n, 0.01) for n in sides]))
        mfu = gf.MeshFem(m, 3)
        mfu.set_classical_fem(2)
        mim = gf.MeshIm(m, 4)
        u, w, multiplier = f"u{k}", f"w{k}", f"lambda{k}"
        md.add_fem_variable(u, mfu)
        md.add_fem_data(w, mfu)
        md.add_isotropic_linearized_elasticity_brick(mim, u, "lambda", "mu")
        md.add_filtered_fem_variable(multiplier, mfu, SURFACE)
        add = md.add_master_slave_contact_boundary_to_large_sliding_contact_brick if len(free) > 1 else \
            md.add_slave_contact_boundary_to_large_sliding_contact_brick
        add(contact, mim, SURFACE, u, multiplier, w)
        parts[k] = (m, mfu, mim, u, w, multiplier)
    planes = [fe.planar_faces(b) for b in blocks]
    touching = {k for a, _, b, _ in fe.shared_faces(blocks, planes, 1e-6 * fe.slab_size(blocks)) for k in (a, b)}
    for k, b in enumerate(blocks):  # those that share a face with a free block (not a line, as corner neighbours)
        if b.fixed and k in touching:
            m = gf.Mesh("empty", 3)
            m.add_convex(gf.GeoTrans("GT_PK(3,1)"), convex_points(meshes[k].nodes, meshes[k].tets[:, :4]))
            m.set_region(SURFACE, m.outer_faces())
            mfu = gf.MeshFem(m, 3)
            mfu.set_classical_fem(1)
            mim = gf.MeshIm(m, 2)
            md.add_fem_variable(f"u{k}", mfu)  # clamped on its whole surface: it does not move
            md.add_isotropic_linearized_elasticity_brick(mim, f"u{k}", "lambda", "mu")
            md.add_Dirichlet_condition_with_simplification(f"u{k}", SURFACE)
            md.add_fem_data(f"w{k}", mfu)  # its previous displacement, 0: friction's slip is u - w
            md.add_master_contact_boundary_to_large_sliding_contact_brick(contact, mim, SURFACE, f"u{k}", f"w{k}")
            parts[k] = (m, mfu, mim)  # GetFEM's objects live while Python holds them

    m, mfu, mim, u, _, _ = parts[loaded]
    centre = blocks[loaded].vertices.mean(axis=0)
    top = blocks[loaded].vertices[:, 2].max()
    faces = m.outer_faces_with_direction([0.0, 0.0, 1.0], 0.01)
    middle = np.array([m.pts(m.pid_in_faces(faces[:, [j]])).mean(axis=1) for j in range(faces.shape[1])])
    on_patch = (np.abs(middle[:, 2] - top) < 1e-6 * h) & (np.hypot(*(middle[:, :2] - centre[:2]).T) <= radius)
    if not on_patch.any():
        raise SystemExit("getfem_case: no element face on the punch patch: refine the mesh or widen the punch")
    m.set_region(PATCH, faces[:, on_patch])
    md.add_initialized_data("pressed", [0.0, 0.0, 0.0])
    md.add_Dirichlet_condition_with_multipliers(mim, u, mfu, PATCH, "pressed")
    volume = gf.asm_generic(mim, 0, "1", -1, md)

    def reach(start: float, end: float, depth: int = 0) -> bool:
        """Newton from the converged state at the patch's displacement `start` to `end`; where it
        fails, the state is restored and the way there halved, at most three times. After each
        converged step friction's reference (w) moves to the displacement reached."""
        saved = md.from_variables()
        md.set_variable("pressed", [0.0, 0.0, -end])
        try:
            converged = md.solve("max_res", 1e-8, "max_iter", 80, "lsearch", "simplest", "lsolver", "mumps")[1]
        except RuntimeError:  # GetFEM raises where Newton diverges or the tangent is singular
            converged = False
        if not converged:
            md.to_variables(saved)
            middle = 0.5 * (start + end)
            return depth < 3 and reach(start, middle, depth + 1) and reach(middle, end, depth + 1)
        for k in free:
            md.set_variable(parts[k][4], md.variable(parts[k][3]))
        return True

    rows = []
    status = "reached the deflection"
    curve = open(out / "curve.csv", "w")  # written as it goes: a stopped run keeps its increments
    curve.write("delta_mm,load_N,block_displacement_mm\n")
    stepping = time.time()
    for step in range(1, args.increments + 1):
        delta = deflection * step / args.increments
        if not reach(deflection * (step - 1) / args.increments, delta):
            status = f"stopped at increment {step}: Newton did not converge, the increment halved three times"
            break
        load = sum(gf.asm_generic(parts[k][2], 0, f"{parts[k][5]}(3)", SURFACE, md) for k in free)
        sink = -gf.asm_generic(mim, 0, f"{u}(3)", -1, md) / volume
        rows.append((delta, load, sink))
        curve.write(f"{delta:.9g},{load:.9g},{sink:.9g}\n")
        curve.flush()
        left = (time.time() - stepping) / step * (args.increments - step)
        print(f"  increment {step}/{args.increments}: delta {delta:.4f} mm, load {load:.2f} N, "
              f"block {sink:.4f} mm (about {left / 60:.0f} min left)", flush=True)

    curve.close()
    peak = max(rows, key=lambda r: r[1]) if rows else (0.0, 0.0, 0.0)
    summary = {"solver": "GetFEM " + gf.__version__ if hasattr(gf, "__version__") else "GetFEM",
               "contact": "integral large sliding contact (raytracing, augmented Lagrangian)",
               "youngs_modulus_Pa": args.youngs_modulus, "poisson": args.poisson, "friction": args.friction,
               "element_size_mm": size, "punch_radius_mm": radius, "deflection_mm": deflection,
               "increments": args.increments, "converged_increments": len(rows), "status": status,
               "free_blocks": len(free), "nodes": int(sum(len(meshes[k].nodes) for k in free)),
               "P_max_N": peak[1], "delta_at_P_max_mm": peak[0], "block_displacement_at_P_max_mm": peak[2],
               "seconds": time.time() - start}
    (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(f"getfem_case: {status}; P_max {peak[1]:.1f} N at delta_b {peak[2]:.3f} mm; {out}")
    return 0 if rows else 1


if __name__ == "__main__":
    sys.exit(main())
