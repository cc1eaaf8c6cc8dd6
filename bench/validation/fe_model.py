"""A finite-element model of a Tessera slab, solved by CalculiX.

Each block of a bundle becomes an elastic solid of quadratic tetrahedra (C3D10, meshed by gmsh);
every pair of faces two blocks share becomes a surface-to-surface penalty contact with Coulomb
friction; fixed blocks have every node clamped (Tessera's fixed blocks never move); the loaded
block's top is pressed down by a prescribed displacement on a round patch at its centre. CalculiX's
static nonlinear solver (ccx 2.20) runs it and the reaction on the patch gives the load-deflection
curve. A slab that is its own mirror image about vertical planes through the loaded block's centre
can be modelled by its half or quarter (mirror_part, symmetry_constraints). Units inside the
model: mm, N, MPa.

Used by run_case.py (one slab) and by tests/validation (a prism pressed on a prism, against the
closed form). Needs Debian's python3-gmsh, python3-h5py, python3-numpy and calculix-ccx.
"""
from __future__ import annotations

import dataclasses
import os
import re
import subprocess
from pathlib import Path

import numpy as np

MM_PER_M = 1000.0


@dataclasses.dataclass
class Block:
    name: str
    fixed: bool
    vertices: np.ndarray   # V x 3, mm, world frame
    triangles: np.ndarray  # T x 3, counter-clockwise seen from outside


def rotation(q: np.ndarray) -> np.ndarray:
    """Rotation matrix of a unit quaternion (w, x, y, z)."""
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def read_bundle(path: str | Path) -> list[Block]:
    """The placed blocks of a tessera-bundle (docs/bundle.md), meshes in world millimetres."""
    import h5py
    with h5py.File(Path(path) / "bundle.h5", "r") as f:
        shapes = {}
        for group in f["shapes"].values():
            shapes[int(group.attrs["index"])] = (group["mesh/vertices"][()], group["mesh/triangles"][()])
        bodies = f["bodies"]
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in bodies["names"][()]]
        blocks = []
        for i, name in enumerate(names):
            vertices, triangles = shapes[int(bodies["shape"][i])]
            world = vertices @ rotation(bodies["orientation"][i]).T + bodies["position"][i]
            blocks.append(Block(name, bool(bodies["fixed"][i]), world * MM_PER_M, triangles.astype(int)))
    return blocks


def span(path: str | Path) -> tuple[int, float]:
    """The bundle's free span: its interfaces M and length L (mm), from which Tessera's span rule
    takes k_n = E M / L (docs/bundle.md)."""
    import h5py
    with h5py.File(Path(path) / "bundle.h5", "r") as f:
        attrs = f["bodies"].attrs
        interfaces, length = int(attrs.get("span_interfaces", 0)), float(attrs.get("span_length", 0.0))
        if interfaces <= 0 or length <= 0:
            raise ValueError(f"{path}: the bundle stores no span (span_interfaces {interfaces}, span_length "
                             f"{length} m): give it one (tessera assemble --span-length --span-interfaces) "
                             "or use rigid faces")
        return interfaces, length * MM_PER_M


def box(name: str, lo, hi, fixed: bool = False) -> Block:
    """An axis-aligned box [lo, hi] (mm) as a closed triangle mesh."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    corners = np.array([[hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]]
                        for i in range(8)])
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    triangles = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return Block(name, fixed, corners, np.array(triangles))


def slab_size(blocks: list[Block]) -> float:
    """The slab's largest extent, mm: the scale of its tolerances."""
    return float(np.ptp(np.vstack([b.vertices for b in blocks]), axis=0).max())


# --- faces --------------------------------------------------------------------------------------

@dataclasses.dataclass
class Face:
    normal: np.ndarray  # outward unit normal
    offset: float       # normal . x on the face, mm
    loop: list[int]     # vertex indices around the face, counter-clockwise seen from outside


