#pragma once
#include "geometry/triangle_mesh.h"

#include <array>
#include <vector>

namespace tessera {

/// An undirected mesh edge and the triangles that use it.
struct MeshEdge {
  std::array<int, 2> vertices;  ///< vertices[0] < vertices[1]
  std::vector<int> triangles;   ///< every triangle using the edge, in triangle order
  int forwardUses = 0;          ///< how many of them traverse vertices[0] -> vertices[1]
};

/// Edge-level connectivity of a triangle soup, built by sorting (not hashing), so deterministic.
struct MeshTopology {
  std::vector<MeshEdge> edges;                   ///< sorted by (vertices[0], vertices[1])
  std::vector<std::array<int, 3>> triangleEdges; ///< edge of triangle corner k -> k+1
};

MeshTopology buildTopology(const TriangleMesh& mesh);

/// For an edge used by exactly two triangles: the one that is not `t`.
inline int otherTriangle(const MeshEdge& e, int t) { return e.triangles[0] == t ? e.triangles[1] : e.triangles[0]; }

/// Vertices whose incident triangles do not form one fan (e.g. two cones touching at a tip).
/// Precondition: every edge is used by exactly two triangles.
std::vector<int> nonManifoldVertices(const TriangleMesh& mesh, const MeshTopology& topology);

/// Connected component id of each triangle (across shared edges); returns the component count.
int connectedComponents(const TriangleMesh& mesh, const MeshTopology& topology, std::vector<int>& component);

}  // namespace tessera
