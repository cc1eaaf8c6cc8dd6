#include "geometry/base_surface.h"

#include "geometry/mesh_import.h"
#include "io/input_error.h"

#include <cmath>
#include <filesystem>
#include <optional>

namespace tessera {

namespace {

// The triangle of a height-field mesh over a plan point, and the point's barycentric
// coordinates in it (the first that holds it, to 1e-9 of the triangle's size).
std::optional<std::pair<int, Eigen::Vector3d>> triangleOver(const TriangleMesh& mesh, const Eigen::Vector2d& plan) {
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Eigen::Vector2d a = triangleCorner(mesh, t, 0).head<2>(), b = triangleCorner(mesh, t, 1).head<2>(),
                          c = triangleCorner(mesh, t, 2).head<2>();
    const Eigen::Vector2d ab = b - a, ac = c - a, ap = plan - a;
    const double area = ab.x() * ac.y() - ab.y() * ac.x();  // twice the plan area, > 0 (turned up)
    if (!(area > 0)) continue;
    const double v = (ap.x() * ac.y() - ap.y() * ac.x()) / area, w = (ab.x() * ap.y() - ab.y() * ap.x()) / area;
    const double tolerance = 1e-9;
    if (v >= -tolerance && w >= -tolerance && v + w <= 1 + tolerance) return std::make_pair(t, Eigen::Vector3d(1 - v - w, v, w));
  }
  return std::nullopt;
}

std::pair<int, Eigen::Vector3d> requireTriangleOver(const BaseSurface& s, const Eigen::Vector2d& plan) {
  const auto found = triangleOver(s.mesh->mesh, plan);
  if (!found)
    throw InputError("the tiling reaches beyond the surface " + s.name + " (no triangle under the tiling's point at x = " +
                     std::to_string(plan.x()) + " m, y = " + std::to_string(plan.y()) +
                     " m); give a smaller --grid or a surface that covers the tiling in plan");
  return *found;
}

SurfaceMesh heightField(TriangleMesh mesh, const std::string& path) {
  int up = 0, down = 0;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Eigen::Vector3d n = triangleAreaVector(mesh, t);
    if (n.z() > 1e-9 * n.norm()) ++up;
    else if (n.z() < -1e-9 * n.norm()) ++down;
    else
      throw InputError(path + ": triangle " + std::to_string(t) + " stands vertical, so the surface is not a height field over "
                       "the plan (x, y); give a surface that every vertical line crosses at most once");
  }
  if (up > 0 && down > 0)
    throw InputError(path + ": " + std::to_string(up) + " triangles face up and " + std::to_string(down) +
                     " down, so the surface is not a height field over the plan (a closed solid, or folded); give an open surface");
  if (down > 0)
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  SurfaceMesh s;
  s.vertexNormals.assign(mesh.vertices.size(), Eigen::Vector3d::Zero());
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) s.vertexNormals[mesh.triangles[t][k]] += triangleAreaVector(mesh, t);
  for (Eigen::Vector3d& n : s.vertexNormals)
    if (n.norm() > 0) n.normalize();
  s.mesh = std::move(mesh);
  return s;
}

}  // namespace

Eigen::Vector3d BaseSurface::point(const Eigen::Vector2d& plan) const {
  if (kind == Kind::Plane) return {plan.x(), plan.y(), 0};
  if (kind == Kind::Mesh) {
    const auto [t, weights] = requireTriangleOver(*this, plan);
    double z = 0;
    for (int k = 0; k < 3; ++k) z += weights[k] * triangleCorner(mesh->mesh, t, k).z();
    return {plan.x(), plan.y(), z};
  }
  const double across = kind == Kind::Sphere ? plan.squaredNorm() : plan.y() * plan.y();
  if (!(across < radius * radius))
    throw InputError("the tiling reaches beyond the " + std::string(kind == Kind::Sphere ? "sphere" : "cylinder") +
                     "'s radius; give a larger --radius or a smaller --grid");
  return {plan.x(), plan.y(), std::sqrt(radius * radius - across) - radius};
}

Eigen::Vector3d BaseSurface::normal(const Eigen::Vector3d& x) const {
  if (kind == Kind::Plane) return Eigen::Vector3d::UnitZ();
  if (kind == Kind::Mesh) {
    const auto [t, weights] = requireTriangleOver(*this, x.head<2>());
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) n += weights[k] * mesh->vertexNormals[mesh->mesh.triangles[t][k]];
    return n.normalized();
  }
  const Eigen::Vector3d fromCentre(kind == Kind::Sphere ? x.x() : 0.0, x.y(), x.z() + radius);
  return fromCentre.normalized();
}

BaseSurface baseSurface(const std::string& name, double radius, double metresPerUnit, const std::string& up) {
  BaseSurface s;
  if (name == "plane") return s;
  if (name == "sphere" || name == "cylinder") {
    s.kind = name == "sphere" ? BaseSurface::Kind::Sphere : BaseSurface::Kind::Cylinder;
    if (!(radius > 0) || !std::isfinite(radius)) throw InputError("--surface " + name + " needs --radius, a positive length in --unit");
    s.radius = radius;
    return s;
  }
  if (!std::filesystem::exists(name))
    throw InputError("--surface '" + name + "': use plane, sphere or cylinder, or a mesh file of the surface (STL, OBJ, PLY)");
  MeshImportOptions options;
  options.metresPerUnit = metresPerUnit;
  options.up = up;
  s.kind = BaseSurface::Kind::Mesh;
  s.name = name;
  s.mesh = std::make_shared<const SurfaceMesh>(heightField(importMesh(name, options).mesh, name));
  return s;
}

}  // namespace tessera
