// Where methods fail: time steps above the stability estimate, penetration deeper than a grid
// band, grazing edge-on-edge contacts, and the candidate node lists that skip far nodes. Each is
// either handled (checked against the analytic answer) or stopped with a diagnostic.
// The measured critical step against E and mu is a benchmark: bench/stability_map.cpp.
#include "geometry/block_generators.h"
#include "levelset/shape.h"
#include "solver/world.h"
#include "solver/world_internals.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {
const double kA = 10e-3, kH = 3.18e-3;
}

TEST_CASE("a fixed time step above the stability estimate 2 / omega_max is refused, naming both") {
  const Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  SolverSettings s;
  const double automatic = World(bundle.shapes, bundle.bodies, ContactParameters{}, s).automaticTimeStep();
  s.timeStep = automatic / s.timeStepFactor * 1.01;  // 1 % above factor 1
  REQUIRE_THROWS_WITH(World(bundle.shapes, bundle.bodies, ContactParameters{}, s),
                      Contains("above the stability estimate") && Contains("time step"));
  s.timeStep = automatic / s.timeStepFactor * 0.99;
  REQUIRE_NOTHROW(World(bundle.shapes, bundle.bodies, ContactParameters{}, s));
  s.timeStep = 10 * automatic;
  s.allowUnsafeTimeStep = true;  // for measuring critical steps only
  REQUIRE_NOTHROW(World(bundle.shapes, bundle.bodies, ContactParameters{}, s));
}

TEST_CASE("deep penetration: grid forces match the exact level set's far past the exterior band, and beyond the bound the run stops") {
  // A box pressed 1 mm (4 voxels, past the grid's 3-voxel exterior band) into a fixed box: the
  // grid's interior values are exact distances, so its forces match the exact planes'.
  ContactParameters p;
  p.friction = 0;
  SolverSettings s;
  s.gravity.setZero();
  s.maxPenetration = 2e-3;
  Bundle bundle = test::stackedBlocks(makeBox(2 * kA, 2 * kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  bundle.bodies[1].position.z() -= 1e-3;
  Eigen::Vector3d force[2];
  for (int grid = 0; grid < 2; ++grid) {
    s.exactConvexLevelSets = grid == 0;
    World world(bundle.shapes, bundle.bodies, p, s);
    world.step();
    force[grid] = world.contactForces()[1];
  }
  const double reference = p.normalStiffness() * kA * kA * 1e-3;  // k_n A d, the whole footprint
  REQUIRE(force[0].z() > 0.6 * reference);  // less near the edges, where the side planes are nearer
  REQUIRE(force[1].z() == Approx(force[0].z()).epsilon(0.02));
  REQUIRE(std::abs(force[1].x()) < 1e-2 * force[1].z());  // the grid is not quite symmetric about the box
  s.maxPenetration = 0;  // the default bound: a quarter of the thinnest block (0.795 mm)
  World world(bundle.shapes, bundle.bodies, p, s);
  REQUIRE_THROWS_WITH(world.step(), Contains("penetration") && Contains("beyond the bound") && Contains("the time step"));  // it sprang apart: dynamics
}

TEST_CASE("a block pressed slowly past the bound stops naming the soft penalty, not the time step (issue #39)") {
  // A sphere ten times stiffer than the blocks' soft penalty (E = 1e5 Pa) pushes the top block
  // into the fixed base at 1 mm/s: the slab follows at rest while its penetration grows past the
  // 0.1 mm bound. The penalty is too soft for the force; the step has nothing to do with it.
  ContactParameters p;
  p.youngsModulus = 1e5;
  SolverSettings s;
  s.gravity.setZero();
  s.localDamping = 0.7;
  s.maxPenetration = 0.1e-3;
  const Bundle bundle = test::stackedBlocks(makeBox(2 * kA, 2 * kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  World world(bundle.shapes, bundle.bodies, p, s);
  SphereObstacle sphere;
  sphere.center = bundle.bodies[1].position + Eigen::Vector3d(0, 0, 0.5 * kH + sphere.radius);
  sphere.velocity = Eigen::Vector3d(0, 0, -1e-3);
  sphere.stiffnessFactor = 10;
  world.addSphere(sphere);
  std::string message;
  try {
    for (int i = 0; i < 200000; ++i) world.step();
  } catch (const SolverInstability& e) {
    message = e.what();
  }
  REQUIRE_THAT(message, Contains("penetration") && Contains("into body 'top'") && Contains("the slab was at rest") &&
                            Contains("too soft for these forces"));
}

TEST_CASE("grazing contact: a block balanced edge-down across another's edge comes to rest on it") {
  // Two 10 x 10 x 3.18 mm boxes turned 45 deg about x (the top one) and about y (the fixed one):
  // their edges cross at right angles and touch at one point, where no node sits. The nodes
  // nearest the edges catch the top block within a fraction of the node spacing; it must neither
  // sink through nor jitter.
  ContactParameters p;
  SolverSettings s;
  s.localDamping = 0.7;
  Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  bundle.bodies[0].orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitY()));
  bundle.bodies[1].orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()));
  // Turned by 45 deg, a 10 x 3.18 section has its corner edge at (a/2 + h/2)/sqrt(2) from the centre.
  const double edge = (kA / 2 + kH / 2) / std::sqrt(2.0);
  bundle.bodies[0].position.setZero();
  bundle.bodies[1].position = Eigen::Vector3d(0, 0, 2 * edge);
  World world(bundle.shapes, bundle.bodies, p, s);
  const double z0 = world.bodies().position[1].z();
  const double mg = world.bodies().mass[1] * 9.81;
  // Keep it balanced: only its vertical motion is free to show the catch (the edge line is an
  // unstable balance point); clear the sideways velocities every step.
  double sink = 0;
  for (int i = 0; i < 40000; ++i) {
    world.step();
    world.setVelocity(1, Eigen::Vector3d(0, 0, world.bodies().velocity[1].z()), Eigen::Vector3d::Zero());
    sink = std::max(sink, z0 - world.bodies().position[1].z());
  }
  INFO("sink " << sink * 1e3 << " mm");
  REQUIRE(sink > 0);
  REQUIRE(sink < 0.6e-3);  // caught within one node spacing
  REQUIRE(world.contactForces()[1].z() == Approx(mg).epsilon(0.01));
  REQUIRE(world.bodies().velocity[1].norm() < 1e-5);
}