def planar_faces(block: Block, tolerance: float = 1e-6) -> list[Face]:
    """The block's planar faces: coplanar triangles merged, each face's boundary as one loop.

    Tessera's exact-plane blocks are convex polyhedra whose faces are flat; a face made of several
    loops (a face with a hole) is refused."""
    v, size = block.vertices, np.ptp(block.vertices, axis=0).max()
    groups: list[tuple[np.ndarray, float, list[int]]] = []
    for t, (a, b, c) in enumerate(block.triangles):
        n = np.cross(v[b] - v[a], v[c] - v[a])
        n /= np.linalg.norm(n)
        d = float(n @ v[a])
        for g in groups:
            if np.linalg.norm(g[0] - n) < tolerance * 100 and abs(g[1] - d) < tolerance * size:
                g[2].append(t)
                break
        else:
            groups.append((n, d, [t]))
    faces = []
    for n, d, members in groups:
        edges: dict[tuple[int, int], int] = {}
        for t in members:
            tri = block.triangles[t]
            for k in range(3):
                a, b = int(tri[k]), int(tri[(k + 1) % 3])
                if (b, a) in edges:
                    del edges[(b, a)]
                else:
                    edges[(a, b)] = 1
        following = dict(edges.keys())
        if len(following) != len(edges):
            raise ValueError(f"block {block.name}: a face's boundary is not a simple loop")
        start = next(iter(following))
        loop = [start]
        while following[loop[-1]] != start:
            loop.append(following[loop[-1]])
        if len(loop) != len(edges):
            raise ValueError(f"block {block.name}: a face has more than one boundary loop (a hole)")
        faces.append(Face(n, d, loop))
    return faces


# --- meshing ------------------------------------------------------------------------------------

@dataclasses.dataclass
class BlockMesh:
    nodes: np.ndarray                 # N x 3, mm
    tets: np.ndarray                  # E x 10, 0-based indices into nodes, CalculiX C3D10 order
    face_elements: list[list[tuple[int, int]]]  # per Face: (element index, CalculiX face 1..4)


# CalculiX's C3D10 faces by corner (0-based): face 1 = 1-2-3, 2 = 1-4-2, 3 = 2-4-3, 4 = 3-4-1.
TET_FACES = ((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0))


def mesh_block(block: Block, faces: list[Face], size: float) -> BlockMesh:
    """Quadratic tetrahedra of element size `size` (mm) filling the block, by gmsh."""
    import gmsh
    gmsh.model.add(block.name)
    geo = gmsh.model.geo
    points = {i: geo.addPoint(*block.vertices[i], size) for f in faces for i in f.loop}
    lines: dict[tuple[int, int], int] = {}
    surfaces = []
    for f in faces:
        curves = []
        for k, a in enumerate(f.loop):
            b = f.loop[(k + 1) % len(f.loop)]
            if (b, a) in lines:
                curves.append(-lines[(b, a)])
            else:
                lines[(a, b)] = geo.addLine(points[a], points[b])
                curves.append(lines[(a, b)])
        surfaces.append(geo.addPlaneSurface([geo.addCurveLoop(curves)]))
    geo.addVolume([geo.addSurfaceLoop(surfaces)])
    geo.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.setOrder(2)

    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = {int(t): i for i, t in enumerate(tags)}
    nodes = coords.reshape(-1, 3)
    _, tet_nodes = gmsh.model.mesh.getElementsByType(11)  # 10-node tetrahedra
    tets = np.vectorize(index.get)(tet_nodes.reshape(-1, 10).astype(int))
    # gmsh's second-order nodes: edges 01, 12, 20, 30, 32, 31; CalculiX's: 01, 12, 20, 03, 13, 23.
    tets = tets[:, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]]
    a, b, c, d = (nodes[tets[:, k]] for k in range(4))
    flipped = np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a) < 0
    tets[flipped] = tets[flipped][:, [0, 2, 1, 3, 6, 5, 4, 7, 9, 8]]
    corner_faces = {}
    for e, tet in enumerate(tets):
        for k, (i, j, m) in enumerate(TET_FACES):
            corner_faces.setdefault(frozenset((tet[i], tet[j], tet[m])), []).append((e, k + 1))
    face_elements = []
    for s in surfaces:
        _, tri_nodes = gmsh.model.mesh.getElementsByType(9, s)  # 6-node triangles on surface s
        corners = np.vectorize(index.get)(tri_nodes.reshape(-1, 6)[:, :3].astype(int))
        face_elements.append([corner_faces[frozenset(t)][0] for t in corners])
    gmsh.model.remove()
    return BlockMesh(nodes, tets, face_elements)


