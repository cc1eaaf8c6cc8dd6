#include "geometry/mesh_symmetry.h"

#include "geometry/closest_point_on_triangle.h"
#include "geometry/mass_properties.h"
#include "geometry/point_grid.h"
#include "geometry/point_mesh_distance.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tessera {

namespace {

// Candidates tried at most: a mesh with thousands of vertices at one distance from its centroid
// (a finely tessellated round block) is taken as it is, without symmetries, rather than slowly.
constexpr std::size_t kMaxCandidates = 20000;

// An orthonormal frame from two independent vectors: a, the part of b across a, and their cross.
Eigen::Matrix3d frameOf(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Eigen::Matrix3d frame;
  frame.col(0) = a.normalized();
  frame.col(1) = (b - b.dot(frame.col(0)) * frame.col(0)).normalized();
  frame.col(2) = frame.col(0).cross(frame.col(1));
  return frame;
}

// The entries of a symmetry of a block built on round angles are exact values; computed from two
// corners they are off by rounding.
Eigen::Matrix3d snapped(Eigen::Matrix3d q) {
  static const std::array<double, 5> exact{0.0, 0.5, std::sqrt(0.5), std::sqrt(0.75), 1.0};
  for (int i = 0; i < 9; ++i)
    for (double e : exact)
      if (std::abs(std::abs(q(i)) - e) < 1e-9) q(i) = std::copysign(e, q(i));
  return q;
}

bool same(const Eigen::Matrix3d& p, const Eigen::Matrix3d& q) { return (p - q).cwiseAbs().maxCoeff() < 1e-6; }

struct References {
  std::vector<Eigen::Vector3d> points;  ///< relative to the centre
  int a = -1, b = -1;
};

// Reference points: the corners, or all vertices when the corners span no plane through the
// centre; a is the farthest from the centre, b the farthest from the line through a.
References referencesOf(const std::vector<Eigen::Vector3d>& points, double tolerance) {
  References refs{points, -1, -1};
  for (int i = 0; i < static_cast<int>(points.size()); ++i)
    if (refs.a < 0 || points[i].norm() > points[refs.a].norm()) refs.a = i;
  if (refs.a < 0 || points[refs.a].norm() <= tolerance) return References{};
  const Eigen::Vector3d axis = points[refs.a].normalized();
  double across = tolerance;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const double d = axis.cross(points[i]).norm();
    if (d > across) {
      across = d;
      refs.b = i;
    }
  }
  if (refs.b < 0) return References{};
  return refs;
}

bool closedUnderProducts(const std::vector<Eigen::Matrix3d>& elements) {
  for (const Eigen::Matrix3d& p : elements)
    for (const Eigen::Matrix3d& q : elements) {
      const Eigen::Matrix3d pq = p * q;
      bool found = false;
      for (const Eigen::Matrix3d& r : elements) found = found || same(pq, r);
      if (!found) return false;
    }
  return true;
}

// images[p]: the patch holding the image of a point well inside patch p (the centroid of its
// largest triangle); empty unless that maps the patches one to one onto patches.
std::vector<int> patchImagesOf(const TriangleMesh& mesh, const MeshFeatures& features, const SymmetryGroup& group,
                               std::size_t g, double tolerance) {
  std::vector<int> largest(features.patchCount, -1);
  double longestEdge = 0.0;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    int& l = largest[features.trianglePatch[t]];
    if (l < 0 || triangleArea(mesh, t) > triangleArea(mesh, l)) l = t;
    for (int k = 0; k < 3; ++k)
      longestEdge = std::max(longestEdge, (triangleCorner(mesh, t, k) - triangleCorner(mesh, t, (k + 1) % 3)).norm());
  }
  // A triangle holding x has its centroid within its longest edge of x.
  PointGrid triangles(longestEdge);
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    triangles.insert(t, (triangleCorner(mesh, t, 0) + triangleCorner(mesh, t, 1) + triangleCorner(mesh, t, 2)) / 3.0);
  std::vector<int> images(features.patchCount, -1);
  std::vector<char> hit(features.patchCount, 0);
  for (int p = 0; p < features.patchCount; ++p) {
    const int t = largest[p];
    const Eigen::Vector3d x =
        group.apply(g, (triangleCorner(mesh, t, 0) + triangleCorner(mesh, t, 1) + triangleCorner(mesh, t, 2)) / 3.0);
    double nearest = INFINITY;
    triangles.forEachNear(x, longestEdge, [&](int u) {
      const double d =
          (closestPointOnTriangle(x, triangleCorner(mesh, u, 0), triangleCorner(mesh, u, 1), triangleCorner(mesh, u, 2))
               .point - x).norm();
      if (d < nearest) {
        nearest = d;
        images[p] = features.trianglePatch[u];
      }
    });
    if (!(nearest <= tolerance) || hit[images[p]]) return {};
    hit[images[p]] = 1;
  }
  return images;
}

}  // namespace

