// CGAL AABB tree: heavy headers, kept in this one translation unit.
#include "geometry/point_mesh_distance.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <cmath>
#include <vector>

namespace tessera {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Kernel::Point_3 point(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

struct PointMeshDistance::Tree {
  std::vector<Triangle> triangles;
  tessera::Tree tree;
};

PointMeshDistance::PointMeshDistance(const TriangleMesh& mesh) : tree_(std::make_unique<Tree>()) {
  tree_->triangles.reserve(mesh.triangles.size());
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    tree_->triangles.emplace_back(point(triangleCorner(mesh, t, 0)), point(triangleCorner(mesh, t, 1)),
                                  point(triangleCorner(mesh, t, 2)));
  tree_->tree.insert(tree_->triangles.begin(), tree_->triangles.end());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
}

PointMeshDistance::~PointMeshDistance() = default;

double PointMeshDistance::distance(const Eigen::Vector3d& p) const {
  return std::sqrt(tree_->tree.squared_distance(point(p)));
}

}  // namespace tessera
