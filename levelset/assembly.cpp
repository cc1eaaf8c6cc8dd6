#include "levelset/assembly.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tessera {

Body placeBody(const Shape& shape, int shapeIndex, const Placement& placement) {
  Body body;
  body.name = placement.name;
  body.shape = shapeIndex;
  body.fixed = placement.fixed;
  const Eigen::Quaterniond shapeAxes(shape.mass.principalAxes);
  body.orientation = (placement.rotation.normalized() * shapeAxes).normalized();
  body.position = placement.rotation.normalized() * shape.mass.centroid + placement.translation;
  return body;
}

Placement placementOf(const Body& body, const Shape& shape) {
  Placement p;
  p.name = body.name;
  p.shape = shape.name;
  p.fixed = body.fixed;
  const Eigen::Quaterniond shapeAxes(shape.mass.principalAxes);
  p.rotation = (body.orientation * shapeAxes.conjugate()).normalized();
  p.translation = body.position - p.rotation * shape.mass.centroid;
  return p;
}

namespace {

double boundingRadius(const Shape& shape) {
  double r = 0.0;
  for (const auto& v : shape.mesh.vertices) r = std::max(r, v.norm());
  return r;
}

// Smallest level-set value of b's shape at the nodes of a (a moved by `shift`).
double nodesInLevelSet(const Bundle& bundle, int a, int b, const Eigen::Vector3d& shift) {
  const Body &A = bundle.bodies[a], &B = bundle.bodies[b];
  const Shape &shapeA = bundle.shapes[A.shape], &shapeB = bundle.shapes[B.shape];
  // x_B = qB^-1 (qA x_A + pA + shift - pB)
  const Eigen::Matrix3d rotation = (B.orientation.conjugate() * A.orientation).toRotationMatrix();
  const Eigen::Vector3d offset = B.orientation.conjugate() * (A.position + shift - B.position);
  // A's centroid too, when it lies inside A: two bodies that coincide have every surface node on
  // the other's surface (phi = 0), but each centroid deep inside the other. (A ring-shaped frame's
  // centroid lies outside it, in whatever the ring surrounds.)
  double smallest = shapeA.sdf.sample(Eigen::Vector3d::Zero()).phi < 0 ? shapeB.sdf.sample(offset).phi
                                                                         : std::numeric_limits<double>::infinity();
  for (const auto& x : shapeA.nodes.positions) smallest = std::min(smallest, shapeB.sdf.sample(rotation * x + offset).phi);
  return smallest;
}

}  // namespace

double separation(const Bundle& bundle, int a, int b, const Eigen::Vector3d& shiftA) {
  return std::min(nodesInLevelSet(bundle, a, b, shiftA), nodesInLevelSet(bundle, b, a, -shiftA));
}

std::vector<std::pair<int, int>> nearbyPairs(const Bundle& bundle, double reach) {
  // All pairs by bounding spheres: O(n^2), fine for slabs of thousands of blocks at set-up.
  std::vector<double> radius;
  for (const Body& b : bundle.bodies) radius.push_back(boundingRadius(bundle.shapes[b.shape]));
  std::vector<std::pair<int, int>> pairs;
  const int n = static_cast<int>(bundle.bodies.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      if ((bundle.bodies[a].position - bundle.bodies[b].position).norm() <= radius[a] + radius[b] + reach)
        pairs.emplace_back(a, b);
  return pairs;
}

AssemblyCheck checkAssembly(const Bundle& bundle, double overlapTolerance, double touchDistance) {
  AssemblyCheck check;
  std::vector<char> touches(bundle.bodies.size(), 0);
  for (const auto& [a, b] : nearbyPairs(bundle, touchDistance)) {
    const double s = separation(bundle, a, b);
    if (s <= touchDistance) {
      check.contacts.push_back({a, b, s});
      touches[a] = touches[b] = 1;
    }
    if (s < -overlapTolerance) check.overlaps.push_back({a, b, s});
  }
  std::sort(check.overlaps.begin(), check.overlaps.end(),
            [](const BodyPair& x, const BodyPair& y) { return x.separation < y.separation; });
  for (int i = 0; i < static_cast<int>(touches.size()); ++i)
    if (!touches[i]) check.isolated.push_back(i);
  return check;
}

std::vector<VerticalLock> verticalLocks(const Bundle& bundle, double shift) {
  const auto pairs = nearbyPairs(bundle, 2 * shift);
  std::vector<VerticalLock> locks;
  for (int i = 0; i < static_cast<int>(bundle.bodies.size()); ++i) {
    if (bundle.bodies[i].fixed) continue;
    VerticalLock lock;
    lock.body = i;
    for (const auto& [a, b] : pairs) {
      if (a != i && b != i) continue;
      const int other = a == i ? b : a;
      lock.upDepth = std::max(lock.upDepth, -separation(bundle, i, other, Eigen::Vector3d(0, 0, shift)));
      lock.downDepth = std::max(lock.downDepth, -separation(bundle, i, other, Eigen::Vector3d(0, 0, -shift)));
    }
    locks.push_back(lock);
  }
  return locks;
}

}  // namespace tessera
