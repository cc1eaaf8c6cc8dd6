#pragma once
#include <Eigen/Core>

namespace tessera {

/// Analytic level sets for rigid obstacles with prescribed motion (no grids, no nodes): the
/// bodies' surface nodes are tested against them.

/// A sphere moving at a constant velocity: phi(x) = |x - c| - R (the indenter).
struct SphereObstacle {
  Eigen::Vector3d center{0, 0, 0};    ///< m
  double radius = 2.5e-3;             ///< m
  Eigen::Vector3d velocity{0, 0, 0};  ///< m/s, prescribed
  double stiffnessFactor = 1.0;       ///< its contact stiffnesses are this x k_n and k_t of the bodies

  double phi(const Eigen::Vector3d& x) const { return (x - center).norm() - radius; }
  /// Unit gradient (outward normal); along +z at the centre itself.
  Eigen::Vector3d normal(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d r = x - center;
    const double n = r.norm();
    return n > 0 ? Eigen::Vector3d(r / n) : Eigen::Vector3d::UnitZ();
  }
};

/// A fixed half-space: phi(x) = n . (x - p), solid where phi < 0 (a floor or a wall).
struct PlaneObstacle {
  Eigen::Vector3d point{0, 0, 0};   ///< m, a point of the plane
  Eigen::Vector3d normal{0, 0, 1};  ///< unit, pointing out of the solid

  double phi(const Eigen::Vector3d& x) const { return normal.dot(x - point); }
};

}  // namespace tessera
