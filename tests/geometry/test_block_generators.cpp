// Generated blocks are valid solids with the closed-form volume; the shipped default block
// is the generator's planar block.
#include "geometry/block_generators.h"
#include "geometry/input_error.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_import.h"
#include "geometry/mesh_validation.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tessera;

TEST_CASE("planar block: valid, closed-form volume, faces inclined by theta") {
  for (double degrees : {0.0, 5.0, 12.0}) {
    const double a = 10, h = 3.18, theta = degrees * M_PI / 180;
    TriangleMesh block = makePlanarBlock(a, h, theta);
    REQUIRE_FALSE(validateSolidMesh(block, "planar").reoriented);
    REQUIRE(signedVolume(block) == Approx(a * a * h - h * h * h * std::pow(std::tan(theta), 2) / 3).epsilon(1e-12));
    // Top face: wider in x, narrower in y, by h tan(theta).
    const Eigen::AlignedBox3d box = boundingBox(block.vertices);
    REQUIRE(box.sizes().x() == Approx(a + h * std::tan(theta)).epsilon(1e-12));
    REQUIRE(box.sizes().z() == Approx(h).epsilon(1e-12));
  }
  REQUIRE_THROWS_AS(makePlanarBlock(1, 3, 80 * M_PI / 180), InputError);
  REQUIRE_THROWS_AS(makeBox(1, 0, 1), InputError);
}

TEST_CASE("the default block in assets/ is the generator's planar block (a 10, h 3.18, 5 deg)") {
  MeshImportOptions options;
  options.metresPerUnit = 1e-3;
  const ImportedMesh asset = importMesh(TESSERA_ASSETS "/blocks/planar_a10_h3.18_5deg.obj", options);
  const TriangleMesh generated = makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180);
  REQUIRE(asset.mesh.triangles.size() == generated.triangles.size());
  for (int t = 0; t < static_cast<int>(generated.triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) REQUIRE((triangleCorner(asset.mesh, t, k) - triangleCorner(generated, t, k)).norm() < 1e-9);
}
