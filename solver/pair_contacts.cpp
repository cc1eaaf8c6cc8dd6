#include "solver/pair_contacts.h"

#include "solver/contact_law.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tessera {

namespace {

// The body-frame box of `other` (a box in its own frame, turned by qO and moved to pO) as seen in
// the frame of a body at (qM, pM): the region where M's nodes can touch it.
Eigen::AlignedBox3d regionInFrame(const Eigen::AlignedBox3d& otherBox, const Eigen::Quaterniond& qO,
                                  const Eigen::Vector3d& pO, const Eigen::Quaterniond& qM, const Eigen::Vector3d& pM) {
  const Eigen::Matrix3d R = (qM.conjugate() * qO).toRotationMatrix();
  const Eigen::Vector3d centre = R * otherBox.center() + qM.conjugate() * (pO - pM);
  const Eigen::Vector3d half = R.cwiseAbs() * (0.5 * otherBox.sizes());
  return Eigen::AlignedBox3d(centre - half, centre + half);
}

// A rigid motion as the contact law needs it: centroid, velocity, angular velocity (world).
struct Motion {
  Eigen::Vector3d position, velocity, angularVelocity;
  Eigen::Vector3d velocityAt(const Eigen::Vector3d& x) const { return velocity + angularVelocity.cross(x - position); }
};

Motion motionOf(const RigidBodies& bodies, int i) {
  return {bodies.position[i], bodies.velocity[i], bodies.angularVelocity(i)};
}

// Merge cursor over the previous step's contacts (sorted by key): the contact of a node that was
// in contact, or none.
struct History {
  const std::vector<NodeContact>& previous;
  std::size_t next = 0;
  const NodeContact* find(std::uint32_t key) {
    while (next < previous.size() && previous[next].key < key) ++next;
    return next < previous.size() && previous[next].key == key ? &previous[next] : nullptr;
  }
};

// Shared per-node work: contact law, history, and the force on body a with its torque about a's
// centroid; b's follow in finish() (equal and opposite force; torque moved by the short lever
// between the two centroids, no cancellation against moments about a far origin).
struct Accumulator {
  const ContactScene& scene;
  PairContacts& pair;
  History history;
  Eigen::Vector3d centreA;  // m, body a's centroid
  double kn, kt;            // N/m^3, this pair's stiffnesses
  double weight = 0.0;      // sum of normal forces, for forcePoint
  Eigen::Vector3d normalSum = Eigen::Vector3d::Zero();  // N, the normal parts of the forces on a

  // One node at world x of the body moving with `node`, inside the other side (moving with
  // `other`) by depth along `normal` (world, out of the other side).
  void add(std::uint32_t key, const Eigen::Vector3d& x, const Eigen::Vector3d& nodeNormal, double area,
           const Eigen::Vector3d& normal, double depth, const Motion& node, const Motion& other, bool nodeBodyIsA) {
    // Effective area: the node's area projected on the contact plane (docs/physics.md).
    const double projection = -nodeNormal.dot(normal);
    const NodeContact* before = history.find(key);
    if (projection <= 0) {
      // Inside, but facing away from the contact normal: no force. Kept with zero area, so that
      // the energy this cut takes (and a return gives back) is booked below.
      if (before) pair.tally.projection += before->energy;
      pair.contacts.push_back({key, Eigen::Vector3d::Zero(), 0.0, 0.0});
      return;
    }
    const NodeContactInput input{normal, depth, area * projection, node.velocityAt(x) - other.velocityAt(x)};
    Eigen::Vector3d spring = before ? before->spring : Eigen::Vector3d::Zero();
    double stored;
    const Eigen::Vector3d f = contactForce(scene.parameters, kn, kt, input, spring, stored, scene.dt, pair.tally);
    // Stored energy is proportional to the area: what the change of area alone removed (a contact
    // coming back from a cut, area 0, brings all of its energy back).
    if (before && before->area == 0) pair.tally.projection -= stored;
    else if (before && scene.parameters.perNodeStiffness <= 0) pair.tally.projection += stored * (before->area / input.area - 1);
    pair.contacts.push_back({key, spring, stored, input.area});
    pair.maxDepth = std::max(pair.maxDepth, depth);
    const double normalForce = f.dot(normal);  // f_n: the tangential part is normal to n
    pair.forcePoint += normalForce * x;
    weight += normalForce;
    const Eigen::Vector3d fA = nodeBodyIsA ? f : Eigen::Vector3d(-f);
    pair.forceA += fA;
    normalSum += (nodeBodyIsA ? normalForce : -normalForce) * normal;
    pair.torqueA += (x - centreA).cross(fA);
  }

