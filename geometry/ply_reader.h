#pragma once
#include "geometry/triangle_mesh.h"

#include <string>

namespace tessera {

/// Whether `path` is a PLY file: by its extension (.ply, any case) or its first line ("ply").
bool isPlyFile(const std::string& path);

/// Reads a PLY mesh (Turk's format: ASCII, binary little- or big-endian): the x, y, z of element
/// "vertex" and the vertex_indices (or vertex_index) lists of element "face", every other element
/// and property read past. Polygons are split into triangles as fans from their first corner (the
/// faces of a block are convex); faces of fewer than three corners (points, lines) are dropped.
/// Coordinates in the file's units. Strict: the header to the letter of the format, counts against
/// the bytes the file holds, every index against the vertices; anything else throws InputError
/// naming the file and the fix. (Tessera reads PLY itself: assimp 5.2's reader looped forever,
/// aborted or reserved unbounded memory on damaged headers and bodies found by fuzz_mesh_import.)
TriangleMesh readPly(const std::string& path);

}  // namespace tessera
