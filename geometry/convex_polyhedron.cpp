#include "geometry/convex_polyhedron.h"

#include "io/input_error.h"

#include <cmath>

namespace tessera {

namespace {

using Polygon = std::vector<Eigen::Vector3d>;

// The part of a convex polygon with n . x <= d (one Sutherland-Hodgman pass).
Polygon clip(const Polygon& polygon, const FacePlane& plane) {
  Polygon kept;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector3d& a = polygon[i];
    const Eigen::Vector3d& b = polygon[(i + 1) % polygon.size()];
    const double da = plane.normal.dot(a) - plane.offset, db = plane.normal.dot(b) - plane.offset;
    if (da <= 0) kept.push_back(a);
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) kept.push_back(a + (b - a) * (da / (da - db)));
  }
  return kept;
}

// A square of half-side `half` in the plane, counter-clockwise about its normal.
Polygon planeSquare(const FacePlane& plane, double half) {
  const Eigen::Vector3d& n = plane.normal;
  const Eigen::Vector3d u = (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).cross(n).normalized();
  const Eigen::Vector3d v = n.cross(u);
  const Eigen::Vector3d centre = n * plane.offset;
  return {centre + half * (-u - v), centre + half * (u - v), centre + half * (u + v), centre + half * (-u + v)};
}

}  // namespace

TriangleMesh convexPolyhedronFromPlanes(const std::vector<FacePlane>& planes, double size) {
  const double mergeDistance = 1e-9 * size;
  TriangleMesh mesh;
  const auto vertexIndex = [&](const Eigen::Vector3d& x) {
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
      if ((mesh.vertices[i] - x).norm() <= mergeDistance) return static_cast<int>(i);
    mesh.vertices.push_back(x);
    return static_cast<int>(mesh.vertices.size()) - 1;
  };
  std::vector<FacePlane> distinct;  // a plane given twice bounds one face
  for (const FacePlane& p : planes) {
    bool repeated = false;
    for (const FacePlane& q : distinct)
      repeated = repeated || (p.normal.dot(q.normal) > 1 - 1e-12 && std::abs(p.offset - q.offset) <= mergeDistance);
    if (!repeated) distinct.push_back(p);
  }
  int faces = 0;
  for (std::size_t i = 0; i < distinct.size(); ++i) {
    Polygon face = planeSquare(distinct[i], 4 * size);
    for (std::size_t j = 0; j < distinct.size() && !face.empty(); ++j)
      if (j != i) face = clip(face, distinct[j]);
    std::vector<int> corners;
    for (const Eigen::Vector3d& x : face) {
      const int v = vertexIndex(x);
      if (corners.empty() || (corners.back() != v && corners.front() != v)) corners.push_back(v);
    }
    if (corners.size() < 3) continue;
    double area = 0;  // twice the area
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      area += (mesh.vertices[corners[k]] - mesh.vertices[corners[0]])
                  .cross(mesh.vertices[corners[k + 1]] - mesh.vertices[corners[0]])
                  .dot(distinct[i].normal);
    if (area <= mergeDistance * size) continue;
    ++faces;
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) mesh.triangles.push_back({corners[0], corners[k], corners[k + 1]});
  }
  if (faces < 4) throw InputError("the planes bound no solid (" + std::to_string(faces) + " faces): check the block's dimensions and angles");
  return mesh;
}

}  // namespace tessera
