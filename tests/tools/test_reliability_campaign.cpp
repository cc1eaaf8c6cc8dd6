// The defects a 4 000-case reliability campaign found (issue #39), one test per family: each fails
// without its fix.
#include "tests/fixtures/temp_dir.h"
#include "tests/tools/cli_runner.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <vector>

#include <sys/stat.h>

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
  const std::size_t error = r.err.find("tessera: error: ");
  REQUIRE(error != std::string::npos);
  const std::string line = r.err.substr(error);
  REQUIRE_THAT(line, Contains(expected));
  REQUIRE(std::count(line.begin(), line.end(), '\n') == 1);  // one line, the last
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

TEST_CASE("campaign 3: block lengths and angles are checked as they come in, never replaced or written infinite") {
  test::TempDir dir;
  const std::string out = " --unit mm -o " + quoted(dir / "b.obj");
  for (const char* bad : {"planar --size inf", "box --width -3", "box --width 0", "box --width nan", "wave --thickness 1e300"})
    requireRefused(test::runTessera(std::string("block ") + bad + out), "is not a positive length of 1 um to 1 km");
  requireRefused(test::runTessera("block planar --angle 90" + out), "below 90 degrees");
  REQUIRE_FALSE(fs::exists(dir / "b.obj"));
  REQUIRE(test::runTessera("block box --width 7" + out).status == 0);
}

TEST_CASE("campaign 3: tilings and layouts no arrangement of their blocks can have are refused") {
  test::TempDir dir;
  const std::string block = "tile --block " + quoted(kDefaultBlock) + " --unit mm ";
  requireRefused(test::runTessera(block + "--grid 3x3 --pitch 10 --spacing 1e300 -o " + quoted(dir / "a")),
                 "is larger than the block");
  requireRefused(test::runTessera(block + "--grid 2x2 --pitch 10 -o " + quoted(dir / "b")), "none is free to load");
  REQUIRE(test::runTessera(block + "--grid 2x2 --pitch 10 --fix none -o " + quoted(dir / "c")).status == 0);
  const std::string mesh = std::string(TESSERA_ASSETS) + "/blocks/planar_a10_h3.18_5deg.obj";
  const auto layout = [&](const std::string& far, const std::string& span) {
    std::string text = "{\"format\": \"tessera-layout\", \"version\": 1, \"unit\": \"mm\", \"shapes\": {\"p\": {\"mesh\": \"" +
                       mesh + "\"}}, \"bodies\": [";
    for (int i = 0; i < 3; ++i)
      text += std::string(i ? ", " : "") + "{\"name\": \"b" + std::to_string(i) + "\", \"shape\": \"p\", \"position\": [" +
              (i == 2 ? far : std::to_string(10 * i)) + ", 0, 0], \"fixed\": " + (i == 1 ? "false" : "true") +
              (i == 1 ? ", \"quaternion\": [0.7071067811865476, 0, 0, 0.7071067811865476]" : "") + "}";  // turned to interlock
    test::writeFile(dir / "layout.json", text + "]" + span + "}");
    return test::runTessera("tile --layout " + quoted(dir / "layout.json") + " --replace -o " + quoted(dir / "d"));
  };
  const test::CliResult good = layout("20", "");
  INFO(good.err);
  REQUIRE(good.status == 0);
  requireRefused(layout("1e300", ""), "lies 1e+300 mm from the middle of the assembly");
  requireRefused(layout("20", ", \"span\": {\"length\": 1e300, \"interfaces\": 2}"), "is longer than the whole assembly");
}

TEST_CASE("campaign 5: a sweep value a run would not take as labelled, or one given twice, is refused before any case is made") {
  test::TempDir dir;
  smallSlab(dir);
  const std::string sweep = "sweep " + quoted(dir / "scene.toml") + " -o " + quoted(dir / "s") + " --set ";
  requireRefused(test::runTessera(sweep + "span.interfaces=2.5,2.4"), "'span.interfaces' takes a whole number, not 2.5");
  requireRefused(test::runTessera(sweep + "solver.threads=1.5"), "'solver.threads' takes a whole number, not 1.5");
  requireRefused(test::runTessera(sweep + "mu=0.2,0.2,0.2"), "0.2 is given twice");
  requireRefused(test::runTessera(sweep + "mu=0.3:0.3:2"), "0.3 is given twice");
  REQUIRE_FALSE(fs::exists(dir / "s/sweep.json"));
}

