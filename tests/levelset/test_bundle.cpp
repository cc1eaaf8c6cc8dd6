// The asset bundle: round trip, versioning, corrupt files, atomic writes.
#include "geometry/block_generators.h"
#include "io/input_error.h"
#include "levelset/bundle.h"
#include "io/hdf5_file.h"
#include "levelset/shape_builder.h"
#include "tests/fixtures/analytic_meshes.h"
#include "tests/fixtures/bit_flips.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {

Bundle sampleBundle() {
  ShapeResolution r;
  PrepLog log;
  Bundle b;
  b.shapes.push_back(buildShape("planar", makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180),
                                {"planar.obj", "mm", 1e-3}, r, "planar", log));
  b.shapes.push_back(buildShape("box", makeBox(6e-3, 5e-3, 4e-3), {"box.stl", "mm", 1e-3}, r, "box", log));
  Body body;
  body.name = "r0c0";
  body.shape = 1;
  body.position = Eigen::Vector3d(0.01, -0.02, 0.003);
  body.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  body.fixed = true;
  b.bodies.push_back(body);
  return b;
}

void setVersion(const std::string& file, std::int64_t version) {
  h5::Handle f(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
  REQUIRE(f.valid());
  H5Adelete(f.get(), "format_version");
  h5::writeAttribute(f.get(), "format_version", version);
}

// Every value a bundle holds, as read: equal bundles have equal values.
bool sameValues(const Bundle& a, const Bundle& b) {
  if (a.generator != b.generator || a.shapes.size() != b.shapes.size() || a.bodies.size() != b.bodies.size() ||
      a.spanLength != b.spanLength || a.spanInterfaces != b.spanInterfaces || a.sourceUp != b.sourceUp)
    return false;
  for (std::size_t i = 0; i < a.shapes.size(); ++i) {
    const Shape &x = a.shapes[i], &y = b.shapes[i];
    const ShapeResolution &r = x.resolution, &q = y.resolution;
    if (x.name != y.name || x.source.file != y.source.file || x.source.unit != y.source.unit ||
        x.source.metresPerUnit != y.source.metresPerUnit || r.voxelSize != q.voxelSize || r.nodeSpacing != q.nodeSpacing ||
        r.edgeSpacingFraction != q.edgeSpacingFraction || r.sizeGradient != q.sizeGradient || r.featureAngle != q.featureAngle ||
        r.exteriorBandVoxels != q.exteriorBandVoxels || x.mass.volume != y.mass.volume ||
        x.mass.surfaceArea != y.mass.surfaceArea || x.mass.centroid != y.mass.centroid || x.mass.inertia != y.mass.inertia ||
        x.mass.principalMoments != y.mass.principalMoments || x.mass.principalAxes != y.mass.principalAxes ||
        x.mesh.vertices != y.mesh.vertices || x.mesh.triangles != y.mesh.triangles || x.nodes.positions != y.nodes.positions ||
        x.nodes.normals != y.nodes.normals || x.nodes.areas != y.nodes.areas || x.nodes.patches != y.nodes.patches ||
        x.nodes.kinds != y.nodes.kinds || x.sdf.origin != y.sdf.origin || x.sdf.voxelSize != y.sdf.voxelSize ||
        x.sdf.dims != y.sdf.dims || x.sdf.values != y.sdf.values || x.sdf.background != y.sdf.background)
      return false;
  }
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const Body &x = a.bodies[i], &y = b.bodies[i];
    if (x.name != y.name || x.shape != y.shape || x.position != y.position ||
        x.orientation.coeffs() != y.orientation.coeffs() || x.fixed != y.fixed)
      return false;
  }
  return true;
}

}  // namespace

TEST_CASE("a bit flipped anywhere in bundle.h5 is refused or changes nothing read (issue #39)") {
  // HDF5 checksums its metadata; every dataset carries a Fletcher-32 checksum of its chunks.
  test::TempDir dir;
  writeBundle(dir / "b", sampleBundle());
  const Bundle original = readBundle(dir / "b");
  const std::string file = dir / "b/bundle.h5";
  test::BitFlips flips(test::readFile(file), 12345);
  int refused = 0, unchanged = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const test::BitFlip flip = flips.next();
    test::writeFile(file, flip.bytes);
    try {
      const Bundle read = readBundle(dir / "b");
      INFO("a bit of byte " << flip.at << " of " << flip.bytes.size() << " flipped");
      REQUIRE(sameValues(read, original));
      ++unchanged;
    } catch (const InputError& e) {
      REQUIRE_THAT(e.what(), Contains("bundle.h5"));
      ++refused;
    }
  }
  INFO(refused << " refused, " << unchanged << " unchanged");
  REQUIRE(refused > 100);  // 3 000 flips: none read changed (measured once)
}

