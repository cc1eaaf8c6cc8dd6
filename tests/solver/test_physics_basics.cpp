// Solver physics with known answers: static equilibrium, friction threshold, Newton's third law,
// energy conservation, free rotation, instability detection, broad phase.
#include "geometry/block_generators.h"
#include "solver/broad_phase.h"
#include "solver/world.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace tessera;
using Catch::Matchers::Contains;

namespace {

const double kA = 10e-3, kH = 3.18e-3;

// Settles the free body with local damping; returns the world.
void settle(World& world, int steps) {
  for (int s = 0; s < steps; ++s) world.step();
}

}  // namespace

TEST_CASE("static equilibrium: a block resting on a fixed block carries m g at penetration m g / (k_n A)") {
  // A soft material (E = 4.2 MPa) makes the penetration large against float32 grid round-off.
  ContactParameters p;
  p.youngsModulus = 4.2e6;
  p.evaluation = GENERATE(ContactEvaluation::TwoWay, ContactEvaluation::OneWay);
  SolverSettings s;
  s.localDamping = 0.7;
  for (bool freeFirst : {false, true}) {
    INFO("free body first: " << freeFirst << ", one-way: " << (p.evaluation == ContactEvaluation::OneWay));
    const Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3, freeFirst);
    World world(bundle.shapes, bundle.bodies, p, s);
    const int top = freeFirst ? 0 : 1;
    const double z0 = world.bodies().position[top].z();
    settle(world, 3000);
    const double mg = world.bodies().mass[top] * 9.81;
    REQUIRE(world.contactForces()[top].z() == Approx(mg).epsilon(1e-3));
    REQUIRE(std::abs(world.contactForces()[top].x()) < 1e-6 * mg);
    const double penetration = z0 - world.bodies().position[top].z();
    REQUIRE(penetration == Approx(mg / (p.normalStiffness() * kA * kA)).epsilon(0.02));
    REQUIRE(world.bodies().velocity[top].norm() < 1e-6);
    // The pair as callers outside the solver see it (World::pair): the force on a (the top's
    // reaction when the support is a), the whole footprint in contact, its depth the penetration,
    // its stored energy 1/2 k_n A d^2.
    REQUIRE(world.pairCount() == 1);
    const PairView pair = world.pair(0);
    REQUIRE(pair.kind == PairKind::Bodies);
    REQUIRE((pair.a == 0 && pair.b == 1));  // a pair is (lower index, higher)
    const Eigen::Vector3d onTop = pair.a == top ? pair.force : Eigen::Vector3d(-pair.force);
    REQUIRE((onTop - world.contactForces()[top]).norm() < 1e-9 * mg);
    REQUIRE((pair.normalForce - pair.force).norm() < 1e-6 * mg);  // at rest: no friction
    REQUIRE(pair.area == Approx(kA * kA).epsilon(0.02));
    REQUIRE(pair.depth == Approx(penetration).epsilon(0.02));
    REQUIRE(pair.elastic == Approx(0.5 * mg * penetration).epsilon(0.05));
    REQUIRE(pair.normalStiffness == p.normalStiffness());
    REQUIRE(pair.nodeContacts > 0);
    REQUIRE(pair.slidingNodes == 0);
    REQUIRE(std::abs(pair.point.z() - (world.bodies().position[top].z() - kH / 2)) < 0.1 * kH);
    REQUIRE_THROWS_AS(world.pair(1), std::out_of_range);
  }
}

TEST_CASE("static equilibrium on an analytic plane: the node areas carry m g at m g / (k_n A)") {
  ContactParameters p;
  p.youngsModulus = 4.2e6;
  SolverSettings s;
  s.localDamping = 0.7;
  Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  bundle.bodies.erase(bundle.bodies.begin());  // the free block alone
  bundle.bodies[0].position = Eigen::Vector3d(0, 0, kH / 2);
  World world(bundle.shapes, bundle.bodies, p, s);
  PlaneObstacle floor;  // z = 0, solid below
  world.addPlane(floor);
  for (int i = 0; i < 3000; ++i) world.step();
  const double mg = world.bodies().mass[0] * 9.81;
  REQUIRE(world.contactForces()[0].z() == Approx(mg).epsilon(1e-3));
  REQUIRE(kH / 2 - world.bodies().position[0].z() == Approx(mg / (p.normalStiffness() * kA * kA)).epsilon(0.02));
}

