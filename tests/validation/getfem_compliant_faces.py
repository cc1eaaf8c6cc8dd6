"""The GetFEM reference's contact (bench/validation/getfem_case.py, contact_terms) against GetFEM's
own brick and against the closed forms of compliant faces, the law Tessera's rigid blocks follow.

A block stands on another whose bottom is clamped; their faces touch over A = a^2. The upper
block's top is driven.
1. Rigid faces (compliance 0), elastic blocks, pressed down by d: contact_terms gives the force of
   GetFEM's integral large sliding contact brick, whose formulation it writes out, to 1e-9.
2. Compliant faces (c = 1/k_n, k_t = k_n, friction mu), nearly rigid blocks (E x 1000):
   a. pressed down by d: the normal force is A d / (c + 2 h / E_b), the faces and the two blocks
      in series (the blocks add 0.08 %), within 0.1 %;
   b. then slid sideways by s, the press held: the tangential force is the spring's, k_t A s, while
      below Coulomb's limit mu N (here up to s = mu d), within 1 % of it, and mu N past it;
   c. then slid back by b: the spring unloads from the limit, mu N - k_t A b, within 1 %.
   A law without the tangential spring sticks rigidly (b. jumps to mu N); one that forgets the
   traction reached (store_last not called) fails b. at its second step.

Usage: getfem_compliant_faces.py. Exit 77 (skipped) where GetFEM is not installed.
"""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench" / "validation"))

E, NU, SIDE, H, SIZE = 4200.0, 0.2, 4.0, 2.0, 1.0  # MPa, -, mm
K_N, MU, PRESS = 840.0, 0.5, 0.01                   # MPa/mm, -, mm


def pair(gf, stiffness: float, compliance: float, brick: bool = False):
    """The two blocks (E x stiffness) in contact, by contact_terms or by GetFEM's brick; returns
    drive(x, z): the top moved to (x, 0, z), the face's force (N) on the upper block."""
    from getfem_case import RAY, U_ALL, W_ALL, contact_terms, store_last
    from getfem_sliding_press import BOTTOM, TOP, elastic_block
    grid = np.linspace(0, SIDE, int(SIDE / SIZE) + 1)
    meshes = {"lower": gf.Mesh("cartesian", grid, grid, np.linspace(0, H, 3)),
              "upper": gf.Mesh("cartesian", grid, grid, np.linspace(H, 2 * H, 3))}
    md = gf.Model("real")
    md.add_initialized_data("lambda", [stiffness * E * NU / ((1 + NU) * (1 - 2 * NU))])
    md.add_initialized_data("mu", [stiffness * E / (2 * (1 + NU))])
    md.add_initialized_data("compliance", [compliance])
    md.add_initialized_data("r", [1 / (compliance + SIZE / (stiffness * E))])  # as getfem_case.py
    md.add_initialized_data("f", [MU])
    md.add_initialized_data("alpha", [1.0])
    md.add_initialized_data("pressed", [0.0, 0.0, 0.0])
    keep = {}  # GetFEM's objects live while Python holds them
    for name, m in meshes.items():
        mfu, mim = elastic_block(gf, md, name, m)
        md.add_fem_data(f"{name}_last", mfu)
        keep[name] = (m, mfu, mim)
    (lower, lower_fem, lower_im), (upper, upper_fem, upper_im) = keep["lower"], keep["upper"]
    md.add_Dirichlet_condition_with_multipliers(lower_im, "lower", lower_fem, BOTTOM)
    md.add_Dirichlet_condition_with_multipliers(upper_im, "upper", upper_fem, TOP, "pressed")
    md.add_filtered_fem_variable("traction", upper_fem, BOTTOM)
    md.add_fem_data("traction_last", upper_fem)
    if brick:
        contact = md.add_integral_large_sliding_contact_brick_raytracing("r", SIZE, "f", "alpha", 0)
        md.add_slave_contact_boundary_to_large_sliding_contact_brick(contact, upper_im, BOTTOM, "upper", "traction",
                                                                     "upper_last")
        md.add_master_contact_boundary_to_large_sliding_contact_brick(contact, lower_im, TOP, "lower", "lower_last")
    else:
        md.add_raytracing_transformation(RAY, SIZE)
        md.define_variable_group(U_ALL, "lower", "upper")
        md.define_variable_group(W_ALL, "lower_last", "upper_last")
        md.add_master_contact_boundary_to_raytracing_transformation(RAY, lower, U_ALL, TOP)
        md.add_slave_contact_boundary_to_raytracing_transformation(RAY, upper, U_ALL, BOTTOM)
        md.add_nonlinear_term(upper_im, contact_terms("upper", "upper_last", "traction"), BOTTOM)

    def drive(x: float, z: float) -> np.ndarray:
        md.set_variable("pressed", [x, 0.0, z])
        converged = md.solve("max_res", 1e-10, "max_iter", 40, "lsearch", "simplest", "lsolver", "mumps")[1]
        assert converged, f"Newton did not converge at x = {x}, z = {z}"
        for name in ("lower", "upper"):
            md.set_variable(f"{name}_last", md.variable(name))
        store_last(md, upper_fem, BOTTOM, "traction")
        return np.array([gf.asm_generic(upper_im, 0, f"traction({i + 1})", BOTTOM, md) for i in range(3)])

    drive.keep = (md, keep)
    return drive


def main() -> int:
    try:
        import getfem as gf
    except ImportError as e:
        print(f"skipped: {e} (scripts/setup.sh installs python3-getfem)")
        return 77
    gf.util_trace_level(0)
    gf.util_warning_level(0)

    ours, brick = pair(gf, 1.0, 0.0)(0.0, -PRESS), pair(gf, 1.0, 0.0, brick=True)(0.0, -PRESS)
    print(f"rigid faces, pressed {PRESS} mm: contact_terms {ours[2]:.9g} N, the brick {brick[2]:.9g} N")
    assert abs(ours[2] / brick[2] - 1) < 1e-9, "contact_terms is not the brick's formulation"

    stiffness = 1000.0
    drive = pair(gf, stiffness, 1 / K_N)
    area = SIDE * SIDE
    normal = area * PRESS / (1 / K_N + 2 * H / (stiffness * E))
    force = drive(0.0, -PRESS)
    print(f"compliant faces, pressed {PRESS} mm: N = {force[2]:.6g} N, closed form {normal:.6g} N")
    assert abs(force[2] / normal - 1) < 1e-3, "the normal force is not A d / (1/k_n + 2h/E)"
    limit = MU * normal
    # (slide, the tangential force's closed form, whether the spring is below the limit): elastic,
    # elastic, at the limit, sliding on, then back by 0.002 mm: unloading from the limit
    for s, expected, elastic in ((0.002, K_N * area * 0.002, True), (0.004, K_N * area * 0.004, True),
                                 (0.006, limit, False), (0.02, limit, False),
                                 (0.018, limit - K_N * area * 0.002, True)):
        force = drive(s, -PRESS)
        tangential = -force[0]
        print(f"slid to {s} mm: T = {tangential:.6g} N, closed form {expected:.6g} N (N = {force[2]:.6g} N)")
        tolerance = 0.01 * (expected if elastic else normal)
        assert abs(tangential - expected) < tolerance, f"the tangential force at s = {s} mm is not the closed form"
        assert abs(force[2] / normal - 1) < 1e-3, "the normal force moved while sliding"
    return 0


if __name__ == "__main__":
    sys.exit(main())
