"""The FE reference pipeline (bench/validation/fe_model.py) against closed forms.

1. Two a x a x h prisms stacked, frictionless penalty contact between them, the bottom held in z,
   the symmetry planes x = 0 and y = 0 held normal to themselves, the top pressed down by delta:
   the stress is uniaxial and uniform, so the force is exactly
       F = a^2 delta / (2 h / E + 1 / K)      (K: the contact's penalty slope, MPa/mm)
   -- independent of Tessera's k_n. CalculiX's answer must be within 2 % (it is exact to rounding
   for a linear field, which quadratic tetrahedra represent exactly).
2. On a 3 x 3 slab made by `tessera tile`, the faces found in contact are the loaded block's four
   lateral faces, each sharing with its neighbour's the area the trapezoids' closed form gives.
3. The quarter model of that slab (run_case.py --mirror): four blocks, of a quarter, a half, a half
   and the whole of a block's volume; the loaded block's two faces in contact share half the area of
   2.; a centre off the slab's mirror planes is refused.
4. Two 2a x 2a x h prisms pressed as in 1. (bottom clamped, top held laterally), whole and by their
   quarter (mirror_part, symmetry_constraints, symmetry_weights): 4 x the quarter's force and its
   weighted mean displacement are the whole model's, to 1 %.

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

    held = [fe.Constraint("SYMX", mesh.nodes_at(0, 0, 0) + mesh.nodes_at(1, 0, 0), 1, 1),
            fe.Constraint("SYMY", mesh.nodes_at(0, 1, 0) + mesh.nodes_at(1, 1, 0), 2, 2),
            fe.Constraint("BOTTOM", mesh.nodes_at(0, 2, 0), 3, 3)]
    pressed = [fe.Constraint("TOP", mesh.nodes_at(1, 2, 2 * h), 3, 3, -delta)]
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


def volume(block) -> float:
    """The volume of a closed, outward triangle mesh (the divergence theorem), mm^3."""
    v, t = block.vertices, block.triangles
    return float(np.einsum("ij,ij->i", v[t[:, 0]], np.cross(v[t[:, 1]], v[t[:, 2]])).sum() / 6)


def slab_quarter(work: Path) -> None:
    import fe_model as fe
    blocks = fe.read_bundle(work / "slab3")
    loaded = next(k for k, b in enumerate(blocks) if not b.fixed)
    centre = blocks[loaded].vertices.mean(axis=0)
    whole = volume(blocks[loaded])
    quarter, axes = fe.mirror_part(blocks, centre)
    assert axes == [0, 1], f"the 3 x 3 slab's mirror planes: {axes}"
    shares = sorted(volume(b) / whole for b in quarter)
    assert np.allclose(shares, [0.25, 0.5, 0.5, 1.0], rtol=1e-9), f"quarter's volumes {shares} of a block's"
    faces = [fe.planar_faces(b) for b in quarter]
    pairs = fe.shared_faces(quarter, faces, 1e-6)
    side, h, tilt = 10.0, 3.18, np.radians(5.0)
    shared = (side * h - np.tan(tilt) * h * h / 2) / np.cos(tilt)
    cut = next(k for k, b in enumerate(quarter) if b.name == blocks[loaded].name)
    assert len(pairs) == 2 and all(cut in (a, b) for a, _, b, _ in pairs), f"pairs {pairs}"
    for a, i, b, j in pairs:
        common = fe.overlap_area(quarter[a].vertices[faces[a][i].loop], quarter[b].vertices[faces[b][j].loop],
                                 faces[a][i].normal)
        assert abs(common / (shared / 2) - 1) < 1e-6, f"the quarter's faces share {common} mm^2, not {shared / 2}"
    # Off centre along x only the plane y = y_c remains a mirror plane: a half.
    half, axes = fe.mirror_part(blocks, centre + [1.0, 0, 0])
    assert axes == [1] and len(half) == 6, f"a half about y = y_c: {len(half)} blocks, axes {axes}"
    try:
        fe.mirror_part(blocks, centre + [1.0, 1.0, 0])
    except ValueError:
        pass
    else:
        raise AssertionError("a part about planes the slab is not symmetric about was accepted")
    print(f"quarter: {len(quarter)} blocks ({', '.join(f'{x:g}' for x in shares)} of a block), {len(pairs)} contact pairs")


def mirror_press(work: Path) -> None:
    import fe_model as fe
    a, h, delta = 10.0, 4.0, 0.01
    model = fe.Model(friction=0.0, element_size=2.0, increments=1)
    whole = [fe.box("lower", [-a, -a, 0], [a, a, h]), fe.box("upper", [-a, -a, h], [a, a, 2 * h])]
    centre = np.zeros(3)
    answers = []
    for name, (blocks, axes) in (("whole", (whole, [])), ("quarter", fe.mirror_part(whole, centre))):
        mesh = fe.mesh_blocks(blocks, model.element_size)
        upper = next(k for k, b in enumerate(blocks) if b.name == "upper")

        held = [fe.Constraint("BOTTOM", mesh.nodes_at(1 - upper, 2, 0), 1, 3)] + fe.symmetry_constraints(mesh, centre, axes)
        top = mesh.nodes_at(upper, 2, 2 * h)
        pressed = [fe.Constraint("TOP", top, 1, 2), fe.Constraint("TOP", top, 3, 3, -delta)]
        watch = mesh.node_ids(upper, np.ones(len(mesh.meshes[upper].nodes), bool))
        fe.write_input(work / f"{name}.inp", mesh, model, held, pressed, watch=watch)
        stopped = fe.run_ccx(work / f"{name}.inp")
        assert not stopped, f"ccx stopped on the {name} model: {stopped}"
        printed = fe.read_dat(work / f"{name}.dat")
        time, force = fe.totals(printed)[-1]
        mean = fe.mean_displacements(printed, fe.symmetry_weights(mesh, centre, axes))[time]
        answers.append((-force[2] * 2 ** len(axes), -mean[2]))
    (f_whole, u_whole), (f_part, u_part) = answers
    print(f"mirror: whole {f_whole:.6g} N, mean {u_whole:.6g} mm; quarter x 4 {f_part:.6g} N, mean {u_part:.6g} mm")
    assert abs(f_part / f_whole - 1) < 0.01, "4 x the quarter's force is not the whole model's"
    assert abs(u_part / u_whole - 1) < 0.01, "the quarter's weighted mean displacement is not the whole model's"


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
    slab_quarter(work)
    mirror_press(work)
    return 0


if __name__ == "__main__":
    sys.exit(main())