TEST_CASE("static equilibrium of the TIS block on a TIS block (inclined sides)") {
  ContactParameters p;
  p.youngsModulus = 4.2e6;
  SolverSettings s;
  s.localDamping = 0.7;
  const double theta = 5 * M_PI / 180;
  // The top face of the lower block and the bottom face of the upper are (a + h tan) x (a - h tan).
  const TriangleMesh block = makePlanarBlock(kA, kH, theta);
  TriangleMesh flipped = block;  // upper block turned upside down: its bottom face matches the lower's top
  for (auto& v : flipped.vertices) v = Eigen::Vector3d(v.x(), -v.y(), -v.z());
  const Bundle bundle = test::stackedBlocks(block, flipped, 0.25e-3, 0.6e-3);
  World world(bundle.shapes, bundle.bodies, p, s);
  const double z0 = world.bodies().position[1].z();
  settle(world, 3000);
  const double mg = world.bodies().mass[1] * 9.81;
  const double area = (kA + kH * std::tan(theta)) * (kA - kH * std::tan(theta));
  REQUIRE(world.contactForces()[1].z() == Approx(mg).epsilon(1e-3));
  REQUIRE(z0 - world.bodies().position[1].z() == Approx(mg / (p.normalStiffness() * area)).epsilon(0.02));
}

TEST_CASE("friction threshold: a block on a tilted block sticks below atan(mu) and slides above") {
  ContactParameters p;
  p.youngsModulus = 4.2e6;
  for (double mu : {0.23, 0.5}) {
    p.friction = mu;
    const double critical = std::atan(mu);
    for (double offset : {-0.5, 0.5}) {
      const double theta = critical + offset * M_PI / 180;
      INFO("mu " << mu << ", tilt " << theta * 180 / M_PI << " deg");
      // Tilting the blocks by theta is tilting gravity by -theta.
      SolverSettings s;
      s.localDamping = 0.3;
      s.gravity = 9.81 * Eigen::Vector3d(std::sin(theta), 0, -std::cos(theta));
      const Bundle bundle = test::stackedBlocks(makeBox(2 * kA, 2 * kA, kH), makeBox(kA, kA, kH), 0.25e-3, 1.0e-3);
      World world(bundle.shapes, bundle.bodies, p, s);
      const double x0 = world.bodies().position[1].x();
      while (world.time() < 0.1) world.step();
      const double slip = world.bodies().position[1].x() - x0;
      if (offset < 0) {
        REQUIRE(std::abs(slip) < 1e-6);  // elastic tangential deflection only (~1e-8 m)
      } else {
        // Sliding: a = g (sin - mu cos), reduced by local damping; well beyond elastic creep.
        REQUIRE(slip > 1e-5);
      }
    }
  }
}

TEST_CASE("Newton's third law over the World's sums: contact forces on all bodies and the indenter add to zero, torques too, with either method") {
  // What each body and the indenter receive, summed as the World scatters them (not pair by pair):
  // every action has its reaction somewhere, so the sums vanish to rounding.
  const auto check = [](SolverMethod method, bool withIndenter) {
    SolverSettings s;
    s.method = method;
    s.threads = 2;
    const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
    World world(slab.shapes, slab.bodies, ContactParameters{}, s);
    if (withIndenter) {
      SphereObstacle indenter;
      indenter.radius = 2.5e-3;
      // 0.1 mm into the top of the centre block (several nodes inside), a little off its centre.
      indenter.center = world.bodies().position[4] + Eigen::Vector3d(0.3e-3, -0.2e-3, world.bodyBox(4, 0).max().z() + 2.5e-3 - 0.1e-3);
      indenter.velocity = Eigen::Vector3d(0, 0, -0.03);
      world.addSphere(indenter);
    }
    world.setVelocity(4, world.bodies().velocity[4], Eigen::Vector3d(1e-9, -2e-9, 0.5e-9));  // a little asymmetry
    for (int i = 0; i < (method == SolverMethod::Explicit ? 50 : 5); ++i) world.step();
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
    double scale = 0.0, lever = 0.0;
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
      const Eigen::Vector3d& f = world.contactForces()[i];
      const Eigen::Vector3d& p = world.bodies().position[i];
      force += f;
      torque += world.contactTorques()[i] + p.cross(f);
      scale = std::max(scale, f.norm());
      lever = std::max(lever, p.norm());
    }
    REQUIRE(scale > 0);
    if (withIndenter) {
      force += world.sphereReaction(0);  // its torque about its centre is not kept: forces only
      REQUIRE(world.sphereReaction(0).norm() > 0);
    } else {
      CHECK(torque.norm() <= 1e-9 * scale * lever);
    }
    CHECK(force.norm() <= 1e-9 * scale);
  };
  for (const SolverMethod method : {SolverMethod::Explicit, SolverMethod::Implicit}) {
    check(method, true);
    check(method, false);
  }
}

