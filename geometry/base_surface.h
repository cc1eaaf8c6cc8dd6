#pragma once
#include "geometry/triangle_mesh.h"

#include <Eigen/Core>
#include <memory>
#include <string>

namespace tessera {

/// A surface given as a triangle mesh that is a height field over the plan: every plan point of
/// the tiling lies over exactly one triangle (an open mesh: a roof, a dome, a vault from a design
/// tool), with smooth normals interpolated from its vertices' (each the area-weighted mean of its
/// triangles', all turned up).
struct SurfaceMesh {
  TriangleMesh mesh;                            ///< m, its triangles turned so that their normals point up
  std::vector<Eigen::Vector3d> vertexNormals;   ///< unit
};

/// The surface a generated tiling is laid on (docs/tiling.md, "On a surface"): a plan point (x, y)
/// is lifted vertically onto it, and blocks are offset along its normal. The sphere's and the
/// cylinder's top is at the origin; the cylinder's axis runs along x (a barrel vault spanning y);
/// a mesh surface is where its file puts it.
struct BaseSurface {
  enum class Kind { Plane, Sphere, Cylinder, Mesh };
  Kind kind = Kind::Plane;
  double radius = 0;  ///< m (sphere, cylinder)
  std::shared_ptr<const SurfaceMesh> mesh;  ///< Kind::Mesh
  std::string name;   ///< the file of a mesh surface (for messages)

  /// The surface point over a plan point; InputError where the surface has none (beyond the
  /// radius, outside the mesh).
  Eigen::Vector3d point(const Eigen::Vector2d& plan) const;
  /// The unit normal, pointing up and out, at a point on or near the surface (for a chord's
  /// midpoint on a sphere or a cylinder it is perpendicular to the chord; on a mesh, the normal
  /// interpolated at the point's plan position).
  Eigen::Vector3d normal(const Eigen::Vector3d& x) const;
};

/// "plane", "sphere" or "cylinder": a built-in surface (anything else names a file).
inline bool isSurfaceKind(const std::string& name) { return name == "plane" || name == "sphere" || name == "cylinder"; }

/// "plane", "sphere" or "cylinder" with its radius (m), or a mesh file (STL, OBJ, PLY) of a
/// height field in `metresPerUnit` units; InputError for a radius that is not positive (sphere,
/// cylinder), a name that is neither a surface nor a file, and a mesh that is not a height field
/// (a triangle standing vertical, or triangles facing up and down).
BaseSurface baseSurface(const std::string& name, double radius, double metresPerUnit = 1.0, const std::string& up = "z");

}  // namespace tessera
