// Surface nodes: weights sum to the area, spacing is near-uniform, every sharp edge carries nodes,
// normals are the outward face normals.
#include "geometry/block_generators.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_features.h"
#include "geometry/mesh_validation.h"
#include "geometry/point_mesh_distance.h"
#include "geometry/point_spacing.h"
#include "geometry/surface_nodes.h"
#include "io/input_error.h"
#include "tests/fixtures/analytic_meshes.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

using namespace tessera;

namespace {

struct Sampled {
  TriangleMesh mesh;
  MeshFeatures features;
  SurfaceNodes nodes;
};

// Uniform nodes at `spacing`, or graded to `edgeSpacing` at the sharp edges when it is given.
Sampled sample(TriangleMesh mesh, double spacing, double edgeSpacing = 0, double sizeGradient = 0.5) {
  validateSolidMesh(mesh, "fixture");
  Sampled s{mesh, findFeatures(mesh, 30 * M_PI / 180), {}};
  SurfaceNodeOptions options;
  options.spacing = spacing;
  options.edgeSpacing = edgeSpacing;
  options.sizeGradient = sizeGradient;
  s.nodes = sampleSurfaceNodes(s.mesh, s.features, options);
  return s;
}

// Distance from x to the nearest sharp edge of the mesh.
double distanceToSharpEdge(const Sampled& s, const Eigen::Vector3d& x) {
  double best = 1e300;
  for (std::size_t e = 0; e < s.features.topology.edges.size(); ++e) {
    if (!s.features.edgeIsSharp[e]) continue;
    const auto& v = s.features.topology.edges[e].vertices;
    const Eigen::Vector3d a = s.mesh.vertices[v[0]], ab = s.mesh.vertices[v[1]] - a;
    const double w = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + w * ab - x).norm());
  }
  return best;
}

void requireAreaSums(const Sampled& s) {
  const double total = std::accumulate(s.nodes.areas.begin(), s.nodes.areas.end(), 0.0);
  REQUIRE(total == Approx(surfaceArea(s.mesh)).epsilon(1e-9));
  // Each patch's nodes carry exactly that patch's area.
  std::map<int, double> nodeArea, patchArea;
  for (std::size_t i = 0; i < s.nodes.size(); ++i) nodeArea[s.nodes.patches[i]] += s.nodes.areas[i];
  for (int t = 0; t < static_cast<int>(s.mesh.triangles.size()); ++t)
    patchArea[s.features.trianglePatch[t]] += triangleArea(s.mesh, t);
  for (const auto& [patch, area] : patchArea) REQUIRE(nodeArea[patch] == Approx(area).epsilon(1e-9));
}

void requireSpacing(const Sampled& s, double spacing) {
  const SpacingStats stats = spacingStats(s.nodes.positions, s.nodes.patches);
  INFO("min " << stats.min << " mean " << stats.mean << " max " << stats.max << " spacing " << spacing);
  REQUIRE(stats.max <= 1.5 * spacing);
  REQUIRE(stats.mean == Approx(spacing).epsilon(0.15));
  REQUIRE(stats.min >= 0.25 * spacing);
}

// Every point of every sharp edge is near an edge or corner node: within half a spacing along the
// edge and about a quarter spacing in from it (nodes sit at their cells' centroids), `reach`
// spacings in all.
void requireSharpEdgesCarryNodes(const Sampled& s, double spacing, double reach = 0.65) {
  std::vector<Eigen::Vector3d> featureNodes;
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    if (s.nodes.kinds[i] != NodeKind::Face) featureNodes.push_back(s.nodes.positions[i]);
  int sharp = 0;
  for (std::size_t e = 0; e < s.features.topology.edges.size(); ++e) {
    if (!s.features.edgeIsSharp[e]) continue;
    ++sharp;
    const auto& v = s.features.topology.edges[e].vertices;
    const Eigen::Vector3d a = s.mesh.vertices[v[0]], b = s.mesh.vertices[v[1]];
    for (double w = 0; w <= 1.0; w += 0.05) {
      const Eigen::Vector3d x = (1 - w) * a + w * b;
      double best = 1e300;
      for (const auto& n : featureNodes) best = std::min(best, (n - x).norm());
      REQUIRE(best <= reach * spacing);
    }
  }
  REQUIRE(sharp > 0);
}

void requireOutwardUnitNormals(const Sampled& s) {
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    REQUIRE(s.nodes.normals[i].norm() == Approx(1.0).epsilon(1e-12));
    REQUIRE(s.nodes.areas[i] > 0);
  }
}

}  // namespace

