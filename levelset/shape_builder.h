#pragma once
#include "geometry/triangle_mesh.h"
#include "levelset/shape.h"

#include <string>
#include <vector>

namespace tessera {

/// Messages for the user collected while preparing a shape (printed by the tools).
struct PrepLog {
  std::vector<std::string> notes;     ///< what was done (welded, re-oriented)
  std::vector<std::string> warnings;  ///< results that are usable but suspect (under-resolved, odd size)
};

/// Checks a resolution against a shape of the given body-frame extents (m). Throws InputError for
/// values that cannot give a meaningful shape; adds warnings for under-resolved ones:
///  - voxel and spacing must be positive and finite;
///  - error if the thinnest dimension spans fewer than 3 voxels, warning below 10 (DESIGN §4);
///  - warning if the thinnest dimension spans fewer than 2 node spacings;
///  - error if the grid or the area quadrature would exceed memory limits (wrong unit?).
void checkResolution(const Eigen::Vector3d& extents, double surfaceArea, const ShapeResolution& resolution,
                     const std::string& label, PrepLog& log);

/// Builds a shape from a mesh in metres: validates it (re-orienting an inverted one), computes
/// mass properties, moves it to the body frame, samples surface nodes and the signed distance.
/// `label` names the input in messages. Throws InputError for meshes or resolutions it refuses.
Shape buildShape(const std::string& name, TriangleMesh mesh, const ShapeSource& source,
                 const ShapeResolution& resolution, const std::string& label, PrepLog& log);

/// Imports a mesh file (STL/OBJ) in the given unit and builds its shape (see buildShape).
Shape prepareShapeFromFile(const std::string& path, const std::string& unit, const std::string& name,
                           const ShapeResolution& resolution, PrepLog& log);

/// A valid shape name: 1-64 characters from [A-Za-z0-9_.-], not starting with '.'.
bool isValidShapeName(const std::string& name);

/// The default shape name of a mesh file: its name without extension, made valid
/// ("my block (v2).stl" -> "my_block__v2_").
std::string shapeNameFromPath(const std::string& path);

}  // namespace tessera
