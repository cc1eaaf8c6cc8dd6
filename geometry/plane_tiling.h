#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

namespace tessera {

/// A tiling of (part of) the plane z = 0 by convex polygons meeting edge to edge. Tile t's corners
/// run counter-clockwise (m); its edge k goes from corner k to corner k + 1.
struct PlaneTiling {
  std::vector<std::string> names;                       ///< one body name per tile
  std::vector<std::vector<Eigen::Vector2d>> tiles;      ///< corners, m
  /// The face angle of edge k of tile t, radians, where the tiling gives one (a tiling file's
  /// `angle_<degrees>` lines: readTilingFile); empty, or NaN for an edge: the slab's angle.
  std::vector<std::vector<double>> edgeAngles;
};

/// The face angle of each edge of tile t: the tiling's own where it gives one, else `angle`. Radians.
std::vector<double> tileEdgeAngles(const PlaneTiling& tiling, std::size_t t, double angle);

/// The built-in tilings (docs/tiling.md, "Generated tilings"), centred at the origin. `pitch` is the
/// distance between the centres of two tiles that share an edge.
///  - square:    columns x rows squares of side p;
///  - hex:       columns x rows hexagons of inradius p/2 (faces normal at 0, 60, ... degrees), odd
///               rows shifted by p/2;
///  - triangle:  rows of `columns` equilateral triangles of side p sqrt 3, alternately pointing up
///               and down;
///  - rhombille: columns x rows hexagons of side 2p/sqrt 3 laid out as `hex`, each cut into three
///               60-degree rhombi that meet at its centre (3 x columns x rows tiles);
///  - voronoi:   the Voronoi cells of columns x rows seeds, one per square of side p jittered by up
///               to 0.35 p (std::mt19937 seeded with `seed`) and moved to their cells' centroids
///               twice (Lloyd), clipped to the columns p x rows p rectangle.
struct TilingOptions {
  std::string kind = "square";  ///< square, hex, triangle, rhombille, voronoi
  double pitch = 10e-3;         ///< m
  int columns = 7, rows = 7;
  unsigned seed = 1;            ///< voronoi only
};
PlaneTiling makeTiling(const TilingOptions& options);

/// The names of the built-in tilings.
const std::vector<std::string>& tilingKinds();
/// Whether `name` is one of them (else it names a tiling file).
bool isTilingKind(const std::string& name);

/// The tile across each edge: across[t][k] = {u, l} when edge k of tile t is edge l of tile u
/// (corners within `tolerance`, m, of each other, in opposite order), {-1, -1} on the boundary.
struct EdgeNeighbour {
  int tile = -1, edge = -1;
};
std::vector<std::vector<EdgeNeighbour>> edgeNeighbours(const PlaneTiling& tiling, double tolerance);

/// The tiles of a polygon mesh (OBJ, PLY, ... through assimp, polygons kept): each face one tile,
/// its corners' (x, y) in `metresPerUnit` after the file's `up` axis is turned into +z
/// (rotationToZUp; the mesh lies in a plane normal to it), turned counter-clockwise. Named
/// "t<face>", the faces numbered in the file's order (its groups as they come). Line segments in
/// a group named `angle_<degrees>`, e.g. `angle_7.5` (the node's name: OBJ's `g` or `o`; else the
/// mesh's), give the tile edges they lie on (end to end, within 1e-6 of the tiling's size) that
/// face angle (edgeAngles); other lines and points are ignored. Throws InputError naming the face
/// for a non-convex or degenerate polygon, for a mesh that does not lie flat, and naming the group
/// for an angle outside [0, 90) degrees, a name that is no number, a segment that is no tile's
/// edge, or an edge in two groups of different angles.
PlaneTiling readTilingFile(const std::string& path, double metresPerUnit, const std::string& up = "z");

/// The part of a convex polygon where n . x <= d (one pass of Sutherland & Hodgman, CACM 17, 1974).
std::vector<Eigen::Vector2d> clipPolygon(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& n, double d);

/// The convex hull of points in the plane, counter-clockwise (Andrew's monotone chain, 1979).
std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> points);

/// The area of a polygon (positive when counter-clockwise) and its centroid.
double polygonArea(const std::vector<Eigen::Vector2d>& polygon);
Eigen::Vector2d polygonCentroid(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace tessera
