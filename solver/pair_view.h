#pragma once
#include <Eigen/Core>

#include <cstdint>

namespace tessera {

/// What the other side of a pair is: a body, or an analytic obstacle.
enum class PairKind : std::uint8_t { Bodies, Sphere, Plane };

/// One contact pair as callers outside the solver see it (World::pair), read-only, from the last
/// evaluation of the forces.
struct PairView {
  /// Bodies: b >= 0 a body; b < 0 an obstacle, sphere -1 - k or plane -1 - spheres - k (the
  /// numbering of the result files).
  int a = -1, b = -1;
  PairKind kind = PairKind::Bodies;
  Eigen::Vector3d force{0, 0, 0};        ///< N, on a
  Eigen::Vector3d torque{0, 0, 0};       ///< N m, on a, about its centroid
  Eigen::Vector3d normalForce{0, 0, 0};  ///< N, the part of `force` along the contact normals (force minus it: friction)
  Eigen::Vector3d point{0, 0, 0};        ///< m, world: the contact points weighted by normal force (force chains)
  int nodeContacts = 0;                  ///< nodes in contact
  int slidingNodes = 0;                  ///< of them, at the Coulomb cap
  double area = 0.0;                     ///< m^2, their effective areas summed
  double elastic = 0.0;                  ///< J, stored in the pair's springs
  double depth = 0.0;                    ///< m, the deepest node's penetration
  double normalStiffness = 0.0;          ///< N/m^3, the pair's k_n (ContactParameters::stiffnessRule; an obstacle's factor included)
};

}  // namespace tessera
