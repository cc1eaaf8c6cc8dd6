// Cross-sections of closed meshes against closed-form areas, in any pose.
#include "geometry/block_generators.h"
#include "geometry/mesh_section.h"
#include "tests/fixtures/analytic_meshes.h"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

using namespace tessera;
using namespace tessera::test;

TEST_CASE("a section of a box is its face at every height, and nothing outside it", "[geometry][section]") {
  const TriangleMesh box = makeBox(2.0, 3.0, 0.5);  // centred at the origin
  for (double z : {-0.2, 0.0, 0.1, 0.2499}) REQUIRE(sectionArea(box, Eigen::Vector3d::UnitZ(), z) == Approx(6.0).epsilon(1e-12));
  for (double x : {-0.9, 0.3}) REQUIRE(sectionArea(box, Eigen::Vector3d::UnitX(), x) == Approx(1.5).epsilon(1e-12));
  REQUIRE(sectionArea(box, Eigen::Vector3d::UnitZ(), 0.3) == 0.0);
  REQUIRE(sectionArea(box, -Eigen::Vector3d::UnitZ(), 0.2) == Approx(6.0).epsilon(1e-12));  // the normal's sign
}

TEST_CASE("a section of an octahedron is the square 2 (r - |c|)^2, rotated and moved too", "[geometry][section]") {
  const double r = 3.0;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(10.0, -4.0, 2.5);
  const TriangleMesh moved = transformed(octahedron(r), R, t);
  for (double c : {-2.5, -1.0, 0.0, 0.4, 2.9}) {
    const double expected = 2 * (r - std::abs(c)) * (r - std::abs(c));
    REQUIRE(sectionArea(octahedron(r), Eigen::Vector3d::UnitZ(), c) == Approx(expected).epsilon(1e-12));
    const Eigen::Vector3d n = R * Eigen::Vector3d::UnitZ();
    REQUIRE(sectionArea(moved, n, c + n.dot(t)) == Approx(expected).epsilon(1e-10));
  }
}

TEST_CASE("a section of a non-convex L prism adds its loops", "[geometry][section]") {
  const double s = 2.0;  // the union of [0,2s]x[0,s]x[0,s] and [0,s]x[s,2s]x[0,s]
  const TriangleMesh l = lPrism(s);
  REQUIRE(sectionArea(l, Eigen::Vector3d::UnitZ(), 0.5 * s) == Approx(3 * s * s).epsilon(1e-12));
  REQUIRE(sectionArea(l, Eigen::Vector3d::UnitX(), 0.5 * s) == Approx(2 * s * s).epsilon(1e-12));
  REQUIRE(sectionArea(l, Eigen::Vector3d::UnitX(), 1.5 * s) == Approx(s * s).epsilon(1e-12));
  // The plane x + y = 1.5 s crosses the corner in one loop, 1.5 s sqrt(2) long; x + y = 2.5 s
  // cuts the two arms' ends apart, two loops of s/2 sqrt(2) each.
  const Eigen::Vector3d diagonal = Eigen::Vector3d(1, 1, 0).normalized();
  REQUIRE(sectionArea(l, diagonal, 1.5 * s / std::sqrt(2.0)) == Approx(1.5 * std::sqrt(2.0) * s * s).epsilon(1e-12));
  REQUIRE(sectionArea(l, diagonal, 2.5 * s / std::sqrt(2.0)) == Approx(std::sqrt(2.0) * s * s).epsilon(1e-12));
}
