#pragma once
#include "solver/world.h"

#include <Eigen/Core>
#include <vector>

namespace tessera {

/// What holds what, read from the node contacts of the World's last evaluation (docs/physics.md,
/// "Failure: fallen and retired bodies"). The indenter is not a block: contact with it neither
/// supports a body nor keeps it from being retired.

/// For each body: it has a node contact with another body.
std::vector<char> touchingBlocks(const World& world);

/// For each body: a chain of block contacts joins it to a support (a body fixed from the start).
/// Supports are supported; retired bodies are not.
std::vector<char> supportedBodies(const World& world);

/// The rule for fallen bodies, as a ratio of each body's size h_i (World::bodySize: the smallest
/// extent of its box, a slab block's thickness).
struct FallenRule {
  /// A free body has fallen when no chain of block contacts joins it to a support and it has
  /// moved down by more than clearance x h_i since the slab settled. A fallen body is retired
  /// when it also touches no block and its box, enlarged by clearance x h_i, meets no other
  /// body's box: it has left the assembly.
  double clearance = 0.1;
};

/// Free, not held by the supports, and dropped by more than the clearance; retired bodies have fallen.
bool hasFallen(const World& world, int i, const std::vector<char>& supported, const Eigen::Vector3d& settledPosition,
               const FallenRule& rule);

/// Fallen, touching no block, and clear of every other body by the clearance (never a body in
/// contact with a block).
bool canRetire(const World& world, int i, const std::vector<char>& touching, const std::vector<char>& supported,
               const Eigen::Vector3d& settledPosition, const FallenRule& rule);

/// For each body: still touching blocks, but moved down more than its own size h_i past the mean
/// of the blocks it touches: out of the slab's plane (a block jammed on its way out), not a dished slab.
std::vector<char> pushedThroughBodies(const World& world, const std::vector<Eigen::Vector3d>& settledPosition);

/// Node contacts of the last evaluation, as a curve sample records them.
struct ContactCounts {
  long all = 0;               ///< every node contact, the indenter's included
  long blocks = 0;            ///< between two bodies
  long blocksSliding = 0;     ///< of those, at the Coulomb cap
  long loaded = 0;            ///< between the loaded body and another body
  long loadedSliding = 0;     ///< of those, at the Coulomb cap
  double indenterDepth = 0;   ///< m, deepest node inside the indenter
};
ContactCounts countContacts(const World& world, int loaded);

/// Every free, non-fallen body moves slower than `speed` (m/s) at its farthest node.
bool restingBodies(const World& world, const std::vector<char>& fallen, double speed);

}  // namespace tessera
