#include "geometry/plane_tiling.h"

#include "io/input_error.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace tessera {

namespace {

using Polygon = std::vector<Eigen::Vector2d>;

std::string gridName(int row, int column) { return "r" + std::to_string(row) + "c" + std::to_string(column); }

// The regular polygon of `corners` corners at circumradius `radius` about `centre`, the first at
// angle `first` (radians), counter-clockwise.
Polygon regularPolygon(const Eigen::Vector2d& centre, double radius, int corners, double first) {
  Polygon p;
  for (int k = 0; k < corners; ++k) {
    const double a = first + 2 * M_PI * k / corners;
    p.push_back(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return p;
}

// Centres of a columns x rows hexagonal lattice of spacing `spacing`, odd rows shifted by half.
Eigen::Vector2d hexLatticeCentre(int column, int row, double spacing) {
  return {spacing * (column + 0.5 * (row % 2)), spacing * std::sqrt(3.0) / 2 * row};
}

// Drops corners within `tolerance` of the previous one.
Polygon withoutRepeatedCorners(const Polygon& polygon, double tolerance) {
  Polygon p;
  for (const Eigen::Vector2d& x : polygon)
    if (p.empty() || (x - p.back()).norm() > tolerance) p.push_back(x);
  while (p.size() > 1 && (p.front() - p.back()).norm() <= tolerance) p.pop_back();
  return p;
}

PlaneTiling squareTiling(const TilingOptions& o) {
  PlaneTiling t;
  for (int r = 0; r < o.rows; ++r)
    for (int c = 0; c < o.columns; ++c) {
      t.names.push_back(gridName(r, c));
      t.tiles.push_back(regularPolygon({c * o.pitch, r * o.pitch}, o.pitch / std::sqrt(2.0), 4, -3 * M_PI / 4));
    }
  return t;
}

// Hexagons of inradius p/2, faces normal at 0, 60, ... degrees (corners at 30 + 60k).
PlaneTiling hexTiling(const TilingOptions& o) {
  PlaneTiling t;
  for (int r = 0; r < o.rows; ++r)
    for (int c = 0; c < o.columns; ++c) {
      t.names.push_back(gridName(r, c));
      t.tiles.push_back(regularPolygon(hexLatticeCentre(c, r, o.pitch), o.pitch / std::sqrt(3.0), 6, M_PI / 6));
    }
  return t;
}

// Triangles of side s = p sqrt 3 (neighbouring centres 2 x inradius = s / sqrt 3 apart); triangle
// (k, r) points up when k + r is even.
PlaneTiling triangleTiling(const TilingOptions& o) {
  PlaneTiling t;
  const double s = o.pitch * std::sqrt(3.0), h = s * std::sqrt(3.0) / 2;
  for (int r = 0; r < o.rows; ++r)
    for (int k = 0; k < o.columns; ++k) {
      const double x = k * s / 2, y = r * h;
      t.names.push_back(gridName(r, k));
      if ((k + r) % 2 == 0) t.tiles.push_back({{x, y}, {x + s, y}, {x + s / 2, y + h}});
      else t.tiles.push_back({{x + s / 2, y}, {x + s, y + h}, {x, y + h}});
    }
  return t;
}

// Hexagons of side 2p / sqrt 3 (centres 2p apart), each cut into the rhombi O V_2j V_2j+1 V_2j+2.
PlaneTiling rhombilleTiling(const TilingOptions& o) {
  PlaneTiling t;
  const double side = 2 * o.pitch / std::sqrt(3.0);
  for (int r = 0; r < o.rows; ++r)
    for (int c = 0; c < o.columns; ++c) {
      const Eigen::Vector2d centre = hexLatticeCentre(c, r, 2 * o.pitch);
      const Polygon hex = regularPolygon(centre, side, 6, M_PI / 6);
      for (int j = 0; j < 3; ++j) {
        t.names.push_back(gridName(r, c) + "_" + std::to_string(j));
        t.tiles.push_back({centre, hex[2 * j], hex[2 * j + 1], hex[(2 * j + 2) % 6]});
      }
    }
  return t;
}

// Voronoi cells of jittered seeds, relaxed twice towards their centroids (Lloyd), in the rectangle.
PlaneTiling voronoiTiling(const TilingOptions& o) {
  const double p = o.pitch, width = o.columns * p, height = o.rows * p;
  std::mt19937 random(o.seed);
  std::uniform_real_distribution<double> jitter(-0.35 * p, 0.35 * p);
  std::vector<Eigen::Vector2d> seeds;
  for (int r = 0; r < o.rows; ++r)
    for (int c = 0; c < o.columns; ++c) {
      const double dx = jitter(random), dy = jitter(random);
      seeds.emplace_back((c + 0.5) * p + dx, (r + 0.5) * p + dy);
    }
  const Polygon rectangle{{0, 0}, {width, 0}, {width, height}, {0, height}};
  PlaneTiling t;
  for (int relaxation = 0; relaxation <= 2; ++relaxation) {
    t = PlaneTiling{};
    for (int i = 0; i < static_cast<int>(seeds.size()); ++i) {
      const int r = i / o.columns, c = i % o.columns;
      Polygon cell = rectangle;
      // Seeds stay within their square's neighbourhood: those three squares away cannot cut the cell.
      for (int rr = std::max(0, r - 3); rr <= std::min(o.rows - 1, r + 3); ++rr)
        for (int cc = std::max(0, c - 3); cc <= std::min(o.columns - 1, c + 3); ++cc) {
          const int j = rr * o.columns + cc;
          if (j == i) continue;
          const Eigen::Vector2d n = seeds[j] - seeds[i];
          cell = clipPolygon(cell, n, n.dot(0.5 * (seeds[i] + seeds[j])));
        }
      t.names.push_back("v" + std::to_string(i));
      t.tiles.push_back(withoutRepeatedCorners(cell, 1e-9 * p));
    }
    for (std::size_t i = 0; i < seeds.size(); ++i) seeds[i] = polygonCentroid(t.tiles[i]);
  }
  return t;
}

}  // namespace

std::vector<double> tileEdgeAngles(const PlaneTiling& tiling, std::size_t t, double angle) {
  std::vector<double> angles(tiling.tiles[t].size(), angle);
  if (t < tiling.edgeAngles.size())
    for (std::size_t k = 0; k < angles.size() && k < tiling.edgeAngles[t].size(); ++k)
      if (std::isfinite(tiling.edgeAngles[t][k])) angles[k] = tiling.edgeAngles[t][k];
  return angles;
}

Polygon clipPolygon(const Polygon& polygon, const Eigen::Vector2d& n, double d) {
  Polygon kept;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    const double da = n.dot(a) - d, db = n.dot(b) - d;
    if (da <= 0) kept.push_back(a);
    if ((da < 0 && db > 0) || (da > 0 && db < 0)) kept.push_back(a + (b - a) * (da / (da - db)));
  }
  return kept;
}

std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (p.size() < 3) return p;
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
}

