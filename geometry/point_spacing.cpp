#include "geometry/point_spacing.h"

#include "geometry/point_grid.h"
#include "geometry/triangle_mesh.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace tessera {

std::vector<double> nearestNeighbourDistances(const std::vector<Eigen::Vector3d>& points, double mergeTolerance) {
  // Distinct points first.
  std::vector<Eigen::Vector3d> distinct;
  {
    PointGrid grid(std::max(mergeTolerance, 1e-12));
    for (const auto& p : points) {
      bool seen = false;
      grid.forEachNear(p, mergeTolerance, [&](int k) { seen = seen || (distinct[k] - p).norm() <= mergeTolerance; });
      if (seen) continue;
      grid.insert(static_cast<int>(distinct.size()), p);
      distinct.push_back(p);
    }
  }
  if (distinct.size() < 2) return {};

  // Cell size from the mean area per point of the bounding box, then growing radius searches.
  const Eigen::AlignedBox3d box = boundingBox(distinct);
  const double cell = std::max(box.diagonal().norm() / std::cbrt(static_cast<double>(distinct.size())), 1e-9);
  PointGrid grid(cell);
  for (int i = 0; i < static_cast<int>(distinct.size()); ++i) grid.insert(i, distinct[i]);
  std::vector<double> out(distinct.size());
  for (int i = 0; i < static_cast<int>(distinct.size()); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (double radius = cell; best > radius; radius *= 2)
      grid.forEachNear(distinct[i], radius, [&](int k) {
        if (k != i) best = std::min(best, (distinct[k] - distinct[i]).norm());
      });
    out[i] = best;
  }
  return out;
}

SpacingStats spacingStats(const std::vector<Eigen::Vector3d>& points, double mergeTolerance) {
  const std::vector<double> d = nearestNeighbourDistances(points, mergeTolerance);
  SpacingStats s;
  s.distinctPoints = d.size();
  if (d.empty()) return s;
  s.min = *std::min_element(d.begin(), d.end());
  s.max = *std::max_element(d.begin(), d.end());
  s.mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  return s;
}

}  // namespace tessera
