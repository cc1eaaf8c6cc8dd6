#pragma once
#include "levelset/bundle.h"

#include <string>

namespace tessera {

/// Checks the values of a bundle read from a file before anything uses them, and throws
/// std::invalid_argument naming the first bad one (readBundle reports it as a corrupt bundle):
///  - every shape: a closed, outward, not self-intersecting mesh with valid indices, at least 4
///    surface nodes with finite positions, unit normals and positive areas, a grid of positive size
///    with finite values, a positive voxel (the recorded one), finite face planes with unit normals,
///    resolution values in range; and what prep derived from the mesh, recomputed from it: volume,
///    surface area, principal moments, the centroid at the origin, principal axes that are a
///    rotation, nodes on the surface with areas summing to its area;
///  - every body: a non-empty name, unique; a shape that exists; a finite position; a unit quaternion;
///  - the span: finite, not negative.
void checkBundleValues(const Bundle& bundle);

}  // namespace tessera
