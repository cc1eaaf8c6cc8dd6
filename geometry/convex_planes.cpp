#include "geometry/convex_planes.h"

#include <cmath>

namespace tessera {

std::optional<std::vector<FacePlane>> convexPolyhedronPlanes(const TriangleMesh& mesh, int maxPlanes) {
  const double size = boundingBox(mesh.vertices).diagonal().norm();
  const double tolerance = 1e-9 * size;
  std::vector<FacePlane> planes;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Eigen::Vector3d n = triangleAreaVector(mesh, t).normalized();
    const double d = n.dot(triangleCorner(mesh, t, 0));
    bool known = false;
    for (const FacePlane& p : planes)
      known = known || ((p.normal - n).norm() < 1e-9 && std::abs(p.offset - d) < tolerance);
    if (known) continue;
    if (static_cast<int>(planes.size()) == maxPlanes) return std::nullopt;
    planes.push_back({n, d});
  }
  // Convex: every vertex lies on or behind every face plane.
  for (const FacePlane& p : planes)
    for (const auto& v : mesh.vertices)
      if (p.normal.dot(v) - p.offset > tolerance) return std::nullopt;
  return planes;
}

}  // namespace tessera
