#pragma once
#include "geometry/triangle_mesh.h"

namespace tessera {

/// Axis-aligned box of sides a (x), b (y), h (z), metres, centred at the origin.
TriangleMesh makeBox(double a, double b, double h);

/// The planar-faced TIS block (DESIGN §4): square mid-section of side a in the plane z = 0,
/// thickness h, the faces normal to x inclined outward by +theta (the block widens in x upwards)
/// and the faces normal to y by -theta (it narrows in y upwards), so that the same block turned
/// 90 degrees about z interlocks with it. Face planes: x = ±(a/2 + z tan(theta)),
/// y = ±(a/2 - z tan(theta)), z = ±h/2. Volume a^2 h - h^3 tan^2(theta) / 3.
/// Lengths in metres, theta in radians; requires h tan(theta) < a.
TriangleMesh makePlanarBlock(double a, double h, double theta);

}  // namespace tessera
