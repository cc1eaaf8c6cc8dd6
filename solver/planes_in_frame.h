#pragma once
// The face planes of a convex body in another body's frame: its exact level set, evaluated where
// the other body's nodes are (solver/pair_contacts.cpp, solver/implicit_contacts.cpp).
#include "geometry/convex_planes.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace tessera {

/// The face planes of a convex body expressed in another body's frame (x_O = R x_M + t), in hot
/// arrays: phi(p) = max_f (n_f . p - d_f), the exact level set of a convex polyhedron (1-Lipschitz),
/// evaluated without transforming p.
struct PlanesInFrame {
  static constexpr int kMax = kMaxConvexPlanes;
  static_assert(kMax <= 64, "the kept planes are bits of a 64-bit mask");
  std::array<double, kMax> nx, ny, nz, offset;  // M's frame
  int count = 0;

  /// R, t: the other body's frame from M's. Only the planes of `kept` (bit f: plane f), in their
  /// order.
  PlanesInFrame(const std::vector<FacePlane>& planes, const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                std::uint64_t kept = ~0ull) {
    const int all = static_cast<int>(planes.size());  // <= kMax: makeShapeModel refuses more
    for (int f = 0; f < all; ++f) {
      if (!(kept >> f & 1)) continue;
      const Eigen::Vector3d n = R.transpose() * planes[f].normal;
      nx[count] = n.x();
      ny[count] = n.y();
      nz[count] = n.z();
      offset[count] = planes[f].offset - planes[f].normal.dot(t);
      ++count;
    }
  }
  double value(int f, const Eigen::Vector3d& p) const { return nx[f] * p.x() + ny[f] * p.y() + nz[f] * p.z() - offset[f]; }
  /// phi at p, and `best`, the first plane of largest value.
  double phi(const Eigen::Vector3d& p, int& best) const {
    best = 0;
    double highest = value(0, p);
    for (int f = 1; f < count; ++f) {
      const double v = value(f, p);
      if (v > highest) {
        highest = v;
        best = f;
      }
    }
    return highest;
  }
  /// phi at p and `best`, as phi(), for a caller that needs only whether phi < enough: the first
  /// plane whose value reaches `enough` settles it, and that value (at least `enough`, at most phi)
  /// is returned without the others. The largest by selects, not branches: which plane is nearest
  /// is no pattern a branch predictor learns.
  double phiBelow(const Eigen::Vector3d& p, double enough, int& best) const {
    best = 0;
    double highest = -std::numeric_limits<double>::infinity();
    for (int f = 0; f < count; ++f) {
      const double v = value(f, p);
      if (v >= enough) return v;
      const bool higher = v > highest;
      best = higher ? f : best;
      highest = higher ? v : highest;
    }
    return highest;
  }
};

}  // namespace tessera
