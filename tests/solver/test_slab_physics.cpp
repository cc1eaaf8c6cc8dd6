// Solver physics on small slabs of the default block: scaling with E, convergence under node
// refinement (and the non-convergence of a per-node stiffness), the indenter's contact, and
// determinism.
#include "geometry/block_generators.h"
#include "solver/world.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace tessera;

namespace {

constexpr int kCentre = 4;       // r1c1 in a 3 x 3 slab
constexpr double kTop = 1.59e-3; // top face of a block, m
constexpr double kRadius = 2.5e-3;

struct Curve {
  std::vector<double> delta;  // m, indenter travel
  std::vector<double> load;   // N, P
  std::vector<double> drop;   // m, downward displacement of the loaded block
};

// Indents the centre block of `slab` at constant speed until the indenter has travelled deltaMax.
Curve indent(const Bundle& slab, const ContactParameters& p, const SolverSettings& s, double speed, double deltaMax) {
  World world(slab.shapes, slab.bodies, p, s);
  SphereObstacle indenter;
  indenter.radius = kRadius;
  indenter.center = Eigen::Vector3d(0, 0, kTop + kRadius);
  indenter.velocity = Eigen::Vector3d(0, 0, -speed);
  world.addSphere(indenter);
  const double z0 = world.bodies().position[kCentre].z();
  Curve c;
  while (speed * world.time() < deltaMax) {
    world.step();
    c.delta.push_back(speed * world.time());
    c.load.push_back(world.sphereReaction(0).z());
    c.drop.push_back(z0 - world.bodies().position[kCentre].z());
  }
  return c;
}

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  const auto it = std::lower_bound(x.begin(), x.end(), at);
  if (it == x.begin()) return y.front();
  if (it == x.end()) return y.back();
  const std::size_t i = it - x.begin();
  const double w = (at - x[i - 1]) / (x[i] - x[i - 1]);
  return (1 - w) * y[i - 1] + w * y[i];
}

SolverSettings quasiStatic() {
  SolverSettings s;
  s.gravity.setZero();
  s.localDamping = 0.5;  // rate-independent: does not break the scaling with E
  return s;
}

}  // namespace

TEST_CASE("scaling with E: at 4E with speed x2 and time step /2, P/E is the same to the last bit") {
  // Without gravity the model has no length or force scale besides E: at 4E with twice the speed
  // and half the step every force is 4x, every velocity 2x and every position the same. Powers of
  // two scale floating-point arithmetic exactly, so the curves must agree bit for bit.
  const Bundle slab = test::smallSlab(3, 0.25e-3, 1.0e-3);
  ContactParameters p;
  const double speed = 2e-3, deltaMax = 0.03e-3;
  SolverSettings s = quasiStatic();
  s.timeStep = World(slab.shapes, slab.bodies, p, s).automaticTimeStep();
  const Curve soft = indent(slab, p, s, speed, deltaMax);
  ContactParameters stiff = p;
  stiff.youngsModulus = 4 * p.youngsModulus;
  s.timeStep /= 2;
  const Curve hard = indent(slab, stiff, s, speed * 2, deltaMax);
  REQUIRE(soft.load.size() == hard.load.size());
  double largest = 0, worst = 0;
  for (std::size_t i = 0; i < soft.load.size(); ++i) {
    largest = std::max(largest, std::abs(soft.load[i] / p.youngsModulus));
    worst = std::max(worst, std::abs(soft.load[i] / p.youngsModulus - hard.load[i] / stiff.youngsModulus));
  }
  INFO("largest P/E " << largest << " m^2, worst difference " << worst);
  REQUIRE(largest > 0);
  REQUIRE(worst == 0);

  SECTION("at one slow speed and each E's automatic step, P(delta)/E agrees within 1 %") {
    SolverSettings automatic = quasiStatic();
    const Curve a = indent(slab, p, automatic, speed, deltaMax);
    const Curve b = indent(slab, stiff, automatic, speed, deltaMax);
    for (double delta = 0.5 * deltaMax; delta <= deltaMax * 0.999; delta += 0.1 * deltaMax) {
      const double pa = interpolate(a.delta, a.load, delta) / p.youngsModulus;
      const double pb = interpolate(b.delta, b.load, delta) / stiff.youngsModulus;
      INFO("delta " << delta << ": P/E " << pa << " vs " << pb);
      REQUIRE(pb == Approx(pa).epsilon(0.01));
    }
  }
}

