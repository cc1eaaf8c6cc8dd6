// Fuzz target: the scene reader (TOML). Anything but a valid scene must be an InputError.
#include "io/input_error.h"
#include "run/scene.h"

#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    tessera::readSceneText(std::string(reinterpret_cast<const char*>(data), size), "/tmp/fuzz-scene.toml");
  } catch (const tessera::InputError&) {
  }
  return 0;
}