TEST_CASE("energy: without damping or friction a bouncing block conserves energy to 1 % at factor 0.1, 5 % at the default") {
  ContactParameters p;
  p.friction = 0.0;
  Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  bundle.bodies[1].position.z() += 20e-6;  // dropped from 20 um
  // Worst energy error after each of ten bounces, at an automatic step of `factor`.
  const auto bounce = [&](double factor) {
    SolverSettings s;  // no damping
    s.timeStepFactor = factor;
    World world(bundle.shapes, bundle.bodies, p, s);
    // Measured in flight, after each contact: within a contact, Verlet's full-step kinetic energy
    // differs from its conserved (shadow) energy by O((omega dt)^2) and returns to it.
    int bounces = 0;
    bool inContact = false;
    double worst = 0.0;
    while (bounces < 10) {
      world.step();
      const bool touching = world.maxPenetration() > 0;
      if (inContact && !touching) {
        ++bounces;
        worst = std::max(worst, std::abs(world.energy().residual()));
      }
      inContact = touching;
      REQUIRE(world.time() < 1.0);
    }
    return worst / (world.bodies().mass[1] * 9.81 * 20e-6);
  };
  // Each node entering or leaving contact mid-step costs an error that grows with the step, in
  // no clean power (measured: 0.03 % at 0.05, 0.4 % at 0.1, 3 % at 0.25 and 0.5). Quasi-static
  // results are insensitive to it (docs/performance.md: P_max, K, W within 0.05 % from 0.25 to 1).
  const double fine = bounce(0.1), standard = bounce(0.5);
  INFO("worst energy error " << fine << " (factor 0.1), " << standard << " (factor 0.5) of the drop energy");
  REQUIRE(fine < 0.01);
  REQUIRE(standard < 0.05);
}

TEST_CASE("free rotation near the intermediate axis: the block flips, energy and momentum are kept to 1e-4") {
  // Box 1 x 2 x 3 mm: principal moments I_x > I_y > I_z; y is the intermediate axis.
  Bundle bundle = test::stackedBlocks(makeBox(1e-3, 1e-3, 1e-3), makeBox(1e-3, 2e-3, 3e-3), 0.1e-3, 0.3e-3);
  bundle.bodies[1].position.z() += 1.0;  // far from the base: no contact
  SolverSettings s;
  s.gravity.setZero();
  const double omega = 100.0;
  s.timeStep = 0.01 / omega;
  s.allowUnsafeTimeStep = true;  // no contact here: the contact-based estimate does not apply
  World world(bundle.shapes, bundle.bodies, ContactParameters{}, s);
  const RigidBodies& b = world.bodies();
  const Eigen::Vector3d w(1e-3 * omega, omega, 1e-3 * omega);  // nearly about y
  world.setVelocity(1, b.velocity[1], b.inertia[1].cwiseProduct(w));
  const double energy0 = b.kineticEnergy(1);
  const Eigen::Vector3d momentum0 = b.orientation[1] * b.angularMomentum[1];
  bool flipped = false;
  double energyError = 0, momentumError = 0;
  for (int step = 0; step < 100000; ++step) {
    world.step();
    flipped = flipped || b.angularMomentum[1].y() < 0;
    energyError = std::max(energyError, std::abs(b.kineticEnergy(1) / energy0 - 1));
    momentumError = std::max(momentumError, (b.orientation[1] * b.angularMomentum[1] - momentum0).norm() / momentum0.norm());
  }
  INFO("energy error " << energyError << ", momentum error " << momentumError);
  REQUIRE(flipped);
  REQUIRE(energyError < 1e-4);
  REQUIRE(momentumError < 1e-4);
}

