#pragma once
#include "geometry/triangle_mesh.h"

#include <algorithm>
#include <limits>
#include <optional>
#include <vector>

namespace tessera {

/// A face plane n . x = d of a polyhedron, n the unit outward normal (m for d).
struct FacePlane {
  Eigen::Vector3d normal;
  double offset;
};

/// The most face planes a convex shape may have: the solver marks the planes it keeps per pair in a
/// 64-bit mask and holds them in fixed arrays of this size (solver/pair_contacts.cpp).
constexpr int kMaxConvexPlanes = 64;

/// How near to convex a mesh may be and still be treated as a convex polyhedron.
struct ConvexFitOptions {
  /// Vertices may lie this far (relative to the bounding-box diagonal) off their face's plane and
  /// outside the other faces' planes. 1e-4 covers the rounding of exported coordinates (6 decimals
  /// in metres: 5e-7 m, 1e-5 of a 50 mm block; single-precision STL: 1e-7) and is 250 x finer than
  /// the default voxel (1/40 of the diagonal): no grid could tell the fitted polyhedron from the mesh.
  double relativeTolerance = 1e-4;
  int maxPlanes = kMaxConvexPlanes;  ///< more faces than this: not worth planes (the grid is as fast); at most kMaxConvexPlanes
};

/// The face planes of a (near-)convex polyhedron.
struct ConvexFit {
  std::vector<FacePlane> planes;
  double deviation = 0;  ///< m, the largest distance of a vertex off its face's plane or outside another's
  double tolerance = 0;  ///< m, what was accepted
};

/// If the closed mesh is convex to within the tolerance with at most maxPlanes faces, its face
/// planes, each fitted to its triangles (area-weighted normal and offset); otherwise nothing.
/// Triangles join a face when their normal is within 25 degrees of it and their three vertices lie
/// within the tolerance of its plane. Then phi(x) = max_f (n_f . x - d_f) is the exact signed
/// distance of the fitted polyhedron inside and a positive lower bound of it outside: an analytic
/// level set.
std::optional<ConvexFit> fitConvexPolyhedron(const TriangleMesh& mesh, const ConvexFitOptions& options = {});

/// phi(x) = max_f (n_f . x - d_f), the planes' level set at x (m; see fitConvexPolyhedron).
inline double planesLevelSet(const std::vector<FacePlane>& planes, const Eigen::Vector3d& x) {
  double phi = -std::numeric_limits<double>::infinity();
  for (const FacePlane& f : planes) phi = std::max(phi, f.normal.dot(x) - f.offset);
  return phi;
}

}  // namespace tessera
