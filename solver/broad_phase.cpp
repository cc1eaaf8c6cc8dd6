#include "solver/broad_phase.h"

#include <algorithm>
#include <numeric>

namespace tessera {

std::vector<std::pair<int, int>> sweepPairs(const std::vector<Eigen::AlignedBox3d>& boxes, const std::vector<char>& fixed) {
  const int n = static_cast<int>(boxes.size());
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    return boxes[i].min().x() < boxes[j].min().x() || (boxes[i].min().x() == boxes[j].min().x() && i < j);
  });
  std::vector<std::pair<int, int>> pairs;
  for (int s = 0; s < n; ++s) {
    const int i = order[s];
    for (int t = s + 1; t < n && boxes[order[t]].min().x() <= boxes[i].max().x(); ++t) {
      const int j = order[t];
      if ((fixed[i] && fixed[j]) || !boxes[i].intersects(boxes[j])) continue;
      pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<std::pair<int, int>> bruteForcePairs(const std::vector<Eigen::AlignedBox3d>& boxes,
                                                 const std::vector<char>& fixed) {
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(boxes.size()); ++j)
      if (!(fixed[i] && fixed[j]) && boxes[i].intersects(boxes[j])) pairs.emplace_back(i, j);
  return pairs;
}

Eigen::AlignedBox3d worldBox(const Eigen::AlignedBox3d& bodyBox, const Eigen::Quaterniond& q, const Eigen::Vector3d& p,
                             double margin) {
  const Eigen::Matrix3d R = q.toRotationMatrix();
  const Eigen::Vector3d centre = R * bodyBox.center() + p;
  const Eigen::Vector3d half = R.cwiseAbs() * (0.5 * bodyBox.sizes()) + Eigen::Vector3d::Constant(margin);
  return Eigen::AlignedBox3d(centre - half, centre + half);
}

}  // namespace tessera