TEST_CASE("free rotation of many bodies: each turns as the splitting with library sines says, alone or among others, and fixed and retired ones stay") {
  // Bodies turned in lanes of several (rotateFreely) against the five sub-rotations written with
  // Eigen's AngleAxis (std::sin, std::cos). The half angles per sub-step span 2e-11 to 0.13 rad: the
  // Taylor series below 1/16 rad and the library above.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  RigidBodies bodies;
  const int count = 21;
  const double dt = 1e-3;
  for (int i = 0; i < count; ++i) {
    bodies.position.push_back(Eigen::Vector3d::Zero());
    bodies.velocity.push_back(Eigen::Vector3d::Zero());
    bodies.orientation.push_back(Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized());
    const Eigen::Vector3d inertia(2e-8 + 1e-8 * unit(random), 3e-8 + 1e-8 * unit(random), 5e-8 + 1e-8 * unit(random));
    bodies.inertia.push_back(inertia);
    const double angle = std::pow(10.0, -10 + 9.5 * i / (count - 1));  // rad per step, about each axis
    bodies.angularMomentum.push_back(inertia.cwiseProduct(Eigen::Vector3d(0.9, -0.7, 0.8)) * (angle / dt));
    bodies.mass.push_back(1e-3);
    bodies.fixed.push_back(i % 7 == 3 ? 1 : 0);
    bodies.retired.push_back(i % 7 == 5 ? 1 : 0);
    bodies.shape.push_back(0);
    bodies.name.push_back("b" + std::to_string(i));
  }
  const RigidBodies before = bodies;
  // Both paths of the sine are taken: the largest first half angle, 0.9 x 10^-0.5 / 4, is above 1/16.
  REQUIRE(0.25 * before.angularMomentum[count - 1].x() / before.inertia[count - 1].x() * dt > 0.0625);
  REQUIRE(0.25 * before.angularMomentum[count - 2].x() / before.inertia[count - 2].x() * dt < 0.0625);
  rotateFreely(bodies, dt);

  const auto subRotation = [](Eigen::Quaterniond& q, Eigen::Vector3d& pi, const Eigen::Vector3d& inertia, int k, double t) {
    const double phi = t * pi[k] / inertia[k];
    const Eigen::AngleAxisd turn(phi, Eigen::Vector3d::Unit(k));
    q = q * Eigen::Quaterniond(turn);
    pi = turn.inverse() * pi;
  };
  for (int i = 0; i < count; ++i) {
    INFO("body " << i);
    if (!before.moves(i)) {
      REQUIRE(bodies.orientation[i].coeffs() == before.orientation[i].coeffs());
      REQUIRE(bodies.angularMomentum[i] == before.angularMomentum[i]);
      continue;
    }
    Eigen::Quaterniond q = before.orientation[i];
    Eigen::Vector3d pi = before.angularMomentum[i];
    for (const auto& [k, t] : {std::pair{0, 0.5 * dt}, {1, 0.5 * dt}, {2, dt}, {1, 0.5 * dt}, {0, 0.5 * dt}})
      subRotation(q, pi, before.inertia[i], k, t);
    q.normalize();
    REQUIRE((bodies.orientation[i].coeffs() - q.coeffs()).norm() < 1e-14);
    REQUIRE((bodies.angularMomentum[i] - pi).norm() < 1e-13 * pi.norm());
    REQUIRE(std::abs(bodies.angularMomentum[i].norm() / before.angularMomentum[i].norm() - 1) < 1e-14);  // |Pi| kept

    // Alone: the same bits as among the others.
    RigidBodies alone;
    alone.position = {before.position[i]};
    alone.velocity = {before.velocity[i]};
    alone.orientation = {before.orientation[i]};
    alone.angularMomentum = {before.angularMomentum[i]};
    alone.inertia = {before.inertia[i]};
    alone.mass = {before.mass[i]};
    alone.fixed = {0};
    alone.retired = {0};
    alone.shape = {0};
    alone.name = {before.name[i]};
    rotateFreely(alone, dt);
    REQUIRE(alone.orientation[0].coeffs() == bodies.orientation[i].coeffs());
    REQUIRE(alone.angularMomentum[0] == bodies.angularMomentum[i]);
  }
}

