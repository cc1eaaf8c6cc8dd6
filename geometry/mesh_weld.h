#pragma once
#include "geometry/triangle_mesh.h"

#include <cstddef>

namespace tessera {

struct WeldReport {
  std::size_t mergedVertices = 0;      ///< vertices merged into an earlier one
  std::size_t collapsedTriangles = 0;  ///< triangles dropped because two corners merged
};

/// Merges vertices closer than `tolerance` (m) into the first of them, drops triangles that
/// collapse, and removes unreferenced vertices. STL facets do not share vertices, so every
/// STL import needs this. Deterministic: the result depends only on the input order.
WeldReport weldVertices(TriangleMesh& mesh, double tolerance);

}  // namespace tessera