TEST_CASE("planar block nodes: exact area, uniform spacing, nodes on every edge and corner") {
  const double spacing = 0.6e-3;
  const Sampled s = sample(makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180), spacing);
  REQUIRE(s.features.patchCount == 6);
  REQUIRE(s.features.corners.size() == 8);
  REQUIRE(s.features.chains.size() == 12);
  requireAreaSums(s);
  requireSpacing(s, spacing);
  requireSharpEdgesCarryNodes(s, spacing);
  requireOutwardUnitNormals(s);
  // A corner node per face meeting at each corner: 8 x 3.
  REQUIRE(std::count(s.nodes.kinds.begin(), s.nodes.kinds.end(), NodeKind::Corner) == 24);
  // On a flat face every node carries the face normal exactly.
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    for (int t = 0; t < static_cast<int>(s.mesh.triangles.size()); ++t)
      if (s.features.trianglePatch[t] == s.nodes.patches[i])
        REQUIRE(s.nodes.normals[i].dot(triangleAreaVector(s.mesh, t).normalized()) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("L-prism nodes: the concave edge carries nodes too") {
  const double spacing = 0.1;
  const Sampled s = sample(test::lPrism(1.0), spacing);
  REQUIRE(s.features.patchCount == 8);
  requireAreaSums(s);
  requireSpacing(s, spacing);
  requireSharpEdgesCarryNodes(s, spacing);
  requireOutwardUnitNormals(s);
}

TEST_CASE("icosphere nodes: one smooth patch, face nodes only, outward normals") {
  const double spacing = 0.15;
  const Sampled s = sample(test::icosphere(1.0, 3), spacing);
  REQUIRE(s.features.patchCount == 1);
  REQUIRE(s.features.corners.empty());
  requireAreaSums(s);
  requireSpacing(s, spacing);
  requireOutwardUnitNormals(s);
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    REQUIRE(s.nodes.kinds[i] == NodeKind::Face);
    REQUIRE(s.nodes.normals[i].dot(s.nodes.positions[i].normalized()) > 0.98);
  }
}

TEST_CASE("torus nodes: smooth, non-convex, weights still sum to the area") {
  const double spacing = 0.1;
  const Sampled s = sample(test::torus(1.0, 0.4, 48, 24), spacing);
  REQUIRE(s.features.patchCount == 1);
  requireAreaSums(s);
  requireSpacing(s, spacing);
  requireOutwardUnitNormals(s);
}

// A node at its cell's centroid lies off a curved face by the cell's sagitta (about kappa l^2 / 8:
// 2 mm on this sphere at l = 0.15, 10 um on the osteomorphic block's faces); on the surface, a
// matching neighbour reads no overlap.
TEST_CASE("nodes on curved faces lie on the surface, not at their cells' centroids inside or outside it") {
  const Sampled sphere = sample(test::icosphere(1.0, 3), 0.15), torus = sample(test::torus(1.0, 0.4, 48, 24), 0.1),
                osteo = sample(makeOsteomorphicBlock(10e-3, 10e-3, 3.18e-3, 0.5e-3, 0.5e-3, 12), 0.6e-3, 0.3e-3);
  for (const Sampled* s : {&sphere, &torus, &osteo}) {
    const PointMeshDistance distance(s->mesh);
    double size = 0, farthest = 0;
    for (const Eigen::Vector3d& v : s->mesh.vertices) size = std::max(size, v.cwiseAbs().maxCoeff());
    for (const Eigen::Vector3d& x : s->nodes.positions) farthest = std::max(farthest, distance.distance(x));
    REQUIRE(farthest < 1e-12 * size);
    requireAreaSums(*s);
  }
}

TEST_CASE("node sampling is deterministic") {
  const Sampled a = sample(test::lPrism(1.0), 0.2), b = sample(test::lPrism(1.0), 0.2);
  REQUIRE(a.nodes.positions == b.nodes.positions);
  REQUIRE(a.nodes.areas == b.nodes.areas);
}

TEST_CASE("halving the spacing roughly quadruples the node count") {
  const TriangleMesh block = makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180);
  const double coarse = static_cast<double>(sample(block, 0.6e-3).nodes.size());
  const double fine = static_cast<double>(sample(block, 0.3e-3).nodes.size());
  REQUIRE(fine / coarse == Approx(4.0).epsilon(0.15));
}

