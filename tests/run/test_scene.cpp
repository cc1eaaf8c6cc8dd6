// Scene files: what they set, and bad ones refused naming the file, the key and the range.
#include "io/input_error.h"
#include "levelset/bundle.h"
#include "run/geometry_bundle.h"
#include "run/scene.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace tessera;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {
Scene sceneFrom(const test::TempDir& dir, const std::string& text) {
  test::writeFile(dir / "scene.toml", text);
  return readScene(dir / "scene.toml");
}
}  // namespace

TEST_CASE("a scene file fills the settings, with defaults for what it leaves out") {
  test::TempDir dir;
  const Scene s = sceneFrom(dir, R"(bundle = "slab"
[material]
youngs_modulus = 10e9
friction = 0.5
[span]
length = 0.05
interfaces = 6
[indenter]
speed = 0.01
target = "r3c3"
[damping]
local = 0.2
[solver]
threads = 2
gravity = [0.0, 0.0, 0.0]
)");
  REQUIRE(s.bundle == dir / "slab");
  REQUIRE(s.contact.youngsModulus == 10e9);
  REQUIRE(s.contact.friction == 0.5);
  REQUIRE(s.contact.spanInterfaces == 6);
  REQUIRE(s.indenter.speed == 0.01);
  REQUIRE(s.indenter.radius == 0);  // default: radius_ratio x h, 2.5 mm on the paper's block
  REQUIRE(s.indenter.radiusRatio * 3.18e-3 == Approx(2.5e-3).epsilon(1e-12));
  REQUIRE(s.indenter.target == "r3c3");
  REQUIRE(s.solver.localDamping == 0.2);
  REQUIRE(s.solver.threads == 2);
  REQUIRE(s.solver.gravity.norm() == 0.0);
  REQUIRE(s.protocol.deltaMax == 0);  // default: 2 h of the loaded block
  REQUIRE(s.protocol.deltaMaxRatio == 2.0);
}

TEST_CASE("the shipped default scene reads") {
  const Scene s = readScene(TESSERA_ASSETS "/scenes/default.toml");
  REQUIRE(s.contact.youngsModulus == 4.2e9);
  REQUIRE(s.contact.friction == 0.23);
  REQUIRE(s.indenter.radius == 2.5e-3);
}

TEST_CASE("bad scene files are refused with the key and the reason") {
  test::TempDir dir;
  const auto refused = [&](const std::string& text, const std::string& problem) {
    INFO(text);
    REQUIRE_THROWS_WITH(sceneFrom(dir, text), Contains("scene.toml") && Contains(problem));
  };
  refused("bundle = \"b\"\n[material]\nyoungs_modulus = -4.2e9\n", "material.youngs_modulus must be in [1000, 1e+13] (Pa), got -4.2e+09");
  refused("bundle = \"b\"\n[material]\nfriction = -0.1\n", "material.friction must be in [0");
  refused("bundle = \"b\"\n[material]\nyoungs = 4.2e9\n", "unknown key 'material.youngs'");
  refused("bundle = \"b\"\ncolour = 1\n", "unknown key 'colour'");
  refused("bundle = \"b\"\n[materials]\n", "unknown table [materials]");
  refused("[material]\nfriction = 0.2\n", "bundle = \"...\" is missing");
  refused("bundle = \"b\"\n[indenter]\nspeed = \"fast\"\n", "indenter.speed must be a number");
  refused("bundle = \"b\"\n[solver]\nthreads = 1.5\n", "solver.threads must be a whole number");
  refused("bundle = \"b\"\n[material\n", "not valid TOML");
  REQUIRE_THROWS_WITH(readScene(dir / "none.toml"), Contains("none.toml") && Contains("no such scene file"));
}

