// Convex polyhedra as exact planes: exact meshes, meshes rounded as exporters write them, and
// non-convex meshes that must stay on the grid.
#include "geometry/block_generators.h"
#include "geometry/convex_planes.h"
#include "tests/fixtures/analytic_meshes.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tessera;

namespace {

// The mesh as a design tool exports it: placed in the world in metres, coordinates rounded to
// `decimals` decimals.
TriangleMesh exported(TriangleMesh mesh, int decimals) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  mesh = test::transformed(mesh, R, Eigen::Vector3d(1.234567, -0.5, 2.25));
  const double q = std::pow(10.0, decimals);
  for (auto& v : mesh.vertices) v = (v * q).array().round().matrix() / q;
  return mesh;
}

double distanceOff(const FacePlane& p, const Eigen::Vector3d& x) { return p.normal.dot(x) - p.offset; }

}  // namespace

TEST_CASE("a box and the paper's block give their exact face planes") {
  const auto box = fitConvexPolyhedron(makeBox(8e-3, 4e-3, 2e-3));
  REQUIRE(box);
  REQUIRE(box->planes.size() == 6);
  REQUIRE(box->deviation < 1e-15);
  for (const FacePlane& p : box->planes) REQUIRE(p.normal.cwiseAbs().maxCoeff() == Approx(1.0).epsilon(1e-15));
  const auto block = fitConvexPolyhedron(makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180));
  REQUIRE(block);
  REQUIRE(block->planes.size() == 6);  // top, bottom and four tilted sides
}

TEST_CASE("a convex part exported with 6-decimal metre coordinates is still convex: planes fitted to its faces") {
  // A 180 mm block of the size the design tools export; rounding moves vertices by up to 5e-7 m.
  const TriangleMesh mesh = exported(makePlanarBlock(0.18, 0.06, 10 * M_PI / 180), 6);
  const auto fit = fitConvexPolyhedron(mesh);
  REQUIRE(fit);
  REQUIRE(fit->planes.size() == 6);
  REQUIRE(fit->deviation < 2e-6);
  REQUIRE(fit->deviation <= fit->tolerance);
  // Every vertex is within the deviation of the fitted polyhedron's surface.
  for (const auto& v : mesh.vertices) {
    double phi = -1e9;
    for (const FacePlane& p : fit->planes) phi = std::max(phi, distanceOff(p, v));
    REQUIRE(std::abs(phi) <= fit->deviation + 1e-15);
  }
}

TEST_CASE("non-convex meshes are refused: an L prism, a wave block, and an octahedron with a shallow dent") {
  REQUIRE_FALSE(fitConvexPolyhedron(test::lPrism(10e-3)));
  REQUIRE_FALSE(fitConvexPolyhedron(makeWaveBlock(10e-3, 3.18e-3, 5 * M_PI / 180, 0.3e-3, 2, 8)));
  // An octahedron with one corner pushed in past the centre plane by 1 % of its size: the four
  // faces around it form a shallow re-entrant dent, 30 x the tolerance.
  TriangleMesh dented = test::octahedron(5e-3);
  dented.vertices[0] = Eigen::Vector3d(-0.01 * 5e-3, 0, 0);
  REQUIRE_FALSE(fitConvexPolyhedron(dented));
}

TEST_CASE("a convex polyhedron with more faces than the solver holds stays on the grid, whatever maxPlanes asks") {
  // A prism over a regular n-gon: n + 2 faces (sides 360 / n degrees apart, each its own plane).
  const auto prism = [](int n) {
    TriangleMesh m;
    for (int z = 0; z < 2; ++z)
      for (int k = 0; k < n; ++k)
        m.vertices.push_back({std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n), z - 0.5});
    m.vertices.push_back({0, 0, -0.5});
    m.vertices.push_back({0, 0, 0.5});
    const int bottom = 2 * n, top = 2 * n + 1;
    for (int k = 0; k < n; ++k) {
      const int a = k, b = (k + 1) % n;
      m.triangles.push_back({a, b, n + b});
      m.triangles.push_back({a, n + b, n + a});
      m.triangles.push_back({bottom, b, a});
      m.triangles.push_back({top, n + a, n + b});
    }
    return m;
  };
  ConvexFitOptions options;
  options.maxPlanes = 1000;
  const auto fewest = fitConvexPolyhedron(prism(kMaxConvexPlanes - 2), options);
  REQUIRE(fewest);
  REQUIRE(fewest->planes.size() == static_cast<std::size_t>(kMaxConvexPlanes));
  REQUIRE_FALSE(fitConvexPolyhedron(prism(kMaxConvexPlanes - 1), options));
}
