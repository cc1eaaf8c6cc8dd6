#pragma once
#include <Eigen/Geometry>
#include <utility>
#include <vector>

namespace tessera {

/// Candidate body pairs (a < b) whose world bounding boxes overlap, never two fixed bodies.
/// Boxes are sorted by their lower x bound and swept (sort and sweep).
std::vector<std::pair<int, int>> sweepPairs(const std::vector<Eigen::AlignedBox3d>& boxes, const std::vector<char>& fixed);

/// The same by testing every pair: the reference the tests hold the sweep to.
std::vector<std::pair<int, int>> bruteForcePairs(const std::vector<Eigen::AlignedBox3d>& boxes,
                                                 const std::vector<char>& fixed);

/// World box of a body-frame box turned by q and moved to p, enlarged by margin on every side.
Eigen::AlignedBox3d worldBox(const Eigen::AlignedBox3d& bodyBox, const Eigen::Quaterniond& q, const Eigen::Vector3d& p,
                             double margin);

}  // namespace tessera
