#include "geometry/block_generators.h"

#include "geometry/input_error.h"

#include <cmath>

namespace tessera {

namespace {

// A hexahedron from its 8 corners, numbered as the bits (x, y, z) of the index: corner
// i has x = bit 0, y = bit 1, z = bit 2 (0 = low side). Faces are split into two triangles,
// counter-clockwise seen from outside.
TriangleMesh hexahedron(const std::array<Eigen::Vector3d, 8>& corner) {
  TriangleMesh mesh;
  mesh.vertices.assign(corner.begin(), corner.end());
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6},   // z-, z+
                           {0, 1, 5, 4}, {2, 6, 7, 3},   // y-, y+
                           {0, 4, 6, 2}, {1, 3, 7, 5}};  // x-, x+
  for (const auto& q : quads) {
    mesh.triangles.push_back({q[0], q[1], q[2]});
    mesh.triangles.push_back({q[0], q[2], q[3]});
  }
  return mesh;
}

}  // namespace

TriangleMesh makeBox(double a, double b, double h) {
  if (!(a > 0 && b > 0 && h > 0)) throw InputError("box sides must be positive");
  std::array<Eigen::Vector3d, 8> corner;
  for (int i = 0; i < 8; ++i)
    corner[i] = Eigen::Vector3d((i & 1 ? 0.5 : -0.5) * a, (i & 2 ? 0.5 : -0.5) * b, (i & 4 ? 0.5 : -0.5) * h);
  return hexahedron(corner);
}

TriangleMesh makePlanarBlock(double a, double h, double theta) {
  if (!(a > 0 && h > 0)) throw InputError("planar block: side and thickness must be positive");
  const double slope = std::tan(theta);
  if (!(std::abs(theta) < M_PI / 2) || h * std::abs(slope) >= a)
    throw InputError("planar block: the inclined faces meet inside the block (need thickness x tan(angle) < side)");
  std::array<Eigen::Vector3d, 8> corner;
  for (int i = 0; i < 8; ++i) {
    const double z = (i & 4 ? 0.5 : -0.5) * h;
    const double halfX = 0.5 * a + z * slope, halfY = 0.5 * a - z * slope;
    corner[i] = Eigen::Vector3d((i & 1 ? 1 : -1) * halfX, (i & 2 ? 1 : -1) * halfY, z);
  }
  return hexahedron(corner);
}

}  // namespace tessera
