#pragma once
#include "geometry/triangle_mesh.h"
#include "levelset/shape.h"

#include <functional>
#include <string>
#include <vector>

namespace tessera {

/// Messages for the user collected while preparing a shape (printed by the tools).
struct PrepLog {
  std::function<void(const std::string&)> now;  ///< if set, hears the estimate at once, before the heavy work
  std::vector<std::string> notes;     ///< what was done (welded, re-oriented)
  std::vector<std::string> warnings;  ///< results that are usable but suspect (under-resolved, odd size)
};

/// What preparing a shape will cost, estimated before the work (prep prints it, and refuses above
/// ShapeLimits::maxMemoryBytes). Rates measured by bench_prep (docs/performance.md).
struct ShapeEstimate {
  long long grid[3] = {0, 0, 0};  ///< grid nodes along x, y, z
  double gridNodes = 0;
  double surfaceNodes = 0;
  double bytes = 0;     ///< peak memory
  double seconds = 0;   ///< on one core
  std::string text() const;  ///< "grid 45 x 45 x 16 (32 k nodes), about 1 900 surface nodes, 4 MB, 0.3 s"
};
ShapeEstimate estimateShape(const Eigen::Vector3d& extents, double surfaceArea, const ShapeResolution& resolution);

/// What a shape may cost, and which sizes are plausible for a block (anything else is most likely
/// a mesh read in the wrong unit).
struct ShapeLimits {
  double maxMemoryBytes = 4e9;   ///< refuse a shape whose estimate needs more
  double smallest = 1e-3;        ///< m: a block's largest extent below this is refused ...
  double largest = 10.0;         ///< m: ... and above this
  bool anySize = false;          ///< accept any size (micro-scale or architectural blocks)
};

/// Checks a resolution against a shape of the given body-frame extents (m). Throws InputError for
/// values that cannot give a meaningful shape; adds warnings for under-resolved ones:
///  - voxel and spacing must be positive and finite;
///  - error if the thinnest dimension spans fewer than 3 voxels, warning below 10;
///  - warning if the thinnest dimension spans fewer than 2 node spacings;
void checkResolution(const Eigen::Vector3d& extents, const ShapeResolution& resolution,
                     const std::string& label, PrepLog& log);

/// Builds a shape from a mesh in metres: validates it (re-orienting an inverted one), computes
/// mass properties, moves it to the body frame, samples surface nodes and the signed distance.
/// `label` names the input in messages. Throws InputError for meshes or resolutions it refuses.
/// Zero lengths of `resolution` are relative to the shape (ShapeResolution::resolvedFor); the shape
/// keeps the absolute values it was built at. Prints nothing; the estimate goes to log.now.
Shape buildShape(const std::string& name, TriangleMesh mesh, const ShapeSource& source,
                 const ShapeResolution& resolution, const std::string& label, PrepLog& log,
                 const ShapeLimits& limits = {});

/// Imports a mesh file (STL/OBJ) in the given unit, turns its up axis `up` ("x", "y" or "z") into
/// +z (rotationToZUp), and builds its shape (see buildShape).
Shape prepareShapeFromFile(const std::string& path, const std::string& unit, const std::string& name,
                           const ShapeResolution& resolution, PrepLog& log, const ShapeLimits& limits = {},
                           const std::string& up = "z");

/// A valid shape name: 1-64 characters from [A-Za-z0-9_.-], not starting with '.'.
bool isValidShapeName(const std::string& name);

/// The default shape name of a mesh file: its name without extension, made valid
/// ("my block (v2).stl" -> "my_block__v2_").
std::string shapeNameFromPath(const std::string& path);

}  // namespace tessera
