// A pair's contact does not depend on which body is `a`: the same two bodies evaluated as (a, b)
// and as (b, a) give the same force and torque on each, the same node contacts and energy.
#include "geometry/block_generators.h"
#include "solver/world.h"
#include "solver/world_internals.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tessera;

namespace {

const double kA = 10e-3, kH = 3.18e-3;

// The upper block pressed into the lower one off-centre and tilted, so that both sides' nodes
// (a's in b and b's in a) touch; one step evaluated. `upper` is 1, or 0 with the free body first.
const PairContacts& pressedPair(World& world, int upper) {
  const RigidBodies& b = world.bodies();
  world.setPose(upper, b.position[upper] + Eigen::Vector3d(0.7e-3, -0.4e-3, -0.03e-3),
                Eigen::Quaterniond(Eigen::AngleAxisd(0.004, Eigen::Vector3d(1, 0.3, 0).normalized())) * b.orientation[upper]);
  world.setVelocity(upper, b.velocity[upper], Eigen::Vector3d(2e-9, -1e-9, 3e-9));
  world.step();
  for (const PairContacts& p : WorldInternals::pairs(world))
    if (p.b >= 0) return p;
  FAIL("no body pair");
  return WorldInternals::pairs(world).front();
}

}  // namespace

TEST_CASE("pair symmetry: (a, b) and (b, a) give the same forces, torques and contacts, grid and exact planes") {
  // The TIS block on a box: inclined faces against a flat one, a non-symmetric contact.
  const TriangleMesh lower = makeBox(kA, kA, kH);
  const TriangleMesh upper = makePlanarBlock(kA, kH, 5.0 * M_PI / 180);
  for (bool exact : {true, false}) {
    INFO((exact ? "exact planes" : "grid level sets"));
    SolverSettings s;
    s.exactConvexLevelSets = exact;
    s.threads = 1;
    ContactParameters p;
    p.friction = 0.3;
    const Bundle built = test::stackedBlocks(lower, upper, 0.25e-3, 0.6e-3, false), flipped = test::stackedBlocks(lower, upper, 0.25e-3, 0.6e-3, true);
    World asBuilt(built.shapes, built.bodies, p, s);        // pair (lower, upper)
    World swapped(flipped.shapes, flipped.bodies, p, s);    // pair (upper, lower)
    const PairContacts& one = pressedPair(asBuilt, 1);
    const PairContacts& two = pressedPair(swapped, 0);
    REQUIRE(one.a == 0);
    REQUIRE(two.a == 0);
    // Both sides touch: keys of side 0 and side 1 in each.
    const auto sides = [](const PairContacts& q) {
      int s0 = 0, s1 = 0;
      for (const NodeContact& c : q.contacts) (c.key >> 31 ? s1 : s0)++;
      return std::pair<int, int>{s0, s1};
    };
    REQUIRE(sides(one).first > 0);
    REQUIRE(sides(one).second > 0);
    REQUIRE(sides(one).first == sides(two).second);
    REQUIRE(sides(one).second == sides(two).first);

    const double scale = one.forceA.norm();
    REQUIRE(scale > 0);
    // The same to the law's rounding: it runs in ContactReal (float, relative 6e-8 a contact), and
    // the two orders see each contact's inputs computed from other levers (about 1e-9 of the
    // force and 2e-8 of the torque measured here).
    const double rounding = 1e-6;
    // On the upper block: forceB of the first, forceA of the second.
    CHECK((one.forceB - two.forceA).norm() <= rounding * scale);
    CHECK((one.forceA - two.forceB).norm() <= rounding * scale);
    const double torqueScale = std::max(one.torqueA.norm(), one.torqueB.norm());
    CHECK((one.torqueB - two.torqueA).norm() <= rounding * torqueScale);
    CHECK((one.torqueA - two.torqueB).norm() <= rounding * torqueScale);
    CHECK(one.tally.elastic == Approx(two.tally.elastic).epsilon(rounding));
    CHECK(one.tally.sliding == two.tally.sliding);
    CHECK((one.forcePoint - two.forcePoint).norm() <= rounding * kA);
  }
}

