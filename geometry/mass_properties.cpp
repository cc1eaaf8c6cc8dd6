#include "geometry/mass_properties.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>

namespace tessera {

namespace {

struct Moments {
  double volume = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();   // integral of y dV
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // integral of y y^T dV
};

// Volume integrals over the solid, relative to a reference point r, as a sum over signed
// tetrahedra (r, a, b, c), one per triangle (divergence theorem). With u = a - r, v = b - r,
// w = c - r, s = u + v + w and V_t = u . (v x w) / 6:
//   integral of 1     = V_t
//   integral of y     = V_t s / 4
//   integral of y y^T = V_t / 20 (u u^T + v v^T + w w^T + s s^T)
// Source: Tonon, "Explicit exact formulas for the 3-D tetrahedron inertia tensor in terms of its
// vertex coordinates", J. Math. Stat. 1(1), 2005; Eberly, "Polyhedral mass properties", 2002.
Moments integrate(const TriangleMesh& mesh, const Eigen::Vector3d& r) {
  Moments m;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Eigen::Vector3d u = triangleCorner(mesh, t, 0) - r;
    const Eigen::Vector3d v = triangleCorner(mesh, t, 1) - r;
    const Eigen::Vector3d w = triangleCorner(mesh, t, 2) - r;
    const Eigen::Vector3d s = u + v + w;
    const double vt = u.dot(v.cross(w)) / 6.0;
    m.volume += vt;
    m.first += vt * s / 4.0;
    m.second += vt / 20.0 * (u * u.transpose() + v * v.transpose() + w * w.transpose() + s * s.transpose());
  }
  return m;
}

Eigen::Vector3d referencePoint(const TriangleMesh& mesh) { return boundingBox(mesh.vertices).center(); }

// Orthonormal basis of span(columns of `basis`) made of vectors as close as possible to the mesh
// axes: project each mesh axis onto the span, take them in order of projected length, Gram-Schmidt.
Eigen::MatrixXd alignedBasis(const Eigen::MatrixXd& basis) {
  const Eigen::Index dim = basis.cols();
  Eigen::MatrixXd out(3, dim);
  std::array<int, 3> axes{0, 1, 2};
  const Eigen::Matrix3d projector = basis * basis.transpose();
  std::stable_sort(axes.begin(), axes.end(),
                   [&](int a, int b) { return projector(a, a) > projector(b, b); });
  Eigen::Index filled = 0;
  for (int a : axes) {
    if (filled == dim) break;
    Eigen::Vector3d v = projector.col(a);
    for (Eigen::Index k = 0; k < filled; ++k) v -= out.col(k).dot(v) * out.col(k);
    if (v.norm() < 1e-6) continue;
    out.col(filled++) = v.normalized();
  }
  return out;
}

}  // namespace

double signedVolume(const TriangleMesh& mesh) { return integrate(mesh, referencePoint(mesh)).volume; }

MassProperties computeMassProperties(const TriangleMesh& mesh) {
  MassProperties p;
  const Eigen::Vector3d r = referencePoint(mesh);
  const Moments m = integrate(mesh, r);
  p.volume = m.volume;
  p.surfaceArea = surfaceArea(mesh);
  const Eigen::Vector3d d = m.first / m.volume;
  p.centroid = r + d;
  // Parallel-axis shift to the centroid, then inertia I = tr(C) 1 - C.
  const Eigen::Matrix3d c = m.second - m.volume * d * d.transpose();
  p.inertia = c.trace() * Eigen::Matrix3d::Identity() - c;
  p.inertia = 0.5 * (p.inertia + p.inertia.transpose());

  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(p.inertia);
  const Eigen::Vector3d values = eigen.eigenvalues();  // ascending
  Eigen::Matrix3d vectors = eigen.eigenvectors();
  // Re-choose axes inside groups of equal moments so that they follow the mesh axes.
  const double scale = std::max(values.cwiseAbs().maxCoeff(), 1e-300);
  for (int i = 0; i < 3;) {
    int j = i + 1;
    while (j < 3 && values(j) - values(i) <= 1e-6 * scale) ++j;
    if (j - i > 1) vectors.middleCols(i, j - i) = alignedBasis(vectors.middleCols(i, j - i));
    i = j;
  }
  // Assign eigenvectors to mesh axes: the permutation with the largest sum of |cosines|.
  std::array<int, 3> perm{0, 1, 2}, best = perm;
  double bestScore = -1.0;
  do {
    double score = 0.0;
    for (int k = 0; k < 3; ++k) score += std::abs(vectors(k, perm[k]));
    if (score > bestScore + 1e-12) {
      bestScore = score;
      best = perm;
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d axis = vectors.col(best[k]);
    if (axis(k) < 0) axis = -axis;
    p.principalAxes.col(k) = axis;
    p.principalMoments(k) = values(best[k]);
  }
  if (p.principalAxes.determinant() < 0) p.principalAxes.col(2) = -p.principalAxes.col(2);
  return p;
}

TriangleMesh toBodyFrame(const TriangleMesh& mesh, const MassProperties& properties) {
  TriangleMesh body = mesh;
  for (auto& v : body.vertices) v = properties.principalAxes.transpose() * (v - properties.centroid);
  return body;
}

}  // namespace tessera
