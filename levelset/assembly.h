#pragma once
#include "geometry/tessellation.h"
#include "levelset/bundle.h"

#include <string>
#include <vector>

namespace tessera {

/// The body pose of a shape placed by a mesh-frame placement:
///   orientation = rotation * R_shape,  position = rotation * c_shape + translation
/// (x_world = rotation x_mesh + translation and x_mesh = R_shape x_body + c_shape).
Body placeBody(const Shape& shape, int shapeIndex, const Placement& placement);

/// The inverse of placeBody: the mesh-frame placement of a body.
Placement placementOf(const Body& body, const Shape& shape);

/// Pairs whose bounding spheres come within `reach` (m) of each other, a < b, fixed-fixed included.
std::vector<std::pair<int, int>> nearbyPairs(const Bundle& bundle, double reach);

/// Two bodies and their signed separation (m): the smallest level-set value of any surface node
/// (or the centroid) of one body in the other's level set, both ways; negative = overlap by that
/// depth. The level set is the one a run takes by default: a convex shape's face planes, else its
/// exact mesh level set near the surface (derived for the check when the shape has none yet), and
/// the grid beyond it; so faces that match exactly read 0, not the grid's rounding.
struct BodyPair {
  int a = -1, b = -1;
  double separation = 0.0;  ///< m, negative = overlap depth
};

/// The level set of each shape of a bundle as BodyPair reads it; built once for a bundle's checks
/// (deriving an exact mesh level set costs more than the checks).
class AssemblyLevelSets {
public:
  explicit AssemblyLevelSets(const Bundle& bundle);
  /// Shape s's level set at a body-frame point, m.
  double phi(int s, const Eigen::Vector3d& x) const;
  /// The same with its gradient (body frame; the nearest face's normal on exact planes).
  double phi(int s, const Eigen::Vector3d& x, Eigen::Vector3d& gradient) const;

private:
  const std::vector<Shape>& shapes_;
  std::vector<MeshSdf> derived_;  ///< for shapes without planes or an exact mesh of their own
};

struct AssemblyCheck {
  std::vector<BodyPair> overlaps;   ///< pairs overlapping by more than the tolerance, deepest first
  std::vector<int> isolated;        ///< bodies within `touchDistance` of no other body
  std::vector<BodyPair> contacts;   ///< pairs within `touchDistance`
};

/// Checks the initial assembly: overlaps deeper than `overlapTolerance` (m) and bodies that touch
/// nothing (no other body within `touchDistance`, m).
AssemblyCheck checkAssembly(const Bundle& bundle, double overlapTolerance, double touchDistance);
AssemblyCheck checkAssembly(const Bundle& bundle, const AssemblyLevelSets& levelSets, double overlapTolerance,
                            double touchDistance);

struct VerticalLock {
  int body = -1;
  double upDepth = 0.0;    ///< m, deepest overlap with a neighbour after moving up by the shift
  double downDepth = 0.0;  ///< m, the same moving down
};

/// For each free body: how deep it runs into its neighbours when translated up and down by
/// `shift` (m) with everything else in place. A body is interlocked when both depths are well
/// above zero (blocked both ways); a small fraction of the shift is a good threshold.
std::vector<VerticalLock> verticalLocks(const Bundle& bundle, double shift);
std::vector<VerticalLock> verticalLocks(const Bundle& bundle, const AssemblyLevelSets& levelSets, double shift);

}  // namespace tessera
