#include "levelset/mesh_sdf_builder.h"

#include "geometry/mesh_topology.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace tessera {

namespace {

// The distance from p to the box [lo, hi] (0 inside): a lower bound of its distance to what the box holds.
double boxDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
}

double triangleDistance(const Eigen::Vector3d& p, const MeshSdf::Triangle& t) {
  return std::sqrt(MeshSdf::squaredDistance(p, t));
}

// Unit face normals and the pseudo-normals of edges and vertices (Baerentzen & Aanaes 2005).
std::vector<MeshSdf::Triangle> pseudoNormalTriangles(const TriangleMesh& mesh) {
  const int count = static_cast<int>(mesh.triangles.size());
  std::vector<Eigen::Vector3d> faceNormal(count);
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3d n = triangleAreaVector(mesh, t);
    faceNormal[t] = n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
  }
  // Vertex: sum over its faces of the face's angle at the vertex times its unit normal.
  std::vector<Eigen::Vector3d> vertexNormal(mesh.vertices.size(), Eigen::Vector3d::Zero());
  for (int t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = triangleCorner(mesh, t, (k + 1) % 3) - triangleCorner(mesh, t, k);
      const Eigen::Vector3d e2 = triangleCorner(mesh, t, (k + 2) % 3) - triangleCorner(mesh, t, k);
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      vertexNormal[mesh.triangles[t][k]] += angle * faceNormal[t];
    }
  const MeshTopology topology = buildTopology(mesh);
  std::vector<MeshSdf::Triangle> triangles(count);
  for (int t = 0; t < count; ++t) {
    MeshSdf::Triangle& r = triangles[t];
    r.normal = faceNormal[t];
    for (int k = 0; k < 3; ++k) {
      r.corner[k] = triangleCorner(mesh, t, k);
      r.vertexNormal[k] = vertexNormal[mesh.triangles[t][k]];
      const MeshEdge& edge = topology.edges[topology.triangleEdges[t][k]];
      r.edgeNormal[k] = edge.triangles.size() == 2 ? Eigen::Vector3d(faceNormal[edge.triangles[0]] + faceNormal[edge.triangles[1]])
                                                   : faceNormal[t];
    }
    for (int k = 0; k < 3; ++k) {
      r.edge[k] = r.corner[(k + 1) % 3] - r.corner[k];
      const double length2 = r.edge[k].squaredNorm();
      r.inverseEdgeLength2[k] = length2 > 0 ? 1.0 / length2 : 0.0;
      r.edgeOutward[k] = length2 > 0 ? Eigen::Vector3d(r.edge[k].cross(r.normal) / std::sqrt(length2)) : Eigen::Vector3d::Zero();
    }
    r.faceLimit = r.normal.squaredNorm() > 0 ? 0.0 : -1.0;
  }
  return triangles;
}

}  // namespace

MeshSdf buildMeshSdf(const TriangleMesh& mesh, const DenseSdf& grid, double band) {
  MeshSdf m;
  if (mesh.triangles.empty() || grid.values.empty()) return m;
  m.triangles = pseudoNormalTriangles(mesh);
  // The grid's own voxels as cells (half-voxel cells were measured slower: shorter lists, more
  // cache misses; bench/bench_level_set.cpp).
  m.origin = grid.origin;
  m.cellSize = grid.voxelSize;
  m.inverseCellSize = 1.0 / grid.voxelSize;
  m.band = band;
  for (int a = 0; a < 3; ++a) m.cells[a] = grid.dims[a] - 1;
  const int triangleCount = static_cast<int>(m.triangles.size());
  std::vector<Eigen::Vector3d> lo(triangleCount), hi(triangleCount);
  for (int t = 0; t < triangleCount; ++t) {
    const auto& c = m.triangles[t].corner;
    lo[t] = c[0].cwiseMin(c[1]).cwiseMin(c[2]);
    hi[t] = c[0].cwiseMax(c[1]).cwiseMax(c[2]);
  }
  const double diagonal = std::sqrt(3.0) * m.cellSize;
  const std::size_t cellCount = static_cast<std::size_t>(m.cells[0]) * m.cells[1] * m.cells[2];
  std::vector<std::vector<std::pair<float, std::uint32_t>>> lists(cellCount);  // (distance from the centre, triangle)
  tbb::parallel_for(0, m.cells[0], [&](int i) {
    for (int j = 0; j < m.cells[1]; ++j)
      for (int k = 0; k < m.cells[2]; ++k) {
        // The grid's nodes hold exact distances and phi is 1-Lipschitz: a cell whose nearest
        // corner is farther than band + D from the surface holds no point within band of it.
        double nearest = INFINITY;
        for (int c = 0; c < 8; ++c) nearest = std::min(nearest, std::abs(double(grid.at(i + (c >> 2), j + ((c >> 1) & 1), k + (c & 1)))));
        if (nearest > band + diagonal) continue;
        const Eigen::Vector3d centre = m.origin + m.cellSize * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        double closest = INFINITY;
        for (int t = 0; t < triangleCount; ++t)
          if (boxDistance(centre, lo[t], hi[t]) < closest) closest = std::min(closest, triangleDistance(centre, m.triangles[t]));
        auto& list = lists[(static_cast<std::size_t>(i) * m.cells[1] + j) * m.cells[2] + k];
        const double reach = closest + m.listReach();
        for (int t = 0; t < triangleCount; ++t) {
          if (boxDistance(centre, lo[t], hi[t]) > reach) continue;
          const double d = triangleDistance(centre, m.triangles[t]);
          // Rounded down to float, so that the evaluation's early stop stays conservative.
          if (d <= reach) list.emplace_back(std::nextafter(static_cast<float>(d), 0.0f), static_cast<std::uint32_t>(t));
        }
        std::sort(list.begin(), list.end());
      }
  });
  m.cellStart.assign(cellCount + 1, 0);
  for (std::size_t c = 0; c < cellCount; ++c) m.cellStart[c + 1] = m.cellStart[c] + static_cast<std::uint32_t>(lists[c].size());
  m.cellTriangles.reserve(m.cellStart.back());
  m.centreDistance.reserve(m.cellStart.back());
  for (const auto& list : lists)
    for (const auto& [distance, triangle] : list) {
      m.centreDistance.push_back(distance);
      m.cellTriangles.push_back(triangle);
    }
  return m;
}

}  // namespace tessera
