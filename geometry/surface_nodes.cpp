#include "geometry/surface_nodes.h"

#include "io/input_error.h"
#include "geometry/point_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

namespace tessera {

namespace {

// Stop farthest-point sampling once every candidate point is this close to a node, in units of
// the spacing. Measured: it gives a mean nearest-node distance close to the spacing
// (docs/geometry.md, "Surface nodes").
constexpr double kCoverageRadius = 0.9;
// Candidate points for farthest-point sampling: sub-triangles of edge <= spacing / 4.
constexpr double kCandidatesPerSpacing = 4.0;

struct QuadraturePoint {
  Eigen::Vector3d position;
  double area;
};

// Calls visit(point) for the k^2 congruent sub-triangles of triangle t (k = ceil(longest edge /
// h)): their centroids, each with area A / k^2, so the areas sum exactly to A.
template <class Visit>
void forEachQuadraturePoint(const TriangleMesh& mesh, int t, double h, Visit&& visit) {
  const Eigen::Vector3d a = triangleCorner(mesh, t, 0), b = triangleCorner(mesh, t, 1), c = triangleCorner(mesh, t, 2);
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const int k = std::max(1, static_cast<int>(std::ceil(longest / h)));
  const double subArea = triangleArea(mesh, t) / (static_cast<double>(k) * k);
  const Eigen::Vector3d du = (b - a) / k, dv = (c - a) / k;
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      visit(QuadraturePoint{a + (i + 1.0 / 3.0) * du + (j + 1.0 / 3.0) * dv, subArea});  // upward
      if (i + j < k - 1) visit(QuadraturePoint{a + (i + 2.0 / 3.0) * du + (j + 2.0 / 3.0) * dv, subArea});  // downward
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

struct PatchNodes {
  std::vector<Eigen::Vector3d> positions;
  std::vector<NodeKind> kinds;
};

// Farthest-point sampling of one patch over its candidate points, seeded with its edge and
// corner nodes: repeatedly add the candidate farthest from all nodes, until every candidate is
// within kCoverageRadius x spacing of a node.
PatchNodes farthestPointSample(const std::vector<SeedNode>& seeds, const std::vector<Eigen::Vector3d>& candidates,
                               double spacing) {
  const int n = static_cast<int>(candidates.size());
  // distance[i]: from candidate i to its nearest node, capped at `cap`. The cap keeps every
  // update local; while distances sit at the cap, the picks pack the patch greedily in index
  // order, then farthest-point sampling proper refines the packing.
  const double cap = 2.0 * spacing;
  std::vector<double> distance(n, cap);
  PointGrid grid(cap);
  for (int i = 0; i < n; ++i) grid.insert(i, candidates[i]);

  PatchNodes nodes;
  // Max-heap of (distance, -index): the farthest candidate first, the lowest index among ties.
  std::priority_queue<std::pair<double, int>> heap;
  const auto addNode = [&](const Eigen::Vector3d& x, NodeKind kind, double radius) {
    nodes.positions.push_back(x);
    nodes.kinds.push_back(kind);
    grid.forEachNear(x, radius, [&](int j) {
      const double dj = (candidates[j] - x).norm();
      if (dj < distance[j]) {
        distance[j] = dj;
        heap.push({dj, -j});
      }
    });
  };
  for (const SeedNode& seed : seeds) addNode(seed.position, seed.kind, cap);
  for (int i = 0; i < n; ++i)
    if (distance[i] == cap) heap.push({cap, -i});
  const double coverage = kCoverageRadius * spacing;
  while (!heap.empty()) {
    const auto [d, negIndex] = heap.top();
    heap.pop();
    const int c = -negIndex;
    if (d != distance[c]) continue;  // stale entry
    if (d < coverage) break;
    addNode(candidates[c], NodeKind::Face, d);
  }
  return nodes;
}

// Nearest node of one patch to a stream of nearby points. Points arrive in runs within the same
// grid cell, so the candidate nodes of a cell's neighbourhood are gathered once per run.
class NearestNode {
public:
  NearestNode(const std::vector<Eigen::Vector3d>& nodes, double reach)
      : nodes_(nodes), reach_(reach), grid_(reach) {
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) grid_.insert(i, nodes[i]);
  }

  int operator()(const Eigen::Vector3d& x) {
    const Eigen::Array3i cell = (x.array() / reach_).floor().cast<int>();
    if (!haveCell_ || (cell != cell_).any()) {
      haveCell_ = true;
      cell_ = cell;
      near_.clear();
      grid_.forEachNear((cell.cast<double>() + 0.5) * reach_, reach_, [&](int i) { near_.push_back(i); });
    }
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (int i : near_) {
      const double d = (nodes_[i] - x).squaredNorm();
      if (d < bestDistance || (d == bestDistance && i < best)) {
        bestDistance = d;
        best = i;
      }
    }
    if (best >= 0 && bestDistance <= reach_ * reach_) return best;
    // Beyond the guaranteed reach (cannot happen after coverage): search every node.
    for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
      const double d = (nodes_[i] - x).squaredNorm();
      if (d < bestDistance) {
        bestDistance = d;
        best = i;
      }
    }
    return best;
  }

private:
  const std::vector<Eigen::Vector3d>& nodes_;
  double reach_;
  PointGrid grid_;
  bool haveCell_ = false;
  Eigen::Array3i cell_;
  std::vector<int> near_;
};

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

