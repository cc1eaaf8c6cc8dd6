// Fuzz target: the layout reader (JSON). Anything but a valid layout must be an InputError.
#include "fuzz/input_file.h"
#include "io/input_error.h"
#include "levelset/layout_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    tessera::readLayout(tessera::fuzz::writeInput(data, size, ".json"));
  } catch (const tessera::InputError&) {
  }
  return 0;
}
