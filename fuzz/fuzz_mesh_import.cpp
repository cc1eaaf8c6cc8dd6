// Fuzz target: mesh import and validation (assimp's STL/OBJ readers, then ours). The first byte
// picks the extension; a bad mesh must be an InputError, never a crash or a hang.
#include "fuzz/input_file.h"
#include "io/input_error.h"
#include "geometry/mesh_import.h"
#include "geometry/mesh_validation.h"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string path = tessera::fuzz::writeInput(data + 1, size - 1, data[0] % 2 ? ".obj" : ".stl");
  try {
    tessera::ImportedMesh imported = tessera::importMesh(path, {});
    tessera::validateSolidMesh(imported.mesh, path);
  } catch (const tessera::InputError&) {
  }
  return 0;
}