  // Nodes of each patch by farthest-point sampling over candidate points.
  std::vector<std::vector<Eigen::Vector3d>> candidates(features.patchCount);
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    forEachQuadraturePoint(mesh, t, spacing / kCandidatesPerSpacing,
                           [&](const QuadraturePoint& q) { candidates[features.trianglePatch[t]].push_back(q.position); });
  std::vector<PatchNodes> patchNodes(features.patchCount);
  for (int p = 0; p < features.patchCount; ++p) patchNodes[p] = farthestPointSample(seeds[p], candidates[p], spacing);

  // Area weights: a fine quadrature of each triangle, every point given to the nearest node of
  // its patch. Every candidate is within coverage of a node and every fine point within one
  // candidate cell of a candidate, so the nearest node lies within `reach`.
  const double reach = (kCoverageRadius + 1.0 / kCandidatesPerSpacing) * spacing;
  const double h = spacing / std::max(1, options.quadraturePerSpacing);
  std::vector<std::vector<double>> area(features.patchCount);
  std::vector<std::vector<Eigen::Vector3d>> normal(features.patchCount), centroid(features.patchCount);
  std::vector<NearestNode> nearest;
  nearest.reserve(features.patchCount);
  for (int p = 0; p < features.patchCount; ++p) {
    nearest.emplace_back(patchNodes[p].positions, reach);
    area[p].assign(patchNodes[p].positions.size(), 0.0);
    normal[p].assign(patchNodes[p].positions.size(), Eigen::Vector3d::Zero());
    centroid[p].assign(patchNodes[p].positions.size(), Eigen::Vector3d::Zero());
  }
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const int p = features.trianglePatch[t];
    const Eigen::Vector3d unitNormal = triangleAreaVector(mesh, t).normalized();
    forEachQuadraturePoint(mesh, t, h, [&](const QuadraturePoint& q) {
      const int node = nearest[p](q.position);
      area[p][node] += q.area;
      normal[p][node] += q.area * unitNormal;
      centroid[p][node] += q.area * q.position;
    });
  }

  SurfaceNodes out;
  for (int p = 0; p < features.patchCount; ++p)
    for (std::size_t k = 0; k < patchNodes[p].positions.size(); ++k) {
      if (area[p][k] <= 0.0) continue;  // a seed that owns no quadrature point carries no load
      // The node is the quadrature point of its cell: at the cell's centroid (see the header).
      out.positions.push_back(centroid[p][k] / area[p][k]);
      out.normals.push_back(normal[p][k].normalized());
      out.areas.push_back(area[p][k]);
      out.patches.push_back(p);
      out.kinds.push_back(patchNodes[p].kinds[k]);
    }
  return out;
}

}  // namespace tessera
