// `tessera prep` and `tessera inspect` as a user runs them: outputs, and bad input refused with
// one clear line naming the file and the problem, a non-zero exit, and nothing written.
#include "geometry/block_generators.h"
#include "geometry/mesh_export.h"
#include "levelset/bundle.h"
#include "tests/fixtures/bad_meshes.h"
#include "tests/fixtures/temp_dir.h"
#include "tests/tools/cli_runner.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

using namespace tessera;
using tessera::test::kDefaultBlock;
using tessera::test::quoted;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// The run failed with status 2, one line on stderr naming `file` and `problem`, and no output.
void requireRefused(const test::CliResult& r, const std::string& file, const std::string& problem, const fs::path& out) {
  INFO("stderr: " << r.err);
  REQUIRE(r.status == 2);
  const std::string last = r.err.substr(r.err.rfind("tessera: error: "));
  REQUIRE(std::count(last.begin(), last.end(), '\n') == 1);
  REQUIRE_THAT(last, Contains(file) && Contains(problem));
  REQUIRE_FALSE(fs::exists(out));
}

}  // namespace

TEST_CASE("help describes every flag with its unit") {
  const test::CliResult top = test::runTessera("--help");
  REQUIRE(top.status == 0);
  REQUIRE_THAT(top.out, Contains("prep") && Contains("inspect"));
  const test::CliResult prep = test::runTessera("prep --help");
  REQUIRE(prep.status == 0);
  REQUIRE_THAT(prep.out, Contains("--unit") && Contains("--voxel") && Contains("in --unit") && Contains("degrees"));
}

TEST_CASE("prep writes a bundle that inspect describes") {
  test::TempDir dir;
  const std::string out = dir / "slab";
  const test::CliResult r = test::runTessera("prep " + quoted(kDefaultBlock) + " --unit mm --voxel 0.25 --spacing 0.6 -o " + quoted(out));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.out, Contains("written to"));
  REQUIRE(fs::exists(out + "/bundle.h5"));
  REQUIRE(fs::exists(out + "/planar_a10_h3.18_5deg.vdb"));

  const test::CliResult inspect = test::runTessera("inspect " + quoted(out) + " --json");
  REQUIRE(inspect.status == 0);
  const auto j = nlohmann::json::parse(inspect.out);
  const auto& shape = j["shapes"][0];
  REQUIRE(shape["name"] == "planar_a10_h3.18_5deg");
  REQUIRE(shape["source_unit"] == "mm");
  const double volume = 10e-3 * 10e-3 * 3.18e-3 - std::pow(3.18e-3, 3) * std::pow(std::tan(5 * M_PI / 180), 2) / 3;
  REQUIRE(shape["volume_m3"].get<double>() == Approx(volume).epsilon(1e-6));
  REQUIRE(shape["nodes"]["area_sum_m2"].get<double>() == Approx(shape["surface_area_m2"].get<double>()).epsilon(1e-9));
  REQUIRE(shape["nodes"]["nearest_spacing_m"]["max"].get<double>() <= 1.5 * 0.6e-3);
  REQUIRE(shape["sdf"]["voxel_size_m"].get<double>() == Approx(0.25e-3));
  REQUIRE(j["bodies"].empty());

  const test::CliResult text = test::runTessera("inspect " + quoted(out));
  REQUIRE(text.status == 0);
  REQUIRE_THAT(text.out, Contains("nearest-node gap") && Contains("mm^3"));

  // The signed distance at the centre is minus half the thickness.
  const test::CliResult sdf = test::runTessera("inspect " + quoted(out) + " --sdf 0,0,0 --json");
  REQUIRE(sdf.status == 0);
  REQUIRE(nlohmann::json::parse(sdf.out)["phi_m"].get<double>() == Approx(-1.59e-3).epsilon(1e-4));
  const test::CliResult sdfText = test::runTessera("inspect " + quoted(out) + " --sdf 0,0,1.79");
  REQUIRE_THAT(sdfText.out, Contains("0.2 mm (outside)"));
}

