#include "geometry/surface_nodes.h"

#include "geometry/input_error.h"
#include "geometry/point_grid.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace tessera {

namespace {

// Stop farthest-point sampling once every quadrature point is this close to a node, in units of
// the spacing. Measured: it gives a mean nearest-node distance close to the spacing
// (docs/geometry.md, "Surface nodes").
constexpr double kCoverageRadius = 0.9;

struct QuadraturePoint {
  Eigen::Vector3d position;
  Eigen::Vector3d normal;  // unit normal of its triangle
  double area;
};

// Splits triangle t into k^2 congruent sub-triangles (k = ceil(longest edge / h)) and returns
// their centroids with area A / k^2 each; the areas sum exactly to A.
void appendQuadrature(const TriangleMesh& mesh, int t, double h, std::vector<QuadraturePoint>& out) {
  const Eigen::Vector3d a = triangleCorner(mesh, t, 0), b = triangleCorner(mesh, t, 1), c = triangleCorner(mesh, t, 2);
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const int k = std::max(1, static_cast<int>(std::ceil(longest / h)));
  const Eigen::Vector3d areaVector = (b - a).cross(c - a);
  const Eigen::Vector3d normal = areaVector.normalized();
  const double subArea = 0.5 * areaVector.norm() / (static_cast<double>(k) * k);
  const Eigen::Vector3d du = (b - a) / k, dv = (c - a) / k;
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      out.push_back({a + (i + 1.0 / 3.0) * du + (j + 1.0 / 3.0) * dv, normal, subArea});      // upward
      if (i + j < k - 1) out.push_back({a + (i + 2.0 / 3.0) * du + (j + 2.0 / 3.0) * dv, normal, subArea});  // downward
    }
}

struct SeedNode {
  Eigen::Vector3d position;
  NodeKind kind;
};

// Points along a polyline at equal arc length, at most `spacing` apart, excluding the ends
// (an open chain's ends are corners, which carry their own nodes). A closed loop gets >= 3.
std::vector<Eigen::Vector3d> pointsAlongChain(const TriangleMesh& mesh, const FeatureChain& chain, double spacing) {
  std::vector<double> arc{0.0};
  for (std::size_t i = 1; i < chain.vertices.size(); ++i)
    arc.push_back(arc.back() + (mesh.vertices[chain.vertices[i]] - mesh.vertices[chain.vertices[i - 1]]).norm());
  const double length = arc.back();
  int segments = std::max(1, static_cast<int>(std::ceil(length / spacing - 1e-9)));
  if (chain.closed) segments = std::max(3, segments);
  std::vector<Eigen::Vector3d> points;
  std::size_t piece = 1;
  for (int s = chain.closed ? 0 : 1; s < segments; ++s) {
    const double target = length * s / segments;
    while (piece + 1 < arc.size() && arc[piece] < target) ++piece;
    const double span = arc[piece] - arc[piece - 1];
    const double w = span > 0 ? (target - arc[piece - 1]) / span : 0.0;
    points.push_back((1 - w) * mesh.vertices[chain.vertices[piece - 1]] + w * mesh.vertices[chain.vertices[piece]]);
  }
  return points;
}

// Farthest-point sampling of one patch, seeded with its edge and corner nodes. Appends the
// patch's nodes with their Voronoi areas and normals to `out`.
void samplePatch(int patch, const std::vector<SeedNode>& seeds, const std::vector<QuadraturePoint>& quad,
                 double spacing, SurfaceNodes& out) {
  const int n = static_cast<int>(quad.size());
  if (n == 0) return;

  // distance[i]: from quadrature point i to its nearest node, capped at `cap`; nearest[i]: that
  // node. The cap keeps every update local; while distances sit at the cap, the picks pack the
  // patch greedily in index order, then farthest-point sampling proper refines the packing.
  const double cap = 2.0 * spacing;
  std::vector<double> distance(n, cap);
  std::vector<int> nearest(n, -1);
  PointGrid quadGrid(cap);
  for (int i = 0; i < n; ++i) quadGrid.insert(i, quad[i].position);

  std::vector<Eigen::Vector3d> nodes;
  std::vector<NodeKind> kinds;
  // Max-heap of (distance, -index): the farthest point first, the lowest index among ties.
  std::priority_queue<std::pair<double, int>> heap;
  const auto addNode = [&](const Eigen::Vector3d& x, NodeKind kind, double radius) {
    const int node = static_cast<int>(nodes.size());
    nodes.push_back(x);
    kinds.push_back(kind);
    quadGrid.forEachNear(x, radius, [&](int j) {
      const double dj = (quad[j].position - x).norm();
      if (dj < distance[j]) {
        distance[j] = dj;
        nearest[j] = node;
        heap.push({dj, -j});
      }
    });
  };

  for (const SeedNode& seed : seeds) addNode(seed.position, seed.kind, cap);
  for (int i = 0; i < n; ++i)
    if (nearest[i] < 0) heap.push({cap, -i});
  const double coverage = kCoverageRadius * spacing;
  while (!heap.empty()) {
    const auto [d, negIndex] = heap.top();
    heap.pop();
    const int c = -negIndex;
    if (d != distance[c]) continue;  // stale entry
    if (d < coverage) break;
    addNode(quad[c].position, NodeKind::Face, d);
  }

  // Discrete Voronoi areas and area-weighted normals.
  std::vector<double> area(nodes.size(), 0.0);
  std::vector<Eigen::Vector3d> normal(nodes.size(), Eigen::Vector3d::Zero());
  for (int i = 0; i < n; ++i) {
    area[nearest[i]] += quad[i].area;
    normal[nearest[i]] += quad[i].area * quad[i].normal;
  }
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    if (area[k] <= 0.0) continue;  // a seed that owns no quadrature point carries no load
    out.positions.push_back(nodes[k]);
    out.normals.push_back(normal[k].normalized());
    out.areas.push_back(area[k]);
    out.patches.push_back(patch);
    out.kinds.push_back(kinds[k]);
  }
}

}  // namespace

SurfaceNodes sampleSurfaceNodes(const TriangleMesh& mesh, const MeshFeatures& features,
                                const SurfaceNodeOptions& options) {
  if (!(options.spacing > 0.0)) throw InputError("node spacing must be positive");
  const double spacing = options.spacing;

  // Seeds (corner and edge nodes) of each patch.
  std::vector<std::vector<SeedNode>> seeds(features.patchCount);
  std::vector<std::vector<int>> trianglesAt(mesh.vertices.size());
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    for (int v : mesh.triangles[t]) trianglesAt[v].push_back(t);
  for (int v : features.corners) {
    std::vector<int> patches;
    for (int t : trianglesAt[v]) patches.push_back(features.trianglePatch[t]);
    std::sort(patches.begin(), patches.end());
    patches.erase(std::unique(patches.begin(), patches.end()), patches.end());
    for (int p : patches) seeds[p].push_back({mesh.vertices[v], NodeKind::Corner});
  }
  for (const FeatureChain& chain : features.chains)
    for (const Eigen::Vector3d& x : pointsAlongChain(mesh, chain, spacing))
      for (int p : chain.patches) seeds[p].push_back({x, NodeKind::Edge});

  // Quadrature points of each patch.
  std::vector<std::vector<QuadraturePoint>> quad(features.patchCount);
  const double h = spacing / std::max(1, options.quadraturePerSpacing);
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    appendQuadrature(mesh, t, h, quad[features.trianglePatch[t]]);

  SurfaceNodes out;
  for (int p = 0; p < features.patchCount; ++p) samplePatch(p, seeds[p], quad[p], spacing, out);
  return out;
}

}  // namespace tessera
