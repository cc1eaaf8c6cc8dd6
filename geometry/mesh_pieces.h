#pragma once
#include "geometry/triangle_mesh.h"

#include <vector>

namespace tessera {

/// The connected pieces of a mesh (triangles joined across edges that exactly two triangles share),
/// each with only its own vertices, in the order of their first triangle. A multi-object file or a
/// frame exported as one mesh becomes one piece per solid, also where solids meet along an edge.
std::vector<TriangleMesh> splitPieces(const TriangleMesh& mesh);

}  // namespace tessera
