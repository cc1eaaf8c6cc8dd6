#!/usr/bin/env python3
"""One FE reference run to the peak with GetFEM's large-sliding contact (docs/validation.md, "To the
peak with GetFEM").

CalculiX's contacts overstate a press slid past an edge (sliding_press.py); GetFEM's raytracing
contact with an augmented-Lagrangian multiplier (the formulation of its integral large sliding
contact brick, written out here in its weak-form language: contact_terms; Y. Renard & K.
Poulios, GetFEM's user documentation, "Large sliding/large deformation contact with friction
bricks") follows it: slid in 10 increments it ends on the pressed-in-place force to six digits
(getfem_sliding_press.py). Here the slab's free blocks are elastic solids (linear elasticity or,
with --large-displacements, Saint Venant-Kirchhoff's finite strain; quadratic elements on the
corners of gmsh's tetrahedra, fe_model.mesh_block). Each face a free block shares with another
block is a contact interface with Coulomb friction, taken once: the free block is its slave side
against a fixed block (meshed, clamped on its whole surface: Tessera's fixed blocks never move, as
fe_model clamps every node of them) and against a free block of higher index, its master side
against one of lower index. The faces are rigid (no penetration), or with
--span-contact compliant as Tessera's: traction k_n times the penetration, k_n = E M / L from the
bundle's span, and a tangential spring k_t = k_n held to Coulomb's limit (contact_terms). The
loaded block's top is pressed down on a round patch at its centre, held laterally (as
run_case.py); the load is the patch's reaction (its check, support_N: the vertical force the free
blocks put on the fixed ones, the same where the model has no weight and the faces against fixed
blocks touch nothing else), and friction's slip in an increment is measured from the last one's
displacement. Units: mm, N, MPa.

Usage: getfem_case.py BUNDLE -o DIR [--youngs-modulus PA] [--poisson NU] [--friction MU]
                      [--element-size F] [--deflection F] [--punch-radius F] [--increments N] [--mirror]
                      [--neighbour-stiffness F] [--block-stiffness F] [--span-contact]
                      [--large-displacements] [--augmentation F] [--newton-log] [--resume]
Lengths F are fractions of the loaded block's thickness h, as in run_case.py. --mirror models the
half or quarter of the slab on the positive side of its mirror planes through the loaded block's
centre, as run_case.py --mirror does (fe_model.mirror_part: blocks across them cut; here the cut
faces of the free blocks held normal to their plane by a penalty 10^4 times the stiffest blocks'
E / element size) and reports the whole slab's load (exit 2 for a slab with neither plane, and for
--span-contact on a bundle without a span). --neighbour-stiffness F
multiplies the Young's modulus of the free blocks other than the loaded one (100: nearly rigid, as
Tessera's blocks are, which separates their own deformation from the rest); --block-stiffness F
every free block's. With --block-stiffness 1000 --span-contact --large-displacements the FE solves
Tessera's own model, rigid blocks on compliant faces, quasi-statically (on the 3 x 3 slab; on the
5 x 5 ones Newton does not converge so: docs/validation.md). Writes DIR/curve.csv
(delta_mm, load_N, block_displacement_mm: the loaded block's mean downward displacement, Tessera's
delta_b, and support_N),
DIR/blocks.csv (delta_mm, each free block's mean downward displacement by name, and its mean
rotation about x, y and z in degrees, NAME_tilt_x_deg ...) and
DIR/summary.json, all after every increment: a stopped run keeps what it reached, and
DIR/state.npz, from which --resume goes on (with the same options except --augmentation; the
curves come out the same to the digit; summary.json lists each session's augmentation). An
increment Newton does not get through is cut into 2, 4 ... 16 sub-steps, kept while they are
needed (reach). --augmentation F scales the augmentation parameter, which moves
Newton's path and, where friction's solution is not unique, the answer by up to 2 % (hex5 at
0.6 h: 0.1 and 1 are 0.3-2.1 % apart). Needs Debian's
python3-getfem (scripts/setup.sh) and python3-gmsh.
"""
import argparse
import json
import sys
import time
import zipfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import fe_model as fe  # noqa: E402
from run_case import add_slab_arguments, face_stiffness, factor, refuse, slab_part  # noqa: E402


def convex_points(nodes, corners):
    """Tetrahedra by their corners as GetFEM's add_convex takes them: dim x 4 x convexes (straight
    simplices: the blocks' faces are planes)."""
    return np.ascontiguousarray(nodes[corners].transpose(2, 1, 0))


