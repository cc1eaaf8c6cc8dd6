// `tessera block`, `tessera tile` and `tessera export` as a user runs them.
#include "geometry/mass_properties.h"
#include "geometry/mesh_export.h"
#include "geometry/mesh_import.h"
#include "levelset/bundle.h"
#include "tests/fixtures/temp_dir.h"
#include "tests/tools/cli_runner.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace tessera;
using tessera::test::kDefaultBlock;
using tessera::test::quoted;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

TEST_CASE("block writes valid meshes of every family in the stated unit") {
  test::TempDir dir;
  const test::CliResult planar =
      test::runTessera("block planar --size 10 --thickness 3.18 --angle 5 --unit mm -o " + quoted(dir / "p.obj"));
  REQUIRE(planar.status == 0);
  MeshImportOptions mm;
  mm.metresPerUnit = 1e-3;
  const double volume = computeMassProperties(importMesh(dir / "p.obj", mm).mesh).volume;
  REQUIRE(volume == Approx(1e-4 * 3.18e-3 - std::pow(3.18e-3, 3) * std::pow(std::tan(5 * M_PI / 180), 2) / 3).epsilon(1e-6));
  // The same block in metres: the same vertices to double precision (an OBJ written in float
  // moved them by 1e-10 m), and no made-up normals.
  REQUIRE(test::runTessera("block planar --size 0.01 --thickness 0.00318 --angle 5 --unit m -o " + quoted(dir / "pm.obj")).status == 0);
  const auto vertexLines = [](const std::string& path) {
    std::vector<double> values;
    std::ifstream obj(path);
    for (std::string line; std::getline(obj, line);) {
      REQUIRE(line.rfind("vn", 0) != 0);
      if (line.rfind("v ", 0) != 0) continue;
      std::istringstream in(line.substr(2));
      for (double x; in >> x;) values.push_back(x);
    }
    return values;
  };
  const std::vector<double> inMm = vertexLines(dir / "p.obj"), inM = vertexLines(dir / "pm.obj");
  REQUIRE(inM.size() == 24);
  REQUIRE(inM.size() == inMm.size());
  for (std::size_t i = 0; i < inM.size(); ++i) REQUIRE(std::abs(inM[i] * 1e3 - inMm[i]) < 1e-14 * std::abs(inMm[i]));
  for (const std::string family : {"box", "wave", "hex", "osteomorphic"}) {
    const test::CliResult r = test::runTessera("block " + family + " --unit cm --size 1 --thickness 0.318 --amplitude 0.02 -o " +
                                               quoted(dir / (family + ".stl")));
    INFO(family << ": " << r.err);
    REQUIRE(r.status == 0);
    REQUIRE(test::runTessera("prep " + quoted(dir / (family + ".stl")) + " --unit cm -o " + quoted(dir / "b")).status == 0);
  }
  REQUIRE(readBundle(dir / "b").shapes.size() == 4);

  const test::CliResult bad = test::runTessera("block planar --size 1 --thickness 5 --angle 80 --unit mm -o " + quoted(dir / "x.obj"));
  REQUIRE(bad.status == 2);
  REQUIRE_THAT(bad.err, Contains("inclined faces meet"));
  REQUIRE_FALSE(fs::exists(dir / "x.obj"));
  const test::CliResult misplaced = test::runTessera("block wave --y-amplitude 0.3 --unit mm -o " + quoted(dir / "y.obj"));
  REQUIRE(misplaced.status == 2);
  REQUIRE_THAT(misplaced.err, Contains("--y-amplitude applies to the osteomorphic family only"));
  REQUIRE_FALSE(fs::exists(dir / "y.obj"));
}

