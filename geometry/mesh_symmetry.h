#pragma once
#include "geometry/mesh_features.h"
#include "geometry/triangle_mesh.h"

#include <vector>

namespace tessera {

/// The symmetries of a closed mesh: the orthogonal maps x -> centre + Q (x - centre) that carry
/// its surface onto itself (mirrors, rotations, rotoreflections, the inversion), the identity
/// first. A group: the product of any two elements is an element.
struct SymmetryGroup {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();   ///< m; the volume centroid
  std::vector<Eigen::Matrix3d> elements{Eigen::Matrix3d::Identity()};
  std::vector<std::vector<int>> patchImages;           ///< [g][p]: the patch element g maps patch p onto;
                                                       ///< empty for the identity alone

  Eigen::Vector3d apply(std::size_t g, const Eigen::Vector3d& x) const { return centre + elements[g] * (x - centre); }
  std::size_t size() const { return elements.size(); }
};

/// Finds the symmetry group of a validated, outward mesh, to `tolerance` (m) of its surface.
/// Every symmetry maps corners to corners at the same distance from the centroid. So two
/// independent reference corners a, b (mesh vertices where the mesh has no corners) and each
/// pair of corners (a', b') at their distances and angle fix one proper and one improper
/// candidate Q (Q a = a', Q b = b'), and a candidate is kept when it maps every corner onto a
/// corner and every vertex onto the surface, both within `tolerance`. Entries within 1e-9 of 0,
/// +-1/2, +-sqrt(2)/2, +-sqrt(3)/2 or +-1 are snapped to them, so that a mirror of a block built
/// on the coordinate axes is exact. When the kept maps are not closed under products (a
/// near-symmetric mesh read at the edge of the tolerance), or one of them does not map the patches
/// (MeshFeatures) one to one onto patches, the group is the identity alone.
SymmetryGroup findSymmetries(const TriangleMesh& mesh, const MeshFeatures& features, double tolerance);

}  // namespace tessera
