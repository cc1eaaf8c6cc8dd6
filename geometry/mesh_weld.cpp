#include "geometry/mesh_weld.h"

#include "geometry/point_grid.h"

namespace tessera {

WeldReport weldVertices(TriangleMesh& mesh, double tolerance) {
  WeldReport report;
  const int n = static_cast<int>(mesh.vertices.size());
  std::vector<int> representative(n, -1);
  std::vector<Eigen::Vector3d> kept;
  PointGrid grid(tolerance > 0 ? tolerance : 1e-12);
  for (int v = 0; v < n; ++v) {
    const Eigen::Vector3d& p = mesh.vertices[v];
    int match = -1;
    grid.forEachNear(p, tolerance, [&](int k) {
      if (match < 0 && (kept[k] - p).norm() <= tolerance) match = k;
    });
    if (match < 0) {
      match = static_cast<int>(kept.size());
      kept.push_back(p);
      grid.insert(match, p);
    } else {
      ++report.mergedVertices;
    }
    representative[v] = match;
  }

  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    const std::array<int, 3> w{representative[t[0]], representative[t[1]], representative[t[2]]};
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) {
      ++report.collapsedTriangles;
      continue;
    }
    triangles.push_back(w);
  }

  // Drop vertices no triangle uses, keeping the order of the rest.
  std::vector<int> remap(kept.size(), -1);
  for (const auto& t : triangles)
    for (int v : t) remap[v] = 0;
  std::vector<Eigen::Vector3d> used;
  for (std::size_t v = 0; v < kept.size(); ++v)
    if (remap[v] == 0) {
      remap[v] = static_cast<int>(used.size());
      used.push_back(kept[v]);
    }
  for (auto& t : triangles)
    for (int& v : t) v = remap[v];

  mesh.vertices = std::move(used);
  mesh.triangles = std::move(triangles);
  return report;
}

}  // namespace tessera