TEST_CASE("osteomorphic blocks tiled unturned touch face to face and hold the free block both ways") {
  test::TempDir dir;
  // One-way (flat y-faces) and two-way (curved y-faces too).
  for (const std::string yAmplitude : {"0", "0.5"}) {
    REQUIRE(test::runTessera("block osteomorphic --size 10 --thickness 3.18 --amplitude 0.5 --y-amplitude " + yAmplitude +
                             " --unit mm -o " + quoted(dir / "o.obj")).status == 0);
    const test::CliResult r = test::runTessera("tile --block " + quoted(dir / "o.obj") +
                                               " --unit mm --grid 3x3 --pitch 10 --no-alternate --fix perimeter"
                                               " --overlap-tolerance 1e-5 -o " + quoted(dir / ("slab" + yAmplitude)));
    INFO(yAmplitude << ": " << r.err);
    // The curved faces coincide: the check, on the exact mesh level set as the run reads it, finds
    // no overlap beyond 10 nm (1e-13 mm measured). On the grid it read 4-5 um, its interpolation
    // error; with nodes at their cells' centroids, 12 um.
    REQUIRE(r.status == 0);
    REQUIRE_THAT(r.out, Contains("1 of 1 free bodies held both up and down"));
  }
}

TEST_CASE("tile builds the paper's slab in one command, and inspect lists its bodies") {
  test::TempDir dir;
  const std::string out = dir / "slab";
  const test::CliResult r = test::runTessera("tile --block " + quoted(kDefaultBlock) +
                                             " --unit mm --grid 7x7 --pitch 10 --fix perimeter -o " + quoted(out));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.out, Contains("49 bodies (24 fixed, 25 free), 1 distinct shape(s)"));
  REQUIRE_THAT(r.out, Contains("25 of 25 free bodies held both up and down"));
  REQUIRE_THAT(r.out, Contains("L = 50 mm free span, M = 6 interfaces"));

  const test::CliResult inspect = test::runTessera("inspect " + quoted(out) + " --json");
  REQUIRE(inspect.status == 0);
  const auto j = nlohmann::json::parse(inspect.out);
  REQUIRE(j["shapes"].size() == 1);
  REQUIRE(j["bodies"].size() == 49);
  REQUIRE(j["span"]["interfaces"] == 6);
  const auto& centre = j["bodies"][24];
  REQUIRE(centre["name"] == "r3c3");
  REQUIRE(centre["shape"] == "planar_a10_h3.18_5deg");
  REQUIRE(centre["fixed"] == false);
  REQUIRE(std::abs(centre["position_m"][0].get<double>()) < 1e-15);
  REQUIRE(centre["orientation_wxyz"].size() == 4);
}

TEST_CASE("a block mesh with its origin at a corner still gives a slab centred on the origin") {
  test::TempDir dir;
  MeshImportOptions mm;
  mm.metresPerUnit = 1e-3;
  TriangleMesh block = importMesh(kDefaultBlock, mm).mesh;
  for (auto& v : block.vertices) v += Eigen::Vector3d(5e-3, 5e-3, 0);  // origin at a corner
  writeMesh(block, dir / "corner.obj", MeshFileFormat::Obj, 1e-3);
  const test::CliResult r = test::runTessera("tile --block " + quoted(dir / "corner.obj") + " --unit mm --grid 3x3 --pitch 10 -o " +
                                             quoted(dir / "slab"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.err, Contains("centred at (5, 5) mm in plan"));
  const Bundle b = readBundle(dir / "slab");
  REQUIRE(b.bodies[4].name == "r1c1");
  REQUIRE(b.bodies[4].position.head<2>().norm() < 1e-12);
}

TEST_CASE("tile refuses overlapping blocks and bad layouts, writing nothing") {
  test::TempDir dir;
  const std::string out = dir / "slab";
  const test::CliResult tight =
      test::runTessera("tile --block " + quoted(kDefaultBlock) + " --unit mm --grid 3x3 --pitch 9 -o " + quoted(out));
  REQUIRE(tight.status == 2);
  REQUIRE_THAT(tight.err, Contains("bodies 'r") && Contains("overlap by 0.99") && Contains("check --pitch"));
  REQUIRE_FALSE(fs::exists(out));

  test::writeFile(dir / "dup.json", R"({"format": "tessera-layout", "version": 1, "unit": "mm",
      "shapes": {"b": {"mesh": ")" + kDefaultBlock + R"("}},
      "bodies": [{"name": "a", "shape": "b", "position": [0, 0, 0]}, {"name": "a", "shape": "b", "position": [10, 0, 0]}]})");
  const test::CliResult dup = test::runTessera("tile --layout " + quoted(dir / "dup.json") + " -o " + quoted(out));
  REQUIRE(dup.status == 2);
  REQUIRE_THAT(dup.err, Contains("dup.json") && Contains("duplicate name"));
  REQUIRE_FALSE(fs::exists(out));

  test::writeFile(dir / "nofile.json", R"({"format": "tessera-layout", "version": 1, "unit": "mm",
      "shapes": {"b": {"mesh": "no-such-block.stl"}}, "bodies": [{"name": "a", "shape": "b", "position": [0, 0, 0]}]})");
  const test::CliResult missing = test::runTessera("tile --layout " + quoted(dir / "nofile.json") + " -o " + quoted(out));
  REQUIRE(missing.status == 2);
  REQUIRE_THAT(missing.err, Contains("no-such-block.stl") && Contains("no such file"));
  REQUIRE_FALSE(fs::exists(out));

  test::writeFile(dir / "same.json", R"({"format": "tessera-layout", "version": 1, "unit": "mm",
      "shapes": {"b": {"mesh": ")" + kDefaultBlock + R"("}},
      "bodies": [{"name": "a", "shape": "b", "position": [0, 0, 0]}, {"name": "c", "shape": "b", "position": [0, 0, 1]}]})");
  const test::CliResult same = test::runTessera("tile --layout " + quoted(dir / "same.json") + " -o " + quoted(out));
  REQUIRE(same.status == 2);
  REQUIRE_THAT(same.err, Contains("bodies 'a' and 'c' overlap by"));
  REQUIRE_FALSE(fs::exists(out));
}