TEST_CASE("candidate node lists: the forces are those of candidates built afresh every step, to the last bit, and a wider band keeps more nodes") {
  // Nodes beyond the band when a pair's candidates are built cannot touch before the pair's sides
  // have moved band / sqrt(3) relative to each other, when they are built again; a wider band
  // only adds nodes that never touch. A margin of 1e-9 of the default rebuilds the pairs and their
  // candidates at every step: the reference. On the exact-mesh path that also drops every
  // candidate's kept NearestFace at every step, so each evaluation is a full search; on the planes
  // path it chooses the planes near the candidates (PairContacts::planesKept) at every step, with
  // a margin of 2e-9 of the default band. (planesNear with a margin of 0 instead of 2 bands fails
  // this test.)
  Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  for (Shape& shape : slab.shapes) deriveExactMesh(shape);  // as a run does, for the exact-mesh path
  enum Path { Planes, ExactMesh, Grid };
  for (Path path : {Planes, ExactMesh, Grid}) {
    INFO((path == Planes ? "exact planes" : path == ExactMesh ? "exact mesh level sets" : "grid level sets"));
    SolverSettings s;
    s.localDamping = 0.3;
    s.threads = 1;
    s.exactConvexLevelSets = path == Planes;
    s.exactMeshLevelSets = path == ExactMesh;
    SolverSettings wide = s, fresh = s;
    wide.broadPhaseMarginRatio = 4 * s.broadPhaseMarginRatio;
    fresh.broadPhaseMarginRatio = 1e-9 * s.broadPhaseMarginRatio;
    World narrow(slab.shapes, slab.bodies, ContactParameters{}, s), broad(slab.shapes, slab.bodies, ContactParameters{}, wide),
        every(slab.shapes, slab.bodies, ContactParameters{}, fresh);
    for (World* w : {&narrow, &broad, &every}) {
      SphereObstacle indenter;
      indenter.center = Eigen::Vector3d(0, 0, kH / 2 + indenter.radius - 5e-6);
      indenter.velocity = Eigen::Vector3d(0, 0, -0.5);  // 0.3 mm in the run: many rebuilds
      w->addSphere(indenter);
    }
    for (int i = 0; i < 600; ++i)
      for (World* w : {&narrow, &broad, &every}) w->step();
    for (std::size_t b = 0; b < slab.bodies.size(); ++b) {
      INFO("body " << slab.bodies[b].name);
      REQUIRE(narrow.contactForces()[b] == every.contactForces()[b]);
      REQUIRE(narrow.bodies().position[b] == every.bodies().position[b]);
      REQUIRE(narrow.bodies().orientation[b].coeffs() == every.bodies().orientation[b].coeffs());
      REQUIRE(broad.contactForces()[b] == every.contactForces()[b]);
    }
    REQUIRE(narrow.sphereReaction(0).z() > 1.0);  // loaded: over a newton on the indenter
    std::size_t narrowCandidates = 0, broadCandidates = 0;
    for (const PairContacts& pair : WorldInternals::pairs(narrow)) narrowCandidates += pair.candidates.nodes();
    for (const PairContacts& pair : WorldInternals::pairs(broad)) broadCandidates += pair.candidates.nodes();
    REQUIRE(narrowCandidates < broadCandidates);
  }
}

