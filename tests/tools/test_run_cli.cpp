// `tessera run` end to end on a small slab, and bad scenes refused with nothing written.
#include "levelset/bundle.h"
#include "io/hdf5_file.h"
#include "tests/fixtures/temp_dir.h"
#include "tests/tools/cli_runner.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace tessera;
using tessera::test::kDefaultBlock;
using tessera::test::quoted;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

// A 3 x 3 slab (one free block) at coarse nodes, indented fast to 0.3 mm.
std::string smallRun(const test::TempDir& dir, const std::string& extra = "") {
  REQUIRE(test::runTessera("tile --block " + quoted(kDefaultBlock) + " --unit mm --grid 3x3 --pitch 10 --spacing 1.0 --edge-spacing 1 -o " +
                           quoted(dir / "slab"))
              .status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nspeed = 0.05\n[protocol]\ndelta_max = 0.3e-3\n"
                                      "[damping]\nlocal = 0.3\n" + extra);
  return dir / "scene.toml";
}

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// A square slab of the default block (`tile` with `tileOptions`), run with the scene text given;
// the run must succeed. Returns summary.json.
nlohmann::json runSlab(const test::TempDir& dir, const std::string& tileOptions, const std::string& scene) {
  REQUIRE(test::runTessera("tile --block " + quoted(kDefaultBlock) + " --unit mm --pitch 10 " + tileOptions + " -o " +
                           quoted(dir / "slab"))
              .status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n" + scene);
  const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "out"));
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  return readJson(dir / "out/summary.json");
}

}  // namespace