TEST_CASE("restore: a World given another's state mid-slide goes on bit-identically, finding the nodes the block slides onto") {
  // A block overhanging a fixed one by 2.5 mm slides back over it without friction for about
  // 1.3 mm, is handed to a new World, and both go on for about 1 mm more: more than a node spacing,
  // so the new World must rebuild the candidates from the travel it measures itself (restore resets
  // each pair's checked travel); trusting the first World's travel, it would miss the fixed block's
  // nodes the block slides onto.
  ContactParameters p;
  p.friction = 0;
  Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  bundle.bodies[1].position.x() -= 2.5e-3;
  World first(bundle.shapes, bundle.bodies, p, SolverSettings{});
  first.setVelocity(1, Eigen::Vector3d(0.1, 0, 0), Eigen::Vector3d::Zero());
  const int before = static_cast<int>(1.3e-3 / 0.1 / first.timeStep()), after = static_cast<int>(1e-3 / 0.1 / first.timeStep());
  for (int i = 0; i < before; ++i) first.step();
  World second(bundle.shapes, bundle.bodies, p, SolverSettings{});
  second.restore(first.state());
  for (int i = 0; i < after; ++i) {
    first.step();
    second.step();
  }
  INFO("slid " << (first.bodies().position[1].x() - bundle.bodies[1].position.x()) * 1e3 << " mm");
  REQUIRE(first.bodies().position[1].x() - bundle.bodies[1].position.x() > 2e-3);
  INFO("position difference " << (second.bodies().position[1] - first.bodies().position[1]).transpose());
  REQUIRE(second.bodies().position[1] == first.bodies().position[1]);
  REQUIRE(second.bodies().velocity[1] == first.bodies().velocity[1]);
  REQUIRE(second.bodies().orientation[1].coeffs() == first.bodies().orientation[1].coeffs());
  REQUIRE(second.contactForces()[1] == first.contactForces()[1]);
}

