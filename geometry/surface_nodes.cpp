#include "geometry/surface_nodes.h"

#include "io/input_error.h"
#include "geometry/closest_point_on_triangle.h"
#include "geometry/mesh_symmetry.h"
#include "geometry/point_grid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <queue>
#include <stdexcept>

namespace tessera {

namespace {

// Stop farthest-point sampling once every candidate point is this close to a node, in units of
// the spacing. Measured: it gives a mean nearest-node distance close to the spacing
// (docs/geometry.md, "Surface nodes").
constexpr double kCoverageRadius = 0.9;
// Candidate points for farthest-point sampling: sub-triangles of edge <= spacing / 4.
constexpr double kCandidatesPerSpacing = 4.0;
// Images of a node closer than this (in units of the spacing) are one node: a point on a mirror,
// moved by rounding or by a mesh written to single precision.
constexpr double kSamePoint = 1e-3;
// Symmetries are found to this fraction of the block's size (a mesh written to single precision
// is symmetric to about 1e-7 of it).
constexpr double kSymmetryTolerance = 1e-6;

// |a - b|^2 written out: these loops run millions of times, and unoptimized (sanitizer) builds
// do not inline Eigen's expression templates.
inline double squaredDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double x = a[0] - b[0], y = a[1] - b[1], z = a[2] - b[2];
  return x * x + y * y + z * z;
}

struct QuadraturePoint {
  Eigen::Vector3d position;
  double area;
  double spacing;  ///< m, the local node spacing there (a lower bound over the sub-triangle)
};

// The local node spacing l(x) = min(s, s_e + g d(x)): s_e at the sharp edges bounding x's patch,
// growing with the distance d from them by the size gradient g up to the face spacing s (the
// graded-mesh size function of mesh generators, e.g. Persson & Strang, SIAM Review 46(2), 2004).
// Uniform (l = s everywhere, and no distance is computed) when s_e >= s or the mesh has no sharp
// edge.
class LocalSpacing {
public:
  LocalSpacing(const TriangleMesh& mesh, const MeshFeatures& features, const SurfaceNodeOptions& options)
      : face_(options.spacing),
        edge_(options.edgeSpacing > 0 ? std::min(options.edgeSpacing, options.spacing) : options.spacing),
        gradient_(options.sizeGradient),
        band_(uniform() ? 0.0 : (face_ - edge_) / gradient_),
        cell_(std::max(band_, face_)),
        grid_(uniform() ? 1.0 : cell_) {
    if (uniform()) return;
    // The sharp edges in pieces no longer than a cell, each filed under its midpoint. A cell is
    // the band, or the face spacing where a steep gradient makes the band narrower: cells of the
    // band's width made a look-up visit ~(1 / band)^3 empty cells (gradient 100: no end).
    for (const FeatureChain& chain : features.chains)
      for (std::size_t i = 1; i < chain.vertices.size(); ++i) {
        const Eigen::Vector3d a = mesh.vertices[chain.vertices[i - 1]], b = mesh.vertices[chain.vertices[i]];
        const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / cell_)));
        for (int k = 0; k < n; ++k) {
          const Piece piece{a + (b - a) * (static_cast<double>(k) / n), a + (b - a) * (static_cast<double>(k + 1) / n),
                            &chain.patches};
          grid_.insert(static_cast<int>(pieces_.size()), 0.5 * (piece.from + piece.to));
          pieces_.push_back(piece);
        }
      }
    if (pieces_.empty()) edge_ = face_;  // no sharp edge (a smooth mesh): uniform
  }

  bool uniform() const { return !(edge_ < face_); }
  double face() const { return face_; }
  double edge() const { return edge_; }

  /// The edge pieces bounding patch p that come within the band of some point within `reach` of x.
  std::vector<int> piecesNear(const Eigen::Vector3d& x, double reach, int p) const {
    std::vector<int> found;
    if (uniform()) return found;
    grid_.forEachNear(x, band_ + reach + 0.5 * cell_, [&](int i) {
      const Piece& piece = pieces_[i];
      if (std::find(piece.patches->begin(), piece.patches->end(), p) != piece.patches->end() &&
          distance(piece, x) <= band_ + reach)
        found.push_back(i);
    });
    return found;
  }

  /// The smallest l over a ball of `radius` about x, from the pieces near it (`pieces`, a superset
  /// of those within the band of the ball); `kept` gets those that can matter to a ball centred
  /// within it of at most twice the radius (a sub-triangle's: its corners lie in this triangle).
  double at(const Eigen::Vector3d& x, double radius, const std::vector<int>& pieces, std::vector<int>& kept) const {
    kept.clear();
    if (uniform()) return face_;
    double nearest = INFINITY;
    for (int i : pieces) {
      const double d = distance(pieces_[i], x);
      nearest = std::min(nearest, d);
      if (d <= band_ + 3 * radius) kept.push_back(i);
    }
    return std::min(face_, edge_ + gradient_ * std::max(0.0, nearest - radius));
  }