TEST_CASE("a bundle reads back exactly what was written") {
  test::TempDir dir;
  const Bundle written = sampleBundle();
  writeBundle(dir / "b", written);
  REQUIRE(std::filesystem::exists(dir / "b/planar.vdb"));
  REQUIRE(std::filesystem::exists(dir / "b/box.vdb"));
  const Bundle read = readBundle(dir / "b");
  REQUIRE(read.generator == generatorVersion());
  REQUIRE(read.shapes.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    const Shape &a = written.shapes[i], &b = read.shapes[i];
    REQUIRE(b.name == a.name);
    REQUIRE(b.source.file == a.source.file);
    REQUIRE(b.source.unit == a.source.unit);
    REQUIRE(b.resolution.voxelSize == a.resolution.voxelSize);
    REQUIRE(b.mass.volume == a.mass.volume);
    REQUIRE(b.mass.inertia == a.mass.inertia);
    REQUIRE(b.mass.principalAxes == a.mass.principalAxes);
    REQUIRE(b.mesh.vertices == a.mesh.vertices);
    REQUIRE(b.mesh.triangles == a.mesh.triangles);
    REQUIRE(b.nodes.positions == a.nodes.positions);
    REQUIRE(b.nodes.normals == a.nodes.normals);
    REQUIRE(b.nodes.areas == a.nodes.areas);
    REQUIRE(b.nodes.kinds == a.nodes.kinds);
    REQUIRE(b.sdf.origin == a.sdf.origin);
    REQUIRE(b.sdf.dims == a.sdf.dims);
    REQUIRE(b.sdf.values == a.sdf.values);
  }
  REQUIRE(read.bodies.size() == 1);
  REQUIRE(read.bodies[0].name == "r0c0");
  REQUIRE(read.bodies[0].shape == 1);
  REQUIRE(read.bodies[0].fixed);
  REQUIRE(read.bodies[0].position == written.bodies[0].position);
  REQUIRE(read.bodies[0].orientation.coeffs() == written.bodies[0].orientation.coeffs());
}

TEST_CASE("bundles of another format version are refused with a clear message") {
  test::TempDir dir;
  writeBundle(dir / "b", sampleBundle());
  setVersion(dir / "b/bundle.h5", 99);
  REQUIRE_THROWS_WITH(readBundle(dir / "b"), Contains("bundle.h5") && Contains("format version 99 is not supported"));
}

TEST_CASE("corrupt, truncated or foreign files are refused naming the file") {
  test::TempDir dir;
  REQUIRE_THROWS_WITH(readBundle(dir / "nothing"), Contains("no such bundle"));

  std::filesystem::create_directories(dir / "noise");
  test::writeFile(dir / "noise/bundle.h5", std::string(4096, '\x5a'));
  REQUIRE_THROWS_WITH(readBundle(dir / "noise"), Contains("noise/bundle.h5") && Contains("corrupt"));

  writeBundle(dir / "b", sampleBundle());
  const auto size = std::filesystem::file_size(dir / "b/bundle.h5");
  std::filesystem::resize_file(dir / "b/bundle.h5", size / 2);
  REQUIRE_THROWS_AS(readBundle(dir / "b"), InputError);

  {  // an HDF5 file that is not a bundle
    h5::Handle f = h5::createFile(dir / "other.h5");
    h5::writeAttribute(f.get(), "format", std::string("something-else"));
  }
  REQUIRE_THROWS_WITH(readBundle(dir / "other.h5"), Contains("not a Tessera bundle"));
}

TEST_CASE("writing leaves no temporary files behind") {
  test::TempDir dir;
  writeBundle(dir / "b", sampleBundle());
  for (const auto& entry : std::filesystem::directory_iterator(dir / "b"))
    REQUIRE(entry.path().filename().string().rfind(".tmp", 0) != 0);
}
