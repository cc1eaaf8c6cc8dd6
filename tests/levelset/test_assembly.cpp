// Assemblies: poses, the paper's slab (counts, no overlap, interlocking checked with the level
// sets), overlap detection, and the layout round trip tile -> export -> re-read.
#include "geometry/block_generators.h"
#include "io/input_error.h"
#include "geometry/mesh_export.h"
#include "levelset/assembly.h"
#include "levelset/assembly_export.h"
#include "levelset/tiler.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {

const std::string kPlanar = TESSERA_ASSETS "/blocks/planar_a10_h3.18_5deg.obj";

Bundle squareSlab(const std::string& mesh, double pitch = 10e-3) {
  SquareGridOptions grid;
  grid.pitch = pitch;
  LayoutShape shape;
  shape.key = "block";
  shape.mesh = mesh;
  PrepLog log;
  Bundle b = tileAssembly({shape}, squareGrid(grid, "block"), "mm", ShapeResolution{}, log);
  return b;
}

std::string writeBlock(const test::TempDir& dir, const TriangleMesh& mm, const std::string& name) {
  writeMesh(mm, dir / name, MeshFileFormat::Obj, 1.0);
  return dir / name;
}

}  // namespace

TEST_CASE("placement and body pose are inverse of each other") {
  Shape shape;
  shape.name = "s";
  shape.mass.centroid = Eigen::Vector3d(1e-3, -2e-3, 0.5e-3);
  shape.mass.principalAxes = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  Placement p;
  p.name = "b";
  p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(1.2, Eigen::Vector3d(0.2, -0.3, 1).normalized()));
  p.translation = Eigen::Vector3d(0.01, 0.02, -0.03);
  const Body body = placeBody(shape, 0, p);
  // A mesh point lands where the placement puts it.
  const Eigen::Vector3d xMesh(2e-3, 1e-3, -1e-3);
  const Eigen::Vector3d xBody = shape.mass.principalAxes.transpose() * (xMesh - shape.mass.centroid);
  REQUIRE((body.orientation * xBody + body.position - (p.rotation * xMesh + p.translation)).norm() < 1e-15);
  const Placement back = placementOf(body, shape);
  REQUIRE((back.translation - p.translation).norm() < 1e-15);
  REQUIRE(back.rotation.angularDistance(p.rotation) < 1e-12);
}

TEST_CASE("the paper's slab: 49 bodies, 24 fixed, one shape, no overlap, every free block interlocked") {
  const Bundle slab = squareSlab(kPlanar);
  REQUIRE(slab.bodies.size() == 49);
  REQUIRE(slab.shapes.size() == 1);
  int fixed = 0;
  for (const Body& b : slab.bodies) fixed += b.fixed;
  REQUIRE(fixed == 24);

  const double voxel = slab.shapes[0].sdf.voxelSize;
  const AssemblyCheck check = checkAssembly(slab, 1e-3 * voxel, 0.5 * voxel);
  REQUIRE(check.overlaps.empty());
  REQUIRE(check.isolated.empty());
  // Edge neighbours touch face to face (84 pairs); corner neighbours meet along a vertical line,
  // which the nodes graded towards the edges sample (72 pairs).
  REQUIRE(check.contacts.size() == 84 + 72);

  // Moving a free block up or down by s runs it into its neighbours by about s sin(5 deg).
  const double shift = 0.1e-3;
  const auto locks = verticalLocks(slab, shift);
  REQUIRE(locks.size() == 25);
  for (const VerticalLock& l : locks) {
    INFO(slab.bodies[l.body].name << " up " << l.upDepth << " down " << l.downDepth);
    REQUIRE(l.upDepth == Approx(shift * std::sin(5 * M_PI / 180)).epsilon(0.05));
    REQUIRE(l.downDepth == Approx(shift * std::sin(5 * M_PI / 180)).epsilon(0.05));
  }
}

