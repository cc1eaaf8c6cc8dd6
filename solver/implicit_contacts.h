#pragma once
// The contacts of one pair at a trial configuration of an implicit increment: the same law as the
// explicit step's (node_contact_law.h), in double, with its derivative. docs/physics.md,
// "Implicit method".
#include "solver/pair_contacts.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace tessera {

/// Poses at the start of an increment: each node's relative displacement over the increment, which
/// loads its tangential spring, is measured from them.
struct IncrementStart {
  std::vector<Eigen::Vector3d> position;        ///< m, each body's centroid
  std::vector<Eigen::Quaterniond> orientation;  ///< body -> world
  std::vector<Eigen::Vector3d> sphereCentre;    ///< m
};

/// What an implicit evaluation reads (nothing of it is changed).
struct ImplicitScene {
  const RigidBodies* bodies;  ///< the trial configuration
  const std::vector<ShapeModel>* shapes;
  const std::vector<SphereObstacle>* spheres;  ///< centres at the trial configuration
  const std::vector<PlaneObstacle>* planes;
  const IncrementStart* start;
  ContactParameters parameters;
  double kn = 0.0, kt = 0.0;  ///< N/m^3
  double increment = 0.0;     ///< s, the increment's duration (the normal viscosity's rate)
};

/// A pair's contacts at a trial configuration.
///   force:     on body a, [F; M] with M about a's centroid (N, N m)
///   stiffness: S = sum_c G(r_c)^T K_c G(r_c), G(r) = [I, -[r]x], r_c = x_c - c_a: the pair's
///              tangent about a's centroid. K_c = -df_c / d(rel_c), the derivative of a contact's
///              force on its node's body with respect to the node's displacement relative to the
///              other side (normal, sticking or sliding: docs/physics.md). The generalised
///              stiffness of the pair in (q_a, q_b) is [I, -T_b]^T S [I, -T_b], T_b the shift of
///              b's generalised displacement to a's centroid (ImplicitPairResult::shift).
///   contacts:  the trial contacts (springs after the Coulomb cap), what a converged increment keeps.
struct ImplicitPairResult {
  Eigen::Matrix<double, 6, 1> force = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 6> stiffness = Eigen::Matrix<double, 6, 6>::Zero();
  NodeContacts contacts;
  ContactTally tally;  ///< elastic stored now; friction and projection over the increment
  Eigen::Vector3d normalForceA{0, 0, 0}, forcePoint{0, 0, 0};
  double maxDepth = 0.0;
  double forceScale = 0.0;  ///< N, sum of |f| over the contacts (the size the residual is judged by)
};

/// T such that a generalised displacement (dx, dtheta) of a body with centroid `centroid` moves
/// the points near `origin` as (dx', dtheta) = T (dx, dtheta) about `origin`: [[I, -[origin -
/// centroid]x], [0, I]].
Eigen::Matrix<double, 6, 6> shiftToPoint(const Eigen::Vector3d& origin, const Eigen::Vector3d& centroid);

/// Evaluates pair `pair` at the scene's trial configuration into `out`, with `committed` the
/// pair's node contacts at the increment's start (their springs; empty: none). Every node of each side inside the other side's box is tested, as the
/// explicit step's evaluation with its candidates rebuilt (evaluatePair): the same level sets,
/// areas and law. Thread-safe for distinct outputs.
void evaluateImplicitPair(const ImplicitScene& scene, const PairContacts& pair, const NodeContacts& committed,
                          ImplicitPairResult& out);

}  // namespace tessera