private:
  struct Piece {
    Eigen::Vector3d from, to;
    const std::vector<int>* patches;  ///< the patches meeting along it
  };
  static double distance(const Piece& piece, const Eigen::Vector3d& x) {
    const Eigen::Vector3d along = piece.to - piece.from;
    const double w = std::clamp((x - piece.from).dot(along) / along.squaredNorm(), 0.0, 1.0);
    return (piece.from + w * along - x).norm();
  }

  double face_, edge_, gradient_, band_, cell_;
  PointGrid grid_;
  std::vector<Piece> pieces_;
};

// Calls visit(point) for the quadrature points of triangle t: small sub-triangles of longest edge
// <= l / perSpacing, each as its centroid with its area, so the areas sum exactly to the
// triangle's.
//  - Uniform spacing: the k^2 congruent sub-triangles, k = ceil(longest edge / (s / perSpacing)).
//  - Graded spacing: the triangle halved across its longest edge, recursively, until each piece is
//    small enough for the local spacing over it. Bisection keeps the count near area / h^2 even
//    for slivers, where k^2 pieces would be far more.
template <class Visit>
void forEachQuadraturePoint(const TriangleMesh& mesh, int t, int patch, const LocalSpacing& spacing, double perSpacing,
                            Visit&& visit) {
  const Eigen::Vector3d a = triangleCorner(mesh, t, 0), b = triangleCorner(mesh, t, 1), c = triangleCorner(mesh, t, 2);
  if (spacing.uniform()) {
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int k = std::max(1, static_cast<int>(std::ceil(longest / (spacing.face() / perSpacing))));
    const double subArea = triangleArea(mesh, t) / (static_cast<double>(k) * k);
    const Eigen::Vector3d du = (b - a) / k, dv = (c - a) / k;
    for (int i = 0; i < k; ++i)
      for (int j = 0; i + j < k; ++j) {
        visit(QuadraturePoint{a + (i + 1.0 / 3.0) * du + (j + 1.0 / 3.0) * dv, subArea, spacing.face()});  // upward
        if (i + j < k - 1)
          visit(QuadraturePoint{a + (i + 2.0 / 3.0) * du + (j + 2.0 / 3.0) * dv, subArea, spacing.face()});  // downward
      }
    return;
  }
  // A piece with corners p[0..2] and area `area`, and the edge pieces that can reach it: kept, or
  // halved. The pieces near a piece at each depth of the recursion go in one reused list (a deque:
  // growing it keeps the shallower lists in place).
  std::deque<std::vector<int>> keptAtDepth;
  const auto bisect = [&](auto&& self, const std::array<Eigen::Vector3d, 3>& p, double area,
                          const std::vector<int>& pieces, std::size_t depth) -> void {
    const Eigen::Vector3d centre = (p[0] + p[1] + p[2]) / 3.0;
    const double reach = std::max({(p[0] - centre).norm(), (p[1] - centre).norm(), (p[2] - centre).norm()});
    if (keptAtDepth.size() <= depth) keptAtDepth.resize(depth + 1);
    std::vector<int>& kept = keptAtDepth[depth];
    const double l = spacing.at(centre, reach, pieces, kept);
    // The longest edge p[longest] - p[longest + 1]; of edges equal to rounding the first, so that
    // the pieces do not depend on the scale or orientation of the mesh.
    int longest = 0;
    double length = (p[1] - p[0]).norm();
    for (int e = 1; e < 3; ++e) {
      const double edge = (p[(e + 1) % 3] - p[e]).norm();
      if (edge > length * (1 + 1e-9)) {
        longest = e;
        length = edge;
      }
    }
    if (length <= l / perSpacing) {
      visit(QuadraturePoint{centre, area, l});
      return;
    }
    const Eigen::Vector3d &from = p[longest], &to = p[(longest + 1) % 3], &apex = p[(longest + 2) % 3];
    const Eigen::Vector3d middle = 0.5 * (from + to);
    self(self, std::array<Eigen::Vector3d, 3>{from, middle, apex}, area / 2, kept, depth + 1);
    self(self, std::array<Eigen::Vector3d, 3>{middle, to, apex}, area / 2, kept, depth + 1);
  };
  const Eigen::Vector3d g = (a + b + c) / 3.0;
  const double reach = std::max({(a - g).norm(), (b - g).norm(), (c - g).norm()});
  bisect(bisect, std::array<Eigen::Vector3d, 3>{a, b, c}, triangleArea(mesh, t), spacing.piecesNear(g, reach, patch), 0);
}

