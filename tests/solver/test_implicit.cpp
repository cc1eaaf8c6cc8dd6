// The implicit method against what it must reproduce: its tangent is the derivative of its forces,
// resting and sliding blocks as the closed forms say, the balance of forces on every free body of
// a slab, determinism across a restore (docs/physics.md, "Implicit method").
#include "geometry/block_generators.h"
#include "solver/implicit_contacts.h"
#include "solver/world.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tessera;

namespace {

const double kA = 10e-3, kH = 3.18e-3;
using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

Eigen::Quaterniond turned(const Eigen::Quaterniond& q, const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  return angle > 0 ? (Eigen::Quaterniond(Eigen::AngleAxisd(angle, theta / angle)) * q).normalized() : q;
}

// A pair of bodies (or a body and a sphere) evaluated on its own, as the implicit increment does.
struct PairBench {
  std::vector<ShapeModel> shapes;
  RigidBodies bodies;
  std::vector<SphereObstacle> spheres;
  std::vector<PlaneObstacle> planes;
  IncrementStart start;
  ContactParameters parameters;
  PairContacts pair;

  ImplicitPairResult evaluate() const {
    const ImplicitScene scene{&bodies, &shapes, &spheres, &planes, &start, parameters,
                              parameters.normalStiffness(), parameters.tangentialStiffness(), 1e-3, 1e-4};
    ImplicitCandidates candidates;
    ImplicitPairResult out;
    evaluateImplicitPair(scene, pair, NodeContacts{}, candidates, out);
    return out;
  }
  // The generalised forces on a and (for two bodies) b, [F_a; M_a; F_b; M_b], moments about each centroid.
  Vector12 forces() const {
    const ImplicitPairResult r = evaluate();
    Vector12 f = Vector12::Zero();
    f.head<6>() = r.force;
    if (pair.b >= 0) f.tail<6>() = -shiftToPoint(bodies.position[0], bodies.position[1]).transpose() * r.force;
    return f;
  }
  // The same with body `body`'s coordinate k (x, y, z, turn about x, y, z) moved by h.
  Vector12 forcesMoved(int body, int k, double h) {
    const RigidBodies kept = bodies;
    if (k < 3) bodies.position[body][k] += h;
    else bodies.orientation[body] = turned(bodies.orientation[body], h * Eigen::Vector3d::Unit(k - 3));
    const Vector12 f = forces();
    bodies = kept;
    return f;
  }
};

PairBench blockOnBlock(double friction, const Eigen::Vector3d& slip) {
  // An 8 mm block sunk 2 um into a 10 mm one, turned a little, and moved by `slip` over the
  // increment: its edges do not meet the lower block's, so no node sits on a switch of planes.
  const Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(0.8 * kA, 0.8 * kA, kH), 0.25e-3, 0.6e-3);
  PairBench bench;
  for (const Shape& s : bundle.shapes) bench.shapes.push_back(makeShapeModel(s, true, true));
  bench.bodies = makeRigidBodies(bundle.shapes, bundle.bodies, 2500);
  bench.bodies.position[1] += Eigen::Vector3d(0.3e-3, -0.2e-3, -2e-6);
  bench.bodies.orientation[1] = turned(bench.bodies.orientation[1], Eigen::Vector3d(2e-4, -1e-4, 0.01));
  bench.start.position = bench.bodies.position;
  bench.start.orientation = bench.bodies.orientation;
  bench.start.position[1] -= slip;
  bench.parameters.friction = friction;
  bench.pair.a = 0;
  bench.pair.b = 1;
  return bench;
}