TEST_CASE("one-way evaluation: only the smaller block's nodes, whole areas, whichever block is a (issue #38)") {
  // A 6 mm box on the 10 mm TIS block: the box's nodes in the block's level set, in either order.
  const TriangleMesh lower = makePlanarBlock(kA, kH, 5.0 * M_PI / 180);
  const TriangleMesh upper = makeBox(0.6 * kA, 0.6 * kA, kH);
  SolverSettings s;
  s.threads = 1;
  ContactParameters p;
  p.friction = 0.3;
  p.evaluation = ContactEvaluation::OneWay;
  const Bundle built = test::stackedBlocks(lower, upper, 0.25e-3, 0.6e-3, false), flipped = test::stackedBlocks(lower, upper, 0.25e-3, 0.6e-3, true);
  World asBuilt(built.shapes, built.bodies, p, s);        // pair (lower, upper)
  World swapped(flipped.shapes, flipped.bodies, p, s);    // pair (upper, lower)
  const PairContacts& one = pressedPair(asBuilt, 1);
  const PairContacts& two = pressedPair(swapped, 0);
  REQUIRE_FALSE(one.contacts.empty());
  for (const NodeContact& c : one.contacts) REQUIRE(c.key >> 31 == 1);  // b's (the box's) nodes only
  for (const NodeContact& c : two.contacts) REQUIRE(c.key >> 31 == 0);  // a's (the box's) nodes only
  REQUIRE(one.contacts.size() == two.contacts.size());
  const double scale = one.forceA.norm(), rounding = 1e-6;
  CHECK((one.forceB - two.forceA).norm() <= rounding * scale);
  CHECK((one.forceA - two.forceB).norm() <= rounding * scale);
  CHECK((one.forceA + one.forceB).norm() <= rounding * scale);  // Newton's third law within the pair
  CHECK(one.tally.elastic == Approx(two.tally.elastic).epsilon(rounding));
  // Whole areas: the box's nodes carry their areas once, where two-way gives each side half.
  double area = 0;
  for (const NodeContact& c : one.contacts) area += c.area;
  CHECK(area == Approx(0.36 * kA * kA).epsilon(0.05));
}

TEST_CASE("viscous damping: a free spinning, moving block slows as exp(-c t), and the balance books the loss") {
  // Far from everything and without gravity: F = -c m v and tau = -c I omega alone.
  Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  bundle.bodies[1].position.z() += 1.0;  // a metre above the fixed block
  SolverSettings s;
  s.gravity = Eigen::Vector3d::Zero();
  s.viscousDamping = 40.0;  // 1/s
  World world(bundle.shapes, bundle.bodies, ContactParameters{}, s);
  const RigidBodies& b = world.bodies();
  world.setVelocity(1, Eigen::Vector3d(0.01, -0.02, 0.005), b.inertia[1].cwiseProduct(Eigen::Vector3d(0, 0, 3.0)));  // about a principal axis
  const double v0 = b.velocity[1].norm(), w0 = b.angularVelocity(1).norm(), e0 = b.kineticEnergy(1);
  const int steps = static_cast<int>(0.02 / world.timeStep());
  for (int i = 0; i < steps; ++i) world.step();
  const double t = steps * world.timeStep(), decay = std::exp(-s.viscousDamping * t);
  REQUIRE(b.velocity[1].norm() == Approx(v0 * decay).epsilon(1e-3));
  REQUIRE(b.angularVelocity(1).norm() == Approx(w0 * decay).epsilon(1e-3));
  const EnergyBudget e = world.energy();
  REQUIRE(e.damping == Approx(e0 - b.kineticEnergy(1)).epsilon(1e-3));
  REQUIRE(std::abs(e.residual()) < 1e-3 * e0);
}
