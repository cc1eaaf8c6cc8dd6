#pragma once
#include "geometry/triangle_mesh.h"

#include <Eigen/Core>

namespace tessera {

/// Mass properties of a closed, outward-oriented polyhedron, per unit density.
struct MassProperties {
  double volume = 0.0;                  ///< m^3
  double surfaceArea = 0.0;             ///< m^2
  Eigen::Vector3d centroid{0, 0, 0};    ///< m, in the mesh frame
  Eigen::Matrix3d inertia;              ///< m^5, about the centroid, mesh axes (multiply by density for kg m^2)
  Eigen::Vector3d principalMoments;     ///< m^5, about body axes 0, 1, 2
  Eigen::Matrix3d principalAxes;        ///< columns: body axes in the mesh frame; a rotation (det = +1)
};

/// Exact mass properties of the polyhedron (signed tetrahedra; divergence theorem).
/// Body axes are the principal axes, ordered and signed to lie closest to the mesh axes
/// (an axis-aligned box keeps its axes). Where principal moments coincide to 1e-6 relative
/// (a cube, a square block), the axes in that subspace are taken as close to the mesh axes as possible.
MassProperties computeMassProperties(const TriangleMesh& mesh);

/// Signed volume only (m^3); negative for an inward-oriented closed mesh.
double signedVolume(const TriangleMesh& mesh);

/// The mesh expressed in the body frame: x_body = R^T (x - centroid).
TriangleMesh toBodyFrame(const TriangleMesh& mesh, const MassProperties& properties);

}  // namespace tessera
