// tessera check's analyses on closed-form cases: a wedged block is interlocked and stands without
// friction; a box among boxes slides upwards and down, rigid equilibrium holds it at any friction,
// yet built unstressed it sinks at any friction up to 10, as in its run; a block
// on a ramp of slope alpha (a way out, friction needed: the elastic settling decides) stands from
// mu = tan(alpha) on (rigid equilibrium within the friction pyramid's 1 / cos(22.5 deg)),
// whichever body is listed first; a triangle slab, which rigid equilibrium holds at mu = 0.23,
// does not settle there built unstressed, as in its run.
#include "geometry/block_generators.h"
#include "levelset/assembly_checks.h"
#include "levelset/elastic_settling.h"
#include "levelset/generated_slab.h"
#include "levelset/interlocking_signs.h"
#include "levelset/rigid_block_analysis.h"
#include "geometry/tilted_blocks.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tessera;

namespace {

Bundle assembled(std::vector<AssemblyPart> parts) {
  AssembleOptions options;
  options.unit = "m";
  PrepLog log;
  AssembleReport report;
  return assembleParts(std::move(parts), options, log, report);
}

// An n x n slab of a tiling, pitch 0.1 m, h = 31.8 mm (the paper's proportions), perimeter fixed.
GeneratedSlabOptions slabOptions(const char* tiling, int n, double degrees) {
  GeneratedSlabOptions options;
  options.tiling.kind = tiling;
  options.tiling.pitch = 0.1;
  options.tiling.columns = options.tiling.rows = n;
  options.thickness = 0.0318;
  options.angle = degrees * M_PI / 180;
  return options;
}

Bundle squareSlab(double degrees) { return assembled(generatedSlabParts(slabOptions("square", 3, degrees))); }

AssemblyStatics analysed(const Bundle& bundle, double friction) { return analyseAssembly(bundle, AssemblyLevelSets(bundle), friction); }

// A box of side a on a fixed ramp of slope alpha (about y); `blockFirst` lists the block first.
Bundle blockOnRamp(double alpha, bool blockFirst) {
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitY()).toRotationMatrix();
  AssemblyPart ramp{"ramp", "ramp", makeBox(1.0, 1.0, 0.2), true};
  AssemblyPart block{"block", "block", makeBox(0.2, 0.2, 0.2), false};
  for (Eigen::Vector3d& x : ramp.mesh.vertices) x = tilt * x;
  for (Eigen::Vector3d& x : block.mesh.vertices) x = tilt * (x + Eigen::Vector3d(0, 0, 0.2));
  return blockFirst ? assembled({block, ramp}) : assembled({ramp, block});
}

}  // namespace

TEST_CASE("rigid blocks: a planar block wedged among fixed ones is interlocked and stands without friction") {
  const AssemblyStatics s = analysed(squareSlab(10), 0.23);
  REQUIRE(s.pairs == 4);  // the centre block's faces (the corner neighbours meet it along a line only)
  REQUIRE(s.interlocking.interlocked);
  REQUIRE(s.interlocking.slidingModes == 0);
  REQUIRE(s.stability.stable);
  REQUIRE(s.stability.leastFriction == Approx(0.0));
  REQUIRE(s.stability.rigidLeastFriction == Approx(0.0));
}

namespace {

// A 7 x 7 Voronoi slab (seed 1): the alternating rule leaves it a way out.
GeneratedSlabOptions voronoiSlab(double degrees) { return slabOptions("voronoi", 7, degrees); }

// The rule's signs and the searched ones of a generated slab's tiling.
struct SearchedSigns {
  std::vector<std::vector<EdgeNeighbour>> across;
  std::vector<std::vector<int>> rule, tilts;
  InterlockingSearch search;
};
SearchedSigns searched(const GeneratedSlabOptions& options) {
  const PlaneTiling tiling = makeTiling(options.tiling);
  SearchedSigns s;
  s.across = edgeNeighbours(tiling, 1e-9 * options.tiling.pitch);
  std::vector<char> fixed;
  for (const auto& edges : s.across) fixed.push_back(!freeTile(edges));
  s.rule = s.tilts = interlockingTilts(tiling, s.across, options.angle);
  s.search = interlockSigns(tiling, s.across, fixed, options.thickness, options.angle, options.surface, s.tilts);
  return s;
}

}  // namespace

