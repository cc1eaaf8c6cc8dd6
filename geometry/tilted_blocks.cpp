#include "geometry/tilted_blocks.h"

#include "geometry/convex_polyhedron.h"
#include "io/input_error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>

namespace tessera {

namespace {

int pattern(int k) { return k % 2 == 0 ? 1 : -1; }

bool hasBothSigns(const std::vector<int>& signs, const std::vector<EdgeNeighbour>& across) {
  bool out = false, in = false;
  for (std::size_t k = 0; k < signs.size(); ++k)
    if (across[k].tile >= 0) (signs[k] > 0 ? out : in) = true;
  return out && in;
}

// The edge that starts the smallest cyclic sequence of (sign, angle, length, turn), each rounded to
// 1e-6: lengths of the corners lifted onto the surface, turns in plan.
int canonicalStart(const std::vector<Eigen::Vector2d>& tile, const std::vector<Eigen::Vector3d>& corners, const std::vector<int>& tilts,
                   const std::vector<double>& angles) {
  const int n = static_cast<int>(tile.size());
  double size = 0;
  for (const Eigen::Vector2d& x : tile) size = std::max(size, x.norm());
  std::vector<std::array<long long, 4>> key(n);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d e = tile[(k + 1) % n] - tile[k], f = tile[(k + 2) % n] - tile[(k + 1) % n];
    key[k] = {tilts[k], std::llround(1e6 * angles[k]), std::llround(1e6 * (corners[(k + 1) % n] - corners[k]).norm() / size),
              std::llround(1e6 * std::atan2(e.x() * f.y() - e.y() * f.x(), e.dot(f)))};
  }
  int best = 0;
  for (int start = 1; start < n; ++start)
    for (int i = 0; i < n; ++i) {
      const auto& a = key[(start + i) % n];
      const auto& b = key[(best + i) % n];
      if (a != b) {
        if (a < b) best = start;
        break;
      }
    }
  return best;
}

// A search for flips that hold an unheld tile t: flip one of its edges so that t is held (or it
// is fixed), the tile u across it then held too, or fixed, or itself held by a further flip, up to
// `depth` tiles on; the flips are kept where it succeeds and undone where it does not.
// A tile on the perimeter is not held (it has no neighbour over some edge); it keeps faces of
// both kinds where it had them (`mixed`).
struct HoldingSearch {
  const PlaneTiling& tiling;
  const std::vector<std::vector<EdgeNeighbour>>& across;
  std::vector<std::vector<int>>& tilts;
  double angle;  // radians, of the edges the tiling gives none (heldAngles)
  std::vector<char> onPath, mixed;

  bool held(int t) const {
    return freeTile(across[t]) ? heldByNeighbours(tiling.tiles[t], tilts[t], across[t], heldAngles(tiling, t, angle))
                               : !mixed[t] || hasBothSigns(tilts[t], across[t]);
  }
  void flip(int t, int k) {
    tilts[t][k] = -tilts[t][k];
    tilts[across[t][k].tile][across[t][k].edge] = -tilts[t][k];
  }
  bool hold(int t, int depth) {
    onPath[t] = 1;
    for (int k = 0; k < static_cast<int>(across[t].size()); ++k) {
      const int u = across[t][k].tile;
      if (u < 0 || onPath[u]) continue;
      flip(t, k);
      if (held(t) && (held(u) || (depth > 0 && hold(u, depth - 1)))) {
        onPath[t] = 0;
        return true;
      }
      flip(t, k);
    }
    onPath[t] = 0;
    return false;
  }
};

}  // namespace

bool freeTile(const std::vector<EdgeNeighbour>& across) {
  return std::all_of(across.begin(), across.end(), [](const EdgeNeighbour& e) { return e.tile >= 0; });
}

