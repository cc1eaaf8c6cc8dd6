// The three level-set paths on one slab of the default (convex) block: its exact planes, the exact
// mesh level set (the planes turned off) and the trilinear grid (both turned off). The two exact
// paths describe the same polyhedron, so they must give the same answer; the grid rounds the
// interlocked edges and softens the slab.
#include "run/run_session.h"
#include "tests/fixtures/scenes.h"
#include "tests/fixtures/temp_dir.h"

#include <catch2/catch.hpp>

#include <algorithm>

using namespace tessera;

namespace {

struct PathResult {
  double peak = 0;       // N, largest load to delta = 0.6 mm
  double stiffness = 0;  // N/m, K
  std::string path;      // as summary.json names it
};

PathResult runWith(const test::TempDir& dir, const std::string& name, const std::string& solverKeys) {
  const std::string scene = dir / (name + ".toml");
  test::writeFile(scene, "bundle = \"slab\"\n[material]\nyoungs_modulus = 4.2e9\nfriction = 0.23\n"
                         "[indenter]\nradius = 2.5e-3\nspeed = 0.03\n[protocol]\ndelta_max = 0.6e-3\n"
                         "[damping]\nlocal = 0.3\n[output]\ncheckpoint_seconds = 1e5\n[solver]\n" + solverKeys);
  RunRequest request;
  request.scene = scene;
  request.threads = 1;
  auto session = RunSession::start(request, {});
  session->run({});
  PathResult r;
  for (const CurveSample& s : session->record().curve) r.peak = std::max(r.peak, s.load);
  r.stiffness = session->response().stiffness;
  r.path = levelSetPath(session->bundle().shapes.front(), session->scene().solver.exactConvexLevelSets,
                        session->scene().solver.exactMeshLevelSets);
  return r;
}

}  // namespace

TEST_CASE("level-set paths: the default block through its exact mesh level set gives its exact planes' answer, the grid softens it") {
  test::TempDir dir;
  writeBundle(dir / "slab", test::smallSlab(3, 0.25e-3, 1.0e-3));
  const PathResult planes = runWith(dir, "planes", "");
  const PathResult mesh = runWith(dir, "mesh", "exact_convex_level_sets = false\n");
  const PathResult grid = runWith(dir, "grid", "exact_convex_level_sets = false\nexact_mesh_level_sets = false\n");
  CHECK(planes.path.rfind("exact planes", 0) == 0);
  CHECK(mesh.path.rfind("exact mesh", 0) == 0);
  CHECK(grid.path.rfind("grid", 0) == 0);
  INFO("P_max: planes " << planes.peak << " N, mesh " << mesh.peak << " N, grid " << grid.peak << " N; K: planes "
                        << planes.stiffness << ", mesh " << mesh.stiffness << ", grid " << grid.stiffness << " N/m");
  CHECK(std::abs(mesh.peak / planes.peak - 1) < 1e-3);
  CHECK(std::abs(mesh.stiffness / planes.stiffness - 1) < 1e-3);
  // The grid's rounded edges soften the slab (measured: K -9 %, P_max -2 % to 0.6 mm).
  CHECK(grid.stiffness < 0.95 * planes.stiffness);
}