TEST_CASE("signs searched: a Voronoi slab, not interlocked under the alternating rule, interlocks, and a triangle slab keeps its signs") {
  for (const double degrees : {5.0, 10.0, 20.0}) {
    INFO(degrees << " degrees");
    const SearchedSigns s = searched(voronoiSlab(degrees));
    REQUIRE(s.search.interlocked);
    REQUIRE(s.search.flips > 0);
    REQUIRE(s.tilts != s.rule);
    for (std::size_t t = 0; t < s.tilts.size(); ++t)
      for (std::size_t k = 0; k < s.tilts[t].size(); ++k)
        if (s.across[t][k].tile >= 0) REQUIRE(s.tilts[t][k] == -s.tilts[s.across[t][k].tile][s.across[t][k].edge]);  // one plane an edge
  }
  // On a sphere ten times the span (a dome) and a cylinder (a barrel vault) too.
  for (const BaseSurface::Kind kind : {BaseSurface::Kind::Sphere, BaseSurface::Kind::Cylinder}) {
    GeneratedSlabOptions curved = voronoiSlab(5);
    curved.surface.kind = kind;
    curved.surface.radius = 10 * 7 * curved.tiling.pitch;
    const SearchedSigns s = searched(curved);
    REQUIRE(s.search.interlocked);
    REQUIRE(s.search.flips > 0);
  }
  GeneratedSlabOptions triangles = voronoiSlab(10);
  triangles.tiling.kind = "triangle";
  const SearchedSigns s = searched(triangles);
  REQUIRE_FALSE(s.search.interlocked);  // Gordan: no triangle is held (docs/tiling.md)
  REQUIRE(s.search.programs > 0);
  REQUIRE(s.tilts == s.rule);
  for (const char* kind : {"square", "hex"}) {  // they alternate: interlocked as the rule leaves them
    GeneratedSlabOptions alternating = voronoiSlab(10);
    alternating.tiling.kind = kind;
    const SearchedSigns a = searched(alternating);
    REQUIRE(a.search.interlocked);
    REQUIRE(a.search.programs == 1);
    REQUIRE(a.tilts == a.rule);
  }
}

TEST_CASE("signs searched: tessera check on the Voronoi slab's blocks finds it interlocked, and standing") {
  PrepLog log;
  const AssemblyStatics s = analysed(assembled(generatedSlabParts(voronoiSlab(20), &log)), 0.23);
  REQUIRE(s.interlocking.interlocked);
  REQUIRE(s.stability.stable);
  REQUIRE(log.notes.size() == 1);  // how many edges were flipped
}

TEST_CASE("rigid blocks: a block whose faces all lean out rests on its neighbours: not interlocked, lifts off, stands") {
  TilingOptions options;
  options.pitch = 0.1;
  options.columns = options.rows = 3;
  const PlaneTiling tiling = makeTiling(options);
  const auto across = edgeNeighbours(tiling, 1e-9);
  auto tilts = interlockingTilts(tiling, across, 10 * M_PI / 180);
  for (std::size_t k = 0; k < 4; ++k) {  // the centre tile (4): every face leans out, its neighbours' in
    tilts[4][k] = 1;
    tilts[across[4][k].tile][across[4][k].edge] = -1;
  }
  std::vector<AssemblyPart> parts;
  for (std::size_t t = 0; t < tiling.tiles.size(); ++t)
    parts.push_back({tiling.names[t], tiling.names[t], tiltedBlock(tiling.tiles[t], tilts[t], {}, 0.0318, 10 * M_PI / 180), t != 4});
  const Bundle bundle = assembled(parts);
  const AssemblyStatics s = analysed(bundle, 0.23);
  REQUIRE_FALSE(s.interlocking.interlocked);
  REQUIRE(s.interlocking.motion.size() == 1);
  REQUIRE(s.interlocking.motion.front().translation.z() > 0.5);  // upwards
  REQUIRE(s.stability.stable);
  REQUIRE(s.stability.leastFriction == Approx(0.0));
}

TEST_CASE("rigid blocks: a box among boxes opens no contact but slides, and built unstressed no friction holds it") {
  const Bundle bundle = squareSlab(0);
  const AssemblyStatics s = analysed(bundle, 0.23);
  REQUIRE(s.interlocking.interlocked);
  REQUIRE(s.interlocking.slidingModes == 1);
  REQUIRE(s.interlocking.sliding.size() == 1);
  const BodyMotion& m = s.interlocking.sliding.front();
  REQUIRE(bundle.bodies[m.body].name == "r1c1");
  REQUIRE(std::abs(m.translation.z()) == Approx(1.0));
  REQUIRE(m.translation.head<2>().norm() < 1e-6);
  REQUIRE(m.rotation.norm() < 1e-6);
  // Rigid equilibrium holds it with any friction, by a prestress (the normal forces may grow
  // without bound). Built unstressed it gets none: sliding down presses no face, so no friction
  // holds it, as in a run, where it sinks.
  REQUIRE(*s.stability.rigidLeastFriction <= 1e-3);
  for (double mu : {0.0, 0.23, 10.0}) {
    const StabilityVerdict v = mu == 0.23 ? s.stability : analysed(bundle, mu).stability;
    INFO("friction " << mu);
    REQUIRE_FALSE(v.stable);
    if (mu == 0) continue;  // no friction: rigid equilibrium already says no
    REQUIRE(v.settled);
    REQUIRE_FALSE(v.leastFriction);
    REQUIRE(v.falling.size() == 1);
    REQUIRE(v.falling.front().translation.normalized().z() < -0.999);  // straight down
  }
}

