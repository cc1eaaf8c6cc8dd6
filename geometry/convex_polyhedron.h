#pragma once
#include "geometry/convex_planes.h"
#include "geometry/triangle_mesh.h"

#include <vector>

namespace tessera {

/// The closed, outward-oriented mesh of the bounded convex polyhedron {x : n_i . x <= d_i for all
/// planes i}. Each plane's face is a large square in the plane clipped by every other half-space
/// (Sutherland & Hodgman, CACM 17, 1974); a plane whose face is empty or of zero area is not a face.
/// Corners within 1e-9 `size` of each other are one vertex; each face is a fan about its first
/// corner. `size` is the polyhedron's size (m): the polyhedron must lie within `size` of the
/// origin. Deterministic in the order of the planes. Throws InputError when the planes bound
/// fewer than four faces (empty, unbounded or flat).
TriangleMesh convexPolyhedronFromPlanes(const std::vector<FacePlane>& planes, double size);

}  // namespace tessera
