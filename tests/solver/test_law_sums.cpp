// The explicit step's pair evaluation (its SIMD passes in float: level sets, the law, the sums
// with side 1's sign and the padding; pair_contacts.cpp, lawAndSums) against the implicit method's
// (the same law one contact at a time in double; implicit_contacts.cpp): two codes, one model. On a
// pair whose springs were loaded by sliding, at rest, both must give the same contacts, forces,
// torques and energies to the float law's rounding.
#include "geometry/block_generators.h"
#include "solver/implicit_contacts.h"
#include "solver/world.h"
#include "solver/world_internals.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tessera;

namespace {

const double kA = 10e-3, kH = 3.18e-3;

}  // namespace

TEST_CASE("the explicit pair sums and the implicit pair evaluation agree on a pressed, sliding pair: contacts, force, torque, energy") {
  // Exact planes (the planar block) and an exact mesh level set (the wave block, not convex).
  const bool wave = GENERATE(false, true);
  INFO((wave ? "wave blocks" : "planar blocks"));
  const TriangleMesh block =
      wave ? makeWaveBlock(kA, kH, 5.0 * M_PI / 180, 0.2e-3, 2, 8) : makePlanarBlock(kA, kH, 5.0 * M_PI / 180);
  const TriangleMesh& lower = block;
  const TriangleMesh& upper = block;
  const Bundle bundle = test::stackedBlocks(lower, upper, 0.25e-3, 0.6e-3, false);
  ContactParameters p;
  p.friction = 0.3;
  SolverSettings s;
  s.threads = 1;
  s.gravity.setZero();
  World world(bundle.shapes, bundle.bodies, p, s);
  // Stacked and pressed in off-centre and tilted, or side by side as tiled (the upper block turned
  // 90 degrees beside the lower one, their tilted or wavy faces against each other, pressed 20 um);
  // then slid and turned for a while, so that the springs are loaded: some stick, some slide.
  const bool sideBySide = GENERATE(false, true);
  INFO((sideBySide ? "side by side" : "stacked"));
  const RigidBodies& b = world.bodies();
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.004, Eigen::Vector3d(1, 0.3, 0).normalized()));
  if (sideBySide)
    world.setPose(1, b.position[0] + Eigen::Vector3d(kA - 20e-6, 0.3e-3, 0.05e-3),
                  tilt * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())) * b.orientation[0]);
  else
    world.setPose(1, b.position[1] + Eigen::Vector3d(0.7e-3, -0.4e-3, -0.03e-3), tilt * b.orientation[1]);
  for (int i = 0; i < 40; ++i) {
    world.setVelocity(1, sideBySide ? Eigen::Vector3d(0.0, 0.05, 0.2) : Eigen::Vector3d(0.02, 0.01, 0.0),
                      b.inertia[1].cwiseProduct(Eigen::Vector3d(0, 0, 0.5)));
    world.step();
  }
  const PairContacts* loaded = nullptr;
  for (const PairContacts& pair : WorldInternals::pairs(world))
    if (pair.b >= 0 && !pair.contacts.empty()) loaded = &pair;
  REQUIRE(loaded != nullptr);
  int side1 = 0;  // both sides' nodes touch
  for (std::size_t i = 0; i < loaded->contacts.size(); ++i) side1 += static_cast<int>(loaded->contacts[i].key >> 31);
  REQUIRE(side1 > 0);
  REQUIRE(side1 < static_cast<int>(loaded->contacts.size()));

  // Both evaluations at the bodies' poses, at rest: the springs are turned and capped, not loaded.
  RigidBodies bodies = world.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies.velocity[i].setZero();
    bodies.angularMomentum[i].setZero();
  }
  std::vector<ShapeModel> shapes;
  for (const Shape& shape : bundle.shapes) shapes.push_back(makeShapeModel(shape, s.exactConvexLevelSets, s.exactMeshLevelSets));
  const std::vector<SphereObstacle> spheres;
  const std::vector<PlaneObstacle> planes;
  const double kn = world.parameters().normalStiffness(), kt = world.parameters().tangentialStiffness();
  const double band = 0.1e-3;

  BodyKinematics kinematics;
  kinematics.update(bodies);
  const ContactScene explicitScene{&bodies, &kinematics, &shapes, &spheres, &planes, world.parameters(), kn, kt, world.timeStep(), band, nullptr};
  PairContacts stepped = *loaded;
  stepped.candidatesValid = false;
  evaluatePair(explicitScene, stepped);

  IncrementStart start{bodies.position, bodies.orientation, {}};
  const ImplicitScene implicitScene{&bodies, &shapes, &spheres, &planes, &start, world.parameters(), kn, kt, world.timeStep(), band};
  ImplicitCandidates candidates;
  ImplicitPairResult solved;
  evaluateImplicitPair(implicitScene, *loaded, loaded->contacts, candidates, solved);

  // The same node contacts, in the same order, with the same springs after the cap.
  REQUIRE(stepped.contacts.size() == solved.contacts.size());
  const double springScale = 1e-9;  // m
  for (std::size_t i = 0; i < solved.contacts.size(); ++i) {
    const NodeContact e = stepped.contacts[i], m = solved.contacts[i];
    REQUIRE(e.key == m.key);
    CHECK((e.spring - m.spring).norm() <= 1e-5 * std::max(m.spring.norm(), springScale));
    CHECK(e.area == Approx(m.area).epsilon(1e-5).margin(1e-14));
  }
  // Stacked: some springs at the Coulomb cap, some below it. (Which of those at the cap each code counts as
  // sliding is rounding: at rest a spring on the cap stays there, |k_t a u| = mu f_n in float or in
  // double; the springs themselves agree above.)
  if (!sideBySide) REQUIRE(stepped.tally.sliding > 0);
  REQUIRE(solved.tally.sliding < static_cast<int>(solved.contacts.size()));
  // Force and torque on a (about its centroid), and on b: the sums, side 1's sign and the padding.
  const double force = solved.force.head<3>().norm(), torque = solved.force.tail<3>().norm();
  REQUIRE(force > 0);
  CHECK((stepped.forceA - solved.force.head<3>()).norm() <= 1e-5 * force);
  CHECK((stepped.torqueA - solved.force.tail<3>()).norm() <= 1e-5 * (torque + force * kA));
  CHECK((stepped.normalForceA - solved.normalForceA).norm() <= 1e-5 * force);
  CHECK(stepped.tally.elastic == Approx(solved.tally.elastic).epsilon(1e-5));
  CHECK(stepped.maxDepth == Approx(solved.maxDepth).epsilon(1e-5));
}