  // Newton's third law: on b, -F_A at the same points: tau_B = -(tau_A + (c_A - c_B) x F_A).
  void finish() {
    pair.normalForceA = normalSum;
    pair.forceB = -pair.forceA;
    if (pair.b >= 0) pair.torqueB = -(pair.torqueA + (centreA - scene.bodies->position[pair.b]).cross(pair.forceA));
    if (weight > 0) pair.forcePoint /= weight;
  }
};

// Visits the nodes of one side (key = side << 31 | rank) that can touch: the pair's candidates
// of that side or, when they are being rebuilt, every node in `region`, keeping as candidates
// those with phi below the band. `test(key)` returns the node's phi.
template <class Test>
void visitSide(const NodeBins& nodes, const Eigen::AlignedBox3d& region, std::uint32_t side, bool rebuild,
               double band, PairContacts& pair, Test&& test) {
  if (rebuild) {
    nodes.forEachNodeIn(region, [&](int rank) {
      const std::uint32_t key = side << 31 | static_cast<std::uint32_t>(rank);
      if (test(key) < band) pair.candidates.push_back(key);
    });
    return;
  }
  const auto first = std::lower_bound(pair.candidates.begin(), pair.candidates.end(), side << 31);
  const auto last = side == 0 ? std::lower_bound(first, pair.candidates.end(), 1u << 31) : pair.candidates.end();
  for (auto k = first; k != last; ++k) test(*k);
}

constexpr std::uint32_t kRankMask = (1u << 31) - 1;

// The face planes of a convex body expressed in another body's frame (x_O = R x_M + t), in hot
// arrays: phi(p) = max_f (n_f . p - d_f), the exact level set of a convex polyhedron (1-Lipschitz),
// evaluated without transforming p.
struct PlanesInFrame {
  static constexpr int kMax = 64;  // ConvexFitOptions::maxPlanes' default
  std::array<Eigen::Vector3d, kMax> normal;
  std::array<double, kMax> offset;
  int count = 0;

  PlanesInFrame(const std::vector<FacePlane>& planes, const Eigen::Matrix3d& R, const Eigen::Vector3d& t)
      : count(static_cast<int>(std::min<std::size_t>(planes.size(), kMax))) {
    for (int f = 0; f < count; ++f) {
      normal[f] = R.transpose() * planes[f].normal;
      offset[f] = planes[f].offset - planes[f].normal.dot(t);
    }
  }
  double phi(const Eigen::Vector3d& p, int& best) const {
    best = 0;
    double value = normal[0].dot(p) - offset[0];
    for (int f = 1; f < count; ++f) {
      const double v = normal[f].dot(p) - offset[f];
      if (v > value) {
        value = v;
        best = f;
      }
    }
    return value;
  }
};

}  // namespace

namespace {

// Clears the pair's last evaluation (its contacts become the history) and says whether its
// candidate nodes are to be rebuilt.
bool beginEvaluation(PairContacts& pair) {
  std::swap(pair.contacts, pair.previous);
  pair.contacts.clear();
  pair.forceA = pair.torqueA = pair.forceB = pair.torqueB = pair.normalForceA = pair.forcePoint = Eigen::Vector3d::Zero();
  pair.tally = ContactTally{};
  pair.maxDepth = 0.0;
  pair.evaluations = 0;
  const bool rebuild = !pair.candidatesValid;
  if (rebuild) pair.candidates.clear();
  pair.candidatesValid = true;
  return rebuild;
}

// A body's nodes (full area) against an analytic obstacle moving as `other`; phiAndNormal(x, n)
// gives phi at a world point and, inside, the obstacle's outward normal.
template <class PhiAndNormal>
void visitObstacle(const ContactScene& scene, PairContacts& pair, Accumulator& acc, bool rebuild,
                   const Eigen::AlignedBox3d& region, const Motion& other, PhiAndNormal&& phiAndNormal) {
  const RigidBodies& bodies = *scene.bodies;
  const int m = pair.a;
  const ShapeModel& sm = (*scene.shapes)[bodies.shape[m]];
  const Eigen::Matrix3d RM = bodies.orientation[m].toRotationMatrix();
  const Motion node = motionOf(bodies, m);
  visitSide(sm.nodes, region, 0, rebuild, scene.candidateBand, pair, [&](std::uint32_t key) {
    ++pair.evaluations;
    const Eigen::Vector3d x = RM * sm.nodes.position[key] + node.position;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    const double phi = phiAndNormal(x, normal);
    if (phi < 0) acc.add(key, x, RM * sm.nodes.normal[key], sm.nodes.area[key], normal, -phi, node, other, true);
    return phi;
  });
  acc.finish();
}

}  // namespace

void evaluatePair(const ContactScene& scene, PairContacts& pair) {
  switch (pair.kind) {
    case PairKind::Bodies: return evaluateBodyPair(scene, pair);
    case PairKind::Sphere: return evaluateSpherePair(scene, pair);
    case PairKind::Plane: return evaluatePlanePair(scene, pair);
  }
}

