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
///
/// The section rule (StiffnessRule::Sections) weights each bar by the block's own sections: a bar
/// of sections A(y) has the compliance of a prism of the contact's section A_c and length
///     w' = f w,   f = (A_c / s) int_0^s dy / A(y)                      (a bar's series compliance)
/// with y along the block's facing normal m from its centroid to its support s along m, A(y) its
/// section by the plane m . x = y (sectionArea), and m, A_c the direction and length of the
/// summed area vectors of the faces turned towards the contact (within 40 degrees of it: a
/// diagonal neighbour of vertical-faced blocks, at 45 degrees to both faces, has none). A prism
/// has f = 1 (the bar rule); a hexagonal block, twice as wide at its centre as at a face, f = ln 2;
/// a block whose face is wider than its inside (a tetrahedral block's side), f > 1. The integral is the midpoint rule over
/// kSectionSamples slices; sections below a tenth of A_c count as a tenth (a curved face's tip, where
/// 1/A(y) diverges). Each f is at least the body's least f over its largest faces' normals, the
/// bound the time step uses.
class ContactBars {
public:
  /// meshes: each shape's surface in its body frame (centroid at the origin); bodies: the start
  /// poses, shapes and fixed flags (a body retired later keeps its bar); sections:
  /// weight the bars by the blocks' sections.
  ContactBars(const std::vector<TriangleMesh>& meshes, std::vector<int> shape, std::vector<Eigen::Vector3d> position,
              std::vector<Eigen::Quaterniond> orientation, std::vector<char> fixed, bool sections = false);
  ContactBars() = default;

  static constexpr int kSectionSamples = 32;
  static constexpr double kFacingCosine = 0.766044443118978;  ///< cos 40 degrees
  static constexpr int kBoundFaces = 64;  ///< the largest faces whose normals bound f below

  /// m, w_a + w_b of two bodies.
  double betweenBodies(int a, int b) const;
  /// m, w of body a against an obstacle whose surface faces the body along `towards` (unit, from
  /// the body to the obstacle: +z for the indenter, -normal for a plane).
  double againstObstacle(int a, const Eigen::Vector3d& towards) const;
  /// m, the shortest bar of body a: its least support along its faces' normals (times its least
  /// section factor under the section rule).
  double shortest(int a) const { return shortestOfShape_[shape_[a]] * leastFactorOfShape_[shape_[a]]; }
  /// The section factor f of shape `shape` towards `local` (unit, in its body frame; 1 without sections).
  double sectionFactor(int shape, const Eigen::Vector3d& local) const;

private:
  double support(int body, const Eigen::Vector3d& direction) const;  // m, max over hull points of direction . (x - c)
  double bar(int body, const Eigen::Vector3d& towards, double length) const;  // m, w' of `length` towards `towards`
  double unboundedFactor(int shape, const Eigen::Vector3d& local) const;

  std::vector<TriangleMesh> meshes_;
  bool sections_ = false;
  std::vector<double> leastFactorOfShape_;
  std::vector<int> shape_;
  std::vector<Eigen::Vector3d> position_;
  std::vector<Eigen::Quaterniond> orientation_;
  std::vector<char> fixed_;
  std::vector<double> shortestOfShape_;
};

}  // namespace tessera
