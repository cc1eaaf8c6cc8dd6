#pragma once
#include "geometry/triangle_mesh.h"

#include <string>

namespace tessera {

enum class MeshFileFormat { Obj, StlAscii, StlBinary };

/// Writes `mesh` (metres) to `path` in `metresPerUnit` units through assimp's exporters.
/// Writes to a temporary name and renames on success; throws std::runtime_error on failure.
void writeMesh(const TriangleMesh& mesh, const std::string& path, MeshFileFormat format, double metresPerUnit);

/// The format implied by a file name: .obj -> Obj, .stl -> StlBinary; throws InputError otherwise.
MeshFileFormat meshFormatFromPath(const std::string& path);

}  // namespace tessera
