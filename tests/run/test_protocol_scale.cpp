// The protocol's defaults are ratios (docs/scene.md, "Scale"): the paper's values on its slab, in
// proportion elsewhere.
#include "geometry/block_generators.h"
#include "run/load_point.h"
#include "run/protocol_scale.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

using namespace tessera;

TEST_CASE("settle threshold: 1e-9 of the free bodies' sum m g h, or the absolute value given") {
  const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  SolverSettings settings;
  World world(slab.shapes, slab.bodies, ContactParameters{}, settings);
  const double m = settings.density * slab.shapes[0].mass.volume;  // one free body: the centre
  ProtocolSettings protocol;
  REQUIRE(settleThreshold(world, protocol) == Approx(1e-9 * m * 9.81 * 3.18e-3).epsilon(1e-6));
  protocol.settleKinetic = 1e-12;
  REQUIRE(settleThreshold(world, protocol) == 1e-12);
}

TEST_CASE("settle time limit: the longer of a plate's period scale and a block's fall time, or the absolute value given") {
  const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  ProtocolSettings protocol;
  // The paper's span: the fall time, 2 sqrt(2 t / g) = 0.0509 s, just above the plate's 0.05 s.
  const double fall = 2 * std::sqrt(2 * 3.18e-3 / 9.81);
  REQUIRE(settleTimeLimit(World(slab.shapes, slab.bodies, ContactParameters{}, SolverSettings{}), protocol) == Approx(fall).epsilon(1e-6));
  ContactParameters wide;
  wide.spanLength *= 3;  // 9 x the period scale
  REQUIRE(settleTimeLimit(World(slab.shapes, slab.bodies, wide, SolverSettings{}), protocol) == Approx(0.45).epsilon(1e-6));
  protocol.settleMaxTime = 0.01;
  REQUIRE(settleTimeLimit(World(slab.shapes, slab.bodies, ContactParameters{}, SolverSettings{}), protocol) == 0.01);
}

TEST_CASE("indenter speed: 30 mm/s on the paper's slab, the same at any scale, as sqrt(E) and (h / L)^2") {
  const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  ContactParameters paper;  // E = 4.2 GPa, L = 50 mm
  IndenterSettings indenter;
  REQUIRE(indenterSpeed(World(slab.shapes, slab.bodies, paper, SolverSettings{}), indenter, 3.18e-3) == Approx(0.03).epsilon(1e-12));
  ContactParameters large = paper;
  large.spanLength *= 10;
  REQUIRE(indenterSpeed(World(slab.shapes, slab.bodies, large, SolverSettings{}), indenter, 31.8e-3) == Approx(0.03).epsilon(1e-12));
  ContactParameters stiff = paper;
  stiff.youngsModulus *= 4;
  REQUIRE(indenterSpeed(World(slab.shapes, slab.bodies, stiff, SolverSettings{}), indenter, 3.18e-3) == Approx(0.06).epsilon(1e-12));
  ContactParameters wide = paper;
  wide.spanLength *= 2;
  REQUIRE(indenterSpeed(World(slab.shapes, slab.bodies, wide, SolverSettings{}), indenter, 3.18e-3) == Approx(0.0075).epsilon(1e-12));
  indenter.speed = 0.006;
  REQUIRE(indenterSpeed(World(slab.shapes, slab.bodies, paper, SolverSettings{}), indenter, 3.18e-3) == 0.006);
}