TEST_CASE("straight-sided boxes do not interlock, and wave faces interlock even at zero angle") {
  test::TempDir dir;
  const double shift = 0.1e-3;
  const Bundle boxes = squareSlab(writeBlock(dir, makeBox(10, 10, 3.18), "box.obj"));
  for (const VerticalLock& l : verticalLocks(boxes, shift)) {
    REQUIRE(l.upDepth < 1e-3 * shift);
    REQUIRE(l.downDepth < 1e-3 * shift);
  }
  const Bundle waves = squareSlab(writeBlock(dir, makeWaveBlock(10, 3.18, 0.0, 0.2, 1, 24), "wave.obj"));
  // Matching faces read no overlap on the exact mesh level set (the grid read micrometres).
  REQUIRE(checkAssembly(waves, 1e-9, 1e-4).overlaps.empty());
  for (const VerticalLock& l : verticalLocks(waves, shift)) {
    REQUIRE(l.upDepth > 0.1 * shift);
    REQUIRE(l.downDepth > 0.1 * shift);
  }
}

TEST_CASE("overlapping blocks are found with their depth, isolated ones reported") {
  const Bundle tight = squareSlab(kPlanar, 9e-3);
  const AssemblyCheck check = checkAssembly(tight, 25e-6, 1e-4);
  REQUIRE_FALSE(check.overlaps.empty());
  // Neighbours 9 mm apart with 10 mm mid-sections (10.28 mm at the wide face): about 1 to 1.3 mm
  // deep (measured normal to the 5-degree faces: 1 mm x cos 5 deg at mid-height).
  REQUIRE(-check.overlaps.front().separation > 0.95e-3);
  REQUIRE(-check.overlaps.front().separation < 1.35e-3);

  Bundle spread = squareSlab(kPlanar);
  spread.bodies[0].position += Eigen::Vector3d(-5e-3, -5e-3, 0);  // corner block moved away
  const AssemblyCheck apart = checkAssembly(spread, 25e-6, 1e-4);
  REQUIRE(apart.isolated == std::vector<int>{0});
}

TEST_CASE("layout round trip: tile -> export -> re-read -> tile preserves poses to 1e-12") {
  test::TempDir dir;
  const Bundle slab = squareSlab(kPlanar);
  writeBundle(dir / "slab", slab);
  exportAssembly(slab, dir / "slab", dir / "export");
  const Layout layout = readLayout(dir / "export/layout.json");
  REQUIRE(layout.bodies.size() == 49);
  REQUIRE(layout.spanInterfaces == 0);  // squareSlab() sets no span
  PrepLog log;
  const Bundle again = tileAssembly(layout.shapes, layout.bodies, layout.unit, ShapeResolution{}, log);
  REQUIRE(again.bodies.size() == slab.bodies.size());
  for (std::size_t i = 0; i < slab.bodies.size(); ++i) {
    REQUIRE(again.bodies[i].name == slab.bodies[i].name);
    REQUIRE(again.bodies[i].fixed == slab.bodies[i].fixed);
    REQUIRE((again.bodies[i].position - slab.bodies[i].position).norm() < 1e-12);
    REQUIRE(again.bodies[i].orientation.angularDistance(slab.bodies[i].orientation) < 1e-12);
  }
  REQUIRE(again.shapes[0].sdf.values == slab.shapes[0].sdf.values);  // taken from the bundle, not re-made
}

TEST_CASE("the shipped hexagonal slab tiles, interlocks and reads its span") {
  const Layout layout = readLayout(TESSERA_ASSETS "/layouts/hex_slab.json");
  PrepLog log;
  const Bundle hex = tileAssembly(layout.shapes, layout.bodies, layout.unit, ShapeResolution{}, log);
  REQUIRE(hex.bodies.size() == 19);
  int fixed = 0;
  for (const Body& b : hex.bodies) fixed += b.fixed;
  REQUIRE(fixed == 12);
  REQUIRE(layout.spanInterfaces == 4);
  REQUIRE(layout.spanLength == Approx(30e-3));
  const double voxel = hex.shapes[0].sdf.voxelSize;
  const AssemblyCheck check = checkAssembly(hex, 0.1 * voxel, 0.5 * voxel);
  REQUIRE(check.overlaps.empty());
  REQUIRE(check.contacts.size() == 42);
  for (const VerticalLock& l : verticalLocks(hex, 0.1e-3)) {
    REQUIRE(l.upDepth > 0.5 * 0.1e-3 * std::sin(5 * M_PI / 180));
    REQUIRE(l.downDepth > 0.5 * 0.1e-3 * std::sin(5 * M_PI / 180));
  }
}
