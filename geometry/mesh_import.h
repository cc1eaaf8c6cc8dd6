#pragma once
#include "geometry/mesh_weld.h"
#include "geometry/triangle_mesh.h"

#include <string>

namespace tessera {

struct MeshImportOptions {
  double metresPerUnit = 1e-3;  ///< the file's length unit in metres (mm -> 1e-3); files carry none
  double weldTolerance = -1.0;  ///< m; vertices closer than this are merged. < 0: 1e-6 x bounding-box diagonal
  std::string up = "z";         ///< the file's up axis, turned into +z (rotationToZUp)
};

struct ImportedMesh {
  TriangleMesh mesh;            ///< in metres, welded
  std::size_t fileVertices = 0; ///< distinct vertices as read (exact duplicates joined), before welding
  WeldReport weld;
};

/// Reads STL (ASCII or binary), OBJ and the other formats assimp knows, and PLY (readPly: Tessera's
/// own reader, assimp's failed on damaged files), triangulates polygons,
/// joins identical vertices, bakes node transforms, scales to metres, welds vertices closer than
/// the tolerance (STL facets repeat their corners, sometimes with rounding differences) and turns
/// the up axis into +z. Throws InputError naming the file for: missing or unreadable file, empty
/// file, a file assimp cannot parse, no triangles, non-finite coordinates; and for an up axis
/// that is not x, y or z.
ImportedMesh importMesh(const std::string& path, const MeshImportOptions& options);

}  // namespace tessera
