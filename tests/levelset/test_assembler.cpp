// Assemblies imported in place (levelset/assembler.h): pieces, the up axis, shared shapes,
// supports, the span — checked against the same slab built by the tiler.
#include "geometry/block_generators.h"
#include "io/input_error.h"
#include "geometry/mesh_export.h"
#include "geometry/up_axis.h"
#include "levelset/assembler.h"
#include "levelset/tiler.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {

const std::string kBlock = TESSERA_ASSETS "/blocks/planar_a10_h3.18_5deg.obj";

// The paper's 5 x 5 slab from the tiler (mm, z up).
Bundle tiled() {
  SquareGridOptions grid;
  grid.columns = grid.rows = 5;
  LayoutShape shape;
  shape.key = "planar";
  shape.mesh = kBlock;
  PrepLog log;
  return tileAssembly({shape}, squareGrid(grid, "planar"), "mm", ShapeResolution{}, log);
}

// The same slab as a design tool exports it: every block placed in world coordinates, y up, in
// metres; the inner blocks as one multi-piece mesh, the outer ring as another.
void exportSlab(const Bundle& slab, const std::string& parts, const std::string& frame) {
  const Eigen::Matrix3d toFile = rotationToZUp("y").transpose();
  TriangleMesh inner, ring;
  for (const Body& b : slab.bodies) {
    const Shape& s = slab.shapes[b.shape];
    TriangleMesh& into = b.fixed ? ring : inner;
    const int base = static_cast<int>(into.vertices.size());
    for (const auto& v : s.mesh.vertices) into.vertices.push_back(toFile * (b.orientation * v + b.position));
    for (const auto& t : s.mesh.triangles) into.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  writeMesh(inner, parts, MeshFileFormat::Obj, 1.0);
  writeMesh(ring, frame, MeshFileFormat::Obj, 1.0);
}

}  // namespace

TEST_CASE("an exported y-up assembly imports in place: the tiler's slab, one shared shape, the frame fixed, the paper's span") {
  test::TempDir dir;
  const Bundle reference = tiled();
  exportSlab(reference, dir / "parts.obj", dir / "frame.obj");
  AssembleOptions options;
  options.unit = "m";
  options.up = "y";
  options.frameFiles = {dir / "frame.obj"};
  PrepLog log;
  AssembleReport report;
  const Bundle b = assembleParts({dir / "parts.obj"}, options, log, report);
  REQUIRE(report.pieces == 25);
  REQUIRE(b.bodies.size() == 25);
  REQUIRE(b.shapes.size() == 1);
  REQUIRE(b.sourceUp == "y");
  REQUIRE(b.shapes[0].convex);
  int fixed = 0;
  for (const Body& body : b.bodies) fixed += body.fixed;
  REQUIRE(fixed == 16);
  // Every tiled body has an imported twin at the same place, z up, with the same surface (to the
  // 1e-8 m of the digits assimp writes).
  for (const Body& r : reference.bodies) {
    const Body* twin = nullptr;
    for (const Body& body : b.bodies)
      if ((body.position - r.position).norm() < 1e-8) twin = &body;
    INFO(r.name);
    REQUIRE(twin);
    REQUIRE(twin->fixed == r.fixed);
    for (const auto& v : reference.shapes[r.shape].mesh.vertices) {
      const Eigen::Vector3d world = r.orientation * v + r.position;
      double nearest = 1e9;
      for (const auto& w : b.shapes[twin->shape].mesh.vertices)
        nearest = std::min(nearest, (twin->orientation * w + twin->position - world).norm());
      REQUIRE(nearest < 1e-8);  // the OBJ file's digits
    }
  }
  // The span of Feldfogel et al. for a 5 x 5 slab: L = 3 pitches, M = 4.
  REQUIRE(b.spanLength == Approx(30e-3).epsilon(1e-6));
  REQUIRE(b.spanInterfaces == 4);
}

