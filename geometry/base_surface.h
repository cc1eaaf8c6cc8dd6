#pragma once
#include <Eigen/Core>
#include <string>

namespace tessera {

/// The surface a generated tiling is laid on (docs/tiling.md, "On a surface"): a plan point (x, y)
/// is lifted vertically onto it, and blocks are offset along its normal. The sphere's and the
/// cylinder's top is at the origin; the cylinder's axis runs along x (a barrel vault spanning y).
struct BaseSurface {
  enum class Kind { Plane, Sphere, Cylinder };
  Kind kind = Kind::Plane;
  double radius = 0;  ///< m (sphere, cylinder)

  /// The surface point over a plan point; InputError where the surface has none (beyond the radius).
  Eigen::Vector3d point(const Eigen::Vector2d& plan) const;
  /// The unit normal, pointing up and out, at a point on or near the surface (for a chord's
  /// midpoint it is perpendicular to the chord).
  Eigen::Vector3d normal(const Eigen::Vector3d& x) const;
};

/// "plane", "sphere" or "cylinder" with its radius (m); InputError for another name or a radius
/// that is not positive (sphere, cylinder).
BaseSurface baseSurface(const std::string& name, double radius);

}  // namespace tessera
