#include "geometry/base_surface.h"

#include "io/input_error.h"

#include <cmath>

namespace tessera {

Eigen::Vector3d BaseSurface::point(const Eigen::Vector2d& plan) const {
  if (kind == Kind::Plane) return {plan.x(), plan.y(), 0};
  const double across = kind == Kind::Sphere ? plan.squaredNorm() : plan.y() * plan.y();
  if (!(across < radius * radius))
    throw InputError("the tiling reaches beyond the " + std::string(kind == Kind::Sphere ? "sphere" : "cylinder") +
                     "'s radius; give a larger --radius or a smaller --grid");
  return {plan.x(), plan.y(), std::sqrt(radius * radius - across) - radius};
}

Eigen::Vector3d BaseSurface::normal(const Eigen::Vector3d& x) const {
  if (kind == Kind::Plane) return Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d fromCentre(kind == Kind::Sphere ? x.x() : 0.0, x.y(), x.z() + radius);
  return fromCentre.normalized();
}

BaseSurface baseSurface(const std::string& name, double radius) {
  BaseSurface s;
  if (name == "plane") return s;
  if (name == "sphere") s.kind = BaseSurface::Kind::Sphere;
  else if (name == "cylinder") s.kind = BaseSurface::Kind::Cylinder;
  else throw InputError("--surface '" + name + "': use plane, sphere or cylinder");
  if (!(radius > 0) || !std::isfinite(radius)) throw InputError("--surface " + name + " needs --radius, a positive length in --unit");
  s.radius = radius;
  return s;
}

}  // namespace tessera
