// The blended contact area (solver/blended_area.h, docs/physics.md "Contact area"): the nearest
// plane's projection away from edges, continuous where the nearest plane switches, its slope the
// depth times its gradient; and the energy balance it exists for: moving a block over another's
// edge, the contact forces' work equals the stored energy's loss, in the explicit step's float
// law and in the implicit method's double one, where the nearest plane's projection loses it.
#include "geometry/block_generators.h"
#include "solver/blended_area.h"
#include "solver/implicit_contacts.h"
#include "solver/planes_in_frame.h"
#include "solver/world.h"
#include "solver/world_internals.h"
#include "tests/fixtures/scenes.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

using namespace tessera;

namespace {

const double kA = 10e-3, kH = 3.18e-3;

// The lower box's planes (its frame: centred at the origin).
PlanesInFrame boxPlanes() {
  const ShapeModel box = makeShapeModel(test::stackedBlocks(makeBox(kA, kA, kH), makeBox(kA, kA, kH), 0.25e-3, 0.6e-3).shapes[0], true, true);
  REQUIRE(box.planes.size() == 6);
  return PlanesInFrame(box.planes, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
}

BlendedArea<double> areaAt(const PlanesInFrame& planes, const Eigen::Vector3d& p, const Eigen::Vector3d& areaNormal) {
  int best;
  const double phi = planes.phi(p, best);
  BlendedArea<double> out;
  blendedArea(planes, p.x(), p.y(), p.z(), phi, planes.nx[best], planes.ny[best], planes.nz[best], areaNormal.x(),
              areaNormal.y(), areaNormal.z(), 0.5, out);
  return out;
}

}  // namespace

TEST_CASE("blended area: the nearest plane's projection away from edges and continuous where the nearest plane switches") {
  const PlanesInFrame planes = boxPlanes();
  const double A = 0.36e-6, d = 20e-6;
  // A node of a block above, its outward normal tilted 0.1 rad from -z towards +x.
  const Eigen::Vector3d n = Eigen::Vector3d(std::sin(0.1), 0, -std::cos(0.1)), area = A * n;
  SECTION("far from every edge: half the area projected on the top face, no slope") {
    const BlendedArea<double> b = areaAt(planes, Eigen::Vector3d(1e-3, 2e-3, kH / 2 - d), area);
    CHECK(b.area == 0.5 * A * std::cos(0.1));
    CHECK(b.slopeX == 0);
    CHECK(b.slopeY == 0);
    CHECK(b.slopeZ == 0);
  }
  SECTION("across the top edge at x = a/2, through the switch to the side face (projection 0)") {
    double last = -1, largestStep = 0;
    for (int i = 0; i < 400; ++i) {
      const double x = kA / 2 - 3 * d + i * 3 * d / 400;  // from 3 d inside the side face to just inside it
      const double value = areaAt(planes, Eigen::Vector3d(x, 0, kH / 2 - d), area).area;
      if (last >= 0) largestStep = std::max(largestStep, std::abs(value - last));
      last = value;
    }
    CHECK(last == 0);  // nearest the side face, which the node's normal does not face
    // 400 steps over a change of 0.5 A cos 0.1: a jump would be the whole of it.
    CHECK(largestStep < 0.5 * A * std::cos(0.1) / 50);
  }
  SECTION("the slope is the depth times the area's gradient (central differences), in the blend") {
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(kA / 2 - 1.3 * d, 0.2e-3, kH / 2 - d),
                                     Eigen::Vector3d(kA / 2 - 0.8 * d, -1e-3, kH / 2 - 1.2 * d),
                                     Eigen::Vector3d(kA / 2 - 1.5 * d, kA / 2 - 1.2 * d, kH / 2 - d)}) {
      const BlendedArea<double> b = areaAt(planes, p, area);
      int best;
      const double depth = -planes.phi(p, best);
      const double h = 1e-10;
      Eigen::Vector3d numeric;
      for (int k = 0; k < 3; ++k)
        numeric[k] = depth * (areaAt(planes, p + h * Eigen::Vector3d::Unit(k), area).area -
                              areaAt(planes, p - h * Eigen::Vector3d::Unit(k), area).area) / (2 * h);
      INFO("at " << p.transpose() << ": slope " << b.slopeX << " " << b.slopeY << " " << b.slopeZ << ", numeric " << numeric.transpose());
      REQUIRE(numeric.norm() > 0.01 * A);  // in the blend
      CHECK((Eigen::Vector3d(b.slopeX, b.slopeY, b.slopeZ) - numeric).norm() <= 1e-5 * numeric.norm());
    }
  }
}

