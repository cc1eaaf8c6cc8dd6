// Where the indenter comes down (docs/scene.md, [indenter]).
#include "run/load_point.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace tessera {

std::pair<double, double> heightRange(const TriangleMesh& mesh, const Eigen::Quaterniond& orientation,
                                      const Eigen::Vector3d& position) {
  double bottom = std::numeric_limits<double>::infinity(), top = -bottom;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    const double z = (orientation * v + position).z();
    bottom = std::min(bottom, z);
    top = std::max(top, z);
  }
  return {bottom, top};
}

std::optional<std::pair<double, double>> verticalExtent(const TriangleMesh& mesh, const Eigen::Quaterniond& orientation,
                                                        const Eigen::Vector3d& position, const Eigen::Vector2d& at) {
  std::optional<std::pair<double, double>> extent;
  for (const auto& t : mesh.triangles) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = orientation * mesh.vertices[t[k]] + position;
    // Barycentric coordinates of (x, y) in the triangle's plan projection.
    const Eigen::Vector2d e1 = (p[1] - p[0]).head<2>(), e2 = (p[2] - p[0]).head<2>(), r = at - p[0].head<2>();
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    if (std::abs(det) < 1e-30) continue;  // a vertical triangle
    const double u = (r.x() * e2.y() - r.y() * e2.x()) / det, v = (e1.x() * r.y() - e1.y() * r.x()) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    const double z = p[0].z() + u * (p[1] - p[0]).z() + v * (p[2] - p[0]).z();
    extent = extent ? std::make_pair(std::min(extent->first, z), std::max(extent->second, z)) : std::make_pair(z, z);
  }
  return extent;
}

double loadedThickness(const TriangleMesh& mesh, const Eigen::Quaterniond& orientation, const Eigen::Vector3d& position,
                       const Eigen::Vector2d& at) {
  if (const auto through = verticalExtent(mesh, orientation, position, at); through && through->second > through->first)
    return through->second - through->first;
  const auto [bottom, top] = heightRange(mesh, orientation, position);
  return top - bottom;
}

std::optional<double> sphereTouchHeight(const SurfaceNodes& nodes, const Eigen::Quaterniond& orientation,
                                        const Eigen::Vector3d& position, const Eigen::Vector2d& at, double radius) {
  std::optional<double> height;
  for (const Eigen::Vector3d& node : nodes.positions) {
    const Eigen::Vector3d x = orientation * node + position;
    const double r2 = (x.head<2>() - at).squaredNorm();
    if (r2 >= radius * radius) continue;
    const double z = x.z() + std::sqrt(radius * radius - r2);
    height = height ? std::max(*height, z) : z;
  }
  return height;
}

namespace {

// The highest point of body i's surface on the vertical line through (x, y), if the line meets it.
std::optional<double> topAt(const Bundle& bundle, int i, const Eigen::Vector2d& at) {
  const Body& body = bundle.bodies[i];
  const auto extent = verticalExtent(bundle.shapes[body.shape].mesh, body.orientation, body.position, at);
  if (!extent) return std::nullopt;
  return extent->second;
}

std::string planPoint(const Eigen::Vector2d& p) {
  char buffer[80];
  std::snprintf(buffer, sizeof buffer, "(%.4g, %.4g) mm", p.x() * 1e3, p.y() * 1e3);
  return buffer;
}

}  // namespace

int centralFreeBody(const Bundle& bundle) {
  const auto& bodies = bundle.bodies;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Body& b : bodies) centre += b.position.head<2>() / static_cast<double>(bodies.size());
  int best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].fixed) continue;
    const double d = (bodies[i].position.head<2>() - centre).norm();
    if (d < bestDistance - 1e-12) {
      bestDistance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

LoadPoint chooseLoadPoint(const Bundle& bundle, const IndenterSettings& indenter) {
  const auto& bodies = bundle.bodies;
  LoadPoint load;
  if (indenter.atPoint) {
    // The body whose surface is highest on the vertical through the point.
    const Eigen::Vector2d& at = indenter.point;
    double highest = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(bodies.size()); ++i)
      if (const auto top = topAt(bundle, i, at); top && *top > highest) {
        highest = *top;
        load.body = i;
      }
    if (load.body < 0) throw std::invalid_argument("indenter.point " + planPoint(at) + " lies on no body of the slab");
    if (bodies[load.body].fixed)
      throw std::invalid_argument("indenter.point " + planPoint(at) + " lies on the fixed body '" + bodies[load.body].name +
                                  "'; choose a point on a free body");
    load.offset = at - bodies[load.body].position.head<2>();
    return load;
  }
  if (!indenter.target.empty()) {
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (bodies[i].name == indenter.target) load.body = static_cast<int>(i);
    if (load.body < 0) throw std::invalid_argument("indenter.target '" + indenter.target + "' is not a body of the bundle");
    if (bodies[load.body].fixed)
      throw std::invalid_argument("indenter.target '" + indenter.target + "' is a fixed body; name a free one");
  } else {
    load.body = centralFreeBody(bundle);
    if (load.body < 0) throw std::invalid_argument("the bundle has no free body to load");
  }
  load.offset = indenter.offset;
  const Eigen::Vector2d at = bodies[load.body].position.head<2>() + load.offset;
  if (!load.offset.isZero() && !topAt(bundle, load.body, at))
    throw std::invalid_argument("indenter.offset puts the indenter at " + planPoint(at) + ", off the body '" +
                                bodies[load.body].name + "'; use a smaller offset");
  return load;
}

}  // namespace tessera
