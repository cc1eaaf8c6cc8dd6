#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace tessera {

struct SdfSample {
  double phi;                 ///< m; negative inside
  Eigen::Vector3d gradient;   ///< d phi / dx (unit length away from kinks)
};

/// A signed-distance field on a dense regular grid (the solver-side copy of an OpenVDB grid).
/// Grid node (i, j, k) sits at origin + voxelSize * (i, j, k); values are stored with k fastest:
/// values[(i * dims[1] + j) * dims[2] + k]. Negative inside. The grid covers the shape's bounding
/// box plus an exterior band; every node holds the signed distance to the polyhedron.
/// Sampling is read-only and thread-safe.
struct DenseSdf {
  Eigen::Vector3d origin{0, 0, 0};  ///< m, position of node (0, 0, 0) in the body frame
  double voxelSize = 0.0;           ///< m
  std::array<int, 3> dims{0, 0, 0}; ///< nodes along x, y, z
  std::vector<float> values;        ///< m
  float background = 0.0f;          ///< m, the exterior band width: the .vdb's inactive value

  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(i) * dims[1] + j) * dims[2] + k;
  }
  float at(int i, int j, int k) const { return values[index(i, j, k)]; }
  Eigen::Vector3d nodePosition(int i, int j, int k) const { return origin + voxelSize * Eigen::Vector3d(i, j, k); }
  Eigen::Vector3d upperCorner() const {
    return origin + voxelSize * Eigen::Vector3d(dims[0] - 1, dims[1] - 1, dims[2] - 1);
  }
  bool contains(const Eigen::Vector3d& x) const {
    return (x.array() >= origin.array()).all() && (x.array() <= upperCorner().array()).all();
  }

  /// The cell of a point inside the grid (its lower node i0) and the weights w in [0, 1] within it.
  /// (Scaled by 1 / voxelSize, one division, as the solver's SIMD copy of value(), gridSamples,
  /// does; that copy may fuse multiply-adds on CPUs that have them, so the two agree to rounding.
  /// Nothing needs them to agree to the bit: the candidates' band has margin, and each step lists
  /// every contact through gridSamples.)
  void locate(const Eigen::Vector3d& inside, int i0[3], double w[3]) const {
    const Eigen::Vector3d u = (inside - origin) * (1.0 / voxelSize);
    for (int a = 0; a < 3; ++a) {
      i0[a] = std::min(static_cast<int>(u[a]), dims[a] - 2);  // u >= 0: truncation is floor
      w[a] = u[a] - i0[a];
    }
  }

  /// The value of sample(x) alone (no gradient): the cheap test of whether x is inside.
  double value(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d clamped = x.cwiseMax(origin).cwiseMin(upperCorner());
    int i0[3];
    double w[3];
    locate(clamped, i0, w);
    const float* c = &values[index(i0[0], i0[1], i0[2])];
    const std::size_t dj = dims[2], di = static_cast<std::size_t>(dims[1]) * dims[2];
    const auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
    const double c00 = lerp(c[0], c[1], w[2]), c01 = lerp(c[dj], c[dj + 1], w[2]);
    const double c10 = lerp(c[di], c[di + 1], w[2]), c11 = lerp(c[di + dj], c[di + dj + 1], w[2]);
    const double phi = lerp(lerp(c00, c01, w[1]), lerp(c10, c11, w[1]), w[0]);
    return phi + (x - clamped).norm();
  }

  /// A positive lower bound of phi(x) proven by a node of x's cell, or 0 when none proves x outside:
  /// phi is 1-Lipschitz, so phi(x) >= phi_i - |x - c_i| for each corner c_i, and a node's value is
  /// its exact distance (to float rounding, covered by a margin of 1e-6 voxel; in the background,
  /// less than it). The first corner whose value exceeds its distance from x (compared squared)
  /// gives the bound. 0 outside the grid.
  double provenOutside(const Eigen::Vector3d& x) const {
    if (!contains(x)) return 0.0;
    int i0[3];
    double w[3];
    locate(x, i0, w);
    const double margin = 1e-6 * voxelSize;
    for (int c = 0; c < 8; ++c) {
      const int di = c >> 2, dj = (c >> 1) & 1, dk = c & 1;
      const double v = at(i0[0] + di, i0[1] + dj, i0[2] + dk) - margin;
      const double d2 = (voxelSize * voxelSize) * ((w[0] - di) * (w[0] - di) + (w[1] - dj) * (w[1] - dj) + (w[2] - dk) * (w[2] - dk));
      if (v > 0 && v * v > d2) return v - std::sqrt(d2);
    }
    return 0.0;
  }

  /// Trilinear interpolation of the node values and its exact gradient.
  /// Outside the grid: the value at the nearest grid point plus the distance to it (positive,
  /// continuous, growing away from the grid), with the gradient pointing away from the grid.
  SdfSample sample(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d clamped = x.cwiseMax(origin).cwiseMin(upperCorner());
    int i0[3];
    double w[3];
    locate(clamped, i0, w);
    double c[2][2][2];
    for (int di = 0; di < 2; ++di)
      for (int dj = 0; dj < 2; ++dj)
        for (int dk = 0; dk < 2; ++dk) c[di][dj][dk] = at(i0[0] + di, i0[1] + dj, i0[2] + dk);
    // Interpolate along z, then y, then x; differentiate each stage.
    double cy[2][2], cyz[2][2];
    for (int di = 0; di < 2; ++di)
      for (int dj = 0; dj < 2; ++dj) {
        cy[di][dj] = c[di][dj][0] + w[2] * (c[di][dj][1] - c[di][dj][0]);
        cyz[di][dj] = c[di][dj][1] - c[di][dj][0];
      }
    const double cx0 = cy[0][0] + w[1] * (cy[0][1] - cy[0][0]), cx1 = cy[1][0] + w[1] * (cy[1][1] - cy[1][0]);
    SdfSample s;
    s.phi = cx0 + w[0] * (cx1 - cx0);
    s.gradient.x() = (cx1 - cx0) / voxelSize;
    const double dy0 = cy[0][1] - cy[0][0], dy1 = cy[1][1] - cy[1][0];
    s.gradient.y() = (dy0 + w[0] * (dy1 - dy0)) / voxelSize;
    const double dz00 = cyz[0][0] + w[1] * (cyz[0][1] - cyz[0][0]);
    const double dz10 = cyz[1][0] + w[1] * (cyz[1][1] - cyz[1][0]);
    s.gradient.z() = (dz00 + w[0] * (dz10 - dz00)) / voxelSize;

    const Eigen::Vector3d away = x - clamped;
    const double gap = away.norm();
    if (gap > 0) {
      s.phi += gap;
      s.gradient = away / gap;
    }
    return s;
  }
};

}  // namespace tessera
