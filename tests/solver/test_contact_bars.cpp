// The bar and section rules of contact stiffness (solver/contact_bars.h, docs/physics.md "Contact
// stiffness"): their lengths against hand-computed bars and a bar's series compliance, equality
// with E M / L over a row of blocks, symmetry in a and b, pose and scale, and the equilibrium they
// give a block resting on a support.
#include "geometry/block_generators.h"
#include "solver/contact_bars.h"
#include "solver/world.h"
#include "solver/world_internals.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tessera;

namespace {

const double kA = 10e-3, kH = 3.18e-3;

// A row of n boxes a x a x h along x, centroids a apart, the two end ones fixed.
ContactBars row(int n, double a, double h) {
  std::vector<Eigen::Vector3d> position;
  std::vector<char> fixed;
  for (int i = 0; i < n; ++i) {
    position.emplace_back(i * a, 0.0, 0.0);
    fixed.push_back(i == 0 || i == n - 1);
  }
  return ContactBars({makeBox(a, a, h)}, std::vector<int>(n, 0), position,
                     std::vector<Eigen::Quaterniond>(n, Eigen::Quaterniond::Identity()), fixed);
}

}  // namespace

TEST_CASE("bar rule: half a block's width each side, none for a support, and a row as compliant as E M / L says") {
  for (int n : {3, 5, 7, 31}) {
    INFO("row of " << n);
    const ContactBars bars = row(n, kA, kH);
    REQUIRE(bars.betweenBodies(0, 1) == Approx(kA / 2).epsilon(1e-12));      // against a support: a/2
    REQUIRE(bars.betweenBodies(n - 1, n - 2) == Approx(kA / 2).epsilon(1e-12));
    if (n > 3) REQUIRE(bars.betweenBodies(1, 2) == Approx(kA).epsilon(1e-12));  // between free blocks: a
    // The row's compliance: sum over its M = n - 1 contacts of 1 / k = (w_a + w_b) / E, against the
    // paper's M contacts of 1 / (E M / L), L = (n - 2) a the free span.
    double bars_sum = 0;
    for (int i = 0; i + 1 < n; ++i) bars_sum += bars.betweenBodies(i, i + 1);
    const double span = (n - 2) * kA;
    REQUIRE(bars_sum == Approx(span).epsilon(1e-12));
    // The shortest bar of a flat block is half its thickness, which is also its bar to the indenter.
    REQUIRE(bars.shortest(1) == Approx(kH / 2).epsilon(1e-12));
    REQUIRE(bars.againstObstacle(1, Eigen::Vector3d::UnitZ()) == Approx(kH / 2).epsilon(1e-12));
  }
}

TEST_CASE("bar rule: the shortest bar is the distance to the nearest face plane, h/2 for a flat block, (a/2) cos(theta) for a steep one") {
  // The paper's block (faces at 5 deg, 3.18 mm thick) and a near-tetrahedron of the same family
  // (faces at 35.26 deg, 13.5 mm thick: its side planes are nearer than its top).
  const double steep = 35.26 * M_PI / 180;
  const ContactBars bars({makePlanarBlock(kA, kH, 5 * M_PI / 180), makePlanarBlock(kA, 13.5e-3, steep)}, {0, 1},
                         {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 0.1)},
                         {Eigen::Quaterniond::Identity(), Eigen::Quaterniond::Identity()}, {0, 0});
  REQUIRE(bars.shortest(0) == Approx(kH / 2).epsilon(1e-9));
  REQUIRE(bars.shortest(1) == Approx(kA / 2 * std::cos(steep)).epsilon(1e-9));
}

TEST_CASE("bar rule: symmetric in a and b, split by the bodies' extents, and proportional to the geometry's scale") {
  // A box on top of a box twice as tall, both free, turned about z: bars h and h/2 along z,
  // centroids 1.5 h apart, split 2:1.
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  for (double scale : {1e-3, 1.0, 1e3}) {
    INFO("scale " << scale);
    const double h = kH * scale;
    const ContactBars bars({makeBox(kA * scale, kA * scale, 2 * h), makeBox(kA * scale, kA * scale, h)},
                           {0, 1}, {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1.5 * h)}, {turn, turn}, {0, 0});
    REQUIRE(bars.betweenBodies(0, 1) == Approx(1.5 * h).epsilon(1e-12));
    REQUIRE(bars.betweenBodies(1, 0) == bars.betweenBodies(0, 1));
    const ContactBars lowerFixed({makeBox(kA * scale, kA * scale, 2 * h), makeBox(kA * scale, kA * scale, h)},
                                {0, 1}, {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1.5 * h)}, {turn, turn}, {1, 0});
    REQUIRE(lowerFixed.betweenBodies(0, 1) == Approx(0.5 * h).epsilon(1e-12));  // the upper box's share: 1/3
    REQUIRE(lowerFixed.betweenBodies(1, 0) == lowerFixed.betweenBodies(0, 1));
  }
}

