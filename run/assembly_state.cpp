#include "run/assembly_state.h"

#include <numeric>

namespace tessera {

std::vector<char> touchingBlocks(const World& world) {
  std::vector<char> touching(world.bodies().size(), 0);
  for (int k = 0; k < world.pairCount(); ++k)
    if (const PairView p = world.pair(k); p.kind == PairKind::Bodies && p.nodeContacts > 0) touching[p.a] = touching[p.b] = 1;
  return touching;
}

std::vector<char> supportedBodies(const World& world) {
  // Union-find over the block contacts; a component is supported when it holds a support.
  const int n = static_cast<int>(world.bodies().size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (int k = 0; k < world.pairCount(); ++k)
    if (const PairView p = world.pair(k); p.kind == PairKind::Bodies && p.nodeContacts > 0) parent[root(p.a)] = root(p.b);
  std::vector<char> held(n, 0), supported(n, 0);
  for (int i = 0; i < n; ++i)
    if (world.isSupport(i)) held[root(i)] = 1;
  for (int i = 0; i < n; ++i) supported[i] = !world.isRetired(i) && held[root(i)];
  return supported;
}

bool hasFallen(const World& world, int i, const std::vector<char>& supported, const Eigen::Vector3d& settledPosition,
               const FallenRule& rule) {
  if (world.isRetired(i)) return true;
  if (world.isSupport(i) || supported[i]) return false;
  const double drop = settledPosition.z() - world.bodies().position[i].z();  // down: the indenter's direction, -z
  return drop > rule.clearance * world.bodySize(i);
}

bool canRetire(const World& world, int i, const std::vector<char>& touching, const std::vector<char>& supported,
               const Eigen::Vector3d& settledPosition, const FallenRule& rule) {
  if (world.isRetired(i) || touching[i] || !hasFallen(world, i, supported, settledPosition, rule)) return false;
  const Eigen::AlignedBox3d box = world.bodyBox(i, rule.clearance * world.bodySize(i));
  for (int j = 0; j < static_cast<int>(world.bodies().size()); ++j)
    if (j != i && !world.isRetired(j) && box.intersects(world.bodyBox(j, 0.0))) return false;
  return true;
}

std::vector<char> pushedThroughBodies(const World& world, const std::vector<Eigen::Vector3d>& settledPosition) {
  const std::size_t n = world.bodies().size();
  const auto drop = [&](int j) { return settledPosition[j].z() - world.bodies().position[j].z(); };
  // One pass over the pairs: the summed drop of each body's touching neighbours, and their count.
  std::vector<double> sum(n, 0.0);
  std::vector<int> touching(n, 0);
  for (int k = 0; k < world.pairCount(); ++k)
    if (const PairView p = world.pair(k); p.kind == PairKind::Bodies && p.nodeContacts > 0) {
      sum[p.a] += drop(p.b);
      sum[p.b] += drop(p.a);
      ++touching[p.a];
      ++touching[p.b];
    }
  std::vector<char> through(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const int b = static_cast<int>(i);
    through[i] = touching[i] > 0 && !world.isSupport(b) && drop(b) - sum[i] / touching[i] > world.bodySize(b);
  }
  return through;
}

ContactCounts countContacts(const World& world, int loaded) {
  ContactCounts c;
  for (int k = 0; k < world.pairCount(); ++k) {
    const PairView p = world.pair(k);
    const long n = p.nodeContacts;
    c.all += n;
    if (p.kind != PairKind::Bodies) {
      if (n > 0 && p.kind == PairKind::Sphere) c.indenterDepth = std::max(c.indenterDepth, p.depth);
      continue;
    }
    c.blocks += n;
    c.blocksSliding += p.slidingNodes;
    if (p.a == loaded || p.b == loaded) {
      c.loaded += n;
      c.loadedSliding += p.slidingNodes;
    }
  }
  return c;
}

bool restingBodies(const World& world, const std::vector<char>& fallen, double speed) {
  const RigidBodies& b = world.bodies();
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!b.moves(i) || fallen[i]) continue;
    const double reach = 0.5 * world.bodyBox(static_cast<int>(i), 0.0).sizes().norm();
    if (b.velocity[i].norm() + b.angularVelocity(i).norm() * reach > speed) return false;
  }
  return true;
}

}  // namespace tessera
