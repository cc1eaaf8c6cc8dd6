#pragma once
#include "levelset/assembly.h"

#include <vector>

namespace tessera {

/// A corner of the polygon over which two bodies touch (docs/check.md). For a pair of bodies, the
/// surface nodes of each that lie within the touch distance of the other's surface, with their own
/// normal opposite to the other's surface normal there (within 10 degrees: face against face),
/// are grouped by that normal (within 10 degrees: one group per contact plane); each group's
/// points, projected on its mean plane, give a convex polygon (reduced to at most 8 corners, and
/// without the corners that add less than 0.5 % of its area; which only shrinks it) whose corners carry the contact in a rigid-block analysis (a
/// pressure over a plane polygon is equivalent to forces at its corners).
/// Groups whose points are collinear (blocks meeting along an edge line) or fewer than three are
/// no contact.
struct ContactCorner {
  int first = -1, second = -1;  ///< bodies, first < second
  Eigen::Vector3d point;        ///< world, m
  Eigen::Vector3d normal;       ///< unit, world, from `first` into `second`
  int polygon = -1;             ///< index of its polygon (corners of one polygon share it)
};

/// A surface node of one body touching another's surface: a point spring of the LS-DEM contact
/// (docs/physics.md), for the elastic settling of levelset/elastic_settling.h.
struct ContactNode {
  int first = -1, second = -1;  ///< bodies, first < second
  Eigen::Vector3d point;        ///< world, m
  Eigen::Vector3d normal;       ///< unit, world, from `first` into `second`: the other body's surface normal
  double area = 0;              ///< m^2: half the node's area times max(0, -n_node . n_other), as the run's two-way rule
};
/// The nodes of every pair of bodies (not both fixed) within `touchDistance` (m) of the other's
/// surface, both ways: every contact the LS-DEM run starts with, faces, edges and corners alike.
std::vector<ContactNode> contactNodes(const Bundle& bundle, const AssemblyLevelSets& levelSets, double touchDistance);

/// The contact corners of every pair of bodies of the bundle, pair by pair. `touchDistance` (m):
/// how far from the other's surface a node still touches it.
std::vector<ContactCorner> contactPolygons(const Bundle& bundle, const AssemblyLevelSets& levelSets, double touchDistance);

}  // namespace tessera
