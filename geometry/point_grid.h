#pragma once
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace tessera {

/// A uniform hash grid over points for radius queries at set-up time (not for hot loops).
/// Points are added by index; the caller keeps the coordinates.
class PointGrid {
public:
  explicit PointGrid(double cellSize) : cell_(cellSize) {}

  void insert(int index, const Eigen::Vector3d& p) { cells_[key(cellOf(p))].push_back(index); }

  /// Calls visit(index) for every inserted point whose cell is within `radius` of p
  /// (a superset of the points within radius; the caller checks the distance).
  template <class Visit>
  void forEachNear(const Eigen::Vector3d& p, double radius, Visit&& visit) const {
    const Eigen::Array3i lo = cellOf(p.array() - radius), hi = cellOf(p.array() + radius);
    for (int i = lo.x(); i <= hi.x(); ++i)
      for (int j = lo.y(); j <= hi.y(); ++j)
        for (int k = lo.z(); k <= hi.z(); ++k) {
          const auto it = cells_.find(key({i, j, k}));
          if (it == cells_.end()) continue;
          for (int index : it->second) visit(index);
        }
  }

private:
  // Clamped to +-2^30 cells: a point far beyond them (a coordinate 10^9 cells out) shares the
  // outermost cell, which costs time, never a wrong answer (the caller checks the distance); a
  // plain cast there was undefined behaviour (found by fuzz_mesh_import).
  Eigen::Array3i cellOf(const Eigen::Array3d& p) const {
    constexpr double kLimit = 1 << 30;
    return (p / cell_).floor().max(-kLimit).min(kLimit).cast<int>();
  }
  static std::uint64_t key(const Eigen::Array3i& c) {
    const auto part = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v) & 0x1FFFFFu); };
    return part(c.x()) | (part(c.y()) << 21) | (part(c.z()) << 42);
  }

  double cell_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

}  // namespace tessera