TEST_CASE("node refinement: resting penetration and slab stiffness change by < 2 % from s to s/2") {
  ContactParameters soft;
  soft.youngsModulus = 4.2e6;
  SolverSettings settle;
  settle.localDamping = 0.7;
  const TriangleMesh block = makePlanarBlock(10e-3, 3.18e-3, 5 * M_PI / 180);
  TriangleMesh flipped = block;
  for (auto& v : flipped.vertices) v = Eigen::Vector3d(v.x(), -v.y(), -v.z());
  double penetration[2];
  for (int level = 0; level < 2; ++level) {
    const Bundle b = test::stackedBlocks(block, flipped, 0.25e-3, 0.6e-3 / (1 << level));
    World world(b.shapes, b.bodies, soft, settle);
    const double z0 = world.bodies().position[1].z();
    for (int i = 0; i < 3000; ++i) world.step();
    penetration[level] = z0 - world.bodies().position[1].z();
  }
  REQUIRE(penetration[1] == Approx(penetration[0]).epsilon(0.02));

  // Slab stiffness: load over the loaded block's drop, at the end of a short indentation.
  ContactParameters p;
  const double speed = 6e-3, deltaMax = 0.03e-3;
  double stiffness[2], perNode[2];
  for (int level = 0; level < 2; ++level) {
    const double spacing = 0.6e-3 / (1 << level);
    const Bundle slab = test::smallSlab(3, 0.25e-3, spacing);
    const Curve traction = indent(slab, p, quasiStatic(), speed, deltaMax);
    stiffness[level] = traction.load.back() / traction.drop.back();
    // The same with a per-node stiffness fixed at the coarse level's mean node area.
    ContactParameters nodes = p;
    nodes.perNodeStiffness = p.normalStiffness() * 0.6e-3 * 0.6e-3;
    const Curve naive = indent(slab, nodes, quasiStatic(), speed, deltaMax);
    perNode[level] = naive.load.back() / naive.drop.back();
  }
  INFO("traction: " << stiffness[0] << " -> " << stiffness[1] << " N/m; per node: " << perNode[0] << " -> " << perNode[1]);
  REQUIRE(stiffness[1] == Approx(stiffness[0]).epsilon(0.02));
  // Four times the nodes, each as stiff as before: the slab comes out about four times stiffer.
  REQUIRE(perNode[1] / perNode[0] > 2.5);
}

TEST_CASE("the indenter's contact converges with node spacing to the traction integral") {
  // A sphere of radius R pressed by depth w into a flat face: with d = R - rho and cos(a) =
  // (R - w) / rho, rho = sqrt(r^2 + (R - w)^2), the law gives P = k_n integral d cos^2(a) 2 pi r dr.
  const double w = 0.2e-3;
  ContactParameters p;
  const double R = kRadius;
  const double rc = std::sqrt(R * R - (R - w) * (R - w));
  double exact = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double r = (i + 0.5) * rc / n;
    const double rho = std::hypot(r, R - w);
    exact += p.normalStiffness() * (R - rho) * std::pow((R - w) / rho, 2) * 2 * M_PI * r * rc / n;
  }
  double error[3];
  for (int level = 0; level < 3; ++level) {
    Bundle b = test::stackedBlocks(makeBox(10e-3, 10e-3, 3.18e-3), makeBox(1e-3, 1e-3, 1e-3), 0.25e-3,
                                   0.6e-3 / (1 << level));
    b.bodies.resize(1);  // the fixed block alone
    SolverSettings s;
    s.maxPenetration = 1e-3;  // pressed in deliberately
    World world(b.shapes, b.bodies, p, s);
    SphereObstacle sphere;
    sphere.radius = R;
    sphere.center = Eigen::Vector3d(0.1e-3, 0.2e-3, kTop + R - w);  // off any node pattern's centre
    world.addSphere(sphere);
    world.step();
    error[level] = world.sphereReaction(0).z() / exact - 1;
  }
  INFO("relative errors at 0.6, 0.3, 0.15 mm: " << error[0] << ", " << error[1] << ", " << error[2]);
  REQUIRE(std::abs(error[2]) < 0.02);
  REQUIRE(std::abs(error[2]) < std::abs(error[0]));
}

TEST_CASE("determinism: the same run gives bit-identical states, for one thread or two") {
  const Bundle slab = test::smallSlab(3, 0.25e-3, 0.6e-3);
  const auto run = [&](int threads) {
    SolverSettings s;
    s.threads = threads;
    World world(slab.shapes, slab.bodies, ContactParameters{}, s);
    SphereObstacle indenter;
    indenter.center = Eigen::Vector3d(0.2e-3, 0.1e-3, kTop + kRadius);
    indenter.velocity = Eigen::Vector3d(0, 0, -0.05);
    world.addSphere(indenter);
    for (int i = 0; i < 400; ++i) world.step();
    return world.bodies();
  };
  const RigidBodies a = run(2), b = run(2), c = run(1);
  for (std::size_t i = 0; i < a.size(); ++i) {
    REQUIRE(a.position[i] == b.position[i]);
    REQUIRE(a.velocity[i] == b.velocity[i]);
    REQUIRE(a.orientation[i].coeffs() == b.orientation[i].coeffs());
    REQUIRE(a.angularMomentum[i] == b.angularMomentum[i]);
    REQUIRE(a.position[i] == c.position[i]);
    REQUIRE(a.angularMomentum[i] == c.angularMomentum[i]);
  }
  REQUIRE(a.position[kCentre] != slab.bodies[kCentre].position);  // something happened
}
