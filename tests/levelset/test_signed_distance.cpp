// OpenVDB signed distance against the exact distance to the mesh (brute force), on shapes with
// flat faces, curved faces, a concave edge and a hole.
#include "geometry/block_generators.h"
#include "geometry/mesh_validation.h"
#include "levelset/signed_distance.h"
#include "tests/fixtures/analytic_meshes.h"
#include "tests/fixtures/mesh_distance.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <random>

using namespace tessera;

namespace {

struct Check {
  const char* name;
  TriangleMesh mesh;
  double voxel;
};

// Every grid node, inside and out: the right sign, and the exact distance to within 0.1 voxel.
void requireGridMatchesExactDistance(const Check& c) {
  TriangleMesh mesh = c.mesh;
  validateSolidMesh(mesh, c.name);
  SignedDistanceOptions options;
  options.voxelSize = c.voxel;
  const DenseSdf sdf = buildSignedDistance(mesh, options);
  const double band = options.exteriorBandVoxels * c.voxel;  // the grid's padding
  double worst = 0;
  Eigen::Vector3d worstAt = Eigen::Vector3d::Zero();
  double worstExact = 0;
  int inside = 0;
  for (int i = 0; i < sdf.dims[0]; ++i)
    for (int j = 0; j < sdf.dims[1]; ++j)
      for (int k = 0; k < sdf.dims[2]; ++k) {
        const Eigen::Vector3d x = sdf.nodePosition(i, j, k);
        const double exact = test::signedDistance(mesh, x);
        const double grid = sdf.at(i, j, k);
        if (std::abs(exact) < 1e-3 * c.voxel) continue;  // on the surface: either sign
        INFO(c.name << " node " << x.transpose() << " exact " << exact << " grid " << grid);
        REQUIRE((grid < 0) == (exact < 0));
        if (exact < 0) ++inside;
        if (std::abs(grid - exact) > worst) {
          worst = std::abs(grid - exact);
          worstAt = x;
          worstExact = exact;
        }
      }
  INFO(c.name << ": worst error " << worst / c.voxel << " voxel at " << worstAt.transpose() << " (exact "
              << worstExact << ")");
  REQUIRE(worst <= 0.1 * c.voxel);
  REQUIRE(inside > 0);
  // The padding keeps a band-wide shell of exterior nodes around the shape.
  const Eigen::AlignedBox3d box = boundingBox(mesh.vertices);
  REQUIRE((box.min() - sdf.origin).minCoeff() >= band - 1e-12);
  REQUIRE((sdf.upperCorner() - box.max()).minCoeff() >= band - 1e-12);
}

}  // namespace

TEST_CASE("grid distances are exact to 0.1 voxel: box") {
  requireGridMatchesExactDistance({"box", makeBox(2.0, 1.0, 0.6), 0.1});
}

TEST_CASE("grid distances are exact to 0.1 voxel: planar TIS block (mm-scale, SI units)") {
  requireGridMatchesExactDistance({"planar", makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180), 0.25e-3});
}

TEST_CASE("grid distances are exact to 0.1 voxel: icosphere") {
  requireGridMatchesExactDistance({"icosphere", test::icosphere(1.0, 2), 0.125});
}

TEST_CASE("grid distances are exact to 0.1 voxel: L-prism (concave edge)") {
  requireGridMatchesExactDistance({"L", test::lPrism(1.0), 0.1});
}

TEST_CASE("grid distances are exact to 0.1 voxel: torus (a hole)") {
  requireGridMatchesExactDistance({"torus", test::torus(1.0, 0.4, 24, 12), 0.1});
}

TEST_CASE("interior is filled: the centre of a block reads minus half its thickness") {
  TriangleMesh block = makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180);
  SignedDistanceOptions options;
  options.voxelSize = 0.25e-3;
  const DenseSdf sdf = buildSignedDistance(block, options);
  REQUIRE(sdf.sample(Eigen::Vector3d::Zero()).phi == Approx(-1.59e-3).margin(1e-9));
  // Near a flat face the field is linear, so interpolation is exact: a point 0.1 mm above the top.
  const SdfSample s = sdf.sample(Eigen::Vector3d(0.3e-3, -0.7e-3, 1.69e-3));
  REQUIRE(s.phi == Approx(0.1e-3).margin(1e-7));
  REQUIRE((s.gradient - Eigen::Vector3d::UnitZ()).norm() < 1e-4);
}

TEST_CASE("the .vdb file holds the same grid") {
  test::TempDir dir;
  TriangleMesh mesh = test::lPrism(1.0);
  SignedDistanceOptions options;
  options.voxelSize = 0.1;
  const DenseSdf sdf = buildSignedDistance(mesh, options);
  FileSetWriter files;
  writeVdb(files, sdf, dir / "l.vdb", "l");
  REQUIRE_FALSE(std::filesystem::exists(dir / "l.vdb"));  // until the set is committed
  files.commit();
  const DenseSdf back = readVdb(dir / "l.vdb", "l", sdf);
  // The .vdb is a level set: the inside and the band are stored, beyond the band reads background.
  REQUIRE(back.background == sdf.background);
  for (std::size_t i = 0; i < sdf.values.size(); ++i)
    REQUIRE(back.values[i] == (sdf.values[i] < sdf.background ? sdf.values[i] : sdf.background));
}
