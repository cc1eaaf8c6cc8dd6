# YADE's half of the side-by-side with Tessera (bench/peer_yade.sh runs both); the same scenes as
# bench/peer_tessera.cpp, built with YADE's LS-DEM (LevelSet bodies, Ig2_LevelSet_LevelSet_ScGeom).
#
#   yade -j THREADS -n -x bench/peer_yade.py step BUNDLE_DIR DT STEPS
#       the bundle's slab, every block 0.05 % closer to the centre, outer ring fixed, gravity, the
#       2.5 mm sphere (a LevelSet sphere: YADE 2023.02a has no sphere-LevelSet functor) 20 um into
#       the centre block: time per step. Each block's distance field is the
#       bundle's own grid (0.25 mm); YADE places the same number of surface nodes as the bundle has.
#   yade -n -x bench/peer_yade.py rest DT          10 x 10 x 3.18 mm box resting on a fixed one
#   yade -n -x bench/peer_yade.py incline DEG DT   the same on an incline of DEG degrees, mu = 0.23
# Prints one JSON object on the last line.
import json
import math
import os
import sys
import time

import h5py
import numpy

E, DENSITY, MU, DAMPING = 4.2e9, 2500.0, 0.23, 0.3
SIDE, THICKNESS = 10e-3, 3.18e-3


def engines(gravity):
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_LevelSet_Aabb()], verletDist=0),
        InteractionLoop([Ig2_LevelSet_LevelSet_ScGeom()],
                        [Ip2_FrictMat_FrictMat_FrictPhys()],
                        [Law2_ScGeom_FrictPhys_CundallStrack(sphericalBodies=False)]),
        NewtonIntegrator(damping=DAMPING, gravity=gravity),
    ]


def material():
    return O.materials.append(FrictMat(young=E, poisson=1.0, frictionAngle=math.atan(MU), density=DENSITY))


def step_timing(bundle_dir, dt, steps):
    mat = material()
    with h5py.File(bundle_dir + "/bundle.h5", "r") as f:
        shapes = {}
        for name, g in f["shapes"].items():
            sdf = g["sdf"]
            voxel = float(sdf.attrs["voxel_size"])
            values = numpy.asarray(sdf["values"], dtype=float)
            grid = RegularGrid(min=Vector3(*sdf["origin"][:]), nGP=Vector3i(*values.shape), spacing=voxel)
            shapes[int(g.attrs["index"])] = (grid, values.tolist(), len(g["nodes/positions"]))
        positions = f["bodies/position"][:]
        orientations = f["bodies/orientation"][:]
        fixed = f["bodies/fixed"][:]
        shape_of = f["bodies/shape"][:]
    for p, q, fx, s in zip(positions, orientations, fixed, shape_of):
        grid, field, nodes = shapes[int(s)]
        centre = Vector3(p[0] * (1 - 5e-4), p[1] * (1 - 5e-4), p[2])
        b = levelSetBody(grid=grid, distField=field, nSurfNodes=nodes, nodesPath=2, center=centre,
                         orientation=Quaternion(q[0], q[1], q[2], q[3]), dynamic=not bool(fx), material=mat)
        O.bodies.append(b)
    radius = 2.5e-3
    # YADE 2023.02a has no sphere-LevelSet functor: the indenter is a LevelSet sphere.
    O.bodies.append(levelSetBody("sphere", radius=radius, spacing=0.25e-3, nSurfNodes=shapes[0][2], nodesPath=2,
                                 center=(0, 0, THICKNESS / 2 + radius - 20e-6), dynamic=False, material=mat))
    engines((0, 0, -9.81))
    O.dt = dt
    O.run(100, True)
    start = time.time()
    O.run(steps, True)
    seconds = time.time() - start
    real = sum(1 for i in O.interactions if i.isReal)
    return {"code": "yade", "threads": O.numThreads, "us_per_step": 1e6 * seconds / steps,
            "real_interactions": real, "nodes_per_block": shapes[0][2], "bodies": len(O.bodies)}


def stacked_boxes(gravity, dt):
    mat = material()
    extents = (SIDE / 2, SIDE / 2, THICKNESS / 2)
    base = levelSetBody("box", extents=extents, spacing=0.25e-3, nSurfNodes=921, nodesPath=2,
                        dynamic=False, material=mat)
    top = levelSetBody("box", extents=extents, spacing=0.25e-3, nSurfNodes=921, nodesPath=2,
                       center=(0, 0, THICKNESS), material=mat)
    O.bodies.append([base, top])
    engines(gravity)
    O.dt = dt
    return base.id, top.id


def resting(dt):
    base, top = stacked_boxes((0, 0, -9.81), dt)
    weight = O.bodies[top].state.mass * 9.81
    steps = int(0.05 / dt)
    forces = []
    for i in range(steps):
        O.step()
        if i >= steps * 4 // 5:
            forces.append(-O.forces.f(base)[2])  # the fixed base carries the top block
    f = numpy.array(forces)
    return {"code": "yade", "check": "rest", "force_over_weight": float(f.mean() / weight),
            "spread_over_mean": float(f.std() / f.mean())}


def incline(degrees, dt):
    theta = math.radians(degrees)
    base, top = stacked_boxes((9.81 * math.sin(theta), 0, -9.81 * math.cos(theta)), dt)
    x0 = O.bodies[top].state.pos[0]
    O.run(int(0.05 / dt), True)
    return {"code": "yade", "check": "incline", "degrees": degrees, "slip_m": O.bodies[top].state.pos[0] - x0}


mode = sys.argv[1]
if mode == "step":
    result = step_timing(sys.argv[2], float(sys.argv[3]), int(sys.argv[4]))
elif mode == "rest":
    result = resting(float(sys.argv[2]))
else:
    result = incline(float(sys.argv[2]), float(sys.argv[3]))
print(json.dumps(result))
sys.stdout.flush()
os._exit(0)  # skip YADE's slow interpreter teardown; the result is printed
