#pragma once
#include <Eigen/Core>

namespace tessera {

/// Which feature of a triangle (a, b, c) holds a closest point: a corner, an edge (named by its
/// first corner: ab, bc, ca) or the face.
enum class TriangleFeature { CornerA, CornerB, CornerC, EdgeAB, EdgeBC, EdgeCA, Face };

struct ClosestPointOnTriangle {
  Eigen::Vector3d point;
  TriangleFeature feature;
};

/// The point of triangle (a, b, c) closest to p, and the feature holding it: the Voronoi regions
/// of the corners, then of the edges, else the projection onto the face (Ericson, Real-Time
/// Collision Detection, 2005, section 5.1.5). A degenerate triangle gives a corner or edge point.
inline ClosestPointOnTriangle closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, TriangleFeature::CornerA};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, TriangleFeature::CornerB};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return {a + (d1 / (d1 - d3)) * ab, TriangleFeature::EdgeAB};
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, TriangleFeature::CornerC};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return {a + (d2 / (d2 - d6)) * ac, TriangleFeature::EdgeCA};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return {b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b), TriangleFeature::EdgeBC};
  const double denominator = 1.0 / (va + vb + vc);
  return {a + ab * (vb * denominator) + ac * (vc * denominator), TriangleFeature::Face};
}

}  // namespace tessera
