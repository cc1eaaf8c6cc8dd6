"""The GetFEM reference's compliant faces (bench/validation/getfem_case.py --span-contact) against
their closed forms: the law Tessera's rigid blocks follow, solved by the FE.

A nearly rigid block (E x 1000) stands on another whose bottom is clamped; their faces touch over
A = a^2 with compliance c = 1/k_n (k_t = k_n), friction mu. The upper block's top is driven:
1. pressed down by d: the normal force is A d / (c + 2 h / E_b) (the faces and the two blocks in
   series; the blocks add 0.2 %);
2. then slid sideways by s, the press held: the tangential force is the spring's, k_t A s, while
   below Coulomb's limit mu N (here up to s = mu d), and mu N past it;
3. then slid back by b: the spring unloads from the limit, mu N - k_t A b.
Each within 1 % of N. A law without the tangential spring sticks rigidly (2. jumps to mu N); one
without history forgets the limit reached (3. gives k_t A (s - b) or its sign flipped).

Usage: getfem_compliant_faces.py. Exit 77 (skipped) where GetFEM is not installed.
"""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench" / "validation"))

E, NU, A_SIDE, H, SIZE = 4200.0 * 1000, 0.2, 4.0, 2.0, 1.0  # MPa (nearly rigid), -, mm
K_N, MU, PRESS = 840.0, 0.5, 0.01  # MPa/mm, -, mm


def main() -> int:
    try:
        import getfem as gf
    except ImportError as e:
        print(f"skipped: {e} (scripts/setup.sh installs python3-getfem)")
        return 77
    from getfem_case import RAY, U_ALL, W_ALL, contact_terms
    gf.util_trace_level(0)
    gf.util_warning_level(0)
    TOP, BOTTOM = 1, 2
    grid = np.linspace(0, A_SIDE, int(A_SIDE / SIZE) + 1)
    lower = gf.Mesh("cartesian", grid, grid, np.linspace(0, H, 3))
    upper = gf.Mesh("cartesian", grid, grid, np.linspace(H, 2 * H, 3))
    md = gf.Model("real")
    md.add_initialized_data("lambda", [E * NU / ((1 + NU) * (1 - 2 * NU))])
    md.add_initialized_data("mu", [E / (2 * (1 + NU))])
    md.add_initialized_data("compliance", [1 / K_N])
    md.add_initialized_data("r", [K_N])
    md.add_initialized_data("f", [MU])
    md.add_initialized_data("alpha", [1.0])
    md.add_initialized_data("pressed", [0.0, 0.0, 0.0])
    md.add_raytracing_transformation(RAY, SIZE)
    keep = []  # GetFEM's objects live while Python holds them
    for name, m in (("lower", lower), ("upper", upper)):
        m.set_region(TOP, m.outer_faces_with_direction([0.0, 0.0, 1.0], 0.01))
        m.set_region(BOTTOM, m.outer_faces_with_direction([0.0, 0.0, -1.0], 0.01))
        mfu = gf.MeshFem(m, 3)
        mfu.set_classical_fem(2)
        mim = gf.MeshIm(m, 5)
        md.add_fem_variable(name, mfu)
        md.add_fem_data(f"{name}_last", mfu)
        md.add_isotropic_linearized_elasticity_brick(mim, name, "lambda", "mu")
        keep.append((m, mfu, mim))
    (_, lower_fem, lower_im), (_, upper_fem, upper_im) = keep
    md.add_Dirichlet_condition_with_multipliers(lower_im, "lower", lower_fem, BOTTOM)
    md.add_Dirichlet_condition_with_multipliers(upper_im, "upper", upper_fem, TOP, "pressed")
    md.add_filtered_fem_variable("traction", upper_fem, BOTTOM)
    md.add_fem_data("traction_last", upper_fem)
    md.define_variable_group(U_ALL, "lower", "upper")
    md.define_variable_group(W_ALL, "lower_last", "upper_last")
    md.add_master_contact_boundary_to_raytracing_transformation(RAY, lower, U_ALL, TOP)
    md.add_slave_contact_boundary_to_raytracing_transformation(RAY, upper, U_ALL, BOTTOM)
    md.add_nonlinear_term(upper_im, contact_terms("upper", "upper_last", "traction"), BOTTOM)

    def drive(x: float, z: float) -> np.ndarray:
        """The top moved to (x, 0, z); the face's force (x, y, z) on the upper block (N)."""
        md.set_variable("pressed", [x, 0.0, z])
        converged = md.solve("max_res", 1e-10, "max_iter", 40, "lsearch", "simplest", "lsolver", "mumps")[1]
        assert converged, f"Newton did not converge at x = {x}, z = {z}"
        for name in ("lower", "upper"):
            md.set_variable(f"{name}_last", md.variable(name))
        last = np.zeros(upper_fem.nbdof())
        last[upper_fem.basic_dof_on_region(BOTTOM)] = md.variable("traction")
        md.set_variable("traction_last", last)
        return np.array([gf.asm_generic(upper_im, 0, f"traction({i + 1})", BOTTOM, md) for i in range(3)])

    area = A_SIDE * A_SIDE
    normal = area * PRESS / (1 / K_N + 2 * H / E)
    force = drive(0.0, -PRESS)
    print(f"pressed {PRESS} mm: N = {force[2]:.6g} N, closed form {normal:.6g} N")
    assert abs(force[2] / normal - 1) < 0.01, "the normal force is not k_n A d"
    limit = MU * normal
    # (slide, the tangential force's closed form, N): elastic, elastic, at the limit, sliding on,
    # then back by 0.002 mm: unloading from the limit
    for s, expected in ((0.002, K_N * area * 0.002), (0.004, K_N * area * 0.004), (0.006, limit),
                        (0.02, limit), (0.018, limit - K_N * area * 0.002)):
        force = drive(s, -PRESS)
        tangential = -force[0]
        print(f"slid to {s} mm: T = {tangential:.6g} N, closed form {expected:.6g} N (N = {force[2]:.6g} N)")
        assert abs(tangential - expected) < 0.01 * normal, f"the tangential force at s = {s} mm is not the closed form"
        assert abs(force[2] / normal - 1) < 0.01, "the normal force moved while sliding"
    return 0


if __name__ == "__main__":
    sys.exit(main())
