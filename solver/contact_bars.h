#pragma once
#include "geometry/triangle_mesh.h"

#include <Eigen/Geometry>

#include <vector>

namespace tessera {

/// The bar rule of contact stiffness (StiffnessRule::Bars; docs/physics.md, "Contact stiffness").
/// A penalty contact between rigid blocks stands for the blocks' own elastic shortening. Taking
/// each block as a bar of modulus E from its centroid to the contact, a contact's normal
/// stiffness per unit area is
///     k_n = E / (w_a + w_b)                                              (N/m^3)
/// with w the bar of each side: between bodies whose centroids are d apart (at the start), the
/// part of d on each side in proportion to the bodies' extents towards each other,
///     w_a = d s_a / (s_a + s_b),   s_a = support of a along the line of centroids;
/// 0 for a fixed body (the rigid frame of the tests this models) and for an obstacle (the
/// indenter, a plane: rigid; a fixed body against one keeps its own bar); against the indenter
/// (which comes down along -z) the support along +z, against a plane the support towards it.
/// Each w is at least the body's shortest bar, its least support along the normals of its own
/// faces (for a convex block the distance from its centroid to its nearest face plane: h/2 for a
/// flat block), which also bounds the stiffest contact it can have (the time step).
/// On a row of equal blocks of width a between fixed supports, as in Feldfogel et al.'s square
/// slabs: w = a/2 on each side (k_n = E / a between free blocks, 2 E / a against a support), and the
/// row's compliance, (n - 3) a / E + 2 (a/2) / E = L / E for n - 2 free blocks over the span L, is
/// exactly that of their rule k_n = E M / L (M = n - 1 contacts of L / (E M) each).
class ContactBars {
public:
  /// meshes: each shape's surface in its body frame (centroid at the origin); bodies: the start
  /// poses, shapes and fixed flags (a body fixed later, when retired, keeps its bar).
  ContactBars(const std::vector<TriangleMesh>& meshes, std::vector<int> shape, std::vector<Eigen::Vector3d> position,
              std::vector<Eigen::Quaterniond> orientation, std::vector<char> fixed);
  ContactBars() = default;

  /// m, w_a + w_b of two bodies.
  double betweenBodies(int a, int b) const;
  /// m, w of body a against an obstacle whose surface faces the body along `towards` (unit, from
  /// the body to the obstacle: +z for the indenter, -normal for a plane).
  double againstObstacle(int a, const Eigen::Vector3d& towards) const;
  /// m, the shortest bar of body a: its least support along its faces' normals.
  double shortest(int a) const { return shortestOfShape_[shape_[a]]; }

private:
  double support(int body, const Eigen::Vector3d& direction) const;  // m, max over hull points of direction . (x - c)

  std::vector<std::vector<Eigen::Vector3d>> vertices_;
  std::vector<int> shape_;
  std::vector<Eigen::Vector3d> position_;
  std::vector<Eigen::Quaterniond> orientation_;
  std::vector<char> fixed_;
  std::vector<double> shortestOfShape_;
};

}  // namespace tessera
