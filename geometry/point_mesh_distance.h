#pragma once
#include "geometry/triangle_mesh.h"

#include <memory>

namespace tessera {

/// Exact Euclidean distance from points to a triangle mesh (CGAL AABB tree). Build once, then
/// query from any number of threads.
class PointMeshDistance {
public:
  explicit PointMeshDistance(const TriangleMesh& mesh);
  ~PointMeshDistance();
  PointMeshDistance(const PointMeshDistance&) = delete;
  PointMeshDistance& operator=(const PointMeshDistance&) = delete;

  /// Unsigned distance (m) from p to the nearest point of the mesh surface.
  double distance(const Eigen::Vector3d& p) const;

private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace tessera
