#pragma once
#include "geometry/closest_point_on_triangle.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tessera {

/// The exact signed distance to a closed triangle mesh near its surface: for each cell of a
/// grid (the voxels of the shape's DenseSdf), the few triangles that can hold the closest
/// point of any point in the cell. Cells farther than `band` from the surface hold none; there the grid's
/// value serves. Read-only and thread-safe.
///
///   phi(x) = s |x - q|,  q the closest point of the mesh to x,
///   s = sign((x - q) . N), N the angle-weighted pseudo-normal of the feature (face, edge or
///   vertex) holding q (Baerentzen & Aanaes, IEEE TVCG 11(3), 2005: the sign is exact for a
///   closed, outward-oriented, manifold mesh),
///   grad phi = s (x - q) / |x - q|  (N / |N| on the surface itself).
struct MeshSdf {
  /// One triangle: corners, unit face normal, and the pseudo-normals of its edges (corner k to
  /// k+1: the sum of the unit normals of the two faces sharing it) and of its corners
  /// (the angle-weighted sum of the unit normals of every face at the vertex).
  ///
  /// For the distance (squaredDistance): the edges e_k = corner k+1 - corner k, 1 / |e_k|^2 (0 for
  /// a degenerate edge), and the unit in-plane outward edge normals m_k = e_k x n / |e_k| (0 for a
  /// degenerate triangle), so that (p - corner_k) . m_k is p's distance beyond edge line k.
  struct Triangle {
    // What squaredDistance reads first, together (272 bytes), then the pseudo-normals.
    std::array<Eigen::Vector3d, 3> corner;
    Eigen::Vector3d normal;
    std::array<Eigen::Vector3d, 3> edge;
    std::array<Eigen::Vector3d, 3> edgeOutward;
    std::array<double, 3> inverseEdgeLength2{0, 0, 0};
    /// The projection of p is on the face when max_k (p - corner_k) . m_k <= faceLimit: 0, or -1
    /// for a degenerate triangle (no face, only its edges).
    double faceLimit = 0.0;
    std::array<Eigen::Vector3d, 3> edgeNormal;
    std::array<Eigen::Vector3d, 3> vertexNormal;
  };
  std::vector<Triangle> triangles;
  Eigen::Vector3d origin{0, 0, 0};        ///< m, lower corner of cell (0, 0, 0)
  double cellSize = 0.0;                   ///< m
  double inverseCellSize = 0.0;            ///< 1/m, 1 / cellSize
  std::array<int, 3> cells{0, 0, 0};       ///< cells along x, y, z
  double band = 0.0;                       ///< m, every point within this distance of the surface has a list
  std::vector<std::uint32_t> cellStart;    ///< cell c's triangles: cellTriangles[cellStart[c] .. cellStart[c + 1])
  std::vector<std::uint32_t> cellTriangles;  ///< each cell's in increasing distance from its centre
  std::vector<float> centreDistance;         ///< m, of each listed triangle from its cell's centre (rounded down)

  bool empty() const { return triangles.empty(); }
  /// m: a cell lists every triangle within its nearest triangle's distance plus this of its
  /// centre (the cell's diagonal: any triangle nearest to a point of the cell is that near).
  double listReach() const { return std::sqrt(3.0) * cellSize; }

  /// What an evaluation leaves for later ones at points near it (the solver keeps one for each
  /// candidate node): the triangle whose face holds the closest point of `at`, and `clearance`,
  /// a distance within which no other triangle comes of `at`. At a later x in the same cell that
  /// projects onto that face, with |phi_T(x)| < clearance - |x - at| (less a rounding margin), the
  /// triangle is still strictly the nearest (every other is at least clearance - |x - at| from x),
  /// so phi and the gradient come from its plane without the search, with the bits the search
  /// would give.
  struct NearestFace {
    Eigen::Vector3d at{0, 0, 0};  ///< m, body frame
    double clearance = -1.0;      ///< m; negative: nothing kept
    std::size_t cell = 0;         ///< the cell of `at`
    std::uint32_t triangle = 0;
  };

