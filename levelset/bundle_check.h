#pragma once
#include "levelset/bundle.h"

#include <string>

namespace tessera {

/// Checks the values of a bundle read from a file before anything uses them, and throws
/// std::invalid_argument naming the first bad one (readBundle reports it as a corrupt bundle):
///  - every shape: a closed mesh with valid indices, at least 4 surface nodes with finite positions,
///    unit normals and positive areas, a grid of positive size with finite values, a positive voxel,
///    a positive volume and principal moments, finite face planes with unit normals;
///  - every body: a non-empty name, unique; a shape that exists; a finite position; a unit quaternion;
///  - the span: finite, not negative.
void checkBundleValues(const Bundle& bundle);

}  // namespace tessera
