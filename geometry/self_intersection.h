#pragma once
#include "geometry/triangle_mesh.h"

#include <utility>
#include <vector>

namespace tessera {

/// Pairs of triangles that intersect other than along a shared edge or vertex (CGAL,
/// exact predicates). A degenerate triangle is reported paired with itself.
/// Precondition: the mesh is a manifold (every edge used by two triangles, vertex fans single).
std::vector<std::pair<int, int>> findSelfIntersections(const TriangleMesh& mesh);

}  // namespace tessera
