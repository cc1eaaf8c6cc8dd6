#include "geometry/mesh_pieces.h"

#include "geometry/mesh_topology.h"

#include <unordered_map>

namespace tessera {

std::vector<TriangleMesh> splitPieces(const TriangleMesh& mesh) {
  std::vector<int> component;
  const int count = connectedComponents(mesh, buildTopology(mesh), component);
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