namespace {

// A frictionless 8 mm box sunk 20 um into a fixed 10 mm one, overhanging its edge at x = 5 mm,
// moved along a straight path of pose (0.7 mm over the edge, 5 um deeper, turned 1e-3 rad about
// y): the contact forces' work on it, by the trapezoidal rule over `steps` poses, and the change
// of the stored energy. forcesAt(position, orientation, force, torque) returns the stored energy.
struct PathBalance {
  double work = 0, stored = 0, initial = 0;  // J: the forces' work, the stored energy's change, and at the start
};
using ForcesAt = std::function<double(const Eigen::Vector3d&, const Eigen::Quaterniond&, Eigen::Vector3d&, Eigen::Vector3d&)>;

PathBalance balanceOverEdge(const Eigen::Vector3d start, const Eigen::Quaterniond q0, const ForcesAt& forcesAt) {
  const Eigen::Vector3d p0 = start + Eigen::Vector3d(5.5e-3, 0.3e-3, -20e-6), move(0.7e-3, 0.05e-3, -5e-6);
  const Eigen::Vector3d turn(0.2e-3, 1e-3, 0);
  const int steps = 1400;
  PathBalance b;
  Eigen::Vector3d f0, t0;
  const double e0 = forcesAt(p0, q0, f0, t0);
  double e = e0;
  for (int i = 1; i <= steps; ++i) {
    const double s = static_cast<double>(i) / steps;
    const Eigen::Quaterniond q = Eigen::Quaterniond(Eigen::AngleAxisd(s * turn.norm(), turn.normalized())) * q0;
    Eigen::Vector3d f, t;
    e = forcesAt(p0 + s * move, q, f, t);
    b.work += 0.5 * (f0 + f).dot(move / steps) + 0.5 * (t0 + t).dot(turn / steps);
    f0 = f;
    t0 = t;
  }
  b.stored = e - e0;
  b.initial = e0;
  return b;
}

// Blended: the work is the stored energy's loss to 1e-3 of the energy stored (the trapezoidal
// rule's error where a node's nearest plane switches and its force turns: measured 2e-4). The
// nearest plane's projection loses a quarter of it on this path (measured 0.24): what shows that
// the path crosses the switches the blend is for.
void requireBalance(const PathBalance& b, bool blended) {
  INFO("work " << b.work << " J, stored " << b.stored << " J, at the start " << b.initial << " J");
  REQUIRE(b.initial > 1e-3);
  const double leak = std::abs(b.work + b.stored) / b.initial;
  if (blended) CHECK(leak <= 1e-3);
  else CHECK(leak >= 0.1);
}

}  // namespace

TEST_CASE("blended area: over an edge the contact forces' work is the stored energy's loss (explicit and implicit)") {
  const Bundle bundle = test::stackedBlocks(makeBox(kA, kA, kH), makeBox(0.8 * kA, 0.8 * kA, kH), 0.25e-3, 0.6e-3);
  for (const ContactArea rule : {ContactArea::Blended, ContactArea::Nearest}) {
    const bool blended = rule == ContactArea::Blended;
    INFO((blended ? "blended" : "nearest"));
    ContactParameters p;
    p.friction = 0;
    p.area = rule;
    SECTION(std::string("explicit step ") + (blended ? "blended" : "nearest")) {
      SolverSettings s;
      s.exactConvexLevelSets = true;
      s.threads = 1;
      World world(bundle.shapes, bundle.bodies, p, s);
      world.step();
      const PathBalance b = balanceOverEdge(world.bodies().position[1], world.bodies().orientation[1],
                                            [&](const Eigen::Vector3d& x, const Eigen::Quaterniond& q, Eigen::Vector3d& f, Eigen::Vector3d& t) {
                                              world.setPose(1, x, q);
                                              f = t = Eigen::Vector3d::Zero();
                                              double stored = 0;
                                              for (const PairContacts& pair : WorldInternals::pairs(world)) {
                                                if (pair.b != 1) continue;
                                                f += pair.forceB;
                                                t += pair.torqueB;
                                                stored += pair.tally.elastic;
                                              }
                                              return stored;
                                            });
      requireBalance(b, blended);
    }
    SECTION(std::string("implicit ") + (blended ? "blended" : "nearest")) {
      std::vector<ShapeModel> shapes;
      for (const Shape& shape : bundle.shapes) shapes.push_back(makeShapeModel(shape, true, true));
      RigidBodies bodies = makeRigidBodies(bundle.shapes, bundle.bodies, 2500);
      IncrementStart start;
      const std::vector<SphereObstacle> spheres;
      const std::vector<PlaneObstacle> planes;
      PairContacts pair;
      pair.a = 0;
      pair.b = 1;
      const PathBalance b = balanceOverEdge(bodies.position[1], bodies.orientation[1],
                                            [&](const Eigen::Vector3d& x, const Eigen::Quaterniond& q, Eigen::Vector3d& f, Eigen::Vector3d& t) {
                                              bodies.position[1] = x;
                                              bodies.orientation[1] = q;
                                              start.position = bodies.position;
                                              start.orientation = bodies.orientation;
                                              const ImplicitScene scene{&bodies, &shapes, &spheres, &planes, &start, p,
                                                                        p.normalStiffness(), p.tangentialStiffness(), 1e-3, 1e-4};
                                              ImplicitCandidates candidates;
                                              ImplicitPairResult out;
                                              evaluateImplicitPair(scene, pair, NodeContacts{}, candidates, out);
                                              // On b: -F_a, and -(M_a + (c_a - c_b) x F_a) about b's centroid.
                                              f = -out.force.head<3>();
                                              t = -(out.force.tail<3>() + (bodies.position[0] - x).cross(Eigen::Vector3d(out.force.head<3>())));
                                              return out.tally.elastic;
                                            });
      requireBalance(b, blended);
    }
  }
}
