// The protocol's defaults are ratios (docs/scene.md, "Scale"): the paper's values on its slab, in
// proportion elsewhere.
#include "solver/indentation.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

using namespace tessera;

TEST_CASE("settle threshold: 1e-9 of the free bodies' sum m g h, or the absolute value given") {
  const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  SolverSettings settings;
  World world(slab, ContactParameters{}, settings);
  const double m = settings.density * slab.shapes[0].mass.volume;  // one free body: the centre
  ProtocolSettings protocol;
  REQUIRE(settleThreshold(world, protocol) == Approx(1e-9 * m * 9.81 * 3.18e-3).epsilon(1e-6));
  protocol.settleKinetic = 1e-12;
  REQUIRE(settleThreshold(world, protocol) == 1e-12);
}

TEST_CASE("indenter speed: 30 mm/s on the paper's slab, the same at any scale, as sqrt(E) and (h / L)^2") {
  const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  ContactParameters paper;  // E = 4.2 GPa, L = 50 mm
  IndenterSettings indenter;
  REQUIRE(indenterSpeed(World(slab, paper, SolverSettings{}), indenter, 3.18e-3) == Approx(0.03).epsilon(1e-12));
  ContactParameters large = paper;
  large.spanLength *= 10;
  REQUIRE(indenterSpeed(World(slab, large, SolverSettings{}), indenter, 31.8e-3) == Approx(0.03).epsilon(1e-12));
  ContactParameters stiff = paper;
  stiff.youngsModulus *= 4;
  REQUIRE(indenterSpeed(World(slab, stiff, SolverSettings{}), indenter, 3.18e-3) == Approx(0.06).epsilon(1e-12));
  ContactParameters wide = paper;
  wide.spanLength *= 2;
  REQUIRE(indenterSpeed(World(slab, wide, SolverSettings{}), indenter, 3.18e-3) == Approx(0.0075).epsilon(1e-12));
  indenter.speed = 0.006;
  REQUIRE(indenterSpeed(World(slab, paper, SolverSettings{}), indenter, 3.18e-3) == 0.006);
}