// The pair's tangent against -dF/dq by central differences.
void requireTangentIsDerivative(PairBench& bench, int bodies) {
  const ImplicitPairResult r = bench.evaluate();
  REQUIRE(r.contacts.size() > 8);
  const Matrix12 K = pairTangent(r, bench.bodies.position[0], bench.bodies.position[bodies == 2 ? 1 : 0]);
  Matrix12 numeric = Matrix12::Zero();
  for (int body = 0; body < bodies; ++body)
    for (int k = 0; k < 6; ++k) {
      const double h = k < 3 ? 1e-11 : 1e-9;
      numeric.col(6 * body + k) = -(bench.forcesMoved(body, k, h) - bench.forcesMoved(body, k, -h)) / (2 * h);
    }
  const int n = 6 * bodies;
  // Translation rows/columns in N/m, rotation ones scaled by a lever of 5 mm to compare alike.
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(n);
  for (int i = 0; i < n; ++i)
    if (i % 6 >= 3) scale[i] = 1 / 5e-3;
  const Eigen::MatrixXd a = scale.asDiagonal() * K.topLeftCorner(n, n) * scale.asDiagonal();
  const Eigen::MatrixXd b = scale.asDiagonal() * numeric.topLeftCorner(n, n) * scale.asDiagonal();
  INFO("analytic\n" << a << "\nnumeric\n" << b);
  // The terms left out are d / r of those kept (a few 1e-4 here).
  REQUIRE((a - b).cwiseAbs().maxCoeff() <= 2e-3 * a.cwiseAbs().maxCoeff());
}

}  // namespace

TEST_CASE("implicit: a pair's tangent is the derivative of its forces, sticking and sliding, between blocks and under a sphere") {
  SECTION("two blocks, sticking") {
    PairBench bench = blockOnBlock(5.0, Eigen::Vector3d(1e-9, 2e-9, 0));
    REQUIRE(bench.evaluate().tally.sliding == 0);
    requireTangentIsDerivative(bench, 2);
  }
  SECTION("two blocks, sliding") {
    PairBench bench = blockOnBlock(0.3, Eigen::Vector3d(2e-6, 1e-6, 0));
    REQUIRE(bench.evaluate().tally.sliding == static_cast<int>(bench.evaluate().contacts.size()));
    requireTangentIsDerivative(bench, 2);
  }
  SECTION("a block under the sphere, sliding on it") {
    PairBench bench = blockOnBlock(0.3, Eigen::Vector3d::Zero());
    SphereObstacle sphere;
    sphere.radius = 2.5e-3;
    const Eigen::Vector3d top = bench.bodies.position[0] + Eigen::Vector3d(0.4e-3, 0.1e-3, kH / 2);
    sphere.center = top + Eigen::Vector3d(0, 0, sphere.radius - 0.4e-3);
    bench.spheres.push_back(sphere);
    bench.start.sphereCentre = {sphere.center + Eigen::Vector3d(60e-6, 0, 0)};
    bench.pair.b = -1;
    bench.pair.kind = PairKind::Sphere;
    REQUIRE(bench.evaluate().tally.sliding > 0);
    requireTangentIsDerivative(bench, 1);
  }
}

namespace {

// The implicit method converged to `tolerance`.
SolverSettings implicitSettings(double tolerance) {
  SolverSettings s;
  s.method = SolverMethod::Implicit;
  s.implicit.tolerance = tolerance;
  return s;
}

// A soft material (E = 4.2 MPa) sinks the blocks 1e-7 m: double coordinates of 3 mm resolve that
// to 1e-11 of itself (1e-10 m at 4.2 GPa only to 1e-9).
const double kSoft = 4.2e6;

}  // namespace

TEST_CASE("implicit: a block resting on a fixed block sinks m g / (k_n A), on exact planes, in a dozen increments") {
  ContactParameters p;
  p.youngsModulus = kSoft;
  const SolverSettings s = implicitSettings(1e-10);
  const Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3);
  World world(bundle.shapes, bundle.bodies, p, s);
  const double z0 = world.bodies().position[1].z();
  // The first increments are short (inertia holds it while it sinks) and each doubles the next:
  // after 12 they are 1e4 explicit steps long and it is at rest.
  for (int i = 0; i < 12; ++i) world.step();
  const double mg = world.bodies().mass[1] * 9.81;
  REQUIRE(world.contactForces()[1].z() == Approx(mg).epsilon(1e-9));
  REQUIRE(z0 - world.bodies().position[1].z() == Approx(mg / (p.normalStiffness() * kA * kA)).epsilon(1e-6));
  REQUIRE(world.implicitCounts().iterations < 60);
}

