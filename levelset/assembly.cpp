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
double nodesInLevelSet(const Bundle& bundle, const AssemblyLevelSets& levelSets, int a, int b, const Eigen::Vector3d& shift) {
  const Body &A = bundle.bodies[a], &B = bundle.bodies[b];
  const Shape& shapeA = bundle.shapes[A.shape];
  // x_B = qB^-1 (qA x_A + pA + shift - pB)
  const Eigen::Matrix3d rotation = (B.orientation.conjugate() * A.orientation).toRotationMatrix();
  const Eigen::Vector3d offset = B.orientation.conjugate() * (A.position + shift - B.position);
  // A's centroid too, when it lies inside A: two bodies that coincide have every surface node on
  // the other's surface (phi = 0), but each centroid deep inside the other. (A ring-shaped frame's
  // centroid lies outside it, in whatever the ring surrounds.)
  double smallest = levelSets.phi(A.shape, Eigen::Vector3d::Zero()) < 0 ? levelSets.phi(B.shape, offset)
                                                                        : std::numeric_limits<double>::infinity();
  for (const auto& x : shapeA.nodes.positions) smallest = std::min(smallest, levelSets.phi(B.shape, rotation * x + offset));
  return smallest;
}

// The signed separation of bodies a and b (BodyPair), a moved by `shiftA` (world, m).
double separation(const Bundle& bundle, const AssemblyLevelSets& levelSets, int a, int b,
                  const Eigen::Vector3d& shiftA = Eigen::Vector3d::Zero()) {
  return std::min(nodesInLevelSet(bundle, levelSets, a, b, shiftA), nodesInLevelSet(bundle, levelSets, b, a, -shiftA));
}

}  // namespace

AssemblyLevelSets::AssemblyLevelSets(const Bundle& bundle) : shapes_(bundle.shapes), derived_(bundle.shapes.size()) {
  for (std::size_t s = 0; s < shapes_.size(); ++s)
    if (!shapes_[s].convex && shapes_[s].exactMesh.empty() && !shapes_[s].mesh.triangles.empty())
      derived_[s] = exactMeshLevelSet(shapes_[s]);
}

double AssemblyLevelSets::phi(int s, const Eigen::Vector3d& x) const {
  Eigen::Vector3d gradient;
  return phi(s, x, gradient);
}

double AssemblyLevelSets::phi(int s, const Eigen::Vector3d& x, Eigen::Vector3d& gradient) const {
  const Shape& shape = shapes_[s];
  if (shape.convex) {
    double phi = -std::numeric_limits<double>::infinity();
    for (const FacePlane& f : shape.convex->planes)
      if (f.normal.dot(x) - f.offset > phi) {
        phi = f.normal.dot(x) - f.offset;
        gradient = f.normal;
      }
    return phi;
  }
  const MeshSdf& exact = shape.exactMesh.empty() ? derived_[s] : shape.exactMesh;
  double phi;
  if (!exact.empty() && exact.evaluate(x, phi, gradient)) return phi;
  const SdfSample sample = shape.sdf.sample(x);
  gradient = sample.gradient.normalized();
  return sample.phi;
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
  return checkAssembly(bundle, AssemblyLevelSets(bundle), overlapTolerance, touchDistance);
}

AssemblyCheck checkAssembly(const Bundle& bundle, const AssemblyLevelSets& levelSets, double overlapTolerance,
                            double touchDistance) {
  AssemblyCheck check;
  std::vector<char> touches(bundle.bodies.size(), 0);
  for (const auto& [a, b] : nearbyPairs(bundle, touchDistance)) {
    const double s = separation(bundle, levelSets, a, b);
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
  return verticalLocks(bundle, AssemblyLevelSets(bundle), shift);
}

std::vector<VerticalLock> verticalLocks(const Bundle& bundle, const AssemblyLevelSets& levelSets, double shift) {
  const auto pairs = nearbyPairs(bundle, 2 * shift);
  std::vector<VerticalLock> locks;
  for (int i = 0; i < static_cast<int>(bundle.bodies.size()); ++i) {
    if (bundle.bodies[i].fixed) continue;
    VerticalLock lock;
    lock.body = i;
    for (const auto& [a, b] : pairs) {
      if (a != i && b != i) continue;
      const int other = a == i ? b : a;
      lock.upDepth = std::max(lock.upDepth, -separation(bundle, levelSets, i, other, Eigen::Vector3d(0, 0, shift)));
      lock.downDepth = std::max(lock.downDepth, -separation(bundle, levelSets, i, other, Eigen::Vector3d(0, 0, -shift)));
    }
    locks.push_back(lock);
  }
  return locks;
}

}  // namespace tessera