TEST_CASE("the contact model's names reach the scene, and a name that is none of them is refused listing them") {
  test::TempDir dir;
  const Scene chosen = sceneFrom(dir, "bundle = \"b\"\n[material]\nstiffness_rule = \"sections\"\n"
                                      "[solver]\ncontact_area = \"blended\"\ncontact_evaluation = \"one-way\"\n");
  REQUIRE(chosen.contact.area == ContactArea::Blended);
  REQUIRE(chosen.contact.evaluation == ContactEvaluation::OneWay);
  REQUIRE(chosen.contact.stiffnessRule == StiffnessRule::Sections);
  const Scene plain = sceneFrom(dir, "bundle = \"b\"\n");
  REQUIRE(plain.contact.area == ContactArea::Nearest);
  REQUIRE(plain.contact.evaluation == ContactEvaluation::TwoWay);
  REQUIRE(plain.contact.stiffnessRule == StiffnessRule::Span);
  REQUIRE_THROWS_WITH(sceneFrom(dir, "bundle = \"b\"\n[solver]\ncontact_area = \"smooth\"\n"),
                      Contains("solver.contact_area must be \"blended\" or \"nearest\", got \"smooth\""));
  REQUIRE_THROWS_WITH(sceneFrom(dir, "bundle = \"b\"\n[solver]\ncontact_evaluation = \"both\"\n"),
                      Contains("solver.contact_evaluation must be \"two-way\" or \"one-way\", got \"both\""));
  REQUIRE_THROWS_WITH(sceneFrom(dir, "bundle = \"b\"\n[material]\nstiffness_rule = \"E\"\n"),
                      Contains("material.stiffness_rule must be \"span\", \"bars\" or \"sections\", got \"E\""));
  REQUIRE_THROWS_WITH(sceneFrom(dir, "bundle = \"b\"\n[solver]\ncontact_area = 1\n"), Contains("solver.contact_area"));
}

TEST_CASE("a scene can re-prepare the shapes at another resolution") {
  test::TempDir dir;
  const Scene s = sceneFrom(dir, "bundle = \"b\"\n[resolution]\nnode_spacing = 0.3e-3\nvoxel = 0.125e-3\n");
  REQUIRE(s.resolution.nodeSpacing == 0.3e-3);
  REQUIRE(s.resolution.voxelSize == 0.125e-3);
  REQUIRE_THROWS_WITH(sceneFrom(dir, "bundle = \"b\"\n[resolution]\nnodes = 1\n"), Contains("unknown key 'resolution.nodes'"));
  const Scene graded = sceneFrom(dir, "bundle = \"b\"\n[resolution]\nedge_spacing_fraction = 0.5\nsize_gradient = 1\n");
  REQUIRE(graded.resolution.edgeSpacingFraction == 0.5);
  REQUIRE(graded.resolution.sizeGradient == 1.0);
  REQUIRE(graded.resolution.any());
  REQUIRE_THROWS_WITH(sceneFrom(dir, "bundle = \"b\"\n[resolution]\nedge_spacing_fraction = 0.01\n"),
                      Contains("edge_spacing_fraction must be 0 (the bundle's) or between 0.05 and 1"));
  REQUIRE_THROWS_WITH(sceneFrom(dir, "bundle = \"b\"\n[resolution]\nedge_spacing_fraction = 2\n"),
                      Contains("resolution.edge_spacing_fraction"));
}