SymmetryGroup findSymmetries(const TriangleMesh& mesh, const MeshFeatures& features, double tolerance) {
  SymmetryGroup group;
  group.centre = computeMassProperties(mesh).centroid;
  std::vector<Eigen::Vector3d> corners, vertices;
  for (int v : features.corners) corners.push_back(mesh.vertices[v] - group.centre);
  for (const Eigen::Vector3d& v : mesh.vertices) vertices.push_back(v - group.centre);
  References refs = referencesOf(corners, tolerance);
  if (refs.a < 0) refs = referencesOf(vertices, tolerance);
  if (refs.a < 0) return SymmetryGroup{group.centre, {Eigen::Matrix3d::Identity()}, {}};

  const std::vector<Eigen::Vector3d>& points = refs.points;
  const double extent = points[refs.a].norm();
  PointGrid grid(extent * 1e-3 + tolerance);
  for (int i = 0; i < static_cast<int>(points.size()); ++i) grid.insert(i, points[i]);
  const PointMeshDistance surface(mesh);
  // q maps every reference point onto a reference point, and every vertex onto the surface.
  const auto isSymmetry = [&](const Eigen::Matrix3d& q) {
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector3d image = q * p;
      bool hit = false;
      grid.forEachNear(image, tolerance, [&](int j) { hit = hit || (points[j] - image).norm() <= tolerance; });
      if (!hit) return false;
    }
    for (const Eigen::Vector3d& v : vertices)
      if (surface.distance(group.centre + q * v) > tolerance) return false;
    return true;
  };

  const Eigen::Vector3d &a = points[refs.a], &b = points[refs.b];
  const Eigen::Matrix3d from = frameOf(a, b);
  std::vector<Eigen::Matrix3d> tried{Eigen::Matrix3d::Identity()};
  for (const Eigen::Vector3d& a2 : points) {
    if (std::abs(a2.norm() - a.norm()) > tolerance) continue;
    for (const Eigen::Vector3d& b2 : points) {
      if (std::abs(b2.norm() - b.norm()) > tolerance || std::abs(a2.dot(b2) - a.dot(b)) > tolerance * (a.norm() + b.norm()))
        continue;
      if (a2.cross(b2).norm() <= tolerance * extent) continue;
      const Eigen::Matrix3d to = frameOf(a2, b2);
      for (const double handedness : {1.0, -1.0}) {
        if (tried.size() >= kMaxCandidates) return SymmetryGroup{group.centre, {Eigen::Matrix3d::Identity()}, {}};
        const Eigen::Matrix3d q = snapped(to * Eigen::Vector3d(1, 1, handedness).asDiagonal() * from.transpose());
        bool seen = false;
        for (const Eigen::Matrix3d& t : tried) seen = seen || same(q, t);
        if (seen) continue;
        tried.push_back(q);
        if (isSymmetry(q)) group.elements.push_back(q);
      }
    }
  }
  if (!closedUnderProducts(group.elements)) return SymmetryGroup{group.centre, {Eigen::Matrix3d::Identity()}, {}};
  for (std::size_t g = 0; g < group.size(); ++g) {
    group.patchImages.push_back(patchImagesOf(mesh, features, group, g, tolerance));
    if (group.patchImages.back().empty()) return SymmetryGroup{group.centre, {Eigen::Matrix3d::Identity()}, {}};
  }
  return group;
}

}  // namespace tessera