  /// The exact phi (m, negative inside) and its unit gradient at x (body frame); false when x's
  /// cell has no triangles (x outside the grid or farther than `band` from the surface).
  bool evaluate(const Eigen::Vector3d& x, double& phi, Eigen::Vector3d& gradient) const {
    Cell cell;
    return locate(x, cell) && search<false>(x, cell, phi, gradient, nullptr);
  }
  /// evaluate, first from the NearestFace `kept` holds if it settles x; else by the search, which
  /// then keeps what it found in it (for a face; else nothing). The same bits either way.
  bool evaluate(const Eigen::Vector3d& x, double& phi, Eigen::Vector3d& gradient, NearestFace& kept) const {
    Cell cell;
    if (!locate(x, cell)) return false;
    // (The same cell: x's list holds the triangle. The clearance holds for the whole mesh, but
    // a point in a cell without a list must get `false`, as from the search.)
    if (kept.clearance > 0 && kept.cell == cell.index && kept.triangle < triangles.size()) {
      const Triangle& t = triangles[kept.triangle];
      const Eigen::Vector3d fromA = x - t.corner[0];
      const double plane = fromA.dot(t.normal);
      // |plane| < clearance - |x - at| - margin, without the square root.
      const double room = kept.clearance - std::abs(plane) - kRoundingMargin * cellSize;
      if (faceOutward(x, fromA, t) <= t.faceLimit && room > 0 && (x - kept.at).squaredNorm() < room * room) {
        phi = plane;
        gradient = t.normal;
        return true;
      }
    }
    return search<true>(x, cell, phi, gradient, &kept);
  }

 private:
  /// The cell of a point: its indices and its index in cellStart.
  struct Cell {
    int i = 0, j = 0, k = 0;
    std::size_t index = 0;
  };
  /// x's cell; false outside the grid (or NaN).
  bool locate(const Eigen::Vector3d& x, Cell& cell) const {
    const Eigen::Vector3d u = (x - origin) * inverseCellSize;
    // Compared as doubles first: NaN and far points never reach the integer conversion.
    if (!(u.minCoeff() >= 0) || !(u[0] < cells[0] && u[1] < cells[1] && u[2] < cells[2])) return false;
    cell.i = static_cast<int>(u[0]);
    cell.j = static_cast<int>(u[1]);
    cell.k = static_cast<int>(u[2]);
    cell.index = (static_cast<std::size_t>(cell.i) * cells[1] + cell.j) * cells[2] + cell.k;
    return true;
  }

  /// The search of x's cell list (evaluate); with Keep, it also fills *kept.
  template <bool Keep>
  bool search(const Eigen::Vector3d& x, const Cell& cell, double& phi, Eigen::Vector3d& gradient, NearestFace* kept) const {
    const std::uint32_t begin = cellStart[cell.index], end = cellStart[cell.index + 1];
    if (begin == end) return false;
    // Triangles in increasing distance from the cell's centre c: once a triangle's distance from c
    // less |x - c| exceeds the best distance so far, neither it nor any later one can be closer.
    const Eigen::Vector3d centre = origin + cellSize * Eigen::Vector3d(cell.i + 0.5, cell.j + 0.5, cell.k + 0.5);
    const double offCentre = (x - centre).norm();
    // The nearest triangle, then its closest point and feature. Each listed triangle is first
    // bounded below by its plane and, in the plane, the edge line x's projection is farthest
    // beyond: |x - q|^2 >= ((x - a) . n)^2 + max(0, max_k (x - a_k) . m_k)^2, exact when x
    // projects onto its face (then the bound is the distance). Only a triangle that bound does not
    // rule out, with x beyond one of its edges, takes the distance to its edges.
    // With Keep, the search goes on past the nearest by kClearanceReach cells (stop2: the square
    // of how far it looks), and the least lower bound of every other triangle (other2, squared)
    // is tracked: the clearance it keeps.
    const double reach = kClearanceReach * cellSize;
    double best = INFINITY, stop2 = INFINITY, other2 = INFINITY;
    std::uint32_t nearest = cellTriangles[begin];
    bool nearestOnFace = false;
    double nearestPlane = 0.0;
    std::uint32_t n = begin;
    for (; n < end; ++n) {
      const double bound = centreDistance[n] - offCentre;
      if (bound > 0 && bound * bound > stop2) break;
      const Triangle& t = triangles[cellTriangles[n]];
      const Eigen::Vector3d fromA = x - t.corner[0];  // corner 0 is on edges 0 and 2
      const double plane = fromA.dot(t.normal);
      const double outward = faceOutward(x, fromA, t);
      const double beyond = std::max(outward, 0.0);
      const double lower = plane * plane + beyond * beyond;
      if (lower >= best) {
        if constexpr (Keep) other2 = std::min(other2, lower);
        continue;
      }
      const bool face = outward <= t.faceLimit;
      const double d2 = face ? plane * plane : edgeSquaredDistance(x, t);
      if (d2 < best) {
        if constexpr (Keep) other2 = std::min(other2, best);
        best = d2;
        nearest = cellTriangles[n];
        nearestOnFace = face;
        nearestPlane = plane;
        if constexpr (Keep) {
          const double look = std::sqrt(best) + reach;
          stop2 = look * look;
        } else {
          stop2 = best;
        }
      } else if constexpr (Keep) {
        other2 = std::min(other2, d2);
      }
    }
    if constexpr (Keep) {
      // Triangles not visited: those after the stop, and those not listed (farther from the
      // cell's centre than the nearest listed one plus listReach()): at least their distance
      // from the centre less |x - c|.
      const double unlisted = centreDistance[begin] + listReach();
      const double notVisited = (n < end ? std::min<double>(centreDistance[n], unlisted) : unlisted) - offCentre;
      kept->clearance = nearestOnFace ? std::min(std::sqrt(other2), notVisited) : -1.0;
      kept->at = x;
      kept->cell = cell.index;
      kept->triangle = nearest;
    }
    // Most points near the surface project onto the face of their nearest triangle: then
    // q = x - ((x - a) . n) n, the feature is the face, phi = (x - a) . n and grad phi = n.
    const Triangle& t = triangles[nearest];
    if (nearestOnFace) {
      phi = nearestPlane;
      gradient = t.normal;
      return true;
    }
    Eigen::Vector3d closest;
    const Eigen::Vector3d* feature = nullptr;
    closestPoint(x, t, closest, feature);
    const Eigen::Vector3d& pseudoNormal = *feature;
    const Eigen::Vector3d away = x - closest;
    const double distance = away.norm();
    const double sign = away.dot(pseudoNormal) < 0 ? -1.0 : 1.0;
    phi = sign * distance;
    gradient = distance > 0 ? Eigen::Vector3d(sign * away / distance) : Eigen::Vector3d(pseudoNormal.normalized());
    return true;
  }