TEST_CASE("graded nodes: exact areas, the edge spacing along the edges, the face spacing beyond the band") {
  // l(d) = min(s, s_e + g d): s_e = 0.15 mm at the edges, s = 0.6 mm from d = 0.9 mm on.
  const double spacing = 0.6e-3, edge = 0.15e-3, gradient = 0.5;
  const Sampled s = sample(makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180), spacing, edge, gradient);
  const Sampled uniform = sample(makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180), spacing);
  requireAreaSums(s);
  requireOutwardUnitNormals(s);
  // Every point of an edge within 0.75 s_e of an edge node (measured 0.68): the cells along the
  // edge reach farther in than with uniform nodes, and their centroids with them.
  requireSharpEdgesCarryNodes(s, edge, 0.75);
  REQUIRE(std::count(s.nodes.kinds.begin(), s.nodes.kinds.end(), NodeKind::Corner) == 24);
  REQUIRE(s.nodes.size() > 2 * uniform.nodes.size());
  // The nearest-node distance follows l(d): near s_e along the edges, near s beyond the band, and
  // in between on the way (means over bins of d, within 25 %).
  const std::vector<double> gaps = nearestNeighbourDistances(s.nodes.positions, s.nodes.patches);
  const double band = (spacing - edge) / gradient;
  for (const auto& [from, to] : std::vector<std::pair<double, double>>{{0, 0.1 * band}, {0.4 * band, 0.6 * band},
                                                                       {1.2 * band, 1e9}}) {
    double sum = 0, expected = 0;
    int n = 0;
    for (std::size_t i = 0; i < s.nodes.size(); ++i) {
      const double d = distanceToSharpEdge(s, s.nodes.positions[i]);
      if (d < from || d >= to) continue;
      sum += gaps[i];
      expected += std::min(spacing, edge + gradient * d);
      ++n;
    }
    INFO("d in [" << from << ", " << to << "): " << n << " nodes, mean gap " << sum / n << " against l(d) " << expected / n);
    REQUIRE(n > 20);
    REQUIRE(sum / n == Approx(expected / n).epsilon(0.25));
  }
}

TEST_CASE("graded nodes at the steepest gradient allowed (100) end, with exact areas and the edge spacing at the edges") {
  // A band of (s - s_e) / g = 4.5 um: the edges' look-up grid once had cells that small, and a
  // look-up over a sub-triangle visited ~10^9 of them (no end in 300 s; issue #39).
  const Sampled s = sample(makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180), 0.6e-3, 0.15e-3, 100);
  const Sampled gentle = sample(makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180), 0.6e-3, 0.15e-3, 0.5);
  requireAreaSums(s);
  requireSharpEdgesCarryNodes(s, 0.6e-3);  // as uniform nodes do: only a 4.5 um band is finer
  REQUIRE(s.nodes.size() < gentle.nodes.size());  // the band is almost gone
}

TEST_CASE("graded nodes on non-convex and smooth meshes: exact areas, and an edge spacing of 1 is uniform") {
  requireAreaSums(sample(test::lPrism(1.0), 0.1, 0.025));
  requireAreaSums(sample(makeWaveBlock(10e-3, 3.18e-3, 5 * M_PI / 180, 0.2e-3, 1, 24), 0.6e-3, 0.15e-3));
  // No sharp edge: the same nodes as uniform.
  REQUIRE(sample(test::icosphere(1.0, 3), 0.15, 0.05).nodes.positions == sample(test::icosphere(1.0, 3), 0.15).nodes.positions);
  // An edge spacing at or above the spacing is uniform.
  const TriangleMesh prism = test::lPrism(1.0);
  REQUIRE(sample(prism, 0.1, 0.1).nodes.positions == sample(prism, 0.1).nodes.positions);
  REQUIRE(sample(prism, 0.1, 0.3).nodes.positions == sample(prism, 0.1).nodes.positions);
}

TEST_CASE("graded nodes do not depend on the mesh's scale: a 100x larger block gets the same nodes, in proportion") {
  const Sampled small = sample(makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180), 0.6e-3, 0.15e-3);
  const Sampled large = sample(makePlanarBlock(1.0, 0.318, 5 * M_PI / 180), 0.06, 0.015);
  REQUIRE(large.nodes.size() == small.nodes.size());
  double areaSmall = 0, areaLarge = 0;
  for (std::size_t i = 0; i < small.nodes.size(); ++i) {
    areaSmall += small.nodes.areas[i];
    areaLarge += large.nodes.areas[i];
  }
  REQUIRE(areaLarge == Approx(1e4 * areaSmall).epsilon(1e-9));
}

TEST_CASE("node options out of range are refused") {
  const TriangleMesh block = makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180);
  REQUIRE_THROWS_AS(sample(block, 0.0), InputError);
  REQUIRE_THROWS_AS(sample(block, 0.6e-3, 0.15e-3, 0.0), InputError);
}
