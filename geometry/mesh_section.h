#pragma once
#include "geometry/triangle_mesh.h"

#include <Eigen/Core>

#include <utility>

namespace tessera {

/// m^2: the area of a closed, outward-oriented mesh's cross-section by the plane normal . x = offset
/// (normal a unit vector). Each triangle the plane crosses leaves a segment of the section's
/// boundary; oriented along normal x n_t (n_t the triangle's outward normal) the segments run
/// counter-clockwise about `normal`, and the shoelace formula over them, in any order,
///     A = 1/2 sum normal . (p x q)
/// is the area of the section's loops together (a non-convex mesh may give several). Vertices
/// exactly on the plane count as above it: a face lying in the plane is the section when the
/// solid is below the plane, and there is none when the solid is above it.
/// Header-only: the kernel (solver/) uses it and links no geometry code.
inline double sectionArea(const TriangleMesh& mesh, const Eigen::Vector3d& normal, double offset) {
  double twiceArea = 0.0;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    Eigen::Vector3d corner[3];
    double height[3];
    int below = 0;
    for (int k = 0; k < 3; ++k) {
      corner[k] = triangleCorner(mesh, t, k);
      height[k] = normal.dot(corner[k]) - offset;
      below += height[k] < 0;
    }
    if (below == 0 || below == 3) continue;
    // The two edges with one end below and one not: where each crosses the plane.
    Eigen::Vector3d ends[2];
    int found = 0;
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      if ((height[k] < 0) == (height[l] < 0)) continue;
      const double s = height[k] / (height[k] - height[l]);
      ends[found++] = corner[k] + s * (corner[l] - corner[k]);
    }
    const Eigen::Vector3d tangent = normal.cross(triangleAreaVector(mesh, t));
    if ((ends[1] - ends[0]).dot(tangent) < 0) std::swap(ends[0], ends[1]);
    twiceArea += normal.dot(ends[0].cross(ends[1]));
  }
  return 0.5 * twiceArea;
}

}  // namespace tessera
