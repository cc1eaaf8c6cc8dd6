#include "solver/pair_contacts.h"

#include "solver/contact_law.h"

#include <algorithm>
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

// Merge cursor over the previous step's contacts (sorted by key): the spring of a node that was
// in contact, or zero.
struct History {
  const std::vector<NodeContact>& previous;
  std::size_t next = 0;
  Eigen::Vector3d springFor(std::uint32_t key) {
    while (next < previous.size() && previous[next].key < key) ++next;
    return next < previous.size() && previous[next].key == key ? previous[next].spring : Eigen::Vector3d::Zero();
  }
};

// Shared per-node work: contact law, accumulation on both sides, history.
struct Accumulator {
  const ContactScene& scene;
  PairContacts& pair;
  History history;
  double weight = 0.0;  // sum of force magnitudes, for forcePoint

  void add(std::uint32_t key, int nodeBody, int otherBody, const Eigen::Vector3d& x, const Eigen::Vector3d& nodeNormal,
           double area, const Eigen::Vector3d& normal, double depth, const Eigen::Vector3d& otherVelocityAtX,
           bool nodeBodyIsA) {
    // Effective area: the node's area projected on the contact plane (docs/physics.md).
    const double projection = -nodeNormal.dot(normal);
    if (projection <= 0) return;
    const RigidBodies& bodies = *scene.bodies;
    const Eigen::Vector3d arm = x - bodies.position[nodeBody];
    const Eigen::Vector3d velocity = bodies.velocity[nodeBody] + bodies.angularVelocity(nodeBody).cross(arm);
    NodeContactInput input{normal, depth, area * projection, velocity - otherVelocityAtX};
    Eigen::Vector3d spring = history.springFor(key);
    const Eigen::Vector3d f =
        contactForce(scene.parameters, scene.kn, scene.kt, input, spring, scene.dt, pair.elasticEnergy);
    pair.contacts.push_back({key, spring});
    pair.maxDepth = std::max(pair.maxDepth, depth);
    const double magnitude = f.norm();
    pair.forcePoint += magnitude * x;
    weight += magnitude;
    // Equal and opposite forces at the same point: Newton's third law holds for forces and torques.
    if (nodeBodyIsA) {
      pair.forceA += f;
      pair.torqueA += arm.cross(f);
      pair.forceB -= f;
      if (otherBody >= 0) pair.torqueB -= (x - bodies.position[otherBody]).cross(f);
    } else {
      pair.forceB += f;
      pair.torqueB += arm.cross(f);
      pair.forceA -= f;
      pair.torqueA -= (x - bodies.position[otherBody]).cross(f);
    }
  }
};

}  // namespace

void evaluatePair(const ContactScene& scene, PairContacts& pair) {
  std::swap(pair.contacts, pair.previous);
  pair.contacts.clear();
  pair.forceA = pair.torqueA = pair.forceB = pair.torqueB = pair.forcePoint = Eigen::Vector3d::Zero();
  pair.elasticEnergy = 0.0;
  pair.maxDepth = 0.0;
  pair.evaluations = 0;
  Accumulator acc{scene, pair, History{pair.previous}};
  const RigidBodies& bodies = *scene.bodies;
  const auto& shapes = *scene.shapes;

  if (pair.b >= 0) {
    // Body against body, both ways with half weights.
    for (std::uint32_t side = 0; side < 2; ++side) {
      const int m = side == 0 ? pair.a : pair.b, o = side == 0 ? pair.b : pair.a;
      const ShapeModel& sm = shapes[bodies.shape[m]];
      const ShapeModel& so = shapes[bodies.shape[o]];
      const Eigen::Quaterniond &qM = bodies.orientation[m], &qO = bodies.orientation[o];
      const Eigen::Matrix3d RM = qM.toRotationMatrix(), RO = qO.toRotationMatrix();
      const Eigen::Matrix3d toO = RO.transpose() * RM;  // M body -> O body
      const Eigen::Vector3d shift = RO.transpose() * (bodies.position[m] - bodies.position[o]);
      const Eigen::Vector3d vO = bodies.velocity[o], wO = bodies.angularVelocity(o), pO = bodies.position[o];
      // Only nodes inside the other body's box can be inside the other body.
      const Eigen::AlignedBox3d region = regionInFrame(so.nodes.box, qO, pO, qM, bodies.position[m]);
      sm.nodes.forEachNodeIn(region, [&](int rank) {
        ++pair.evaluations;
        const Eigen::Vector3d xO = toO * sm.nodes.position[rank] + shift;
        double phi;
        Eigen::Vector3d normalO;
        if (!so.penetration(xO, phi, normalO)) return;
        const Eigen::Vector3d x = RM * sm.nodes.position[rank] + bodies.position[m];
        acc.add(side << 31 | static_cast<std::uint32_t>(rank), m, o, x, RM * sm.nodes.normal[rank],
                0.5 * sm.nodes.area[rank], RO * normalO, -phi, vO + wO.cross(x - pO), side == 0);
      });
    }
    if (acc.weight > 0) pair.forcePoint /= acc.weight;
    return;
  }

  // Body against an analytic obstacle, full weights.
  const int m = pair.a;
  const int obstacle = -1 - pair.b;
  const int sphereCount = static_cast<int>(scene.spheres->size());
  const ShapeModel& sm = shapes[bodies.shape[m]];
  const Eigen::Quaterniond& qM = bodies.orientation[m];
  const Eigen::Matrix3d RM = qM.toRotationMatrix();
  const Eigen::Vector3d pM = bodies.position[m];
  if (obstacle < sphereCount) {
    const SphereObstacle& sphere = (*scene.spheres)[obstacle];
    const Eigen::Vector3d centre = qM.conjugate() * (sphere.center - pM);
    const Eigen::AlignedBox3d region(centre.array() - sphere.radius, centre.array() + sphere.radius);
    sm.nodes.forEachNodeIn(region, [&](int rank) {
      ++pair.evaluations;
      const Eigen::Vector3d x = RM * sm.nodes.position[rank] + pM;
      const double phi = sphere.phi(x);
      if (phi >= 0) return;
      acc.add(static_cast<std::uint32_t>(rank), m, pair.b, x, RM * sm.nodes.normal[rank], sm.nodes.area[rank],
              sphere.normal(x), -phi, sphere.velocity, true);
    });
  } else {
    const PlaneObstacle& plane = (*scene.planes)[obstacle - sphereCount];
    sm.nodes.forEachNodeIn(sm.nodes.box, [&](int rank) {
      ++pair.evaluations;
      const Eigen::Vector3d x = RM * sm.nodes.position[rank] + pM;
      const double phi = plane.phi(x);
      if (phi >= 0) return;
      acc.add(static_cast<std::uint32_t>(rank), m, pair.b, x, RM * sm.nodes.normal[rank], sm.nodes.area[rank],
              plane.normal, -phi, Eigen::Vector3d::Zero(), true);
    });
  }
  if (acc.weight > 0) pair.forcePoint /= acc.weight;
}

}  // namespace tessera