 public:
  /// The search's cells beyond the nearest triangle it looks when it keeps a NearestFace (a
  /// farther look gives a larger clearance, kept for more steps), and the rounding margin of the
  /// NearestFace test, in cells: the distances it compares are rounded to about 1e-16 of the
  /// coordinates (body frame, within the grid), far below 1e-9 cells for any grid of fewer than
  /// 10^6 cells a side.
  static constexpr double kClearanceReach = 0.1;
  static constexpr double kRoundingMargin = 1e-9;

  /// How far beyond its farthest edge line p projects in t's plane, max_k (p - a_k) . m_k (fromA:
  /// p - corner 0); at most faceLimit when p projects onto the face.
  static double faceOutward(const Eigen::Vector3d& p, const Eigen::Vector3d& fromA, const Triangle& t) {
    return std::max({fromA.dot(t.edgeOutward[0]), fromA.dot(t.edgeOutward[2]), (p - t.corner[1]).dot(t.edgeOutward[1])});
  }

  /// Whether p projects onto the face of t (inside or on its edges; never for a degenerate t).
  static bool onFace(const Eigen::Vector3d& p, const Triangle& t) { return faceOutward(p, p - t.corner[0], t) <= t.faceLimit; }

  /// |p - q|^2 for the closest point q of triangle t: the distance to the face's plane when p
  /// projects onto the face, else the least distance to its three edges (segments: the closest
  /// point of a triangle whose plane projection misses it is on its boundary).
  static double squaredDistance(const Eigen::Vector3d& p, const Triangle& t) {
    if (!onFace(p, t)) return edgeSquaredDistance(p, t);
    const double plane = (p - t.corner[0]).dot(t.normal);
    return plane * plane;
  }

  /// The least |p - q|^2 over the three edges (segments) of t.
  static double edgeSquaredDistance(const Eigen::Vector3d& p, const Triangle& t) {
    double edges = INFINITY;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d from = p - t.corner[k];
      const double along = std::clamp(from.dot(t.edge[k]) * t.inverseEdgeLength2[k], 0.0, 1.0);
      edges = std::min(edges, (from - along * t.edge[k]).squaredNorm());
    }
    return edges;
  }

  /// The closest point q of triangle t to p and the pseudo-normal of the feature holding it.
  static void closestPoint(const Eigen::Vector3d& p, const Triangle& t, Eigen::Vector3d& q,
                           const Eigen::Vector3d*& feature) {
    const ClosestPointOnTriangle closest = closestPointOnTriangle(p, t.corner[0], t.corner[1], t.corner[2]);
    q = closest.point;
    switch (closest.feature) {
      case TriangleFeature::CornerA: feature = &t.vertexNormal[0]; break;
      case TriangleFeature::CornerB: feature = &t.vertexNormal[1]; break;
      case TriangleFeature::CornerC: feature = &t.vertexNormal[2]; break;
      case TriangleFeature::EdgeAB: feature = &t.edgeNormal[0]; break;
      case TriangleFeature::EdgeBC: feature = &t.edgeNormal[1]; break;
      case TriangleFeature::EdgeCA: feature = &t.edgeNormal[2]; break;
      case TriangleFeature::Face: feature = &t.normal; break;
    }
  }
};

}  // namespace tessera
