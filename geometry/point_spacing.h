#pragma once
#include <Eigen/Core>
#include <vector>

namespace tessera {

struct SpacingStats {
  double min = 0.0, mean = 0.0, max = 0.0;  ///< nearest-neighbour distance, m
};

/// For each point, the distance to the nearest other point of the same group (for surface nodes:
/// of the same patch, so that rows of nodes on the two sides of an edge do not count as
/// neighbours). A point alone in its group gets no entry.
std::vector<double> nearestNeighbourDistances(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& group);

SpacingStats spacingStats(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& group);

}  // namespace tessera
