#include "levelset/interlocking_signs.h"

#include "geometry/tilted_blocks.h"
#include "io/input_error.h"
#include "levelset/rigid_block_analysis.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera {

namespace {

// The points of a block's mesh on a plane (within 1e-9 of its size), in the plane's basis (e1, e2)
// about `origin`: its face there, as a convex polygon.
std::vector<Eigen::Vector2d> faceOn(const TriangleMesh& block, const Eigen::Vector3d& origin, const Eigen::Vector3d& normal,
                                    const Eigen::Vector3d& e1, const Eigen::Vector3d& e2, double size) {
  std::vector<Eigen::Vector2d> points;
  for (const Eigen::Vector3d& x : block.vertices)
    if (std::abs(normal.dot(x - origin)) <= 1e-9 * size) points.emplace_back(e1.dot(x - origin), e2.dot(x - origin));
  if (points.size() < 3) return {};
  std::vector<Eigen::Vector2d> hull = convexHull(points);
  return hull.size() < 3 ? std::vector<Eigen::Vector2d>{} : hull;  // a line or a point: no face
}

// The contact polygons shrunk about the mean of their corners by this factor: a slab interlocked
// on smaller polygons is interlocked on any that hold them (more corners, more constraints), so
// the search keeps a margin for the polygons tessera check finds (the hull of the blocks' touching
// surface nodes, simplified). Without it a 20-degree Voronoi slab found interlocked read not so in
// check.
constexpr double kShrink = 0.8;

// The slab's contact corners: over each shared edge k of tile t, the corners of the two blocks'
// common face on its tilted plane (the intersection of each block's face there), shrunk by
// kShrink, the normal from t into its neighbour. The plane is tiltedBlock's: through the edge's
// chord on the surface, its normal o cos theta - s n_e sin theta (o the chord's outward normal
// across the surface, n_e the surface normal at the chord's middle, s = tilts[t][k]); on the plane
// z = 0, (m cos theta, -s sin theta) through the edge.
std::vector<ContactCorner> slabCorners(const PlaneTiling& tiling, const std::vector<std::vector<EdgeNeighbour>>& across,
                                       const std::vector<std::vector<int>>& tilts, const std::vector<TriangleMesh>& blocks,
                                       double angle, const BaseSurface& surface, double size) {
  std::vector<ContactCorner> corners;
  int polygons = 0;
  for (int t = 0; t < static_cast<int>(tiling.tiles.size()); ++t) {
    const std::vector<Eigen::Vector2d>& tile = tiling.tiles[t];
    const std::vector<double> angles = tileEdgeAngles(tiling, t, angle);
    for (int k = 0; k < static_cast<int>(tile.size()); ++k) {
      const int u = across[t][k].tile;
      if (u < t) continue;  // each shared edge once
      const Eigen::Vector3d a = surface.point(tile[k]), b = surface.point(tile[(k + 1) % tile.size()]);
      const Eigen::Vector3d origin = 0.5 * (a + b), up = surface.normal(origin), chord = b - a;
      const Eigen::Vector3d normal = (chord.cross(up).normalized() * std::cos(angles[k]) - tilts[t][k] * std::sin(angles[k]) * up).normalized();
      // e1, e2 in the face's plane, counter-clockwise seen from along its normal (on a mesh surface
      // the interpolated normal need not be square to the chord: e1 is the chord's part in the plane).
      const Eigen::Vector3d e1 = (chord - normal.dot(chord) * normal).normalized(), e2 = normal.cross(e1);
      std::vector<Eigen::Vector2d> common = faceOn(blocks[t], origin, normal, e1, e2, size);
      const std::vector<Eigen::Vector2d> other = faceOn(blocks[u], origin, normal, e1, e2, size);
      for (std::size_t j = 0; j < other.size() && !common.empty(); ++j) {
        const Eigen::Vector2d p = other[j], q = other[(j + 1) % other.size()];
        const Eigen::Vector2d outward(q.y() - p.y(), p.x() - q.x());
        common = clipPolygon(common, outward, outward.dot(p));
      }
      if (other.empty() || common.size() < 3) continue;
      Eigen::Vector2d centroid(0, 0);
      for (const Eigen::Vector2d& x : common) centroid += x / static_cast<double>(common.size());
      for (const Eigen::Vector2d& x : common) {
        const Eigen::Vector2d shrunk = centroid + kShrink * (x - centroid);
        corners.push_back({t, u, origin + shrunk.x() * e1 + shrunk.y() * e2, normal, polygons});
      }
      ++polygons;
    }
  }
  return corners;
}

}  // namespace