struct SeedNode {
  Eigen::Vector3d position;
  NodeKind kind;
};

// Points along a polyline at equal arc length, at most `spacing` apart, excluding the ends
// (an open chain's ends are corners, which carry their own nodes). A closed loop gets >= 3.
std::vector<Eigen::Vector3d> pointsAlongChain(const TriangleMesh& mesh, const FeatureChain& chain, double spacing) {
  std::vector<double> arc{0.0};
  for (std::size_t i = 1; i < chain.vertices.size(); ++i)
    arc.push_back(arc.back() + (mesh.vertices[chain.vertices[i]] - mesh.vertices[chain.vertices[i - 1]]).norm());
  const double length = arc.back();
  int segments = std::max(1, static_cast<int>(std::ceil(length / spacing - 1e-9)));
  if (chain.closed) segments = std::max(3, segments);
  std::vector<Eigen::Vector3d> points;
  std::size_t piece = 1;
  for (int s = chain.closed ? 0 : 1; s < segments; ++s) {
    const double target = length * s / segments;
    while (piece + 1 < arc.size() && arc[piece] < target) ++piece;
    const double span = arc[piece] - arc[piece - 1];
    const double w = span > 0 ? (target - arc[piece - 1]) / span : 0.0;
    points.push_back((1 - w) * mesh.vertices[chain.vertices[piece - 1]] + w * mesh.vertices[chain.vertices[piece]]);
  }
  return points;
}

struct PatchNodes {
  std::vector<Eigen::Vector3d> positions;
  std::vector<NodeKind> kinds;
};

// Thrown when the symmetries are finer than the spacing: a pick's images crowd it with no point
// nearby that they all fix (two mirrors closer than a spacing apart, as on a finely faceted torus).
// The block is then sampled without symmetries.
struct CrowdedSymmetry {};