TEST_CASE("bar rule: a block resting on a support settles at m g w / (E A) with w its bar, and at m g / (k_n A) under the span rule") {
  // Boxes of thickness t on a fixed box of thickness kH: centroids (t + kH) / 2 apart, the free
  // box's share t / (t + kH), so w = t / 2, whatever the support's thickness.
  ContactParameters p;
  p.youngsModulus = 4.2e6;  // soft: a penetration large against float32 grid round-off
  p.stiffnessRule = GENERATE(StiffnessRule::Span, StiffnessRule::Bars, StiffnessRule::Sections);  // a box's sections: its bars
  SolverSettings s;
  s.localDamping = 0.7;
  for (double t : {kH, 2 * kH}) {
    INFO("thickness " << t << ", rule " << stiffnessRuleName(p.stiffnessRule));
    const Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, t), 0.25e-3, 0.6e-3);
    World world(bundle.shapes, bundle.bodies, p, s);
    const double z0 = world.bodies().position[1].z();
    for (int step = 0; step < 4000; ++step) world.step();
    const double mg = world.bodies().mass[1] * 9.81;
    REQUIRE(world.contactForces()[1].z() == Approx(mg).epsilon(1e-3));
    const double kn = p.stiffnessRule != StiffnessRule::Span ? p.youngsModulus / (t / 2) : p.normalStiffness();
    REQUIRE(z0 - world.bodies().position[1].z() == Approx(mg / (kn * kA * kA)).epsilon(0.02));
    REQUIRE(WorldInternals::pairs(world).size() == 1);
    REQUIRE(WorldInternals::normalStiffness(world, WorldInternals::pairs(world)[0]) == Approx(kn).epsilon(1e-9));
  }
}

TEST_CASE("bar rule on the paper's slab: E / a between free blocks, 2 E / a against a support, E / (h / 2) under the indenter") {
  ContactParameters p;
  p.stiffnessRule = StiffnessRule::Bars;
  p.spanLength = 30e-3;
  p.spanInterfaces = 4;
  const Bundle slab = test::smallSlab(5, 0.5e-3, 1.2e-3);
  World world(slab.shapes, slab.bodies, p, SolverSettings{});
  SphereObstacle indenter;
  indenter.center = world.bodies().position[12] + Eigen::Vector3d(0, 0, kH / 2 + 2.4e-3);  // 0.1 mm into its top
  indenter.radius = 2.5e-3;
  indenter.stiffnessFactor = 2.0;
  world.addSphere(indenter);
  world.step();
  int between = 0, against = 0, sphere = 0;
  for (const PairContacts& pair : WorldInternals::pairs(world)) {
    const double k = WorldInternals::normalStiffness(world, pair);
    if (pair.b < 0) {
      REQUIRE(k == Approx(2.0 * p.youngsModulus / (kH / 2)).epsilon(1e-6));  // the indenter's factor counts
      ++sphere;
      continue;
    }
    const double d = (world.bodies().position[pair.a] - world.bodies().position[pair.b]).norm();
    if (d > 1.01 * kA) continue;  // diagonal neighbours
    const bool support = world.isSupport(pair.a) || world.isSupport(pair.b);
    REQUIRE(k == Approx(p.youngsModulus / (support ? kA / 2 : kA)).epsilon(1e-6));
    ++(support ? against : between);
  }
  REQUIRE(between == 12);  // the 3 x 3 free blocks' 12 shared faces
  REQUIRE(against == 12);  // and their 12 faces against the ring
  REQUIRE(sphere == 1);
}

