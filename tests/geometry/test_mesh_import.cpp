// Import: the same mesh as ASCII STL, binary STL and OBJ gives the same mesh; units scale;
// duplicate vertices are welded; unreadable files are refused with the file name.
#include "geometry/block_generators.h"
#include "io/input_error.h"
#include "geometry/mass_properties.h"
#include "geometry/mesh_export.h"
#include "geometry/mesh_import.h"
#include "geometry/mesh_weld.h"
#include "tests/fixtures/analytic_meshes.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {

ImportedMesh importAs(const std::string& path, double metresPerUnit) {
  MeshImportOptions options;
  options.metresPerUnit = metresPerUnit;
  return importMesh(path, options);
}

}  // namespace

TEST_CASE("ASCII STL, binary STL and OBJ import to the same welded mesh") {
  test::TempDir dir;
  // Dyadic coordinates: exact in the single precision assimp stores.
  const TriangleMesh source = test::lPrism(0.5);
  writeMesh(source, dir / "l.stl", MeshFileFormat::StlAscii, 1.0);
  writeMesh(source, dir / "lb.stl", MeshFileFormat::StlBinary, 1.0);
  writeMesh(source, dir / "l.obj", MeshFileFormat::Obj, 1.0);
  const ImportedMesh ascii = importAs(dir / "l.stl", 1.0);
  const ImportedMesh binary = importAs(dir / "lb.stl", 1.0);
  const ImportedMesh obj = importAs(dir / "l.obj", 1.0);
  // Welding numbers vertices in order of first use; triangles and their corners keep their order.
  for (const ImportedMesh* m : {&ascii, &binary, &obj}) {
    REQUIRE(m->mesh.vertices.size() == source.vertices.size());
    REQUIRE(m->mesh.triangles.size() == source.triangles.size());
    for (int t = 0; t < static_cast<int>(source.triangles.size()); ++t)
      for (int k = 0; k < 3; ++k) REQUIRE(triangleCorner(m->mesh, t, k) == triangleCorner(source, t, k));
  }
  // STL repeats the corners of every facet; identical ones are joined on reading.
  REQUIRE(ascii.fileVertices == 12);
  REQUIRE(ascii.weld.mergedVertices == 0);
}

TEST_CASE("the unit scales the mesh to metres") {
  test::TempDir dir;
  const TriangleMesh block = makePlanarBlock(10, 3.18, 5 * M_PI / 180);  // mm
  writeMesh(block, dir / "mm.obj", MeshFileFormat::Obj, 1.0);
  TriangleMesh inMetres = block;
  for (auto& v : inMetres.vertices) v *= 1e-3;
  writeMesh(inMetres, dir / "m.obj", MeshFileFormat::Obj, 1.0);
  const MassProperties fromMm = computeMassProperties(importAs(dir / "mm.obj", 1e-3).mesh);
  const MassProperties fromM = computeMassProperties(importAs(dir / "m.obj", 1.0).mesh);
  // Files hold single-precision numbers: agreement to ~1e-7 relative.
  REQUIRE(fromMm.volume == Approx(fromM.volume).epsilon(1e-6));
  REQUIRE(fromMm.volume == Approx(318e-9).epsilon(1e-3));
  REQUIRE(fromMm.principalMoments.x() == Approx(fromM.principalMoments.x()).epsilon(1e-6));
}

TEST_CASE("vertices that differ by rounding are welded on import") {
  test::TempDir dir;
  // Two facets of a tetrahedron write a shared corner as 1 and as 1 + 1e-9.
  test::writeFile(dir / "t.stl",
                  "solid t\n"
                  "facet normal 0 0 -1\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 1 0 0\nendloop\nendfacet\n"
                  "facet normal 0 -1 0\nouter loop\nvertex 0 0 0\nvertex 1.000000001 0 0\nvertex 0 0 1\nendloop\nendfacet\n"
                  "facet normal -1 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\n"
                  "facet normal 1 1 1\nouter loop\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
                  "endsolid t\n");
  const ImportedMesh m = importAs(dir / "t.stl", 1.0);
  REQUIRE(m.mesh.vertices.size() == 4);
  REQUIRE(m.mesh.triangles.size() == 4);
}