double polygonArea(const Polygon& polygon) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

// Centroid of the polygon's area (triangles fanned from corner 0).
Eigen::Vector2d polygonCentroid(const Polygon& polygon) {
  Eigen::Vector2d sum(0, 0);
  double area = 0;
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
    const Eigen::Vector2d a = polygon[k] - polygon[0], b = polygon[k + 1] - polygon[0];
    const double twice = a.x() * b.y() - a.y() * b.x();
    sum += twice * (polygon[0] + polygon[k] + polygon[k + 1]) / 3;
    area += twice;
  }
  return sum / area;
}

const std::vector<std::string>& tilingKinds() {
  static const std::vector<std::string> kinds{"square", "hex", "triangle", "rhombille", "voronoi"};
  return kinds;
}

bool isTilingKind(const std::string& name) {
  return std::find(tilingKinds().begin(), tilingKinds().end(), name) != tilingKinds().end();
}

PlaneTiling makeTiling(const TilingOptions& o) {
  if (!(o.pitch > 0) || !std::isfinite(o.pitch)) throw InputError("tiling: the pitch must be positive");
  if (o.columns < 1 || o.rows < 1) throw InputError("tiling: give at least one column and one row");
  PlaneTiling t;
  if (o.kind == "square") t = squareTiling(o);
  else if (o.kind == "hex") t = hexTiling(o);
  else if (o.kind == "triangle") t = triangleTiling(o);
  else if (o.kind == "rhombille") t = rhombilleTiling(o);
  else if (o.kind == "voronoi") t = voronoiTiling(o);
  else throw InputError("tiling '" + o.kind + "': use square, hex, triangle, rhombille, voronoi or a polygon mesh file");
  // Centred at the origin: the mean of the tiles' centroids.
  Eigen::Vector2d mean(0, 0);
  for (const Polygon& tile : t.tiles) mean += polygonCentroid(tile);
  mean /= static_cast<double>(t.tiles.size());
  for (Polygon& tile : t.tiles)
    for (Eigen::Vector2d& x : tile) x -= mean;
  return t;
}

std::vector<std::vector<EdgeNeighbour>> edgeNeighbours(const PlaneTiling& tiling, double tolerance) {
  struct Edge {
    Eigen::Vector2d a, b;
    int tile, edge;
  };
  std::vector<Edge> edges;
  std::vector<std::vector<EdgeNeighbour>> across(tiling.tiles.size());
  for (int t = 0; t < static_cast<int>(tiling.tiles.size()); ++t) {
    const Polygon& p = tiling.tiles[t];
    across[t].resize(p.size());
    for (int k = 0; k < static_cast<int>(p.size()); ++k) edges.push_back({p[k], p[(k + 1) % p.size()], t, k});
  }
  // Sorted by the midpoint's x: the edge matching edge i lies within `tolerance` of it in that order.
  std::sort(edges.begin(), edges.end(), [](const Edge& e, const Edge& f) { return (e.a + e.b).x() < (f.a + f.b).x(); });
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (std::size_t j = i + 1; j < edges.size() && (edges[j].a + edges[j].b).x() - (edges[i].a + edges[i].b).x() <= 2 * tolerance; ++j) {
      const Edge &e = edges[i], &f = edges[j];
      if (e.tile == f.tile || (e.a - f.b).norm() > tolerance || (e.b - f.a).norm() > tolerance) continue;
      across[e.tile][e.edge] = {f.tile, f.edge};
      across[f.tile][f.edge] = {e.tile, e.edge};
    }
  return across;
}

}  // namespace tessera
