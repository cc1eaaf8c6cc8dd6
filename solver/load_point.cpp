// Where the indenter comes down (docs/scene.md, [indenter]).
#include "solver/load_point.h"

#include "solver/indentation.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace tessera {

namespace {

// The highest point of body i's surface on the vertical line through (x, y), if the line meets it.
std::optional<double> topAt(const World& world, const Bundle& bundle, int i, const Eigen::Vector2d& at) {
  const RigidBodies& b = world.bodies();
  const TriangleMesh& mesh = bundle.shapes[b.shape[i]].mesh;
  std::optional<double> top;
  for (const auto& t : mesh.triangles) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = b.orientation[i] * mesh.vertices[t[k]] + b.position[i];
    // Barycentric coordinates of (x, y) in the triangle's plan projection.
    const Eigen::Vector2d e1 = (p[1] - p[0]).head<2>(), e2 = (p[2] - p[0]).head<2>(), r = at - p[0].head<2>();
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    if (std::abs(det) < 1e-30) continue;  // a vertical triangle
    const double u = (r.x() * e2.y() - r.y() * e2.x()) / det, v = (e1.x() * r.y() - e1.y() * r.x()) / det;
    if (u < 0 || v < 0 || u + v > 1) continue;
    const double z = p[0].z() + u * (p[1] - p[0]).z() + v * (p[2] - p[0]).z();
    top = top ? std::max(*top, z) : z;
  }
  return top;
}

std::string planPoint(const Eigen::Vector2d& p) {
  char buffer[80];
  std::snprintf(buffer, sizeof buffer, "(%.4g, %.4g) mm", p.x() * 1e3, p.y() * 1e3);
  return buffer;
}

}  // namespace

LoadPoint chooseLoadPoint(const World& world, const Bundle& bundle, const IndenterSettings& indenter) {
  const RigidBodies& bodies = world.bodies();
  LoadPoint load;
  Eigen::Vector2d& at = load.at;
  if (indenter.atPoint) {
    // The body whose surface is highest on the vertical through the point.
    at = indenter.point;
    double highest = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(bodies.size()); ++i)
      if (const auto top = topAt(world, bundle, i, at); top && *top > highest) {
        highest = *top;
        load.body = i;
      }
    if (load.body < 0) throw std::invalid_argument("indenter.point " + planPoint(at) + " lies on no body of the slab");
    if (bodies.fixed[load.body])
      throw std::invalid_argument("indenter.point " + planPoint(at) + " lies on the fixed body '" + bodies.name[load.body] +
                                  "'; choose a point on a free body");
  } else {
    if (!indenter.target.empty()) {
      for (std::size_t i = 0; i < bodies.size(); ++i)
        if (bodies.name[i] == indenter.target) load.body = static_cast<int>(i);
      if (load.body < 0) throw std::invalid_argument("indenter.target '" + indenter.target + "' is not a body of the bundle");
      if (bodies.fixed[load.body])
        throw std::invalid_argument("indenter.target '" + indenter.target + "' is a fixed body; name a free one");
    } else {
      load.body = centralFreeBody(world);
      if (load.body < 0) throw std::invalid_argument("the bundle has no free body to load");
    }
    at = bodies.position[load.body].head<2>() + indenter.offset;
    if (!indenter.offset.isZero() && !topAt(world, bundle, load.body, at))
      throw std::invalid_argument("indenter.offset puts the indenter at " + planPoint(at) + ", off the body '" +
                                  bodies.name[load.body] + "'; use a smaller offset");
  }
  return load;
}

}  // namespace tessera