// A pick whose images would crowd it (an image closer than `reach`: a point near a mirror or an
// axis) moves onto the set those images fix: the mean of its near images, repeated until every
// image is either the point itself (to kSamePoint x reach) or at least `reach` from it, within
// `reach` of the pick (so that the pick is covered). On a flat patch the mean stays on it; on a
// curved one it sits inside by about the orbit's sagitta, which only places a cell.
Eigen::Vector3d ontoNearbyFixedSet(const SymmetryGroup& symmetry, const std::vector<std::size_t>& stabilizer,
                                   const Eigen::Vector3d& pick, double reach) {
  Eigen::Vector3d x = pick;
  for (int round = 0; round < 8; ++round) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    int near = 0, fixing = 0;
    for (std::size_t g : stabilizer) {
      const Eigen::Vector3d image = symmetry.apply(g, x);
      const double d = (image - x).norm();
      if (d >= reach) continue;
      mean += image;
      ++near;
      if (d <= kSamePoint * reach) ++fixing;
    }
    if (fixing == near) {
      if (!((x - pick).norm() < reach)) break;  // moved too far to cover the pick
      return x;
    }
    x = mean / near;
  }
  throw CrowdedSymmetry{};
}

// Farthest-point sampling of one patch over its candidate points, seeded with its edge and
// corner nodes: repeatedly add the candidate farthest from all nodes, distance measured in units
// of the local spacing, until every candidate is within kCoverageRadius x its local spacing of a
// node. Priorities are d s / l (s the face spacing, l the candidate's): with uniform spacing the
// distances themselves.
// With a symmetry group, `stabilizer` lists the elements that map the patch onto itself, and each
// pick adds the candidate's images under them too (once each where images coincide: a point on a
// mirror), so the nodes keep the patch's symmetries when seeds and candidates do.
PatchNodes farthestPointSample(const std::vector<SeedNode>& seeds, const std::vector<QuadraturePoint>& candidates,
                               double spacing, const SymmetryGroup& symmetry, const std::vector<std::size_t>& stabilizer) {
  const int n = static_cast<int>(candidates.size());
  // distance[i]: from candidate i to its nearest node, capped at `cap`. The cap keeps every
  // update local; while distances sit at the cap, the picks pack the patch greedily in index
  // order, then farthest-point sampling proper refines the packing.
  const double cap = 2.0 * spacing;
  std::vector<double> distance(n, cap);
  // In steps of 1e-9 s: candidates that tie up to rounding tie exactly, and the lower index wins
  // at any scale and orientation of the mesh.
  const auto priority = [&](int i) {
    return std::round(distance[i] * (spacing / candidates[i].spacing) / (1e-9 * spacing));
  };
  PointGrid grid(cap);
  for (int i = 0; i < n; ++i) grid.insert(i, candidates[i].position);

  PatchNodes nodes;
  // Max-heap of (priority, -index): the farthest candidate first, the lowest index among ties.
  std::priority_queue<std::pair<double, int>> heap;
  // A node at x: the candidates within `radius` updated, and re-queued when `queue` (the seeds
  // come first, before the heap is built).
  const auto addNode = [&](const Eigen::Vector3d& x, NodeKind kind, double radius, bool queue) {
    nodes.positions.push_back(x);
    nodes.kinds.push_back(kind);
    grid.forEachNear(x, radius, [&](int j) {
      const double dj = std::sqrt(squaredDistance(candidates[j].position, x));
      if (dj < distance[j]) {
        distance[j] = dj;
        if (queue) heap.push({priority(j), -j});
      }
    });
  };
  for (const SeedNode& seed : seeds) addNode(seed.position, seed.kind, cap, false);
  {
    std::vector<std::pair<double, int>> entries(n);
    for (int i = 0; i < n; ++i) entries[i] = {priority(i), -i};
    heap = std::priority_queue<std::pair<double, int>>(std::less<std::pair<double, int>>(), std::move(entries));
  }
  const double coverage = kCoverageRadius / 1e-9;
  while (!heap.empty()) {
    const auto [d, negIndex] = heap.top();
    heap.pop();
    const int c = -negIndex;
    if (d != priority(c)) continue;  // stale entry
    if (d < coverage) break;
    // A candidate j can come closer only if distance[j] <= d 1e-9 s (priorities scale d s / l, l <= s).
    const Eigen::Vector3d pick = ontoNearbyFixedSet(symmetry, stabilizer, candidates[c].position,
                                                    kCoverageRadius * candidates[c].spacing);
    const std::size_t first = nodes.positions.size();
    for (std::size_t g : stabilizer) {
      const Eigen::Vector3d x = symmetry.apply(g, pick);
      bool repeated = false;
      for (std::size_t k = first; k < nodes.positions.size(); ++k)
        repeated = repeated || squaredDistance(nodes.positions[k], x) <= kSamePoint * kSamePoint * spacing * spacing;
      if (!repeated) addNode(x, NodeKind::Face, (d + 1) * 1e-9 * spacing, true);
    }
  }
  return nodes;
}