TEST_CASE("export writes the assembly for ParaView and a layout that rebuilds it") {
  test::TempDir dir;
  REQUIRE(test::runTessera("tile --layout " + quoted(TESSERA_ASSETS "/layouts/hex_slab.json") + " -o " + quoted(dir / "hex"))
              .status == 0);
  const test::CliResult r = test::runTessera("export " + quoted(dir / "hex") + " -o " + quoted(dir / "view"));
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.out, Contains("exported 19 bodies: 380 triangles"));
  for (const char* file : {"assembly.pvd", "blocks.vtu", "nodes.vtu", "layout.json"}) REQUIRE(fs::exists(fs::path(dir / "view") / file));
  REQUIRE(test::runTessera("tile --layout " + quoted(dir / "view/layout.json") + " -o " + quoted(dir / "again")).status == 0);
  const Bundle a = readBundle(dir / "hex"), b = readBundle(dir / "again");
  REQUIRE(b.bodies.size() == 19);
  REQUIRE(b.spanInterfaces == 4);
  for (std::size_t i = 0; i < a.bodies.size(); ++i) REQUIRE((a.bodies[i].position - b.bodies[i].position).norm() < 1e-12);
}

TEST_CASE("blocks laid out apart are refused before a bundle is written") {
  // A pitch of twice the 10 mm block (or one in another unit than the block's): no two blocks
  // touch, which is no assembly.
  test::TempDir dir;
  const test::CliResult r = test::runTessera("tile --block " + quoted(kDefaultBlock) + " --unit mm --grid 3x3 --pitch 20 -o " +
                                             quoted(dir / "apart"));
  INFO(r.err);
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("no two of the 9 bodies touch") && Contains("--pitch is in the block's unit"));
  REQUIRE_FALSE(fs::exists(dir / "apart"));
}

