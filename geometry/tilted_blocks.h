#pragma once
#include "geometry/base_surface.h"
#include "geometry/plane_tiling.h"
#include "geometry/triangle_mesh.h"

#include <vector>

namespace tessera {

/// Which way each tile's faces lean (docs/tiling.md, "The sign rule"): tilts[t][k] = +1 when the
/// face of tile t over edge k leans out (the block widens upwards there and rests on the
/// neighbour), -1 when it leans in (it holds the neighbour up). Across a shared edge the two signs
/// are opposite, so the two faces are one plane. Around each tile the signs alternate,
/// tilts[t][k] = c_t (-1)^k, with c_t spread from tile 0 over the tiles (breadth first) so that
/// neighbours agree; where the tiling does not allow that (odd polygons, or parities that do not
/// close around a vertex), an edge whose two tiles disagree takes the sign that keeps both kinds
/// of face on both tiles, and a tile left with one kind borrows an edge from a neighbour with both.
/// Every tile with a neighbour then has a face of each kind, if the tiling allows; and a free tile
/// (freeTile) not yet held against every translation (heldByNeighbours) gets flips that hold it
/// without unholding another, where a few suffice.
/// `angle` (radians) is the faces' angle where the tiling gives none: it matters only when the
/// tiling gives some edges their own (heldByNeighbours).
std::vector<std::vector<int>> interlockingTilts(const PlaneTiling& tiling, const std::vector<std::vector<EdgeNeighbour>>& across,
                                                double angle);

/// The angles heldByNeighbours takes for tile t: none (one angle for every face) unless the
/// tiling gives some edges their own, then each edge's (tileEdgeAngles, `angle` elsewhere).
std::vector<double> heldAngles(const PlaneTiling& tiling, std::size_t t, double angle);

/// A tile with a neighbour across every edge (a free block under the perimeter rule).
bool freeTile(const std::vector<EdgeNeighbour>& across);

/// Whether a tile's block, its neighbours held still, is held against every translation: the
/// outward normals of its faces over edges with a neighbour, n_k = (m_k cos theta_k, -s_k sin theta_k)
/// (s_k = tilts[k]), span space positively, so that every translation moves into some face (by
/// Gordan's theorem, positive weights with sum lambda_k n_k = 0 and the n_k spanning). With one
/// theta for every face (`angles` empty) scaling z does not change that, so it holds at every theta
/// in (0, 90) degrees or at none; `angles` (radians, per edge) gives each face its own.
bool heldByNeighbours(const std::vector<Eigen::Vector2d>& tile, const std::vector<int>& tilts, const std::vector<EdgeNeighbour>& across,
                      const std::vector<double>& angles = {});

/// A vertical plane that bounds a block besides its faces: m . (x - point) <= 0 (plan, m).
struct VerticalCut {
  Eigen::Vector2d point, normal;
};

/// Tiles that share a corner V but no edge can overlap near V: where a tile's two edges at V lean
/// the same way (an odd polygon cannot alternate), its two neighbours across them both grow into
/// its corner (by h/2 tan theta, at the top or at the bottom); where V lies on the tiling's
/// boundary, two tiles can grow towards each other into the empty wedge. The overlap is a cone at
/// V, so it shows in the sections z = +-h/2. Each such pair gets a vertical cut through V along
/// the direction from V to the centroid of their overlap, so they meet on that plane instead.
/// cuts[t]: tile t's cuts. Lengths m, angle radians (each edge's own where the tiling gives one:
/// tileEdgeAngles).
std::vector<std::vector<VerticalCut>> cornerCuts(const PlaneTiling& tiling, const std::vector<std::vector<EdgeNeighbour>>& across,
                                                 const std::vector<std::vector<int>>& tilts, double thickness, double angle);

/// The block of a tile on a base surface: between the planes tangent to the surface at the point
/// over the tile's centroid, offset by +-h/2 along its normal, and, over each edge k, the plane
/// through the edge's chord (its corners lifted onto the surface) that contains the surface normal
/// n_e at the chord's midpoint, tilted about the chord by theta:
///   (o_k cos theta - s_k n_e sin theta) . (x - midpoint) <= 0,  o_k = chord x n_e (outward), s_k = tilts[k],
/// so the face leans out (s = +1: the block widens away from the surface) or in (s = -1). On the
/// plane z = 0 this is m_k . (x - c_k) cos theta - s_k z sin theta <= 0, m_k the edge's outward
/// normal. A face whose plane misses the block is dropped; `cuts` (vertical on the plane; along the
/// surface normal at their corner elsewhere) bound it further. The mesh is built in a frame fixed
/// by the tile's own shape (origin on the surface over the centroid, z along the normal there, x
/// towards the edge that starts the smallest cyclic sequence of sign, length and turn), so tiles
/// equal up to a rigid motion get the same vertices and triangles in the same order, and share one
/// shape when assembled. Lengths m, angle radians.
TriangleMesh tiltedBlock(const std::vector<Eigen::Vector2d>& tile, const std::vector<int>& tilts, const std::vector<VerticalCut>& cuts,
                         double thickness, double angle, const BaseSurface& surface = {});
/// The same with each edge's face at its own angle, angles[k] (radians).
TriangleMesh tiltedBlock(const std::vector<Eigen::Vector2d>& tile, const std::vector<int>& tilts, const std::vector<VerticalCut>& cuts,
                         double thickness, const std::vector<double>& angles, const BaseSurface& surface = {});

}  // namespace tessera
