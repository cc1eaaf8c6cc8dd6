// Reliability (issue: never lose, corrupt or mislabel a result): each test is named after the
// defect it guards against.
#include "levelset/bundle.h"
#include "tests/fixtures/temp_dir.h"
#include "tests/tools/cli_runner.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>

using namespace tessera;
using tessera::test::kDefaultBlock;
using tessera::test::quoted;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

std::string tile(const fs::path& out, const std::string& extra = "") {
  return "tile --block " + quoted(kDefaultBlock) + " --unit mm --grid 3x3 --pitch 10 --spacing 1.0 -o " + quoted(out) + extra;
}

}  // namespace

TEST_CASE("reliability 6: tile refuses to replace an existing bundle without --replace") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  const auto before = fs::last_write_time(dir / "slab/bundle.h5");
  const test::CliResult again = test::runTessera(tile(dir / "slab"));
  REQUIRE(again.status == 2);
  REQUIRE_THAT(again.err, Contains("holds a bundle already") && Contains("--replace"));
  REQUIRE(fs::last_write_time(dir / "slab/bundle.h5") == before);
  REQUIRE(test::runTessera(tile(dir / "slab", " --replace")).status == 0);
}

TEST_CASE("reliability 7: output paths are checked before any work") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[protocol]\ndelta_max = 0.2e-3\n");
  test::writeFile(dir / "a_file", "x");
  const struct {
    std::string output, expected;
  } cases[] = {
      {dir / "a_file", "exists and is not a directory"},
      {dir / "a_file/below", "cannot create the output directory"},
      {"/proc/tessera-out", "cannot"},
      {dir / "slab", "is the bundle's folder"},
  };
  for (const auto& c : cases) {
    const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(c.output));
    INFO(c.output << ": " << r.err);
    REQUIRE(r.status == 2);
    REQUIRE_THAT(r.err, Contains(c.expected));
    REQUIRE_THAT(r.err, !Contains("internal error"));
    REQUIRE_THAT(r.err, !Contains("run: delta"));  // refused before the run began
  }
  REQUIRE_FALSE(fs::exists(dir / "slab/summary.json"));
  const test::CliResult tileToFile = test::runTessera(tile(dir / "a_file"));
  REQUIRE(tileToFile.status == 2);
  REQUIRE_THAT(tileToFile.err, Contains("not a directory"));
}

TEST_CASE("reliability 10: command-line mistakes exit 2, help exits 0") {
  const test::CliResult unknown = test::runTessera("run --no-such-flag");
  REQUIRE(unknown.status == 2);
  const test::CliResult missing = test::runTessera("prep");
  REQUIRE(missing.status == 2);
  const test::CliResult notANumber = test::runTessera("tile --block x.obj --unit mm --pitch ten -o y");
  REQUIRE(notANumber.status == 2);
  REQUIRE(test::runTessera("run --help").status == 0);
  REQUIRE(test::runTessera("--version").status == 0);
}

TEST_CASE("reliability 12: nonsense run options are refused: negative threads") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n");
  const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --threads -3 -o " + quoted(dir / "out"));
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("--threads"));
  REQUIRE_FALSE(fs::exists(dir / "out"));
}

TEST_CASE("reliability 2: a sweep re-run with other values is refused, not relabelled") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nspeed = 0.05\n[protocol]\ndelta_max = 0.05e-3\n");
  const std::string sweep = "sweep " + quoted(dir / "scene.toml") + " -o " + quoted(dir / "mu") + " --jobs 2 --set mu=";
  REQUIRE(test::runTessera(sweep + "0.2,0.3").status == 0);
  const test::CliResult other = test::runTessera(sweep + "0.8,0.9");
  REQUIRE(other.status == 2);
  REQUIRE_THAT(other.err, Contains("holds a sweep of other values") && Contains("material.friction = 0.8") &&
                             Contains("--extend"));
  std::ifstream held(dir / "mu/case_000/scene.toml");
  const std::string text((std::istreambuf_iterator<char>(held)), std::istreambuf_iterator<char>());
  REQUIRE_THAT(text, Contains("friction = 0.2"));
  // The same sweep again finishes what is missing (here: nothing).
  const test::CliResult same = test::runTessera(sweep + "0.2,0.3");
  REQUIRE(same.status == 0);
  REQUIRE_THAT(same.err, Contains("already complete"));
  // Told to extend, it adds the new values as new cases and tables all four.
  const test::CliResult extended = test::runTessera(sweep + "0.3,0.8 --extend");
  INFO(extended.err);
  REQUIRE(extended.status == 0);
  REQUIRE_THAT(extended.err, Contains("case_001 already complete") && Contains("running case_002"));
  REQUIRE_THAT(extended.out, Contains("3 of 3 cases"));
  // Another base scene for a value the folder holds: refused, naming the case.
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nspeed = 0.06\n[protocol]\ndelta_max = 0.05e-3\n");
  const test::CliResult otherBase = test::runTessera(sweep + "0.2");
  REQUIRE(otherBase.status == 2);
  REQUIRE_THAT(otherBase.err, Contains("case_000 holds the case material.friction = 0.2 of another base scene"));
}

TEST_CASE("reliability 5: run refuses a bundle whose bodies overlap, coincident ones included") {
  test::TempDir dir;
  REQUIRE(test::runTessera(tile(dir / "slab")).status == 0);
  Bundle edited = readBundle(dir / "slab");
  edited.bodies[3].position = edited.bodies[4].position;  // r1c0 moved onto the centre block
  edited.bodies[3].orientation = edited.bodies[4].orientation;
  writeBundle(dir / "edited", edited);
  test::writeFile(dir / "scene.toml", "bundle = \"edited\"\n[protocol]\ndelta_max = 0.1e-3\n");
  const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "out"));
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("'r1c0' and 'r1c1' overlap") || Contains("'r1c1' and 'r1c0' overlap"));
  REQUIRE_FALSE(fs::exists(dir / "out"));
}
