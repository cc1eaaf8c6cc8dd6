// The defects a 4 000-case reliability campaign found (issue #39), one test per family: each fails
// without its fix.
#include "tests/fixtures/temp_dir.h"
#include "tests/tools/cli_runner.h"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace tessera;
using tessera::test::kDefaultBlock;
using tessera::test::quoted;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// A 3 x 3 slab of the default block in DIR/slab and a scene loading it to 0.2 mm in DIR/scene.toml.
void smallSlab(const test::TempDir& dir, const std::string& sceneExtra = "") {
  REQUIRE(test::runTessera("tile --block " + quoted(kDefaultBlock) + " --unit mm --grid 3x3 --pitch 10 --spacing 1.0 -o " +
                           quoted(dir / "slab"))
              .status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[protocol]\ndelta_max = 0.2e-3\n" + sceneExtra);
}

void requireRefused(const test::CliResult& r, const std::string& expected) {
  INFO(r.err);
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains(expected));
  REQUIRE_THAT(r.err, !Contains("internal error"));
  REQUIRE(std::count(r.err.begin(), r.err.end(), '\n') == 1);  // one line
}

}  // namespace

TEST_CASE("campaign 1: thread counts beyond 1024 are refused before a thread pool is made (a billion crashed)") {
  test::TempDir dir;
  smallSlab(dir);
  requireRefused(test::runTessera("run " + quoted(dir / "scene.toml") + " --threads 1000000000 -o " + quoted(dir / "a")),
                 "--threads must be 0 (all cores) or 1 to 1024, got 1000000000");
  REQUIRE_FALSE(fs::exists(dir / "a"));
  requireRefused(test::runTessera("sweep " + quoted(dir / "scene.toml") + " --set mu=0.2 --threads 100000 -o " + quoted(dir / "s")),
                 "--threads must be 1 to 1024 per case");
}

TEST_CASE("campaign 1: a sweep whose case record cannot be written stops with exit 2, not an abort") {
  test::TempDir dir;
  smallSlab(dir);
  const std::string sweep = "sweep " + quoted(dir / "scene.toml") + " --set mu=0.2 -o " + quoted(dir / "mu");
  fs::rename(dir / "slab", dir / "away");  // the case fails (no bundle) and stays to be run again
  REQUIRE(test::runTessera(sweep).status == 2);
  fs::rename(dir / "away", dir / "slab");
  fs::remove(dir / "mu/case_000/attempt.json");
  fs::create_directory(dir / "mu/case_000/attempt.json");  // the record cannot be written (as on a full disk)
  const test::CliResult r = test::runTessera(sweep);
  INFO(r.err);
  REQUIRE(r.status == 2);
  REQUIRE_THAT(r.err, Contains("attempt.json: cannot write"));
}

TEST_CASE("campaign 2: an indenter speed that could never reach delta_max is refused (5e-324 m/s ran forever)") {
  test::TempDir dir;
  smallSlab(dir, "[indenter]\nspeed = 5e-324\n");
  requireRefused(test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "a")),
                 "time steps of");
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[protocol]\ndelta_max = 0.2e-3\n[indenter]\nspeed = 1e-12\n");
  requireRefused(test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "b")),
                 "more than 1e9; speeds are in m/s");
}
