// The loaded block and the indenter as a run sees them. K is read on the loaded block's own
// thickness along the loading direction (issue #38): a 3 x 3 slab of the default block tilted 30
// degrees as a whole and indented vertically. Its h, which sets K's fit window, the indenter's
// radius rule and delta_max, is the block's extent on the vertical through the load point,
// t / cos 30 = 3.67 mm, not its vertical extent (7.75 mm, which would have stretched K's window
// over twice the curve). And an indenter sunk past half its radius is warned about.
#include "run/run_session.h"
#include "tests/fixtures/scenes.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace tessera;

TEST_CASE("a slab tilted 30 degrees: h and K's window are the loaded block's thickness along the load") {
  const double t = 3.18e-3, tilt = 30 * M_PI / 180;
  test::TempDir dir;
  Bundle slab = test::smallSlab(3, 0.25e-3, 1.0e-3);
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()));
  for (Body& b : slab.bodies) {
    b.position = turn * b.position;
    b.orientation = turn * b.orientation;
  }
  writeBundle(dir / "slab", slab);
  test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nradius = 2.5e-3\nspeed = 0.03\n[protocol]\n"
                                      "delta_max = 1.0e-3\n[damping]\nlocal = 0.3\n");
  RunRequest r;
  r.scene = dir / "scene.toml";
  r.threads = 2;
  auto session = RunSession::start(r, {});
  session->run({});
  const ResponseParameters p = session->response();
  INFO("h " << p.thickness << " m, K " << p.stiffness << " N/m over [" << p.fitFrom << ", " << p.fitTo << "] m, peak at "
            << p.deltaAtPeak << " m");
  REQUIRE(p.thickness == Approx(t / std::cos(tilt)).epsilon(1e-3));
  // The window [0, 0.126 h] (the paper's 0.4 mm on its 3.18 mm block), the peak being past twice that.
  REQUIRE(p.deltaAtPeak > 0.8e-3 / t * p.thickness);
  CHECK(p.fitFrom == 0);
  CHECK(p.fitTo == Approx(0.4e-3 / t * p.thickness).epsilon(1e-9));
  CHECK(p.stiffness > 0);
}

TEST_CASE("an indenter sunk past half its radius is warned about once and the default indenter is not") {
  // A 3 x 3 slab under an indenter 1000 x softer than the blocks' contacts: it sinks into the
  // loaded block by more than 1.25 mm before the slab resists; with the default stiffness, 0.6 mm
  // of travel sinks it by a few hundredths of its radius.
  test::TempDir dir;
  writeBundle(dir / "slab", test::smallSlab(3, 0.25e-3, 1.0e-3));
  for (const double factor : {1e-3, 1.0}) {
    INFO("indenter stiffness factor " << factor);
    test::writeFile(dir / "scene.toml", "bundle = \"slab\"\n[indenter]\nradius = 2.5e-3\nspeed = 0.03\nstiffness_factor = " +
                                            std::to_string(factor) + "\n[protocol]\ndelta_max = 2.0e-3\n[damping]\nlocal = 0.3\n");
    RunRequest r;
    r.scene = dir / "scene.toml";
    r.threads = 2;
    auto session = RunSession::start(r, {});
    std::vector<std::string> warnings;
    RunHooks hooks;
    hooks.warning = [&](const std::string& w) { warnings.push_back(w); };
    session->run(hooks);
    const auto deep = std::count_if(warnings.begin(), warnings.end(),
                                    [](const std::string& w) { return w.find("of its radius) into the bodies") != std::string::npos; });
    CHECK(deep == (factor < 1 ? 1 : 0));
  }
}
