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

/// The nodes of a pair that can touch while an increment's iterations go on: those within
/// `candidateBand` of the other side when they were listed (keys side << 31 | rank, in order). They
/// stay valid while the pair's sides move less than band / sqrt(3) relative to each other (every
/// level set here is at most sqrt(3)-Lipschitz, ContactScene::candidateBand); the caller checks.
struct ImplicitCandidates {
  int a = -1, b = -1;   ///< the pair they were listed for
  bool listed = false;  ///< false: the next evaluation visits every node in range and lists them
  std::vector<std::uint32_t> keys;
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
  double candidateBand = 0.0; ///< m, ImplicitCandidates
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
  std::vector<NodeContact> contacts;  ///< in key order
  /// The geometric part of the tangent: how the moments change as the contact points move with
  /// their bodies, the forces held (docs/physics.md). For side s's contacts (s = 0: a's nodes),
  /// with g each one's force on a and r = x - c_a: sum g and sum [g]x [r]x.
  Eigen::Vector3d sideForce[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  Eigen::Matrix3d sideMoment[2] = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  ContactTally tally;  ///< elastic stored now; friction and projection over the increment
  Eigen::Vector3d normalForceA{0, 0, 0}, forcePoint{0, 0, 0};
  double maxDepth = 0.0;
  double forceScale = 0.0;  ///< N, sum of (1 + mu) f_n >= |f| over the contacts (the size the residual is judged by)
  /// The pair's tangent (pairTangent), where the evaluation asked for it.
  Eigen::Matrix<double, 12, 12> tangent = Eigen::Matrix<double, 12, 12>::Zero();
};

/// [r]x, the matrix of r x .
Eigen::Matrix3d skew(const Eigen::Vector3d& r);

/// T such that a generalised displacement (dx, dtheta) of a body with centroid `centroid` moves
/// the points near `origin` as (dx', dtheta) = T (dx, dtheta) about `origin`: [[I, -[origin -
/// centroid]x], [0, I]].
Eigen::Matrix<double, 6, 6> shiftToPoint(const Eigen::Vector3d& origin, const Eigen::Vector3d& centroid);

/// The pair's tangent in the generalised displacements (dx_a, dtheta_a, dx_b, dtheta_b) of its
/// bodies about their centroids c_a, c_b, -d (F_a, M_a, F_b, M_b) / d q: the material part
/// [I, -T_b]^T S [I, -T_b] and the geometric part of the moments (sideForce, sideMoment). For an
/// obstacle pair only the first 6 x 6 block is used.
Eigen::Matrix<double, 12, 12> pairTangent(const ImplicitPairResult& r, const Eigen::Vector3d& ca, const Eigen::Vector3d& cb);

/// Evaluates pair `pair` at the scene's trial configuration into `out`, with `committed` the
/// pair's node contacts at the increment's start (their springs; empty: none). Every node of each side inside the other side's box is tested, as the
/// explicit step's evaluation with its candidates rebuilt (evaluatePair): the same level sets,
/// areas and law. Thread-safe for distinct outputs.
void evaluateImplicitPair(const ImplicitScene& scene, const PairContacts& pair, const NodeContacts& committed,
                          ImplicitCandidates& candidates, ImplicitPairResult& out);

}  // namespace tessera