// Nearest node of one patch to a stream of nearby points. Points arrive in runs within the same
// grid cell, so the candidate nodes of a cell's neighbourhood are gathered once per run.
class NearestNode {
public:
  NearestNode(const std::vector<Eigen::Vector3d>& nodes, double reach)
      : nodes_(nodes), reach_(reach), grid_(reach) {
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) grid_.insert(i, nodes[i]);
  }

  int operator()(const Eigen::Vector3d& x) {
    const Eigen::Array3i cell = (x.array() / reach_).floor().cast<int>();
    if (!haveCell_ || (cell != cell_).any()) {
      haveCell_ = true;
      cell_ = cell;
      near_.clear();
      grid_.forEachNear((cell.cast<double>() + 0.5) * reach_, reach_, [&](int i) { near_.push_back(i); });
    }
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (int i : near_) {
      const double d = squaredDistance(nodes_[i], x);
      if (d < bestDistance || (d == bestDistance && i < best)) {
        bestDistance = d;
        best = i;
      }
    }
    if (best >= 0 && bestDistance <= reach_ * reach_) return best;
    // Beyond the guaranteed reach (cannot happen after coverage): search every node.
    for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
      const double d = (nodes_[i] - x).squaredNorm();
      if (d < bestDistance) {
        bestDistance = d;
        best = i;
      }
    }
    return best;
  }

private:
  const std::vector<Eigen::Vector3d>& nodes_;
  double reach_;
  PointGrid grid_;
  bool haveCell_ = false;
  Eigen::Array3i cell_;
  std::vector<int> near_;
};

// The node of a cell: its centroid moved onto the cell's surface (the closest point of the cell's
// triangles). On a planar cell the centroid is on the surface and stays, bit for bit; on a curved
// one it lies off the surface by the sagitta, about kappa l^2 / 8 (outside a concave cell, inside
// a convex one), which would read as overlap or gap against a neighbour matching the face.
Eigen::Vector3d onCell(const TriangleMesh& mesh, const std::vector<int>& triangles, const Eigen::Vector3d& centroid,
                       double spacing) {
  Eigen::Vector3d best = centroid;
  double bestDistance = INFINITY;
  for (int t : triangles) {
    const Eigen::Vector3d q =
        closestPointOnTriangle(centroid, triangleCorner(mesh, t, 0), triangleCorner(mesh, t, 1), triangleCorner(mesh, t, 2))
            .point;
    const double d = squaredDistance(q, centroid);
    if (d < bestDistance) {
      bestDistance = d;
      best = q;
    }
  }
  constexpr double kOnSurface = 1e-9;  // in units of the spacing: rounding, not curvature
  return bestDistance <= (kOnSurface * spacing) * (kOnSurface * spacing) ? centroid : best;
}

// The fundamental region of a patch under its stabilizer: the points x for which no image h x
// lies farther along a fixed direction w (one no mirror of a block contains), ties included.
// Restricted to it and completed with their images, seeds and candidates keep the symmetries.
bool inFundamentalRegion(const SymmetryGroup& symmetry, const std::vector<std::size_t>& stabilizer,
                         const Eigen::Vector3d& x, double tolerance) {
  static const Eigen::Vector3d w = Eigen::Vector3d(std::sqrt(2.0), std::sqrt(3.0), M_PI).normalized();
  const double key = w.dot(x - symmetry.centre);
  for (std::size_t h : stabilizer)
    if (w.dot(symmetry.apply(h, x) - symmetry.centre) > key + tolerance) return false;
  return true;
}

