#pragma once
// A World's private parts, for the files that implement it (world.cpp, implicit_increment.cpp)
// and the solver's own tests: its pairs, its threads, and the implicit method's scratch (derived
// from the state at each increment, never saved).
#include "solver/implicit_contacts.h"
#include "solver/world.h"

#include <Eigen/Sparse>
#include <Eigen/SparseLU>

#include <tbb/task_arena.h>

#include <vector>

namespace tessera {

/// The pairs as the solver keeps them (PairContacts), for the solver's own tests and benchmarks;
/// every other caller reads World::pair.
struct WorldInternals {
  static const std::vector<PairContacts>& pairs(const World& world) { return world.pairs_; }
  static double normalStiffness(const World& world, const PairContacts& pair) { return world.normalStiffness(pair); }
};

struct World::ThreadArena {
  tbb::task_arena arena;
  explicit ThreadArena(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}
};

struct World::ImplicitWork {
  IncrementStart start;                 ///< poses at the increment's start
  RigidBodies startBodies;              ///< the bodies then (restored when the increment is cut)
  std::vector<PairContacts> committed;  ///< the pairs then, sorted by (a, b): the springs every trial starts from
  std::vector<Eigen::Vector3d> startReaction;  ///< each sphere's reaction then
  std::vector<Eigen::Vector3d> startForce, startTorque;  ///< each body's contact and gravity force and torque then
  std::vector<Eigen::Matrix3d> startInertia;   ///< kg m^2, each body's inertia tensor then (world)
  std::vector<ImplicitPairResult> results;     ///< of the last evaluation, one per pair
  /// Per pair (by index; a pair found at another index lists its own again): the nodes near
  /// contact, listed at the poses listedPosition/listedOrientation this increment.
  std::vector<ImplicitCandidates> candidates;
  std::vector<Eigen::Vector3d> listedPosition;
  std::vector<Eigen::Quaterniond> listedOrientation;
  std::vector<Eigen::Vector3d> listedSphereCentre;
  std::vector<int> dof;                 ///< body -> its block of six unknowns, -1 for a fixed body
  int freeBodies = 0;
  Eigen::VectorXd residual;             ///< per free body: force, torque (N, N m)
  std::vector<double> bodyScale;        ///< N, each body's weight plus its contacts' |f| sums
  double forceScale = 0.0;              ///< N, the largest of them
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::SparseMatrix<double> matrix;   ///< the tangent, -d residual / d (dx, dtheta)
  /// Per unknown, the factor D of the system solved, (D K D) y = D R, x = D y: 1 for a translation,
  /// 1 / r for a rotation (r: the body's radius), so that it is solved for the arc r theta and the
  /// moment's equation weighs M / r, a force, and the entries compare point motions and forces alike.
  Eigen::VectorXd scale;
  /// The scaled tangent's LU in the order of the unknowns (World::numberFreeBodies), a diagonal
  /// pivot kept while it is at least kPivotThreshold of its column's largest entry (threshold
  /// partial pivoting; scaled, the tangent's diagonals pass it on the slabs measured).
  static constexpr double kPivotThreshold = 0.1;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::NaturalOrdering<int>> solver;
  ImplicitWork() { solver.setPivotThreshold(kPivotThreshold); }
};

}  // namespace tessera