bool heldByNeighbours(const std::vector<Eigen::Vector2d>& tile, const std::vector<int>& tilts, const std::vector<EdgeNeighbour>& across,
                      const std::vector<double>& angles) {
  std::vector<Eigen::Vector3d> n;
  for (std::size_t k = 0; k < tile.size(); ++k) {
    if (across[k].tile < 0) continue;
    const Eigen::Vector2d m = (tile[(k + 1) % tile.size()] - tile[k]).normalized();
    // One angle for every face: any in (0, 90) degrees gives the same verdict; 45 is used.
    const double theta = angles.empty() ? M_PI / 4 : angles[k];
    n.push_back(Eigen::Vector3d(m.y() * std::cos(theta), -m.x() * std::cos(theta), -tilts[k] * std::sin(theta)));
  }
  // Positively spanning: no v != 0 with v . n_k <= 0 for every k. Were there one, the cone of the
  // n_k would be flat or have a facet, and a facet holds two independent n_k: v is one of the
  // n_i x n_j, either way round.
  constexpr double kFlat = 1e-9;
  bool spans = false;
  for (std::size_t i = 0; i < n.size(); ++i)
    for (std::size_t j = i + 1; j < n.size(); ++j) {
      const Eigen::Vector3d v = n[i].cross(n[j]);
      if (v.norm() < kFlat) continue;
      bool above = false, below = false;
      for (const Eigen::Vector3d& m : n) {
        const double side = m.dot(v);
        spans = spans || std::abs(side) > kFlat * v.norm();
        above = above || side > kFlat * v.norm();
        below = below || side < -kFlat * v.norm();
      }
      if (!above || !below) return false;
    }
  return spans;
}

std::vector<double> heldAngles(const PlaneTiling& tiling, std::size_t t, double angle) {
  return tiling.edgeAngles.empty() ? std::vector<double>{} : tileEdgeAngles(tiling, t, angle);
}

std::vector<std::vector<int>> interlockingTilts(const PlaneTiling& tiling, const std::vector<std::vector<EdgeNeighbour>>& across, double angle) {
  const int count = static_cast<int>(tiling.tiles.size());
  std::vector<int> c(count, 0);
  // c_t spread breadth first: c_u (-1)^l = -c_t (-1)^k across edge k of t = edge l of u.
  for (int root = 0; root < count; ++root) {
    if (c[root] != 0) continue;
    c[root] = 1;
    std::queue<int> queue;
    queue.push(root);
    while (!queue.empty()) {
      const int t = queue.front();
      queue.pop();
      for (int k = 0; k < static_cast<int>(across[t].size()); ++k) {
        const EdgeNeighbour& u = across[t][k];
        if (u.tile < 0 || c[u.tile] != 0) continue;
        c[u.tile] = -c[t] * pattern(k) * pattern(u.edge);
        queue.push(u.tile);
      }
    }
  }
  std::vector<std::vector<int>> tilts(count);
  for (int t = 0; t < count; ++t)
    for (int k = 0; k < static_cast<int>(tiling.tiles[t].size()); ++k) tilts[t].push_back(c[t] * pattern(k));
  // Edges whose two tiles disagree: the sign that leaves both tiles with both kinds of face.
  for (int t = 0; t < count; ++t)
    for (int k = 0; k < static_cast<int>(across[t].size()); ++k) {
      const EdgeNeighbour& u = across[t][k];
      if (u.tile <= t || tilts[t][k] == -tilts[u.tile][u.edge]) continue;  // each shared edge once; agreeing
      tilts[u.tile][u.edge] = -tilts[t][k];
      if (!hasBothSigns(tilts[u.tile], across[u.tile])) {
        tilts[t][k] = -tilts[t][k];
        tilts[u.tile][u.edge] = -tilts[t][k];
      }
    }
  // A tile with one kind of face borrows an edge from a neighbour that keeps both kinds.
  for (int t = 0; t < count; ++t) {
    if (hasBothSigns(tilts[t], across[t])) continue;
    for (int k = 0; k < static_cast<int>(across[t].size()); ++k) {
      const EdgeNeighbour& u = across[t][k];
      if (u.tile < 0) continue;
      std::vector<int> flipped = tilts[u.tile];
      flipped[u.edge] = -flipped[u.edge];
      if (!hasBothSigns(flipped, across[u.tile])) continue;
      tilts[u.tile] = flipped;
      tilts[t][k] = -tilts[t][k];
      break;
    }
  }
  // A free tile not yet held against every translation: flips that hold it without unholding
  // another, along a path of up to kHoldingDepth neighbours (which can carry the defect to the
  // fixed perimeter). A tiling that alternates everywhere has none to mend; a triangle is never
  // held (docs/tiling.md), so it keeps its signs.
  constexpr int kHoldingDepth = 4;
  HoldingSearch search{tiling, across, tilts, angle, std::vector<char>(count, 0), std::vector<char>(count, 0)};
  for (int t = 0; t < count; ++t) search.mixed[t] = hasBothSigns(tilts[t], across[t]);
  for (int t = 0; t < count; ++t)
    if (!search.held(t)) search.hold(t, kHoldingDepth);
  return tilts;
}