TEST_CASE("prep adds shapes to an existing bundle, and refuses a duplicate name without --replace") {
  test::TempDir dir;
  const std::string out = dir / "b";
  writeMesh(makeBox(8, 6, 4), dir / "box.stl", MeshFileFormat::StlBinary, 1.0);
  REQUIRE(test::runTessera("prep " + quoted(kDefaultBlock) + " --unit mm -o " + quoted(out)).status == 0);
  REQUIRE(test::runTessera("prep " + quoted(dir / "box.stl") + " --unit mm -o " + quoted(out)).status == 0);
  REQUIRE(readBundle(out).shapes.size() == 2);

  const auto before = fs::last_write_time(out + "/bundle.h5");
  const test::CliResult again = test::runTessera("prep " + quoted(dir / "box.stl") + " --unit mm -o " + quoted(out));
  REQUIRE(again.status == 2);
  REQUIRE_THAT(again.err, Contains("already holds a shape named 'box'"));
  REQUIRE(fs::last_write_time(out + "/bundle.h5") == before);
  REQUIRE(test::runTessera("prep " + quoted(dir / "box.stl") + " --unit mm --spacing 0.5 --replace -o " + quoted(out))
              .status == 0);
  const Bundle b = readBundle(out);
  REQUIRE(b.shapes.size() == 2);
  REQUIRE(b.shapes[1].name == "box");
  REQUIRE(b.shapes[1].resolution.nodeSpacing == Approx(0.5e-3));
  REQUIRE(b.shapes[1].mass.volume == Approx(192e-9).epsilon(1e-9));  // 8 x 6 x 4 mm^3
}

TEST_CASE("an inside-out mesh is re-oriented, and prep says so") {
  test::TempDir dir;
  writeMesh(test::invertedBox(), dir / "inv.obj", MeshFileFormat::Obj, 0.25);  // 8 x 4 x 2 (mm)
  const test::CliResult r = test::runTessera("prep " + quoted(dir / "inv.obj") + " --unit mm -o " + quoted(dir / "o"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.err, Contains("re-oriented"));
}

TEST_CASE("bad input: one clear line naming the file and the problem, exit 2, nothing written") {
  test::TempDir dir;
  const std::string out = dir / "out";
  const auto prep = [&](const std::string& file, const std::string& flags = "--unit mm") {
    return test::runTessera("prep " + quoted(file) + " " + flags + " -o " + quoted(out));
  };
  const auto meshFile = [&](const TriangleMesh& m, const std::string& name) {
    writeMesh(m, dir / name, MeshFileFormat::StlAscii, 1.0);  // unit-size fixtures, read as mm
    return dir / name;
  };

  requireRefused(prep(dir / "missing.stl"), "missing.stl", "no such file", out);
  test::writeFile(dir / "empty.stl", "");
  requireRefused(prep(dir / "empty.stl"), "empty.stl", "empty", out);
  std::string noise;
  for (int i = 0; i < 3000; ++i) noise.push_back(static_cast<char>((i * 7919 + 13) % 251));
  test::writeFile(dir / "noise.stl", noise);
  requireRefused(prep(dir / "noise.stl"), "noise.stl", "cannot read as a mesh", out);
  requireRefused(prep(meshFile(test::openBox(), "open.stl")), "open.stl", "open (not watertight)", out);
  requireRefused(prep(meshFile(test::selfIntersectingBox(), "crossing.stl")), "crossing.stl", "self-intersecting", out);
  requireRefused(prep(meshFile(test::nonManifoldEdgeMesh(), "nm.stl")), "nm.stl", "non-manifold", out);
  requireRefused(prep(meshFile(test::flatMesh(), "flat.stl")), "flat.stl", "encloses no volume", out);

  const std::string good = meshFile(makeBox(1, 1, 1), "cube.stl");  // a 1 mm cube
  requireRefused(prep(good, "--unit mm --voxel 0"), "cube.stl", "--voxel must be positive", out);
  requireRefused(prep(good, "--unit mm --voxel 0.05 --spacing -0.1"), "cube.stl", "--spacing must be positive", out);
  requireRefused(prep(good, "--unit mm --edge-spacing 2"), "cube.stl", "--edge-spacing must be between 0.05 and 1", out);
  requireRefused(prep(good, "--unit mm --size-gradient 0"), "cube.stl", "--size-gradient must be between", out);
  requireRefused(prep(good, "--unit mm --voxel 0.5"), "cube.stl", "too coarse", out);
  requireRefused(prep(good, "--unit furlong"), "furlong", "unknown length unit", out);

  const test::CliResult noUnit = test::runTessera("prep " + quoted(good) + " -o " + quoted(out));
  REQUIRE(noUnit.status != 0);
  REQUIRE_THAT(noUnit.err, Contains("--unit is required"));
  REQUIRE_FALSE(fs::exists(out));
}

TEST_CASE("inspect refuses what is not a bundle") {
  test::TempDir dir;
  fs::create_directories(dir / "x");
  test::writeFile(dir / "x/bundle.h5", "not hdf5 at all");
  const test::CliResult r = test::runTessera("inspect " + quoted(dir / "x"));
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("bundle.h5") && Contains("corrupt"));
}