TEST_CASE("a y-up block mesh tiles with --up y into the z-up slab") {
  // The default block written y-up, (x, y, z) -> (x, z, -y): tiled as it is, its thickness lies in
  // plan and no two blocks touch; with --up y it is the same slab as the z-up block's.
  test::TempDir dir;
  std::ifstream in(kDefaultBlock);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream v(line.substr(2));
      double x, y, z;
      v >> x >> y >> z;
      std::ostringstream turned;
      turned.precision(17);
      turned << "v " << x << " " << z << " " << -y;
      line = turned.str();
    }
    out += line + "\n";
  }
  test::writeFile(dir / "yup.obj", out);
  const std::string grid = " --unit mm --grid 3x3 --pitch 10 --spacing 1.0 --edge-spacing 1 -o ";
  const test::CliResult flat = test::runTessera("tile --block " + quoted(dir / "yup.obj") + grid + quoted(dir / "flat"));
  REQUIRE(flat.status == 2);
  REQUIRE_THAT(flat.err, Contains("no two of the 9 bodies touch") && Contains("--up y for y-up meshes"));
  const test::CliResult up = test::runTessera("tile --block " + quoted(dir / "yup.obj") + " --up y" + grid + quoted(dir / "up"));
  INFO(up.err);
  REQUIRE(up.status == 0);
  REQUIRE(test::runTessera("tile --block " + quoted(kDefaultBlock) + grid + quoted(dir / "z")).status == 0);
  const Bundle a = readBundle(dir / "up"), b = readBundle(dir / "z");
  REQUIRE(a.sourceUp == "y");
  REQUIRE(a.bodies.size() == b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    REQUIRE((a.bodies[i].position - b.bodies[i].position).norm() < 1e-12);
    REQUIRE(a.bodies[i].orientation.angularDistance(b.bodies[i].orientation) < 1e-9);
  }
  REQUIRE_THAT(up.out, Contains("1 of 1 free bodies held both up and down"));
}

TEST_CASE("a body that touches nothing is reported, not refused") {
  test::TempDir dir;
  test::writeFile(dir / "solo.json", R"({"format": "tessera-layout", "version": 1, "unit": "mm",
      "shapes": {"b": {"mesh": ")" + kDefaultBlock + R"("}}, "bodies": [{"name": "solo", "shape": "b", "position": [0, 0, 0]}]})");
  const test::CliResult r = test::runTessera("tile --layout " + quoted(dir / "solo.json") + " -o " + quoted(dir / "s"));
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.err, Contains("body 'solo' touches no other body") && Contains("not held up or down"));
  REQUIRE_THAT(r.out, Contains("0 of 1 free bodies held"));
}

