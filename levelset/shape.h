#pragma once
#include "geometry/convex_planes.h"
#include "geometry/mass_properties.h"
#include "geometry/paper_block.h"
#include "geometry/surface_nodes.h"
#include "geometry/triangle_mesh.h"
#include "levelset/dense_sdf.h"
#include "levelset/mesh_sdf.h"

#include <optional>
#include <string>

namespace tessera {

/// Where a shape came from.
struct ShapeSource {
  std::string file;            ///< mesh file as given to prep (or a generator description)
  std::string unit = "m";      ///< the file's length unit
  double metresPerUnit = 1.0;  ///< m per file unit
};

/// The resolution a shape was prepared at. Zero lengths are relative to the shape: the ratio x its
/// thinnest extent t (its body-frame box), the paper's 0.25 mm and 0.6 mm on its 3.18 mm block.
struct ShapeResolution {
  double voxelSize = 0.0;    ///< m, signed-distance grid spacing (0: voxelRatio x t)
  double nodeSpacing = 0.0;  ///< m, target surface node spacing (0: nodeSpacingRatio x t)
  double voxelRatio = 0.25e-3 / kPaperThickness;        ///< t / 12.7
  double nodeSpacingRatio = 0.6e-3 / kPaperThickness;   ///< t / 5.3
  /// Node spacing at sharp edges and corners as a fraction of nodeSpacing, graded to nodeSpacing
  /// on face interiors by sizeGradient (SurfaceNodeOptions); 1: uniform.
  double edgeSpacingFraction = 0.25;
  double sizeGradient = 0.5;     ///< growth of the node spacing per unit distance from a sharp edge
  double featureAngle = 0.5236;  ///< rad, edges bending more than this are sharp
  int exteriorBandVoxels = 3;    ///< exact distances (and grid padding) outside the surface, voxels

  /// This resolution with its zero lengths made absolute for a shape of thinnest extent t (m).
  ShapeResolution resolvedFor(double t) const {
    ShapeResolution r = *this;
    if (r.voxelSize == 0) r.voxelSize = voxelRatio * t;
    if (r.nodeSpacing == 0) r.nodeSpacing = nodeSpacingRatio * t;
    return r;
  }
};

/// The accepted grading parameters, one rule for prep, tile, assemble, the scene and Python (each
/// names its own option in the error): an edge spacing of 0.05 to 1 of the node spacing (1:
/// uniform), a size gradient of 0.05 to 100.
inline bool validEdgeSpacingFraction(double f) { return f >= 0.05 && f <= 1; }
inline bool validSizeGradient(double g) { return g >= 0.05 && g <= 100; }

/// One distinct block shape, solver-ready. Everything but `mass` is in the body frame: the
/// principal frame with its origin at the centroid. A point x_mesh of the source mesh (in metres)
/// is x_body = R^T (x_mesh - c) with c = mass.centroid, R = mass.principalAxes.
struct Shape {
  std::string name;
  ShapeSource source;
  ShapeResolution resolution;
  MassProperties mass;   ///< per unit density; centroid, inertia and axes in the source mesh frame (m)
  TriangleMesh mesh;     ///< body frame, m
  SurfaceNodes nodes;    ///< body frame
  DenseSdf sdf;          ///< body frame
  /// Body frame: the face planes when the mesh is convex to within the data's precision
  /// (fitConvexPolyhedron); the solver then uses them as an exact level set instead of the grid.
  std::optional<ConvexFit> convex;
  /// Body frame: the exact level set of the mesh near its surface, used where the planes are not;
  /// derived from `mesh` and `sdf` for a run (deriveExactMesh), not stored; empty until then.
  MeshSdf exactMesh;
};

/// Within this many voxels of the surface, the exact mesh level set lists its triangles: more
/// than the solver's candidate band (0.1 voxel at the default resolution) and the grid's
/// interpolation error ((sqrt 3 / 2) voxel), so that every node that can touch is evaluated exactly.
constexpr int kExactMeshBandVoxels = 3;

/// The shape's exact mesh level set, from its mesh and grid (for a run, and for the assembly
/// checks of tile and assemble; a bundle does not store it).
MeshSdf exactMeshLevelSet(const Shape& shape);
/// shape.exactMesh = exactMeshLevelSet(shape).
void deriveExactMesh(Shape& shape);

/// The level-set path a shape takes in the solver, as printed and stored: "exact planes (6 faces,
/// convex to 2e-06 mm)", "exact mesh (212 triangles)", or "grid (...)" when the exact path is
/// turned off.
std::string levelSetPath(const Shape& shape, bool exactConvexLevelSets = true, bool exactMeshLevelSets = true);

}  // namespace tessera
