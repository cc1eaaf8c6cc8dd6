#include "geometry/mesh_pieces.h"

#include "geometry/mesh_topology.h"

#include <numeric>
#include <unordered_map>

namespace tessera {

std::vector<TriangleMesh> splitPieces(const TriangleMesh& mesh) {
  // Triangles join across edges that two triangles share; an edge of four (two solids that meet
  // along it, welded at their common corners) keeps them apart.
  const MeshTopology topology = buildTopology(mesh);
  std::vector<int> parent(mesh.triangles.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  for (const MeshEdge& e : topology.edges)
    if (e.triangles.size() == 2) {
      const int a = root(e.triangles[0]), b = root(e.triangles[1]);
      parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<int> component(mesh.triangles.size()), id(mesh.triangles.size(), -1);
  int count = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int r = root(static_cast<int>(t));
    if (id[r] < 0) id[r] = count++;
    component[t] = id[r];
  }
  std::vector<TriangleMesh> pieces(count);
  // A vertex belongs to one piece (two only where pieces touch at a point): index by (piece, vertex).
  std::unordered_map<long long, int> newIndex;
  const long long n = static_cast<long long>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int c = component[t];
    std::array<int, 3> triangle{};
    for (int k = 0; k < 3; ++k) {
      const auto [it, added] = newIndex.try_emplace(c * n + mesh.triangles[t][k], static_cast<int>(pieces[c].vertices.size()));
      if (added) pieces[c].vertices.push_back(mesh.vertices[mesh.triangles[t][k]]);
      triangle[k] = it->second;
    }
    pieces[c].triangles.push_back(triangle);
  }
  return pieces;
}

}  // namespace tessera