InterlockingSearch interlockSigns(const PlaneTiling& tiling, const std::vector<std::vector<EdgeNeighbour>>& across,
                                  const std::vector<char>& fixed, double thickness, double angle, const BaseSurface& surface,
                                  std::vector<std::vector<int>>& tilts) {
  InterlockingSearch search;
  const int count = static_cast<int>(tiling.tiles.size());
  search.tooLarge = count > InterlockingSearch::kMaxTiles;
  if (search.tooLarge || std::none_of(fixed.begin(), fixed.end(), [](char f) { return f != 0; })) return search;
  // The bodies: each block's middle on the surface over its tile's centroid (where tiltedBlock
  // puts its frame); L their median size.
  std::vector<Eigen::Vector3d> centre;
  std::vector<double> sizes;
  for (const std::vector<Eigen::Vector2d>& tile : tiling.tiles) {
    centre.push_back(surface.point(polygonCentroid(tile)));
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector2d& x : tile) box.extend(x);
    sizes.push_back(std::hypot(box.diagonal().norm(), thickness));
  }
  std::nth_element(sizes.begin(), sizes.begin() + count / 2, sizes.end());
  const double length = sizes[count / 2];
  std::vector<char> moving;  // per tile: moved by the last program's way out
  // The program's optimum for the tilts as they are; a trial whose blocks cannot be built (two
  // tiles that meet at a corner would overlap: cornerCuts refuses them) is as bad as none.
  const auto opening = [&](std::vector<char>* movingNow) {
    ++search.programs;
    std::vector<std::vector<VerticalCut>> cuts;
    try {
      cuts = cornerCuts(tiling, across, tilts, thickness, angle);
    } catch (const InputError&) {
      return std::numeric_limits<double>::infinity();
    }
    std::vector<TriangleMesh> blocks;
    for (int t = 0; t < count; ++t) blocks.push_back(tiltedBlock(tiling.tiles[t], tilts[t], cuts[t], thickness, tileEdgeAngles(tiling, t, angle), surface));
    return largestOpening(centre, fixed, length, slabCorners(tiling, across, tilts, blocks, angle, surface, length), movingNow);
  };
  const auto held = [&](int t) { return fixed[t] || heldByNeighbours(tiling.tiles[t], tilts[t], across[t], heldAngles(tiling, t, angle)); };
  const std::vector<std::vector<int>> rule = tilts;
  // Sweeps over the edges next to a tile the last way out moves (where a flip most likely closes
  // it); a sweep that lowers nothing is followed by one over every edge, then the search stops.
  cornerCuts(tiling, across, tilts, thickness, angle);  // the rule's blocks build, or the error is the rule's
  double best = opening(&moving);
  bool near = true;
  for (int sweep = 0; sweep < InterlockingSearch::kSweeps && best > 0; ++sweep) {
    const double before = best;
    std::vector<char> trial;
    for (int t = 0; t < count && best > 0; ++t)
      for (int k = 0; k < static_cast<int>(across[t].size()) && best > 0; ++k) {
        const int u = across[t][k].tile, l = across[t][k].edge;
        if (u < t || (fixed[t] && fixed[u]) || (near && !moving[t] && !moving[u])) continue;
        tilts[t][k] = -tilts[t][k];
        tilts[u][l] = -tilts[u][l];
        const double now = held(t) && held(u) ? opening(&trial) : best;
        if (now < best - 1e-9 * std::max(1.0, best)) {  // not a rounding-level change of the optimum
          best = now;
          moving = trial;
          ++search.flips;
        } else {
          tilts[t][k] = -tilts[t][k];
          tilts[u][l] = -tilts[u][l];
        }
      }
    if (best < before) {
      near = true;
    } else if (near) {
      near = false;
    } else {
      break;
    }
  }
  search.interlocked = best == 0;
  if (!search.interlocked) {
    tilts = rule;
    search.flips = 0;
  }
  return search;
}

}  // namespace tessera
