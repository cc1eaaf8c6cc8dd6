#include "geometry/mesh_features.h"

#include <algorithm>
#include <cmath>

namespace tessera {

namespace {

Eigen::Vector3d unitNormal(const TriangleMesh& mesh, int t) { return triangleAreaVector(mesh, t).normalized(); }

int otherEnd(const MeshEdge& e, int v) { return e.vertices[0] == v ? e.vertices[1] : e.vertices[0]; }

}  // namespace

MeshFeatures findFeatures(const TriangleMesh& mesh, double featureAngle) {
  MeshFeatures f;
  f.topology = buildTopology(mesh);
  const auto& edges = f.topology.edges;
  const double cosFeature = std::cos(featureAngle);

  f.edgeIsSharp.assign(edges.size(), 0);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto& tris = edges[e].triangles;
    f.edgeIsSharp[e] = unitNormal(mesh, tris[0]).dot(unitNormal(mesh, tris[1])) < cosFeature;
  }

  // Patches: flood fill across edges that are not sharp.
  f.trianglePatch.assign(mesh.triangles.size(), -1);
  std::vector<int> stack;
  for (int seed = 0; seed < static_cast<int>(mesh.triangles.size()); ++seed) {
    if (f.trianglePatch[seed] >= 0) continue;
    f.trianglePatch[seed] = f.patchCount;
    stack.push_back(seed);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int e : f.topology.triangleEdges[t]) {
        if (f.edgeIsSharp[e]) continue;
        const int n = otherTriangle(edges[e], t);
        if (f.trianglePatch[n] < 0) {
          f.trianglePatch[n] = f.patchCount;
          stack.push_back(n);
        }
      }
    }
    ++f.patchCount;
  }

  // Sharp edges incident to each vertex.
  std::vector<std::vector<int>> sharpAt(mesh.vertices.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (f.edgeIsSharp[e])
      for (int v : edges[e].vertices) sharpAt[v].push_back(static_cast<int>(e));

  std::vector<char> isCorner(mesh.vertices.size(), 0);
  for (int v = 0; v < static_cast<int>(mesh.vertices.size()); ++v) {
    const auto& s = sharpAt[v];
    bool corner = !s.empty() && s.size() != 2;
    if (s.size() == 2) {
      const Eigen::Vector3d in = (mesh.vertices[v] - mesh.vertices[otherEnd(edges[s[0]], v)]).normalized();
      const Eigen::Vector3d out = (mesh.vertices[otherEnd(edges[s[1]], v)] - mesh.vertices[v]).normalized();
      corner = in.dot(out) < cosFeature;
    }
    if (corner) {
      isCorner[v] = 1;
      f.corners.push_back(v);
    }
  }

  // Chains: walk sharp edges from corner to corner, then the remaining closed loops.
  std::vector<char> used(edges.size(), 0);
  const auto walk = [&](int start, int firstEdge) {
    FeatureChain chain;
    chain.vertices.push_back(start);
    int v = start, e = firstEdge;
    for (;;) {
      used[e] = 1;
      v = otherEnd(edges[e], v);
      chain.vertices.push_back(v);
      if (isCorner[v] || v == start) break;
      const auto& s = sharpAt[v];
      const int next = s[0] == e ? s[1] : s[0];
      if (used[next]) break;
      e = next;
    }
    chain.closed = chain.vertices.back() == start && !isCorner[start];
    for (int t : edges[firstEdge].triangles) chain.patches.push_back(f.trianglePatch[t]);
    std::sort(chain.patches.begin(), chain.patches.end());
    chain.patches.erase(std::unique(chain.patches.begin(), chain.patches.end()), chain.patches.end());
    f.chains.push_back(std::move(chain));
  };
  for (int v : f.corners)
    for (int e : sharpAt[v])
      if (!used[e]) walk(v, e);
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (f.edgeIsSharp[e] && !used[e]) walk(edges[e].vertices[0], static_cast<int>(e));
  return f;
}

}  // namespace tessera