std::vector<std::vector<VerticalCut>> cornerCuts(const PlaneTiling& tiling, const std::vector<std::vector<EdgeNeighbour>>& across,
                                                 const std::vector<std::vector<int>>& tilts, double thickness, double angle) {
  const int count = static_cast<int>(tiling.tiles.size());
  std::vector<std::vector<double>> tangents(count);  // tan(theta) of each tile's edges
  for (int t = 0; t < count; ++t)
    for (const double theta : tileEdgeAngles(tiling, t, angle)) tangents[t].push_back(std::tan(theta));
  double size = 0;
  for (const auto& tile : tiling.tiles)
    for (const Eigen::Vector2d& x : tile) size = std::max(size, x.norm());
  const double tolerance = 1e-7 * size;
  // Tile t's section at height z: each edge's line moved out by s z tan(theta).
  const auto section = [&](int t, double z) {
    const auto& p = tiling.tiles[t];
    const Eigen::Vector2d centre = polygonCentroid(p);
    double reach = 0;
    for (const Eigen::Vector2d& x : p) reach = std::max(reach, (x - centre).norm());
    reach = 2 * (reach + thickness);
    std::vector<Eigen::Vector2d> s{centre + Eigen::Vector2d(-reach, -reach), centre + Eigen::Vector2d(reach, -reach),
                                   centre + Eigen::Vector2d(reach, reach), centre + Eigen::Vector2d(-reach, reach)};
    for (std::size_t k = 0; k < p.size(); ++k) {
      const Eigen::Vector2d e = (p[(k + 1) % p.size()] - p[k]).normalized(), m(e.y(), -e.x());
      s = clipPolygon(s, m, m.dot(p[k]) + tilts[t][k] * z * tangents[t][k]);
    }
    return s;
  };
  // The area of the overlap of two tiles' sections at height z.
  const auto overlapArea = [&](int a, int b, double z) {
    std::vector<Eigen::Vector2d> s = section(a, z);
    const auto& p = tiling.tiles[b];
    for (std::size_t k = 0; k < p.size() && s.size() >= 3; ++k) {
      const Eigen::Vector2d e = (p[(k + 1) % p.size()] - p[k]).normalized(), m(e.y(), -e.x());
      s = clipPolygon(s, m, m.dot(p[k]) + tilts[b][k] * z * tangents[b][k]);
    }
    return s.size() < 3 ? 0.0 : polygonArea(s);
  };
  // Corners, sorted by x, to find the tiles that share one.
  struct Corner {
    Eigen::Vector2d x;
    int tile;
  };
  std::vector<Corner> corners;
  for (int t = 0; t < count; ++t)
    for (const Eigen::Vector2d& x : tiling.tiles[t]) corners.push_back({x, t});
  std::sort(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) { return a.x.x() < b.x.x(); });
  std::vector<std::vector<VerticalCut>> cuts(count);
  for (std::size_t i = 0; i < corners.size(); ++i)
    for (std::size_t j = i + 1; j < corners.size() && corners[j].x.x() - corners[i].x.x() <= tolerance; ++j) {
      const int a = std::min(corners[i].tile, corners[j].tile), b = std::max(corners[i].tile, corners[j].tile);
      if (a == b || (corners[i].x - corners[j].x).norm() > tolerance ||
          std::any_of(across[a].begin(), across[a].end(), [&](const EdgeNeighbour& e) { return e.tile == b; }))
        continue;
      if (std::max(overlapArea(a, b, thickness / 2), overlapArea(a, b, -thickness / 2)) <= 1e-12 * size * size) continue;
      // The plane through V that bisects the directions from V to the two tiles' centroids.
      const Eigen::Vector2d& v = corners[i].x;
      const Eigen::Vector2d normal = ((polygonCentroid(tiling.tiles[b]) - v).normalized() - (polygonCentroid(tiling.tiles[a]) - v).normalized()).normalized();
      for (const int t : {a, b})
        for (const Eigen::Vector2d& x : tiling.tiles[t])
          if ((t == a ? 1 : -1) * normal.dot(x - v) > tolerance)
            throw InputError("tiles " + tiling.names[a] + " and " + tiling.names[b] + " would overlap at their shared corner, and no vertical plane "
                             "through it separates them; use a smaller --angle (or smaller angle_<degrees> groups in a tiling file) or a tiling whose "
                             "tiles have an even number of edges");
      cuts[a].push_back({v, normal});
      cuts[b].push_back({v, -normal});
    }
  return cuts;
}