TEST_CASE("run indents a small slab and writes the curve, the response and the ParaView series") {
  test::TempDir dir;
  const std::string scene = smallRun(dir);
  const test::CliResult r = test::runTessera("run " + quoted(scene) + " --no-plot -o " + quoted(dir / "out"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.out, Contains("peak load") && Contains("initial stiffness") && Contains("written to"));
  for (const char* file : {"results.h5", "curve.csv", "summary.json", "paraview/slab.pvd", "paraview/blocks_0000.vtu"})
    REQUIRE(fs::exists(fs::path(dir / "out") / file));
  const auto summary = readJson(dir / "out/summary.json");
  REQUIRE(summary["target"] == "r1c1");
  REQUIRE(summary["stop_reason"] == "delta_max");
  REQUIRE(summary["response"]["peak_load_N"].get<double>() > 0);
  REQUIRE(summary["response"]["stiffness_N_per_mm"].get<double>() > 0);
  REQUIRE(summary["response"]["failure_mode"] == "none up to delta_max");
  REQUIRE(summary["response"]["failure_deflection_mm"].is_null());
  for (const char* term : {"external_work_mJ", "elastic_energy_mJ", "kinetic_energy_mJ", "friction_dissipated_mJ", "damping_dissipated_mJ",
                           "gravity_work_mJ", "retired_kinetic_mJ", "projection_energy_mJ", "energy_residual_mJ"})
    REQUIRE(summary["response"]["energy"].contains(term));
  REQUIRE(summary["response"]["quasi_static_ratio"].get<double>() < 0.01);
  REQUIRE(summary["material"]["span_interfaces"] == 2);  // 3 x 3 slab: M = 2, L = 10 mm
  // The curve rises with delta.
  std::ifstream csv(dir / "out/curve.csv");
  std::string header, line;
  std::getline(csv, header);
  REQUIRE(header.rfind("delta_mm,load_N", 0) == 0);
  int rows = 0;
  double last = 0;
  while (std::getline(csv, line)) {
    ++rows;
    last = std::stod(line.substr(line.find(',') + 1));
  }
  REQUIRE(rows > 20);
  REQUIRE(last > 0);
}

TEST_CASE("bad scenes give one clear error and write nothing") {
  test::TempDir dir;
  const std::string scene = smallRun(dir);
  const auto refused = [&](const std::string& text, const std::string& problem) {
    test::writeFile(dir / "bad.toml", text);
    const test::CliResult r = test::runTessera("run " + quoted(dir / "bad.toml") + " -o " + quoted(dir / "none"));
    INFO(r.err);
    REQUIRE(r.status == 2);
    REQUIRE_THAT(r.err, Contains("bad.toml") || Contains("bundle"));
    REQUIRE_THAT(r.err, Contains(problem));
    REQUIRE_FALSE(fs::exists(dir / "none"));
  };
  refused("bundle = \"slab\"\n[material]\nyoungs = 1\n", "unknown key 'material.youngs'");
  refused("bundle = \"slab\"\n[material]\nyoungs_modulus = -4.2e9\n", "youngs_modulus must be in");
  refused("bundle = \"slab\"\n[material]\nfriction = -1\n", "friction must be in");
  refused("bundle = \"missing\"\n", "no such bundle");
  refused("bundle = \"slab\"\n[solver]\ntime_step = 1e-3\n", "above the stability estimate");
  refused("bundle = \"slab\"\n[indenter]\npoint = [0.1, 0.1]\n", "indenter.point (100, 100) mm lies on no body");
  refused("bundle = \"slab\"\n[indenter]\npoint = [0.01, 0.0]\n", "lies on the fixed body 'r1c2'");
  refused("bundle = \"slab\"\n[indenter]\ntarget = \"r1c1\"\noffset = [0.009, 0.0]\n", "off the body 'r1c1'");
  refused("bundle = \"slab\"\n[indenter]\npoint = [0.0, 0.0]\ntarget = \"r1c1\"\n", "not both");
  // Values in mm where metres are meant: against the slab (h = 3.18 mm), before any work.
  refused("bundle = \"slab\"\n[indenter]\nradius = 2.5\n", "indenter.radius = 2.5 m is 786 x the loaded block's thickness");
  refused("bundle = \"slab\"\n[protocol]\ndelta_max = 6\n", "lengths are in m (6 mm is 0.006 m)");
  refused("bundle = \"slab\"\n[indenter]\nspeed = 30\n", "speeds are in m/s (30 mm/s is 0.03 m/s)");
  {
    // With a preset the scene read is a derived one, written beside the results only once they
    // are: the message names the user's file and the preset, not a file that does not exist.
    test::writeFile(dir / "bad.toml", "bundle = \"slab\"\n[indenter]\ntarget = \"r0c0\"\n");
    const test::CliResult r = test::runTessera("run " + quoted(dir / "bad.toml") + " --preset fast -o " + quoted(dir / "none"));
    INFO(r.err);
    REQUIRE(r.status == 2);
    REQUIRE_THAT(r.err, Contains(std::string(dir / "bad.toml") + " (with --preset fast): indenter.target 'r0c0' is a fixed body"));
    REQUIRE_FALSE(fs::exists(dir / "none"));
  }

  // A bundle of another format version.
  fs::copy(dir / "slab", dir / "old", fs::copy_options::recursive);
  {
    h5::Handle f(H5Fopen((dir / "old/bundle.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT));
    H5Adelete(f.get(), "format_version");
    h5::writeAttribute(f.get(), "format_version", std::int64_t{7});
  }
  refused("bundle = \"old\"\n", "format version 7 is not supported");
}

TEST_CASE("a scene's [resolution] re-prepares the shapes for the run") {
  test::TempDir dir;
  const std::string scene = smallRun(dir, "[resolution]\nnode_spacing = 1.5e-3\n");
  const test::CliResult r = test::runTessera("run " + quoted(scene) + " --no-plot -o " + quoted(dir / "out"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.err, Contains("shapes re-prepared at node spacing 1.5 mm"));
  REQUIRE(readJson(dir / "out/summary.json")["response"]["peak_load_N"].get<double>() > 0);
}

TEST_CASE("sweep regression: P_max scales with E (gravity off) and a high-friction slab loses its central block") {
  test::TempDir dir;
  REQUIRE(test::runTessera("tile --block " + quoted(kDefaultBlock) + " --unit mm --grid 5x5 --pitch 10 --spacing 1.0 --edge-spacing 1 -o " +
                           quoted(dir / "slab"))
              .status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nspeed = 0.05\n[protocol]\ndelta_max = 5e-3\n"
                                      "[damping]\nlocal = 0.3\n[solver]\ngravity = [0.0, 0.0, 0.0]\n");
  const test::CliResult e = test::runTessera("sweep " + quoted(dir / "scene.toml") + " -o " + quoted(dir / "E") +
                                             " --set E=4.2e9,8.4e9 --jobs 2");
  INFO(e.err);
  REQUIRE(e.status == 0);
  std::ifstream csv(dir / "E/sweep.csv");
  std::string header, first, second;
  std::getline(csv, header);
  std::getline(csv, first);
  std::getline(csv, second);
  const auto peak = [](const std::string& row) {  // case,E,peak_load_N,...
    std::stringstream in(row);
    std::string field;
    std::getline(in, field, ',');
    std::getline(in, field, ',');
    std::getline(in, field, ',');
    return std::stod(field);
  };
  REQUIRE(peak(second) / peak(first) == Approx(2.0).epsilon(0.01));
  REQUIRE(fs::exists(dir / "E/sweep.h5"));
  // Run again: every case is complete, nothing is re-run.
  const test::CliResult again = test::runTessera("sweep " + quoted(dir / "scene.toml") + " -o " + quoted(dir / "E") +
                                                 " --set E=4.2e9,8.4e9 --jobs 2");
  REQUIRE(again.status == 0);
  REQUIRE_THAT(again.err, Contains("case_000 already complete") && Contains("case_001 already complete"));

  // High friction on the paper's 7 x 7 slab (coarse nodes, fast but quasi-static loading).
  REQUIRE(test::runTessera("tile --block " + quoted(kDefaultBlock) + " --unit mm --grid 7x7 --pitch 10 --spacing 1.2 --edge-spacing 1 -o " +
                           quoted(dir / "slab7"))
              .status == 0);
  test::writeFile(dir / "grippy.toml", "bundle = \"slab7\"\n[material]\nfriction = 3.0\n[indenter]\nspeed = 0.1\n"
                                       "[protocol]\ndelta_max = 6e-3\n[damping]\nlocal = 0.3\n");
  const test::CliResult mu = test::runTessera("run " + quoted(dir / "grippy.toml") + " --no-plot -o " + quoted(dir / "mu"));
  INFO(mu.err);
  REQUIRE(mu.status == 0);
  const auto summary = readJson(dir / "mu/summary.json");
  REQUIRE(summary["response"]["failure_mode"] == "loaded block out");
  REQUIRE(summary["response"]["fallen"][0]["name"] == "r3c3");
}

TEST_CASE("default run: the natural failure, after the loaded block has moved a thickness, and a closed energy balance") {
  test::TempDir dir;
  REQUIRE(test::runTessera("tile --block " + quoted(kDefaultBlock) +
                           " --unit mm --grid 7x7 --pitch 10 --fix perimeter --voxel 0.25 --spacing 0.6 -o " +
                           quoted(dir / "slab"))
              .status == 0);
  const test::CliResult r = test::runTessera("run " + quoted(std::string(TESSERA_ASSETS) + "/scenes/default.toml") +
                                             " --bundle " + quoted(dir / "slab") + " --no-plot -o " + quoted(dir / "out"));
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  const auto summary = readJson(dir / "out/summary.json");
  const auto& response = summary["response"];
  // Not the old retirement at one thickness of sinking (3.31 mm): the load falls below 10 % of
  // P_max only once the loaded block has moved beyond h = 3.18 mm.
  REQUIRE(response["failure_deflection_mm"].get<double>() > 3.6);
  REQUIRE(response["block_displacement_at_failure_mm"].get<double>() > 3.18);
  REQUIRE(response["failure_mode"] == "loaded block out");
  REQUIRE(response["fallen"].size() == 1);
  REQUIRE(response["fallen"][0]["name"] == "r3c3");
  REQUIRE(response["loading_energy_to_end_mJ"].get<double>() >= response["loading_energy_mJ"].get<double>());
  REQUIRE(response["delta_max_mm"].get<double>() == Approx(2 * 3.18).epsilon(1e-3));
  // Energy: everything the indenter and gravity put in is stored, dissipated or booked.
  const auto& e = response["energy"];
  REQUIRE(e["friction_dissipated_mJ"].get<double>() > 0);
  REQUIRE(e["damping_dissipated_mJ"].get<double>() > 0);
  REQUIRE(std::abs(e["energy_residual_mJ"].get<double>()) < 0.01 * e["external_work_mJ"].get<double>());
}

TEST_CASE("a 15 x 15 slab dishes past one thickness without failure: its loaded block still carries the load") {
  // The rule this replaces retired the loaded block once it had sunk h (at 3.21 mm here) while it
  // still carried about 70 % of P_max. Here nothing is out, and no failure is reported, while the
  // loaded block is held by its neighbours (1.2 mm uniform nodes, 60 mm/s, to 1.15 h).
  test::TempDir dir;
  const auto response = runSlab(dir, "--grid 15x15 --spacing 1.2 --edge-spacing 1",
                                "[indenter]\nradius = 2.5e-3\nspeed = 0.06\n[protocol]\ndelta_max_ratio = 1.15\n"
                                "[damping]\nlocal = 0.3\n")["response"];
  REQUIRE(response["failure_mode"] == "none up to delta_max");
  REQUIRE(response["fallen"].empty());
  REQUIRE(response["failure_deflection_mm"].is_null());
  // The loaded block has moved more than its thickness, and still carries most of the peak load.
  const double h = response["thickness_mm"].get<double>();
  REQUIRE(response["end"]["block_displacement_mm"].get<double>() > h);
  REQUIRE(response["end"]["load_N"].get<double>() > 0.5 * response["peak_load_N"].get<double>());
}

TEST_CASE("mu = 9 to 6 mm: the main drop, then a staircase of slips") {
  // At the paper's resolution (uniform 0.6 mm nodes) the loaded block wedges until it has moved about 1.2 h, then the load
  // falls to about a third of P_max and steps down in slips to delta = 6 mm.
  test::TempDir dir;
  const auto response = runSlab(dir, "--grid 7x7 --edge-spacing 1",
                                "[material]\nfriction = 9.0\n[indenter]\nradius = 2.5e-3\nspeed = 0.06\n"
                                "[protocol]\ndelta_max = 6e-3\nstop_on_failure = false\n[damping]\nlocal = 0.3\n")["response"];
  const auto& drops = response["load_drops"];
  std::size_t main = 0;
  const auto fall = [&](std::size_t k) { return drops[k]["load_before_N"].get<double>() - drops[k]["load_after_N"].get<double>(); };
  for (std::size_t k = 1; k < drops.size(); ++k)
    if (fall(k) > fall(main)) main = k;
  REQUIRE(drops.size() >= main + 3);  // at least two after the main one
  REQUIRE(fall(main) > 0.5 * response["peak_load_N"].get<double>());
}

TEST_CASE("a slab that does not stand under its own weight is warned about and counted") {
  // Square boxes (no inclined faces) hold nothing up: the centre block drops through.
  test::TempDir dir;
  REQUIRE(test::runTessera("block box --size 10 --thickness 3.18 --unit mm -o " + quoted(dir / "box.obj")).status == 0);
  REQUIRE(test::runTessera("tile --block " + quoted(dir / "box.obj") + " --unit mm --grid 3x3 --pitch 10 --spacing 1.0 -o " +
                           quoted(dir / "slab"))
              .status == 0);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[protocol]\ndelta_max = 0.2e-3\n[damping]\nlocal = 0.3\n");
  const test::CliResult r = test::runTessera("run " + quoted(dir / "scene.toml") + " --no-plot -o " + quoted(dir / "out"));
  INFO(r.out << r.err);
  REQUIRE_THAT(r.err, Contains("1 free bodies sank") && Contains("does not stand under its own weight"));
  REQUIRE(readJson(dir / "out/summary.json")["run"]["sunk_while_settling"] == 1);
}

TEST_CASE("run with a preset uses its keys, kept as OUT/scene.toml, and refuses an unknown preset") {
  test::TempDir dir;
  const std::string scene = smallRun(dir);
  const test::CliResult r = test::runTessera("run " + quoted(scene) + " --preset fast --no-plot -o " + quoted(dir / "out"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  REQUIRE_THAT(r.err, Contains("re-prepared at node spacing 1.2 mm"));
  std::ifstream in(dir / "out/scene.toml");
  std::stringstream text;
  text << in.rdbuf();
  // Ratios (scale-aware): 1.2 mm / 3.18 mm of each shape's thinnest extent, 20 x the paper's speed ratio.
  REQUIRE_THAT(text.str(), Contains("--preset fast") && Contains("speed_ratio = 0.0228") && Contains("node_spacing_ratio = 0.3773") &&
               Contains("edge_spacing_fraction = 1"));
  REQUIRE_THAT(text.str(), Contains("delta_max = 0.000299999"));  // the scene's own keys stay

  const test::CliResult bad = test::runTessera("run " + quoted(scene) + " --preset turbo -o " + quoted(dir / "none"));
  REQUIRE(bad.status == 2);
  REQUIRE_THAT(bad.err, Contains("unknown preset 'turbo'") && Contains("fast, default, paper, fine"));
  REQUIRE_FALSE(fs::exists(dir / "none"));
}
