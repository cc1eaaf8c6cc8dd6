// The exact mesh level set against CGAL's exact distances and winding-number signs, on meshes with
// re-entrant edges and saddle vertices (an L-prism, a torus, the wave block); its sign and
// gradient at re-entrant edges and vertices; its gradient against finite differences.
#include "tests/fixtures/analytic_meshes.h"
#include "tests/fixtures/mesh_distance.h"
#include "geometry/block_generators.h"
#include "geometry/point_mesh_distance.h"
#include "levelset/mesh_sdf_builder.h"
#include "levelset/signed_distance.h"

#include <catch2/catch.hpp>

#include <random>

using namespace tessera;

namespace {

struct ExactMesh {
  TriangleMesh mesh;
  DenseSdf grid;
  MeshSdf sdf;
  ExactMesh(TriangleMesh m, double voxel) : mesh(std::move(m)) {
    SignedDistanceOptions options;
    options.voxelSize = voxel;
    grid = buildSignedDistance(mesh, options);
    sdf = buildMeshSdf(mesh, grid, 3 * voxel);
  }
};

// Points within the band of the surface, inside and outside: random points of the grid's box kept
// when the grid says they are near the surface.
std::vector<Eigen::Vector3d> pointsNearSurface(const ExactMesh& e, int count, double band, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d lo = e.grid.origin, span = e.grid.upperCorner() - lo;
  std::vector<Eigen::Vector3d> points;
  while (static_cast<int>(points.size()) < count) {
    const Eigen::Vector3d x = lo + span.cwiseProduct(Eigen::Vector3d(unit(random), unit(random), unit(random)));
    if (std::abs(e.grid.value(x)) < band) points.push_back(x);
  }
  return points;
}

void checkAgainstReferences(const ExactMesh& e, double band, unsigned seed) {
  const PointMeshDistance cgal(e.mesh);
  int evaluated = 0;
  for (const Eigen::Vector3d& x : pointsNearSurface(e, 300, band, seed)) {
    double phi = 0;
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
    if (!e.sdf.evaluate(x, phi, gradient)) continue;
    ++evaluated;
    const double distance = cgal.distance(x);
    INFO("x = " << x.transpose() << ", phi = " << phi << ", CGAL distance = " << distance);
    CHECK(std::abs(std::abs(phi) - distance) <= 1e-12 * std::max(distance, e.grid.voxelSize));
    const bool inside = test::windingNumber(e.mesh, x) > 0.5;
    if (distance > 1e-9 * e.grid.voxelSize) CHECK((phi < 0) == inside);
    CHECK(std::abs(gradient.norm() - 1.0) < 1e-12);
  }
  CHECK(evaluated > 260);  // every point within the band has a list (a few fall outside: grid rounding)
}

}  // namespace

TEST_CASE("exact mesh level set: distances equal CGAL's to 1e-12 and signs the winding number's, near re-entrant edges") {
  SECTION("L-prism (a re-entrant edge and two saddle vertices)") {
    const ExactMesh e(test::lPrism(4e-3), 0.25e-3);
    checkAgainstReferences(e, 2 * 0.25e-3, 1);
  }
  SECTION("torus (curved, saddle vertices all round its inner side)") {
    const ExactMesh e(test::torus(4e-3, 1.5e-3, 24, 12), 0.2e-3);
    checkAgainstReferences(e, 2 * 0.2e-3, 2);
  }
  SECTION("wave block (corrugated lateral faces)") {
    const ExactMesh e(makeWaveBlock(10e-3, 3.18e-3, 5.0 * M_PI / 180, 0.2e-3, 1, 24), 0.25e-3);
    checkAgainstReferences(e, 2 * 0.25e-3, 3);
  }
}