TEST_CASE("campaign 6: figures are written whole or not at all, and a bad experiments file is one line") {
  test::TempDir dir;
  smallSlab(dir, "[indenter]\nspeed = 0.05\n");
  REQUIRE(test::runTessera("sweep " + quoted(dir / "scene.toml") + " --set mu=0.2 -o " + quoted(dir / "mu")).status == 0);
  const std::string report = "report " + quoted(dir / "mu");
  // A full disk (files of at most 8 KiB): exit 2 naming the figure, no figure and no temporary left.
  const test::CliResult full = test::runTessera(report, "ulimit -f 8; trap '' XFSZ;");
  INFO(full.err);
  REQUIRE(full.status == 2);
  REQUIRE_THAT(full.err, Contains("cannot write: disk full"));
  REQUIRE_THAT(full.err, !Contains("Traceback"));
  for (const auto& e : fs::directory_iterator(dir / "mu/report")) {
    INFO(e.path());
    REQUIRE(false);  // nothing half-written, and no temporary
  }
  // Experiments: missing, short, not numbers.
  test::writeFile(dir / "short.csv", "label,E_Pa,L_m,h_m,P_peak_N,delta_peak_m\nA,4.2e9,0.05\n");
  test::writeFile(dir / "words.csv", "label,E_Pa,L_m,h_m,P_peak_N,delta_peak_m\nA,4.2e9,0.05,3e-3,high,4e-3\n");
  test::writeFile(dir / "columns.csv", "label,E,L\nA,1,2\n");
  const std::pair<std::string, std::string> cases[] = {{"missing.csv", "cannot read it"},
                                                       {"short.csv", "line 2: a value missing or not a number"},
                                                       {"words.csv", "line 2: a value missing or not a number"},
                                                       {"columns.csv", "no column E_Pa, L_m, h_m"}};
  for (const auto& [file, expected] : cases) {
    const test::CliResult r = test::runTessera(report + " --experiments " + quoted(dir / file));
    INFO(r.err);
    REQUIRE(r.status == 2);
    REQUIRE_THAT(r.err, Contains(file + ": " + expected) && !Contains("Traceback"));
    REQUIRE(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  test::writeFile(dir / "good.csv", "label,E_Pa,L_m,h_m,P_peak_N,delta_peak_m\nA,4.2e9,0.05,3.18e-3,150,4e-3\n");
  REQUIRE(test::runTessera(report + " --experiments " + quoted(dir / "good.csv")).status == 0);
  REQUIRE(fs::file_size(dir / "mu/report/normalised.svg") > 1000);
}

TEST_CASE("campaign 6: adding a shape to a bundle on a full disk leaves the bundle and its grids as they were") {
  test::TempDir dir;
  const std::string prep = "prep " + quoted(kDefaultBlock) + " --unit mm -o " + quoted(dir / "b");
  REQUIRE(test::runTessera(prep).status == 0);
  const std::string grid = dir / "b/planar_a10_h3.18_5deg.vdb";
  const std::string before = test::readFile(dir / "b/bundle.h5"), gridBefore = test::readFile(grid);
  const auto inode = [](const std::string& path) {
    struct stat s {};
    ::stat(path.c_str(), &s);
    return s.st_ino;
  };
  const auto gridInode = inode(grid);
  const test::CliResult full = test::runTessera(prep + " --name second", "ulimit -f 100; trap '' XFSZ;");
  INFO(full.err);
  REQUIRE(full.status == 2);
  REQUIRE_THAT(full.err, Contains("cannot write: disk full"));
  REQUIRE(test::readFile(dir / "b/bundle.h5") == before);
  REQUIRE(test::readFile(grid) == gridBefore);
  REQUIRE(inode(grid) == gridInode);  // not even rewritten
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir / "b")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  REQUIRE(names == std::vector<std::string>{"bundle.h5", "planar_a10_h3.18_5deg.vdb"});  // no orphan second.vdb
}

TEST_CASE("campaign 8: a run stopped while it settles says where it was and how to go on, not a summary of zeros") {
  test::TempDir dir;
  // Never at rest (a threshold of 1e-30 J) for up to 10 s simulated: Ctrl-C after a second lands in the settling.
  smallSlab(dir);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[protocol]\ndelta_max = 0.2e-3\nsettle_kinetic = 1e-30\nsettle_max_time = 10\n");
  const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "run"),
                                             "timeout --preserve-status -s INT 1");
  INFO(r.out << r.err);
  REQUIRE(r.status == 130);
  REQUIRE_THAT(r.out, Contains("stopped: interrupted while settling, at ") && Contains("nothing loaded yet") &&
                          Contains("go on with: tessera run --resume"));
  REQUIRE_THAT(r.out, !Contains("loaded block ''") && !Contains("P_max = 0 N"));
}

TEST_CASE("campaign 8: an unsettled slab's warning says it was loaded as it was and how to settle it") {
  test::TempDir dir;
  smallSlab(dir);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[protocol]\ndelta_max = 0.05e-3\nsettle_kinetic = 1e-30\nsettle_max_time = 1e-4\n");
  const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "run"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.err, Contains("had not settled after") && Contains("was loaded as it was") && Contains("damping.local = 0 here") &&
                          Contains("protocol.settle_max_time_ratio"));
}