void evaluateBodyPair(const ContactScene& scene, PairContacts& pair) {
  const bool rebuild = beginEvaluation(pair);
  Accumulator acc{scene, pair, History{pair.previous}, scene.bodies->position[pair.a], scene.kn, scene.kt};
  const RigidBodies& bodies = *scene.bodies;
  const auto& shapes = *scene.shapes;
  for (std::uint32_t side = 0; side < 2; ++side) {
    const int m = side == 0 ? pair.a : pair.b, o = side == 0 ? pair.b : pair.a;
    const ShapeModel& sm = shapes[bodies.shape[m]];
    const ShapeModel& so = shapes[bodies.shape[o]];
    const Eigen::Matrix3d RM = bodies.orientation[m].toRotationMatrix(), RO = bodies.orientation[o].toRotationMatrix();
    const Eigen::Matrix3d toO = RO.transpose() * RM;  // M body -> O body
    const Eigen::Vector3d shift = RO.transpose() * (bodies.position[m] - bodies.position[o]);
    const Motion node = motionOf(bodies, m), other = motionOf(bodies, o);
    // Only nodes inside the other body's box (and band) can be inside the other body.
    Eigen::AlignedBox3d region;
    if (rebuild) {
      region = regionInFrame(so.nodes.box, bodies.orientation[o], other.position, bodies.orientation[m], node.position);
      region.min().array() -= scene.candidateBand;
      region.max().array() += scene.candidateBand;
    }
    if (!so.planes.empty()) {
      // A convex other side: its planes moved into M's frame once, n' = toO^T n, d' = d - n . shift,
      // so that a candidate is tested as it is: phi = max_f (n'_f . p - d'_f).
      const PlanesInFrame planes(so.planes, toO, shift);
      visitSide(sm.nodes, region, side, rebuild, scene.candidateBand, pair, [&](std::uint32_t key) {
        ++pair.evaluations;
        const int rank = static_cast<int>(key & kRankMask);
        const Eigen::Vector3d& p = sm.nodes.position[rank];
        int best;
        const double phi = planes.phi(p, best);
        if (phi < 0)
          acc.add(key, RM * p + node.position, RM * sm.nodes.normal[rank], 0.5 * sm.nodes.area[rank],
                  RM * planes.normal[best], -phi, node, other, side == 0);
        return phi;
      });
      continue;
    }
    visitSide(sm.nodes, region, side, rebuild, scene.candidateBand, pair, [&](std::uint32_t key) {
      ++pair.evaluations;
      const int rank = static_cast<int>(key & kRankMask);
      const Eigen::Vector3d xO = toO * sm.nodes.position[rank] + shift;
      Eigen::Vector3d normalO = Eigen::Vector3d::Zero();
      const double phi = so.meshLevelSet(xO, normalO);
      if (phi < 0)
        acc.add(key, RO * xO + other.position, RM * sm.nodes.normal[rank], 0.5 * sm.nodes.area[rank], RO * normalO,
                -phi, node, other, side == 0);
      return phi;
    });
  }
  acc.finish();
}

void evaluateSpherePair(const ContactScene& scene, PairContacts& pair) {
  const bool rebuild = beginEvaluation(pair);
  const SphereObstacle& sphere = (*scene.spheres)[-1 - pair.b];
  Accumulator acc{scene, pair, History{pair.previous}, scene.bodies->position[pair.a],
                  scene.kn * sphere.stiffnessFactor, scene.kt * sphere.stiffnessFactor};
  const Eigen::Vector3d& position = scene.bodies->position[pair.a];
  const Eigen::Vector3d centre = scene.bodies->orientation[pair.a].conjugate() * (sphere.center - position);
  const double reach = sphere.radius + scene.candidateBand;
  visitObstacle(scene, pair, acc, rebuild, Eigen::AlignedBox3d(centre.array() - reach, centre.array() + reach),
                Motion{sphere.center, sphere.velocity, Eigen::Vector3d::Zero()},
                [&](const Eigen::Vector3d& x, Eigen::Vector3d& normal) {
                  const double phi = sphere.phi(x);
                  if (phi < 0) normal = sphere.normal(x);
                  return phi;
                });
}

void evaluatePlanePair(const ContactScene& scene, PairContacts& pair) {
  const bool rebuild = beginEvaluation(pair);
  const PlaneObstacle& plane = (*scene.planes)[-1 - pair.b - static_cast<int>(scene.spheres->size())];
  Accumulator acc{scene, pair, History{pair.previous}, scene.bodies->position[pair.a], scene.kn, scene.kt};
  const ShapeModel& sm = (*scene.shapes)[scene.bodies->shape[pair.a]];
  visitObstacle(scene, pair, acc, rebuild, sm.nodes.box, Motion{plane.point, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()},
                [&](const Eigen::Vector3d& x, Eigen::Vector3d& normal) {
                  normal = plane.normal;
                  return plane.phi(x);
                });
}

}  // namespace tessera