TEST_CASE("exact mesh level set: sign and gradient at the re-entrant edge and vertex of an L-prism") {
  // The notch's re-entrant edge runs along z at (s, s); its faces x = s (y > s) and y = s (x > s)
  // face +x and +y; outside is the quadrant x > s, y > s. Outside, the faces are closest; inside,
  // the edge itself.
  const double s = 4e-3, voxel = 0.25e-3;
  const ExactMesh e(test::lPrism(s), voxel);
  const Eigen::Vector3d edge(s, s, 0.5 * s), bisector = Eigen::Vector3d(1, 1, 0).normalized();
  double phi = 0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  for (double d : {1e-9, 1e-6, 0.1e-3, 0.5e-3}) {
    INFO("d = " << d);
    REQUIRE(e.sdf.evaluate(edge - d * bisector, phi, gradient));  // inside: the edge is closest
    CHECK(phi == Approx(-d).epsilon(1e-9));
    CHECK((gradient - bisector).norm() < 1e-9);  // away from the edge, outward
    REQUIRE(e.sdf.evaluate(edge + Eigen::Vector3d(3 * d, d, 0), phi, gradient));  // outside: the face y = s
    CHECK(phi == Approx(d).epsilon(1e-9));
    CHECK((gradient - Eigen::Vector3d::UnitY()).norm() < 1e-9);
  }
  // At the edge's end on the top face, the vertex (s, s, s): just inside along the inward
  // diagonal the top face is closest (a below it); just outside along the outward diagonal the top
  // edges of the notch's faces are (a sqrt 2 away).
  const Eigen::Vector3d vertex(s, s, s);
  const double a = 1e-6 / std::sqrt(3.0);
  REQUIRE(e.sdf.evaluate(vertex - Eigen::Vector3d::Constant(a), phi, gradient));
  CHECK(phi == Approx(-a).epsilon(1e-9));
  CHECK((gradient - Eigen::Vector3d::UnitZ()).norm() < 1e-9);
  REQUIRE(e.sdf.evaluate(vertex + Eigen::Vector3d::Constant(a), phi, gradient));
  CHECK(phi == Approx(a * std::sqrt(2.0)).epsilon(1e-9));
  // On the edge itself: phi 0 and an outward direction (the edge's pseudo-normal, or a face's).
  REQUIRE(e.sdf.evaluate(edge, phi, gradient));
  CHECK(phi == 0.0);
  CHECK(gradient.dot(bisector) > 0.7);
}

TEST_CASE("exact mesh level set: the gradient is the derivative of phi (finite differences, off the medial axis)") {
  const ExactMesh e(makeWaveBlock(10e-3, 3.18e-3, 5.0 * M_PI / 180, 0.2e-3, 1, 24), 0.25e-3);
  const double h = 1e-8;
  int checked = 0;
  for (const Eigen::Vector3d& x : pointsNearSurface(e, 200, 0.5e-3, 7)) {
    double phi, p1 = 0, p2 = 0;
    Eigen::Vector3d gradient = Eigen::Vector3d::Zero(), g;
    if (!e.sdf.evaluate(x, phi, gradient) || std::abs(phi) < 1e-6) continue;
    Eigen::Vector3d numeric;
    bool smooth = true;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d step = h * Eigen::Vector3d::Unit(a);
      smooth = smooth && e.sdf.evaluate(x + step, p1, g) && e.sdf.evaluate(x - step, p2, g);
      numeric[a] = (p1 - p2) / (2 * h);
    }
    if (!smooth || std::abs(numeric.norm() - 1) > 1e-4) continue;  // on the medial axis: phi has a kink
    ++checked;
    CHECK((numeric - gradient).norm() < 1e-5);
  }
  CHECK(checked > 150);
}

TEST_CASE("exact mesh level set: cells beyond the band hold no triangles, and the lists are short") {
  const double voxel = 0.25e-3;
  const ExactMesh e(makeWaveBlock(10e-3, 3.18e-3, 5.0 * M_PI / 180, 0.2e-3, 1, 24), voxel);
  double phi = 0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
  CHECK_FALSE(e.sdf.evaluate(e.grid.origin - Eigen::Vector3d::Constant(1e-3), phi, gradient));  // outside the grid
  CHECK_FALSE(e.sdf.evaluate(Eigen::Vector3d::Zero(), phi, gradient));  // the block's centre: 1.6 mm deep
  std::size_t used = 0;
  for (std::size_t c = 0; c + 1 < e.sdf.cellStart.size(); ++c) used += e.sdf.cellStart[c + 1] > e.sdf.cellStart[c];
  const double mean = double(e.sdf.cellTriangles.size()) / double(used);
  INFO(used << " cells listed, " << mean << " triangles each on average, of " << e.sdf.triangles.size());
  CHECK(mean < 16);
}

TEST_CASE("the grid's trilinear value exceeds the exact phi by at most (sqrt 3 / 2) h, so the solver may trust a grid value above it") {
  // The bound ShapeModel::meshLevelSet relies on: exact, 1-Lipschitz node values, trilinear weights.
  const double voxel = 0.25e-3;
  const ExactMesh e(makeWaveBlock(10e-3, 3.18e-3, 5.0 * M_PI / 180, 0.2e-3, 1, 24), voxel);
  double worst = -INFINITY;
  for (const Eigen::Vector3d& x : pointsNearSurface(e, 1000, 2 * voxel, 11)) {
    const double exact = test::signedDistance(e.mesh, x);
    worst = std::max(worst, e.grid.value(x) - exact);
  }
  INFO("largest overestimate " << worst / voxel << " voxels");
  CHECK(worst <= std::sqrt(3.0) / 2 * voxel * (1 + 1e-9));
  CHECK(worst > 0.05 * voxel);  // the bound is not vacuous: the grid does overestimate near edges
}