TEST_CASE("rigid blocks: a block on a ramp stands from mu = tan(alpha), lifts off, either order") {
  const double alpha = 20 * M_PI / 180, pyramid = 1 / std::cos(M_PI / 8);
  for (bool blockFirst : {true, false}) {
    const Bundle bundle = blockOnRamp(alpha, blockFirst);
    const AssemblyStatics s = analysed(bundle, 0.5);
    INFO("block listed " << (blockFirst ? "first" : "second"));
    REQUIRE(s.pairs == 1);
    REQUIRE_FALSE(s.interlocking.interlocked);  // it can be lifted off
    REQUIRE(s.interlocking.motion.size() == 1);
    REQUIRE(s.stability.stable);
    REQUIRE(s.stability.settled);
    REQUIRE(*s.stability.leastFriction >= std::tan(alpha) * 0.99);  // unstressed, on its nodes: the cone
    REQUIRE(*s.stability.leastFriction <= std::tan(alpha) * 1.02);
    REQUIRE(*s.stability.rigidLeastFriction >= std::tan(alpha) * 0.99);  // rigid: the pyramid
    REQUIRE(*s.stability.rigidLeastFriction <= std::tan(alpha) * pyramid * 1.01);
    const AssemblyStatics below = analysed(bundle, 0.97 * std::tan(alpha));
    REQUIRE_FALSE(below.stability.stable);
    REQUIRE(below.stability.falling.size() == 1);
    REQUIRE(below.stability.falling.front().translation.normalized().dot(Eigen::Vector3d(std::cos(alpha), 0, -std::sin(alpha))) > 0.99);  // down the slope
    REQUIRE(analysed(bundle, 1.02 * std::tan(alpha)).stability.stable);
  }
}

TEST_CASE("stability: a triangle slab has a way out, and rigid equilibrium holds it at mu = 0.23 but the settling of the unstressed slab does not") {
  const Bundle bundle = assembled(generatedSlabParts(slabOptions("triangle", 5, 10)));
  const AssemblyStatics s = analysed(bundle, 0.23);
  INFO("least friction " << s.stability.leastFriction.value_or(-1) << ", rigid " << s.stability.rigidLeastFriction.value_or(-1) << ", " << s.seconds << " s");
  REQUIRE_FALSE(s.interlocking.interlocked);
  REQUIRE(s.stability.rigidLeastFriction);
  REQUIRE(*s.stability.rigidLeastFriction < 0.23);
  REQUIRE(s.stability.settled);
  REQUIRE(s.stability.nodes > 0);
  REQUIRE_FALSE(s.stability.stable);
  REQUIRE(s.stability.leastFriction);
  REQUIRE(*s.stability.leastFriction > 0.23);  // the run's: 0.5-0.69 on the 7 x 7 slab (docs/check.md)
  REQUIRE_FALSE(s.stability.falling.empty());
  // tile and assemble ask for the verdict alone: the same steps, the same answer on either side.
  const AssemblyLevelSets levelSets(bundle);
  REQUIRE_FALSE(analyseAssembly(bundle, levelSets, 0.9 * *s.stability.leastFriction, false).stability.stable);
  REQUIRE(analyseAssembly(bundle, levelSets, 1.1 * *s.stability.leastFriction, false).stability.stable);
}

TEST_CASE("stability: a square slab's sliding modes need friction once the unstressed blocks settle, not just any") {
  const Bundle bundle = assembled(generatedSlabParts(slabOptions("square", 5, 5)));
  const AssemblyStatics s = analysed(bundle, 0.23);
  INFO("least friction " << s.stability.leastFriction.value_or(-1) << ", " << s.seconds << " s");
  REQUIRE(s.interlocking.interlocked);
  REQUIRE(s.interlocking.slidingModes > 0);
  REQUIRE(*s.stability.rigidLeastFriction <= 1e-3);  // rigid: squeezed, any friction
  REQUIRE(s.stability.settled);
  REQUIRE(s.stability.stable);
  REQUIRE(s.stability.leastFriction);
  REQUIRE(*s.stability.leastFriction > 0.05);  // the 7 x 7 slab's run: from (0.10, 0.125] (docs/check.md)
  REQUIRE(*s.stability.leastFriction < 0.2);
  REQUIRE_FALSE(analysed(bundle, 0.9 * *s.stability.leastFriction).stability.stable);
  // Solvers starved of steps neither find the equilibrium nor show a fall: undecided, and then
  // rigid equilibrium decides an interlocked assembly (checkStability).
  const AssemblyLevelSets levelSets(bundle);
  const std::vector<ContactNode> nodes = contactNodes(bundle, levelSets, kTouchFraction * 0.1);
  REQUIRE(settleElastically(bundle, nodes, 0.23, true).decided);
  const ElasticSettling starved = settleElastically(bundle, nodes, 0.23, true, SettlingBudget{1, 1, 0, 1});
  REQUIRE_FALSE(starved.decided);
  REQUIRE_FALSE(starved.stands);
}
