#include "solver/node_bins.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tessera {

NodeBins makeNodeBins(const SurfaceNodes& nodes, int targetPerBin) {
  NodeBins b;
  for (const auto& x : nodes.positions) b.box.extend(x);
  const Eigen::Vector3d size = b.box.sizes().cwiseMax(1e-9);
  // Bins roughly cubic, about targetPerBin nodes each on a surface.
  const double cell = std::max(std::sqrt(size.maxCoeff() * size.minCoeff() * 2.0 * targetPerBin /
                                         std::max<double>(1, nodes.size())),
                               1e-9);
  for (int a = 0; a < 3; ++a) b.bins[a] = std::clamp(static_cast<int>(std::ceil(size[a] / cell)), 1, 256);
  b.binSize = size.array() / b.bins.cast<double>();
  const auto binIndex = [&](const Eigen::Vector3d& x) {
    const Eigen::Array3i c = b.binOf(x).max(0).min(b.bins - 1);
    return (c.x() * b.bins.y() + c.y()) * b.bins.z() + c.z();
  };
  std::vector<int> order(nodes.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int i, int j) { return binIndex(nodes.positions[i]) < binIndex(nodes.positions[j]); });
  b.binStart.assign(b.bins.prod() + 1, 0);
  for (int i : order) ++b.binStart[binIndex(nodes.positions[i]) + 1];
  std::partial_sum(b.binStart.begin(), b.binStart.end(), b.binStart.begin());
  for (int i : order) {
    b.position.push_back(nodes.positions[i]);
    b.normal.push_back(nodes.normals[i]);
    b.area.push_back(nodes.areas[i]);
  }
  return b;
}

}  // namespace tessera