TEST_CASE("a grid node proves a point outside only where it is, and often near the surface") {
  // The shortcut ShapeModel::candidateValue takes before the exact search: phi(x) >= v_i - |x - c_i|.
  const double voxel = 0.25e-3;
  const ExactMesh e(makeWaveBlock(10e-3, 3.18e-3, 5.0 * M_PI / 180, 0.2e-3, 1, 24), voxel);
  int near = 0, proven = 0;
  for (const Eigen::Vector3d& x : pointsNearSurface(e, 2000, std::sqrt(3.0) / 2 * voxel, 12)) {
    const double exact = test::signedDistance(e.mesh, x), bound = e.grid.provenOutside(x);
    INFO("x = " << x.transpose() << ", exact phi " << exact << ", bound " << bound);
    REQUIRE(bound >= 0);
    if (bound > 0) REQUIRE(bound <= exact);
    if (exact > 0.1 * voxel) {
      ++near;
      proven += bound > 0;
    }
  }
  INFO(proven << " of " << near << " points farther than 0.1 voxel outside proven outside");
  CHECK(proven > 0.5 * near);
}

namespace {

// Points near the surface walked in random steps (most of `step`, some of `jump`), each evaluated
// with the NearestFace it kept and without: the results must be the same bits. Returns the share
// of the evaluations at a point projecting onto a face that the kept NearestFace settled (it is
// left unchanged then: the search would have moved it to x).
double keptNearestFaceAgrees(const ExactMesh& e, double step, double jump, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int settled = 0, onFace = 0;
  for (Eigen::Vector3d x : pointsNearSurface(e, 200, e.grid.voxelSize, seed)) {
    MeshSdf::NearestFace kept;
    for (int k = 0; k < 40; ++k) {
      const Eigen::Vector3d direction(gauss(random), gauss(random), gauss(random));
      x += (unit(random) < 0.1 ? jump : step) * direction.normalized();
      double phi = 0, reference = 0;
      Eigen::Vector3d gradient = Eigen::Vector3d::Zero(), referenceGradient = Eigen::Vector3d::Zero();
      const MeshSdf::NearestFace before = kept;
      const bool found = e.sdf.evaluate(x, phi, gradient, kept);
      INFO("x = " << x.transpose() << ", step " << k);
      REQUIRE(found == e.sdf.evaluate(x, reference, referenceGradient));
      if (!found) continue;
      REQUIRE(phi == reference);  // bit for bit
      REQUIRE(gradient == referenceGradient);
      const bool keptAgain = kept.at == before.at && before.clearance > 0;
      if (keptAgain || kept.clearance > 0) {
        ++onFace;
        settled += keptAgain;
      }
    }
  }
  return double(settled) / std::max(onFace, 1);
}

}  // namespace

TEST_CASE("exact mesh level set: a kept NearestFace gives the search's bits, and settles most points that move a little") {
  // A step of the solver moves a node by nanometres; jumps of a fifth of a voxel within and across
  // cells test that the proof never settles a point whose nearest triangle it does not prove.
  SECTION("wave block (faces 0.13 mm wide)") {
    const ExactMesh e(makeWaveBlock(10e-3, 3.18e-3, 5.0 * M_PI / 180, 0.2e-3, 1, 24), 0.25e-3);
    const double share = keptNearestFaceAgrees(e, 1e-7, 0.05e-3, 21);
    INFO(share << " of the evaluations on a face settled by the kept NearestFace");
    CHECK(share > 0.8);
  }
  SECTION("L-prism (a re-entrant edge)") {
    const ExactMesh e(test::lPrism(4e-3), 0.25e-3);
    CHECK(keptNearestFaceAgrees(e, 1e-7, 0.05e-3, 22) > 0.8);
  }
  SECTION("wave block 100 times larger (a 1 m block, 25 mm voxels): the rule scales with the cell") {
    const ExactMesh e(makeWaveBlock(1.0, 0.318, 5.0 * M_PI / 180, 0.02, 1, 24), 25e-3);
    CHECK(keptNearestFaceAgrees(e, 1e-5, 5e-3, 24) > 0.8);
  }
  SECTION("torus (curved)") {
    const ExactMesh e(test::torus(4e-3, 1.5e-3, 24, 12), 0.2e-3);
    CHECK(keptNearestFaceAgrees(e, 1e-7, 0.05e-3, 23) > 0.5);
  }
}