TEST_CASE("section rule: a box's bars are the bar rule's, a hexagonal block's ln 2 of them (its section doubles from a face to its centre), in any pose and at any scale") {
  // Between two hexagonal prisms of apothem r side by side (centroids 2 r apart along a face
  // normal), each bar is r int_0^1 du / (2 - u) = r ln 2: the section across the face normal
  // is 2 s - s y / r at y from the centre. The midpoint rule's error: below 1e-4.
  const Eigen::Quaterniond pose(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()));
  for (double scale : {1e-3, 1.0, 1e3}) {
    INFO("scale " << scale);
    const double r = 5e-3 * scale, h = kH * scale, a = kA * scale;
    const Eigen::Vector3d across = pose * Eigen::Vector3d::UnitX();
    const std::vector<Eigen::Quaterniond> poses(2, pose);
    const ContactBars hexes({makeHexBlock(r, h, 0.0)}, {0, 0}, {Eigen::Vector3d::Zero(), 2 * r * across}, poses, {0, 0}, true);
    REQUIRE(hexes.betweenBodies(0, 1) == Approx(2 * r * std::log(2.0)).epsilon(1e-4));
    REQUIRE(hexes.betweenBodies(1, 0) == hexes.betweenBodies(0, 1));
    REQUIRE(hexes.againstObstacle(0, -across) == Approx(r * std::log(2.0)).epsilon(1e-4));
    REQUIRE(hexes.againstObstacle(0, pose * Eigen::Vector3d::UnitZ()) == Approx(h / 2).epsilon(1e-12));  // a prism along z
    // The time step's bound: the shortest bar times the least factor over the faces' normals.
    REQUIRE(hexes.shortest(0) == Approx(std::min(r, h / 2) * std::log(2.0)).epsilon(1e-4));
    const ContactBars boxes({makeBox(a, a, h)}, {0, 0}, {Eigen::Vector3d::Zero(), a * across}, poses, {0, 0}, true);
    REQUIRE(boxes.betweenBodies(0, 1) == Approx(a).epsilon(1e-12));
    REQUIRE(boxes.shortest(0) == Approx(h / 2).epsilon(1e-12));
  }
}

TEST_CASE("section rule: a block is softer than its bar towards a face wider than its inside, stiffer towards one narrower, by its sections' series compliance") {
  // A square frustum along z, side b at z = -c narrowing to b / 2 at z = +c: its side at z is
  // b (1 - u), u = (z + c) / (4 c), and its centroid at z_c (u_0 there). The bar's compliance
  // int dz / (b (1 - u))^2 = (4 c / b^2) [1 / (1 - u)] between the ends gives
  //   towards the wide face (-z, s = z_c + c = 4 c u_0):  f = 1 / (1 - u_0)                 > 1
  //   towards the narrow face (+z, s = c - z_c):          f = (c / s) (2 - 1 / (1 - u_0))   < 1
  // against which the midpoint rule's 32 slices are held.
  const double b = 10e-3, c = 2e-3;
  TriangleMesh frustum;
  for (double z : {-c, c}) {
    const double half = (z < 0 ? b : b / 2) / 2;
    for (auto [x, y] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) frustum.vertices.emplace_back(x * half, y * half, z);
  }
  frustum.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                       {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  double volume = 0, moment = 0;  // z_c = int z A dz / int A dz
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double z = -c + (i + 0.5) * 2 * c / n, side = b * (1 - (z + c) / (4 * c));
    volume += side * side;
    moment += z * side * side;
  }
  const double zc = moment / volume, u0 = (zc + c) / (4 * c);
  for (Eigen::Vector3d& v : frustum.vertices) v.z() -= zc;  // the body frame: centroid at the origin
  const ContactBars bars({frustum}, {0}, {Eigen::Vector3d::Zero()}, {Eigen::Quaterniond::Identity()}, {0}, true);
  const double wide = 1 / (1 - u0), narrow = c / (c - zc) * (2 - 1 / (1 - u0));
  REQUIRE(wide > 1);
  REQUIRE(narrow < 1);
  REQUIRE(bars.sectionFactor(0, -Eigen::Vector3d::UnitZ()) == Approx(wide).epsilon(1e-3));
  REQUIRE(bars.sectionFactor(0, Eigen::Vector3d::UnitZ()) == Approx(narrow).epsilon(1e-3));
  REQUIRE(bars.againstObstacle(0, Eigen::Vector3d::UnitZ()) == Approx((c - zc) * narrow).epsilon(1e-3));
}