TEST_CASE("implicit: a block on a tilted block sticks below atan(mu) and slides above, as g (sin - mu cos) t^2 / 2") {
  ContactParameters p;
  p.friction = 0.3;
  const double critical = std::atan(p.friction);
  for (double offset : {-2.0, 3.0}) {
    const double theta = critical + offset * M_PI / 180;
    INFO("tilt " << theta * 180 / M_PI << " deg");
    SolverSettings s;
    s.method = SolverMethod::Implicit;
    s.implicit.maxIncrement = 1e-3;  // s: 100 increments over the 0.1 s
    s.gravity = 9.81 * Eigen::Vector3d(std::sin(theta), 0, -std::cos(theta));
    const Bundle bundle = test::stackedBlocks(makeBox(4 * kA, 2 * kA, kH), makeBox(kA, kA, kH), 0.25e-3, 1.0e-3);
    World world(bundle.shapes, bundle.bodies, p, s);
    world.step();  // the first increment: settled (or sliding already)
    const double x0 = world.bodies().position[1].x(), v0 = world.bodies().velocity[1].x(), t0 = world.time();
    const long n0 = world.stepCount();
    while (world.time() < t0 + 0.1 - 1e-9) world.step();
    const double slip = world.bodies().position[1].x() - x0, t = world.time() - t0;
    if (offset < 0) {
      REQUIRE(std::abs(slip) < 1e-8);  // elastic tangential deflection only
    } else {
      // Backward Euler over N increments of dt from v0: v0 t + a dt^2 N (N + 1) / 2 (the exact
      // motion's a t^2 / 2 times 1 + 1/N).
      const double a = 9.81 * (std::sin(theta) - p.friction * std::cos(theta));
      const double N = static_cast<double>(world.stepCount() - n0), dt = t / N;
      REQUIRE(slip == Approx(v0 * t + a * dt * dt * N * (N + 1) / 2).epsilon(2e-3));
      REQUIRE(slip > 0.9 * 0.5 * a * t * t);
    }
  }
}

TEST_CASE("implicit: every free body of a settled 3 x 3 slab is in balance to 1e-9 of its weight") {
  ContactParameters p;
  p.youngsModulus = kSoft;
  const SolverSettings s = implicitSettings(1e-11);
  const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  World world(slab.shapes, slab.bodies, p, s);
  for (int i = 0; i < 12; ++i) world.step();
  int free = 0;
  for (std::size_t i = 0; i < world.bodies().size(); ++i) {
    if (world.bodies().fixed[i]) continue;
    ++free;
    const double weight = world.bodies().mass[i] * 9.81;
    const Eigen::Vector3d total = world.contactForces()[i] + world.bodies().mass[i] * s.gravity;
    REQUIRE(total.norm() <= 1e-9 * weight);
    REQUIRE(world.contactTorques()[i].norm() <= 1e-9 * weight * kA);
  }
  REQUIRE(free == 1);
}

TEST_CASE("implicit: a World given another's state mid-loading goes on bit-identically") {
  ContactParameters p;
  SolverSettings s;
  s.method = SolverMethod::Implicit;
  const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  World first(slab.shapes, slab.bodies, p, s);
  first.step();
  SphereObstacle indenter;
  indenter.radius = 2.5e-3;
  indenter.center = Eigen::Vector3d(0.3e-3, -0.2e-3, first.bodies().position[4].z() + kH / 2 + indenter.radius);
  indenter.velocity = Eigen::Vector3d(0, 0, -0.03);
  first.addSphere(indenter);
  for (int i = 0; i < 15; ++i) first.step();
  World second(slab.shapes, slab.bodies, p, s);
  second.restore(first.state());
  for (int i = 0; i < 15; ++i) {
    first.step();
    second.step();
  }
  REQUIRE(first.sphereReaction(0).z() > 1.0);  // loaded: newtons on the sphere
  for (std::size_t i = 0; i < first.bodies().size(); ++i) {
    REQUIRE(first.bodies().position[i] == second.bodies().position[i]);
    REQUIRE(first.bodies().orientation[i].coeffs() == second.bodies().orientation[i].coeffs());
  }
  REQUIRE(first.sphereReaction(0) == second.sphereReaction(0));
  REQUIRE(first.implicitCounts().iterations == second.implicitCounts().iterations);
  REQUIRE(first.time() == second.time());
}
