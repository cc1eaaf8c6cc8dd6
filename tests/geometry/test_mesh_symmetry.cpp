// Symmetries of blocks and of their surface nodes: findSymmetries finds the point group of the
// generated blocks (in any pose), and the node sets carry it to rounding, with exact area sums.
#include "geometry/block_generators.h"
#include "geometry/mesh_features.h"
#include "geometry/mesh_symmetry.h"
#include "geometry/mesh_validation.h"
#include "geometry/surface_nodes.h"
#include "tests/fixtures/analytic_meshes.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <numeric>

using namespace tessera;

namespace {

struct Block {
  TriangleMesh mesh;
  MeshFeatures features;
  double size;
};

Block prepared(TriangleMesh mesh) {
  validateSolidMesh(mesh, "fixture");
  Block b{mesh, findFeatures(mesh, 30 * M_PI / 180), 0.0};
  b.size = boundingBox(b.mesh.vertices).diagonal().norm();
  return b;
}

SymmetryGroup symmetriesOf(const Block& b) { return findSymmetries(b.mesh, b.features, 1e-6 * b.size); }

SurfaceNodes nodesOf(const Block& b, double spacing, double edgeSpacing, bool keepSymmetries = true) {
  SurfaceNodeOptions options;
  options.spacing = spacing;
  options.edgeSpacing = edgeSpacing;
  options.keepSymmetries = keepSymmetries;
  return sampleSurfaceNodes(b.mesh, b.features, options);
}

// The largest distance, in units of `size`, from the image of a node under x -> centre + q (x -
// centre) to the nearest node carrying the same area and normal (mapped); infinity when some
// image has no such node.
double symmetryDefect(const SurfaceNodes& nodes, const Eigen::Vector3d& centre, const Eigen::Matrix3d& q, double size) {
  double worst = 0.0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Vector3d image = centre + q * (nodes.positions[i] - centre);
    double best = INFINITY;
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      if (std::abs(nodes.areas[j] - nodes.areas[i]) > 1e-9 * nodes.areas[i]) continue;
      if ((nodes.normals[j] - q * nodes.normals[i]).norm() > 1e-9) continue;
      best = std::min(best, (nodes.positions[j] - image).norm() / size);
    }
    worst = std::max(worst, best);
  }
  return worst;
}

void requirePatchAreaSums(const Block& b, const SurfaceNodes& nodes) {
  std::map<int, double> nodeArea, patchArea;
  for (std::size_t i = 0; i < nodes.size(); ++i) nodeArea[nodes.patches[i]] += nodes.areas[i];
  for (int t = 0; t < static_cast<int>(b.mesh.triangles.size()); ++t)
    patchArea[b.features.trianglePatch[t]] += triangleArea(b.mesh, t);
  for (const auto& [patch, area] : patchArea) REQUIRE(nodeArea[patch] == Approx(area).epsilon(1e-12));
}

Eigen::Matrix3d mirror(const Eigen::Vector3d& normal) {
  const Eigen::Vector3d n = normal.normalized();
  return Eigen::Matrix3d::Identity() - 2 * n * n.transpose();
}

}  // namespace