TEST_CASE("welding merges vertices within the tolerance and drops collapsed triangles") {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1e-9, 0, 0}, {1, 1e-9, 0}, {0.5, 0.5, 1}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 3, 5}};
  const WeldReport report = weldVertices(m, 1e-6);
  REQUIRE(report.mergedVertices == 2);
  REQUIRE(report.collapsedTriangles == 1);
  REQUIRE(m.vertices.size() == 4);
  REQUIRE(m.triangles == std::vector<std::array<int, 3>>{{0, 1, 2}, {0, 1, 3}});
}

TEST_CASE("unreadable files are refused naming the file") {
  test::TempDir dir;
  REQUIRE_THROWS_WITH(importAs(dir / "missing.stl", 1), Contains("missing.stl") && Contains("no such file"));
  test::writeFile(dir / "empty.stl", "");
  REQUIRE_THROWS_WITH(importAs(dir / "empty.stl", 1), Contains("empty.stl") && Contains("empty"));
  std::string noise;
  for (int i = 0; i < 5000; ++i) noise.push_back(static_cast<char>((i * 7919 + 13) % 251));
  test::writeFile(dir / "noise.stl", noise);
  REQUIRE_THROWS_AS(importAs(dir / "noise.stl", 1), InputError);
  test::writeFile(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  REQUIRE_THROWS_WITH(importAs(dir / "points.obj", 1), Contains("points.obj") && Contains("no faces"));
  // Twelve triangles, ten of them tiny beside two corners far away (as random bytes in a binary
  // STL read): welding at 1e-6 of the size collapses them, and the message says so, with the span.
  std::string obj;
  for (int t = 0; t < 10; ++t) {
    const double x = t * 1e-3;
    obj += "v " + std::to_string(x) + " 0 0\nv " + std::to_string(x) + " 1e-3 0\nv " + std::to_string(x) + " 0 1e-3\n";
  }
  obj += "v 0 0 0\nv 1e30 0 0\nv 0 1e30 0\nv 0 0 1e30\nv 1e30 1e30 0\nv 0 1e30 1e30\n";
  for (int t = 0; t < 12; ++t) obj += "f " + std::to_string(3 * t + 1) + " " + std::to_string(3 * t + 2) + " " + std::to_string(3 * t + 3) + "\n";
  test::writeFile(dir / "damaged.obj", obj);
  REQUIRE_THROWS_WITH(importAs(dir / "damaged.obj", 1),
                      Contains("damaged.obj: 10 of its 12 triangles collapsed") && Contains("spans 1.73e+30"));
}

TEST_CASE("a PLY header claiming more elements than its file holds, or never ending, is refused before any is read (issue #39)") {
  // assimp reserves what the header claims: 2e9 vertices grew memory without bound.
  test::TempDir dir;
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
  std::string body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n";
  for (const char* f : {"0 2 1", "0 3 2", "4 5 6", "4 6 7", "0 1 5", "0 5 4", "1 2 6", "1 6 5", "2 3 7", "2 7 6", "3 0 4", "3 4 7"})
    body += std::string("3 ") + f + "\n";
  test::writeFile(dir / "cube.ply", header + body);
  REQUIRE(importAs(dir / "cube.ply", 1).mesh.triangles.size() == 12);
  std::string claims = header;
  claims.replace(claims.find("vertex 8"), 8, "vertex 2000000000");
  test::writeFile(dir / "claims.ply", claims + body);
  REQUIRE_THROWS_WITH(importAs(dir / "claims.ply", 1), Contains("claims.ply") && Contains("PLY header claims more"));
  claims.replace(claims.find("vertex 2000000000"), 17, "vertex 18446744073709551615");
  test::writeFile(dir / "overflow.ply", claims + body);
  REQUIRE_THROWS_WITH(importAs(dir / "overflow.ply", 1), Contains("overflow.ply") && Contains("damaged"));
  // A header that never ends (assimp's reader looped forever on it: found by fuzz_mesh_import).
  test::writeFile(dir / "endless.ply", "ply\nformat ascii 1.0\nelement ver\x02ply\nformat ascii 1.0\nelement vertex 8\n"
                                       "property float x\nty float y\nproperty float z\nelement face 12\ntex 8\n"
                                       "property float xproperty list uch\nar int p");
  REQUIRE_THROWS_WITH(importAs(dir / "endless.ply", 1), Contains("endless.ply") && Contains("not a PLY mesh Tessera reads"));
  std::string shouting = header + body;  // keywords as assimp's reader half-understood them
  shouting.replace(shouting.find("end_header"), 10, "end_headeR");
  test::writeFile(dir / "shouting.ply", shouting);
  REQUIRE_THROWS_WITH(importAs(dir / "shouting.ply", 1), Contains("shouting.ply") && Contains("not a PLY mesh Tessera reads"));
}

namespace {

// The mesh as PLY: ASCII, or binary in either byte order; each vertex with an extra property and
// an extra element after the faces, which a reader must read past.
std::string plyOf(const TriangleMesh& mesh, const std::string& format) {
  std::string header = "ply\nformat " + format + " 1.0\ncomment written by the test\nelement vertex " +
                       std::to_string(mesh.vertices.size()) + "\nproperty double x\nproperty double y\nproperty double z\n" +
                       "property uchar red\nelement face " + std::to_string(mesh.triangles.size()) +
                       "\nproperty list uchar int vertex_indices\nelement edge 1\nproperty int a\nproperty int b\nend_header\n";
  std::string body;
  const bool big = format == "binary_big_endian";
  const auto raw = [&](const void* p, std::size_t n) {
    std::string b(static_cast<const char*>(p), n);
    if (big) std::reverse(b.begin(), b.end());  // the test host is little-endian
    body += b;
  };
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (format == "ascii") {
      char line[128];
      std::snprintf(line, sizeof line, "%.17g %.17g %.17g 7\n", v.x(), v.y(), v.z());
      body += line;
    } else {
      for (int d = 0; d < 3; ++d) raw(&v[d], 8);
      body += '\7';
    }
  }
  for (const auto& t : mesh.triangles) {
    if (format == "ascii") {
      body += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
    } else {
      body += '\3';
      for (int k = 0; k < 3; ++k) raw(&t[k], 4);
    }
  }
  const std::int32_t edge[2] = {0, 1};
  if (format == "ascii") body += "0 1\n";
  else for (const std::int32_t& e : edge) raw(&e, 4);
  return header + body;
}

}  // namespace