// Nodes of every patch by farthest-point sampling. Under a symmetry group each orbit of patches is
// sampled once, on its lowest patch P: P's seeds and candidates are restricted to the fundamental
// region of P's stabilizer and completed with their images (seeds closer than kSamePoint x the
// seed spacing are one), and sampled with orbit picks; every other patch Q of the orbit gets the
// images of P's nodes under an element mapping P onto Q.
std::vector<PatchNodes> sampleAllPatches(const std::vector<std::vector<SeedNode>>& seeds,
                                         const std::vector<std::vector<QuadraturePoint>>& candidates, double spacing,
                                         double seedSpacing, const SymmetryGroup& symmetry) {
  const int patches = static_cast<int>(seeds.size());
  std::vector<PatchNodes> nodes(patches);
  if (symmetry.size() == 1) {
    for (int p = 0; p < patches; ++p) nodes[p] = farthestPointSample(seeds[p], candidates[p], spacing, symmetry, {0});
    return nodes;
  }
  const double tolerance = 1e-9 * spacing;
  for (int p = 0; p < patches; ++p) {
    int first = p;
    for (const std::vector<int>& image : symmetry.patchImages) first = std::min(first, image[p]);
    if (first < p) {
      std::size_t g = 0;
      while (symmetry.patchImages[g][first] != p) ++g;
      nodes[p].kinds = nodes[first].kinds;
      for (const Eigen::Vector3d& x : nodes[first].positions) nodes[p].positions.push_back(symmetry.apply(g, x));
      continue;
    }
    std::vector<std::size_t> stabilizer;
    for (std::size_t g = 0; g < symmetry.size(); ++g)
      if (symmetry.patchImages[g][p] == p) stabilizer.push_back(g);
    std::vector<SeedNode> seedOrbits;
    for (const SeedNode& seed : seeds[p]) {
      if (!inFundamentalRegion(symmetry, stabilizer, seed.position, tolerance)) continue;
      for (std::size_t h : stabilizer) {
        const Eigen::Vector3d x = symmetry.apply(h, seed.position);
        bool repeated = false;
        for (const SeedNode& other : seedOrbits)
          repeated = repeated || (other.position - x).norm() <= kSamePoint * seedSpacing;
        if (!repeated) seedOrbits.push_back({x, seed.kind});
      }
    }
    std::vector<QuadraturePoint> candidateOrbits;
    for (const QuadraturePoint& q : candidates[p])
      if (inFundamentalRegion(symmetry, stabilizer, q.position, tolerance))
        for (std::size_t h : stabilizer) candidateOrbits.push_back({symmetry.apply(h, q.position), q.area, q.spacing});
    nodes[p] = farthestPointSample(seedOrbits, candidateOrbits, spacing, symmetry, stabilizer);
  }
  return nodes;
}