TEST_CASE("supports by rule: the outer ring of a square slab is its perimeter, and the span estimate of the default slab") {
  SquareGridOptions grid;  // 7 x 7
  LayoutShape shape;
  shape.key = "planar";
  shape.mesh = kBlock;
  PrepLog log;
  Bundle slab = tileAssembly({shape}, squareGrid(grid, "planar"), "mm", ShapeResolution{}, log);
  const std::vector<int> ring = outerRingBodies(slab);
  REQUIRE(ring.size() == 24);
  for (int i : ring) REQUIRE(slab.bodies[i].fixed);
  double length = 0;
  int interfaces = 0;
  std::string rule;
  estimateSpan(slab, length, interfaces, rule);
  REQUIRE(length == Approx(50e-3).epsilon(1e-9));
  REQUIRE(interfaces == 6);
  REQUIRE_THAT(rule, Contains("pitch"));
}

TEST_CASE("identical parts share a shape only when one is a rigid motion of the other, a mirror image does not") {
  test::TempDir dir;
  const TriangleMesh block = makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180);
  TriangleMesh turned = block, mirrored = block;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, 0.2, 1).normalized()).toRotationMatrix();
  for (auto& v : turned.vertices) v = r * v + Eigen::Vector3d(0.02, 0, 0);
  for (auto& v : mirrored.vertices) v = Eigen::Vector3d(-v.x(), v.y(), v.z()) + Eigen::Vector3d(0, 0.02, 0);
  for (auto& t : mirrored.triangles) std::swap(t[1], t[2]);  // still outward
  writeMesh(block, dir / "a.obj", MeshFileFormat::Obj, 1.0);
  writeMesh(turned, dir / "b.obj", MeshFileFormat::Obj, 1.0);
  writeMesh(mirrored, dir / "c.obj", MeshFileFormat::Obj, 1.0);
  AssembleOptions options;
  options.unit = "m";
  options.fixPatterns = {"a"};
  PrepLog log;
  AssembleReport report;
  const Bundle b = assembleParts({dir / "a.obj", dir / "b.obj", dir / "c.obj"}, options, log, report);
  REQUIRE(b.bodies.size() == 3);
  REQUIRE(b.bodies[1].shape == b.bodies[0].shape);
  REQUIRE(b.bodies[2].shape != b.bodies[0].shape);
  REQUIRE(b.bodies[0].fixed);
  REQUIRE_FALSE(b.bodies[1].fixed);
}

TEST_CASE("assembly refusals: no unit, no support, every body fixed, a missing frame") {
  test::TempDir dir;
  writeMesh(makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180), dir / "a.obj", MeshFileFormat::Obj, 1.0);
  PrepLog log;
  AssembleReport report;
  AssembleOptions options;
  REQUIRE_THROWS_WITH(assembleParts({dir / "a.obj"}, options, log, report), Contains("--unit"));
  options.unit = "m";
  REQUIRE_THROWS_WITH(assembleParts({dir / "a.obj"}, options, log, report), Contains("no body is fixed") && Contains("--frame"));
  options.fixPatterns = {"*"};
  REQUIRE_THROWS_WITH(assembleParts({dir / "a.obj"}, options, log, report), Contains("every body is fixed"));
  options.fixPatterns.clear();
  options.frameFiles = {dir / "nope.obj"};
  REQUIRE_THROWS_WITH(assembleParts({dir / "a.obj"}, options, log, report), Contains("nope.obj") && Contains("--frame"));
}

TEST_CASE("solids of one file that meet along an edge stay separate bodies") {
  // Two boxes touching along a vertical edge: welded, that edge is shared by four triangles.
  test::TempDir dir;
  TriangleMesh pair = makeBox(10e-3, 10e-3, 3e-3), second = makeBox(10e-3, 10e-3, 3e-3);
  const int base = static_cast<int>(pair.vertices.size());
  for (const auto& v : second.vertices) pair.vertices.push_back(v + Eigen::Vector3d(10e-3, 10e-3, 0));
  for (const auto& t : second.triangles) pair.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  writeMesh(pair, dir / "pair.obj", MeshFileFormat::Obj, 1.0);
  AssembleOptions options;
  options.unit = "m";
  options.fixPatterns = {"pair_1"};
  PrepLog log;
  AssembleReport report;
  const Bundle b = assembleParts({dir / "pair.obj"}, options, log, report);
  REQUIRE(report.pieces == 2);
  REQUIRE(b.bodies.size() == 2);
  REQUIRE(b.bodies[0].shape == b.bodies[1].shape);  // the same box, moved
}
