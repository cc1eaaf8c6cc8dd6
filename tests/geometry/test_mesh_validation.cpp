// Validation: each kind of broken mesh is refused with a message naming the problem;
// a consistently inverted mesh is repaired.
#include "geometry/block_generators.h"
#include "io/input_error.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_validation.h"
#include "tests/fixtures/analytic_meshes.h"
#include "tests/fixtures/bad_meshes.h"

#include <catch2/catch.hpp>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {
void requireRefused(TriangleMesh mesh, const std::string& expected) {
  REQUIRE_THROWS_WITH(validateSolidMesh(mesh, "part.stl"), Contains("part.stl") && Contains(expected));
}
}  // namespace

TEST_CASE("valid closed meshes pass unchanged") {
  for (TriangleMesh mesh : {makeBox(1, 2, 3), makePlanarBlock(10, 3.18, 0.087), test::octahedron(1),
                            test::icosphere(1, 2), test::lPrism(1)}) {
    const auto before = mesh.triangles;
    REQUIRE_FALSE(validateSolidMesh(mesh, "ok").reoriented);
    REQUIRE(mesh.triangles == before);
  }
}

TEST_CASE("an inside-out mesh is re-oriented outward and reported") {
  TriangleMesh mesh = test::invertedBox();
  REQUIRE(signedVolume(mesh) < 0);
  REQUIRE(validateSolidMesh(mesh, "inv").reoriented);
  REQUIRE(signedVolume(mesh) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("a torus (genus 1) is a valid solid") {
  TriangleMesh mesh = test::torus(2, 0.5, 24, 12);
  validateSolidMesh(mesh, "torus");
  REQUIRE(signedVolume(mesh) > 0);
}

TEST_CASE("broken meshes are refused with the reason") {
  requireRefused(test::openBox(), "open (not watertight): 3 boundary edge(s)");
  requireRefused(test::selfIntersectingBox(), "self-intersecting");
  requireRefused(test::nonManifoldEdgeMesh(), "non-manifold: 1 edge(s) shared by more than two triangles");
  requireRefused(test::nonManifoldVertexMesh(), "non-manifold: 1 vertex(es)");
  requireRefused(test::flatMesh(), "encloses no volume");
  requireRefused(test::inconsistentBox(), "inconsistent orientation");
  requireRefused(test::twoSeparateBoxes(), "2 separate pieces");
  TriangleMesh two = makeBox(1, 1, 1);
  two.triangles.resize(2);
  requireRefused(two, "only 2 triangle(s)");
  TriangleMesh sliver = makeBox(1, 1, 1);
  sliver.vertices.push_back(Eigen::Vector3d(0.5, 0.5, 0.5));
  sliver.triangles.push_back({0, 1, 8});
  sliver.vertices[8] = sliver.vertices[0] + 0.5 * (sliver.vertices[1] - sliver.vertices[0]);
  requireRefused(sliver, "zero area");
}