// Under a symmetry group: each node's area, normal and position taken over its orbit (the mean
// area; the area-weighted mean of the images' normals and positions brought back by the inverse
// maps), so that a node's cell and its images' cells are exact images of each other. A patch's
// areas still sum to its area: each is the mean of its orbit's patches, whose areas are equal.
void averageOverOrbits(const SymmetryGroup& symmetry, const std::vector<PatchNodes>& patchNodes,
                       std::vector<NearestNode>& nearest, double spacing, std::vector<std::vector<double>>& area,
                       std::vector<std::vector<Eigen::Vector3d>>& normal,
                       std::vector<std::vector<Eigen::Vector3d>>& position) {
  std::vector<std::vector<double>> meanArea = area;
  std::vector<std::vector<Eigen::Vector3d>> meanNormal = normal, meanPosition = position;
  for (std::size_t p = 0; p < patchNodes.size(); ++p)
    for (std::size_t k = 0; k < patchNodes[p].positions.size(); ++k) {
      double total = 0.0;
      Eigen::Vector3d n = Eigen::Vector3d::Zero(), x = Eigen::Vector3d::Zero();
      for (std::size_t g = 0; g < symmetry.size(); ++g) {
        const int q = symmetry.patchImages[g][p];
        const Eigen::Vector3d image = symmetry.apply(g, patchNodes[p].positions[k]);
        const int j = nearest[q](image);
        if (j < 0 || (patchNodes[q].positions[j] - image).norm() > kSamePoint * spacing)
          throw std::logic_error("surface nodes: the image of a node under a symmetry of the block is not a node");
        const Eigen::Matrix3d back = symmetry.elements[g].transpose();
        total += area[q][j];
        n += back * normal[q][j];
        if (area[q][j] > 0.0) x += area[q][j] * (symmetry.centre + back * (position[q][j] - symmetry.centre));
      }
      meanArea[p][k] = total / static_cast<double>(symmetry.size());
      meanNormal[p][k] = n;
      meanPosition[p][k] = total > 0.0 ? Eigen::Vector3d(x / total) : Eigen::Vector3d::Zero();
    }
  area = std::move(meanArea);
  normal = std::move(meanNormal);
  position = std::move(meanPosition);
}

}  // namespace

