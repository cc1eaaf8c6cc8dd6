#include "geometry/mesh_topology.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <tuple>

namespace tessera {

MeshTopology buildTopology(const TriangleMesh& mesh) {
  struct HalfEdge {
    std::uint64_t key;
    int triangle;
    int corner;
  };
  const int triangleCount = static_cast<int>(mesh.triangles.size());
  std::vector<HalfEdge> halfEdges;
  halfEdges.reserve(3 * mesh.triangles.size());
  for (int t = 0; t < triangleCount; ++t)
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint64_t>(mesh.triangles[t][k]);
      const auto b = static_cast<std::uint64_t>(mesh.triangles[t][(k + 1) % 3]);
      halfEdges.push_back({std::min(a, b) << 32 | std::max(a, b), t, k});
    }
  std::sort(halfEdges.begin(), halfEdges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return std::tie(x.key, x.triangle, x.corner) < std::tie(y.key, y.triangle, y.corner);
  });

  MeshTopology topology;
  topology.triangleEdges.assign(mesh.triangles.size(), {-1, -1, -1});
  for (std::size_t i = 0; i < halfEdges.size();) {
    MeshEdge edge;
    edge.vertices = {static_cast<int>(halfEdges[i].key >> 32), static_cast<int>(halfEdges[i].key & 0xFFFFFFFFu)};
    const int index = static_cast<int>(topology.edges.size());
    std::size_t j = i;
    for (; j < halfEdges.size() && halfEdges[j].key == halfEdges[i].key; ++j) {
      const auto& h = halfEdges[j];
      edge.triangles.push_back(h.triangle);
      if (mesh.triangles[h.triangle][h.corner] == edge.vertices[0]) ++edge.forwardUses;
      topology.triangleEdges[h.triangle][h.corner] = index;
    }
    topology.edges.push_back(std::move(edge));
    i = j;
  }
  return topology;
}

namespace {
int findRoot(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}
}  // namespace

std::vector<int> nonManifoldVertices(const TriangleMesh& mesh, const MeshTopology& topology) {
  // Around a manifold vertex, the incident triangles, joined across the incident edges, form a
  // single fan. Count incident triangles and fan roots per vertex with a union-find over
  // (vertex, triangle) corners.
  const int triangleCount = static_cast<int>(mesh.triangles.size());
  std::vector<int> parent(3 * triangleCount);
  std::iota(parent.begin(), parent.end(), 0);
  const auto cornerOf = [&](int t, int v) {
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t][k] == v) return 3 * t + k;
    return -1;
  };
  for (const MeshEdge& e : topology.edges) {
    if (e.triangles.size() != 2) continue;
    for (int v : e.vertices) {
      const int a = findRoot(parent, cornerOf(e.triangles[0], v));
      const int b = findRoot(parent, cornerOf(e.triangles[1], v));
      parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<int> fans(mesh.vertices.size(), 0);
  for (int c = 0; c < 3 * triangleCount; ++c)
    if (findRoot(parent, c) == c) ++fans[mesh.triangles[c / 3][c % 3]];
  std::vector<int> bad;
  for (int v = 0; v < static_cast<int>(fans.size()); ++v)
    if (fans[v] > 1) bad.push_back(v);
  return bad;
}

int connectedComponents(const TriangleMesh& mesh, const MeshTopology& topology, std::vector<int>& component) {
  const int triangleCount = static_cast<int>(mesh.triangles.size());
  std::vector<int> parent(triangleCount);
  std::iota(parent.begin(), parent.end(), 0);
  for (const MeshEdge& e : topology.edges)
    for (std::size_t k = 1; k < e.triangles.size(); ++k) {
      const int a = findRoot(parent, e.triangles[0]), b = findRoot(parent, e.triangles[k]);
      parent[std::max(a, b)] = std::min(a, b);
    }
  component.assign(triangleCount, -1);
  std::vector<int> id(triangleCount, -1);
  int count = 0;
  for (int t = 0; t < triangleCount; ++t) {
    const int root = findRoot(parent, t);
    if (id[root] < 0) id[root] = count++;
    component[t] = id[root];
  }
  return count;
}

}  // namespace tessera
