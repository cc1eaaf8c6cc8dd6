#include "geometry/convex_planes.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tessera {

namespace {

// A face being collected: its current plane and the area-weighted sums that fit it.
struct FaceCluster {
  FacePlane plane;
  Eigen::Vector3d areaNormal{0, 0, 0};  // sum of area x unit normal
  std::vector<int> triangles;
};

}  // namespace

std::optional<ConvexFit> fitConvexPolyhedron(const TriangleMesh& mesh, const ConvexFitOptions& options) {
  ConvexFit fit;
  fit.tolerance = options.relativeTolerance * boundingBox(mesh.vertices).diagonal().norm();
  const double cosLimit = std::cos(25.0 * M_PI / 180.0);

  // Largest triangles first: their normals are the least disturbed by rounding.
  std::vector<int> order(mesh.triangles.size());
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> area(order.size());
  for (int t : order) area[t] = 0.5 * triangleAreaVector(mesh, t).norm();
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] > area[b]; });

  std::vector<FaceCluster> faces;
  for (int t : order) {
    if (!(area[t] > 0)) continue;
    const Eigen::Vector3d n = triangleAreaVector(mesh, t).normalized();
    const Eigen::Vector3d c = (triangleCorner(mesh, t, 0) + triangleCorner(mesh, t, 1) + triangleCorner(mesh, t, 2)) / 3.0;
    FaceCluster* home = nullptr;
    for (FaceCluster& f : faces) {
      if (f.plane.normal.dot(n) < cosLimit) continue;
      bool onPlane = true;
      for (int k = 0; k < 3 && onPlane; ++k)
        onPlane = std::abs(f.plane.normal.dot(triangleCorner(mesh, t, k)) - f.plane.offset) <= fit.tolerance;
      if (onPlane) {
        home = &f;
        break;
      }
    }
    if (!home) {
      if (static_cast<int>(faces.size()) == std::min(options.maxPlanes, kMaxConvexPlanes)) return std::nullopt;
      faces.push_back({{n, n.dot(c)}, {0, 0, 0}, {}});
      home = &faces.back();
    }
    home->areaNormal += area[t] * n;
    home->triangles.push_back(t);
  }

  // Refit each face: the area-weighted normal, and the offset through the area-weighted centroid.
  for (FaceCluster& f : faces) {
    const Eigen::Vector3d n = f.areaNormal.normalized();
    double weighted = 0, total = 0;
    for (int t : f.triangles) {
      const Eigen::Vector3d c = (triangleCorner(mesh, t, 0) + triangleCorner(mesh, t, 1) + triangleCorner(mesh, t, 2)) / 3.0;
      weighted += area[t] * n.dot(c);
      total += area[t];
    }
    f.plane = {n, weighted / total};
    fit.planes.push_back(f.plane);
  }

  // Convex: every vertex on or behind every plane, to the tolerance; and on its own faces' planes.
  for (const FaceCluster& f : faces) {
    for (const auto& v : mesh.vertices) fit.deviation = std::max(fit.deviation, f.plane.normal.dot(v) - f.plane.offset);
    for (int t : f.triangles)
      for (int k = 0; k < 3; ++k)
        fit.deviation = std::max(fit.deviation, std::abs(f.plane.normal.dot(triangleCorner(mesh, t, k)) - f.plane.offset));
  }
  if (fit.deviation > fit.tolerance) return std::nullopt;
  return fit;
}

}  // namespace tessera
