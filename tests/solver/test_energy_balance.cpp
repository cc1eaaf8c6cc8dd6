// The energy balance: what the indenter and gravity put in equals what is stored (kinetic,
// elastic), dissipated (friction, damping) and carried off, to the integrator's error.
#include "geometry/block_generators.h"
#include "solver/world.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>

using namespace tessera;

namespace {
const double kA = 10e-3, kH = 3.18e-3;
}  // namespace

TEST_CASE("energy: a block sliding to rest on a fixed block dissipates its kinetic energy as mu m g s") {
  ContactParameters p;
  p.friction = 0.3;
  const Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  SolverSettings s;  // no damping
  World world(bundle.shapes, bundle.bodies, p, s);
  const double v0 = 0.02;  // m/s along x, from the start (the initial energy counts it)
  world.setVelocity(1, Eigen::Vector3d(v0, 0, 0), Eigen::Vector3d::Zero());
  const double x0 = world.bodies().position[1].x(), m = world.bodies().mass[1];
  for (int i = 0; i < 200000 && world.bodies().velocity[1].x() > 1e-6 * v0; ++i) world.step();
  const EnergyBudget after = world.energy();
  const double slid = world.bodies().position[1].x() - x0;
  const double friction = after.friction;
  INFO("slid " << slid * 1e6 << " um; friction " << friction << " J; mu m g s " << p.friction * m * 9.81 * slid
               << " J; initial kinetic " << 0.5 * m * v0 * v0 << " J; residual " << after.residual());
  // Sliding at constant deceleration mu g: s = v0^2 / (2 mu g).
  REQUIRE(slid == Approx(v0 * v0 / (2 * p.friction * 9.81)).epsilon(0.02));
  REQUIRE(friction == Approx(p.friction * m * 9.81 * slid).epsilon(0.02));
  REQUIRE(friction == Approx(0.5 * m * v0 * v0).epsilon(0.02));
  REQUIRE(std::abs(after.residual()) < 0.01 * after.initial);
}

TEST_CASE("energy: an indenter pressing a block onto a fixed block stores its work elastically") {
  for (double friction : {0.0, 0.5}) {
    ContactParameters p;
    p.friction = friction;
    const Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
    SolverSettings s;
    s.localDamping = 0.3;
    World world(bundle.shapes, bundle.bodies, p, s);
    SphereObstacle indenter;
    indenter.radius = 2.5e-3;
    indenter.center = world.bodies().position[1] + Eigen::Vector3d(1e-3, 0.5e-3, 0.5 * kH + indenter.radius);
    indenter.velocity = Eigen::Vector3d(0, 0, -0.01);
    world.addSphere(indenter);
    while (world.sphere(0).center.z() - indenter.center.z() > -0.2e-3) world.step();
    const EnergyBudget e = world.energy();
    INFO("mu " << friction << ": work " << e.externalWork << " J, elastic " << e.elastic << ", friction " << e.friction
               << ", damping " << e.damping << ", residual " << e.residual());
    REQUIRE(e.externalWork > 0);
    CHECK(std::abs(e.residual()) < 0.01 * e.externalWork);
  }
}


TEST_CASE("energy: indenting a 3 x 3 slab balances to 1 % of the work, with and without friction, either contact area") {
  const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  for (const ContactArea area : {ContactArea::Blended, ContactArea::Nearest})
    for (double friction : {0.0, 0.23}) {
      ContactParameters p;
      p.friction = friction;
      p.area = area;
      SolverSettings s;
      s.localDamping = 0.3;
      World world(slab.shapes, slab.bodies, p, s);
      for (int i = 0; i < 1400; ++i) world.step();
      SphereObstacle indenter;
      indenter.center = world.bodies().position[4] + Eigen::Vector3d(0, 0, 0.5 * kH + indenter.radius);
      indenter.velocity = Eigen::Vector3d(0, 0, -0.03);
      world.addSphere(indenter);
      while (world.sphere(0).center.z() - indenter.center.z() > -0.8e-3) world.step();
      const EnergyBudget e = world.energy();
      INFO((area == ContactArea::Blended ? "blended" : "nearest")
           << " mu " << friction << ": work " << e.externalWork << " J, elastic " << e.elastic << ", friction " << e.friction
           << ", damping " << e.damping << ", projection " << e.projection << ", residual " << e.residual());
      REQUIRE(e.damping > 0);
      REQUIRE((friction > 0) == (e.friction > 0));
      // Without friction, the wedged centre block's nodes cross its neighbours' edges with stored
      // energy: the nearest face's area loses it there (the projection term, about 8 % of the
      // work); the blended area's potential does that work (what is left: the indenter's area).
      if (friction == 0 && area == ContactArea::Nearest) REQUIRE(e.projection > 0.02 * e.externalWork);
      if (friction == 0 && area == ContactArea::Blended) REQUIRE(std::abs(e.projection) < 0.002 * e.externalWork);
      REQUIRE(std::abs(e.residual()) < 0.01 * e.externalWork);
    }
}

TEST_CASE("energy: local damping and normal viscosity dissipate what the balance books") {
  const Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  for (int model = 0; model < 2; ++model) {
    ContactParameters p;
    SolverSettings s;
    // Small steps: a bounce's contact entry costs O((omega dt)^2) of energy on its own (see the
    // bounce test), and the viscous term is booked from the half-step velocity, O(omega dt).
    s.timeStepFactor = 0.05;
    if (model == 0) s.localDamping = 0.5;
    else p.normalViscosity = 2e5;  // Pa s / m
    auto b = bundle;
    b.bodies[1].position.z() += 20e-6;  // dropped from 20 um
    World world(b.shapes, b.bodies, p, s);
    for (int i = 0; i < 20000; ++i) world.step();
    const EnergyBudget e = world.energy();
    INFO((model == 0 ? "local" : "viscous") << ": gravity work " << e.gravityWork << " J, damping " << e.damping
                                            << ", kinetic " << e.kinetic << ", residual " << e.residual());
    REQUIRE(e.damping > 0.2 * e.gravityWork);  // the bounces went into damping
    REQUIRE(std::abs(e.residual()) < 0.01 * e.gravityWork);
  }
}
