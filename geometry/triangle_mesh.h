#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace tessera {

/// An indexed triangle mesh. Lengths in metres. For a solid, triangles are counter-clockwise
/// seen from outside (outward normals by the right-hand rule).
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
};

inline Eigen::Vector3d triangleCorner(const TriangleMesh& m, int t, int k) {
  return m.vertices[m.triangles[t][k]];
}

/// (b - a) x (c - a): twice the area times the unit normal.
inline Eigen::Vector3d triangleAreaVector(const TriangleMesh& m, int t) {
  const Eigen::Vector3d a = triangleCorner(m, t, 0);
  return (triangleCorner(m, t, 1) - a).cross(triangleCorner(m, t, 2) - a);
}

inline double triangleArea(const TriangleMesh& m, int t) { return 0.5 * triangleAreaVector(m, t).norm(); }

inline Eigen::AlignedBox3d boundingBox(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const auto& p : points) box.extend(p);
  return box;
}

inline double surfaceArea(const TriangleMesh& m) {
  double area = 0.0;
  for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) area += triangleArea(m, t);
  return area;
}

}  // namespace tessera