TEST_CASE("mutation contract: forces evaluated again at the same configuration (a sphere added) load no spring twice") {
  // A block sliding on a fixed one with friction; the second World is given a sphere far away
  // between two steps, which makes it evaluate the forces again before its next step. That
  // evaluation must not load the tangential springs by v_t dt a second time.
  ContactParameters p;
  p.friction = 0.5;
  const Bundle bundle = test::stackedBlocks(makeBox(2 * kA, 2 * kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  World first(bundle.shapes, bundle.bodies, p, SolverSettings{}), second(bundle.shapes, bundle.bodies, p, SolverSettings{});
  for (World* w : {&first, &second}) {
    w->setVelocity(1, Eigen::Vector3d(0.02, 0.01, 0), Eigen::Vector3d::Zero());
    for (int i = 0; i < 300; ++i) w->step();
  }
  SphereObstacle far;
  far.center = Eigen::Vector3d(1, 1, 1);
  far.radius = 1e-3;
  second.addSphere(far);
  for (int i = 0; i < 5; ++i) {
    first.step();
    second.step();
  }
  // The same to the rounding of evaluating the same forces twice (the spring turned onto its own
  // plane, the node forces summed in another order): 1e-21 m and 1e-10 of the weight measured.
  // Loaded twice, the friction force differs by 1e-8 of itself here (the springs at the Coulomb
  // cap take the extra v_t dt mostly as sliding), 5e-9 of the weight. The body's net force is
  // nearly zero (it rests), so the scale is its weight.
  const Eigen::Vector3d f = first.contactForces()[1];
  const double weight = first.bodies().mass[1] * 9.81;
  REQUIRE(f.head<2>().norm() > 0);  // friction acts
  REQUIRE((second.contactForces()[1] - f).norm() <= 1e-9 * weight);
  REQUIRE((second.bodies().position[1] - first.bodies().position[1]).norm() <= 1e-15);
  REQUIRE(second.energy().friction == Approx(first.energy().friction).epsilon(1e-9));
}

TEST_CASE("mutation contract: a pose set between steps is found in contact at the next step, and only free bodies are set") {
  // A box a metre above a fixed one, put down into it by 10 um between two steps: the broad phase
  // built at the old pose paired nothing, so the next step must pair them afresh and push back.
  Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  const Eigen::Vector3d resting = bundle.bodies[1].position;
  bundle.bodies[1].position.z() += 1.0;
  SolverSettings s;
  s.gravity.setZero();
  World world(bundle.shapes, bundle.bodies, ContactParameters{}, s);
  world.step();
  REQUIRE(world.contactForces()[1].norm() == 0.0);
  world.setPose(1, resting - Eigen::Vector3d(0, 0, 10e-6), world.bodies().orientation[1]);
  // The jump stored energy in the contact: booked as supplied, the balance stays closed.
  const double stored = world.energy().elastic;
  REQUIRE(stored > 0);
  REQUIRE(world.energy().initial == Approx(stored).epsilon(1e-12));
  REQUIRE(std::abs(world.energy().residual()) < 1e-12 * stored);
  world.step();
  REQUIRE(world.contactForces()[1].z() > 0);  // pushed back at once
  REQUIRE(world.contactForces()[0].z() == -world.contactForces()[1].z());
  for (int i = 0; i < 100; ++i) world.step();  // and off: the stored energy is now kinetic
  REQUIRE(world.energy().kinetic == Approx(stored).epsilon(0.05));
  REQUIRE(std::abs(world.energy().residual()) < 0.05 * stored);
  REQUIRE_THROWS_AS(world.setPose(0, resting, world.bodies().orientation[0]), std::invalid_argument);  // the support
  // Under gravity a body lifted between steps keeps the balance closed: gravity's work on the
  // jump is booked as supplied too.
  const Bundle stack = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  World heavy(stack.shapes, stack.bodies, ContactParameters{}, SolverSettings{});
  for (int k = 0; k < 50; ++k) heavy.step();
  const double before = heavy.energy().residual(), lift = heavy.bodies().mass[1] * 9.81 * 1e-3;
  heavy.setPose(1, heavy.bodies().position[1] + Eigen::Vector3d(0, 0, 1e-3), heavy.bodies().orientation[1]);
  REQUIRE(std::abs(heavy.energy().residual() - before) < 1e-9 * lift);
  REQUIRE(heavy.energy().initial == Approx(lift).epsilon(1e-3));  // the lift's potential energy (what the contact held is far less)
  REQUIRE_THROWS_AS(world.setVelocity(1, Eigen::Vector3d(NAN, 0, 0), Eigen::Vector3d::Zero()), std::invalid_argument);
  REQUIRE_THROWS_AS(world.setPose(1, resting, Eigen::Quaterniond(2, 0, 0, 0)), std::invalid_argument);  // not unit
}

TEST_CASE("instability is caught: 5x the automatic time step stops the run with a diagnostic") {
  // A cube clamped on all six faces by fixed cubes (overlapping by 1 um, sticking: mu = 100):
  // 5x the automatic step is 2.5x the stability estimate 2 / omega_max (allowed here only for the
  // test), past Verlet's limit omega dt = 2 for its clamped modes.
  ContactParameters p;
  p.friction = 100;
  SolverSettings s;
  const double a = 4e-3;
  Bundle bundle = test::stackedBlocks(makeBox(a, a, a), makeBox(a, a, a), 0.25e-3, 0.6e-3, true);
  bundle.bodies.resize(1);
  bundle.bodies[0].position.setZero();
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      Body wall;
      wall.name = "wall" + std::to_string(bundle.bodies.size());
      wall.shape = 0;
      wall.fixed = true;
      wall.position[axis] = side * (a - 1e-6);
      bundle.bodies.push_back(wall);
    }
  const double automatic = World(bundle.shapes, bundle.bodies, p, s).automaticTimeStep();
  const auto knock = [](World& w) {  // a small initial velocity and spin
    w.setVelocity(0, Eigen::Vector3d(1e-4, 2e-4, 0), 1e-3 * w.bodies().inertia[0]);
  };
  s.timeStep = 5 * automatic;
  s.allowUnsafeTimeStep = true;
  World world(bundle.shapes, bundle.bodies, p, s);
  knock(world);
  bool stopped = false;
  try {
    for (int step = 0; step < 20000; ++step) world.step();
  } catch (const SolverInstability& e) {
    stopped = true;
    REQUIRE_THAT(e.what(), Contains("body 'top'") && Contains("time step") && Contains("t = ") &&
                               Contains("kinetic energy"));
  }
  REQUIRE(stopped);
  // At the automatic step the same clamp runs quietly.
  s.timeStep = 0;
  s.allowUnsafeTimeStep = false;
  World calm(bundle.shapes, bundle.bodies, p, s);
  knock(calm);
  for (int step = 0; step < 20000; ++step) calm.step();
  REQUIRE(calm.energy().initial > 0);
  REQUIRE(std::abs(calm.energy().residual()) < 0.05 * calm.energy().initial);  // friction dissipation booked
}

TEST_CASE("sort-and-sweep broad phase finds exactly the pairs of the brute-force reference") {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::AlignedBox3d> boxes;
  std::vector<char> fixed;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d c(u(random), u(random), 0.1 * u(random)), half(0.03 * u(random), 0.03 * u(random), 0.02);
    boxes.emplace_back(c - half, c + half);
    fixed.push_back(u(random) < 0.3);
  }
  const auto sweep = sweepPairs(boxes, fixed);
  REQUIRE(sweep == bruteForcePairs(boxes, fixed));
  REQUIRE(sweep.size() > 100);
  for (const auto& [a, b] : sweep) REQUIRE_FALSE((fixed[a] && fixed[b]));
}
