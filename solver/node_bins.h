#pragma once
#include "geometry/surface_nodes.h"

#include <Eigen/Geometry>
#include <vector>

namespace tessera {

/// A shape's surface nodes sorted into a coarse uniform grid of bins over their bounding box
/// (body frame), so a contact query visits only the bins that overlap the other body. Node data
/// are stored in bin order (hot arrays); `rank` is a node's position in that order.
struct NodeBins {
  Eigen::AlignedBox3d box;                 ///< body frame, m: bounding box of the nodes
  Eigen::Vector3d binSize{1, 1, 1};        ///< m
  Eigen::Array3i bins{1, 1, 1};            ///< count per axis
  std::vector<int> binStart;               ///< CSR: nodes of bin b are ranks binStart[b] .. binStart[b+1]-1
  std::vector<Eigen::Vector3d> position;   ///< body frame, by rank
  std::vector<Eigen::Vector3d> normal;     ///< body frame, by rank
  std::vector<double> area;                ///< m^2, by rank

  /// Calls visit(rank) for the nodes in bins overlapping `region` (body frame), in increasing rank.
  template <class Visit>
  void forEachNodeIn(const Eigen::AlignedBox3d& region, Visit&& visit) const {
    if (!region.intersects(box)) return;
    const Eigen::Array3i lo = binOf(region.min()).max(0), hi = binOf(region.max()).min(bins - 1);
    for (int i = lo.x(); i <= hi.x(); ++i)
      for (int j = lo.y(); j <= hi.y(); ++j) {
        const int first = (i * bins.y() + j) * bins.z();
        for (int rank = binStart[first + lo.z()]; rank < binStart[first + hi.z() + 1]; ++rank) visit(rank);
      }
  }

  Eigen::Array3i binOf(const Eigen::Vector3d& x) const {
    return ((x - box.min()).array() / binSize.array()).floor().cast<int>();
  }
};

/// Bins of about `targetPerBin` nodes each.
NodeBins makeNodeBins(const SurfaceNodes& nodes, int targetPerBin = 16);

}  // namespace tessera