SurfaceNodes sampleSurfaceNodes(const TriangleMesh& mesh, const MeshFeatures& features,
                                const SurfaceNodeOptions& options) {
  if (!(options.spacing > 0.0)) throw InputError("node spacing must be positive");
  if (!(options.sizeGradient > 0.0)) throw InputError("node size gradient must be positive");
  const double spacing = options.spacing;
  const LocalSpacing local(mesh, features, options);

  // Seeds (corner and edge nodes) of each patch.
  std::vector<std::vector<SeedNode>> seeds(features.patchCount);
  std::vector<std::vector<int>> trianglesAt(mesh.vertices.size());
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t)
    for (int v : mesh.triangles[t]) trianglesAt[v].push_back(t);
  for (int v : features.corners) {
    std::vector<int> patches;
    for (int t : trianglesAt[v]) patches.push_back(features.trianglePatch[t]);
    std::sort(patches.begin(), patches.end());
    patches.erase(std::unique(patches.begin(), patches.end()), patches.end());
    for (int p : patches) seeds[p].push_back({mesh.vertices[v], NodeKind::Corner});
  }
  for (const FeatureChain& chain : features.chains)
    for (const Eigen::Vector3d& x : pointsAlongChain(mesh, chain, local.edge()))
      for (int p : chain.patches) seeds[p].push_back({x, NodeKind::Edge});

  // Nodes of each patch by farthest-point sampling over candidate points.
  std::vector<std::vector<QuadraturePoint>> candidates(features.patchCount);
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const int p = features.trianglePatch[t];
    forEachQuadraturePoint(mesh, t, p, local, kCandidatesPerSpacing,
                           [&](const QuadraturePoint& q) { candidates[p].push_back(q); });
  }
  SymmetryGroup symmetry =
      options.keepSymmetries
          ? findSymmetries(mesh, features, kSymmetryTolerance * boundingBox(mesh.vertices).diagonal().norm())
          : SymmetryGroup{};
  std::vector<PatchNodes> patchNodes;
  try {
    patchNodes = sampleAllPatches(seeds, candidates, spacing, local.edge(), symmetry);
  } catch (const CrowdedSymmetry&) {
    symmetry = SymmetryGroup{};
    patchNodes = sampleAllPatches(seeds, candidates, spacing, local.edge(), symmetry);
  }

  // Area weights: a fine quadrature of each triangle, every point given to the nearest node of
  // its patch. Every candidate is within coverage of a node and every fine point within one
  // candidate cell of a candidate, so the nearest node lies within `reach` (l <= s).
  const double reach = (kCoverageRadius + 1.0 / kCandidatesPerSpacing) * spacing;
  const double perSpacing = std::max(1, options.quadraturePerSpacing);
  std::vector<std::vector<double>> area(features.patchCount);
  std::vector<std::vector<Eigen::Vector3d>> normal(features.patchCount), centroid(features.patchCount);
  std::vector<std::vector<std::vector<int>>> cellTriangles(features.patchCount);  // the triangles each cell covers
  std::vector<NearestNode> nearest;
  nearest.reserve(features.patchCount);
  for (int p = 0; p < features.patchCount; ++p) {
    nearest.emplace_back(patchNodes[p].positions, reach);
    area[p].assign(patchNodes[p].positions.size(), 0.0);
    normal[p].assign(patchNodes[p].positions.size(), Eigen::Vector3d::Zero());
    centroid[p].assign(patchNodes[p].positions.size(), Eigen::Vector3d::Zero());
    cellTriangles[p].resize(patchNodes[p].positions.size());
  }
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const int p = features.trianglePatch[t];
    const Eigen::Vector3d unitNormal = triangleAreaVector(mesh, t).normalized();
    forEachQuadraturePoint(mesh, t, p, local, perSpacing, [&](const QuadraturePoint& q) {
      const int node = nearest[p](q.position);
      area[p][node] += q.area;
      normal[p][node] += q.area * unitNormal;
      centroid[p][node] += q.area * q.position;
      if (cellTriangles[p][node].empty() || cellTriangles[p][node].back() != t) cellTriangles[p][node].push_back(t);
    });
  }

  std::vector<std::vector<Eigen::Vector3d>> position(features.patchCount);
  for (int p = 0; p < features.patchCount; ++p)
    for (std::size_t k = 0; k < patchNodes[p].positions.size(); ++k)
      position[p].push_back(area[p][k] > 0.0 ? onCell(mesh, cellTriangles[p][k], centroid[p][k] / area[p][k], spacing)
                                              : Eigen::Vector3d::Zero());
  if (symmetry.size() > 1) averageOverOrbits(symmetry, patchNodes, nearest, spacing, area, normal, position);

  SurfaceNodes out;
  out.symmetries = symmetry.size();
  for (int p = 0; p < features.patchCount; ++p)
    for (std::size_t k = 0; k < patchNodes[p].positions.size(); ++k) {
      if (area[p][k] <= 0.0) continue;  // a seed that owns no quadrature point carries no load
      out.positions.push_back(position[p][k]);
      out.normals.push_back(normal[p][k].normalized());
      out.areas.push_back(area[p][k]);
      out.patches.push_back(p);
      out.kinds.push_back(patchNodes[p].kinds[k]);
    }
  return out;
}

std::size_t keptSymmetries(const SurfaceNodes& nodes, const SymmetryGroup& group, double tolerance) {
  PointGrid grid(std::max(tolerance, 1e-300) * 1e3);
  for (int i = 0; i < static_cast<int>(nodes.size()); ++i) grid.insert(i, nodes.positions[i]);
  std::size_t kept = 0;
  for (std::size_t g = 0; g < group.size(); ++g) {
    bool keeps = true;
    for (std::size_t i = 0; i < nodes.size() && keeps; ++i) {
      const Eigen::Vector3d image = group.apply(g, nodes.positions[i]);
      bool found = false;
      grid.forEachNear(image, tolerance, [&](int j) {
        found = found || (squaredDistance(nodes.positions[j], image) <= tolerance * tolerance &&
                          std::abs(nodes.areas[j] - nodes.areas[i]) <= 1e-9 * nodes.areas[i]);
      });
      keeps = found;
    }
    kept += keeps ? 1 : 0;
  }
  return kept;
}

}  // namespace tessera