TEST_CASE("candidate motion: |dp| + 2 sin(theta/2) r of each side since the candidates were built") {
  // Two bodies of a shape whose farthest point is 5 mm from its centroid, and a sphere.
  std::vector<ShapeModel> shapes(1);
  shapes[0].radius = 5e-3;
  RigidBodies bodies;
  bodies.position = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10e-3, 0, 0)};
  bodies.orientation = {Eigen::Quaterniond::Identity(), Eigen::Quaterniond::Identity()};
  bodies.shape = {0, 0};
  std::vector<SphereObstacle> spheres(1);
  std::vector<PlaneObstacle> planes;
  const ContactScene scene{&bodies, nullptr, &shapes, &spheres, &planes, ContactParameters{}, 0, 0, 0, 0};
  PairContacts pair;
  pair.a = 0;
  pair.b = 1;
  pair.builtPositionB = bodies.position[1];
  REQUIRE(candidateMotion(scene, pair) == 0.0);
  bodies.position[1] += Eigen::Vector3d(3e-6, -4e-6, 0);  // 5 um
  REQUIRE(candidateMotion(scene, pair) == Approx(5e-6).epsilon(1e-12));
  // A turn theta counts the chord 2 sin(theta / 2) r (what the farthest point moves), below the
  // arc theta r, at small and at large angles.
  for (double theta : {1e-3, 0.3, 2.5}) {
    bodies.orientation[0] = Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d(0.6, 0, 0.8)));
    REQUIRE(candidateMotion(scene, pair) == Approx(5e-6 + 2 * std::sin(theta / 2) * 5e-3).epsilon(1e-12));
    REQUIRE(candidateMotion(scene, pair) <= 5e-6 + theta * 5e-3);
  }
  // What a point at r moves when body 0 turns: never more than the bound.
  const Eigen::Vector3d far = Eigen::Vector3d(0, 5e-3, 0);  // at r from the centroid, off the axis
  const Eigen::Vector3d moved = bodies.orientation[0] * far;
  REQUIRE((moved - far).norm() <= candidateMotion(scene, pair) - 5e-6 + 1e-15);
  // A sphere moves, and does not turn: only its centre counts.
  PairContacts touch;
  touch.a = 1;
  touch.b = -1;
  touch.kind = PairKind::Sphere;
  touch.builtPositionA = bodies.position[1];
  spheres[0].center = Eigen::Vector3d(0, 0, 2e-6);
  REQUIRE(candidateMotion(scene, touch) == Approx(2e-6).epsilon(1e-12));
}

TEST_CASE("travel: each body's summed moves bound how far any of its points has gone, poses set between steps included") {
  // One body (its farthest point 5 mm from the centroid) drifting and turning in small random
  // moves, then put somewhere else between two updates; and a sphere.
  RigidBodies bodies;
  bodies.position = {Eigen::Vector3d(0, 0, 0)};
  bodies.orientation = {Eigen::Quaterniond::Identity()};
  const std::vector<double> radius = {5e-3};
  std::vector<SphereObstacle> spheres(1);
  Travel travel;
  travel.update(bodies, radius, spheres);
  REQUIRE(travel.body[0] == 0.0);
  REQUIRE(travel.sphere[0] == 0.0);
  const Eigen::Vector3d p0 = bodies.position[0];
  const Eigen::Quaterniond q0 = bodies.orientation[0];
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int step = 0; step < 200; ++step) {
    bodies.position[0] += 1e-7 * Eigen::Vector3d(unit(random), unit(random), unit(random));
    bodies.orientation[0] =
        bodies.orientation[0] * Eigen::Quaterniond(Eigen::AngleAxisd(1e-4 * unit(random), Eigen::Vector3d(unit(random), unit(random), 1).normalized()));
    travel.update(bodies, radius, spheres);
    // The farthest a point at r can have gone since the start, and the travel above it.
    const double moved = (bodies.position[0] - p0).norm() + turnChord(bodies.orientation[0], q0) * radius[0];
    REQUIRE(moved <= travel.body[0] * (1 + 1e-12));
  }
  // A pose set between updates counts in full.
  const double before = travel.body[0];
  bodies.position[0] += Eigen::Vector3d(0, 0, 1.0);
  spheres[0].center += Eigen::Vector3d(2e-3, 0, 0);
  travel.update(bodies, radius, spheres);
  REQUIRE(travel.body[0] == Approx(before + 1.0).epsilon(1e-12));
  REQUIRE(travel.sphere[0] == Approx(2e-3).epsilon(1e-12));
}