TEST_CASE("PLY in ASCII and binary of either byte order imports to the mesh written, other properties read past") {
  test::TempDir dir;
  const TriangleMesh source = test::lPrism(0.5);
  for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    INFO(format);
    test::writeFile(dir / "l.ply", plyOf(source, format));
    const ImportedMesh m = importAs(dir / "l.ply", 1.0);
    REQUIRE(m.mesh.vertices.size() == source.vertices.size());
    REQUIRE(m.mesh.triangles.size() == source.triangles.size());
    for (int t = 0; t < static_cast<int>(source.triangles.size()); ++t)
      for (int k = 0; k < 3; ++k) REQUIRE(triangleCorner(m.mesh, t, k) == triangleCorner(source, t, k));
  }
  // Quads, as design tools write them: split into two triangles each, the same solid.
  test::writeFile(dir / "quads.ply", "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                                      "element face 6\nproperty list uchar int vertex_indices\nend_header\n"
                                      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                                      "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n");
  const ImportedMesh cube = importAs(dir / "quads.ply", 1.0);
  REQUIRE(cube.mesh.triangles.size() == 12);
  REQUIRE(computeMassProperties(cube.mesh).volume == Approx(1.0).epsilon(1e-12));
  // A face naming a vertex that is not there, and a body cut short: one line each.
  std::string text = plyOf(source, "ascii");
  test::writeFile(dir / "short.ply", text.substr(0, text.size() - 30));
  REQUIRE_THROWS_WITH(importAs(dir / "short.ply", 1), Contains("short.ply") && Contains("export the mesh again"));
  text.replace(text.find("\n3 ") + 3, 1, "999");
  test::writeFile(dir / "index.ply", text);
  REQUIRE_THROWS_WITH(importAs(dir / "index.ply", 1), Contains("index.ply") && Contains("names a vertex that is not there"));
}
