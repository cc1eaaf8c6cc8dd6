// Surface nodes: weights sum to the area, spacing is near-uniform, every sharp edge carries nodes,
// normals are the outward face normals.
#include "geometry/block_generators.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_features.h"
#include "geometry/mesh_validation.h"
#include "geometry/point_spacing.h"
#include "geometry/surface_nodes.h"
#include "tests/fixtures/analytic_meshes.h"

#include <catch2/catch.hpp>

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

Sampled sample(TriangleMesh mesh, double spacing) {
  validateSolidMesh(mesh, "fixture");
  Sampled s{mesh, findFeatures(mesh, 30 * M_PI / 180), {}};
  SurfaceNodeOptions options;
  options.spacing = spacing;
  s.nodes = sampleSurfaceNodes(s.mesh, s.features, options);
  return s;
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
// edge and about a quarter spacing in from it (nodes sit at their cells' centroids).
void requireSharpEdgesCarryNodes(const Sampled& s, double spacing) {
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
      REQUIRE(best <= 0.65 * spacing);
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
