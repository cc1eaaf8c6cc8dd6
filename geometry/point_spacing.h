#pragma once
#include <Eigen/Core>
#include <vector>

namespace tessera {

struct SpacingStats {
  double min = 0.0, mean = 0.0, max = 0.0;  ///< nearest-neighbour distance, m
  std::size_t distinctPoints = 0;
};

/// Distance from each distinct point to its nearest other distinct point. Points closer than
/// `mergeTolerance` (m) count as one (a sharp-edge node has one copy per adjacent face).
std::vector<double> nearestNeighbourDistances(const std::vector<Eigen::Vector3d>& points, double mergeTolerance);

SpacingStats spacingStats(const std::vector<Eigen::Vector3d>& points, double mergeTolerance);

}  // namespace tessera
