#pragma once
#include "geometry/triangle_mesh.h"

#include <optional>
#include <vector>

namespace tessera {

/// A face plane n . x = d of a polyhedron, n the unit outward normal (m for d).
struct FacePlane {
  Eigen::Vector3d normal;
  double offset;
};

/// If the closed mesh is a convex polyhedron with at most `maxPlanes` distinct face planes, those
/// planes; otherwise nothing. Then phi(x) = max_f (n_f . x - d_f) is the exact signed distance
/// everywhere inside and a positive lower bound of it outside: an analytic level set.
/// Triangles within 1e-9 (relative to the mesh size) of each other's plane share one.
std::optional<std::vector<FacePlane>> convexPolyhedronPlanes(const TriangleMesh& mesh, int maxPlanes = 64);

}  // namespace tessera
