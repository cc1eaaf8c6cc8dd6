#pragma once
#include "geometry/triangle_mesh.h"

namespace tessera {

/// Parametric block families (docs/tiling.md). All lengths in metres, angles in radians; every
/// block is centred at the origin with z up, closed and outward-oriented. Invalid parameters
/// throw InputError naming the constraint.

/// The default amplitude of curved faces (wave, osteomorphic), as a fraction of the block's size
/// (0.2 mm on a 10 mm block): a default that scales with the block.
constexpr double kDefaultAmplitudePerSize = 0.02;

/// Axis-aligned box of sides a (x), b (y), h (z).
TriangleMesh makeBox(double a, double b, double h);

/// The planar-faced TIS block: square mid-section of side a in the plane z = 0,
/// thickness h; the faces normal to x lean outward by theta (the block widens in x upwards), the
/// faces normal to y lean inward (it narrows in y upwards), so the same block turned 90 degrees
/// about z interlocks with it. Faces: x = ±(a/2 + z tan(theta)), y = ±(a/2 - z tan(theta)),
/// z = ±h/2. Volume a^2 h - h^3 tan^2(theta) / 3. Requires h tan(theta) < a.
TriangleMesh makePlanarBlock(double a, double h, double theta);

/// The wave-faced TIS block: the planar block with corrugated lateral faces,
///   x = ±(a/2 + f(z)), y = ±(a/2 - f(z)),  f(z) = z tan(theta) + A sin(2 pi n z / h),
/// so a 90-degree-turned copy still matches it face to face (its y-faces become x-faces with the
/// same f). Curved in z, straight along the face; the corrugation locks the blocks vertically even
/// at theta = 0. `levels` planes across the thickness (>= 2n + 1) resolve the curve; between them
/// the faces are flat. Exact polyhedron volume: sum over slabs of the prismatoid formula;
/// smooth-surface volume a^2 h - 4 integral f^2 dz. Requires |f| < a/2.
TriangleMesh makeWaveBlock(double a, double h, double theta, double amplitude, int waves, int levels);

/// The osteomorphic-type block (after Dyskin et al., Adv. Eng. Mater. 5, 2003): a box a (x) by b (y)
/// by h (z) whose two x-faces are the same curved surface, with a convex and a concave part,
///   x = ±a/2 + g(y, z),  g(y, z) = A sin(2 pi y / b) cos(pi z / h),
/// so copies in the same orientation, a apart along x, match face to face: each bulge sits in its
/// neighbour's dimple, which holds the pair against sliding in z (both ways) and in y. With
/// A_y != 0 the y-faces are curved the same way, y = ±b/2 + A_y sin(2 pi x / a) cos(pi z / h), and
/// the block interlocks with all four neighbours; with A_y = 0 they are flat. The z-faces are flat
/// and the corner edges straight (the displacements vanish on the faces' edges). `halfWaveSegments`
/// quads per half-wave resolve the surfaces, each a fan of four triangles about a point of the
/// surface over its middle (keeping the block's symmetries: z -> -z and a half turn about z). Every chord x = const meets the solid over length
/// a, and the y-faces are each other's translates, so the volume is a b h exactly, mesh or smooth
/// (divergence theorem with the field (x, 0, 0)). Requires |A| < a / 2, |A_y| < b / 2 and
/// 4 pi^2 |A A_y| < a b (the faces meet at the corner edges without crossing).
TriangleMesh makeOsteomorphicBlock(double a, double b, double h, double amplitude, double amplitudeY,
                                   int halfWaveSegments);

/// The hexagonal TIS block: a hexagonal prism of mid-height inradius r whose six lateral faces
/// lean alternately outward and inward by theta: face k (outward normal at 60k degrees) is the plane
/// n_k . x = r + (-1)^k z tan(theta). Copies in the same orientation tile the plane (centres 2r
/// apart along the face normals) and interlock: face k of one block is face k+3 of its neighbour.
/// Requires h tan(theta) < r.
TriangleMesh makeHexBlock(double r, double h, double theta);

}  // namespace tessera
