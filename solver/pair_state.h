#pragma once
#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace tessera {

/// A node in contact and its tangential spring: key = side << 31 | rank (side 0: a node of body
/// a in b's level set; side 1: a node of b in a's).
struct NodeContact {
  std::uint32_t key;
  Eigen::Vector3d spring;  ///< m
  double energy;           ///< J, stored in this node contact
  double area;             ///< m^2, its effective (projected) area; 0: inside but facing away
};

/// What a contact pair carries from one evaluation to the next (WorldState::pairs, a checkpoint's
/// pair records): its node contacts with their springs, and its forces and stored energy of the
/// last evaluation. Everything else the solver keeps of a pair (candidate nodes, kept planes) is
/// derived and built again after a restore.
struct PairState {
  int a = -1, b = -1;  ///< bodies; b < 0 an obstacle (PairView::b)
  std::vector<NodeContact> contacts;  ///< sorted by key
  Eigen::Vector3d forceA{0, 0, 0}, torqueA{0, 0, 0}, forceB{0, 0, 0}, torqueB{0, 0, 0};  ///< N, N m
  double elastic = 0.0;  ///< J, stored in its springs
  double depth = 0.0;    ///< m, its deepest node
};

}  // namespace tessera