TEST_CASE("a scene can carry its geometry: [geometry] in place of bundle, built once per recipe") {
  test::TempDir dir;
  const Scene paper = sceneFrom(dir, "[geometry]\n");  // the defaults: the paper's slab
  REQUIRE(paper.bundle.empty());
  REQUIRE(paper.geometry);
  REQUIRE(paper.geometry->tiling == "square");
  REQUIRE(paper.geometry->columns == 7);
  REQUIRE(paper.geometry->pitch == Approx(10e-3));
  REQUIRE(paper.geometry->angle == Approx(5));
  const Scene hex = sceneFrom(dir, "[geometry]\ntiling = \"hex\"\ngrid = [4, 3]\npitch = 0.012\nthickness = 0.004\nangle = 7.5\n");
  REQUIRE(hex.geometry->columns == 4);
  REQUIRE(hex.geometry->rows == 3);
  REQUIRE(sceneFrom(dir, "[geometry]\ntiling = \"my.obj\"\n").geometry->tiling == (dir / "my.obj"));
  const Scene files = sceneFrom(dir, "[geometry]\ntiling = \"my.obj\"\nsurface = \"roof.stl\"\nup = \"y\"\n");
  REQUIRE(files.geometry->surface == (dir / "roof.stl"));
  REQUIRE(files.geometry->up == "y");
  // A sweep's scene (sceneWithOverrides, written elsewhere) names both files absolutely.
  const std::string swept = sceneWithOverrides(dir / "scene.toml", {{"geometry.angle", 6.0}});
  REQUIRE_THAT(swept, Catch::Contains(fs::absolute(dir / "my.obj").lexically_normal().string()));
  REQUIRE_THAT(swept, Catch::Contains(fs::absolute(dir / "roof.stl").lexically_normal().string()));
  for (const std::string& bad : {std::string("bundle = \"slab\"\n[geometry]\n"), std::string("[material]\nE = 4e9\n"),
                                 std::string("[geometry]\ngrid = [0, 3]\n"), std::string("[geometry]\nangle = 95\n"),
                                 std::string("[geometry]\nfix = \"ring\"\n"), std::string("[geometry]\nwidth = 3\n"),
                                 std::string("[geometry]\nup = \"w\"\n")}) {
    INFO(bad);
    REQUIRE_THROWS_AS(sceneFrom(dir, bad), InputError);
  }
  // Built once: a second run finds it; another angle is another bundle.
  std::vector<std::string> heard;
  const auto log = [&](const std::string& m) { heard.push_back(m); };
  GeometryRecipe small = *hex.geometry;
  small.columns = small.rows = 3;
  const std::string first = geometryBundle(small, dir / "cache", log);
  REQUIRE(heard.size() == 1);
  REQUIRE(readBundle(first).bodies.size() == 9);
  REQUIRE(geometryBundle(small, dir / "cache", log) == first);
  REQUIRE(heard.size() == 1);
  small.angle = 10;
  REQUIRE(geometryBundle(small, dir / "cache", log) != first);
  REQUIRE(heard.size() == 2);
  // A tiling from a file: the same file finds its bundle, an edited one (the same path) builds anew.
  const auto squares = [](double pitch) {  // a 3 x 3 grid of squares as an OBJ of quads, in m
    std::string obj;
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 3; ++i) obj += "v " + std::to_string(i * pitch) + " " + std::to_string(j * pitch) + " 0\n";
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const auto at = [](int x, int y) { return std::to_string(y * 4 + x + 1); };
        obj += "f " + at(i, j) + " " + at(i + 1, j) + " " + at(i + 1, j + 1) + " " + at(i, j + 1) + "\n";
      }
    return obj;
  };
  test::writeFile(dir / "tiles.obj", squares(0.01));
  GeometryRecipe fromFile = small;
  fromFile.tiling = dir / "tiles.obj";
  const std::string tiled = geometryBundle(fromFile, dir / "cache", log);
  REQUIRE(geometryBundle(fromFile, dir / "cache", log) == tiled);
  test::writeFile(dir / "tiles.obj", squares(0.012));
  REQUIRE(geometryBundle(fromFile, dir / "cache", log) != tiled);
  // A block family on the square grid: the wave block, one shape for the checkerboard.
  GeometryRecipe wave;
  wave.family = "wave";
  wave.columns = wave.rows = 3;
  const Bundle waves = readBundle(geometryBundle(wave, dir / "cache", log));
  REQUIRE(waves.bodies.size() == 9);
  REQUIRE(waves.shapes.size() == 1);
  REQUIRE(waves.spanLength == Approx(0.01));
  REQUIRE_THROWS_AS(sceneFrom(dir, "[geometry]\nfamily = \"cube\"\n"), InputError);
  // The cases of a sweep share its folder's bundles/.
  fs::create_directories(dir / "sweep");
  test::writeFile(dir / "sweep/sweep.json", "{}");
  REQUIRE(geometryCache(dir / "sweep/case_0") == (fs::path(dir / "sweep") / "bundles").string());
  REQUIRE(geometryCache(dir / "run") == dir / "run");
}