TriangleMesh tiltedBlock(const std::vector<Eigen::Vector2d>& tile, const std::vector<int>& tilts, const std::vector<VerticalCut>& cuts,
                         double thickness, double angle, const BaseSurface& surface) {
  return tiltedBlock(tile, tilts, cuts, thickness, std::vector<double>(tile.size(), angle), surface);
}

TriangleMesh tiltedBlock(const std::vector<Eigen::Vector2d>& tile, const std::vector<int>& tilts, const std::vector<VerticalCut>& cuts,
                         double thickness, const std::vector<double>& angles, const BaseSurface& surface) {
  if (!(thickness > 0) || !std::isfinite(thickness)) throw InputError("tilted block: the thickness must be positive");
  if (angles.size() != tile.size()) throw InputError("tilted block: one angle per edge of the tile is needed");
  if (!std::all_of(angles.begin(), angles.end(), [](double a) { return a >= 0 && a < M_PI / 2; }))
    throw InputError("tilted block: the angle must lie in [0, 90) degrees");
  const int n = static_cast<int>(tile.size());
  std::vector<Eigen::Vector3d> corners;
  for (const Eigen::Vector2d& x : tile) corners.push_back(surface.point(x));
  // The tile's own frame: origin on the surface over its centroid, z along the surface normal
  // there, x along the outward normal of edge `start` (made perpendicular to z).
  const Eigen::Vector3d origin = surface.point(polygonCentroid(tile));
  const Eigen::Vector3d up = surface.normal(origin);
  const int start = canonicalStart(tile, corners, tilts, angles);
  const Eigen::Vector3d d0 = corners[(start + 1) % n] - corners[start];
  const Eigen::Vector3d x0 = (d0.cross(up) - d0.cross(up).dot(up) * up).normalized();
  Eigen::Matrix3d frame;  // columns: the frame's axes in the world
  frame << x0, up.cross(x0), up;
  // A world plane n . x <= d in the frame.
  std::vector<FacePlane> planes;
  const auto add = [&](const Eigen::Vector3d& normal, const Eigen::Vector3d& through) {
    planes.push_back({frame.transpose() * normal, normal.dot(through - origin)});
  };
  add(up, origin + 0.5 * thickness * up);
  add(-up, origin - 0.5 * thickness * up);
  for (int i = 0; i < n; ++i) {
    // The face over edge k contains the edge's chord; untilted it contains the surface normal at
    // the chord's midpoint (perpendicular to the chord), tilted it leans by theta about the chord.
    const int k = (start + i) % n;
    const Eigen::Vector3d &a = corners[k], &b = corners[(k + 1) % n];
    const Eigen::Vector3d middle = 0.5 * (a + b), normal = surface.normal(middle);
    const Eigen::Vector3d outward = (b - a).cross(normal).normalized();  // outward for a counter-clockwise tile
    add(outward * std::cos(angles[k]) - tilts[k] * std::sin(angles[k]) * normal, middle);
  }
  for (const VerticalCut& cut : cuts) {
    const Eigen::Vector3d point = surface.point(cut.point), normal = surface.normal(point);
    const Eigen::Vector3d lifted(cut.normal.x(), cut.normal.y(), 0);
    add((lifted - lifted.dot(normal) * normal).normalized(), point);
  }
  double size = thickness;
  for (const Eigen::Vector3d& x : corners) size = std::max(size, (x - origin).norm());
  TriangleMesh mesh = convexPolyhedronFromPlanes(planes, size + thickness);
  for (Eigen::Vector3d& x : mesh.vertices) x = frame * x + origin;
  return mesh;
}

}  // namespace tessera