TEST_CASE("loading anywhere: the central body by default, a point on the upper surface, a target with an offset") {
  const Bundle slab = test::smallSlab(5, 0.25e-3, 0.6e-3);
  const auto index = [&](const std::string& name) {
    for (std::size_t i = 0; i < slab.bodies.size(); ++i)
      if (slab.bodies[i].name == name) return static_cast<int>(i);
    return -1;
  };
  IndenterSettings indenter;
  REQUIRE(chooseLoadPoint(slab, indenter).body == index("r2c2"));
  // A point 2 mm off the centre of block r1c2 (row 1, column 2: at (0, -10) mm).
  indenter.atPoint = true;
  indenter.point = Eigen::Vector2d(2e-3, -10e-3 + 1e-3);
  const LoadPoint atPoint = chooseLoadPoint(slab, indenter);
  REQUIRE(atPoint.body == index("r1c2"));
  REQUIRE((slab.bodies[atPoint.body].position.head<2>() + atPoint.offset - indenter.point).norm() < 1e-15);
  indenter.point = Eigen::Vector2d(-20e-3, 0);  // the fixed ring
  REQUIRE_THROWS_WITH(chooseLoadPoint(slab, indenter), Catch::Contains("fixed body 'r2c0'"));
  indenter.point = Eigen::Vector2d(0.2, 0);
  REQUIRE_THROWS_WITH(chooseLoadPoint(slab, indenter), Catch::Contains("lies on no body"));
  // A target and an offset in plan.
  indenter.atPoint = false;
  indenter.target = "r3c1";
  indenter.offset = Eigen::Vector2d(1e-3, 2e-3);
  const LoadPoint offset = chooseLoadPoint(slab, indenter);
  REQUIRE(offset.body == index("r3c1"));
  REQUIRE(offset.offset == indenter.offset);
  indenter.offset = Eigen::Vector2d(8e-3, 0);
  REQUIRE_THROWS_WITH(chooseLoadPoint(slab, indenter), Catch::Contains("off the body 'r3c1'"));
  indenter.offset.setZero();
  indenter.target = "r0c0";
  REQUIRE_THROWS_WITH(chooseLoadPoint(slab, indenter), Catch::Contains("is a fixed body"));
}

TEST_CASE("the indenter's first contact with a tilted surface: R / cos(tilt) above the surface on its axis, far below the top") {
  // Nodes 0.01 R apart on a plane tilted 30 degrees about y, z = x tan 30, over a block 4 R wide
  // (its top 2 R tan 30 = 1.15 R above the axis point). A sphere coming down the z axis first
  // touches the plane with its centre R / cos 30 above it (continuous plane; nodes: from below).
  const double R = 2.5e-3, tilt = 30 * M_PI / 180;
  SurfaceNodes nodes;
  for (int i = -200; i <= 200; ++i)
    for (int j = -200; j <= 200; ++j) {
      const double x = 0.01 * R * i, y = 0.01 * R * j;
      nodes.positions.emplace_back(x, y, x * std::tan(tilt));
    }
  const Eigen::Quaterniond identity = Eigen::Quaterniond::Identity();
  const std::optional<double> h = sphereTouchHeight(nodes, identity, Eigen::Vector3d::Zero(), Eigen::Vector2d::Zero(), R);
  REQUIRE(h.has_value());
  REQUIRE(*h <= R / std::cos(tilt));
  REQUIRE(*h == Approx(R / std::cos(tilt)).epsilon(1e-4));
  // Posed: the same nodes raised by 1 mm and turned about z, at another axis point.
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  const std::optional<double> posed =
      sphereTouchHeight(nodes, turn, Eigen::Vector3d(0.1, 0.2, 1e-3), Eigen::Vector2d(0.1, 0.2), R);
  REQUIRE(*posed == Approx(*h + 1e-3).epsilon(1e-9));
  // No node within R of the axis: nothing.
  REQUIRE_FALSE(sphereTouchHeight(nodes, identity, Eigen::Vector3d::Zero(), Eigen::Vector2d(1.0, 0), R).has_value());
}

TEST_CASE("the loaded block's thickness: its extent on the vertical through the load point, t / cos(tilt) on a tilted block") {
  // A 10 x 10 x 3 mm box tilted 30 degrees about y: 3 / cos 30 = 3.46 mm through its centre, while
  // its z-extent is 10 sin 30 + 3 cos 30 = 7.60 mm (what h was: K's window, R and delta_max from it).
  const TriangleMesh box = makeBox(10e-3, 10e-3, 3e-3);
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(30 * M_PI / 180, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d at(0.02, -0.01, 0.5);
  REQUIRE(loadedThickness(box, tilt, at, at.head<2>()) == Approx(3e-3 / std::cos(30 * M_PI / 180)).epsilon(1e-12));
  const auto [bottom, top] = heightRange(box, tilt, at);
  REQUIRE(top - bottom == Approx(10e-3 * 0.5 + 3e-3 * std::cos(30 * M_PI / 180)).epsilon(1e-12));
  // Level: the same as the z-extent; off the block: the z-extent.
  const Eigen::Quaterniond level = Eigen::Quaterniond::Identity();
  REQUIRE(loadedThickness(box, level, at, at.head<2>() + Eigen::Vector2d(1e-3, 2e-3)) == Approx(3e-3).epsilon(1e-12));
  REQUIRE(loadedThickness(box, tilt, at, at.head<2>() + Eigen::Vector2d(1.0, 0)) == Approx(top - bottom).epsilon(1e-12));
}
