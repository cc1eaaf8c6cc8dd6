#include "geometry/point_spacing.h"

#include "geometry/point_grid.h"
#include "geometry/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace tessera {

std::vector<double> nearestNeighbourDistances(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& group) {
  if (points.size() < 2) return {};
  // Cell size from the mean volume per point of the bounding box, then growing radius searches.
  const double cell = std::max(boundingBox(points).diagonal().norm() / std::cbrt(static_cast<double>(points.size())), 1e-9);
  PointGrid grid(cell);
  for (int i = 0; i < static_cast<int>(points.size()); ++i) grid.insert(i, points[i]);
  const double reach = 4 * boundingBox(points).diagonal().norm() + cell;
  std::vector<double> out;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (double radius = cell; best > radius && radius < reach; radius *= 2)
      grid.forEachNear(points[i], radius, [&](int k) {
        if (k != i && group[k] == group[i]) best = std::min(best, (points[k] - points[i]).norm());
      });
    if (std::isfinite(best)) out.push_back(best);
  }
  return out;
}

SpacingStats spacingStats(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& group) {
  const std::vector<double> d = nearestNeighbourDistances(points, group);
  SpacingStats s;
  if (d.empty()) return s;
  s.min = *std::min_element(d.begin(), d.end());
  s.max = *std::max_element(d.begin(), d.end());
  s.mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  return s;
}

}  // namespace tessera
