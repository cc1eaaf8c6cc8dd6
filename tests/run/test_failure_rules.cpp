// Fallen, retired and pushed-through bodies (run/assembly_state.h): judged from contacts, never
// from a displacement alone.
#include "geometry/block_generators.h"
#include "run/assembly_state.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

using namespace tessera;

namespace {
const double kA = 10e-3, kH = 3.18e-3;

// A free block resting on a fixed one, its contacts evaluated (one step).
struct Stack {
  Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  World world{bundle.shapes, bundle.bodies, ContactParameters{}, SolverSettings{}};
  std::vector<Eigen::Vector3d> settled;
  Stack() {
    for (int i = 0; i < 200; ++i) world.step();  // rests on the base, in contact
    settled = world.bodies().position;
  }
};
}  // namespace

TEST_CASE("failure rules: a block sunk by more than its thickness but touching a support is neither fallen nor retired") {
  Stack s;
  // As if the slab had settled one and a half thicknesses higher: the block has "sunk" 1.5 h.
  std::vector<Eigen::Vector3d> high = s.settled;
  high[1].z() += 1.5 * kH;
  const auto touching = touchingBlocks(s.world), supported = supportedBodies(s.world);
  REQUIRE(touching[1]);
  REQUIRE(supported[1]);
  REQUIRE(supported[0]);  // the fixed base is a support
  const FallenRule rule;
  REQUIRE_FALSE(hasFallen(s.world, 1, supported, high[1], rule));
  REQUIRE_FALSE(canRetire(s.world, 1, touching, supported, high[1], rule));
}

TEST_CASE("failure rules: a block that lost every block contact falls, and is retired only once clear of the assembly") {
  Stack s;
  const FallenRule rule;
  // Lift it off by half the clearance: no contact, dropped from a higher "settled" place, but still
  // within clearance x h of the base: fallen, not yet retired.
  s.world.setPose(1, s.world.bodies().position[1] + Eigen::Vector3d(0, 0, 0.5 * rule.clearance * kH), s.world.bodies().orientation[1]);
  std::vector<Eigen::Vector3d> high = s.settled;
  high[1].z() += kH;
  s.world.step();
  auto touching = touchingBlocks(s.world), supported = supportedBodies(s.world);
  REQUIRE_FALSE(touching[1]);
  REQUIRE_FALSE(supported[1]);
  REQUIRE(hasFallen(s.world, 1, supported, high[1], rule));
  REQUIRE_FALSE(canRetire(s.world, 1, touching, supported, high[1], rule));
  // Without the drop it has not fallen (it was lifted, not fallen).
  REQUIRE_FALSE(hasFallen(s.world, 1, supported, s.world.bodies().position[1], rule));
  // Far to the side: clear of every box, retired; retiring books its kinetic energy.
  s.world.setPose(1, s.world.bodies().position[1] + Eigen::Vector3d(2 * kA, 0, 0), s.world.bodies().orientation[1]);
  s.world.setVelocity(1, Eigen::Vector3d(0, 0, -0.1), Eigen::Vector3d::Zero());
  s.world.step();
  touching = touchingBlocks(s.world);
  supported = supportedBodies(s.world);
  REQUIRE(canRetire(s.world, 1, touching, supported, high[1], rule));
  const double kinetic = s.world.bodies().kineticEnergy(1);
  const double before = s.world.energy().residual();
  s.world.retireBody(1);
  REQUIRE(s.world.energy().retiredKinetic == Approx(kinetic));
  REQUIRE(s.world.energy().residual() == Approx(before).margin(1e-12));
  REQUIRE(s.world.isRetired(1));
  REQUIRE_FALSE(s.world.isSupport(1));
}

TEST_CASE("failure rules: support runs through chains of contacts, and a block pushed past its neighbours by h is out") {
  const Bundle slab = test::smallSlab(3, 0.25e-3, 1.0e-3);
  SolverSettings settings;
  settings.localDamping = 0.3;
  World world(slab.shapes, slab.bodies, ContactParameters{}, settings);
  for (int i = 0; i < 1000; ++i) world.step();
  const auto supported = supportedBodies(world);
  for (std::size_t i = 0; i < supported.size(); ++i) REQUIRE(supported[i]);
  const int centre = 4;
  const std::vector<Eigen::Vector3d> settled = world.bodies().position;
  REQUIRE_FALSE(pushedThroughBodies(world, settled)[centre]);
  // The same contacts with the centre's settled place 1.2 h higher: it has moved past its
  // neighbours by more than its thickness while still touching them.
  std::vector<Eigen::Vector3d> higher = settled;
  higher[centre].z() += 1.2 * kH;
  REQUIRE(touchingBlocks(world)[centre]);
  REQUIRE(pushedThroughBodies(world, higher)[centre]);
  // A dished slab: every body "sank" together by 1.2 h: not pushed through.
  for (auto& p : higher) p.z() = p.z() + (&p == &higher[centre] ? 0.0 : 1.2 * kH);
  REQUIRE_FALSE(pushedThroughBodies(world, higher)[centre]);
}