TEST_CASE("tile leaves the rigid-block verdict of a large slab to tessera check, naming it") {
  test::TempDir dir;
  const test::CliResult r =
      test::runTessera("tile --tiling square --grid 13x13 --pitch 10 --thickness 3.18 --angle 5 --unit mm -o " + quoted(dir / "big"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.out, Contains("169 bodies"));
  REQUIRE_THAT(r.out, Contains("interlocked   not checked here for 169 bodies (over 150") && Contains("tessera check " + (dir / "big")));
  REQUIRE_THAT(r.out, !Contains("interlocked   yes") && !Contains("stable"));
}

TEST_CASE("tile --tiling: a generated hex slab and its verdict, a tiling file, and mistakes that exit 2 naming the fix") {
  test::TempDir dir;
  const test::CliResult hex =
      test::runTessera("tile --tiling hex --grid 4x4 --pitch 10 --thickness 3.18 --angle 5 --unit mm -o " + quoted(dir / "hex"));
  INFO(hex.err);
  REQUIRE(hex.status == 0);
  REQUIRE_THAT(hex.out, Contains("16 bodies (12 fixed, 4 free), 1 distinct shape(s)"));
  REQUIRE_THAT(hex.out, Contains("interlocked   yes"));
  const test::CliResult check = test::runTessera("check " + quoted(dir / "hex") + " --json");
  REQUIRE(check.status == 0);
  const nlohmann::json verdict = nlohmann::json::parse(check.out);
  REQUIRE(verdict["interlocked"] == true);
  REQUIRE(verdict["stable"] == true);
  REQUIRE(verdict["least_friction"] == 0.0);
  // The same four free hexagons drawn in a file (mm): a 4 x 4 grid of hexagons as polygons.
  // And drawn y-up, as many design tools export (x, z, -y): the same slab with --up y; read as
  // z-up, it does not lie flat.
  for (const bool yUp : {false, true}) {
    const std::string name = yUp ? "tiles_yup.obj" : "tiles.obj";
    {
      std::ofstream obj(dir / name);
      int base = 1;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
          const double x = 10 * (c + 0.5 * (r % 2)), y = 10 * std::sqrt(3.0) / 2 * r;
          for (int k = 0; k < 6; ++k) {
            const double a = M_PI / 6 + k * M_PI / 3, u = x + 10 / std::sqrt(3.0) * std::cos(a), v = y + 10 / std::sqrt(3.0) * std::sin(a);
            obj << "v " << u << (yUp ? " 0 " + std::to_string(-v) : " " + std::to_string(v) + " 0") << "\n";
          }
          obj << "f";
          for (int k = 0; k < 6; ++k) obj << " " << base + k;
          obj << "\n";
          base += 6;
        }
    }
    const test::CliResult file = test::runTessera("tile --tiling " + quoted(dir / name) + (yUp ? " --up y" : "") +
                                                  " --thickness 3.18 --angle 5 --unit mm -o " + quoted(dir / (name + ".slab")));
    INFO(file.err);
    REQUIRE(file.status == 0);
    REQUIRE_THAT(file.out, Contains("16 bodies (12 fixed, 4 free)"));
    REQUIRE_THAT(file.out, Contains("interlocked   yes"));
  }
  const test::CliResult sideways = test::runTessera("tile --tiling " + quoted(dir / "tiles_yup.obj") +
                                                    " --thickness 3.18 --angle 5 --unit mm -o " + quoted(dir / "sideways"));
  REQUIRE(sideways.status == 2);
  REQUIRE_THAT(sideways.err, Contains("--up for a y-up file"));

  const auto refused = [&](const std::string& args, const std::string& says) {
    const test::CliResult r = test::runTessera("tile " + args + " -o " + quoted(dir / "bad"));
    INFO(args << ": " << r.err);
    REQUIRE(r.status == 2);
    REQUIRE_THAT(r.err, Contains(says));
    REQUIRE_FALSE(fs::exists(dir / "bad/bundle.h5"));
  };
  refused("--tiling hex --grid 4x4 --pitch 10 --unit mm", "needs --thickness");
  refused("--tiling hex --grid 4x4 --thickness 3 --unit mm", "needs --pitch");
  refused("--tiling pentagon --grid 4x4 --pitch 10 --thickness 3 --unit mm", "no such tiling file");
  refused("--tiling hex --grid 4x4 --pitch 10 --thickness 3 --angle 95 --unit mm", "[0, 90)");
  refused("--tiling hex --grid 2x2 --pitch 10 --thickness 3 --unit mm", "every tile lies on the perimeter");
  refused("--tiling hex --grid 9x9 --pitch 10 --thickness 3 --surface sphere --radius 20 --unit mm", "beyond the sphere's radius");
  refused("--tiling hex --block x.obj --grid 4x4 --pitch 10 --thickness 3 --unit mm", "give one of --block");
}

TEST_CASE("a sweep over a scene's [geometry] builds one bundle per geometry, shared by its cases") {
  test::TempDir dir;
  test::writeFile(dir / "scene.toml", "[geometry]\ngrid = [3, 3]\nangle = 5\n");
  const test::CliResult sweep = test::runTessera("sweep " + quoted(dir / "scene.toml") + " -o " + quoted(dir / "sweep") +
                                                 " --preset fast --set geometry.angle=5,10 --set mu=0.23,0.5");
  INFO(sweep.err);
  REQUIRE(sweep.status == 0);
  REQUIRE_THAT(sweep.out + sweep.err, Contains("4 of 4 cases"));
  int bundles = 0;
  for (const auto& entry : fs::directory_iterator(dir / "sweep/bundles")) bundles += fs::exists(entry.path() / "bundle.h5");
  REQUIRE(bundles == 2);
  // Each case ran on its angle's bundle: the steeper faces carry more.
  std::ifstream table(dir / "sweep/sweep.csv");
  std::string header, line;
  std::getline(table, header);
  std::vector<double> load;
  while (std::getline(table, line)) load.push_back(std::stod(line.substr(line.find(',', line.find(',', line.find(',') + 1) + 1) + 1)));
  REQUIRE(load.size() == 4);
  REQUIRE(load[2] > load[0]);  // angle 10 against angle 5, at mu = 0.23
}