def face_centres(mesh, faces) -> np.ndarray:
    """The centre of each of `faces` (GetFEM's 2 x F convex/face array), F x 3."""
    return np.array([mesh.pts(mesh.pid_in_faces(faces[:, [j]])).mean(axis=1) for j in range(faces.shape[1])])


def faces_on(mesh, normal, offset: float, tolerance: float) -> np.ndarray:
    """The mesh's outer faces on the plane normal . x = offset with that outward normal."""
    faces = mesh.outer_faces_with_direction(normal, 0.01)
    if faces.shape[1] == 0:
        return faces
    return faces[:, np.abs(face_centres(mesh, faces) @ normal - offset) <= tolerance]


RAY, U_ALL, W_ALL = "contact", "displacements", "last_displacements"  # the raytracing and its groups
MOST_SUBSTEPS = 16  # an increment's finest cut (getfem_case's reach)


def contact_terms(u: str, w: str, multiplier: str) -> str:
    """The weak form of a slave boundary's contact (GWFL, on its region): GetFEM's integral large
    sliding contact (Renard & Poulios; the brick's non-symmetric form) with the faces' compliance c.
    The multiplier (the traction on the slave side) solves multiplier = P(multiplier, n, V, g, f, r),
    P the augmented projection on Coulomb's cone, n the slave's deformed normal, where the ray meets
    a master; at that fixed point the compliant gap and slip vanish:
        g = (x_master - x) . n - c multiplier . n     (rigid: c = 0; compliant: multiplier . n = g / c)
        V = slip since the last increment + c (multiplier - its last value)_t
    so the traction is k_n = 1/c times the penetration and its tangential part a spring k_t = k_n,
    held to f times the normal one (the projection drops V's normal part). The spring's history is
    the traction at the slave point, in the fixed frame: unlike Tessera's, it is not turned with a
    face that turns, nor dropped when the point's master changes (store_last)."""
    n = f"Transformed_unit_vector(Grad_{u}, Normal)"
    last = f"{multiplier}_last"
    change = f"({multiplier}-{last})"
    gap = f"((Interpolate(X,{RAY})+Interpolate({U_ALL},{RAY})-X-{u}).{n}-compliance*{multiplier}.{n})"
    slip = f"(({u}-Interpolate({U_ALL},{RAY})-{w}+Interpolate({W_ALL},{RAY}))+compliance*{change})*alpha"
    projection = f"Coulomb_friction_coupled_projection({multiplier}, {n}, {slip}, {gap}, f, r)"
    return (f"-{multiplier}.Test_{u} + Interpolate_filter({RAY}, {multiplier}.Interpolate(Test_{U_ALL},{RAY}), 1)"
            f" - (1/r)*{multiplier}.Test_{multiplier}"
            f" + Interpolate_filter({RAY}, (1/r)*{projection}.Test_{multiplier}, 1)")


def store_last(md, mfu, region: int, multiplier: str) -> None:
    """The traction reached, as contact_terms' MULTIPLIER_last (data on the whole mfu: the filtered
    multiplier's dofs are mfu's on the region, in order)."""
    last = np.zeros(mfu.nbdof())
    last[mfu.basic_dof_on_region(region)] = md.variable(multiplier)
    md.set_variable(f"{multiplier}_last", last)


def run_options(args) -> str:
    """What makes a run the run it is (every option but where it writes, how it talks and Newton's
    augmentation parameter), as the state file records it: a run resumes only with the same."""
    options = {k: v for k, v in sorted(vars(args).items()) if k not in ("out", "resume", "newton_log", "augmentation")}
    options["bundle"] = str(Path(args.bundle).resolve())
    return json.dumps(options)


def save_state(path: Path, md, data_names, step: int, steps: int, curve_lines, block_lines, options: str,
               seconds: float, sessions) -> None:
    """The model's state after increment `step` (its variables, friction's references and the
    tractions' history), the lines written so far, the run's time and its sessions (the increment
    each started after, its augmentation), replaced atomically."""
    partial = path.with_name(path.name + ".partial")
    with open(partial, "wb") as f:
        np.savez(f, variables=md.from_variables(), step=step, steps=steps, options=options, seconds=seconds,
                 sessions=json.dumps(sessions),
                 curve="".join(curve_lines), blocks="".join(block_lines),
                 **{name: md.variable(name) for name in data_names})
    partial.replace(path)