# --- contacts -----------------------------------------------------------------------------------

def shared_faces(blocks, faces, tolerance: float) -> list[tuple[int, int, int, int]]:
    """(block a, face i of a, block b, face j of b) for every two faces on one plane, facing each
    other, whose polygons overlap with positive area (tolerance: mm); none between two fixed blocks."""
    pairs = []
    for a in range(len(blocks)):
        for b in range(a + 1, len(blocks)):
            if blocks[a].fixed and blocks[b].fixed:
                continue
            for i, fa in enumerate(faces[a]):
                for j, fb in enumerate(faces[b]):
                    if fa.normal @ fb.normal > -1 + 1e-9 or abs(fa.offset + fb.offset) > tolerance:
                        continue
                    if overlap_area(blocks[a].vertices[fa.loop], blocks[b].vertices[fb.loop],
                                    fa.normal) > tolerance ** 2:
                        pairs.append((a, i, b, j))
    return pairs


def polygon_area(poly) -> float:
    """Signed area of a 2-D polygon (positive counter-clockwise)."""
    return 0.5 * sum(poly[k - 1][0] * poly[k][1] - poly[k][0] * poly[k - 1][1] for k in range(len(poly)))


def overlap_area(p: np.ndarray, q: np.ndarray, normal: np.ndarray) -> float:
    """Area common to two convex coplanar polygons (Sutherland-Hodgman clipping in their plane)."""
    u = np.cross(normal, [1.0, 0, 0] if abs(normal[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    w = np.cross(normal, u)
    P = [np.array([x @ u, x @ w]) for x in p]
    Q = [np.array([x @ u, x @ w]) for x in q]
    if polygon_area(P) < 0:
        P.reverse()
    if polygon_area(Q) < 0:
        Q.reverse()
    out = P
    for k in range(len(Q)):
        a, b = Q[k - 1], Q[k]
        edge = b - a
        inside = [edge[0] * (x[1] - a[1]) - edge[1] * (x[0] - a[0]) >= 0 for x in out]
        clipped = []
        for m in range(len(out)):
            x, y = out[m - 1], out[m]
            ix, iy = inside[m - 1], inside[m]
            if ix != iy:
                d = y - x
                s = (edge[0] * (a[1] - x[1]) - edge[1] * (a[0] - x[0])) / (edge[0] * d[1] - edge[1] * d[0])
                clipped.append(x + s * d)
            if iy:
                clipped.append(y)
        out = clipped
        if len(out) < 3:
            return 0.0
    return abs(polygon_area(out))


# --- the CalculiX input --------------------------------------------------------------------------

# CalculiX's contact pair types by the names the scripts take (--contact).
CONTACT_TYPES = {"surface": "SURFACE TO SURFACE", "mortar": "MORTAR"}


@dataclasses.dataclass
class Model:
    """Material, contact and load of one FE run (mm, N, MPa)."""
    youngs_modulus: float = 4200.0     # MPa
    poisson: float = 0.2
    friction: float = 0.23             # Coulomb coefficient; 0: frictionless
    penalty_factor: float = 50.0       # contact slope K = factor * E / element size (MPa/mm)
    slope: float = 0.0                 # MPa/mm: the contact slope itself, if above 0 (penalty_factor unused)
    block_stiffness: float = 1.0       # the blocks' modulus is E x this (the contact slope keeps E's)
    stick_factor: float = 0.1          # stick slope = factor * K
    increments: int = 20               # the step in this many increments (more where ccx cuts them)
    element_size: float = 1.0          # mm
    contact: str = "surface"           # a key of CONTACT_TYPES
    large_displacements: bool = False  # NLGEOM: the equations on the deformed geometry

    def contact_slope(self) -> float:
        """Penalty slope of the contact pressure against overclosure, MPa/mm."""
        if self.slope > 0:
            return self.slope
        return self.penalty_factor * self.youngs_modulus / self.element_size


@dataclasses.dataclass
class Mesh:
    """The meshed blocks with global node and element numbers (1-based, as CalculiX's)."""
    blocks: list[Block]
    faces: list[list[Face]]
    meshes: list[BlockMesh]
    node_offset: list[int]
    element_offset: list[int]
    pairs: list[tuple[int, int, int, int]]

    def node_ids(self, k: int, select: np.ndarray) -> list[int]:
        """Global ids of block k's nodes where select (a mask over its nodes) holds."""
        return [self.node_offset[k] + i + 1 for i in np.flatnonzero(select)]

    def nodes_at(self, k: int, axis: int, value: float) -> list[int]:
        """Global ids of block k's nodes whose coordinate `axis` is `value` (mm, to 1e-9)."""
        return self.node_ids(k, np.abs(self.meshes[k].nodes[:, axis] - value) < 1e-9)


def mesh_blocks(blocks: list[Block], element_size: float) -> Mesh:
    """Every block meshed at element_size (mm), fixed ones too (meshed twice as coarse, they gave
    the 3 x 3 slab the same K to 4 digits: docs/validation.md; uniform is the simpler model)."""
    import gmsh
    gmsh.initialize(["-nt", "1"])
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        faces = [planar_faces(b) for b in blocks]
        meshes = [mesh_block(b, f, element_size) for b, f in zip(blocks, faces)]
    finally:
        gmsh.finalize()
    size = slab_size(blocks)
    counts = np.cumsum([0] + [len(m.nodes) for m in meshes])
    elements = np.cumsum([0] + [len(m.tets) for m in meshes])
    return Mesh(blocks, faces, meshes, list(counts[:-1]), list(elements[:-1]),
                shared_faces(blocks, faces, 1e-6 * size))


@dataclasses.dataclass
class Constraint:
    """Degrees of freedom first..last of a node set held at `value` (mm): in the model (held at 0)
    or in the loading step (reached at its end)."""
    name: str
    nodes: list[int]
    first: int
    last: int
    value: float = 0.0


def slab_supports(mesh: Mesh, loaded: int, punch_radius: float, deflection: float, centre: np.ndarray | None = None):
    """Tessera's supports: every node of a fixed block clamped; the loaded block pressed down on
    the nodes of its top face within punch_radius (mm) of its centre (`centre`, or its vertices'
    mean), held laterally (a punch that sticks). Returns (model constraints, step constraints)."""
    held = []
    for k, b in enumerate(mesh.blocks):
        if b.fixed:
            held += mesh.node_ids(k, np.ones(len(mesh.meshes[k].nodes), bool))
    nodes = mesh.meshes[loaded].nodes
    top = nodes[:, 2].max()
    centre = mesh.blocks[loaded].vertices.mean(axis=0) if centre is None else centre
    on_patch = (nodes[:, 2] > top - 1e-6 * np.ptp(nodes)) & \
               (np.hypot(nodes[:, 0] - centre[0], nodes[:, 1] - centre[1]) <= punch_radius)
    patch = mesh.node_ids(loaded, on_patch)
    if not patch:
        raise ValueError("no node on the punch patch: refine the mesh or widen the punch")
    return ([Constraint("CLAMPED", held, 1, 3)] if held else [],
            [Constraint("PATCH", patch, 1, 2), Constraint("PATCH", patch, 3, 3, -deflection)])


# --- mirror symmetry -----------------------------------------------------------------------------

def mirrored(blocks: list[Block], centre: np.ndarray, axis: int) -> bool:
    """Whether the slab is its own mirror image in the plane x_axis = centre[axis]: every block's
    vertices, mirrored, are those of a block with the same fixity (to 1e-6 of the slab)."""
    size = slab_size(blocks)

    def key(v):
        return np.array(sorted(map(tuple, np.round(v / (1e-6 * size)))))

    keys = [(b.fixed, key(b.vertices)) for b in blocks]
    for b in blocks:
        m = b.vertices.copy()
        m[:, axis] = 2 * centre[axis] - m[:, axis]
        km = key(m)
        if not any(f == b.fixed and len(k) == len(km) and np.abs(k - km).max() <= 1 for f, k in keys):
            return False
    return True


def clipped(block: Block, cuts: list[tuple[np.ndarray, float]]) -> Block | None:
    """The convex block cut by the half-spaces n . x <= d of `cuts`, as a triangle mesh (each face a
    fan, outward); None where nothing of it is left. Its vertices are the points where three of its
    planes meet inside every other one."""
    planes = [(f.normal, f.offset) for f in planar_faces(block)] + list(cuts)
    size = np.ptp(block.vertices, axis=0).max()
    tolerance = 1e-9 * size
    points = []
    for i in range(len(planes)):
        for j in range(i + 1, len(planes)):
            for k in range(j + 1, len(planes)):
                A = np.array([planes[i][0], planes[j][0], planes[k][0]])
                if abs(np.linalg.det(A)) < 1e-9:
                    continue
                x = np.linalg.solve(A, [planes[i][1], planes[j][1], planes[k][1]])
                if all(n @ x <= d + tolerance for n, d in planes) and \
                        not any(np.linalg.norm(x - p) <= tolerance for p in points):
                    points.append(x)
    if len(points) < 4:
        return None
    vertices = np.array(points)
    centroid = vertices.mean(axis=0)
    if np.linalg.svd(vertices - centroid, compute_uv=False)[-1] <= tolerance:
        return None  # flat: the cut leaves a face, not a solid
    triangles = []
    for n, d in planes:
        on = [v for v in range(len(vertices)) if abs(n @ vertices[v] - d) <= tolerance]
        if len(on) < 3:
            continue
        middle = vertices[on].mean(axis=0)
        u = vertices[on[0]] - middle
        u /= np.linalg.norm(u)
        w = np.cross(n, u)
        on.sort(key=lambda v: np.arctan2((vertices[v] - middle) @ w, (vertices[v] - middle) @ u))
        triangles += [(on[0], on[m], on[m + 1]) for m in range(1, len(on) - 1)]  # counter-clockwise about n
    return Block(block.name, block.fixed, vertices, np.array(triangles))


def mirror_part(blocks: list[Block], centre: np.ndarray) -> tuple[list[Block], list[int]]:
    """The part x_a >= centre_a of the slab for each axis a (0: x, 1: y) about whose vertical plane
    through `centre` the slab is its own mirror image (mirrored): the blocks across those planes
    cut. Returns the part and those axes; ValueError for a slab with neither plane."""
    axes = [axis for axis in (0, 1) if mirrored(blocks, centre, axis)]
    if not axes:
        raise ValueError(f"the slab is not its mirror image about x = {centre[0]:.6g} mm nor y = {centre[1]:.6g} mm: "
                         "no symmetric part to model (run it whole)")
    cuts = [(-np.eye(3)[axis], -centre[axis]) for axis in axes]
    return [c for c in (clipped(b, cuts) for b in blocks) if c is not None], axes


def on_mirror_plane(mesh: Mesh, k: int, centre: np.ndarray, axis: int) -> np.ndarray:
    """Which of block k's nodes lie on the plane x_axis = centre[axis] (to 1e-6 of the slab)."""
    return np.abs(mesh.meshes[k].nodes[:, axis] - centre[axis]) <= 1e-6 * slab_size(mesh.blocks)


def symmetry_weights(mesh: Mesh, centre: np.ndarray, axes: list[int]) -> dict[int, float]:
    """Node id -> 1/2 per mirror plane (mirror_part's axes) the node lies on: the whole slab's mean
    over a block's nodes is the part's mean with these weights (a node on a plane is one node of the
    whole slab, every other one of the part stands for 2 or 4)."""
    weights = {}
    for k, m in enumerate(mesh.meshes):
        planes = np.zeros(len(m.nodes), int)
        for axis in axes:
            planes += on_mirror_plane(mesh, k, centre, axis)
        for i in np.flatnonzero(planes):
            weights[mesh.node_offset[k] + int(i) + 1] = 0.5 ** int(planes[i])
    return weights


def symmetry_constraints(mesh: Mesh, centre: np.ndarray, axes: list[int]) -> list[Constraint]:
    """The symmetric part's planes (mirror_part's axes): nodes on x_a = centre_a held in x_a."""
    held = []
    for axis in axes:
        ids = []
        for k in range(len(mesh.meshes)):
            ids += mesh.node_ids(k, on_mirror_plane(mesh, k, centre, axis))
        if ids:
            held.append(Constraint("SYM" + "XY"[axis], ids, axis + 1, axis + 1))
    return held


def write_input(path: Path, mesh: Mesh, model: Model, held: list[Constraint],
                pressed: list[Constraint], watch: list[int] | None = None) -> None:
    """The CalculiX input: mesh, material, contacts, `held` constraints, one static step that
    reaches the `pressed` values; per increment, the total reaction on the set of pressed[0] and
    the displacements of the `watch` nodes (set WATCH)."""
    blocks, meshes = mesh.blocks, mesh.meshes
    lines = ["*HEADING", f"Tessera FE reference: {len(blocks)} blocks, {len(mesh.pairs)} contact pairs",
             "*NODE, NSET=NALL"]
    for m, o in zip(meshes, mesh.node_offset):
        lines += [f"{o + i + 1}, {x:.12g}, {y:.12g}, {z:.12g}" for i, (x, y, z) in enumerate(m.nodes)]
    for k, (m, no, eo) in enumerate(zip(meshes, mesh.node_offset, mesh.element_offset)):
        lines.append(f"*ELEMENT, TYPE=C3D10, ELSET=B{k}")
        lines += [f"{eo + i + 1}, " + ", ".join(str(no + v + 1) for v in tet) for i, tet in enumerate(m.tets)]
    lines += ["*ELSET, ELSET=EALL"] + [f"B{k}" for k in range(len(blocks))]
    lines += ["*MATERIAL, NAME=BLOCK", "*ELASTIC", f"{model.youngs_modulus * model.block_stiffness:.12g}, {model.poisson:.12g}",
              "*SOLID SECTION, ELSET=EALL, MATERIAL=BLOCK"]

    def surface(k, i):
        name = f"S{k}_{i}"
        lines.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        lines.extend(f"{mesh.element_offset[k] + el + 1}, S{side}" for el, side in meshes[k].face_elements[i])
        return name

    lines += ["*SURFACE INTERACTION, NAME=BLOCKS", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
              f"{model.contact_slope():.12g}"]
    if model.friction > 0:
        lines += ["*FRICTION", f"{model.friction:.12g}, {model.stick_factor * model.contact_slope():.12g}"]
    for a, i, b, j in mesh.pairs:
        # The slave side: a free block's face (a clamped block cannot follow the master's nodes).
        slave, master = ((a, i), (b, j)) if not blocks[a].fixed else ((b, j), (a, i))
        s, m = surface(*slave), surface(*master)
        lines += [f"*CONTACT PAIR, INTERACTION=BLOCKS, TYPE={CONTACT_TYPES[model.contact]}", f"{s}, {m}"]

    sets = {c.name: c.nodes for c in held + pressed}
    if watch:
        sets["WATCH"] = watch
    for name, ids in sets.items():
        lines.append(f"*NSET, NSET={name}")
        lines += [", ".join(map(str, ids[k:k + 16])) for k in range(0, len(ids), 16)]
    if held:
        lines += ["*BOUNDARY"] + [f"{c.name}, {c.first}, {c.last}" for c in held]
    # The step lasts `increments` (time units), in increments of 1 at most: the pressed values are
    # reached at its end, step time t gives t / increments of them (whole numbers, exact in ccx's input).
    nlgeom = "NLGEOM" if model.large_displacements else "NLGEOM=NO"
    lines += [f"*STEP, {nlgeom}, INC=10000", "*STATIC", f"1.0, {model.increments}, 1e-4, 1.0", "*BOUNDARY"]
    lines += [f"{c.name}, {c.first}, {c.last}, {c.value:.12g}" for c in pressed]
    lines += [f"*NODE PRINT, NSET={pressed[0].name}, TOTALS=ONLY", "RF"]
    if watch:
        lines += ["*NODE PRINT, NSET=WATCH", "U"]
    lines.append("*END STEP")
    path.write_text("\n".join(lines) + "\n")


def run_ccx(path: Path, threads: int = 2) -> str:
    """Runs CalculiX on path (a .inp), its output in path.log. Returns "" when the job finished,
    else the reason it stopped (the last lines of its output): a static step past a limit load
    stops where its increments fall below the minimum, and the increments before stand."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), CCX_NPROC_EQUATION_SOLVER=str(threads))
    result = subprocess.run(["ccx", "-i", path.with_suffix("").name], cwd=path.parent, env=env,
                            capture_output=True, text=True)
    output = result.stdout + result.stderr
    path.with_suffix(".log").write_text(output)
    if result.returncode == 0 and "Job finished" in output:
        return ""
    return " / ".join(line.strip() for line in output.strip().splitlines()[-4:] if line.strip())


def read_dat(dat: Path) -> list[tuple[str, str, float, np.ndarray]]:
    """The printed blocks of a CalculiX .dat file, one per *NODE PRINT per converged increment:
    (what, e.g. "total force (fx,fy,fz)", node set, step time, rows as written: a node's rows
    begin with its number, a total's do not)."""
    blocks = []
    for line in dat.read_text().splitlines():
        m = re.search(r"^\s*(\S.*?) for set (\S+) and time\s+(\S+)", line)
        if m:
            blocks.append((m.group(1), m.group(2), float(m.group(3)), []))
        elif blocks and line.strip():
            blocks[-1][3].append([float(x) for x in line.split()])
    return [(what, name, time, np.array(rows)) for what, name, time, rows in blocks]


def totals(blocks) -> list[tuple[float, np.ndarray]]:
    """(step time, total reaction force N on the pressed set) per converged increment (read_dat's blocks)."""
    return [(time, rows[0]) for what, _, time, rows in blocks if what.startswith("total force")]


def mean_displacements(blocks, weights: dict[int, float] | None = None) -> dict[float, np.ndarray]:
    """Step time -> mean displacement mm of the WATCH nodes, per converged increment (read_dat's
    blocks), each node weighted by weights[its id] (default 1: symmetry_weights for a mirror part)."""
    means = {}
    for what, name, time, rows in blocks:
        if what.startswith("displacements") and name == "WATCH":
            w = np.array([1.0 if weights is None else weights.get(int(i), 1.0) for i in rows[:, 0]])
            means[time] = (w[:, None] * rows[:, 1:4]).sum(axis=0) / w.sum()
    return means
