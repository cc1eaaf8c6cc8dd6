"""The FE reference pipeline (bench/validation/fe_model.py) against closed forms.

1. Two a x a x h prisms stacked, frictionless penalty contact between them, the bottom held in z,
   the symmetry planes x = 0 and y = 0 held normal to themselves, the top pressed down by delta:
   the stress is uniaxial and uniform, so the force is exactly
       F = a^2 delta / (2 h / E + 1 / K)      (K: the contact's penalty slope, MPa/mm)
   -- independent of Tessera's k_n. CalculiX's answer must be within 2 % (it is exact to rounding
   for a linear field, which quadratic tetrahedra represent exactly).
2. On a 3 x 3 slab made by `tessera tile`, the faces found in contact are the loaded block's four
   lateral faces, each sharing with its neighbour's the area the trapezoids' closed form gives.

Usage: fe_prism.py TESSERA_EXE WORK_DIR. Exit 77 (skipped) where ccx or gmsh is not installed.
"""
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench" / "validation"))


def prism(work: Path) -> None:
    import fe_model as fe
    a, h, delta = 10.0, 4.0, 0.01
    model = fe.Model(friction=0.0, element_size=2.0, increments=2)
    blocks = [fe.box("lower", [0, 0, 0], [a, a, h]), fe.box("upper", [0, 0, h], [a, a, 2 * h])]
    mesh = fe.mesh_blocks(blocks, model.element_size)
    assert len(mesh.pairs) == 1, f"expected one contact pair, found {mesh.pairs}"

    def on(k, axis, value):
        return mesh.node_ids(k, np.abs(mesh.meshes[k].nodes[:, axis] - value) < 1e-9)

    held = [fe.Constraint("SYMX", on(0, 0, 0) + on(1, 0, 0), 1, 1),
            fe.Constraint("SYMY", on(0, 1, 0) + on(1, 1, 0), 2, 2),
            fe.Constraint("BOTTOM", on(0, 2, 0), 3, 3)]
    pressed = [fe.Constraint("TOP", on(1, 2, 2 * h), 3, 3, -delta)]
    fe.write_input(work / "prism.inp", mesh, model, held, pressed)
    stopped = fe.run_ccx(work / "prism.inp")
    assert not stopped, f"ccx stopped: {stopped}"
    time, force = fe.totals(fe.read_dat(work / "prism.dat"))[-1]
    exact = a * a * delta / (2 * h / model.youngs_modulus + 1 / model.contact_slope())
    error = -force[2] / exact - 1
    print(f"prism: F = {-force[2]:.6g} N at t = {time}, closed form {exact:.6g} N, error {error:.2e}")
    assert time == model.increments, f"the step stopped at {time} of {model.increments}"
    assert abs(error) < 0.02, "the FE force differs from the closed form"
    assert np.hypot(force[0], force[1]) < 1e-6 * exact, "a lateral force on a frictionless press"


def slab_contacts(tessera: str, work: Path) -> None:
    import fe_model as fe
    root = Path(__file__).resolve().parents[2]
    bundle = work / "slab3"
    subprocess.run([tessera, "tile", "--block", str(root / "assets/blocks/planar_a10_h3.18_5deg.obj"),
                    "--unit", "mm", "--grid", "3x3", "--pitch", "10", "-o", str(bundle), "--replace"],
                   check=True, capture_output=True)
    blocks = fe.read_bundle(bundle)
    faces = [fe.planar_faces(b) for b in blocks]
    assert all(len(f) == 6 for f in faces), "a planar block has six faces"
    pairs = fe.shared_faces(blocks, faces, 1e-6)
    centre = next(k for k, b in enumerate(blocks) if not b.fixed)
    assert len(pairs) == 4 and all(centre in (a, b) for a, _, b, _ in pairs), f"pairs {pairs}"
    # Each face is a trapezoid (a -/+ 2 z tan(theta) wide at height z, up its 1 / cos(theta) slope)
    # and its neighbour's the same one upside down: they share a - 2 |z| tan(theta).
    side, h, tilt = 10.0, 3.18, np.radians(5.0)
    whole = side * h / np.cos(tilt)
    shared = (side * h - np.tan(tilt) * h * h / 2) / np.cos(tilt)
    for a, i, b, j in pairs:
        fa, fb = faces[a][i], faces[b][j]
        own = fe.overlap_area(blocks[a].vertices[fa.loop], blocks[a].vertices[fa.loop], fa.normal)
        common = fe.overlap_area(blocks[a].vertices[fa.loop], blocks[b].vertices[fb.loop], fa.normal)
        assert abs(own / whole - 1) < 1e-6, f"face {a}.{i} has {own} mm^2, not {whole}"
        assert abs(common / shared - 1) < 1e-6, f"faces {a}.{i} and {b}.{j} share {common} mm^2, not {shared}"
    print(f"slab: {len(pairs)} contact pairs, each sharing {shared:.4f} of {whole:.4f} mm^2 as the closed form says")


def main() -> int:
    try:
        import gmsh  # noqa: F401
    except ImportError:
        print("skipped: python3-gmsh is not installed (scripts/setup.sh installs it)")
        return 77
    if shutil.which("ccx") is None:
        print("skipped: ccx (calculix-ccx) is not installed (scripts/setup.sh installs it)")
        return 77
    tessera, work = sys.argv[1], Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    prism(work)
    slab_contacts(tessera, work)
    return 0


if __name__ == "__main__":
    sys.exit(main())