def read_state(path: Path, options: str):
    """The state save_state wrote, for a run with these options (else the reason and exit 2)."""
    try:
        state = np.load(path)
        recorded = str(state["options"])
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile) as e:
        refuse("getfem_case", f"{path}: not a state this script wrote ({e}); start again without --resume")
    if recorded != options:
        refuse("getfem_case", f"{path} is a run with other options; resume with the same ones, or start again "
               "without --resume")
    return state


def restore_state(state, md, data_names):
    """Put a read_state state back in md; (step, steps, curve lines, block lines, seconds, sessions)."""
    if state["variables"].size != md.from_variables().size:
        refuse("getfem_case", "the state is of another model (its size differs); start again without --resume")
    md.to_variables(state["variables"])
    for name in data_names:
        md.set_variable(name, state[name])
    return (int(state["step"]), int(state["steps"]), str(state["curve"]).splitlines(keepends=True),
            str(state["blocks"]).splitlines(keepends=True), float(state["seconds"]),
            json.loads(str(state["sessions"])))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_slab_arguments(parser)
    parser.add_argument("--neighbour-stiffness", type=factor, default=1.0,
                        help="Young's modulus of the free blocks other than the loaded one, x this (default 1; "
                             "100: nearly rigid, the run that separates their own deformation from the rest)")
    parser.add_argument("--large-displacements", action="store_true",
                        help="finite-strain elasticity (Saint Venant-Kirchhoff), for blocks that turn by degrees "
                             "(default: linearised, where a block turned by theta grows by about theta^2 / 2)")
    parser.add_argument("--augmentation", type=factor, default=1.0,
                        help="the augmentation parameter r x this (default 1: one element of the stiffest "
                             "blocks in series with the faces); it moves Newton's path, the answer by up to 2 %%")
    parser.add_argument("--newton-log", action="store_true", help="print Newton's residual at every iteration")
    parser.add_argument("--resume", action="store_true",
                        help="go on from the last increment a run with the same options (--augmentation may "
                             "differ) saved in DIR/state.npz")
    args = parser.parse_args()
    import getfem as gf
    gf.util_trace_level(0)
    gf.util_warning_level(0)

    start = time.time()
    out = Path(args.out)
    options, state_file = run_options(args), out / "state.npz"
    state = read_state(state_file, options) if args.resume and state_file.exists() else None
    if args.resume and state is None:
        print(f"getfem_case: no {state_file}: starting from the beginning", flush=True)
    blocks, loaded, h, centre, axes = slab_part(args.bundle, args.mirror, "getfem_case")
    k_n = face_stiffness(args, "getfem_case")
    compliance = 1.0 / k_n if k_n else 0.0  # mm/MPa, the faces' (0: rigid)
    share = 2 ** len(axes)  # the whole slab's load per the model's
    out.mkdir(parents=True, exist_ok=True)  # (after the refusals of the slab and its span)
    if state is None and state_file.exists():
        state_file.unlink()  # another run's: it must not sit beside this one's curves
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
    stiffest = E * args.block_stiffness * max(1.0, args.neighbour_stiffness)
    md = gf.Model("real")
    md.add_initialized_data("lambda", [args.block_stiffness * lam])
    md.add_initialized_data("mu", [args.block_stiffness * mu])
    md.add_initialized_data("lambda_neighbour", [args.block_stiffness * args.neighbour_stiffness * lam])
    md.add_initialized_data("mu_neighbour", [args.block_stiffness * args.neighbour_stiffness * mu])
    # the augmentation parameter: an element of the stiffest blocks in series with the faces
    # (convergence, not the answer)
    md.add_initialized_data("r", [args.augmentation / (compliance + size / stiffest)])
    md.add_initialized_data("f", [args.friction])
    md.add_initialized_data("alpha", [1.0])
    md.add_initialized_data("held", [1e4 * stiffest / size])  # the mirror planes' penalty (MPa/mm)
    md.add_initialized_data("compliance", [compliance])
    md.add_raytracing_transformation(RAY, size)  # (release distance: an element)
    slaves, masters = [], []  # the contact boundaries, given to the transformation once every variable exists
    # Regions of a free block's mesh: SLAVE its faces in contact as the slave side (against a fixed
    # block, AGAINST_FIXED too, or a free block of higher index), MASTER as the master side (against
    # a free block of lower index: each interface is constrained once), PATCH the punch, MIRROR + a
    # the cut faces on the mirror plane of axis a. A fixed block's mesh: SLAVE its whole surface.
    SLAVE, AGAINST_FIXED, MASTER, PATCH, MIRROR = 1, 2, 3, 4, 5
    tolerance = 1e-6 * fe.slab_size(blocks)
    planes = [fe.planar_faces(b) for b in blocks]
    pairs = fe.shared_faces(blocks, planes, tolerance)
    partners = {}  # (block, face) -> the blocks across that face
    for a, i, b, j in pairs:
        partners.setdefault((a, i), []).append(b)
        partners.setdefault((b, j), []).append(a)

    def on_mirror(face, axis):
        return face.normal @ np.eye(3)[axis] < -1 + 1e-9 and abs(face.offset + centre[axis]) <= tolerance

    parts = {}
    for k in free:
        m = gf.Mesh("empty", 3)
        m.add_convex(gf.GeoTrans("GT_PK(3,1)"), convex_points(meshes[k].nodes, meshes[k].tets[:, :4]))
        faces = planes[k]

        def region(which):  # the mesh faces of the block's planar faces i for which which(partners) holds
            chosen = [faces_on(m, f.normal, f.offset, tolerance) for i, f in enumerate(faces)
                      if which(partners.get((k, i), []))]
            return np.hstack(chosen) if chosen else np.zeros((2, 0), int)
        m.set_region(SLAVE, region(lambda across: any(blocks[b].fixed or b > k for b in across)))
        m.set_region(AGAINST_FIXED, region(lambda across: any(blocks[b].fixed for b in across)))
        m.set_region(MASTER, region(lambda across: any(not blocks[b].fixed and b < k for b in across)))
        mfu = gf.MeshFem(m, 3)
        mfu.set_classical_fem(2)
        mim = gf.MeshIm(m, 4)
        u, w, multiplier = f"u{k}", f"w{k}", f"lambda{k}"
        md.add_fem_variable(u, mfu)
        md.add_fem_data(w, mfu)
        moduli = "" if k == loaded else "_neighbour"
        if args.large_displacements:  # Saint Venant-Kirchhoff: a rigid rotation strains nothing
            md.add_finite_strain_elasticity_brick(mim, "SaintVenant Kirchhoff", u, f"[lambda{moduli}; mu{moduli}]")
        else:  # linearised: turned by theta, points move along tangents: the block grows by ~theta^2 / 2
            md.add_isotropic_linearized_elasticity_brick(mim, u, f"lambda{moduli}", f"mu{moduli}")
        for a in axes:  # symmetry: the cut face moves in its plane only (a penalty 10^4 times the
            # elements' own stiffness E/size: a multiplier would conflict with the punch's on the loaded block)
            if any(on_mirror(f, a) for f in faces):
                m.set_region(MIRROR + a, faces_on(m, -np.eye(3)[a], -centre[a], tolerance))
                md.add_linear_term(mim, f"held*{u}({a + 1})*Test_{u}({a + 1})", MIRROR + a)
        if m.region(SLAVE).size:
            md.add_filtered_fem_variable(multiplier, mfu, SLAVE)
            md.add_fem_data(f"{multiplier}_last", mfu)  # the traction at the last increment (on SLAVE)
            slaves.append((m, mim, u, w, multiplier))
        else:
            multiplier = None
        if m.region(MASTER).size:
            masters.append((m, MASTER))
        parts[k] = (m, mfu, mim, u, w, multiplier)
    touching = {k for a, _, b, _ in pairs for k in (a, b)}
    for k, b in enumerate(blocks):  # those that share a face with a free block (not a line, as corner neighbours)
        if b.fixed and k in touching:
            m = gf.Mesh("empty", 3)
            m.add_convex(gf.GeoTrans("GT_PK(3,1)"), convex_points(meshes[k].nodes, meshes[k].tets[:, :4]))
            m.set_region(SLAVE, m.outer_faces())
            mfu = gf.MeshFem(m, 3)
            mfu.set_classical_fem(1)
            mim = gf.MeshIm(m, 2)
            md.add_fem_variable(f"u{k}", mfu)  # clamped on its whole surface: it does not move
            md.add_isotropic_linearized_elasticity_brick(mim, f"u{k}", "lambda", "mu")
            md.add_Dirichlet_condition_with_simplification(f"u{k}", SLAVE)
            md.add_fem_data(f"w{k}", mfu)  # its previous displacement, 0: friction's slip is u - w
            masters.append((m, SLAVE))
            parts[k] = (m, mfu, mim, f"u{k}", f"w{k}", None)  # GetFEM's objects live while Python holds them
    md.define_variable_group(U_ALL, *[p[3] for p in parts.values()])
    md.define_variable_group(W_ALL, *[p[4] for p in parts.values()])
    for m, region in masters:
        md.add_master_contact_boundary_to_raytracing_transformation(RAY, m, U_ALL, region)
    for m, mim, u, w, multiplier in slaves:
        md.add_slave_contact_boundary_to_raytracing_transformation(RAY, m, U_ALL, SLAVE)
        md.add_nonlinear_term(mim, contact_terms(u, w, multiplier), SLAVE)

    m, mfu, mim, u, _, _ = parts[loaded]
    top = blocks[loaded].vertices[:, 2].max()
    faces = m.outer_faces_with_direction([0.0, 0.0, 1.0], 0.01)
    middle = face_centres(m, faces)
    on_patch = (np.abs(middle[:, 2] - top) < 1e-6 * h) & (np.hypot(*(middle[:, :2] - centre[:2]).T) <= radius)
    if not on_patch.any():
        raise SystemExit("getfem_case: no element face on the punch patch: refine the mesh or widen the punch")
    m.set_region(PATCH, faces[:, on_patch])
    md.add_initialized_data("pressed", [0.0, 0.0, 0.0])
    punch = md.mult_varname_Dirichlet(md.add_Dirichlet_condition_with_multipliers(mim, u, mfu, PATCH, "pressed"))
    volumes = {k: gf.asm_generic(parts[k][2], 0, "1", -1, md) for k in free}

    def sinking(k):  # block k's mean downward displacement (of its part: the whole's, by symmetry)
        return -gf.asm_generic(parts[k][2], 0, f"{parts[k][3]}(3)", -1, md) / volumes[k]

    def tilt(k, i, j):  # block k's mean rotation (degrees) from axis i towards axis j (1-based): the
        # skew part of its deformation gradient, sin of the angle for a rigid rotation
        u = parts[k][3]
        skew = gf.asm_generic(parts[k][2], 0, f"(Grad_{u}({j},{i})-Grad_{u}({i},{j}))/2", -1, md) / volumes[k]
        return np.degrees(np.arcsin(np.clip(skew, -1, 1)))

    def solve(end: float) -> bool:
        """Newton from the converged state to the patch's displacement `end`; where it fails, the
        state is restored. After a converged step friction's reference (w) and the tractions'
        history move to the state reached."""
        saved = md.from_variables()
        md.set_variable("pressed", [0.0, 0.0, -end])
        try:
            converged = md.solve(*(["noisy"] if args.newton_log else []), "max_res", 1e-8, "max_iter", 80,
                                 "lsearch", "simplest", "lsolver", "mumps")[1]
        except RuntimeError:  # GetFEM raises where Newton diverges or the tangent is singular
            converged = False
        if not converged:
            md.to_variables(saved)
            return False
        for k in free:
            m, mfu, mim, u, w, multiplier = parts[k]
            md.set_variable(w, md.variable(u))
            if multiplier:
                store_last(md, mfu, SLAVE, multiplier)
        return True

    steps = 1  # sub-steps an increment takes: doubled where Newton fails, halved after an increment without

    def reach(start: float, end: float) -> bool:
        """From the converged state at the patch's displacement `start` to `end` in `steps` equal
        sub-steps, their number doubled (at most to 16) wherever one does not converge, so that a
        hard stretch (contacts switching between stick and slip on several blocks at once) is not
        tried again at full length increment after increment."""
        nonlocal steps
        position, failed = start, False
        while position < end:
            target = min(end, position + (end - start) / steps)
            if solve(target):
                position = end if end - target < 1e-9 * (end - start) else target
            elif steps < MOST_SUBSTEPS:
                steps, failed = 2 * steps, True
            else:
                return False
        if not failed:
            steps = max(1, steps // 2)
        return True

    def write_summary(rows, status):
        peak = max(rows, key=lambda r: r[1]) if rows else (0.0, 0.0, 0.0)
        summary = {"solver": "GetFEM",
                   "contact": "integral large sliding contact (raytracing, augmented Lagrangian)",
                   "faces_k_n_MPa_per_mm": 1.0 / compliance if compliance else None,  # None: rigid faces
                   "large_displacements": args.large_displacements,
                   "sessions": [{"after_increment": k, "augmentation": a} for k, a in sessions],
                   "youngs_modulus_Pa": args.youngs_modulus, "block_stiffness": args.block_stiffness,
                   "neighbour_stiffness": args.neighbour_stiffness,
                   "poisson": args.poisson, "friction": args.friction,
                   "element_size_mm": size, "punch_radius_mm": radius, "deflection_mm": deflection,
                   "mirror_planes": ["xy"[a] for a in axes], "increments": args.increments,
                   "converged_increments": len(rows), "status": status, "free_blocks": len(free),
                   "nodes": int(sum(len(meshes[k].nodes) for k in free)), "P_max_N": peak[1],
                   "delta_at_P_max_mm": peak[0], "block_displacement_at_P_max_mm": peak[2],
                   "seconds": earlier + time.time() - start}
        (out / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
        return peak

    data_names = [p[4] for p in parts.values()] + [f"{p[5]}_last" for p in parts.values() if p[5]]
    done, curve_lines, block_lines, earlier, sessions = 0, [], [], 0.0, []  # earlier: the resumed runs' seconds
    if state is not None:
        done, steps, curve_lines, block_lines, earlier, sessions = restore_state(state, md, data_names)
        md.set_variable("pressed", [0.0, 0.0, -deflection * done / args.increments])
        print(f"getfem_case: resuming after increment {done} ({state_file})", flush=True)
    sessions.append((done, args.augmentation))
    rows = [tuple(float(x) for x in line.split(",")[:3]) for line in curve_lines]
    status = "reached the deflection"
    curve = open(out / "curve.csv", "w")  # written as it goes: a stopped run keeps its increments
    curve.write("delta_mm,load_N,block_displacement_mm,support_N\n" + "".join(curve_lines))
    sinks = open(out / "blocks.csv", "w")  # every free block's delta_b, to compare the neighbours' motion
    sinks.write("delta_mm," + ",".join(blocks[k].name for k in free) + "," +
                ",".join(f"{blocks[k].name}_tilt_{axis}_deg" for k in free for axis in "xyz") + "\n" +
                "".join(block_lines))
    stepping = time.time()
    for step in range(done + 1, args.increments + 1):
        delta = deflection * step / args.increments
        if not reach(deflection * (step - 1) / args.increments, delta):
            status = (f"stopped at increment {step}: Newton did not converge, the increment cut into "
                      f"{MOST_SUBSTEPS} sub-steps")
            break
        # the load: the punch's reaction; its check, the support: the vertical force the free blocks
        # put on the fixed ones (equal where the faces against fixed blocks touch nothing else)
        load = share * gf.asm_generic(mim, 0, f"{punch}(3)", PATCH, md)
        support = share * sum(gf.asm_generic(parts[k][2], 0, f"{parts[k][5]}(3)", AGAINST_FIXED, md)
                              for k in free if parts[k][5])
        sunk = {k: sinking(k) for k in free}
        sink = sunk[loaded]
        rows.append((delta, load, sink))
        curve_lines.append(f"{delta:.9g},{load:.9g},{sink:.9g},{support:.9g}\n")
        curve.write(curve_lines[-1])
        curve.flush()
        tilts = [tilt(k, i, j) for k in free for i, j in ((2, 3), (3, 1), (1, 2))]  # about x, y, z
        block_lines.append(f"{delta:.9g}," + ",".join(f"{sunk[k]:.9g}" for k in free) + "," +
                           ",".join(f"{t:.6g}" for t in tilts) + "\n")
        sinks.write(block_lines[-1])
        sinks.flush()
        save_state(state_file, md, data_names, step, steps, curve_lines, block_lines, options,
                   earlier + time.time() - start, sessions)
        write_summary(rows, f"running: {step} of {args.increments} increments")
        left = (time.time() - stepping) / (step - done) * (args.increments - step)
        print(f"  increment {step}/{args.increments}: delta {delta:.4f} mm, load {load:.2f} N, "
              f"block {sink:.4f} mm (about {left / 60:.0f} min left)", flush=True)

    curve.close()
    sinks.close()
    peak = write_summary(rows, status)
    print(f"getfem_case: {status}; P_max {peak[1]:.1f} N at delta_b {peak[2]:.3f} mm; {out}")
    return 0 if rows else 1


if __name__ == "__main__":
    sys.exit(main())
