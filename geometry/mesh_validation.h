#pragma once
#include "geometry/triangle_mesh.h"

#include <string>

namespace tessera {

struct ValidationReport {
  bool reoriented = false;  ///< the mesh was consistently inward-facing and has been flipped
};

/// Checks that `mesh` is the closed surface of one solid and makes it outward-oriented.
/// Rules, in order (the first failure throws InputError naming `label`, the problem, a
/// location and the fix):
///  1. at least 4 triangles, no zero-area triangle;
///  2. closed: every edge is used by exactly two triangles (one: a hole; more: non-manifold edge);
///  3. orientation consistent: the two triangles of an edge traverse it in opposite directions;
///  4. manifold vertices: the triangles around each vertex form a single fan;
///  5. one connected piece;
///  6. bounds a volume: |signed volume| > 1e-9 x (bounding-box diagonal)^3;
///  7. no self-intersection (CGAL, exact predicates).
/// A consistently inverted mesh (negative volume) is flipped and reported, not refused.
ValidationReport validateSolidMesh(TriangleMesh& mesh, const std::string& label);

}  // namespace tessera