TEST_CASE("symmetry groups of the generated blocks, in any pose") {
  const double theta = 5 * M_PI / 180;
  // Box a x b x h: D2h (8). Cube: Oh (48). Planar block: D2d (8; the faces lean in along one
  // axis and out along the other). Hex block: D3d (12; the faces lean alternately).
  // Osteomorphic block: its waves keep the two mirrors through the axes.
  REQUIRE(symmetriesOf(prepared(makeBox(3, 2, 1))).size() == 8);
  REQUIRE(symmetriesOf(prepared(makeBox(1, 1, 1))).size() == 48);
  REQUIRE(symmetriesOf(prepared(makePlanarBlock(10e-3, 3.18e-3, theta))).size() == 8);
  REQUIRE(symmetriesOf(prepared(makeHexBlock(5e-3, 3.18e-3, theta))).size() == 12);
  REQUIRE(symmetriesOf(prepared(test::lPrism(1.0))).size() == 4);
  // In a tilted, shifted pose the same groups, about the centroid.
  const Eigen::Matrix3d pose = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Block tilted = prepared(test::transformed(makePlanarBlock(10e-3, 3.18e-3, theta), pose, Eigen::Vector3d(1, -2, 0.5)));
  const SymmetryGroup group = symmetriesOf(tilted);
  REQUIRE(group.size() == 8);
  REQUIRE((group.centre - Eigen::Vector3d(1, -2, 0.5)).norm() < 1e-12);
  // Every element is orthogonal and the products stay in the group.
  for (const Eigen::Matrix3d& q : group.elements) REQUIRE((q * q.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-9);
  // A block with no symmetry but the identity: a box with one corner cut off at an odd plane.
  TriangleMesh skew = makeBox(3, 2, 1);
  skew.vertices[0] += Eigen::Vector3d(0.21, 0.13, 0.07);
  REQUIRE(symmetriesOf(prepared(skew)).size() == 1);
}

TEST_CASE("surface nodes keep the block's symmetries to rounding, with exact area sums") {
  const double theta = 5 * M_PI / 180;
  struct Case {
    const char* name;
    TriangleMesh mesh;
    double spacing;
  };
  const std::vector<Case> cases{
      {"planar", makePlanarBlock(10e-3, 3.18e-3, theta), 0.6e-3},
      {"hex", makeHexBlock(5e-3, 3.18e-3, theta), 0.6e-3},
      {"osteomorphic", makeOsteomorphicBlock(10e-3, 10e-3, 3.18e-3, 1e-3, 0.0, 6), 0.8e-3},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const Block b = prepared(c.mesh);
    const SymmetryGroup group = symmetriesOf(b);
    REQUIRE(group.size() > 1);
    for (const double edgeSpacing : {0.0, 0.5 * c.spacing}) {
      const SurfaceNodes nodes = nodesOf(b, c.spacing, edgeSpacing);
      REQUIRE(nodes.symmetries == group.size());
      REQUIRE(keptSymmetries(nodes, group, 1e-12 * b.size) == group.size());
      for (std::size_t g = 0; g < group.size(); ++g)
        REQUIRE(symmetryDefect(nodes, group.centre, group.elements[g], b.size) < 1e-12);
      requirePatchAreaSums(b, nodes);
      // Without the option the sampler gives the asymmetric set of before.
      const SurfaceNodes plain = nodesOf(b, c.spacing, edgeSpacing, false);
      double worst = 0.0;
      for (std::size_t g = 0; g < group.size(); ++g)
        worst = std::max(worst, symmetryDefect(plain, group.centre, group.elements[g], b.size));
      REQUIRE(worst > 1e-6);
      REQUIRE(keptSymmetries(plain, group, 1e-12 * b.size) < group.size());
    }
  }
  // The planar block's two mirrors, written exactly: x -> -x and y -> -y about the centroid.
  const Block planar = prepared(makePlanarBlock(10e-3, 3.18e-3, theta));
  const SurfaceNodes nodes = nodesOf(planar, 0.6e-3, 0.3e-3);
  const Eigen::Vector3d centre = symmetriesOf(planar).centre;
  REQUIRE(symmetryDefect(nodes, centre, mirror({1, 0, 0}), planar.size) < 1e-12);
  REQUIRE(symmetryDefect(nodes, centre, mirror({0, 1, 0}), planar.size) < 1e-12);
  // The mean of the nodes (area-weighted) is the surface's centroid, on both mirrors.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    mean += nodes.areas[i] * nodes.positions[i];
    total += nodes.areas[i];
  }
  mean /= total;
  REQUIRE(std::abs(mean.x() - centre.x()) < 1e-12 * planar.size);
  REQUIRE(std::abs(mean.y() - centre.y()) < 1e-12 * planar.size);
}
