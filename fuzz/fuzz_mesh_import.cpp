// Fuzz target: mesh import and validation (assimp's STL/OBJ/PLY readers, then ours). The first byte
// picks the extension; a bad mesh must be an InputError, never a crash or a hang.
#include "fuzz/input_file.h"
#include "io/input_error.h"
#include "geometry/mesh_import.h"
#include "geometry/mesh_validation.h"

#include <stdexcept>

static const char* const kExtensions[] = {".stl", ".obj", ".ply"};

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string path = tessera::fuzz::writeInput(data + 1, size - 1, kExtensions[data[0] % 3]);
  try {
    tessera::ImportedMesh imported = tessera::importMesh(path, {});
    tessera::validateSolidMesh(imported.mesh, path);
  } catch (const tessera::InputError&) {
  }
  return 0;
}
